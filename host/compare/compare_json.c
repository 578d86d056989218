/*
 * compare_json.c - `compare --format json`: the report's content as one JSON
 * document (layout in cmd_compare.c).  Numbers that are not finite (no
 * ratio, no p, an unbounded interval end) are written as null.
 */
#include "host/compare/compare.h"
#include "host/compare/compare_subset.h"

#include <math.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "host/io/output.h"

static void jnum(FILE *f, double x)
{
    char b[40];
    if (!isfinite(x)) {
        fputs("null", f);
        return;
    }
    ob_fmt_double(b, sizeof b, x);
    fputs(b, f);
}

/* A string or null. */
static void jstr(FILE *f, const char *s)
{
    if (s)
        ob_json_string(f, s);
    else
        fputs("null", f);
}

static void jlist(FILE *f, const char *key, const ob_strlist *l, int last)
{
    fprintf(f, "    \"%s\": [", key);
    for (int i = 0; i < l->n; i++) {
        fputs(i ? ", " : "", f);
        ob_json_string(f, l->v[i]);
    }
    fprintf(f, "]%s\n", last ? "" : ",");
}

static void jside(FILE *f, const char *key, const ob_cmp_side *s)
{
    const ob_json_entry *c = ob_json_get(&s->meta, "git_commit"), *d = ob_json_get(&s->meta, "git_dirty");
    const ob_json_entry *ts = ob_json_get(&s->meta, "timestamp"), *cpu = ob_json_get(&s->meta, "cpu_model");
    fprintf(f, "  \"%s\": {\"results\": ", key);
    ob_json_string(f, s->results_path);
    fprintf(f, ", \"rows\": %d, \"meta\": %s, \"git_commit\": ", s->res.n, s->has_meta ? "true" : "false");
    jstr(f, c ? c->value : NULL);
    fprintf(f, ", \"git_dirty\": %s, \"timestamp\": ", d && strcmp(d->value, "true") == 0 ? "true" : "false");
    jstr(f, ts ? ts->value : NULL);
    fprintf(f, ", \"cpu_model\": ");
    jstr(f, cpu ? cpu->value : NULL);
    const ob_json_entry *mn = ob_json_get(&s->meta, "machine.name"), *mi = ob_json_get(&s->meta, "machine.id");
    fprintf(f, ", \"machine\": ");
    jstr(f, mn ? mn->value : NULL);
    fprintf(f, ", \"machine_id\": ");
    jstr(f, mi ? mi->value : NULL);
    fprintf(f, ", \"repetitions\": %d},\n", s->has_samples ? s->res.maxrep : 0);
}

/* A change's value of its field: a string (status), a number (certified:
 * err_upper), or null. */
static void jvalue(FILE *f, const ob_res_row *row, const char *field)
{
    if (!row)
        fputs("null", f);
    else if (strcmp(field, "status") == 0)
        ob_json_string(f, row->status);
    else if (strcmp(field, "ctrl_points") == 0)
        fprintf(f, "%ld", row->ctrl_points);
    else if (strcmp(field, "max_err") == 0)
        jnum(f, row->max_err);
    else if (strcmp(field, "certified") == 0)
        jnum(f, row->err_upper);  /* the certificate, not the job's time */
    else
        jnum(f, row->fit_ns + row->eval_ns);
}

