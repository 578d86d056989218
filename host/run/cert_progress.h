/*
 * cert_progress.h - the progress of run --certify's pass (certify.h):
 * "certified N/M jobs, X s elapsed, ETA Y s" (a bar on a terminal), through
 * the run's own display and estimator (progress.h), each job one work
 * group that runs on one thread.
 *
 * The cost model: a job's certificate costs about its pieces times a figure
 * per piece, and a limit job's pieces (at the depth limit, near the error
 * floor) cost several times an ok job's.  The figures are the medians per
 * piece of `run --random 20:7 --methods all --tols 1e-3 --certify` on the
 * development machine (4.3 ms per piece ok, 19.6 ms limit), in the unit the
 * estimator starts from (ms of thread time there); the pass calibrates them
 * per method and status (the group's kind) on the jobs certified so far,
 * as the run's progress calibrates ob_job_cost per method: measured cert_ns
 * against predicted.  The ETA is the list schedule of what is left on the
 * pass's threads, in the order they take the jobs (the most pieces first),
 * at the speed measured (thread time per wall time).
 */
#ifndef OB_CERT_PROGRESS_H
#define OB_CERT_PROGRESS_H

#include <stddef.h>

#include "host/run/progress.h"
#include "methods/driver/driver.h"

#define OB_CERT_MS_PER_PIECE 4.0        /* an ok job's piece */
#define OB_CERT_MS_PER_PIECE_LIMIT 20.0 /* a limit job's piece */

/* Purpose: the predicted cost of job j's certificate (ms; at least one
 *          piece's). */
double ob_cert_cost(const ob_job *j);
/* Purpose: job j's calibration slot: its method and whether it is a limit
 *          job (2 x ob_method_index + limit; -1 without a method). */
int ob_cert_kind(const ob_job *j);

typedef struct {
    ob_work_group *g;   /* the jobs, in the order the pass takes them */
    double *start;      /* when each began (s, the pass's clock) */
    size_t n, done;
    int threads;
    double done_ns, done_wall_s; /* the jobs done: their thread time, their wall time */
    ob_progress bar;    /* the display */
    double t0;          /* the pass's start (ob_mono_s) */
} ob_cert_progress;

/* Purpose: a progress of n jobs on `threads` threads, starting now.
 * Returns: 0, or -1 without memory. */
int ob_cert_progress_init(ob_cert_progress *p, size_t n, int threads);
/* Purpose: job k of the pass is j (its predicted cost and kind). */
void ob_cert_progress_set(ob_cert_progress *p, size_t k, const ob_job *j);
/* Purpose: job k began, or was done after cert_ns of thread time, at `now`
 *          (s since init: ob_cert_progress_now).  Called from one thread at
 *          a time. */
void ob_cert_progress_start(ob_cert_progress *p, size_t k, double now);
void ob_cert_progress_done(ob_cert_progress *p, size_t k, double cert_ns, double now);
/* Purpose: every job's state at `now` into out[0 .. n-1]: a running job's
 *          wall time so far, and its thread time taken as that at the
 *          speed of the jobs done (1 before any). */
void ob_cert_progress_groups(const ob_cert_progress *p, double now, ob_work_group *out);
/* Purpose: the pass's clock: s since init. */
double ob_cert_progress_now(const ob_cert_progress *p);
/* Purpose: the display told (a bar redrawn, or a log line every
 *          OB_PROGRESS_LOG_SECONDS): call after each job done. */
void ob_cert_progress_show(ob_cert_progress *p);
/* Purpose: the bar's line cleared before a message (a warning) is written
 *          on a terminal; the next show draws it again. */
void ob_cert_progress_clear(ob_cert_progress *p);
/* Purpose: the bar cleared and what p holds freed. */
void ob_cert_progress_end(ob_cert_progress *p);

#endif
