/*
 * jobs.c - job vocabulary: each job's bookkeeping (its end, its first pieces,
 * what it accepts, its final outputs) and the share groups.
 * See driver.h (the contract) and driver_int.h (the pieces).
 */
#include "methods/driver/driver_int.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int drv_push(itemvec *q, const item *it)
{
    if (ob_grow(&q->v, &q->cap, q->n, sizeof *q->v, 256))
        return -1;
    q->v[q->n++] = *it;
    return 0;
}

void drv_job_end(ob_job *j, jstate *s, ob_status st, const char *msg)
{
    if (j->status == OB_OK || (j->status == OB_LIMIT && st != OB_LIMIT)) {
        j->status = st;
        snprintf(j->message, sizeof j->message, "%s", msg);
    }
    if (st == OB_FAIL || st == OB_SKIP || st == OB_TIMEOUT)
        s->dead = 1;
}

/* Inputs a method or metric cannot take: the job is skipped before any work. */
int drv_check_applicable(ob_job *j, jstate *s)
{
    const ob_method *m = j->method;
    char msg[160];
    for (int i = 0; i < j->curve->nseg; i++) {
        const ob_bez *b = &j->curve->seg[i];
        if (b->rational && !(m->caps & OB_CAP_RATIONAL_IN)) {
            drv_job_end(j, s, OB_SKIP, "rational input is not supported by this method");
            return 0;
        }
        int od = ob_method_out_degree(m, b->deg, b->rational, j->params);
        if (od > OB_MAX_DEG) {
            snprintf(msg, sizeof msg, "output degree %d exceeds the limit %d", od, OB_MAX_DEG);
            drv_job_end(j, s, OB_SKIP, msg);
            return 0;
        }
    }
    if (ob_metric_same_param(j->metric) && !(m->caps & OB_CAP_SAME_PARAM)) {
        snprintf(msg, sizeof msg, "metric %s needs an approximation in the base's parameter",
                 ob_metric_name(j->metric));
        drv_job_end(j, s, OB_SKIP, msg);
        return 0;
    }
    return 1;
}

/* The offset's cusps of segment b (OB_CAP_CUSP_BREAKS) merged into the
 * ascending cuts[1..nc-1] (room entries in all); returns the new nc. */
static int add_cusp_cuts(const ob_bez *b, double d, double *cuts, int nc, int room)
{
    double ts[3 * OB_MAX_DEG];
    int k = ob_bez_offset_cusps(b, d, ts, 3 * OB_MAX_DEG);
    k = k > 3 * OB_MAX_DEG ? 3 * OB_MAX_DEG : k;  /* more: the method splits the rest itself */
    for (int i = 0; i < k && nc < room; i++) {
        int p = nc++;
        while (p > 1 && cuts[p - 1] > ts[i]) {
            cuts[p] = cuts[p - 1];
            p--;
        }
        cuts[p] = ts[i];
    }
    return nc;
}

/* Initial pieces of one job: inflections (and the offset's cusps when the
 * method asks), then the method's turning limit. */
int drv_plan_job(const ob_job *j, int jobidx, int grp, const ob_driver_opts *o, itemvec *out)
{
    const ob_method *m = j->method;
    int convex = o->inflections || (m->caps & OB_CAP_CONVEX);
    for (int s = 0; s < j->curve->nseg; s++) {
        const ob_bez *b = &j->curve->seg[s];
        double cuts[2 * OB_MAX_DEG * 3 + 2];
        int nc = 0;
        cuts[nc++] = 0.0;
        if (convex)
            nc += ob_bez_inflections(b, cuts + 1, 3 * OB_MAX_DEG);
        if (m->caps & OB_CAP_CUSP_BREAKS)
            nc = add_cusp_cuts(b, j->d, cuts, nc, (int)(sizeof cuts / sizeof cuts[0]) - 1);
        cuts[nc++] = 1.0;
        for (int i = 0; i + 1 < nc; i++) {
            double a = cuts[i], e = cuts[i + 1];
            if (e - a < 1e-12)
                continue;
            int k = 1;
            ob_bez sub;
            double turn = 0.0;
            if (m->max_turn > 0) {
                ob_bez_subsegment(b, a, e, &sub);
                turn = ob_bez_turn(&sub, 128);
                if (turn >= m->max_turn)
                    k = (int)floor(turn / m->max_turn) + 1;
            }
            double prev = a;
            for (int p = 1; p <= k; p++) {
                double next = p == k ? e : a + (e - a) * ob_bez_turn_param(&sub, turn * p / k);
                item it = {.job = jobidx, .grp = grp, .seg = s, .depth = 0, .a = prev, .b = next,
                           .end = next, .lo = prev, .hi = next, .parent_err = INFINITY,
                           .start = prev, .level = j->tol};
                if (drv_push(out, &it))
                    return -1;
                prev = next;
            }
        }
    }
    return 0;
}