static void jchange(FILE *f, const ob_change *c, const char *kind)
{
    const ob_res_row *k = c->base ? c->base : c->nw;
    fprintf(f, "    {\"kind\": \"%s\", \"curve\": ", kind);
    ob_json_string(f, k->curve);
    fprintf(f, ", \"d\": ");
    jnum(f, k->d);
    fprintf(f, ", \"method\": ");
    ob_json_string(f, k->method);
    fprintf(f, ", \"metric\": ");
    ob_json_string(f, k->metric);
    fprintf(f, ", \"split\": ");
    ob_json_string(f, k->split);
    fprintf(f, ", \"tol\": ");
    jnum(f, k->tol);
    fprintf(f, ", \"field\": \"%s\", \"base\": ", c->field);
    jvalue(f, c->base, c->field);
    fprintf(f, ", \"new\": ");
    jvalue(f, c->nw, c->field);
    fprintf(f, ", \"ratio\": ");
    jnum(f, c->ratio);
    fprintf(f, ", \"p_value\": ");
    jnum(f, c->p);
    fprintf(f, ", \"ci_lo\": ");
    jnum(f, c->ci_lo);
    fprintf(f, ", \"ci_hi\": ");
    jnum(f, c->ci_hi);
    fprintf(f, ", \"note\": ");
    ob_json_string(f, c->note ? c->note : "");
    fputc('}', f);
}

static void jmethod(FILE *f, const ob_method_sum *m)
{
    fprintf(f, "    {\"method\": ");
    ob_json_string(f, m->method);
    fprintf(f, ", \"rows\": %d, \"ctrl_points_gm\": ", m->rows);
    jnum(f, m->gm_cp);
    fprintf(f, ", \"max_err_gm\": ");
    jnum(f, m->gm_err);
    fprintf(f, ", \"time_gm\": ");
    jnum(f, m->gm_t);
    fprintf(f, ", \"time_base_ns\": ");
    jnum(f, m->t_base);
    fprintf(f, ", \"time_new_ns\": ");
    jnum(f, m->t_new);
    fprintf(f, ", \"time_estimate\": ");
    jnum(f, m->t_est);
    fprintf(f, ", \"timing\": ");
    jstr(f, m->timing);
    fprintf(f, ", \"p_value\": ");
    jnum(f, m->p);
    fprintf(f, ", \"ci_lo\": ");
    jnum(f, m->ci_lo);
    fprintf(f, ", \"ci_hi\": ");
    jnum(f, m->ci_hi);
    fprintf(f, ", \"reps_base\": %d, \"reps_new\": %d, \"regressions\": %d, \"improvements\": %d, \"verdict\": \"%s\", "
               "\"timing_not_judged\": ",
            m->reps_base, m->reps_new, m->regressions, m->improvements,
            m->verdict > 0 ? "slower" : m->verdict < 0 ? "faster" : "same");
    jstr(f, m->not_judged);
    fprintf(f, ", \"need_reps\": %d, \"timing_words\": ", m->need_reps);
    ob_json_string(f, ob_cmp_timing_word(m));
    /* "verdict" is the timing's (as it always was); this is the method's, as
     * report.md's per-method table gives it */
    fprintf(f, ", \"method_verdict\": \"%s\"}", ob_method_verdict(m));
}

/* "left_out": the rows of BASE outside NEW's selection (compare_subset.h):
 * how many, the summary and NEW's selection in words (null without). */
static void jleft_out(FILE *f, const ob_cmp_result *r)
{
    fprintf(f, "  \"left_out\": {\"rows\": %d, \"summary\": ", r->n_left_out);
    jstr(f, ob_cmp_left_out_text(r));
    fprintf(f, ", \"selection\": ");
    jstr(f, ob_cmp_selection_text(r));
    fprintf(f, "},\n");
}

