/*
 * progress.c - see progress.h.
 */
#include "host/run/progress.h"

#include "host/diag.h"

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
    p->total_cost = p->done_cost = 0.0;
}

void ob_progress_set_cost(ob_progress *p, double total_cost)
{
    p->total_cost = total_cost > 0 ? total_cost : 0.0;
}

void ob_progress_job_done(ob_progress *p, double cost)
{
    p->done_cost += cost;
}

/* Seconds left: from the share of the estimated cost done when there is a
 * cost model, else from the rate of jobs; < 0 when nothing is known yet. */
static double eta_s(const ob_progress *p, double elapsed, size_t done, size_t total)
{
    if (p->total_cost > 0 && p->done_cost > 0)
        return elapsed * (p->total_cost - p->done_cost) / p->done_cost;
    return done > 0 ? elapsed * (double)(total - done) / (double)done : -1.0;
}

static void fmt_eta(char *buf, size_t len, double eta)
{
    if (eta < 0)
        snprintf(buf, len, "ETA ?");
    else
        snprintf(buf, len, "ETA %.0f s", eta > 0 ? eta : 0.0);
}

void ob_progress_cb(void *ctx, size_t done, size_t total)
{
    ob_progress *p = ctx;
    if (total == 0)
        return;
    const double t = now_s(), el = t - p->t0;
    char eta[32];
    if (!p->tty) {  /* a log: one line now and then, none at the end (the run's summary says it) */
        if (t - p->last < OB_PROGRESS_LOG_SECONDS || done >= total)
            return;
        p->last = t;
        fmt_eta(eta, sizeof eta, eta_s(p, el, done, total));
        ob_info("%zu/%zu jobs (%.0f %%), %.0f s elapsed, %s", done, total, 100.0 * (double)done / (double)total, el,
                eta);
        return;
    }
    if (t - p->last < 0.1 && done < total)
        return;
    p->last = t;
    enum { W = 30 };
    char bar[W + 1];
    int fill = (int)((double)W * done / total);
    for (int i = 0; i < W; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[W] = '\0';
    fmt_eta(eta, sizeof eta, eta_s(p, el, done, total));
    /* raw, not through the funnel: a bar redrawn in place ("\r", no newline,
     * no "offbench: " prefix), drawn only on a terminal */
    fprintf(stderr, "\r[%s] %zu/%zu jobs, %.0f s, %s   ", bar, done, total, el, eta);
    fflush(stderr);
    p->drawn = 1;
}

void ob_progress_end(ob_progress *p)
{
    if (p->tty && p->drawn) {
        /* raw: blanks the bar in place before the next line */
        fprintf(stderr, "\r%*s\r", 78, "");
        fflush(stderr);
    }
    p->drawn = 0;
}
