/*
 * compare_report.c - the Markdown and CSV reports of `compare` (their
 * layout is documented in cmd_compare.c).
 */
#include "host/compare/compare.h"
#include "host/compare/compare_subset.h"

#include <math.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "host/io/output.h"

/* A field of a change as text: value of `row` for `field`; md: time in ms;
 * certified: its err_upper (md: "yes (err_upper X)"). */

const char *ob_method_verdict(const ob_method_sum *m)
{
    const int reg = m->regressions > 0 || m->verdict > 0, imp = m->improvements > 0 || m->verdict < 0;
    return reg ? "regression" : imp ? "improvement" : "same";
}

static void value_text(char *buf, size_t len, const ob_res_row *row, const char *field, int md)
{
    if (!row)
        snprintf(buf, len, "%s", md ? "-" : "");
    else if (strcmp(field, "status") == 0)
        snprintf(buf, len, "%s", row->status);
    else if (strcmp(field, "ctrl_points") == 0)
        snprintf(buf, len, "%ld", row->ctrl_points);
    else if (strcmp(field, "max_err") == 0)
        snprintf(buf, len, "%s", *row->max_err_text ? row->max_err_text : "nan");
    else if (strcmp(field, "certified") == 0) {  /* the certificate, not the job's time */
        char up[40];
        ob_fmt_double(up, sizeof up, row->err_upper);
        if (md)
            snprintf(buf, len, "%s (err_upper %s)", *row->certified ? row->certified : "-", up);
        else
            snprintf(buf, len, "%s", up);
    } else if (md)
        snprintf(buf, len, "%.4g ms", (row->fit_ns + row->eval_ns) * 1e-6);
    else
        snprintf(buf, len, "%.0f", row->fit_ns + row->eval_ns);
}

static void num_text(char *buf, size_t len, double x, int md, const char *md_fmt)
{
    if (isnan(x))
        snprintf(buf, len, "%s", md ? "-" : "");
    else if (md)
        snprintf(buf, len, md_fmt, x);
    else
        ob_fmt_double(buf, len, x);
}

/* ---- Markdown ---- */

static void side_line(FILE *f, const ob_cmp_side *s)
{
    fprintf(f, "- %s: `%s` (%d rows", s->label, s->results_path, s->res.n);
    const ob_json_entry *c = ob_json_get(&s->meta, "git_commit"), *d = ob_json_get(&s->meta, "git_dirty");
    const ob_json_entry *ts = ob_json_get(&s->meta, "timestamp");
    if (s->has_meta)
        fprintf(f, "; commit %.12s%s%s%s", c ? c->value : "?", d && strcmp(d->value, "true") == 0 ? " (dirty)" : "",
                ts ? ", " : "", ts ? ts->value : "");
    else
        fprintf(f, "; no meta.json");
    if (s->has_samples)
        fprintf(f, "; samples.csv: %d repetitions", s->res.maxrep);
    fprintf(f, ")\n");
}

static const char *kind_name(ob_ch_kind k)
{
    static const char *const n[] = {"regression", "improvement", "new", "missing", "not_judged", "left_out"};
    return n[k];
}

/* A timing interval for the Markdown report: "[lo, hi]", "unbounded" or "-". */
static void interval_text(char *buf, size_t len, double lo, double hi)
{
    if (isnan(lo) || isnan(hi))
        snprintf(buf, len, "-");
    else if (!isfinite(hi) || !(lo > 0))
        snprintf(buf, len, "unbounded");
    else
        snprintf(buf, len, "[%.4g, %.4g]", lo, hi);
}

/* Which changes a table lists: those of one kind, and among timing
 * changes of rows, those that count for the exit status or those that do
 * not (--method-timing-only). */
typedef enum { ROWS_ALL, ROWS_COUNTED, ROWS_NOT_COUNTED } row_filter;

static int listed(const ob_cmp_result *r, const ob_change *c, ob_ch_kind kind, row_filter flt)
{
    if (c->kind != kind)
        return 0;
    const int uncounted_time = strcmp(c->field, "time") == 0 && kind == OB_CH_REGRESSION && !r->t_rows_count;
    return flt == ROWS_ALL || (flt == ROWS_COUNTED) != uncounted_time;
}

