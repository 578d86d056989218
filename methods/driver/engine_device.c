/*
 * engine_device.c - the device engine: the level engine's chunks, in two
 * cohorts of share groups, for an asynchronous batch backend (a GPU).
 * While the device measures one cohort's chunk, all threads fit the other
 * cohort's next chunk (double buffering); the next batch is queued on the
 * device before the host waits for the one in flight, so the device does
 * not idle between them.  Each cohort goes level by level through its own
 * groups, sorted and decided exactly as the level engine does (a job's
 * items, and so its decisions, are the same whatever else runs), so the
 * rows are the same.  The measuring time of a record is its share of its
 * kernel's own time (profiling events), not of a wall time the overlap
 * makes meaningless.
 * See driver.h (the contract) and driver_int.h (the pieces).
 */
#include "methods/driver/driver_int.h"

#include <stdlib.h>
#include <string.h>

/* One cohort: its queues, the chunk it has prepared, its buffers. */
typedef struct {
    itemvec cur, next;
    size_t start;       /* the prepared chunk's first item in cur */
    long cnt;           /* the prepared chunk's items; 0: none (done) */
    int sorted;         /* cur is sorted (drv_item_share_cmp) */
    int in_flight;      /* its sampled records are on the device */
    double submitted;   /* wall time of the submission */
    drv_scratch S;
} cohort;

typedef struct {
    drv_run *R;
    cohort c[2];
} dengine;

static int tell_now(void *ctx, size_t job) { return drv_job_finished(((dengine *)ctx)->R, job); }

/* The cohort's next chunk, the next level's first when this level is done:
 * 1, or 0 when the cohort has no piece left. */
static int next_chunk(drv_run *R, cohort *k)
{
    if (k->sorted && k->start >= k->cur.n) {
        itemvec tmp = k->cur;
        k->cur = k->next;
        k->next = tmp;
        k->next.n = 0;
        k->start = 0;
        k->sorted = 0;
    }
    if (k->cur.n == 0)
        return 0;
    if (!k->sorted) {
        /* the items of one share group on one piece side by side */
        qsort(k->cur.v, k->cur.n, sizeof *k->cur.v, drv_item_share_cmp);
        k->sorted = 1;
    }
    k->cnt = drv_chunk_count(&k->cur, k->start, R->o.chunk);
    return 1;
}

/* Fit the cohort's chunk and make its records (all threads). */
static void prepare(drv_run *R, cohort *k)
{
    const item *its = k->cur.v + k->start;
    drv_chunk_fit(R, &k->S, its, k->cnt, DRV_TEAM);
    drv_measure_prepare(R->jobs, its, k->cnt, k->S.fits, k->S.stop, k->S.res, R->o.samples, &R->h, &k->S.B,
                        DRV_TEAM);
}

/* Its sampled records to the device, in the cohort's own slot. */
static void submit(drv_run *R, cohort *k, int slot)
{
    k->in_flight = 0;
    if (k->S.B.nsampled == 0)
        return;
    k->submitted = drv_wall_ns();
    k->in_flight = R->h.batch_submit(R->h.batch_ctx, slot, k->S.B.srec, k->S.B.nsampled, R->o.samples) == 0;
    if (!k->in_flight && R->h.batch_fallbacks)
        (*R->h.batch_fallbacks)++;
}

/* Wait for the cohort's batch, measure the rest on the CPU, decide.
 * 0, or -1 (memory, or the test hook). */
static int complete(dengine *D, cohort *k, int slot)
{
    drv_run *R = D->R;
    int ok = 0;
    if (k->in_flight) {
        double dev = 0.0;
        const double t0 = drv_wall_ns();
        ok = R->h.batch_wait(R->h.batch_ctx, slot, k->S.B.sout, &dev) == 0;
        const double t1 = drv_wall_ns();
        R->st.blocked_ns += t1 - t0;
        R->st.device_ns += dev;
        if (ok)
            drv_measure_backend_done(&k->S.B, dev > 0.0 ? dev : t1 - k->submitted);
        else if (R->h.batch_fallbacks)
            (*R->h.batch_fallbacks)++;
        k->in_flight = 0;
    }
    const item *its = k->cur.v + k->start;
    drv_measure_finish(R->jobs, its, k->cnt, k->S.fits, k->S.stop, k->S.res, k->S.eval_ns, R->o.samples, &k->S.B,
                       ok, DRV_TEAM);
    R->st.work_ns += drv_chunk_account(R, &k->S, k->cnt);
    if (drv_chunk_decide(R, &k->S, its, k->cnt, &k->next, tell_now, D) != 0)
        return -1;
    drv_progress(R);
    k->start += (size_t)k->cnt;
    k->cnt = 0;
    return 0;
}

/* Two cohorts in turn: queue one's batch, wait for the other's, decide
 * it, fit its next chunk while the device measures.  0, -1, 1 (stop). */
static int pipeline(dengine *D)
{
    drv_run *R = D->R;
    cohort *c = D->c;
    if (next_chunk(R, &c[0])) {
        prepare(R, &c[0]);
        submit(R, &c[0], 0);
    }
    if (next_chunk(R, &c[1]))
        prepare(R, &c[1]);
    for (int a = 0; c[0].cnt > 0 || c[1].cnt > 0; a = 1 - a) {
        const int b = 1 - a;
        if (c[b].cnt > 0 && !c[b].in_flight)
            submit(R, &c[b], b);  /* queued behind a's: the device does not wait for the host */
        if (c[a].cnt == 0)
            continue;
        if (complete(D, &c[a], a) != 0)
            return -1;
        if (R->h.stop && *R->h.stop)
            return 1;
        if (next_chunk(R, &c[a]))
            prepare(R, &c[a]);  /* while the device measures b's */
    }
    return 0;
}

/* Purpose: run a started run (drv_run_start) with the device engine: the
 *          share groups split into two cohorts (group id parity), each
 *          job's first pieces queued in its cohort in job order.
 * Returns: 0, -1 (memory, or the test hook), 1 (stopped). */
int drv_run_device(drv_run *R)
{
    dengine D;
    memset(&D, 0, sizeof D);
    D.R = R;
    itemvec *plans = calloc(R->njobs ? R->njobs : 1, sizeof *plans);
    int rc = !plans || drv_scratch_alloc(&D.c[0].S, R->o.chunk) || drv_scratch_alloc(&D.c[1].S, R->o.chunk)
                 ? -1
                 : drv_plan_all(R, plans);
    for (size_t i = 0; i < R->njobs && rc == 0; i++)
        for (size_t k = 0; k < plans[i].n && rc == 0; k++)
            rc = drv_push(&D.c[R->grp[i] % 2].cur, &plans[i].v[k]) ? -1 : 0;
    for (size_t i = 0; plans && i < R->njobs; i++)
        free(plans[i].v);
    free(plans);
    if (rc == 0)
        rc = pipeline(&D);
    for (int k = 0; k < 2; k++) {
        if (D.c[k].in_flight) {  /* stopped early: nothing may still write the buffers */
            ob_errval *sink = D.c[k].S.B.sout;
            double dev;
            R->h.batch_wait(R->h.batch_ctx, k, sink, &dev);
        }
        drv_scratch_free(&D.c[k].S);
        free(D.c[k].cur.v);
        free(D.c[k].next.v);
    }
    return rc;
}
