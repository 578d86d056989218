/*
 * run.c - what every engine shares: a run's state from start to end, the
 * work of one chunk of items (fit, joints, measure) and its decisions, and
 * a job's end.  An engine decides only when and where a chunk runs; what
 * becomes of each piece is decided here and in rules.c, in the order of the
 * chunk's items, the same for every engine.
 * See driver.h (the contract) and driver_int.h (the pieces).
 */
#include "methods/driver/driver_int.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Every job's outputs cleared, its bookkeeping started. */
static void init_jobs(drv_run *R)
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

/* Each share group's predicted cost (its costliest job's: the others share
 * its pieces), the schedule by that cost, its jobs, its work so far (none).
 * 0, or -1 (memory). */
static int groups_start(drv_run *R)
{
    const size_t ng = (size_t)R->ngroups ? (size_t)R->ngroups : 1;
    R->gcost = calloc(ng, sizeof *R->gcost);
    R->gorder = malloc(ng * sizeof *R->gorder);
    R->gspent = calloc(ng, sizeof *R->gspent);
    R->gleft = calloc(ng, sizeof *R->gleft);
    R->gstart = calloc(ng, sizeof *R->gstart);
    R->gend = calloc(ng, sizeof *R->gend);
    R->gkind = calloc(ng, sizeof *R->gkind);
    if (!R->gcost || !R->gorder || !R->gspent || !R->gleft || !R->gstart || !R->gend || !R->gkind)
        return -1;
    for (size_t i = 0; i < R->njobs; i++) {
        const int g = R->grp[i];
        R->gcost[g] = fmax(R->gcost[g], ob_job_cost(&R->jobs[i]));
        R->gkind[g] = ob_method_index(R->jobs[i].method);  /* one method per group */
        R->gleft[g]++;
    }
    return ob_cost_order(R->gcost, (size_t)R->ngroups, R->gorder);
}

/* Purpose: start a run: options (NULL: defaults), hooks (NULL: none), each
 *          job's bookkeeping and share group, the work areas.
 * Returns: 0, or -1 when memory ran out (drv_run_end still applies). */
int drv_run_start(drv_run *R, ob_job *jobs, size_t njobs, const ob_driver_opts *opts, const ob_driver_hooks *hooks)
{
    memset(R, 0, sizeof *R);
    R->st.wall_ns = -drv_wall_ns();
    R->jobs = jobs;
    R->njobs = njobs;
    if (opts)
        R->o = *opts;
    else
        ob_driver_defaults(&R->o);
    if (hooks)
        R->h = *hooks;
    if (R->o.chunk < 1)
        R->o.chunk = R->h.batch && R->h.batch_chunk > 0 ? R->h.batch_chunk : OB_CPU_CHUNK;
    R->st.chunk = R->o.chunk;
    R->st.threads = omp_get_max_threads();
    R->js = calloc(njobs ? njobs : 1, sizeof *R->js);
    R->wsize = 1;
    for (size_t i = 0; i < njobs; i++)
        if (jobs[i].method->work_size > R->wsize)
            R->wsize = jobs[i].method->work_size;
    R->work = malloc(R->wsize * (size_t)R->st.threads);
    R->grp = drv_share_groups(jobs, njobs);
    if (!R->js || !R->work || !R->grp)
        return -1;
    for (size_t i = 0; i < njobs; i++)
        if (R->grp[i] + 1 > R->ngroups)
            R->ngroups = R->grp[i] + 1;
    R->st.groups = R->ngroups;
    init_jobs(R);
    return groups_start(R);
}

/* Purpose: the first pieces of every job (in parallel), plans[i] for job i
 *          (njobs entries, zeroed by the caller); jobs skipped before any
 *          work finish here, in job order.
 * Returns: 0, or -1 (memory). */
