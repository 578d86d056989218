/*
 * fittime.c - `run --time-fits` (see fittime.h).
 */
#include "host/run/fittime.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "host/diag.h"
#include "host/run/clock.h"
#include "host/run/progress.h"
#include "host/run/signals.h"
#include "host/run/spread.h"

/* No measurement repeats the workload more often than this (a workload of
 * a few nanoseconds would otherwise calibrate to billions). */
#define MAX_ITERS 1000000L

int ob_fittime_wants(const ob_job *j) { return j->status == OB_OK || j->status == OB_LIMIT; }

/* One timed job: its workload, cut out before any clock runs. */
typedef struct {
    size_t i;           /* the job's index */
    int n;              /* its accepted pieces */
    ob_bez *sub;        /* their base pieces, as the driver cut them */
    int *times;         /* fits of each per iteration: 1 (the test hook: more) */
    double par[OB_MAX_PARAMS];
    long iters;         /* iterations per measurement (calibrated) */
    int bad;            /* a fit did not succeed again: not timed (a warning) */
} timed_job;

/* What one thread fits with. */
typedef struct {
    void *work;
    ob_fit *fit;
} scratch;

/* One iteration of job j's workload: a fit of each of its pieces (each done
 * times[k] times: the test hook, as the driver does).  0, or -1 when a fit
 * does not succeed (it did in the run: fits are deterministic). */
static int fit_all(const ob_job *j, const timed_job *t, const scratch *s)
{
    const ob_fit_args args = {j->d, j->tol, t->par};
    char msg[160];
    int bad = 0;
    for (int k = 0; k < t->n; k++)
        for (int r = 0; r < t->times[k]; r++)
            bad |= j->method->fit(&t->sub[k], &args, s->work, s->fit, msg, sizeof msg) != OB_FIT_OK;
    return bad ? -1 : 0;
}

/* The calling thread's CPU time, and what its fits spent outside it (a
 * server process: sisl), ns. */
static double fit_clock_ns(void) { return ob_thread_ns() + ob_fit_foreign_ns(); }

/* CPU time of `iters` iterations, per iteration: 0, or -1. */
static int measure(const ob_job *j, const timed_job *t, const scratch *s, long iters, double *per)
{
    const double t0 = fit_clock_ns();
    for (long k = 0; k < iters; k++)
        if (fit_all(j, t, s) != 0)
            return -1;
    *per = (fit_clock_ns() - t0) / (double)iters;
    return 0;
}

/* Warm-up and calibration (Google Benchmark's way): 1, 10, 100, ...
 * iterations until a run lasts a tenth of min_ns, then as many as make
 * min_ns.  0, or -1 when a fit fails. */
static int calibrate(const ob_job *j, timed_job *t, const scratch *s, double min_ns)
{
    for (long n = 1;; n *= 10) {
        double per;
        if (measure(j, t, s, n, &per) != 0)
            return -1;
        if (per * (double)n >= 0.1 * min_ns || n >= MAX_ITERS) {
            const double want = per > 0 ? ceil(min_ns / per) : (double)MAX_ITERS;
            t->iters = want < 1 ? 1 : want > (double)MAX_ITERS ? MAX_ITERS : (long)want;
            return 0;
        }
    }
}

static void free_jobs(timed_job *t, size_t n)
{
    for (size_t k = 0; t && k < n; k++) {
        free(t[k].sub);
        free(t[k].times);
    }
    free(t);
}

/* The timed jobs with their workloads; NULL (after ob_error) without memory. */
static timed_job *plan_jobs(const ob_job *jobs, size_t njobs, const ob_span_log *spans, size_t *n)
{
    timed_job *t = calloc(njobs ? njobs : 1, sizeof *t);
    *n = 0;
    for (size_t i = 0; t && i < njobs; i++) {
        const ob_span_log *log = &spans[i];
        if (!ob_fittime_wants(&jobs[i]) || log->n < 1 || log->oom)
            continue;
        timed_job *tj = &t[(*n)++];
        tj->i = i;
        tj->n = log->n;
        if (jobs[i].params)
            memcpy(tj->par, jobs[i].params, sizeof tj->par);
        else
            ob_param_defaults(jobs[i].method, tj->par);
        tj->sub = malloc((size_t)log->n * sizeof *tj->sub);
        tj->times = malloc((size_t)log->n * sizeof *tj->times);
        if (!tj->sub || !tj->times) {
            free_jobs(t, *n);
            t = NULL;
            break;
        }
        for (int k = 0; k < log->n; k++) {
            const ob_span *sp = &log->v[k];
            ob_bez_subsegment(&jobs[i].curve->seg[sp->seg], sp->a, sp->b, &tj->sub[k]);
            tj->times[k] = jobs[i].test_fit_repeat > 1 ? ob_test_fit_times(&jobs[i], sp->seg, sp->a, sp->b) : 1;
        }
    }
    if (!t)
        ob_error("--time-fits: out of memory");
    return t;
}


static size_t max_work_size(void)
{
    size_t w = 1;
    for (int m = 0; ob_methods[m]; m++)
        if (ob_methods[m]->work_size > w)
            w = ob_methods[m]->work_size;
    return w;
}

