/*
 * engine_level.c - the level engine: every pending piece of every job,
 * level by level, in chunks: the threads fit a chunk, its joints are
 * measured, one batch measures it (a batch backend's launch), then one
 * thread decides in order.  Barriers between those phases; the batch
 * backend gets records a chunk at a time.
 * See driver.h (the contract) and driver_int.h (the pieces).
 */
#include "methods/driver/driver_int.h"

#include <stdlib.h>

/* The level engine's queues and buffers. */
typedef struct {
    drv_run *R;
    itemvec cur, next;
    drv_scratch S;
} level;

/* A job ends: told at once (finished callback of drv_chunk_decide). */
static int tell_now(void *ctx, size_t job) { return drv_job_finished(((level *)ctx)->R, job); }

/* Level after level until no piece is pending.  0, -1 (memory), 1 (stop). */
static int run_levels(level *L)
{
    drv_run *R = L->R;
    ob_trace *t = R->h.trace;
    while (L->cur.n > 0) {
        L->next.n = 0;
        double serial = drv_wall_ns();
        /* the items of one share group on one piece side by side */
        qsort(L->cur.v, L->cur.n, sizeof *L->cur.v, drv_item_share_cmp);
        serial = drv_wall_ns() - serial;
        long cnt;
        for (size_t start = 0; start < L->cur.n; start += (size_t)cnt) {
            cnt = drv_chunk_count(&L->cur, start, R->o.chunk);
            const item *its = L->cur.v + start;
            R->st.work_ns += drv_chunk_work(R, &L->S, its, cnt, DRV_TEAM);
            const double t0 = drv_wall_ns();
            if (drv_chunk_decide(R, &L->S, its, cnt, &L->next, tell_now, L) != 0)
                return -1;
            drv_progress(R);
            serial += drv_wall_ns() - t0;
            if (t && t->nphase > 0)  /* the decisions (and the sorting before them): one thread */
                t->phase[t->nphase - 1].serial_ns += serial;
            serial = 0.0;
            if (R->h.stop && *R->h.stop)
                return 1;
        }
        itemvec tmp = L->cur;
        L->cur = L->next;
        L->next = tmp;
    }
    return 0;
}

/* Purpose: run a started run (drv_run_start) with the level engine: plan,
 *          then level after level.
 * Returns: 0, -1 (memory, or the test hook), 1 (stopped). */
int drv_run_level(drv_run *R)
{
    level L = {R, {0}, {0}, {0}};
    itemvec *plans = calloc(R->njobs ? R->njobs : 1, sizeof *plans);
    int rc = !plans || drv_scratch_alloc(&L.S, R->o.chunk) ? -1 : drv_plan_all(R, plans);
    for (size_t i = 0; i < R->njobs && rc == 0; i++)
        for (size_t k = 0; k < plans[i].n && rc == 0; k++)
            rc = drv_push(&L.cur, &plans[i].v[k]) ? -1 : 0;
    for (size_t i = 0; plans && i < R->njobs; i++)
        free(plans[i].v);
    free(plans);
    if (rc == 0)
        rc = run_levels(&L);
    drv_scratch_free(&L.S);
    free(L.cur.v);
    free(L.next.v);
    return rc;
}
