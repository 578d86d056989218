/*
 * compare_report.c - the Markdown and CSV reports of `compare` (their
 * layout is documented in cmd_compare.c).
 */
#include "host/compare/compare.h"

#include <math.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "host/io/output.h"

/* A field of a change as text: value of `row` for `field`; md: time in ms. */
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
    else if (md)
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
    static const char *const n[] = {"regression", "improvement", "new", "missing", "not_judged"};
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

/* Rows of one kind: changes (field, base, new, ratio, p) or rows (new / missing). */
static void md_table(FILE *f, const ob_cmp_result *r, ob_ch_kind kind, const char *title, int max_rows,
                     int always)
{
    int total = 0;
    for (int i = 0; i < r->nch; i++)
        total += r->ch[i].kind == kind;
    if (!total && !always)
        return;
    fprintf(f, "\n## %s (%d)\n\n", title, total);
    if (!total) {
        fprintf(f, "None.\n");
        return;
    }
    const int rows_only = kind == OB_CH_NEW || kind == OB_CH_MISSING;
    fprintf(f, "| curve | d | method | metric | split | tol | %s |\n",
            rows_only ? "status | ctrl_points | max_err" : "field | base | new | new/base | p | interval");
    fprintf(f, "|---|---:|---|---|---|---:|%s\n", rows_only ? "---|---:|---:|" : "---|---:|---:|---:|---:|---:|");
    int shown = 0;
    for (int i = 0; i < r->nch && shown < max_rows; i++) {
        const ob_change *c = &r->ch[i];
        if (c->kind != kind)
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

static void md_methods(FILE *f, const ob_cmp_result *r)
{
    fprintf(f, "\n## Per method (geometric mean of new/base over the joined rows)\n\n");
    if (!r->nms) {
        fprintf(f, "None.\n");
        return;
    }
    fprintf(f, "| method | rows | ctrl_points | max_err | time | p | time interval | regressions | improvements | "
               "verdict |\n"
               "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int i = 0; i < r->nms; i++) {
        const ob_method_sum *m = &r->ms[i];
        char cp[32], er[32], t[32], p[32], ci[64];
        num_text(cp, sizeof cp, m->gm_cp, 1, "%.4g");
        num_text(er, sizeof er, m->gm_err, 1, "%.4g");
        num_text(t, sizeof t, m->gm_t, 1, "%.4g");
        num_text(p, sizeof p, m->p, 1, "%.3g");
        interval_text(ci, sizeof ci, m->ci_lo, m->ci_hi);
        const int reg = m->regressions > 0 || m->verdict > 0, imp = m->improvements > 0 || m->verdict < 0;
        fprintf(f, "| %s | %d | %s | %s | %s | %s | %s | %d | %d | %s%s%s%s |\n", m->method, m->rows, cp, er, t, p,
                ci, m->regressions, m->improvements, reg ? "regression" : imp ? "improvement" : "same",
                m->verdict > 0 ? " (slower)" : m->verdict < 0 ? " (faster)" : "",
                m->not_judged ? "; timing not judged: " : "", m->not_judged ? m->not_judged : "");
    }
}

int ob_cmp_write_md(FILE *f, const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o,
                    const ob_cmp_result *r)
{
    static const char *const verdict[] = {"OK: no regression", "REGRESSION", "error", "NOT COMPARABLE"};
    const int st = ob_cmp_status(r);
    fprintf(f, "# offbench compare\n\n");
    side_line(f, b);
    side_line(f, n);
    fprintf(f, "\n**%s** (exit %d)", st == 3 && !r->incomparable.n ? "TIMINGS NOT JUDGED (--strict-timing)" : verdict[st],
            st);
    if (r->incomparable.n) {
        fprintf(f, "\n\n## Context\n\n");
        for (int i = 0; i < r->incomparable.n; i++)
            fprintf(f, "- not comparable: %s\n", r->incomparable.v[i]);
        for (int i = 0; i < r->notes.n; i++)
            fprintf(f, "- note: %s\n", r->notes.v[i]);
        return ferror(f) ? -1 : 0;
    }
    fprintf(f, ": %d joined rows; %d regressions (quality %d, timing %d%s, missing rows %d); "
               "%d improvements (quality %d, timing %d); %d new rows; %d missing rows; "
               "per method: %d slower, %d faster.\n",
            r->joined, r->q_reg + r->t_reg + r->n_missing, r->q_reg, r->t_reg,
            r->t_rows_count || !r->t_reg ? "" : " not counted: --method-timing-only", r->n_missing, r->q_imp + r->t_imp,
            r->q_imp, r->t_imp, r->n_new, r->n_missing, r->m_reg, r->m_imp);
    fprintf(f, "\n## Context\n\n");
    if (r->checked)
        fprintf(f, "- comparable: samples_per_segment, max_depth, max_segments, inflection_split, seed, and the "
                   "method_params and method_versions of the methods both runs ran are equal\n");
    if (o->no_timing)
        fprintf(f, "- timings: not compared (--no-timing)\n");
    else if (r->timing_diffs.n) {
        fprintf(f, "- timings: **not compared**, the timing context differs:\n");
        for (int i = 0; i < r->timing_diffs.n; i++)
            fprintf(f, "  - %s\n", r->timing_diffs.v[i]);
    } else {
        fprintf(f, "- timings: compared (%s); a row is judged when both statuses are equal and both times "
                   "(fit_ns + eval_ns) are at least %g ms; a change is beyond %g%%",
                r->checked ? "same compiler, cflags, backend, OpenCL device and driver, OMP threads, CPU model"
                           : "timing context not checked",
                o->time_floor_ns * 1e-6, o->time_threshold * 100);
        fprintf(f, " and, with at least 2 repetitions per side, significant by a two-sided Mann–Whitney U test "
                   "(alpha %g)\n", o->alpha);
        fprintf(f, "- intervals: %g%% confidence intervals of new/base, Hodges–Lehmann with its rank-based (Moses) "
                   "interval on the log times of the repetitions; a row that is no significant change is not judged "
                   "when its interval is unbounded (too few repetitions) or wider than a factor %.4g "
                   "((1 + time threshold)^2): %d too noisy, %d too few repetitions\n",
                100 * (1 - o->alpha), ob_cmp_noise_width(o), r->t_noisy, r->t_few_reps);
        fprintf(f, "- %d rows judged for timing: %d tested on their repetitions, %d by the threshold alone%s\n",
                r->t_judged, r->t_tested, r->t_threshold_only,
                r->t_threshold_only && !(b->has_samples && n->has_samples)
                    ? (b->has_samples || n->has_samples ? " (samples.csv on one side only)" : " (no samples.csv)")
                    : "");
    }
    for (int i = 0; i < r->notes.n; i++)
        fprintf(f, "- note: %s\n", r->notes.v[i]);
    for (int i = 0; i < r->strict.n; i++)
        fprintf(f, "- not judged (--strict-timing: exit 3): %s\n", r->strict.v[i]);
    md_table(f, r, OB_CH_REGRESSION, "Regressions: quality and timing", o->max_rows, 1);
    md_table(f, r, OB_CH_MISSING, "Missing rows: regressions", o->max_rows, 0);
    md_table(f, r, OB_CH_IMPROVEMENT, "Improvements", o->max_rows, 1);
    md_table(f, r, OB_CH_NEW, "New rows", o->max_rows, 0);
    md_table(f, r, OB_CH_NOT_JUDGED, "Timings not judged: interval unbounded or too wide", o->max_rows, 0);
    md_methods(f, r);
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

int ob_cmp_write_csv(FILE *f, const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o,
                     const ob_cmp_result *r)
{
    (void)b;
    (void)n;
    (void)o;
    fprintf(f, "kind,curve,d,method,metric,split,tol,field,base,new,ratio,p_value,ci_lo,ci_hi,note\n");
    for (int i = 0; i < r->incomparable.n; i++)
        csv_line(f, "context", NULL, NULL, "not_comparable", r->incomparable.v[i], "", NAN, NAN, NAN, NAN, "");
    for (int i = 0; i < r->timing_diffs.n; i++)
        csv_line(f, "context", NULL, NULL, "timing_not_compared", r->timing_diffs.v[i], "", NAN, NAN, NAN, NAN, "");
    for (int i = 0; i < r->notes.n; i++)
        csv_line(f, "context", NULL, NULL, "note", r->notes.v[i], "", NAN, NAN, NAN, NAN, "");
    for (int i = 0; i < r->strict.n; i++)
        csv_line(f, "context", NULL, NULL, "timing_not_judged", r->strict.v[i], "", NAN, NAN, NAN, NAN, "");
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
        const char *nj = m->not_judged ? m->not_judged : "";
        if (m->verdict)
            csv_line(f, m->verdict > 0 ? "regression" : "improvement", NULL, m->method, "time_gm", "", "", m->gm_t,
                     m->p, m->ci_lo, m->ci_hi, "");
        csv_line(f, "method", NULL, m->method, "ctrl_points_gm", "", "", m->gm_cp, NAN, NAN, NAN, "");
        csv_line(f, "method", NULL, m->method, "max_err_gm", "", "", m->gm_err, NAN, NAN, NAN, "");
        csv_line(f, "method", NULL, m->method, "time_gm", "", "", m->gm_t, m->p, m->ci_lo, m->ci_hi, nj);
    }
    return ferror(f) ? -1 : 0;
}