/* Rows of one kind: changes (field, base, new, ratio, p) or rows (new / missing). */
static void md_table(FILE *f, const ob_cmp_result *r, ob_ch_kind kind, row_filter flt, const char *title,
                     int max_rows, int always)
{
    int total = 0;
    for (int i = 0; i < r->nch; i++)
        total += listed(r, &r->ch[i], kind, flt);
    if (!total && !always)
        return;
    fprintf(f, "\n## %s (%d)\n\n", title, total);
    if (!total) {
        fprintf(f, "None.\n");
        return;
    }
    const int rows_only = kind == OB_CH_NEW || kind == OB_CH_MISSING || kind == OB_CH_LEFT_OUT;
    fprintf(f, "| curve | d | method | metric | split | tol | %s |\n",
            rows_only ? "status | ctrl_points | max_err" : "field | base | new | new/base | p | interval");
    fprintf(f, "|---|---:|---|---|---|---:|%s\n", rows_only ? "---|---:|---:|" : "---|---:|---:|---:|---:|---:|");
    int shown = 0;
    for (int i = 0; i < r->nch && shown < max_rows; i++) {
        const ob_change *c = &r->ch[i];
        if (!listed(r, c, kind, flt))
            continue;
        const ob_res_row *k = c->base ? c->base : c->nw;
        char b[64], n[64], ratio[32], p[32], ci[64];
        fprintf(f, "| %s | %s | %s | %s | %s | %s | ", k->curve, k->d_text, k->method, k->metric, k->split,
                k->tol_text);
        if (rows_only) {
            value_text(b, sizeof b, k, "ctrl_points", 1);
            value_text(n, sizeof n, k, "max_err", 1);
            fprintf(f, "%s | %s | %s |\n", k->status, b, n);
        } else {
            value_text(b, sizeof b, c->base, c->field, 1);
            value_text(n, sizeof n, c->nw, c->field, 1);
            num_text(ratio, sizeof ratio, c->ratio, 1, "%.4g");
            num_text(p, sizeof p, c->p, 1, "%.3g");
            interval_text(ci, sizeof ci, c->ci_lo, c->ci_hi);
            fprintf(f, "%s%s%s | %s | %s | %s | %s | %s |\n", c->field, *c->note ? ": " : "", c->note, b, n, ratio,
                    p, ci);
        }
        shown++;
    }
    if (shown < total)
        fprintf(f, "\n%d more not shown (--max-rows %d).\n", total - shown, max_rows);
}

const char *ob_cmp_timing_word(const ob_method_sum *m)
{
    static _Thread_local char need[96];
    if (!m->timing)
        return "-";
    const int tested = m->reps_base >= 2 && m->reps_new >= 2;
    if (strcmp(m->timing, "slower") == 0)
        return tested ? "slower" : "slower (threshold only)";
    if (strcmp(m->timing, "faster") == 0)
        return tested ? "faster" : "faster (threshold only)";
    if (strcmp(m->timing, "same") == 0)
        return tested ? "no change" : "no change (threshold only)";
    if (strcmp(m->timing, "noisy") != 0)
        return "not judged: too few repetitions";
    const int have = m->reps_base < m->reps_new ? m->reps_base : m->reps_new;
    snprintf(need, sizeof need, "cannot decide: need %d more repetitions per side", m->need_reps - have);
    return need;
}

/* The harness's line of the per-method table (compare.h). */
static void md_harness(FILE *f, const ob_cmp_result *r)
{
    const ob_method_sum *h = &r->harness;
    if (!h->timing)
        return;
    char tb[32], tn[32], t[32], p[32], ci[64];
    num_text(tb, sizeof tb, h->t_base * 1e-6, 1, "%.4g ms");
    num_text(tn, sizeof tn, h->t_new * 1e-6, 1, "%.4g ms");
    num_text(t, sizeof t, h->t_est, 1, "%.4g");
    num_text(p, sizeof p, h->p, 1, "%.3g");
    interval_text(ci, sizeof ci, h->ci_lo, h->ci_hi);
    fprintf(f, "| *harness* (eval_ns) | %d | - | - | - | - | %s | %s | %s | %s | %s | %s | %s |\n", h->rows, tb, tn, t,
            ci, p, ob_cmp_timing_word(h), !r->harness_counts ? "reported only" : h->verdict > 0 ? "regression"
                                                        : h->verdict < 0 ? "improvement" : "same");
}

