/*
 * engine_group.c - the group engine: the share group (the jobs that share
 * pieces: same curve, d, method, parameters, metric and split) is the unit
 * of work.  Threads take whole groups, largest predicted cost first
 * (ob_job_cost), and run each to completion on their own buffers: the
 * group's own levels, chunks and decisions, in the same order as the level
 * engine decides them (so the same results), with no barrier between
 * groups and no pass over all jobs.  A thread left without a group helps
 * the groups still running: their fits and measurements become tasks it
 * can take (the tail of the run).  Jobs are told finished (job_done) group
 * by group in the schedule's order, so the journal's order does not depend
 * on the threads.
 * See driver.h (the contract) and driver_int.h (the pieces).
 */
#include "methods/driver/driver_int.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* One share group: its jobs, the jobs it has finished (its predicted cost:
 * drv_run's gcost). */
typedef struct {
    size_t first, n;    /* its jobs: members[first .. first + n - 1], ascending */
    size_t ntold;       /* jobs finished, in told[first ..] in that order */
} group;

typedef struct {
    drv_run *R;
    group *g;
    const size_t *order; /* the schedule: group ids by decreasing predicted
                            cost (drv_run's gorder) */
    size_t *members;    /* job ids, group by group */
    size_t *told;       /* njobs: each group's finished jobs, in its slice */
    itemvec *plans;     /* each job's first pieces (drv_plan_all) */
    char *ran;          /* per schedule position: the group ran (or gave up) */
    ob_trace *gtr;      /* per schedule position, when tracing: the group's
                           chunks, moved into hooks.trace in schedule order */
    int next;           /* the next schedule position to take */
    int commit;         /* positions told up to here */
    int abort;          /* nonzero: take no more groups (-1 memory or the
                           test hook, 1 stopped) */
    int hook_fired;     /* the out-of-memory test hook fired: tell no more */
    int idle;           /* threads without a group: they help the rest */
} gengine;

/* The groups and their members in job order (the schedule is drv_run's).
 * 0 or -1. */
static int build_groups(gengine *G)
{
    drv_run *R = G->R;
    const size_t ng = (size_t)R->ngroups, nj = R->njobs;
    G->g = calloc(ng ? ng : 1, sizeof *G->g);
    G->order = R->gorder;
    G->members = malloc((nj ? nj : 1) * sizeof *G->members);
    G->told = malloc((nj ? nj : 1) * sizeof *G->told);
    G->ran = calloc(ng ? ng : 1, 1);
    G->gtr = R->h.trace ? calloc(ng ? ng : 1, sizeof *G->gtr) : NULL;
    if (!G->g || !G->members || !G->told || !G->ran || (R->h.trace && !G->gtr))
        return -1;
    for (size_t i = 0; i < nj; i++)
        G->g[R->grp[i]].n++;
    size_t at = 0;
    for (size_t k = 0; k < ng; k++) {
        G->g[k].first = at;
        at += G->g[k].n;
        G->g[k].n = 0;
    }
    for (size_t i = 0; i < nj; i++) {
        group *gr = &G->g[R->grp[i]];
        G->members[gr->first + gr->n++] = i;
    }
    return 0;
}

/* A job of the running group ends: kept, told when the group is committed. */
static int tell_later(void *ctx, size_t job)
{
    gengine *G = ((void **)ctx)[0];
    group *gr = ((void **)ctx)[1];
    G->told[gr->first + gr->ntold++] = job;
    return 0;
}

static int aborted(gengine *G)
{
    int a;
#pragma omp atomic read
    a = G->abort;
    return a;
}

/* Purpose: run group g to completion on this thread's buffers: its jobs'
 *          first pieces, then level after level of its own items, each
 *          level sorted as the level engine sorts it, in chunks.
 * Returns: 0, -1 (memory), 1 (stopped or the run aborted: given up). */
/* The trace of one chunk of a group: its items' fits and measurements (a
 * shared one once) as tasks, its decisions (and its level's sorting) as
 * serial time. */
static void trace_chunk(ob_trace *gt, const drv_scratch *S, long cnt, double serial_ns, int pos)
{
    const size_t first = gt->ntask;
    for (long i = 0; i < cnt; i++)
        if (S->rep[i] == i && S->fit_ns[i] + S->eval_ns[i] > 0.0)
            drv_trace_task(gt, S->fit_ns[i] + S->eval_ns[i]);
    if (drv_trace_phase(gt, first, 4, serial_ns) == 0)
        gt->phase[gt->nphase - 1].group = pos;
}

