/*
 * steps.c - the pure per-item steps: fit a piece, measure a chunk's pieces
 * (CPU or a batch backend), their joints, and the chunk helpers that let the
 * items of one share group on one piece take a single fit.
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

static double clock_ns(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

/* Wall time: what a batch backend's launch costs the run. */
double drv_wall_ns(void) { return clock_ns(CLOCK_MONOTONIC); }

/* CPU time of the calling thread: what one fit or one CPU measurement cost,
 * whatever else the machine was doing meanwhile (other threads, other
 * processes, a thread descheduled mid-call); with the CPU time its fits had
 * spent for it in other processes (ob_fit_foreign_add: sisl's server), so
 * that a job's fit_ns and --job-timeout count what the method cost. */
double drv_thread_ns(void) { return clock_ns(CLOCK_THREAD_CPUTIME_ID) + ob_fit_foreign_ns(); }

int ob_test_fit_times(const ob_job *j, int seg, double a, double b)
{
    const double f = j->test_fit_repeat, whole = floor(f);
    uint64_t h = 1469598103934665603ull ^ (uint64_t)(unsigned)seg;
    double ab[2] = {a, b};
    unsigned char bytes[sizeof ab];
    memcpy(bytes, ab, sizeof ab);
    for (size_t k = 0; k < sizeof bytes; k++)
        h = (h ^ bytes[k]) * 1099511628211ull;
    const double u = (double)(h >> 11) * 0x1p-53;  /* in [0, 1) */
    return (int)whole + (u < f - whole);
}

/* Fit one item; returns the thread time spent in the method. */
double drv_fit_item(const ob_job *jobs, const item *it, double budget_ns, void *work, ob_fit *fit, itemres *r)
{
    const ob_job *j = &jobs[it->job];
    ob_bez sub;
    ob_bez_subsegment(&j->curve->seg[it->seg], it->a, it->b, &sub);
    r->msg[0] = '\0';
    r->chain_to = 0;
    r->err = 0.0;
    r->t = 0.5 * (it->a + it->b);
    r->ctrl_add = r->maxdeg = 0;
    double defaults[OB_MAX_PARAMS];
    const double *par = j->params;
    if (!par) {
        ob_param_defaults(j->method, defaults);
        par = defaults;
    }
    double t0 = drv_thread_ns();
    const ob_fit_args args = {j->d, j->tol, par};
    ob_fit_budget_set(budget_ns);
    r->st = j->method->fit(&sub, &args, work, fit, r->msg, sizeof r->msg);
    const int times = j->test_fit_repeat > 1 ? ob_test_fit_times(j, it->seg, it->a, it->b) : 1;
    for (int k = 1; k < times; k++)  /* test hook (driver.h): the same fit again */
        r->st = j->method->fit(&sub, &args, work, fit, r->msg, sizeof r->msg);
    double t1 = drv_thread_ns();
    ob_fit_budget_set(0.0);  /* a fit called outside the driver has no budget */
    r->n = r->st == OB_FIT_OK ? fit->n : 0;
    if (r->st == OB_FIT_RETRY_SMALLER)
        r->err = INFINITY;
    if (r->st == OB_FIT_OK && (fit->n < 1 || fit->n > OB_MAX_PIECES)) {
        r->st = OB_FIT_FAIL;
        snprintf(r->msg, sizeof r->msg, "method returned %d pieces", fit->n);
    }
    return t1 - t0;
}