/* The table that decides the verdict: per method, the quality summary
 * (geometric means, the row changes that count) and the timing claim, one
 * statistic: the estimate of new/base with its own interval. */
static void md_methods(FILE *f, const ob_cmp_opts *o, const ob_cmp_result *r)
{
    fprintf(f, "\n## Verdict by method\n\n");
    if (!r->nms) {
        fprintf(f, "None.\n");
        return;
    }
    fprintf(f, "ctrl_points, max_err: geometric means of new/base over the joined rows; regressions, "
               "improvements: the row changes that count; time: the method's total (%s over its rows "
               "judged for timing), base and new the medians of the per-%s totals, new/base the "
               "Hodges-Lehmann estimate of their ratio and interval that estimate's own %g%% interval (without "
               "repetitions: the summed times, no interval); slower or faster when the estimate is beyond %g%%, the interval excludes 1 "
               "and is no wider than the change; the last line is the harness (eval_ns: offbench's measuring) over "
               "every row judged.\n\n",
            r->method_time ? "method_ns, the method's own fit time" : "fit_ns + eval_ns",
            r->method_time ? "round (fits.csv)" : "repetition", 100 * (1 - o->alpha), 100 * o->time_threshold);
    fprintf(f, "| method | rows | ctrl_points | max_err | regressions | improvements | time base | time new | "
               "time new/base | interval | p | timing | verdict |\n"
               "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n");
    for (int i = 0; i < r->nms; i++) {
        const ob_method_sum *m = &r->ms[i];
        char cp[32], er[32], tb[32], tn[32], t[32], p[32], ci[64];
        num_text(cp, sizeof cp, m->gm_cp, 1, "%.4g");
        num_text(er, sizeof er, m->gm_err, 1, "%.4g");
        num_text(tb, sizeof tb, m->timing ? m->t_base * 1e-6 : NAN, 1, "%.4g ms");
        num_text(tn, sizeof tn, m->timing ? m->t_new * 1e-6 : NAN, 1, "%.4g ms");
        num_text(t, sizeof t, m->timing ? m->t_est : NAN, 1, "%.4g");
        num_text(p, sizeof p, m->p, 1, "%.3g");
        interval_text(ci, sizeof ci, m->ci_lo, m->ci_hi);
        fprintf(f, "| %s | %d | %s | %s | %d | %d | %s | %s | %s | %s | %s | %s | %s |\n", m->method, m->rows, cp, er,
                m->regressions, m->improvements, tb, tn, t, ci, p, ob_cmp_timing_word(m), ob_method_verdict(m));
    }
    md_harness(f, r);
}

/* The rows NEW left out on purpose (compare_subset.h): what NEW set out
 * to run, in the context; the rows, last and collapsed.  Nothing when no
 * row was left out, so that a full run's report stays as it was. */
static void md_selection(FILE *f, const ob_cmp_result *r)
{
    if (ob_cmp_left_out_text(r))
        fprintf(f, "- selection: NEW set out to run %s (meta.json \"selection\"); the %d rows of BASE outside it are "
                   "left out, not regressions; a row inside it that NEW lacks is missing, a regression\n",
                ob_cmp_selection_text(r), r->n_left_out);
}

static void md_left_out(FILE *f, const ob_cmp_opts *o, const ob_cmp_result *r)
{
    if (!ob_cmp_left_out_text(r))
        return;
    fprintf(f, "\n<details>\n<summary>Left out, not regressions: %d rows of BASE outside NEW's selection</summary>\n",
            r->n_left_out);
    md_table(f, r, OB_CH_LEFT_OUT, ROWS_ALL, "Left out: outside NEW's selection", o->max_rows, 0);
    fprintf(f, "\n</details>\n");
}

