/*
 * trace.c - task traces of a driver run and the schedule model that turns
 * one into the wall time of another thread count (driver.h, ob_trace).
 * The model is a list schedule: OpenMP's dynamic schedule hands the next
 * `grain` tasks to whichever thread is free first, and that is what is
 * simulated, phase after phase; a phase's serial time runs on one thread
 * while the others wait.  The group engine's chunks are simulated as it
 * runs them (group_span).  What it leaves out: memory bandwidth, the cost
 * of taking a task, and, for the group engine, that a helper helps only
 * the chunks that start after it became idle (the model lets it take any
 * chunk's tasks: slightly optimistic there).
 */
#include "methods/driver/driver_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int drv_trace_task(ob_trace *t, double ns)
{
    if (t->oom || ob_grow(&t->task, &t->captask, t->ntask, sizeof *t->task, 1024)) {
        t->oom = 1;
        return -1;
    }
    t->task[t->ntask++] = ns;
    return 0;
}

/* The phase of tasks first .. ntask - 1, after serial_ns on one thread. */
int drv_trace_phase(ob_trace *t, size_t first, int grain, double serial_ns)
{
    if (t->oom || ob_grow(&t->phase, &t->capphase, t->nphase, sizeof *t->phase, 64)) {
        t->oom = 1;
        return -1;
    }
    t->phase[t->nphase++] = (ob_trace_phase){first, t->ntask - first, grain > 0 ? grain : 1, serial_ns, -1};
    return 0;
}

/* Purpose: append the phases and tasks of part (a group's chunks, traced
 *          by the thread that ran it) to t, keeping their group.
 * Returns: 0, or -1 (memory: t->oom). */
int drv_trace_append(ob_trace *t, const ob_trace *part)
{
    for (size_t p = 0; p < part->nphase; p++) {
        const ob_trace_phase *ph = &part->phase[p];
        const size_t first = t->ntask;
        for (size_t k = 0; k < ph->n; k++)
            if (drv_trace_task(t, part->task[ph->first + k]))
                return -1;
        if (drv_trace_phase(t, first, ph->grain, ph->serial_ns))
            return -1;
        t->phase[t->nphase - 1].group = ph->group;
    }
    t->oom |= part->oom;
    return t->oom ? -1 : 0;
}

void ob_sched_heap_down(double *h, size_t n, size_t i)
{
    for (;;) {
        size_t l = 2 * i + 1, m = i;
        if (l < n && h[l] < h[m])
            m = l;
        if (l + 1 < n && h[l + 1] < h[m])
            m = l + 1;
        if (m == i)
            return;
        const double x = h[i];
        h[i] = h[m];
        h[m] = x;
        i = m;
    }
}

/* One phase on `threads` threads that all start at 0: its makespan. */
static double phase_span(const ob_trace *t, const ob_trace_phase *ph, int threads, double *heap)
{
    memset(heap, 0, (size_t)threads * sizeof *heap);
    double span = 0.0;
    for (size_t k = 0; k < ph->n; k += (size_t)ph->grain) {
        double block = 0.0;
        for (size_t q = k; q < ph->n && q < k + (size_t)ph->grain; q++)
            block += t->task[ph->first + q];
        heap[0] += block;  /* the earliest free thread takes the block */
        if (heap[0] > span)
            span = heap[0];
        ob_sched_heap_down(heap, (size_t)threads, 0);
    }
    return span;
}

/* The group engine's groups, phases [from, to) of t (chunks of groups in
 * schedule order), on `threads` threads: an event simulation.  A thread
 * takes the next group and runs its chunks in order: a chunk's serial time
 * on the owner, then its tasks (grain at a time) by the owner and by any
 * helper; the next chunk starts when the last of its tasks has ended.  A
 * thread that finds no group left helps.  Returns the makespan. */
typedef struct {
    size_t ph, last;     /* the current chunk (phase index) and the group's last */
    size_t next;         /* its next task not yet taken */
    double avail, end;   /* its tasks can be taken from avail; the last taken ends at end */
    int live;
} gstate;

static size_t group_end(const ob_trace *t, size_t p, size_t to)
{
    size_t q = p;
    while (q < to && t->phase[q].group == t->phase[p].group)
        q++;
    return q;
}

