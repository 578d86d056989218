/*
 * driver.c - adaptive subdivision, level by level over all jobs.  See driver.h.
 */
#include "methods/driver/driver.h"
#include "methods/core/grow.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *const split_names[OB_SPLIT_COUNT] = {"mid", "maxerr", "greedy", "optimal"};

const char *ob_split_name(ob_split s) { return (s >= 0 && s < OB_SPLIT_COUNT) ? split_names[s] : "?"; }

const char *ob_status_name(ob_status s)
{
    switch (s) {
    case OB_OK: return "ok";
    case OB_LIMIT: return "limit";
    case OB_FAIL: return "fail";
    case OB_SKIP: return "skip";
    case OB_TIMEOUT: return "timeout";
    }
    return "?";
}

int ob_split_parse(const char *name, ob_split *s)
{
    for (int i = 0; i < OB_SPLIT_COUNT; i++)
        if (strcmp(name, split_names[i]) == 0) {
            *s = (ob_split)i;
            return 0;
        }
    return -1;
}

void ob_driver_defaults(ob_driver_opts *o)
{
    memset(o, 0, sizeof *o);  /* no batch backend: the CPU measures */
    o->samples = OB_DEFAULT_SAMPLES;
    o->max_depth = 40;
    o->max_segments = 20000;
    o->inflections = 1;
    o->chunk = 512;
}

/* greedy bisection stops when the bracket on the end parameter is this
 * fraction of the stretch still to cover */
static const double GREEDY_EPS = 1e-4;
/* optimal: the bisection on the common error level stops when its bracket
 * is within this ratio, or after OPT_ROUNDS passes */
static const double OPT_RATIO = 1.02;
enum { OPT_ROUNDS = 12 };
/* maxerr split keeps this fraction of the piece on either side */
static const double MAXERR_MARGIN = 0.05;
/* A piece whose error has not dropped below STALL_RATIO of its parent's over
 * STALL_LEVELS successive splits cannot reach the tolerance by subdivision
 * (an error floor of the method, e.g. Lee's circle approximation under the
 * Hausdorff metric); it is accepted and the job ends with status limit.
 * Convergent methods gain a factor 4 to 16 per split, so this never fires for
 * them; slowly converging pieces (a factor 2) are not taken for stalled. */
static const double STALL_RATIO = 0.9;
enum { STALL_LEVELS = 4 };
/* A method asks for a smaller piece when its output would not fit (too many
 * arcs, spans or a pole); a few halvings cure that.  A piece still asking
 * after this many halvings below its initial size never will: the job fails
 * (instead of halving down to the segment limit). */
enum { RETRY_LEVELS = 12 };

/* What the joints need of one fit (joints.h): the start of its first piece,
 * the end of its last, and the joints between its own pieces. */
typedef struct {
    ob_end first, last;
    ob_joint_stats in;
    int count_open;     /* open inner joints counted in ctrl_points (none for a
                           method's own representation: it has its own count) */
} fitjoints;

/* One pending piece of one job. */
typedef struct {
    int job, seg, depth;
    int grp;            /* the job's share group (share_groups) */
    double a, b;        /* the piece fitted now: base parameters of segment seg */
    double end;         /* greedy: end of the stretch being covered */
    double lo, hi;      /* greedy: longest passing / shortest failing end so far */
    double pass_err;    /* greedy: results of the candidate [a, lo] */
    int pass_ctrl_add, pass_maxdeg, pass_n;
    fitjoints pass_fj;  /* greedy: the joints of the candidate [a, lo] */
    int final;          /* greedy: accept this fit whatever its error */
    double parent_err;  /* mid/maxerr: the error of the piece this one was split from */
    int stall;          /* successive splits without a real drop of the error */
    int chain_to;       /* > 0: the leftmost piece of a chain of requests for a
                           smaller piece, already fitted down to this depth
                           (probe_retry_chain): not fitted again above it */
    /* optimal (decide_optimal): greedy passes over the stretch [start, end]
     * at an error level; phase 0 counts the pieces at tol, 1 bisects the
     * level, 2 is the final pass (the greedy code, at the level) */
    int phase, pieces, target, rounds;
    double start, level, elo, ehi, pass_max;
} item;

typedef struct {
    item *v;
    size_t n, cap;
} itemvec;

static int push(itemvec *q, const item *it)
{
    if (ob_grow(&q->v, &q->cap, q->n, sizeof *q->v, 256))
        return -1;
    q->v[q->n++] = *it;
    return 0;
}

/* Per-job bookkeeping the caller does not see. */
typedef struct {
    long ctrl_add;  /* sum over accepted fits of the control points each adds
                       beyond the shared start point */
    long pending;   /* items of this job still queued */
    int dead;       /* failed or skipped: drop its remaining items */
    int finished;   /* counted as done for progress */
    int floored;    /* a piece hit an error floor: keep the rest as they are */
    ob_span_log *spans; /* NULL, or where accepted pieces go */
    /* joints: the ends of every accepted fit until the job is finalized */
    double gap_tol;     /* a joint is open past this (joints.h) */
    struct fitends *ends;
    int nends, capends;
    int ends_oom;       /* an end could not be stored */
    ob_joint_stats st;  /* inner joints of the accepted fits, then (finalized) all */
    long open_count;    /* joints counted twice in ctrl_points */
    int joined;         /* the joints between fits are measured, ends freed */
} jstate;