/* The inputs, the comparability and how timings were judged. */
static void md_context(FILE *f, const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o,
                       const ob_cmp_result *r)
{
    fprintf(f, "\n## Context\n\n");
    side_line(f, b);
    side_line(f, n);
    if (r->checked)
        fprintf(f, "- comparable: samples_per_segment, max_depth, max_segments, inflection_split, seed, and the "
                   "method_params and method_versions of the methods both runs ran are equal\n");
    if (o->timing_only)
        fprintf(f, "- quality: not judged (--timing-only); rows missing from NEW and new rows are not listed\n");
    if (o->methods)
        fprintf(f, "- methods: only %s (--methods)\n", o->methods);
    if (o->no_timing)
        fprintf(f, "- timings: not compared (--no-timing)\n");
    else if (!r->timing) {
        fprintf(f, "- timings: **not judged**:\n");
        for (int i = 0; i < r->timing_diffs.n; i++)
            fprintf(f, "  - %s\n", r->timing_diffs.v[i]);
    } else {
        fprintf(f, "- timings: judged (same machine id, logical cores and memory; same compiler, cflags, backend, "
                   "OpenCL device and driver, OMP threads, CPU model; both runs' load average within their cores); "
                   "a row is judged when both statuses are equal and both times (fit_ns + eval_ns) are at least %g "
                   "ms\n", o->time_floor_ns * 1e-6);
        fprintf(f, "- intervals: %g%% confidence intervals of new/base, Hodges–Lehmann with its rank-based (Moses) "
                   "interval on the log times of the repetitions (the interval of the rank-sum test); a change beyond "
                   "%g%% is judged when its interval excludes 1 and is no wider than the change, no change when the "
                   "interval is no wider than a factor %.4g ((1 + time threshold)^2), otherwise not judged: %d too "
                   "noisy, %d too few repetitions\n",
                100 * (1 - o->alpha), 100 * o->time_threshold, ob_cmp_noise_width(o), r->t_noisy, r->t_few_reps);
        fprintf(f, "- %d rows judged for timing: %d tested on their repetitions, %d by the threshold alone%s\n",
                r->t_judged, r->t_tested, r->t_threshold_only,
                r->t_threshold_only && !(b->has_samples && n->has_samples)
                    ? (b->has_samples || n->has_samples ? " (samples.csv on one side only)" : " (no samples.csv)")
                    : "");
    }
    md_selection(f, r);
    for (int i = 0; i < r->notes.n; i++)
        fprintf(f, "- note: %s\n", r->notes.v[i]);
    for (int i = 0; i < r->strict.n; i++)
        fprintf(f, "- not judged (exit 3): %s\n", r->strict.v[i]);
}

/* What does not decide the verdict, after it, in a collapsed section. */
static void md_not_counted(FILE *f, const ob_cmp_opts *o, const ob_cmp_result *r)
{
    int imp = 0, nw = 0, unc = 0, nj = 0;
    for (int i = 0; i < r->nch; i++) {
        imp += r->ch[i].kind == OB_CH_IMPROVEMENT;
        nw += r->ch[i].kind == OB_CH_NEW;
        unc += listed(r, &r->ch[i], OB_CH_REGRESSION, ROWS_NOT_COUNTED);
        nj += r->ch[i].kind == OB_CH_NOT_JUDGED;
    }
    fprintf(f, "\n<details>\n<summary>Not counted in the verdict: %d improvements, %d new rows, %d timing changes of "
               "rows (--method-timing-only), %d row timings not judged</summary>\n", imp, nw, unc, nj);
    md_table(f, r, OB_CH_IMPROVEMENT, ROWS_ALL, "Improvements", o->max_rows, 1);
    md_table(f, r, OB_CH_NEW, ROWS_ALL, "New rows", o->max_rows, 0);
    md_table(f, r, OB_CH_REGRESSION, ROWS_NOT_COUNTED, "Timing changes of rows, not counted (--method-timing-only: "
             "only the per-method verdicts count)", o->max_rows, 0);
    md_table(f, r, OB_CH_NOT_JUDGED, ROWS_ALL, "Timings not judged: interval unbounded or too wide", o->max_rows, 0);
    fprintf(f, "\n</details>\n");
}