int ob_cmp_write_json(FILE *f, const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o,
                      const ob_cmp_result *r)
{
    static const char *const verdict[] = {"ok", "regression", "error", "not_comparable"};
    const int st = ob_cmp_status(r);
    fprintf(f, "{\n  \"program\": \"offbench compare\",\n  \"status\": %d,\n  \"verdict\": \"%s\",\n", st,
            st == 3 && !r->incomparable.n ? "timing_not_judged" : verdict[st]);
    jside(f, "base", b);
    jside(f, "new", n);
    fprintf(f, "  \"options\": {\"err_rtol\": ");
    jnum(f, o->err_rtol);
    fprintf(f, ", \"err_atol\": ");
    jnum(f, o->err_atol);
    fprintf(f, ", \"time_threshold\": ");
    jnum(f, o->time_threshold);
    fprintf(f, ", \"time_floor_ns\": ");
    jnum(f, o->time_floor_ns);
    fprintf(f, ", \"alpha\": ");
    jnum(f, o->alpha);
    fprintf(f, ", \"no_timing\": %s, \"method_timing_only\": %s, \"strict_timing\": %s, \"timing_only\": %s, "
               "\"methods\": ",
            o->no_timing ? "true" : "false", o->method_timing_only ? "true" : "false",
            o->strict_timing ? "true" : "false", o->timing_only ? "true" : "false");
    jstr(f, o->methods);
    fprintf(f, "},\n");
    char timing[2048];
    ob_cmp_timing_text(b, n, o, r, 0, timing, sizeof timing);
    fprintf(f, "  \"context\": {\n    \"checked\": %s,\n    \"timing_compared\": %s,\n    \"timing\": ",
            r->checked ? "true" : "false", r->timing ? "true" : "false");
    ob_json_string(f, timing);
    fprintf(f, ",\n");
    fprintf(f, "    \"interval\": \"%g%% Hodges-Lehmann (Moses) interval of new/base on the log times of the "
               "repetitions\",\n    \"noise_width\": ", 100 * (1 - o->alpha));
    jnum(f, ob_cmp_noise_width(o));
    fprintf(f, ",\n");
    jlist(f, "not_comparable", &r->incomparable, 0);
    jlist(f, "timing_not_compared", &r->timing_diffs, 0);
    jlist(f, "timing_not_judged", &r->strict, 0);
    jlist(f, "notes", &r->notes, 1);
    fprintf(f, "  },\n  \"counts\": {\"joined\": %d, \"quality_regressions\": %d, \"timing_regressions\": %d, "
               "\"timing_regressions_count\": %s, \"missing\": %d, \"new\": %d, \"quality_improvements\": %d, "
               "\"timing_improvements\": %d, \"methods_slower\": %d, \"methods_faster\": %d, \"timing_judged\": %d, "
               "\"timing_tested\": %d, \"timing_threshold_only\": %d, \"timing_noisy\": %d, "
               "\"timing_few_reps\": %d},\n",
            r->joined, r->q_reg, r->t_reg, r->t_rows_count ? "true" : "false", r->n_missing, r->n_new, r->q_imp,
            r->t_imp, r->m_reg, r->m_imp, r->t_judged, r->t_tested, r->t_threshold_only, r->t_noisy, r->t_few_reps);
    jleft_out(f, r);
    fprintf(f, "  \"changes\": [");
    int first = 1;
    for (int i = 0; !r->incomparable.n && i < r->nch; i++) {
        fputs(first ? "\n" : ",\n", f);
        jchange(f, &r->ch[i], (const char *[]){"regression", "improvement", "new", "missing", "not_judged",
                                               "left_out"}[r->ch[i].kind]);
        first = 0;
    }
    fprintf(f, "%s],\n  \"methods\": [", first ? "" : "\n  ");
    for (int i = 0; !r->incomparable.n && i < r->nms; i++) {
        fputs(i ? ",\n" : "\n", f);
        jmethod(f, &r->ms[i]);
    }
    fprintf(f, "%s],\n  \"timed\": \"%s\",\n  \"harness\": ", r->nms && !r->incomparable.n ? "\n  " : "",
            r->method_time ? "method_ns" : "fit_ns+eval_ns");
    if (r->harness.timing && !r->incomparable.n) {
        jmethod(f, &r->harness);
        fprintf(f, ",\n  \"harness_counts\": %s\n}\n", r->harness_counts ? "true" : "false");
    } else {
        fprintf(f, "null,\n  \"harness_counts\": %s\n}\n", r->harness_counts ? "true" : "false");
    }
    return ferror(f) ? -1 : 0;
}