/* Purpose: find out at once whether a piece that asked for a smaller piece
 * (r->st == OB_FIT_RETRY_SMALLER, split mid or maxerr) heads a chain of such
 * requests down to the retry limit.
 * Method: such a piece is halved, and a descendant still asking at
 * RETRY_LEVELS halvings (or at the depth limit) fails the job (drv_decide).
 * Where the method's request does not depend on the piece's size (a
 * rational fit whose every iterate has a pole, at any scale), the
 * breadth-first driver fitted all 2^(RETRY_LEVELS - depth) descendants
 * before the first of them failed the job at the limit.  The leftmost chain
 * of halvings is fitted here instead; if every piece on it asks again,
 * r->chain_to gets the depth it reached, and drv_decide() then carries only the
 * leftmost descendant down, unfitted, to be fitted (and to fail the job, in
 * its turn among the items of that level) at that depth: the first piece at
 * that level the breadth-first driver would have failed the job on.  What is
 * not fitted, the rest of the subtree, could change the outcome only by a
 * terminal event of its own above that depth (a fit error, a limit).
 * Returns the thread time spent.  fit: scratch, overwritten. */
double drv_probe_retry_chain(const ob_job *jobs, const item *it, int max_depth, double budget_ns, void *work,
                             ob_fit *fit, itemres *r)
{
    const ob_job *j = &jobs[it->job];
    if (r->st != OB_FIT_RETRY_SMALLER || (j->split != OB_SPLIT_MID && j->split != OB_SPLIT_MAXERR) || it->chain_to > 0)
        return 0.0;
    item c = *it;
    itemres cr;
    double ns = 0.0;
    while (c.depth < RETRY_LEVELS && c.depth < max_depth) {
        c.b = 0.5 * (c.a + c.b);
        c.depth++;
        ns += drv_fit_item(jobs, &c, budget_ns > 0 ? fmax(1.0, budget_ns - ns) : 0.0, work, fit, &cr);
        if (cr.st != OB_FIT_RETRY_SMALLER)
            return ns;
    }
    if (c.depth > it->depth)
        r->chain_to = c.depth;
    return ns;
}

int drv_batch_alloc(batch *b, int chunk)
{
    const size_t n = (size_t)chunk * OB_MAX_PIECES;
    b->base = malloc(n * sizeof *b->base);
    b->rec = malloc(n * sizeof *b->rec);
    b->out = malloc(n * sizeof *b->out);
    b->ns = malloc(n * sizeof *b->ns);
    b->first = malloc(((size_t)chunk + 1) * sizeof *b->first);
    b->sampled = malloc(n * sizeof *b->sampled);
    b->srec = malloc(n * sizeof *b->srec);
    b->sout = malloc(n * sizeof *b->sout);
    return b->base && b->rec && b->out && b->ns && b->first && b->sampled && b->srec && b->sout ? 0 : -1;
}

void drv_batch_free(batch *b)
{
    free(b->base);
    free(b->rec);
    free(b->out);
    free(b->ns);
    free(b->first);
    free(b->sampled);
    free(b->srec);
    free(b->sout);
}

void drv_for(drv_how how, long n, long min_par, int grain, void (*fn)(const void *ctx, long i), const void *ctx)
{
    if (how == DRV_TEAM && n >= min_par) {
#pragma omp parallel for schedule(dynamic, grain)
        for (long i = 0; i < n; i++)
            fn(ctx, i);
    } else if (how == DRV_TASKS && n >= min_par) {
#pragma omp taskloop grainsize(grain)
        for (long i = 0; i < n; i++)
            fn(ctx, i);
    } else {
        for (long i = 0; i < n; i++)
            fn(ctx, i);
    }
}

/* What the loops of one chunk's measuring read. */
typedef struct {
    const ob_job *jobs;
    const item *its;
    const ob_fit *fits;
    const double *stop;
    const itemres *res;
    int samples;
    batch *B;
    int backend_ok;     /* the backend measured the sampled records */
} chunk_ctx;

/* The records of item i: its base sub-pieces cut, one per piece of its fit. */
static void make_records(const void *ctx, long i)
{
    const chunk_ctx *c = ctx;
    if (c->res[i].st != OB_FIT_OK)
        return;
    const ob_job *j = &c->jobs[c->its[i].job];
    ob_bez sub;
    ob_bez_subsegment(&j->curve->seg[c->its[i].seg], c->its[i].a, c->its[i].b, &sub);
    for (int p = 0; p < c->fits[i].n; p++) {
        const int r = c->B->first[i] + p;
        ob_bez_subsegment(&sub, c->fits[i].t[p], c->fits[i].t[p + 1], &c->B->base[r]);
        c->B->rec[r] = (ob_measure_rec){&c->B->base[r], &c->fits[i].seg[p], j->d, j->metric, c->stop[i],
                                        {&j->curve->seg[c->its[i].seg], c->its[i].a, c->its[i].b, c->fits[i].t[p],
                                         c->fits[i].t[p + 1]}};
    }
}