static void log_span(ob_span_log *L, int seg, double a, double b, double err)
{
    if (!L)
        return;
    if (L->n == L->cap) {
        int nc = L->cap ? 2 * L->cap : 16;
        ob_span *nv = realloc(L->v, (size_t)nc * sizeof *nv);
        if (!nv) {
            L->oom = 1;
            return;
        }
        L->v = nv;
        L->cap = nc;
    }
    L->v[L->n++] = (ob_span){seg, a, b, err};
}

int drv_span_cmp(const void *x, const void *y)
{
    const ob_span *p = x, *q = y;
    if (p->seg != q->seg)
        return p->seg < q->seg ? -1 : 1;
    return p->a < q->a ? -1 : p->a > q->a;
}

/* Keeps the ends of an accepted fit for the joints between fits. */
static void keep_ends(jstate *s, int seg, double a, const fitjoints *fj)
{
    if (s->nends == s->capends) {
        const int nc = s->capends ? 2 * s->capends : 16;
        fitends *nv = realloc(s->ends, (size_t)nc * sizeof *nv);
        if (!nv) {
            s->ends_oom = 1;
            return;
        }
        s->ends = nv;
        s->capends = nc;
    }
    s->ends[s->nends++] = (fitends){seg, a, fj->first, fj->last};
}

/* Accept a finished segment (pieces with their degrees and error, the
 * joints of its fit) covering [a, b] of base segment seg. */
void drv_accept(ob_job *j, jstate *s, int seg, double a, double b, int npieces, int ctrl_add, int maxdeg,
                   double err, const fitjoints *fj)
{
    log_span(s->spans, seg, a, b, err);
    keep_ends(s, seg, a, fj);
    ob_joint_merge(&s->st, &fj->in);
    s->open_count += fj->count_open;
    j->segments += npieces;
    s->ctrl_add += ctrl_add;
    if (maxdeg > j->out_degree)
        j->out_degree = maxdeg;
    if (!(err <= j->max_err))
        j->max_err = err;
}

/* Accept the item's whole fit. */
void drv_accept_item(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj)
{
    drv_accept(j, s, it->seg, it->a, it->b, r->n, r->ctrl_add, r->maxdeg, r->err, fj);
}

static int ends_cmp(const void *x, const void *y)
{
    const fitends *p = x, *q = y;
    if (p->seg != q->seg)
        return p->seg < q->seg ? -1 : 1;
    return p->a < q->a ? -1 : p->a > q->a;
}

/* The joints between consecutive accepted fits, in curve order (once: the
 * ends are freed). */
static void join_fits(ob_job *j, jstate *s)
{
    if (s->joined)
        return;
    s->joined = 1;
    if (s->nends > 1)
        qsort(s->ends, (size_t)s->nends, sizeof *s->ends, ends_cmp);
    for (int i = 1; i < s->nends; i++)
        s->open_count += ob_joint_between(&s->st, j->curve, s->gap_tol, s->ends[i - 1].seg, &s->ends[i - 1].last,
                                          s->ends[i].seg, &s->ends[i].first);
    free(s->ends);
    s->ends = NULL;
    s->nends = s->capends = 0;
}

/* A finished job's outputs: the control points of what was accepted (one
 * more for each joint whose ends are apart) and its joints, or none for a
 * job that failed, was skipped or timed out.  Called again for a finished
 * job, it gives the same outputs. */
void drv_finalize(ob_job *j, jstate *s)
{
    if ((j->status == OB_OK || j->status == OB_LIMIT) && s->ends_oom)
        drv_job_end(j, s, OB_FAIL, "out of memory keeping the ends of the accepted pieces");
    if (j->status == OB_OK && !ob_err_can_pass(j->max_err))  /* never ok with an error it cannot state */
        drv_job_end(j, s, OB_FAIL, "the measured error is not finite");
    if (j->status == OB_OK || j->status == OB_LIMIT) {
        join_fits(j, s);
        j->ctrl_points = j->segments > 0 ? 1 + s->ctrl_add + s->open_count : 0;
        j->joints = s->st.joints;
        j->open_joints = (int)s->open_count;
        j->max_gap = s->st.joints > 0 ? s->st.max_gap : NAN;
        j->max_kink = s->st.joints > 0 ? s->st.max_kink : NAN;
        j->continuity = ob_joint_continuity(&s->st);
    } else {
        free(s->ends);
        s->ends = NULL;
        s->nends = s->capends = 0;
        j->ctrl_points = 0;
        j->segments = 0;
        j->out_degree = 0;
        j->max_err = NAN;
        j->max_gap = j->max_kink = NAN;
        j->continuity = OB_CONT_NONE;
        j->joints = j->open_joints = 0;
    }
}