/* The ends of one accepted fit over [a, ...] of base segment seg. */
typedef struct fitends {
    int seg;
    double a;
    ob_end first, last;
} fitends;

static double clock_ns(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

/* Wall time: what a batch backend's launch costs the run. */
static double wall_ns(void) { return clock_ns(CLOCK_MONOTONIC); }

/* CPU time of the calling thread: what one fit or one CPU measurement cost,
 * whatever else the machine was doing meanwhile (other threads, other
 * processes, a thread descheduled mid-call). */
static double thread_ns(void) { return clock_ns(CLOCK_THREAD_CPUTIME_ID); }

/* The job status that a fit status ends a job with: the one place where a
 * method's fit status becomes a job's.  OB_FIT_OK and OB_FIT_RETRY_SMALLER
 * end no job (decide accepts or splits the piece): OB_OK. */
static ob_status job_status_of(ob_fit_status st)
{
    switch (st) {
    case OB_FIT_FAIL: return OB_FAIL;
    case OB_FIT_SKIP: return OB_SKIP;
    case OB_FIT_OK:
    case OB_FIT_RETRY_SMALLER: break;
    }
    return OB_OK;
}

static void job_end(ob_job *j, jstate *s, ob_status st, const char *msg)
{
    if (j->status == OB_OK || (j->status == OB_LIMIT && st != OB_LIMIT)) {
        j->status = st;
        snprintf(j->message, sizeof j->message, "%s", msg);
    }
    if (st == OB_FAIL || st == OB_SKIP || st == OB_TIMEOUT)
        s->dead = 1;
}

/* Inputs a method or metric cannot take: the job is skipped before any work. */
static int check_applicable(ob_job *j, jstate *s)
{
    const ob_method *m = j->method;
    char msg[160];
    for (int i = 0; i < j->curve->nseg; i++) {
        const ob_bez *b = &j->curve->seg[i];
        if (b->rational && !(m->caps & OB_CAP_RATIONAL_IN)) {
            job_end(j, s, OB_SKIP, "rational input is not supported by this method");
            return 0;
        }
        int od = ob_method_out_degree(m, b->deg, b->rational, j->params);
        if (od > OB_MAX_DEG) {
            snprintf(msg, sizeof msg, "output degree %d exceeds the limit %d", od, OB_MAX_DEG);
            job_end(j, s, OB_SKIP, msg);
            return 0;
        }
    }
    if (ob_metric_same_param(j->metric) && !(m->caps & OB_CAP_SAME_PARAM)) {
        snprintf(msg, sizeof msg, "metric %s needs an approximation in the base's parameter",
                 ob_metric_name(j->metric));
        job_end(j, s, OB_SKIP, msg);
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
static int plan_job(const ob_job *j, int jobidx, int grp, const ob_driver_opts *o, itemvec *out)
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
                if (push(out, &it))
                    return -1;
                prev = next;
            }
        }
    }
    return 0;
}

static void log_span(ob_span_log *L, int seg, double a, double b)
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
    L->v[L->n++] = (ob_span){seg, a, b};
}

static int span_cmp(const void *x, const void *y)
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
static void accept(ob_job *j, jstate *s, int seg, double a, double b, int npieces, int ctrl_add, int maxdeg,
                   double err, const fitjoints *fj)
{
    log_span(s->spans, seg, a, b);
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

/* Results of fitting and measuring one item. */
typedef struct {
    ob_fit_status st;       /* the method's, or OB_FIT_FAIL where its output
                               is not usable (piece count, not measurable) */
    int ctrl_add, maxdeg, n;
    double err, t;          /* t: base parameter of the largest error */
    int chain_to;           /* > 0: asks for a smaller piece, and so do its
                               leftmost descendants down to this depth, the
                               retry or depth limit (probe_retry_chain) */
    char msg[160];
} itemres;

/* Fit one item; returns the thread time spent in the method. */
static double fit_item(const ob_job *jobs, const item *it, void *work, ob_fit *fit, itemres *r)
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
    double t0 = thread_ns();
    const ob_fit_args args = {j->d, j->tol, par};
    r->st = j->method->fit(&sub, &args, work, fit, r->msg, sizeof r->msg);
    double t1 = thread_ns();
    r->n = r->st == OB_FIT_OK ? fit->n : 0;
    if (r->st == OB_FIT_RETRY_SMALLER)
        r->err = INFINITY;
    if (r->st == OB_FIT_OK && (fit->n < 1 || fit->n > OB_MAX_PIECES)) {
        r->st = OB_FIT_FAIL;
        snprintf(r->msg, sizeof r->msg, "method returned %d pieces", fit->n);
    }
    return t1 - t0;
}

/* What decide() says of a piece that asks for a smaller piece (r: its fit's
 * result) when none may be made: at the retry limit, or past the depth or
 * segment limits. */
