/*
 * trace.c - task traces of a driver run and the schedule model that turns
 * one into the wall time of another thread count (driver.h, ob_trace).
 * The model is a list schedule: OpenMP's dynamic schedule hands the next
 * `grain` tasks to whichever thread is free first, and that is what is
 * simulated, phase after phase; a phase's serial time runs on one thread
 * while the others wait.  What it leaves out: memory bandwidth, the cost of
 * taking a task, and threads that help a group in the group engine's tail
 * (so the group engine's figure is a lower bound).
 */
#include "methods/driver/driver_int.h"

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
    t->phase[t->nphase++] = (ob_trace_phase){first, t->ntask - first, grain > 0 ? grain : 1, serial_ns};
    return 0;
}

/* A binary heap of the threads' free times: the earliest at the top. */
static void heap_down(double *h, int n, int i)
{
    for (;;) {
        int l = 2 * i + 1, m = i;
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
        heap_down(heap, threads, 0);
    }
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
    for (size_t p = 0; p < t->nphase; p++)
        total += t->phase[p].serial_ns + phase_span(t, &t->phase[p], threads, heap);
    free(heap);
    return total;
}

void ob_trace_free(ob_trace *t)
{
    free(t->task);
    free(t->phase);
    memset(t, 0, sizeof *t);
}