/* Record r measured on the CPU (unless the backend did), its thread time
 * kept. */
static void measure_record(const void *ctx, long r)
{
    const chunk_ctx *c = ctx;
    batch *B = c->B;
    if (c->backend_ok && ob_metric_batched(B->rec[r].metric))
        return;
    const double t0 = drv_thread_ns();
    const ob_measure_rec *m = &B->rec[r];
    if (ob_measure_src(m->metric, m->base, m->src.seg ? &m->src : NULL, m->approx, m->d, c->samples, m->stop,
                       &B->out[r]))
        B->out[r].err = NAN;  /* cannot be measured: reported below */
    B->ns[r] = drv_thread_ns() - t0;
}

/* The sampled records B->srec[0..ns-1] to the batch backend; its wall time
 * in *wall.  Engines that measure from several threads at once
 * (DRV_TASKS, DRV_SERIAL inside a parallel region) take turns: a backend
 * holds one queue.  1 when the backend measured them. */
static int call_backend(const ob_driver_hooks *h, batch *B, int ns, int samples, drv_how how, double *wall)
{
    int ok;
    if (how == DRV_TEAM) {
        const double t0 = drv_wall_ns();
        ok = h->batch(h->batch_ctx, B->srec, ns, samples, B->sout) == 0;
        *wall = drv_wall_ns() - t0;
        if (!ok && h->batch_fallbacks)
            (*h->batch_fallbacks)++;
        return ok;
    }
#pragma omp critical(drv_backend)
    {
        const double t0 = drv_wall_ns();
        ok = h->batch(h->batch_ctx, B->srec, ns, samples, B->sout) == 0;
        *wall = drv_wall_ns() - t0;
        if (!ok && h->batch_fallbacks)
            (*h->batch_fallbacks)++;
    }
    return ok;
}

/* Purpose: the records of a chunk's measurement: every piece of every
 *          fitted item against its base sub-piece (B->rec, B->first); the
 *          sampled ones a batch backend takes listed in B->srec (ns of
 *          them; none without hooks.batch).
 * Returns: the number of records. */
int drv_measure_prepare(const ob_job *jobs, const item *its, long cnt, const ob_fit *fits, const double *stop,
                        const itemres *res, int samples, const ob_driver_hooks *h, batch *B, drv_how how)
{
    int n = 0;
    for (long i = 0; i < cnt; i++) {
        B->first[i] = n;
        if (res[i].st == OB_FIT_OK)
            n += fits[i].n;
    }
    B->first[cnt] = n;
    /* the records: base sub-pieces cut in parallel (a level of one item, as
     * greedy bisection often makes, runs without waking the other threads) */
    const chunk_ctx cc = {jobs, its, fits, stop, res, samples, B, 0};
    drv_for(how, cnt, 2, 8, make_records, &cc);
    /* sampled records to the backend in one call, the rest on the CPU */
    B->nsampled = 0;
    B->backend_n = 0;
    B->backend_wall = 0.0;
    if (h->batch)
        for (int r = 0; r < n; r++)
            if (ob_metric_batched(B->rec[r].metric)) {
                B->srec[B->nsampled] = B->rec[r];
                B->sampled[B->nsampled++] = r;
            }
    return n;
}

/* Purpose: the backend's results (B->sout) in their records, each charged
 *          its share of the launch's ns (wall, or the device's time) by the
 *          work it took (the kernel counts it). */
