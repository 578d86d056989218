/*
 * compare.c - the join and the verdicts of `compare` (the rules are spelled
 * out in cmd_compare.c; loading and comparability: compare_context.c).
 */
#include "host/compare/compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/compare/compare_subset.h"
#include "host/compare/hlshift.h"
#include "host/compare/ranktest.h"
#include "host/io/strmap.h"
#include "methods/driver/driver.h"

/* ---- join and verdicts ---- */

typedef struct {
    const ob_res_row *b, *n;
    int judged; /* for timing */
    int m;      /* index in r->ms */
} pair;

static int add_change_ci(ob_cmp_result *r, ob_ch_kind kind, const char *field, const ob_res_row *b,
                         const ob_res_row *n, double ratio, double p, double lo, double hi, const char *note)
{
    if (r->nch == r->capch) {
        int cap = r->capch ? 2 * r->capch : 64;
        ob_change *nv = realloc(r->ch, (size_t)cap * sizeof *nv);
        if (!nv)
            return -1;
        r->ch = nv;
        r->capch = cap;
    }
    r->ch[r->nch++] = (ob_change){kind, field, b, n, ratio, p, lo, hi, note};
    return 0;
}

static int add_change(ob_cmp_result *r, ob_ch_kind kind, const char *field, const ob_res_row *b, const ob_res_row *n,
                      double ratio, double p)
{
    return add_change_ci(r, kind, field, b, n, ratio, p, NAN, NAN, "");
}

double ob_cmp_noise_width(const ob_cmp_opts *o)
{
    return (1 + o->time_threshold) * (1 + o->time_threshold);
}

/* The Hodges-Lehmann estimate of new/base and its interval from the
 * repetitions xn[0..kn), xb[0..kb) (hlshift.h, on log times; a time under
 * 1 ns counts as 1 ns, so that its log is finite): the estimate and the
 * interval are of the same statistic, so the estimate always lies inside.
 * Overwrites xn and xb with their logs.  Returns 1 when the interval is
 * bounded, 0 when there are too few repetitions for one at alpha. */
static int hl_time(double *xn, int kn, double *xb, int kb, const ob_cmp_opts *o, double *est, double *lo, double *hi)
{
    for (int i = 0; i < kn; i++)
        xn[i] = log(xn[i] > 1 ? xn[i] : 1);
    for (int j = 0; j < kb; j++)
        xb[j] = log(xb[j] > 1 ? xb[j] : 1);
    const ob_hl_result h = ob_hl_shift(xn, kn, xb, kb, o->alpha);
    *est = exp(h.est);
    *lo = exp(h.lo);
    *hi = exp(h.hi);
    return h.k > 0 && isfinite(h.lo) && isfinite(h.hi) && isfinite(h.est);
}

/* The timing verdict of an estimate est of new/base with its interval
 * [lo, hi] (bounded: hl_time), band = 1 + time_threshold:
 *   - no bounded interval: "few_reps";
 *   - est beyond the band (est > band or est < 1 / band): "slower" /
 *     "faster" when the interval excludes 1 on the same side (significant,
 *     as the rank test the interval inverts) and is no wider than the change
 *     it reports (log(hi / lo) <= |log est|), else "noisy";
 *   - est within the band: "same" when hi / lo <= band^2 (the interval no
 *     wider than the band of ratios that count as unchanged), else "noisy".
 * So the repetitions of a run decide only when their spread is smaller than
 * what they would report. */
static const char *time_verdict(double est, double lo, double hi, int bounded, const ob_cmp_opts *o)
{
    const double band = 1 + o->time_threshold;
    if (!bounded)
        return "few_reps";
    if (est > band || est < 1 / band) {
        const int excludes_one = est > 1 ? lo > 1 : hi < 1;
        if (excludes_one && log(hi / lo) <= fabs(log(est)))
            return est > 1 ? "slower" : "faster";
        return "noisy";
    }
    return hi / lo <= band * band ? "same" : "noisy";
}