/* The shared state of one pass. */
typedef struct {
    const ob_fittime_opts *o;
    ob_job *jobs;
    size_t njobs;
    timed_job *t;
    size_t n;
    double *round_ns;
    int failed, stopped;
    long nbad;              /* jobs left untimed (a fit did not succeed again) */
    double start, last;
    size_t done, total;     /* measurements, for the progress line */
} pass;

/* Phase r of the pass: r < 0 the calibration, else round r; every thread
 * takes whole jobs in job order. */
static void run_phase(pass *p, int r, const scratch *s)
{
#pragma omp for schedule(dynamic, 1)
    for (long k = 0; k < (long)p->n; k++) {
        int quit, failed;
#pragma omp atomic read
        quit = p->stopped;
#pragma omp atomic read
        failed = p->failed;
        if (failed || !s->work || !s->fit)
            continue;
        if (quit || ob_stop_signal()) {
#pragma omp atomic write
            p->stopped = 1;
            continue;
        }
        timed_job *t = &p->t[k];
        if (t->bad)
            continue;
        const ob_job *j = &p->jobs[t->i];
        double per = 0;
        const int rc = r < 0 ? calibrate(j, t, s, p->o->min_ns) : measure(j, t, s, t->iters, &per);
        if (r >= 0)
            p->round_ns[(size_t)r * p->njobs + t->i] = per;
        t->bad = rc != 0;
#pragma omp critical(ob_fittime_report)
        {
            /* a fit that ran out of its time (sisl's caps) or failed now: the
             * job keeps its row, without a method time, and the run goes on */
            if (rc != 0 && p->nbad++ < 5)
                ob_warn("--time-fits: %s d=%g %s tol=%g: a fit of an accepted piece did not succeed again: "
                        "its method time is left empty", j->curve->id, j->d, j->method->name, j->tol);
            const double now = ob_mono_s();
            if (++p->done < p->total && now - p->last >= OB_PROGRESS_LOG_SECONDS) {
                p->last = now;
                ob_info("timed the fits %zu/%zu measurements, %.0f s elapsed", p->done, p->total, now - p->start);
            }
        }
    }
}

/* Each timed job's median and spread over the rounds, per iteration. */
static void summarize(pass *p)
{
    const int rounds = p->o->rounds;
    double *v = malloc((size_t)rounds * sizeof *v), *tmp = malloc((size_t)rounds * sizeof *tmp);
    for (size_t k = 0; v && tmp && k < p->n; k++) {
        ob_job *j = &p->jobs[p->t[k].i];
        if (p->t[k].bad) {
            for (int r = 0; r < rounds; r++)
                p->round_ns[(size_t)r * p->njobs + p->t[k].i] = NAN;
            continue;
        }
        for (int r = 0; r < rounds; r++)
            v[r] = tmp[r] = p->round_ns[(size_t)r * p->njobs + p->t[k].i];
        double cv;
        ob_spread(v, rounds, 1, tmp, &j->method_iqr_ns, &cv);  /* NAN for one round */
        for (int r = 0; r < rounds; r++)
            tmp[r] = v[r];
        j->method_ns = ob_median(tmp, rounds);
        j->fit_calls = p->t[k].n;
    }
    if (!v || !tmp) {
        ob_error("--time-fits: out of memory");
        p->failed = 1;
    }
    free(v);
    free(tmp);
}

int ob_fittime_run(const ob_fittime_opts *o, ob_job *jobs, size_t njobs, const ob_span_log *spans, double *round_ns,
                   double *seconds)
{
    pass p = {.o = o, .jobs = jobs, .njobs = njobs, .round_ns = round_ns, .start = ob_mono_s()};
    p.last = p.start;
    *seconds = 0;
    for (size_t i = 0; i < (size_t)o->rounds * njobs; i++)
        round_ns[i] = NAN;
    if (!(p.t = plan_jobs(jobs, njobs, spans, &p.n)))
        return -1;
    p.total = p.n * (size_t)(o->rounds + 1);
    if (p.n)
        ob_info("timing the fits of %zu jobs: %d rounds, each measurement about %g ms", p.n, o->rounds,
                o->min_ns * 1e-6);
    const size_t wsize = max_work_size();
#pragma omp parallel
    {
        scratch s = {malloc(wsize), malloc(sizeof(ob_fit))};
        if (!s.work || !s.fit) {
#pragma omp atomic write
            p.failed = 1;
        }
#pragma omp barrier
        /* every thread meets every phase's worksharing loop (its jobs are
         * skipped once the pass has failed or was stopped) */
        for (int r = -1; r < o->rounds; r++)
            run_phase(&p, r, &s);
        free(s.work);
        free(s.fit);
    }
    if (!p.failed && !p.stopped)
        summarize(&p);
    if (p.nbad > 5)
        ob_warn("--time-fits: %ld jobs left without a method time (fits that did not succeed again)", p.nbad);
    else if (!p.stopped)
        ob_error("--time-fits: the fits could not be timed");
    free_jobs(p.t, p.n);
    *seconds = ob_mono_s() - p.start;
    if (p.failed || p.stopped)
        for (size_t i = 0; i < njobs; i++)
            jobs[i].fit_calls = 0;
    return p.failed ? -1 : p.stopped ? 1 : 0;
}
