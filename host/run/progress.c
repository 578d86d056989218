/*
 * progress.c - see progress.h.
 */
#include "host/run/progress.h"

#include <stdio.h>
#include <time.h>
#include <unistd.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void ob_progress_init(ob_progress *p)
{
    p->tty = isatty(2);
    p->drawn = 0;
    p->t0 = p->last = now_s();
}

void ob_progress_cb(void *ctx, size_t done, size_t total)
{
    ob_progress *p = ctx;
    if (!p->tty || total == 0)
        return;
    double t = now_s();
    if (t - p->last < 0.1 && done < total)
        return;
    p->last = t;
    enum { W = 30 };
    char bar[W + 1];
    int fill = (int)((double)W * done / total);
    for (int i = 0; i < W; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[W] = '\0';
    double el = t - p->t0, rate = el > 0 ? done / el : 0.0;
    double eta = rate > 0 ? (total - done) / rate : 0.0;
    fprintf(stderr, "\r[%s] %zu/%zu jobs, %.1f jobs/s, ETA %.0f s   ", bar, done, total, rate, eta);
    fflush(stderr);
    p->drawn = 1;
}

void ob_progress_end(ob_progress *p)
{
    if (p->tty && p->drawn) {
        fprintf(stderr, "\r%*s\r", 78, "");
        fflush(stderr);
    }
    p->drawn = 0;
}
