/*
 * progress.h - how far a run is, on stderr: jobs done, elapsed time and the
 * ETA.  On a terminal a bar redrawn in place; otherwise (logs, pipes, batch
 * jobs) one line every OB_PROGRESS_LOG_SECONDS, so a long run in a log is not
 * silent and a short one adds nothing.
 *
 * The ETA comes from the cost model `--shard` balances with (shard.h) when the
 * run gives it the jobs' estimated costs (the share of the estimated work
 * done so far, not of the jobs: a run's jobs differ in cost by orders of
 * magnitude); otherwise from the rate of jobs so far.
 */
#ifndef OB_PROGRESS_H
#define OB_PROGRESS_H

#include <stddef.h>

enum { OB_PROGRESS_LOG_SECONDS = 10 };

typedef struct {
    int tty;            /* stderr is a terminal */
    int drawn;          /* something is on the line */
    double t0, last;    /* start, last redraw or line (s) */
    double total_cost;  /* the jobs' estimated cost (ms, shard.h); 0: unknown */
    double done_cost;   /* of the jobs finished */
} ob_progress;

void ob_progress_init(ob_progress *p);
/* Purpose: the estimated cost of all the run's jobs (ob_job_cost summed):
 *          the ETA follows the cost model from now on. */
void ob_progress_set_cost(ob_progress *p, double total_cost);
/* Purpose: one job of estimated cost `cost` has finished. */
void ob_progress_job_done(ob_progress *p, double cost);
/* The driver's progress callback (ctx: an ob_progress*); redraws at most
 * ten times a second. */
void ob_progress_cb(void *ctx, size_t done, size_t total);
/* Clears the bar's line. */
void ob_progress_end(ob_progress *p);

#endif