static void retry_end_msg(const item *it, const itemres *r, int at_retry_limit, char *msg, size_t len)
{
    const char *why = r->msg[0] ? r->msg : "the method needs a smaller piece";
    if (at_retry_limit)
        snprintf(msg, len, "%.60s, still after %d halvings, at t in [%.6g, %.6g] of segment %d", why,
                 RETRY_LEVELS, it->a, it->b, it->seg);
    else
        snprintf(msg, len, "%.60s; pieces that small are past the limits, at t in [%.6g, %.6g] of segment %d",
                 why, it->a, it->b, it->seg);
}

/* Purpose: find out at once whether a piece that asked for a smaller piece
 * (r->st == OB_FIT_RETRY_SMALLER, split mid or maxerr) heads a chain of such
 * requests down to the retry limit.
 * Method: such a piece is halved, and a descendant still asking at
 * RETRY_LEVELS halvings (or at the depth limit) fails the job (decide).
 * Where the method's request does not depend on the piece's size (a
 * rational fit whose every iterate has a pole, at any scale), the
 * breadth-first driver fitted all 2^(RETRY_LEVELS - depth) descendants
 * before the first of them failed the job at the limit.  The leftmost chain
 * of halvings is fitted here instead; if every piece on it asks again,
 * r->chain_to gets the depth it reached, and decide() then carries only the
 * leftmost descendant down, unfitted, to be fitted (and to fail the job, in
 * its turn among the items of that level) at that depth: the first piece at
 * that level the breadth-first driver would have failed the job on.  What is
 * not fitted, the rest of the subtree, could change the outcome only by a
 * terminal event of its own above that depth (a fit error, a limit).
 * Returns the thread time spent.  fit: scratch, overwritten. */
static double probe_retry_chain(const ob_job *jobs, const item *it, int max_depth, void *work, ob_fit *fit,
                                itemres *r)
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
        ns += fit_item(jobs, &c, work, fit, &cr);
        if (cr.st != OB_FIT_RETRY_SMALLER)
            return ns;
    }
    if (c.depth > it->depth)
        r->chain_to = c.depth;
    return ns;
}

/* The measurements of one batch: every piece of every fitted item. */
typedef struct {
    ob_bez *base;          /* base sub-piece of each record */
    ob_measure_rec *rec;
    ob_errval *out;
    double *ns;
    int *first;            /* first record of each item (nitems + 1 entries) */
    int *sampled;          /* indices of the records a batch backend takes */
    ob_measure_rec *srec;
    ob_errval *sout;
} batch;

static int batch_alloc(batch *b, int chunk)
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

static void batch_free(batch *b)
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

/* Measure all pieces of all fitted items of a chunk: one batch. */
static void measure_chunk(const ob_job *jobs, const item *its, long cnt, const ob_fit *fits, const double *stop,
                          itemres *res, double *eval_ns, int samples, const ob_driver_hooks *h, batch *B)
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
#pragma omp parallel for schedule(dynamic, 8) if (cnt > 1)
    for (long i = 0; i < cnt; i++) {
        if (res[i].st != OB_FIT_OK)
            continue;
        const ob_job *j = &jobs[its[i].job];
        ob_bez sub;
        ob_bez_subsegment(&j->curve->seg[its[i].seg], its[i].a, its[i].b, &sub);
        for (int p = 0; p < fits[i].n; p++) {
            const int r = B->first[i] + p;
            ob_bez_subsegment(&sub, fits[i].t[p], fits[i].t[p + 1], &B->base[r]);
            B->rec[r] = (ob_measure_rec){&B->base[r], &fits[i].seg[p], j->d, j->metric, stop[i]};
        }
    }
    /* sampled records to the backend in one call, the rest on the CPU */
    int ns = 0;
    if (h->batch)
        for (int r = 0; r < n; r++)
            if (B->rec[r].metric != OB_METRIC_BOUND)
                B->sampled[ns++] = r;
    int backend_ok = 0;
    if (ns > 0) {
        for (int k = 0; k < ns; k++)
            B->srec[k] = B->rec[B->sampled[k]];
        const double t0 = wall_ns();
        backend_ok = h->batch(h->batch_ctx, B->srec, ns, samples, B->sout) == 0;
        const double wall = wall_ns() - t0;
        if (backend_ok) {
            /* one launch measured them all: each record's share of its wall
             * time is its share of the work (the kernel counts it) */
            double total = 0.0;
            for (int k = 0; k < ns; k++)
                total += B->sout[k].work;
            for (int k = 0; k < ns; k++) {
                B->out[B->sampled[k]] = B->sout[k];
                B->ns[B->sampled[k]] = total > 0.0 ? wall * (B->sout[k].work / total) : wall / ns;
            }
        } else if (h->batch_fallbacks) {
            (*h->batch_fallbacks)++;
        }
    }
#pragma omp parallel for schedule(dynamic, 4) if (n > 1)
    for (int r = 0; r < n; r++) {
        if (backend_ok && B->rec[r].metric != OB_METRIC_BOUND)
            continue;
        const double t0 = thread_ns();
        if (ob_measure_until(B->rec[r].metric, B->rec[r].base, B->rec[r].approx, B->rec[r].d, samples,
                             B->rec[r].stop, &B->out[r]))
            B->out[r].err = NAN;  /* cannot be measured: reported below */
        B->ns[r] = thread_ns() - t0;
    }
    /* per item: the largest error over its pieces, at a base parameter */
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
static void joints_chunk(const jstate *js, const item *its, long cnt, const ob_fit *fits, const itemres *res,
                         fitjoints *fj)
{
#pragma omp parallel for schedule(dynamic, 16) if (cnt > 64)
    for (long i = 0; i < cnt; i++) {
        if (res[i].st == OB_FIT_OK)
            fit_joints(&fits[i], js[its[i].job].gap_tol, &fj[i]);
        else
            memset(&fj[i], 0, sizeof fj[i]);
    }
}