/* The verdict of a ratio measured once per side: the threshold alone. */
static const char *threshold_verdict(double ratio, const ob_cmp_opts *o)
{
    const double band = 1 + o->time_threshold;
    return ratio > band ? "slower" : ratio < 1 / band ? "faster" : "same";
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of x[0..n) (n >= 1); sorts x. */
static double median_sorting(double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, cmp_double);
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/* The methods of the join: r->ms grown by doubling (cap), found by name in
 * ix, so that n rows of n methods cost n, not n x n. */
typedef struct {
    ob_strmap ix;
    int cap;
} method_table;

/* The index of method m in r->ms (added when new), or -1 out of memory. */
static int method_index(ob_cmp_result *r, method_table *t, const char *m)
{
    const long i = ob_strmap_put(&t->ix, m, r->nms);
    if (i != -1)
        return i >= 0 ? (int)i : -1;
    if (r->nms >= t->cap) {
        const int cap = r->nms < 8 ? 16 : 2 * r->nms;
        ob_method_sum *nv = realloc(r->ms, (size_t)cap * sizeof *nv);
        if (!nv)
            return -1;  /* the map then names a method r->ms lacks: the comparison fails */
        r->ms = nv;
        t->cap = cap;
    }
    memset(&r->ms[r->nms], 0, sizeof *r->ms);
    r->ms[r->nms].method = m;
    r->ms[r->nms].p = NAN;
    r->ms[r->nms].ci_lo = r->ms[r->nms].ci_hi = NAN;
    r->ms[r->nms].t_base = r->ms[r->nms].t_new = r->ms[r->nms].t_est = NAN;
    return r->nms++;
}

static int is_ok(const char *s) { return strcmp(s, "ok") == 0; }

static double ratio_of(double n, double b) { return b > 0 && isfinite(b) && isfinite(n) ? n / b : NAN; }

/* What a row's time is (r->method_time): the method's own time (run
 * --time-fits: method_ns, its rounds in fits.csv), or fit_ns + eval_ns
 * (its repetitions in samples.csv). */
static double row_time(const ob_res_row *row, int method_time)
{
    return method_time ? row->method_ns : row->fit_ns + row->eval_ns;
}

static const double *row_reps(const ob_res_row *row, int method_time)
{
    return method_time ? row->round_m : row->rep_t;
}

/* The repetitions a side holds of what is timed. */
static int side_reps(const ob_cmp_side *s, int method_time)
{
    return method_time ? s->res.maxround : s->res.maxrep;
}

/* Quality of a joined row: status, then ctrl_points, then max_err, then
 * (both certified) whether err_upper is within tol. */
static int judge_quality(const ob_res_row *b, const ob_res_row *n, const ob_cmp_opts *o, ob_cmp_result *r,
                         ob_method_sum *m)
{
    ob_ch_kind k;
    const char *field;
    double ratio = NAN;
    if (strcmp(b->status, n->status) != 0) {
        field = "status";
        k = !is_ok(b->status) && is_ok(n->status) ? OB_CH_IMPROVEMENT : OB_CH_REGRESSION;
    } else if (!is_ok(b->status) && strcmp(b->status, "limit") != 0) {
        return 0; /* both fail or both skip: nothing to measure */
    } else if (n->ctrl_points != b->ctrl_points) {
        field = "ctrl_points";
        k = n->ctrl_points > b->ctrl_points ? OB_CH_REGRESSION : OB_CH_IMPROVEMENT;
        ratio = ratio_of((double)n->ctrl_points, (double)b->ctrl_points);
    } else {
        double eb = b->max_err, en = n->max_err;
        field = "max_err";
        if (isnan(eb) && isnan(en))
            return 0;
        ratio = ratio_of(en, eb);
        if (isnan(en) || (!isnan(eb) && en > eb * (1 + o->err_rtol) + o->err_atol)) {
            k = OB_CH_REGRESSION;
        } else if (isnan(eb) || eb > en * (1 + o->err_rtol) + o->err_atol) {
            k = OB_CH_IMPROVEMENT;
        } else if (b->cert_done && n->cert_done && (b->err_upper <= b->tol) != (n->err_upper <= n->tol)) {
            /* both certified (run --certify): within tol no longer, or now */
            field = "certified";
            k = n->err_upper <= n->tol ? OB_CH_IMPROVEMENT : OB_CH_REGRESSION;
            ratio = ratio_of(n->err_upper, b->err_upper);
        } else {
            return 0;
        }
    }
    if (k == OB_CH_REGRESSION)
        r->q_reg++, m->regressions++;
    else
        r->q_imp++, m->improvements++;
    return add_change(r, k, field, b, n, ratio, NAN);
}

/* The repetitions v[0..maxrep) present (not NAN), into x; their count. */
static int rep_values(const double *v, int maxrep, double *x)
{
    int k = 0;
    for (int i = 0; v && i < maxrep; i++)
        if (!isnan(v[i]))
            x[k++] = v[i];
    return k;
}

/* Timing of a joined row; *judged = 1 when it was due to be judged (timings
 * compared, same status, both above the floor).  With repetitions on both
 * sides the row's estimate is the HL ratio with its interval and
 * time_verdict decides; without, the ratio of the two times and the
 * threshold.  A row too noisy to judge, or with too few repetitions, is
 * listed as not judged. */
static int judge_time(const ob_cmp_side *bs, const ob_cmp_side *ns, const ob_res_row *b, const ob_res_row *n,
                      const ob_cmp_opts *o, ob_cmp_result *r, ob_method_sum *m, double *xb, double *xn,
                      int *judged)
{
    const int mt = r->method_time;
    const double tb = row_time(b, mt), tn = row_time(n, mt);
    /* the floor keeps single short timings out; a method time is already a
     * calibrated measurement (fittime.h), so it needs none: only both timed */
    const int long_enough = mt ? b->fit_calls > 0 && n->fit_calls > 0
                               : tb >= o->time_floor_ns && tn >= o->time_floor_ns;
    *judged = r->timing && strcmp(b->status, n->status) == 0 && long_enough && tb > 0 && tn > 0;
    if (!*judged)
        return 0;
    r->t_judged++;
    int kb = rep_values(row_reps(b, mt), side_reps(bs, mt), xb), kn = rep_values(row_reps(n, mt), side_reps(ns, mt), xn);
    const int tested = kb >= 2 && kn >= 2;
    if (tested)
        r->t_tested++;
    else
        r->t_threshold_only++;
    double ratio = tn / tb, p = NAN, lo = NAN, hi = NAN;
    const char *v;
    if (tested) {
        p = ob_mann_whitney(xn, kn, xb, kb).p;
        const int bounded = hl_time(xn, kn, xb, kb, o, &ratio, &lo, &hi);
        v = time_verdict(ratio, lo, hi, bounded, o);
    } else {
        v = threshold_verdict(ratio, o);
    }
    if (strcmp(v, "same") == 0)
        return 0;
    if (strcmp(v, "noisy") == 0 || strcmp(v, "few_reps") == 0) {
        if (strcmp(v, "noisy") == 0)
            r->t_noisy++;
        else
            r->t_few_reps++;
        return add_change_ci(r, OB_CH_NOT_JUDGED, "time", b, n, ratio, p, lo, hi, v);
    }
    const ob_ch_kind k = strcmp(v, "slower") == 0 ? OB_CH_REGRESSION : OB_CH_IMPROVEMENT;
    if (k == OB_CH_REGRESSION)
        r->t_reg++, m->regressions += r->t_rows_count;
    else
        r->t_imp++, m->improvements += r->t_rows_count;
    return add_change_ci(r, k, "time", b, n, ratio, p, lo, hi, "");
}

/* The pairs of each method together: order[start[mi] .. start[mi + 1])
 * are the indices in pr of method mi's pairs, in file order (a counting
 * sort), so that each per-method pass reads its own pairs only (methods x
 * pairs would be quadratic).  0, or -1 out of memory. */
static int group_by_method(const pair *pr, int np, int nms, int **order, int **start)
{
    int *o = malloc((size_t)(np ? np : 1) * sizeof *o), *st = calloc((size_t)nms + 2, sizeof *st);
    *order = o;
    *start = st;
    if (!o || !st)
        return -1;
    for (int i = 0; i < np; i++)
        st[pr[i].m + 2]++;
    for (int m = 2; m < nms + 2; m++)
        st[m] += st[m - 1];
    for (int i = 0; i < np; i++)  /* st[m + 1]: the next place of method m */
        o[st[pr[i].m + 1]++] = i;
    return 0;
}

/* Per-repetition totals over the judged rows of one method (its pairs
 * pr[grp[0..ng)]) on one side (a repetition counts when every one of those
 * rows has it); their count. */
static int method_totals(const pair *pr, const int *grp, int ng, int new_side, int maxrep, int mt, int harness,
                         double *tot)
{
    int k = 0;
    for (int rep = 0; rep < maxrep; rep++) {
        double sum = 0;
        int complete = 1, rows = 0;
        for (int g = 0; g < ng && complete; g++) {
            const int i = grp ? grp[g] : g;
            if (!pr[i].judged)
                continue;
            const ob_res_row *row = new_side ? pr[i].n : pr[i].b;
            const double *v = harness ? row->rep_e : row_reps(row, mt);
            complete = v && !isnan(v[rep]);
            sum += complete ? v[rep] : 0;
            rows++;
        }
        if (complete && rows)
            tot[k++] = sum;
    }
    return k;
}

/* Repetitions per side that would make an interval of width log(hi / lo)
 * from n per side narrow enough for time_verdict to decide: a change
 * beyond the band needs a width of at most |log est|, no change at most
 * the band's own 2 log(1 + threshold); the width of a rank interval
 * shrinks about as 1 / sqrt(n). */
static int reps_needed(double est, double lo, double hi, int n, const ob_cmp_opts *o)
{
    const double band = 1 + o->time_threshold, w = log(hi / lo);
    const double target = est > band || est < 1 / band ? fabs(log(est)) : 2 * log(band);
    const double need = ceil(n * (w / target) * (w / target));
    return !(need > n) ? n + 1 : need > 100000 ? 100000 : (int)need;
}

/* One timing claim from per-repetition totals xb[0..reps_base),
 * xn[0..reps_new) (both at least 2: the HL estimate and its interval), else
 * from m->t_new / m->t_base by the threshold alone. */
static void judge_totals(ob_method_sum *m, const ob_cmp_opts *o, double *xb, double *xn)
{
    if (m->reps_base >= 2 && m->reps_new >= 2) {
        m->p = ob_mann_whitney(xn, m->reps_new, xb, m->reps_base).p;
        m->t_base = median_sorting(xb, m->reps_base);
        m->t_new = median_sorting(xn, m->reps_new);
        const int bounded = hl_time(xn, m->reps_new, xb, m->reps_base, o, &m->t_est, &m->ci_lo, &m->ci_hi);
        m->timing = time_verdict(m->t_est, m->ci_lo, m->ci_hi, bounded, o);
        m->not_judged = strcmp(m->timing, "noisy") == 0 || strcmp(m->timing, "few_reps") == 0 ? m->timing : NULL;
        if (strcmp(m->timing, "noisy") == 0)
            m->need_reps = reps_needed(m->t_est, m->ci_lo, m->ci_hi,
                                       m->reps_base < m->reps_new ? m->reps_base : m->reps_new, o);
    } else {
        m->t_est = m->t_new / m->t_base;
        m->timing = threshold_verdict(m->t_est, o);
        m->not_judged = "no_samples";
    }
}

/* The timing verdict of each method: on its per-repetition totals when
 * both sides have at least 2 complete repetitions (the HL estimate and its
 * interval, time_verdict), else on the ratio of its summed times
 * (method_means) by the threshold alone. */
static void judge_methods(const ob_cmp_side *bs, const ob_cmp_side *ns, const pair *pr, const int *order,
                          const int *start, const ob_cmp_opts *o, ob_cmp_result *r, double *xb, double *xn)
{
    for (int mi = 0; mi < r->nms; mi++) {
        ob_method_sum *m = &r->ms[mi];
        if (!(m->n_t > 0) || !r->timing)
            continue;
        const int *grp = order + start[mi], ng = start[mi + 1] - start[mi], mt = r->method_time;
        m->reps_base = method_totals(pr, grp, ng, 0, side_reps(bs, mt), mt, 0, xb);
        m->reps_new = method_totals(pr, grp, ng, 1, side_reps(ns, mt), mt, 0, xn);
        judge_totals(m, o, xb, xn);
        if (strcmp(m->timing, "slower") == 0)
            m->verdict = 1, r->m_reg++;
        else if (strcmp(m->timing, "faster") == 0)
            m->verdict = -1, r->m_imp++;
        else if (strcmp(m->timing, "noisy") == 0)
            r->undecided++;
        if (m->verdict)
            m->not_judged = NULL;  /* a change was judged (by the threshold alone without samples) */
    }
}

/* The harness's line: the measuring time (eval_ns) of every row judged for
 * timing, per repetition (samples.csv), judged as a method is; without
 * repetitions on both sides, the summed eval_ns by the threshold. */
static void judge_harness(const ob_cmp_side *bs, const ob_cmp_side *ns, const pair *pr, int np,
                          const ob_cmp_opts *o, ob_cmp_result *r, double *xb, double *xn)
{
    ob_method_sum *h = &r->harness;
    memset(h, 0, sizeof *h);
    h->method = "harness";
    h->p = h->ci_lo = h->ci_hi = h->t_est = NAN;
    double sb = 0, sn = 0;
    for (int i = 0; i < np; i++)
        if (pr[i].judged)
            sb += pr[i].b->eval_ns, sn += pr[i].n->eval_ns, h->n_t++, h->rows++;
    if (!r->timing || !h->n_t || !(sb > 0) || !(sn > 0))
        return;
    h->t_base = sb;
    h->t_new = sn;
    h->reps_base = method_totals(pr, NULL, np, 0, bs->res.maxrep, 0, 1, xb);
    h->reps_new = method_totals(pr, NULL, np, 1, ns->res.maxrep, 0, 1, xn);
    judge_totals(h, o, xb, xn);
    h->verdict = strcmp(h->timing, "slower") == 0 ? 1 : strcmp(h->timing, "faster") == 0 ? -1 : 0;
}

/* The joint columns (max_gap, max_kink, continuity) are informational: a
 * note says how many joined rows reach another measured continuity, or that
 * one side has no such columns (an older build).  Never judged: an open
 * joint already shows in ctrl_points.  0, or -1 without memory. */
static int joints_note(const ob_cmp_side *bs, const ob_cmp_side *ns, const pair *pr, int np, ob_cmp_result *r)
{
    if (!bs->res.has_joints || !ns->res.has_joints) {
        if (bs->res.has_joints == ns->res.has_joints)
            return 0;
        return ob_strlist_addf(&r->notes,
                               "%s has no joint columns (max_gap, max_kink, continuity: written by an older offbench): "
                               "joints not compared; ctrl_points now counts both ends of a joint that does not "
                               "close", bs->res.has_joints ? ns->label : bs->label);
    }
    int n = 0;
    const pair *first = NULL;
    for (int i = 0; i < np; i++)
        if (strcmp(pr[i].b->continuity, pr[i].n->continuity) != 0) {
            if (!n++)
                first = &pr[i];
        }
    if (!n)
        return 0;
    return ob_strlist_addf(&r->notes, "%d joined row(s) reach another measured continuity (informational), e.g. "
                           "%s d=%s %s tol=%s: '%s' -> '%s'", n, first->b->curve, first->b->d_text, first->b->method,
                           first->b->tol_text, first->b->continuity, first->n->continuity);
}

/* Certificates (run --certify) are judged only where both rows of a pair
 * have one (judge_quality): a note says when one run is certified and the
 * other not, or how many joined rows with an approximation on both sides
 * have a certificate on one side only (e.g. stopped by --job-timeout).
 * Informational: the exit status is unchanged.  0, or -1 without memory. */
static int cert_note(const ob_cmp_side *bs, const ob_cmp_side *ns, const pair *pr, int np, ob_cmp_result *r)
{
    int cb = 0, cn = 0, one = 0;
    for (int i = 0; i < bs->res.n && !cb; i++)
        cb = bs->res.v[i].cert_done != 0;
    for (int i = 0; i < ns->res.n && !cn; i++)
        cn = ns->res.v[i].cert_done != 0;
    if (cb != cn)
        return ob_strlist_addf(&r->notes, "%s is certified (run --certify), %s is not: the certificates were not "
                               "compared", cb ? bs->label : ns->label, cb ? ns->label : bs->label);
    const pair *first = NULL;
    for (int i = 0; cb && i < np; i++) {
        const ob_res_row *b = pr[i].b, *n = pr[i].n;
        const int appr = (is_ok(b->status) || strcmp(b->status, "limit") == 0) &&
                         (is_ok(n->status) || strcmp(n->status, "limit") == 0);
        if (appr && (b->cert_done == OB_CERT_DONE) != (n->cert_done == OB_CERT_DONE) && !one++)
            first = &pr[i];
    }
    if (!one)
        return 0;
    return ob_strlist_addf(&r->notes, "%d joined row(s) have a certificate on one side only (none, or stopped by "
                           "--job-timeout): their certificates were not compared, e.g. %s d=%s %s tol=%s", one,
                           first->b->curve, first->b->d_text, first->b->method, first->b->tol_text);
}

/* --strict-timing: what could not be judged, into r->strict (exit 3). */
static int strict_reasons(const ob_cmp_opts *o, ob_cmp_result *r)
{
    int rc = 0;
    if (!o->strict_timing || o->no_timing || r->tstate == OB_TIMING_FEW_REPS)
        return 0;  /* (too few repetitions is in r->strict already) */
    if (!r->timing) {
        for (int i = 0; i < r->timing_diffs.n; i++)
            rc |= ob_strlist_addf(&r->strict, "timings not judged: %s", r->timing_diffs.v[i]);
        return rc;
    }
    if (!o->method_timing_only) {
        if (r->t_threshold_only)
            rc |= ob_strlist_addf(&r->strict, "%d row(s) without at least 2 repetitions on both sides "
                                  "(samples.csv): judged by the threshold alone", r->t_threshold_only);
        if (r->t_few_reps)
            rc |= ob_strlist_addf(&r->strict, "%d row(s) with too few repetitions for a bounded interval at "
                                  "alpha %g", r->t_few_reps, o->alpha);
        if (r->t_noisy)
            rc |= ob_strlist_addf(&r->strict, "%d row(s) too noisy to judge (interval wider than a factor %.4g)",
                                  r->t_noisy, ob_cmp_noise_width(o));
    }
    for (int i = 0; i < r->nms; i++)
        if (r->ms[i].not_judged)
            rc |= ob_strlist_addf(&r->strict, "method %s: %s", r->ms[i].method,
                                  strcmp(r->ms[i].not_judged, "noisy") == 0 ? "too noisy to judge"
                                  : strcmp(r->ms[i].not_judged, "few_reps") == 0
                                      ? "too few complete repetitions for a bounded interval"
                                      : "fewer than 2 complete repetitions per side");
    return rc;
}

/* The geometric means of new/base of each method over its joined pairs,
 * and its summed times over the rows judged for timing (t_base, t_new). */
static void method_means(const pair *pr, const int *order, const int *start, ob_cmp_result *r)
{
    for (int mi = 0; mi < r->nms; mi++) {
        ob_method_sum *m = &r->ms[mi];
        double s[3] = {0, 0, 0}, sum_b = 0, sum_n = 0;
        int c[3] = {0, 0, 0};
        for (int g = start[mi]; g < start[mi + 1]; g++) {
            const ob_res_row *b = pr[order[g]].b, *n = pr[order[g]].n;
            if (b->ctrl_points > 0 && n->ctrl_points > 0)
                s[0] += log((double)n->ctrl_points / (double)b->ctrl_points), c[0]++;
            if (isfinite(b->max_err) && isfinite(n->max_err) && b->max_err > 0 && n->max_err > 0)
                s[1] += log(n->max_err / b->max_err), c[1]++;
            if (pr[order[g]].judged) {
                const double tb = row_time(b, r->method_time), tn = row_time(n, r->method_time);
                s[2] += log(tn / tb), c[2]++;
                sum_b += tb;
                sum_n += tn;
            }
        }
        m->t_base = c[2] ? sum_b : NAN;
        m->t_new = c[2] ? sum_n : NAN;
        m->n_cp = c[0], m->n_err = c[1], m->n_t = c[2];
        m->gm_cp = c[0] ? exp(s[0] / c[0]) : NAN;
        m->gm_err = c[1] ? exp(s[1] / c[1]) : NAN;
        m->gm_t = c[2] ? exp(s[2] / c[2]) : NAN;
    }
}

/* Too few repetitions to detect anything: with n and m repetitions the
 * smallest two-sided p of the rank test is 2 / C(n + m, n); when that is
 * not below alpha no timing change can be significant (3 + 3 at 0.05: 0.1),
 * and a comparison that passed would claim what it cannot see.  Then
 * timings are not judged, and the comparison says how many repetitions are
 * needed (r->strict: exit 3).  Runs without repetitions on both sides are
 * judged by the threshold alone (and said to be).  0, or -1 no memory. */
static int few_reps(const ob_cmp_side *bs, const ob_cmp_side *ns, const ob_cmp_opts *o, ob_cmp_result *r)
{
    const int mt = r->method_time, kb = side_reps(bs, mt), kn = side_reps(ns, mt);
    const int have = mt ? bs->has_fits && ns->has_fits : bs->has_samples && ns->has_samples;
    if (!r->timing || !have || ob_mw_min_p(kn, kb) < o->alpha)
        return 0;
    int need = 2;
    while (need < 1000 && !(ob_mw_min_p(need, need) < o->alpha))
        need++;
    r->timing = 0;
    r->tstate = OB_TIMING_FEW_REPS;
    r->need_reps = need;
    return ob_strlist_addf(&r->strict,
                           "too few repetitions to judge timing: need %d per side (BASE has %d, NEW %d; the smallest "
                           "two-sided p of the rank test is then %.3g, not below alpha %g: run %s %d)",
                           need, kb, kn, ob_mw_min_p(kn, kb), o->alpha, mt ? "--time-fits --fit-reps" : "--reps", need);
}

int ob_cmp_method_selected(const ob_cmp_opts *o, const char *method)
{
    if (!o->methods)
        return 1;
    const size_t len = strlen(method);
    for (const char *p = o->methods; *p;) {
        const size_t n = strcspn(p, ",");
        if (n == len && strncmp(p, method, n) == 0)
            return 1;
        p += n + (p[n] == ',');
    }
    return 0;
}

/* 1 when a row of t has method name[0..len). */
static int has_method(const ob_res_table *t, const char *name, size_t len)
{
    for (int i = 0; i < t->n; i++)
        if (strlen(t->v[i].method) == len && strncmp(t->v[i].method, name, len) == 0)
            return 1;
    return 0;
}

int ob_cmp_check_methods(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, ob_err *err)
{
    for (const char *p = o->methods; p && *p;) {
        const size_t len = strcspn(p, ",");
        if (!has_method(&b->res, p, len) && !has_method(&n->res, p, len)) {
            ob_fail(err, "--methods: no rows of method '%.*s' in either run", (int)(len < 100 ? len : 100), p);
            return -1;
        }
        p += len + (p[len] == ',');
    }
    return 0;
}

int ob_cmp_rows(const ob_cmp_side *bs, const ob_cmp_side *ns, const ob_cmp_opts *o, ob_cmp_result *r, ob_err *err)
{
    const ob_res_table *bt = &bs->res, *nt = &ns->res;
    /* room for the most repetitions or rounds of any side (xb, xn) */
    int maxrep = bt->maxrep > nt->maxrep ? bt->maxrep : nt->maxrep;
    if (bt->maxround > maxrep)
        maxrep = bt->maxround;
    if (nt->maxround > maxrep)
        maxrep = nt->maxround;
    pair *pr = malloc((size_t)(bt->n ? bt->n : 1) * sizeof *pr);
    char *matched = calloc((size_t)(nt->n ? nt->n : 1), 1);
    double *xb = malloc((size_t)(maxrep ? maxrep : 1) * sizeof *xb);
    double *xn = malloc((size_t)(maxrep ? maxrep : 1) * sizeof *xn);
    int np = 0, rc = -1, *order = NULL, *start = NULL;
    method_table mt = {{0}, r->nms};
    r->t_rows_count = !o->method_timing_only;
    if (!pr || !matched || !xb || !xn || few_reps(bs, ns, o, r) != 0)
        goto done;
    for (int i = 0; i < bt->n; i++) {
        const ob_res_row *b = &bt->v[i], *n = ob_res_find(nt, b);
        if (!ob_cmp_method_selected(o, b->method) || (!n && o->timing_only))
            continue;
        /* outside NEW's selection: left out on purpose, not missing (compare_subset.h) */
        const int left_out = n ? 0 : ob_cmp_subset_left_out(r, b);
        if (left_out < 0 || (left_out && add_change(r, OB_CH_LEFT_OUT, "status", b, NULL, NAN, NAN)))
            goto done;
        if (left_out)
            continue;
        int mi = method_index(r, &mt, b->method);
        if (mi < 0)
            goto done;
        if (!n) {
            r->n_missing++;
            r->ms[mi].regressions++;
            if (add_change(r, OB_CH_MISSING, "status", b, NULL, NAN, NAN))
                goto done;
            continue;
        }
        matched[n - nt->v] = 1;
        r->joined++;
        ob_method_sum *m = &r->ms[mi];
        m->rows++;
        int judged;
        if ((!o->timing_only && judge_quality(b, n, o, r, m)) || judge_time(bs, ns, b, n, o, r, m, xb, xn, &judged))
            goto done;
        pr[np++] = (pair){b, n, judged, mi};
    }
    for (int j = 0; j < nt->n && !o->timing_only; j++)
        if (!matched[j] && ob_cmp_method_selected(o, nt->v[j].method)) {
            r->n_new++;
            if (add_change(r, OB_CH_NEW, "status", NULL, &nt->v[j], NAN, NAN))
                goto done;
        }
    if (ob_cmp_subset_finish(r) != 0)
        goto done;
    if (group_by_method(pr, np, r->nms, &order, &start) != 0)
        goto done;
    method_means(pr, order, start, r);
    judge_methods(bs, ns, pr, order, start, o, r, xb, xn);
    judge_harness(bs, ns, pr, np, o, r, xb, xn);
    rc = joints_note(bs, ns, pr, np, r) || cert_note(bs, ns, pr, np, r) || strict_reasons(o, r) ? -1 : 0;
done:
    ob_strmap_free(&mt.ix);
    free(order);
    free(start);
    free(pr);
    free(matched);
    free(xb);
    free(xn);
    if (rc)
        ob_fail(err, "out of memory");
    return rc;
}

int ob_cmp_status(const ob_cmp_result *r)
{
    if (r->incomparable.n || r->strict.n)
        return 3;
    const int harness_slower = r->harness_counts && r->harness.verdict > 0;
    if (r->q_reg || (r->t_rows_count && r->t_reg) || r->m_reg || r->n_missing || harness_slower)
        return 1;
    return r->undecided ? 3 : 0;  /* a method's timing the data cannot decide: never a pass */
}

void ob_cmp_result_free(ob_cmp_result *r)
{
    if (!r)
        return;
    ob_strlist_free(&r->incomparable);
    ob_strlist_free(&r->timing_diffs);
    ob_strlist_free(&r->notes);
    ob_strlist_free(&r->strict);
    ob_cmp_subset_free(r->subset);
    free(r->ch);
    free(r->ms);
    memset(r, 0, sizeof *r);
}