int ob_cmp_write_md(FILE *f, const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o,
                    const ob_cmp_result *r)
{
    static const char *const verdict[] = {"OK: no regression", "REGRESSION", "error", "NOT COMPARABLE"};
    const int st = ob_cmp_status(r);
    fprintf(f, "# offbench compare\n\n");
    fprintf(f, "**%s** (exit %d)", st == 3 && !r->incomparable.n ? "TIMINGS NOT JUDGED" : verdict[st], st);
    if (r->incomparable.n) {
        fprintf(f, "\n\n## Context\n\n");
        side_line(f, b);
        side_line(f, n);
        for (int i = 0; i < r->incomparable.n; i++)
            fprintf(f, "- not comparable: %s\n", r->incomparable.v[i]);
        for (int i = 0; i < r->notes.n; i++)
            fprintf(f, "- note: %s\n", r->notes.v[i]);
        return ferror(f) ? -1 : 0;
    }
    fprintf(f, ": %d joined rows; %d regressions (quality %d, timing %d%s, missing rows %d); "
               "%d improvements (quality %d, timing %d); %d new rows; %d missing rows; "
               "per method: %d slower, %d faster.\n",
            r->joined, r->q_reg + (r->t_rows_count ? r->t_reg : 0) + r->n_missing, r->q_reg, r->t_reg,
            r->t_rows_count || !r->t_reg ? "" : " not counted: --method-timing-only", r->n_missing, r->q_imp + r->t_imp,
            r->q_imp, r->t_imp, r->n_new, r->n_missing, r->m_reg, r->m_imp);
    char timing[2048];
    ob_cmp_timing_text(b, n, o, r, 1, timing, sizeof timing);
    fprintf(f, "Timing: %s.\n", timing);
    if (ob_cmp_left_out_text(r))
        fprintf(f, "Left out: %s (rows of BASE outside NEW's selection: not regressions).\n", ob_cmp_left_out_text(r));
    md_methods(f, o, r);
    md_table(f, r, OB_CH_REGRESSION, ROWS_COUNTED, "Regressions: quality and timing", o->max_rows, 1);
    md_table(f, r, OB_CH_MISSING, ROWS_ALL, "Missing rows: regressions", o->max_rows, 0);
    md_context(f, b, n, o, r);
    md_not_counted(f, o, r);
    md_left_out(f, o, r);
    return ferror(f) ? -1 : 0;
}

/* ---- CSV ---- */

static void csv_line(FILE *f, const char *kind, const ob_res_row *k, const char *method, const char *field,
                     const char *base, const char *nw, double ratio, double p, double lo, double hi,
                     const char *note)
{
    char rt[40], pt[40], lt[40], ht[40];
    num_text(rt, sizeof rt, ratio, 0, NULL);
    num_text(pt, sizeof pt, p, 0, NULL);
    num_text(lt, sizeof lt, lo, 0, NULL);
    num_text(ht, sizeof ht, hi, 0, NULL);
    fprintf(f, "%s,", kind);
    if (k) {
        ob_csv_field(f, k->curve);
        fprintf(f, ",%s,", k->d_text);
        ob_csv_field(f, k->method);
        fputc(',', f);
        ob_csv_field(f, k->metric);
        fputc(',', f);
        ob_csv_field(f, k->split);
        fprintf(f, ",%s,", k->tol_text);
    } else {
        fprintf(f, ",,");
        ob_csv_field(f, method ? method : "");
        fprintf(f, ",,,,");
    }
    ob_csv_field(f, field);
    fputc(',', f);
    ob_csv_field(f, base);
    fputc(',', f);
    ob_csv_field(f, nw);
    fprintf(f, ",%s,%s,%s,%s,", rt, pt, lt, ht);
    ob_csv_field(f, note ? note : "");
    fputc('\n', f);
}

/* "cannot decide": the repetitions needed per side (base) and how many more
 * (new), field need_reps. */
static void csv_need(FILE *f, const char *kind, const ob_method_sum *m)
{
    if (!m->need_reps)
        return;
    const int have = m->reps_base < m->reps_new ? m->reps_base : m->reps_new;
    char need[24], more[24];
    snprintf(need, sizeof need, "%d", m->need_reps);
    snprintf(more, sizeof more, "%d", m->need_reps - have);
    csv_line(f, kind, NULL, m->method, "need_reps", need, more, NAN, NAN, NAN, NAN, "noisy");
}