/* ---- shared pieces -------------------------------------------------------
 * Jobs that differ only in their tolerance (same curve, d, method,
 * parameters, metric and split) of a method whose fit ignores the tolerance
 * (ob_method_fit_uses_tol) fit and measure the same piece to the same
 * result, and their mid and maxerr trees of a coarser tolerance lie inside
 * a finer one's.  Such jobs form a share group.  Each level is sorted by
 * (group, segment, piece, job), so that the items of a group on one piece
 * are adjacent; the first live one is fitted and measured, the others take
 * its results.  A job's decisions see exactly what they would alone (its own
 * items keep their order: (segment, piece) within a job), and every job is
 * charged the piece's full cost (fit_ns, eval_ns say what the job costs
 * run alone). */

typedef struct {
    const ob_job *j;
    size_t i;
} jobref;

static int ptr_cmp(const void *p, const void *q) { return (uintptr_t)p < (uintptr_t)q ? -1 : (uintptr_t)p > (uintptr_t)q; }

static int job_share_cmp(const void *x, const void *y)
{
    const ob_job *a = ((const jobref *)x)->j, *b = ((const jobref *)y)->j;
    int c;
    if ((c = ptr_cmp(a->curve, b->curve)) || (c = ptr_cmp(a->method, b->method)) ||
        (c = ptr_cmp(a->params, b->params)))
        return c;
    if (a->d != b->d)
        return a->d < b->d ? -1 : 1;
    if (a->metric != b->metric)
        return a->metric < b->metric ? -1 : 1;
    if (a->split != b->split)
        return a->split < b->split ? -1 : 1;
    const size_t i = ((const jobref *)x)->i, k = ((const jobref *)y)->i;
    return i < k ? -1 : i > k;
}

/* Purpose: the share group of every job (grp[i]), or NULL when memory ran out. */
int *drv_share_groups(const ob_job *jobs, size_t njobs)
{
    int *grp = malloc((njobs ? njobs : 1) * sizeof *grp);
    jobref *r = malloc((njobs ? njobs : 1) * sizeof *r);
    if (!grp || !r) {
        free(grp);
        free(r);
        return NULL;
    }
    for (size_t i = 0; i < njobs; i++)
        r[i] = (jobref){&jobs[i], i};
    qsort(r, njobs, sizeof *r, job_share_cmp);
    int id = -1;
    for (size_t k = 0; k < njobs; k++) {
        const ob_job *j = r[k].j, *p = k ? r[k - 1].j : NULL;
        const int same = p && p->curve == j->curve && p->method == j->method && p->params == j->params &&
                         p->d == j->d && p->metric == j->metric && p->split == j->split;
        if (!same || ob_method_fit_uses_tol(j->method, j->params))
            id++;
        grp[r[k].i] = id;
    }
    free(r);
    return grp;
}

double ob_job_cost(const ob_job *j)
{
    /* the method's own figure (method.h), else 2 ms */
    const double ms = j->method->cost_ms > 0 ? j->method->cost_ms : 2.0;
    double size = 0.0;
    for (int s = 0; s < j->curve->nseg; s++)
        size += j->curve->seg[s].deg + 1;
    const double tol = j->tol > 0 ? j->tol : 1e-3;
    return ms * (size / 4.0) * pow(tol / 1e-3, -0.25);
}

/* A cost and its index, for ob_cost_order's sort. */
typedef struct {
    double cost;
    size_t i;
} costed;

static int by_cost_desc(const void *a, const void *b)
{
    const costed *x = a, *y = b;
    if (x->cost != y->cost)
        return x->cost > y->cost ? -1 : 1;
    return (x->i > y->i) - (x->i < y->i);
}

int ob_cost_order(const double *cost, size_t n, size_t *order)
{
    costed *c = malloc((n ? n : 1) * sizeof *c);
    if (!c)
        return -1;
    for (size_t i = 0; i < n; i++)
        c[i] = (costed){cost[i], i};
    qsort(c, n, sizeof *c, by_cost_desc);
    for (size_t k = 0; k < n; k++)
        order[k] = c[k].i;
    free(c);
    return 0;
}