static int run_group(gengine *G, int pos, drv_scratch *S, itemvec *cur, itemvec *next, double *helped)
{
    drv_run *R = G->R;
    group *gr = &G->g[G->order[pos]];
    ob_trace *gt = G->gtr ? &G->gtr[pos] : NULL;
    cur->n = 0;
    for (size_t k = 0; k < gr->n; k++) {
        itemvec *p = &G->plans[G->members[gr->first + k]];
        for (size_t q = 0; q < p->n; q++)
            if (drv_push(cur, &p->v[q]))
                return -1;
        free(p->v);
        memset(p, 0, sizeof *p);
    }
    void *ctx[2] = {G, gr};
    while (cur->n > 0) {
        next->n = 0;
        double serial = drv_thread_ns();
        qsort(cur->v, cur->n, sizeof *cur->v, drv_item_share_cmp);
        serial = drv_thread_ns() - serial;
        long cnt;
        for (size_t start = 0; start < cur->n; start += (size_t)cnt) {
            cnt = drv_chunk_count(cur, start, R->o.chunk);
            int idle;
#pragma omp atomic read
            idle = G->idle;
            const drv_how how = idle > 0 ? DRV_TASKS : DRV_SERIAL;
            const double own = drv_thread_ns();
            const double work = drv_chunk_work(R, S, cur->v + start, cnt, how);
            if (how == DRV_TASKS)
                *helped += fmax(0.0, work - (drv_thread_ns() - own));
#pragma omp atomic
            R->st.work_ns += work;
            const double d0 = drv_thread_ns();
            if (drv_chunk_decide(R, S, cur->v + start, cnt, next, tell_later, ctx) != 0)
                return -1;
            if (gt)
                trace_chunk(gt, S, cnt, serial + drv_thread_ns() - d0, pos);
            serial = 0.0;
            drv_progress_tick(R);  /* a long group alone in the tail keeps the display moving */
            if ((R->h.stop && *R->h.stop) || aborted(G))
                return 1;
        }
        itemvec tmp = *cur;
        *cur = *next;
        *next = tmp;
    }
    return 0;
}

/* Tell the finished jobs of the group at schedule position pos. */
static void tell_group(gengine *G, int pos)
{
    const group *gr = &G->g[G->order[pos]];
    if (G->gtr) {
        drv_trace_append(G->R->h.trace, &G->gtr[pos]);
        ob_trace_free(&G->gtr[pos]);
    }
    for (size_t k = 0; k < gr->ntold && !G->hook_fired; k++)
        if (drv_job_finished(G->R, G->told[gr->first + k]) != 0) {
            G->hook_fired = 1;
#pragma omp atomic write
            G->abort = -1;
        }
}

/* The group at schedule position pos has run (rc: run_group's): its jobs
 * and those of every group after it that has run, up to the first that
 * has not, are told, in schedule order. */
static void commit(gengine *G, int pos, int rc)
{
    drv_run *R = G->R;
#pragma omp critical(drv_commit)
    {
        G->ran[pos] = 1;
        if (rc != 0 && !aborted(G)) {
#pragma omp atomic write
            G->abort = rc;
        }
        while (G->commit < R->ngroups && G->ran[G->commit])
            tell_group(G, G->commit++);
        drv_progress(R);
    }
}

/* One thread's part: groups taken in schedule order until none is left,
 * then help the others (at the region's closing barrier, where the tasks
 * of the groups still running are taken). */
static void worker(gengine *G)
{
    drv_run *R = G->R;
    drv_scratch S;
    itemvec cur = {0}, next = {0};
    if (drv_scratch_alloc(&S, R->o.chunk) != 0) {
#pragma omp atomic write
        G->abort = -1;
    }
    double helped = 0.0;
    while (!aborted(G)) {
        int pos;
#pragma omp atomic capture
        pos = G->next++;
        if (pos >= R->ngroups)
            break;
        const size_t gid = G->order[pos];
#pragma omp atomic write
        R->gstart[gid] = drv_wall_ns();
        const int rc = run_group(G, pos, &S, &cur, &next, &helped);
#pragma omp atomic write
        R->gend[gid] = drv_wall_ns();
        commit(G, pos, rc);
    }
#pragma omp atomic
    R->st.helped_ns += helped;
#pragma omp atomic
    G->idle++;
    drv_scratch_free(&S);
    free(cur.v);
    free(next.v);
}

static void gengine_free(gengine *G)
{
    for (size_t i = 0; G->plans && i < G->R->njobs; i++)
        free(G->plans[i].v);
    free(G->plans);
    free(G->g);
    free(G->members);
    free(G->told);
    free(G->ran);
    for (int k = 0; G->gtr && k < G->R->ngroups; k++)
        ob_trace_free(&G->gtr[k]);
    free(G->gtr);
}

/* Purpose: run a started run (drv_run_start) with the group engine.
 * Returns: 0, -1 (memory, or the test hook), 1 (stopped).  Jobs of groups
 *          that ran are told even when the run ends early. */
int drv_run_group(drv_run *R)
{
    gengine G;
    memset(&G, 0, sizeof G);
    G.R = R;
    R->whole_groups = 1;
    G.plans = calloc(R->njobs ? R->njobs : 1, sizeof *G.plans);
    int rc = !G.plans || build_groups(&G) ? -1 : drv_plan_all(R, G.plans);
    if (rc == 0) {
#pragma omp parallel
        worker(&G);
        rc = G.abort;
        /* a run that ended early: the groups that ran after one that did not */
        for (int pos = G.commit; pos < R->ngroups; pos++)
            if (G.ran[pos])
                tell_group(&G, pos);
        if (G.hook_fired)
            rc = -1;
    }
    gengine_free(&G);
    return rc;
}