/* The harness's line: kind harness, field time_total; note its verdict,
 * with "reported_only" when it does not count (compare.h). */
static void csv_harness(FILE *f, const ob_cmp_result *r)
{
    const ob_method_sum *h = &r->harness;
    if (!h->timing)
        return;
    char tb[40], tn[40], note[64];
    num_text(tb, sizeof tb, h->t_base, 0, NULL);
    num_text(tn, sizeof tn, h->t_new, 0, NULL);
    snprintf(note, sizeof note, "%s%s", h->timing, r->harness_counts ? "" : " reported_only");
    csv_line(f, "harness", NULL, "harness", "time_total", tb, tn, h->t_est, h->p, h->ci_lo, h->ci_hi, note);
    csv_need(f, "harness", h);
}

int ob_cmp_write_csv(FILE *f, const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o,
                     const ob_cmp_result *r)
{
    fprintf(f, "kind,curve,d,method,metric,split,tol,field,base,new,ratio,p_value,ci_lo,ci_hi,note\n");
    for (int i = 0; i < r->incomparable.n; i++)
        csv_line(f, "context", NULL, NULL, "not_comparable", r->incomparable.v[i], "", NAN, NAN, NAN, NAN, "");
    for (int i = 0; i < r->timing_diffs.n; i++)
        csv_line(f, "context", NULL, NULL, "timing_not_compared", r->timing_diffs.v[i], "", NAN, NAN, NAN, NAN,
                 r->tstate == OB_TIMING_NOISY ? "noisy" : "");
    for (int i = 0; i < r->notes.n; i++)
        csv_line(f, "context", NULL, NULL, "note", r->notes.v[i], "", NAN, NAN, NAN, NAN, "");
    for (int i = 0; i < r->strict.n; i++)
        csv_line(f, "context", NULL, NULL, "timing_not_judged", r->strict.v[i], "", NAN, NAN, NAN, NAN, "");
    if (!r->incomparable.n) {
        char timing[2048];
        ob_cmp_timing_text(b, n, o, r, 0, timing, sizeof timing);
        csv_line(f, "context", NULL, NULL, "timing", timing, "", NAN, NAN, NAN, NAN, "");
    }
    if (!r->incomparable.n && ob_cmp_left_out_text(r))  /* the summary of the left_out lines below */
        csv_line(f, "context", NULL, NULL, "left_out", ob_cmp_left_out_text(r), "", NAN, NAN, NAN, NAN, "");
    if (r->incomparable.n)
        return ferror(f) ? -1 : 0;
    for (int i = 0; i < r->nch; i++) {
        const ob_change *c = &r->ch[i];
        char bt[64], nt[64];
        value_text(bt, sizeof bt, c->base, c->field, 0);
        value_text(nt, sizeof nt, c->nw, c->field, 0);
        csv_line(f, kind_name(c->kind), c->base ? c->base : c->nw, NULL, c->field, bt, nt, c->ratio, c->p, c->ci_lo,
                 c->ci_hi, c->note);
    }
    for (int i = 0; i < r->nms; i++) {
        const ob_method_sum *m = &r->ms[i];
        char tb[40], tn[40];
        num_text(tb, sizeof tb, m->t_base, 0, NULL);
        num_text(tn, sizeof tn, m->t_new, 0, NULL);
        if (m->verdict)
            csv_line(f, m->verdict > 0 ? "regression" : "improvement", NULL, m->method, "time_total", tb, tn,
                     m->t_est, m->p, m->ci_lo, m->ci_hi, m->timing);
        csv_line(f, "method", NULL, m->method, "ctrl_points_gm", "", "", m->gm_cp, NAN, NAN, NAN, "");
        csv_line(f, "method", NULL, m->method, "max_err_gm", "", "", m->gm_err, NAN, NAN, NAN, "");
        csv_line(f, "method", NULL, m->method, "time_gm", "", "", m->gm_t, NAN, NAN, NAN, "");
        if (m->timing)
            csv_line(f, "method", NULL, m->method, "time_total", tb, tn, m->t_est, m->p, m->ci_lo, m->ci_hi,
                     m->timing);
        csv_need(f, "method", m);
    }
    csv_harness(f, r);
    return ferror(f) ? -1 : 0;
}
