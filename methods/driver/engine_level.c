/*
 * engine_level.c - the level engine: every pending piece of every job, level
 * by level, in chunks (fit, joints and measure in parallel, then decide in
 * order).
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
    double *stop;       /* each measuring item's stop (drv_chunk_stops) */
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
    R->grp = drv_share_groups(R->jobs, R->njobs);
    const int bad = drv_batch_alloc(&R->B, R->o.chunk);
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
    drv_batch_free(&R->B);
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
    drv_finalize(&R->jobs[i], &R->js[i]);
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
        if (!drv_check_applicable(&R->jobs[i], &R->js[i]))
            continue;
        fail |= drv_plan_job(&R->jobs[i], (int)i, R->grp[i], &R->o, &plans[i]) != 0;
    }
    for (size_t i = 0; i < R->njobs && !fail; i++) {
        if (plans[i].n == 0)  /* skipped before any work (the hook cannot fire: nothing ran) */
            job_finished(R, i);
        for (size_t k = 0; k < plans[i].n && !fail; k++)
            fail = drv_push(&R->cur, &plans[i].v[k]) != 0;
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
        R->fit_ns[i] = drv_fit_item(R->jobs, &its[i], w, &R->fits[i], &R->res[i]);
        R->fit_ns[i] += drv_probe_retry_chain(R->jobs, &its[i], R->o.max_depth, w, &R->fits[i], &R->res[i]);
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
        drv_job_end(j, s, OB_TIMEOUT, msg);
    }
}

/* One chunk of a level: fit, joints, measure, then decide in job order.
 * 0, or -1 (memory, or the test hook). */
static int run_chunk(drun *R, const item *its, long cnt)
{
    drv_chunk_reps(its, cnt, R->js, R->rep);
    fit_chunk(R, its, cnt);
    drv_joints_chunk(R->js, its, cnt, R->fits, R->res, R->fj);  /* the ends and inner joints (joints.h) */
    drv_chunk_stops(R->jobs, its, cnt, R->rep, R->o.full_probes, R->stop);
    drv_measure_chunk(R->jobs, its, cnt, R->fits, R->stop, R->res, R->eval_ns, R->o.samples, &R->h, &R->B);
    drv_copy_shared(cnt, R->rep, R->res, R->fj, R->fit_ns, R->eval_ns);
    for (long i = 0; i < cnt; i++) {
        const int job = its[i].job;
        R->jobs[job].fit_ns += R->fit_ns[i];
        R->jobs[job].eval_ns += R->eval_ns[i];
        if (drv_decide(R->jobs, R->js, &its[i], &R->res[i], &R->fj[i], &R->o, &R->next))
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
        qsort(R->cur.v, R->cur.n, sizeof *R->cur.v, drv_item_share_cmp);
        long cnt;
        for (size_t start = 0; start < R->cur.n; start += (size_t)cnt) {
            cnt = drv_chunk_count(&R->cur, start, R->o.chunk);
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
            drv_finalize(j, &R->js[i]);
        } else {
            j->ctrl_points = 0;
            j->segments = j->out_degree = 0;
            j->max_err = NAN;
            j->max_gap = j->max_kink = NAN;
            j->continuity = OB_CONT_NONE;
            j->joints = j->open_joints = 0;
        }
        if (R->h.spans && R->h.spans[i].n > 1)
            qsort(R->h.spans[i].v, (size_t)R->h.spans[i].n, sizeof *R->h.spans[i].v, drv_span_cmp);
    }
}

int drv_run_level(ob_job *jobs, size_t njobs, const ob_driver_opts *opts, const ob_driver_hooks *hooks)
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