void drv_measure_backend_done(batch *B, double ns)
{
    double total = 0.0;
    const int k_n = B->nsampled;
    for (int k = 0; k < k_n; k++)
        total += B->sout[k].work;
    for (int k = 0; k < k_n; k++) {
        B->out[B->sampled[k]] = B->sout[k];
        B->ns[B->sampled[k]] = total > 0.0 ? ns * (B->sout[k].work / total) : ns / k_n;
    }
    B->backend_n = k_n;
    B->backend_wall = ns;
}

/* Purpose: the rest of a prepared measurement (drv_measure_prepare): the
 *          records the backend did not take (backend_ok 0: all of them)
 *          measured on the CPU, then per item the largest error over its
 *          pieces, at a base parameter, its pieces' degrees, its
 *          measuring time. */
void drv_measure_finish(const ob_job *jobs, const item *its, long cnt, const ob_fit *fits, const double *stop,
                        itemres *res, double *eval_ns, int samples, batch *B, int backend_ok, drv_how how)
{
    const int n = B->first[cnt];
    const chunk_ctx mc = {jobs, its, fits, stop, res, samples, B, backend_ok};
    drv_for(how, n, 2, 4, measure_record, &mc);
    for (long i = 0; i < cnt; i++) {
        itemres *r = &res[i];
        eval_ns[i] = 0.0;
        if (r->st != OB_FIT_OK)
            continue;
        const item *it = &its[i];
        const ob_fit *fit = &fits[i];
        r->err = 0.0;
        for (int p = 0; p < fit->n; p++) {
            const ob_errval e = B->out[B->first[i] + p];
            const double pa = fit->t[p], pb = fit->t[p + 1];
            eval_ns[i] += B->ns[B->first[i] + p];
            if (isnan(e.err)) {
                r->st = OB_FIT_FAIL;
                snprintf(r->msg, sizeof r->msg, "metric %s cannot measure a degree-%d approximation",
                         ob_metric_name(jobs[it->job].metric), fit->seg[p].deg);
                break;
            }
            r->ctrl_add += fit->seg[p].deg;  /* 1 + sum deg when the pieces are the output */
            if (fit->seg[p].deg > r->maxdeg)
                r->maxdeg = fit->seg[p].deg;
            if (!(e.err <= r->err)) {
                r->err = e.err;
                r->t = it->a + (it->b - it->a) * (pa + (pb - pa) * e.t);
            }
        }
        if (fit->ctrl_points > 0)  /* the method's own representation, e.g. a B-spline */
            r->ctrl_add = (int)(fit->ctrl_points - 1);
    }
}

/* Measure all pieces of all fitted items of a chunk: one batch (the
 * backend's launch in the calling thread, between prepare and finish). */
void drv_measure_chunk(const ob_job *jobs, const item *its, long cnt, const ob_fit *fits, const double *stop,
                       itemres *res, double *eval_ns, int samples, const ob_driver_hooks *h, batch *B, drv_how how)
{
    drv_measure_prepare(jobs, its, cnt, fits, stop, res, samples, h, B, how);
    int backend_ok = 0;
    if (B->nsampled > 0) {
        double wall;
        backend_ok = call_backend(h, B, B->nsampled, samples, how, &wall);
        if (backend_ok)
            drv_measure_backend_done(B, wall);
    }
    drv_measure_finish(jobs, its, cnt, fits, stop, res, eval_ns, samples, B, backend_ok, how);
}

/* The joints of one fit's pieces (joints.h); fit->n >= 1. */
static void fit_joints(const ob_fit *fit, double gap_tol, fitjoints *fj)
{
    memset(fj, 0, sizeof *fj);
    ob_bez_end(&fit->seg[0], 0, &fj->first);
    ob_bez_end(&fit->seg[fit->n - 1], 1, &fj->last);
    for (int p = 1; p < fit->n; p++) {
        ob_end l, r;
        ob_bez_end(&fit->seg[p - 1], 1, &l);
        ob_bez_end(&fit->seg[p], 0, &r);
        fj->count_open += ob_joint_measure(&fj->in, &l, &r, gap_tol);
    }
    if (fit->ctrl_points > 0)  /* the method's own representation has its own count */
        fj->count_open = 0;
}