/* Accept the item's whole fit. */
static void accept_item(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj)
{
    accept(j, s, it->seg, it->a, it->b, r->n, r->ctrl_add, r->maxdeg, r->err, fj);
}

/* The optimal rule at the end of one pass over its stretch: the next
 * level, or the final pass.  Phase 0 (at tol) gives the target count; a
 * pass of phase 1 is feasible when it covers the stretch in at most target
 * pieces.  The upper level is always one whose pass was feasible, so the
 * final pass at it (the same fits, the same decisions) takes that pass's
 * pieces; the lower one starts at 1/64 of phase 0's largest error. */
static void optimal_next_pass(item *g, int covered)
{
    if (g->phase == 0) {
        g->target = g->pieces;
        g->ehi = g->level;
        g->elo = g->pass_max / 64;
    } else if (covered && g->pieces <= g->target) {
        g->ehi = g->level;
    } else {
        g->elo = g->level;
    }
    g->rounds++;
    const int done = g->target <= 1 || g->ehi <= OPT_RATIO * g->elo || g->rounds > OPT_ROUNDS;
    g->phase = done ? 2 : 1;
    g->level = done ? g->ehi : sqrt(g->elo * g->ehi);
    g->pieces = 0;
    g->pass_max = 0.0;
    g->a = g->lo = g->start;
    g->hi = g->b = g->end;
}

/* Purpose: the optimal split rule's counting passes (phases 0 and 1): the
 *          greedy bisection on the end of the prefix [a, b] at the item's
 *          level, counting the pieces instead of accepting them.
 * Method:  a pass that needs more than target pieces, or where not even a
 *          sliver meets the level, is infeasible and ends early; phase 0
 *          where not even a sliver passes goes straight to the final pass
 *          at tol, which is greedy's (with its limit rules).  The level is
 *          bisected geometrically between an infeasible and a feasible one;
 *          the final pass (phase 2, in decide) accepts the pieces at the
 *          lowest feasible level found.  Every pass fits the same pieces
 *          as a greedy run at that tolerance would.  A stretch whose first
 *          probe of phase 0 (the whole of it) passes is accepted at once:
 *          the target is then 1 and the final pass would fit and measure
 *          that same piece again. */
static int decide_optimal(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj, int pass,
                          itemvec *next)
{
    item g = *it;
    if (g.phase == 0 && pass && it->a == g.start && it->b >= g.end) {
        /* the whole stretch is one piece at tol: the final pass would fit
         * and measure this same piece again (target 1) and accept it */
        accept_item(j, s, it, r, fj);
        return 0;
    }
    if (pass) {
        g.lo = it->b;
        g.pass_err = r->err;
    } else {
        g.hi = it->b;
    }
    const int reached = pass && it->b >= it->end;
    if (reached || g.hi - g.lo <= GREEDY_EPS * (g.end - g.a)) {
        if (g.lo > g.a) {  /* a piece of this pass: [a, lo] */
            g.pieces++;
            g.pass_max = fmax(g.pass_max, g.pass_err);
            g.a = g.lo;
            g.hi = g.b = g.end;
            if (g.a >= g.end || (g.phase == 1 && g.pieces > g.target))
                optimal_next_pass(&g, g.a >= g.end);
        } else if (g.phase == 0) {
            g.phase = 2;  /* not even a sliver at tol: greedy decides */
            g.level = j->tol;
            g.a = g.lo = g.start;
            g.hi = g.b = g.end;
        } else {
            optimal_next_pass(&g, 0);
        }
    } else {
        g.b = 0.5 * (g.lo + g.hi);
    }
    s->pending++;
    return push(next, &g);
}

/* What decide() found of one measured item: it asks for a smaller piece
 * (msg then says why none may be made), it meets its error level, the job
 * is at its segment limit; msg: the message of the job's end, if it ends. */
typedef struct {
    int retry, pass, full;
    char msg[160];
} verdict;

/* mid / maxerr: the two halves of a piece that is to be split (cut at the
 * middle, or at the largest error kept MAXERR_MARGIN from the ends), or, for
 * a chain of requests for a smaller piece down to the limit, its leftmost
 * half alone. */
static int split_children(jstate *s, const item *it, const itemres *r, int split, int retry, int stall,
                          itemvec *next)
{
    double cut = 0.5 * (it->a + it->b);
    if (split == OB_SPLIT_MAXERR && !retry) {
        double w = it->b - it->a;
        cut = fmin(it->b - MAXERR_MARGIN * w, fmax(it->a + MAXERR_MARGIN * w, r->t));
    }
    item l = *it, rr = *it;
    l.b = cut;
    rr.a = cut;
    l.depth = rr.depth = it->depth + 1;
    l.parent_err = rr.parent_err = retry ? INFINITY : r->err;
    l.stall = rr.stall = stall;
    l.end = l.hi = l.b;
    l.lo = l.a;
    rr.end = rr.hi = rr.b;
    rr.lo = rr.a;
    l.chain_to = retry ? (it->chain_to > 0 ? it->chain_to : r->chain_to) : 0;
    if (l.chain_to > 0) {  /* a chain of requests down to the limit: its leftmost piece alone */
        s->pending += 1;
        return push(next, &l);
    }
    s->pending += 2;
    return push(next, &l) || push(next, &rr) ? -1 : 0;
}