int drv_plan_all(drv_run *R, itemvec *plans)
{
    double *ns = R->h.trace ? calloc(R->njobs ? R->njobs : 1, sizeof *ns) : NULL;
    int fail = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(| : fail)
    for (long i = 0; i < (long)R->njobs; i++) {
        const double c0 = drv_thread_ns();
        if (drv_check_applicable(&R->jobs[i], &R->js[i]))
            fail |= drv_plan_job(&R->jobs[i], (int)i, R->grp[i], &R->o, &plans[i]) != 0;
        if (ns)
            ns[i] = drv_thread_ns() - c0;
    }
    if (R->h.trace) {
        const size_t first = R->h.trace->ntask;
        for (size_t i = 0; ns && i < R->njobs; i++)
            drv_trace_task(R->h.trace, ns[i]);
        drv_trace_phase(R->h.trace, first, 16, 0.0);
        if (!ns)
            R->h.trace->oom = 1;
    }
    free(ns);
    for (size_t i = 0; i < R->njobs && !fail; i++) {
        if (plans[i].n == 0) {  /* skipped before any work (the hook cannot fire: nothing ran) */
            R->gleft[R->grp[i]]--;
            drv_job_finished(R, i);
        }
        R->js[i].pending = (long)plans[i].n;
    }
    return fail ? -1 : 0;
}

/* Purpose: job i is done: its outputs final, the caller told (job_done).
 * Returns: 0, or -1 when the out-of-memory test hook fires. */
int drv_job_finished(drv_run *R, size_t i)
{
    R->js[i].finished = 1;
    R->done++;
    drv_finalize(&R->jobs[i], &R->js[i]);
    if (R->h.job_done)
        R->h.job_done(R->h.job_done_ctx, i);
    return R->o.test_oom_after > 0 && R->done >= (size_t)R->o.test_oom_after ? -1 : 0;
}

/* Purpose: end a run, whatever happened: jobs not finished when it ended
 *          early (rc != 0) fail with the reason ("interrupted" for rc > 0,
 *          "out of memory" for rc < 0); every job's outputs final, its
 *          spans in curve order; the engine's figures to hooks.stats; the
 *          run's memory freed. */
void drv_run_end(drv_run *R, int rc)
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
    R->st.wall_ns += drv_wall_ns();
    if (R->h.trace)
        R->h.trace->work_ns = R->st.work_ns;
    if (R->h.stats)
        *R->h.stats = R->st;
    free(R->js);
    free(R->work);
    free(R->grp);
    R->js = NULL;
    R->work = NULL;
    R->grp = NULL;
    free(R->gcost);
    free(R->gorder);
    free(R->gspent);
    free(R->gleft);
    free(R->gstart);
    free(R->gend);
    free(R->gkind);
    R->gkind = NULL;
    R->gcost = R->gspent = R->gstart = R->gend = NULL;
    R->gorder = NULL;
    R->gleft = NULL;
}

int drv_scratch_alloc(drv_scratch *S, int chunk)
{
    const size_t nc = (size_t)chunk;
    memset(S, 0, sizeof *S);
    S->chunk = chunk;
    S->fits = malloc(nc * sizeof *S->fits);
    S->res = malloc(nc * sizeof *S->res);
    S->fit_ns = malloc(nc * sizeof *S->fit_ns);
    S->eval_ns = malloc(nc * sizeof *S->eval_ns);
    S->stop = malloc(nc * sizeof *S->stop);
    S->fj = malloc(nc * sizeof *S->fj);
    S->rep = malloc(nc * sizeof *S->rep);
    const int bad = drv_batch_alloc(&S->B, chunk);
    return !bad && S->fits && S->res && S->fit_ns && S->eval_ns && S->stop && S->fj && S->rep ? 0 : -1;
}

void drv_scratch_free(drv_scratch *S)
{
    free(S->fits);
    free(S->res);
    free(S->fit_ns);
    free(S->eval_ns);
    free(S->stop);
    free(S->fj);
    free(S->rep);
    drv_batch_free(&S->B);
    memset(S, 0, sizeof *S);
}

/* What fit_one reads. */
typedef struct {
    drv_run *R;
    drv_scratch *S;
    const item *its;
} fit_ctx;