/* The joints of every fitted item of a chunk (items whose fit failed get
 * none). */
typedef struct {
    const jstate *js;
    const item *its;
    const ob_fit *fits;
    const itemres *res;
    fitjoints *fj;
} joints_ctx;

static void item_joints(const void *ctx, long i)
{
    const joints_ctx *c = ctx;
    if (c->res[i].st == OB_FIT_OK)
        fit_joints(&c->fits[i], c->js[c->its[i].job].gap_tol, &c->fj[i]);
    else
        memset(&c->fj[i], 0, sizeof c->fj[i]);
}

void drv_joints_chunk(const jstate *js, const item *its, long cnt, const ob_fit *fits, const itemres *res,
                      fitjoints *fj, drv_how how)
{
    const joints_ctx c = {js, its, fits, res, fj};
    drv_for(how, cnt, 65, 16, item_joints, &c);
}

/* 1 when items x and y fit the same piece for the same share group. */
int drv_same_piece(const item *x, const item *y)
{
    return x->grp == y->grp && x->seg == y->seg && x->a == y->a && x->b == y->b;
}

int drv_item_share_cmp(const void *x, const void *y)
{
    const item *p = x, *q = y;
    if (p->grp != q->grp)
        return p->grp < q->grp ? -1 : 1;
    if (p->seg != q->seg)
        return p->seg < q->seg ? -1 : 1;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    if (p->b != q->b)
        return p->b < q->b ? -1 : 1;
    return p->job < q->job ? -1 : p->job > q->job;
}

/* Items in a chunk: how many of the n items from start to take (at most
 * chunk), ending before a run of one piece that the chunk would cut (unless
 * the run fills it). */
long drv_chunk_count(const itemvec *cur, size_t start, int chunk)
{
    size_t n = cur->n - start < (size_t)chunk ? cur->n - start : (size_t)chunk;
    size_t end = start + n;
    if (end < cur->n) {
        size_t r = end;
        while (r > start && drv_same_piece(&cur->v[r - 1], &cur->v[end]))
            r--;
        if (r > start)
            end = r;
    }
    return (long)(end - start);
}

/* rep[i]: the item of the chunk whose fit item i takes (i itself: its own). */
void drv_chunk_reps(const item *its, long cnt, const jstate *js, int *rep)
{
    long first = -1; /* the run's first live item */
    for (long i = 0; i < cnt; i++) {
        if (i == 0 || !drv_same_piece(&its[i - 1], &its[i]))
            first = -1;
        rep[i] = (int)i;
        if (js[its[i].job].dead)
            continue;
        if (first < 0)
            first = i;
        else
            rep[i] = (int)first;
    }
}

/* stop[i] for the items that measure (rep[i] == i): the largest of the
 * stops of the items taking that fit, 0 when any needs it in full. */
void drv_chunk_stops(const ob_job *jobs, const item *its, long cnt, const int *rep, int full_probes,
                        double *stop)
{
    for (long i = 0; i < cnt; i++) {
        const double s = drv_item_stop(&jobs[its[i].job], &its[i], full_probes);
        const long r = rep[i];
        if (r == i)
            stop[i] = s;
        else if (stop[r] > 0.0)
            stop[r] = s > 0.0 ? fmax(stop[r], s) : 0.0;
    }
}

/* Items that take another's fit get its results (and are charged its cost). */
void drv_copy_shared(long cnt, const int *rep, itemres *res, fitjoints *fj, double *fit_ns, double *eval_ns)
{
    for (long i = 0; i < cnt; i++) {
        const int r = rep[i];
        if (r == i)
            continue;
        res[i] = res[r];
        fj[i] = fj[r];
        fit_ns[i] = fit_ns[r];
        eval_ns[i] = eval_ns[r];
    }
}