/* The mid and maxerr rules: accept a piece that passes; else end the job at
 * the retry limit, keep the piece where the job has hit an error floor or
 * the error stalls, or at the depth or segment limit; else split it. */
static int decide_split(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj,
                        const ob_driver_opts *o, verdict *v, itemvec *next)
{
    const int retry = v->retry, full = v->full;
    if (v->pass) {
        accept_item(j, s, it, r, fj);
        return 0;
    }
    const int stall = !retry && r->err >= STALL_RATIO * it->parent_err ? it->stall + 1 : 0;
    if (retry && it->depth >= RETRY_LEVELS) {
        retry_end_msg(it, r, 1, v->msg, sizeof v->msg);
        job_end(j, s, OB_FAIL, v->msg);
        return 0;
    }
    if (!retry && s->floored) {  /* the job cannot reach tol: no more splitting */
        accept_item(j, s, it, r, fj);
        return 0;
    }
    if (stall >= STALL_LEVELS && !(it->depth >= o->max_depth || full)) {
        accept_item(j, s, it, r, fj);
        snprintf(v->msg, sizeof v->msg, "error stalls at %.3g > tol under subdivision at t in [%.6g, %.6g] "
                 "of segment %d (%d splits without a 10%% drop); the rest kept as it was", r->err, it->a,
                 it->b, it->seg, STALL_LEVELS);
        job_end(j, s, OB_LIMIT, v->msg);
        s->floored = 1;
        return 0;
    }
    if (it->depth >= o->max_depth || full) {
        if (retry) {
            job_end(j, s, OB_FAIL, v->msg);
            return 0;
        }
        accept_item(j, s, it, r, fj);
        if (full)
            snprintf(v->msg, sizeof v->msg, "segment limit %d reached (error %.3g > tol)", o->max_segments,
                     r->err);
        else
            snprintf(v->msg, sizeof v->msg, "depth limit %d reached at t in [%.6g, %.6g] of segment %d "
                     "(error %.3g)", o->max_depth, it->a, it->b, it->seg, r->err);
        job_end(j, s, OB_LIMIT, v->msg);
        return 0;
    }
    return split_children(s, it, r, j->split, retry, stall, next);
}

/* The greedy rule (and the optimal rule's final pass): bisection on the end
 * of the prefix [a, b]; the longest passing prefix is accepted once the
 * bracket [lo, hi] is within GREEDY_EPS, and the rest of the stretch starts
 * over. */
static int decide_greedy(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj,
                         const ob_driver_opts *o, verdict *v, itemvec *next)
{
    item g = *it;
    if (it->final) {
        if (v->retry) {
            job_end(j, s, OB_FAIL, v->msg);
            return 0;
        }
        accept_item(j, s, it, r, fj);
        if (!v->pass) {
            snprintf(v->msg, sizeof v->msg, "segment limit %d reached (error %.3g > tol)", o->max_segments,
                     r->err);
            job_end(j, s, OB_LIMIT, v->msg);
        }
        return 0;
    }
    if (v->pass) {
        if (it->b >= it->end) {
            accept_item(j, s, it, r, fj);
            return 0;
        }
        g.lo = it->b;
        g.pass_err = r->err;
        g.pass_ctrl_add = r->ctrl_add;
        g.pass_maxdeg = r->maxdeg;
        g.pass_n = r->n;
        g.pass_fj = *fj;
    } else {
        g.hi = it->b;
    }
    if (g.hi - g.lo <= GREEDY_EPS * (g.end - g.a)) {
        if (g.lo > g.a) {
            accept(j, s, it->seg, it->a, g.lo, g.pass_n, g.pass_ctrl_add, g.pass_maxdeg, g.pass_err, &g.pass_fj);
            g.a = g.lo;
        } else if (v->retry) {
            job_end(j, s, OB_FAIL, v->msg);
            return 0;
        } else {
            /* not even a sliver passes: an error floor subdivision cannot get
             * under; keep the sliver, fit the rest of the stretch once and keep
             * it too, and end the job with status limit */
            accept_item(j, s, it, r, fj);
            snprintf(v->msg, sizeof v->msg, "no prefix longer than %.3g passes at t = %.6g of segment %d "
                     "(error %.3g)", it->b - it->a, it->a, it->seg, r->err);
            job_end(j, s, OB_LIMIT, v->msg);
            g.a = it->b;
            g.final = 1;
        }
        if (g.a >= g.end)
            return 0;
        g.lo = g.a;
        g.hi = g.b = g.end;
        /* out of segments: the rest is fitted once and kept whatever its error */
        g.final = g.final || j->segments + 1 >= o->max_segments;
    } else {
        g.b = 0.5 * (g.lo + g.hi);
    }
    s->pending++;
    return push(next, &g);
}