/* Take a block of the current chunk of g at time now; returns its end. */
static double take(const ob_trace *t, gstate *g, double now)
{
    const ob_trace_phase *ph = &t->phase[g->ph];
    double block = 0.0;
    for (int q = 0; q < ph->grain && g->next < ph->n; q++)
        block += t->task[ph->first + g->next++];
    const double e = fmax(now, g->avail) + block;
    g->end = fmax(g->end, e);
    return e;
}

static double group_span(const ob_trace *t, size_t from, size_t to, int threads)
{
    gstate *gs = calloc((size_t)threads, sizeof *gs);   /* the group each thread owns */
    double *free_at = calloc((size_t)threads, sizeof *free_at);
    int *helper = calloc((size_t)threads, sizeof *helper);
    if (!gs || !free_at || !helper) {
        free(gs), free(free_at), free(helper);
        return 0.0;
    }
    size_t next_phase = from;
    double span = 0.0;
    int active = threads;
    while (active > 0) {
        int p = -1;  /* the thread free first (threads are few: a scan) */
        for (int k = 0; k < threads; k++)
            if (free_at[k] >= 0 && (p < 0 || free_at[k] < free_at[p]))
                p = k;
        double now = free_at[p];
        gstate *g = &gs[p];
        if (!helper[p]) {
            if (g->live && g->next < t->phase[g->ph].n) {
                free_at[p] = take(t, g, now);
                continue;
            }
            if (g->live && g->ph < g->last) {  /* the chunk is taken: the next, once it has ended */
                now = fmax(now, g->end);
                g->ph++;
                g->next = 0;
                g->avail = g->end = now + t->phase[g->ph].serial_ns;
                free_at[p] = g->avail;
                continue;
            }
            if (g->live) {
                now = fmax(now, g->end);
                g->live = 0;
            }
            if (next_phase < to) {  /* the next group in the schedule */
                const size_t e = group_end(t, next_phase, to);
                *g = (gstate){next_phase, e - 1, 0, 0.0, 0.0, 1};
                g->avail = g->end = now + t->phase[next_phase].serial_ns;
                next_phase = e;
                free_at[p] = g->avail;
                continue;
            }
            helper[p] = 1;
        }
        /* a helper: the task of a running group that can be taken first */
        int best = -1;
        double soonest = INFINITY;
        int running = 0;
        for (int k = 0; k < threads; k++) {
            if (helper[k] || !gs[k].live)
                continue;
            running = 1;
            if (gs[k].next < t->phase[gs[k].ph].n && gs[k].avail < soonest) {
                soonest = gs[k].avail;
                best = k;
            }
        }
        span = fmax(span, now);
        if (!running) {  /* nothing left to help: this thread is done */
            free_at[p] = -1.0;
            active--;
            continue;
        }
        if (best >= 0 && soonest <= now) {
            free_at[p] = take(t, &gs[best], now);
            continue;
        }
        /* wait for the next event: a chunk's tasks, or another thread */
        double wake = best >= 0 ? soonest : INFINITY;
        for (int k = 0; k < threads; k++)
            if (k != p && free_at[k] > now && free_at[k] < wake)
                wake = free_at[k];
        free_at[p] = isfinite(wake) ? wake : now + 1.0;
    }
    for (int k = 0; k < threads; k++)
        span = fmax(span, gs[k].end);
    free(gs), free(free_at), free(helper);
    return span;
}

double ob_trace_makespan(const ob_trace *t, int threads)
{
    if (threads < 1)
        threads = 1;
    double *heap = malloc((size_t)threads * sizeof *heap);
    if (!heap)
        return 0.0;
    double total = 0.0;
    for (size_t p = 0; p < t->nphase;) {
        if (t->phase[p].group >= 0) {  /* the group engine's groups, all of them */
            size_t q = p;
            while (q < t->nphase && t->phase[q].group >= 0)
                q++;
            total += group_span(t, p, q, threads);
            p = q;
            continue;
        }
        total += t->phase[p].serial_ns + phase_span(t, &t->phase[p], threads, heap);
        p++;
    }
    free(heap);
    return total;
}

void ob_trace_free(ob_trace *t)
{
    free(t->task);
    free(t->phase);
    memset(t, 0, sizeof *t);
}