/* Fit item i of a chunk, unless it takes another's fit or its job is dead. */
static void fit_one(const void *ctx, long i)
{
    const fit_ctx *c = ctx;
    drv_run *R = c->R;
    drv_scratch *S = c->S;
    const item *it = &c->its[i];
    void *w = R->work + R->wsize * (size_t)omp_get_thread_num();
    if (it->chain_to > it->depth) {  /* its fit asked for a smaller piece (the probe) */
        memset(&S->res[i], 0, sizeof S->res[i]);
        S->res[i].st = OB_FIT_RETRY_SMALLER;
        S->res[i].err = INFINITY;
        S->fit_ns[i] = 0.0;
        return;
    }
    if (R->js[it->job].dead || S->rep[i] != i) {
        S->res[i].st = OB_FIT_SKIP;  /* dead, or takes its representative's fit below */
        S->fit_ns[i] = 0.0;
        return;
    }
    /* what the job has left of --job-timeout (ob_fit_args.budget_ns; 0: none) */
    const ob_job *j = &R->jobs[it->job];
    const double budget = R->o.job_timeout_ns > 0 ? fmax(1.0, R->o.job_timeout_ns - j->fit_ns - j->eval_ns) : 0.0;
    S->fit_ns[i] = drv_fit_item(R->jobs, it, budget, w, &S->fits[i], &S->res[i]);
    S->fit_ns[i] += drv_probe_retry_chain(R->jobs, it, R->o.max_depth, budget > 0 ? fmax(1.0, budget - S->fit_ns[i]) : 0.0,
                                          w, &S->fits[i], &S->res[i]);
}

/* The level engine's trace of one chunk: its fits, then its measurements on
 * the CPU (a batch backend's launch is serial time). */
static void trace_chunk(ob_trace *t, const drv_scratch *S, long cnt)
{
    size_t first = t->ntask;
    for (long i = 0; i < cnt; i++)
        drv_trace_task(t, S->fit_ns[i]);
    drv_trace_phase(t, first, 4, 0.0);
    first = t->ntask;
    const int n = S->B.first[cnt];
    for (int r = 0; r < n; r++)
        if (!(S->B.backend_n > 0 && ob_metric_batched(S->B.rec[r].metric)))
            drv_trace_task(t, S->B.ns[r]);
    drv_trace_phase(t, first, 4, S->B.backend_wall);
}

/* Purpose: the work of one chunk of items (adjacent per share group and
 *          piece, drv_item_share_cmp): each piece fitted once per share
 *          group, its joints, its measurement; the results in S, one entry
 *          per item (the items that take another's fit hold its results).
 * Inputs:  how: how the loops run (drv_how); with DRV_TEAM (the level
 *          engine) the chunk's task times go to hooks.trace.
 * Returns: the thread time of the fits and measurements run (a shared piece
 *          once). */
double drv_chunk_work(drv_run *R, drv_scratch *S, const item *its, long cnt, drv_how how)
{
    drv_chunk_fit(R, S, its, cnt, how);
    drv_measure_chunk(R->jobs, its, cnt, S->fits, S->stop, S->res, S->eval_ns, R->o.samples, &R->h, &S->B, how);
    if (how == DRV_TEAM && R->h.trace)
        trace_chunk(R->h.trace, S, cnt);
    return drv_chunk_account(R, S, cnt);
}

/* Purpose: the first half of a chunk's work: each piece fitted once per
 *          share group (S->rep), its joints, each measurement's stop. */
void drv_chunk_fit(drv_run *R, drv_scratch *S, const item *its, long cnt, drv_how how)
{
    drv_chunk_reps(its, cnt, R->js, S->rep);
    const fit_ctx fc = {R, S, its};
    drv_for(how, cnt, 2, 4, fit_one, &fc);
    drv_joints_chunk(R->js, its, cnt, S->fits, S->res, S->fj, how);  /* the ends and inner joints (joints.h) */
    drv_chunk_stops(R->jobs, its, cnt, S->rep, R->o.full_probes, S->stop);
}

/* Purpose: the last step of a chunk's work, once it is measured: the
 *          batch backend's figures counted, the shared results copied to
 *          the items that take them.
 * Returns: the thread time of the fits and measurements run (a shared
 *          piece once). */