/* Decide what becomes of one measured item (fj: the joints of its fit);
 * children go to `next`. */
static int decide(ob_job *jobs, jstate *js, const item *it, const itemres *r, const fitjoints *fj,
                  const ob_driver_opts *o, itemvec *next)
{
    ob_job *j = &jobs[it->job];
    jstate *s = &js[it->job];
    verdict v;
    s->pending--;
    if (s->dead)
        return 0;
    if (r->st != OB_FIT_OK && r->st != OB_FIT_RETRY_SMALLER) {
        snprintf(v.msg, sizeof v.msg, "%.100s at t in [%.6g, %.6g] of segment %d",
                 r->msg[0] ? r->msg : "fit failed", it->a, it->b, it->seg);
        job_end(j, s, job_status_of(r->st), v.msg);
        return 0;
    }
    /* a method that asks for a smaller piece is treated as too large an error;
     * if no smaller piece may be made, there is nothing to accept */
    v.retry = r->st == OB_FIT_RETRY_SMALLER;
    if (v.retry)
        retry_end_msg(it, r, 0, v.msg, sizeof v.msg);
    /* the optimal rule's passes are greedy at their own error level */
    v.pass = !v.retry && r->err <= (j->split == OB_SPLIT_OPTIMAL ? it->level : j->tol);
    v.full = j->segments + s->pending + 1 >= o->max_segments;

    if (j->split == OB_SPLIT_OPTIMAL && it->phase < 2)
        return decide_optimal(j, s, it, r, fj, v.pass, next);
    if (j->split == OB_SPLIT_MID || j->split == OB_SPLIT_MAXERR)
        return decide_split(j, s, it, r, fj, o, &v, next);
    return decide_greedy(j, s, it, r, fj, o, &v, next);
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
static void finalize(ob_job *j, jstate *s)
{
    if ((j->status == OB_OK || j->status == OB_LIMIT) && s->ends_oom)
        job_end(j, s, OB_FAIL, "out of memory keeping the ends of the accepted pieces");
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
static int *share_groups(const ob_job *jobs, size_t njobs)
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

/* 1 when items x and y fit the same piece for the same share group. */
static int same_piece(const item *x, const item *y)
{
    return x->grp == y->grp && x->seg == y->seg && x->a == y->a && x->b == y->b;
}

static int item_share_cmp(const void *x, const void *y)
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
static long chunk_count(const itemvec *cur, size_t start, int chunk)
{
    size_t n = cur->n - start < (size_t)chunk ? cur->n - start : (size_t)chunk;
    size_t end = start + n;
    if (end < cur->n) {
        size_t r = end;
        while (r > start && same_piece(&cur->v[r - 1], &cur->v[end]))
            r--;
        if (r > start)
            end = r;
    }
    return (long)(end - start);
}

/* rep[i]: the item of the chunk whose fit item i takes (i itself: its own). */
static void chunk_reps(const item *its, long cnt, const jstate *js, int *rep)
{
    long first = -1; /* the run's first live item */
    for (long i = 0; i < cnt; i++) {
        if (i == 0 || !same_piece(&its[i - 1], &its[i]))
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

/* Purpose: the stop of one item's measurement (ob_measure_rec.stop).
 * Returns: its error level where only whether the error exceeds it
 *          matters: a greedy or optimal probe that fails only narrows the
 *          bracket on its end (decide_greedy, decide_optimal), unless it
 *          would end the search with not even a sliver passing (its error
 *          is then reported); else 0, the full measurement: for mid and
 *          maxerr (a failing piece's error drives the stall rule and the
 *          split point), final pieces and that sliver. */
static double item_stop(const ob_job *j, const item *it, int full_probes)
{
    if (full_probes || it->final || (j->split != OB_SPLIT_GREEDY && j->split != OB_SPLIT_OPTIMAL))
        return 0.0;
    if (j->split == OB_SPLIT_OPTIMAL && it->phase < 2)
        return it->level;
    /* decide_greedy's test of the bracket after a failing probe */
    const int sliver = !(it->lo > it->a) && it->b - it->lo <= GREEDY_EPS * (it->end - it->a);
    return sliver ? 0.0 : j->split == OB_SPLIT_OPTIMAL ? it->level : j->tol;
}

/* stop[i] for the items that measure (rep[i] == i): the largest of the
 * stops of the items taking that fit, 0 when any needs it in full. */
static void chunk_stops(const ob_job *jobs, const item *its, long cnt, const int *rep, int full_probes,
                        double *stop)
{
    for (long i = 0; i < cnt; i++) {
        const double s = item_stop(&jobs[its[i].job], &its[i], full_probes);
        const long r = rep[i];
        if (r == i)
            stop[i] = s;
        else if (stop[r] > 0.0)
            stop[r] = s > 0.0 ? fmax(stop[r], s) : 0.0;
    }
}

/* Items that take another's fit get its results (and are charged its cost). */
static void copy_shared(long cnt, const int *rep, itemres *res, fitjoints *fj, double *fit_ns, double *eval_ns)
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

/* One driver run: its jobs, settings, hooks and the buffers of one chunk. */
typedef struct {
    ob_job *jobs;
    size_t njobs;
    ob_driver_opts o;
    ob_driver_hooks h;
    jstate *js;
    itemvec cur, next;
    size_t wsize;       /* the largest work area a method asks for */
    char *work;         /* wsize bytes per thread */
    ob_fit *fits;       /* chunk entries each, from here to rep */
    itemres *res;
    double *fit_ns, *eval_ns;
    double *stop;       /* each measuring item's stop (chunk_stops) */
    fitjoints *fj;
    int *rep;
    int *grp;           /* njobs: each job's share group */
    batch B;
    size_t done;        /* jobs finished */
} drun;

static int drun_alloc(drun *R)
{
    const size_t nj = R->njobs ? R->njobs : 1, nc = (size_t)R->o.chunk;
    R->js = calloc(nj, sizeof *R->js);
    R->wsize = 1;
    for (size_t i = 0; i < R->njobs; i++)
        if (R->jobs[i].method->work_size > R->wsize)
            R->wsize = R->jobs[i].method->work_size;
    R->work = malloc(R->wsize * (size_t)omp_get_max_threads());
    R->fits = malloc(nc * sizeof *R->fits);
    R->res = malloc(nc * sizeof *R->res);
    R->fit_ns = malloc(nc * sizeof *R->fit_ns);
    R->eval_ns = malloc(nc * sizeof *R->eval_ns);
    R->stop = malloc(nc * sizeof *R->stop);
    R->fj = malloc(nc * sizeof *R->fj);
    R->rep = malloc(nc * sizeof *R->rep);
    R->grp = share_groups(R->jobs, R->njobs);
    const int bad = batch_alloc(&R->B, R->o.chunk);
    return !bad && R->js && R->work && R->fits && R->res && R->fit_ns && R->eval_ns && R->stop && R->fj && R->rep &&
                   R->grp
               ? 0 : -1;
}

static void drun_free(drun *R)
{
    free(R->cur.v);
    free(R->next.v);
    free(R->js);
    free(R->work);
    free(R->fits);
    free(R->res);
    free(R->fit_ns);
    free(R->eval_ns);
    free(R->stop);
    batch_free(&R->B);
    free(R->fj);
    free(R->grp);
    free(R->rep);
}

/* Every job's outputs cleared, its bookkeeping started. */
static void init_jobs(drun *R)
{
    for (size_t i = 0; i < R->njobs; i++) {
        ob_job *j = &R->jobs[i];
        j->status = OB_OK;
        j->ctrl_points = 0;
        j->segments = 0;
        j->out_degree = 0;
        j->max_err = 0.0;
        j->fit_ns = j->eval_ns = 0.0;
        j->message[0] = '\0';
        R->js[i].spans = R->h.spans ? &R->h.spans[i] : NULL;
        j->max_gap = j->max_kink = NAN;
        j->continuity = OB_CONT_NONE;
        j->joints = j->open_joints = 0;
        R->js[i].gap_tol = ob_joint_gap_tol(j->curve, j->d);
    }
}

/* Job i is done: its outputs final, the caller told.  Returns -1 when the
 * out-of-memory test hook fires. */
static int job_finished(drun *R, size_t i)
{
    R->js[i].finished = 1;
    R->done++;
    finalize(&R->jobs[i], &R->js[i]);
    if (R->h.job_done)
        R->h.job_done(R->h.job_done_ctx, i);
    return R->o.test_oom_after > 0 && R->done >= (size_t)R->o.test_oom_after ? -1 : 0;
}

/* The first pieces of every job (in parallel), queued in job order; jobs
 * that are skipped before any work finish here.  0, or -1 (memory). */
static int plan_all(drun *R)
{
    itemvec *plans = calloc(R->njobs ? R->njobs : 1, sizeof *plans);
    if (!plans)
        return -1;
    int fail = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : fail)
    for (long i = 0; i < (long)R->njobs; i++) {
        if (!check_applicable(&R->jobs[i], &R->js[i]))
            continue;
        fail |= plan_job(&R->jobs[i], (int)i, R->grp[i], &R->o, &plans[i]) != 0;
    }
    for (size_t i = 0; i < R->njobs && !fail; i++) {
        if (plans[i].n == 0)  /* skipped before any work (the hook cannot fire: nothing ran) */
            job_finished(R, i);
        for (size_t k = 0; k < plans[i].n && !fail; k++)
            fail = push(&R->cur, &plans[i].v[k]) != 0;
        R->js[i].pending = (long)plans[i].n;
    }
    for (size_t i = 0; i < R->njobs; i++)
        free(plans[i].v);
    free(plans);
    return fail ? -1 : 0;
}

/* Fit every pending piece of a chunk (once per share group). */
static void fit_chunk(drun *R, const item *its, long cnt)
{
#pragma omp parallel for schedule(dynamic, 4) if (cnt > 1)
    for (long i = 0; i < cnt; i++) {
        void *w = R->work + R->wsize * (size_t)omp_get_thread_num();
        if (its[i].chain_to > its[i].depth) {  /* its fit asked for a smaller piece (the probe) */
            memset(&R->res[i], 0, sizeof R->res[i]);
            R->res[i].st = OB_FIT_RETRY_SMALLER;
            R->res[i].err = INFINITY;
            R->fit_ns[i] = 0.0;
            continue;
        }
        if (R->js[its[i].job].dead || R->rep[i] != i) {
            R->res[i].st = OB_FIT_SKIP;  /* dead, or takes its representative's fit below */
            R->fit_ns[i] = 0.0;
            continue;
        }
        R->fit_ns[i] = fit_item(R->jobs, &its[i], w, &R->fits[i], &R->res[i]);
        R->fit_ns[i] += probe_retry_chain(R->jobs, &its[i], R->o.max_depth, w, &R->fits[i], &R->res[i]);
    }
}

/* A job past its --job-timeout ends with status timeout. */
static void check_timeout(drun *R, int job)
{
    ob_job *j = &R->jobs[job];
    jstate *s = &R->js[job];
    if (R->o.job_timeout_ns > 0 && !s->dead && s->pending > 0 && j->fit_ns + j->eval_ns > R->o.job_timeout_ns) {
        char msg[160];
        snprintf(msg, sizeof msg, "job timeout: %.3g s of thread time used, limit %.3g s (%d segments "
                 "accepted so far)", (j->fit_ns + j->eval_ns) * 1e-9, R->o.job_timeout_ns * 1e-9, j->segments);
        job_end(j, s, OB_TIMEOUT, msg);
    }
}

/* One chunk of a level: fit, joints, measure, then decide in job order.
 * 0, or -1 (memory, or the test hook). */
static int run_chunk(drun *R, const item *its, long cnt)
{
    chunk_reps(its, cnt, R->js, R->rep);
    fit_chunk(R, its, cnt);
    joints_chunk(R->js, its, cnt, R->fits, R->res, R->fj);  /* the ends and inner joints (joints.h) */
    chunk_stops(R->jobs, its, cnt, R->rep, R->o.full_probes, R->stop);
    measure_chunk(R->jobs, its, cnt, R->fits, R->stop, R->res, R->eval_ns, R->o.samples, &R->h, &R->B);
    copy_shared(cnt, R->rep, R->res, R->fj, R->fit_ns, R->eval_ns);
    for (long i = 0; i < cnt; i++) {
        const int job = its[i].job;
        R->jobs[job].fit_ns += R->fit_ns[i];
        R->jobs[job].eval_ns += R->eval_ns[i];
        if (decide(R->jobs, R->js, &its[i], &R->res[i], &R->fj[i], &R->o, &R->next))
            return -1;
        check_timeout(R, job);
        const jstate *s = &R->js[job];
        if (!s->finished && (s->pending == 0 || s->dead) && job_finished(R, (size_t)job) != 0)
            return -1;
    }
    return 0;
}

/* Level after level until no piece is pending.  0, -1 (memory), 1 (stop). */
static int run_levels(drun *R)
{
    while (R->cur.n > 0) {
        R->next.n = 0;
        /* the items of one share group on one piece side by side */
        qsort(R->cur.v, R->cur.n, sizeof *R->cur.v, item_share_cmp);
        long cnt;
        for (size_t start = 0; start < R->cur.n; start += (size_t)cnt) {
            cnt = chunk_count(&R->cur, start, R->o.chunk);
            if (run_chunk(R, R->cur.v + start, cnt) != 0)
                return -1;
            if (R->h.progress)
                R->h.progress(R->h.progress_ctx, R->done, R->njobs);
            if (R->h.stop && *R->h.stop)
                return 1;
        }
        itemvec tmp = R->cur;
        R->cur = R->next;
        R->next = tmp;
    }
    return 0;
}

/* Every job's outputs, whatever happened: jobs not finished when the run
 * ended early (rc != 0) fail with the reason. */
static void end_jobs(drun *R, int rc)
{
    for (size_t i = 0; i < R->njobs; i++) {
        ob_job *j = &R->jobs[i];
        if (rc != 0 && (!R->js || !R->js[i].finished)) {
            j->status = OB_FAIL;
            snprintf(j->message, sizeof j->message, "%s", rc > 0 ? "interrupted" : "out of memory");
        }
        if (R->js) {
            finalize(j, &R->js[i]);
        } else {
            j->ctrl_points = 0;
            j->segments = j->out_degree = 0;
            j->max_err = NAN;
            j->max_gap = j->max_kink = NAN;
            j->continuity = OB_CONT_NONE;
            j->joints = j->open_joints = 0;
        }
        if (R->h.spans && R->h.spans[i].n > 1)
            qsort(R->h.spans[i].v, (size_t)R->h.spans[i].n, sizeof *R->h.spans[i].v, span_cmp);
    }
}

int ob_driver_run(ob_job *jobs, size_t njobs, const ob_driver_opts *opts, const ob_driver_hooks *hooks)
{
    drun R;
    memset(&R, 0, sizeof R);
    R.jobs = jobs;
    R.njobs = njobs;
    if (opts)
        R.o = *opts;
    else
        ob_driver_defaults(&R.o);
    if (hooks)
        R.h = *hooks;
    if (R.o.chunk < 1)
        R.o.chunk = 1;
    int rc = drun_alloc(&R);
    if (rc == 0) {
        init_jobs(&R);
        rc = plan_all(&R);
    }
    if (rc == 0)
        rc = run_levels(&R);
    end_jobs(&R, rc);
    drun_free(&R);
    return rc;
}