double drv_chunk_account(drv_run *R, drv_scratch *S, long cnt)
{
    double work = 0.0;
    for (long i = 0; i < cnt; i++)
        if (S->rep[i] == i)
            work += S->fit_ns[i] + S->eval_ns[i];
    if (S->B.backend_n > 0) {
#pragma omp atomic
        R->st.launches++;
#pragma omp atomic
        R->st.records += S->B.backend_n;
    }
    drv_copy_shared(cnt, S->rep, S->res, S->fj, S->fit_ns, S->eval_ns);
    return work;
}

/* A job past its --job-timeout ends with status timeout. */
static void check_timeout(drv_run *R, int job)
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

/* Purpose: the decisions on one worked chunk (drv_chunk_work), in the order
 *          of its items: each job charged its items' costs, each item
 *          accepted, split or narrowed (children to next), each job that
 *          ends told through finished(ctx, job), once.
 * Returns: 0, or -1 (memory, or finished's own -1). */
int drv_chunk_decide(drv_run *R, drv_scratch *S, const item *its, long cnt, itemvec *next,
                     int (*finished)(void *ctx, size_t job), void *ctx)
{
    for (long i = 0; i < cnt; i++) {
        const int job = its[i].job;
        R->jobs[job].fit_ns += S->fit_ns[i];
        R->jobs[job].eval_ns += S->eval_ns[i];
        if (S->rep[i] == i) {  /* the group's work: a shared piece once, as work_ns */
#pragma omp atomic
            R->gspent[its[i].grp] += S->fit_ns[i] + S->eval_ns[i];
        }
        if (drv_decide(R->jobs, R->js, &its[i], &S->res[i], &S->fj[i], &R->o, next))
            return -1;
        check_timeout(R, job);
        jstate *s = &R->js[job];
        if (!s->told && (s->pending == 0 || s->dead)) {
            s->told = 1;
#pragma omp atomic
            R->gleft[its[i].grp]--;
            if (finished(ctx, (size_t)job) != 0)
                return -1;
        }
    }
    return 0;
}

/* The groups' state, in schedule order (ob_progress_info.groups). */
static void read_groups(const ob_progress_info *pi, ob_work_group *out)
{
    const drv_run *R = pi->run;
    const double now = drv_wall_ns();
    for (size_t k = 0; k < pi->ngroups; k++) {
        const size_t g = R->gorder[k];
        double spent, start, end;
        int left;
#pragma omp atomic read
        spent = R->gspent[g];
#pragma omp atomic read
        left = R->gleft[g];
#pragma omp atomic read
        start = R->gstart[g];
#pragma omp atomic read
        end = R->gend[g];
        out[k].cost = R->gcost[g];
        out[k].spent_ns = spent;
        out[k].wall_ns = start > 0.0 ? (end > 0.0 ? end : now) - start : 0.0;
        out[k].kind = R->gkind[g];
        out[k].state = left <= 0 ? OB_WORK_DONE : start > 0.0 || spent > 0.0 ? OB_WORK_RUNNING : OB_WORK_PENDING;
    }
}

/* Purpose: tell hooks.progress (if any) the jobs finished and the work so
 *          far.  The caller makes it one thread at a time (drv_progress_tick
 *          and the group engine's commit hold the engine's lock). */
void drv_progress(drv_run *R)
{
    if (!R->h.progress)
        return;
    const ob_progress_info pi = {R->done, R->njobs, R->st.threads, R->whole_groups, (size_t)R->ngroups, read_groups,
                                 R};
#pragma omp atomic write
    R->last_tick = drv_wall_ns();
    R->h.progress(R->h.progress_ctx, &pi);
}

/* Purpose: drv_progress from any thread, at most OB_PROGRESS_TICK_MS apart:
 *          the group engine's threads call it after every chunk, so a long
 *          group (the tail) keeps the display moving between finished groups. */
void drv_progress_tick(drv_run *R)
{
    if (!R->h.progress)
        return;
    const double now = drv_wall_ns();
    double last;
#pragma omp atomic read
    last = R->last_tick;
    if (now - last < OB_PROGRESS_TICK_MS * 1e6)
        return;
#pragma omp critical(drv_commit)
    {
#pragma omp atomic read
        last = R->last_tick;
        if (now - last >= OB_PROGRESS_TICK_MS * 1e6)
            drv_progress(R);
    }
}
