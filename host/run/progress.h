/*
 * progress.h - how far a run is, on stderr: jobs done, the share of the
 * work done, elapsed time and the ETA.  On a terminal a bar redrawn in
 * place; otherwise (logs, pipes, batch jobs) one line every
 * OB_PROGRESS_LOG_SECONDS, so a long run in a log is not silent and a short
 * one adds nothing.
 *
 * Progress is counted in work, not in jobs: the group engine runs share
 * groups largest first and tells their jobs finished in schedule order, so
 * the count of finished jobs lags (it reads 0 for as long as the first,
 * largest group runs: the "0 %, ETA ?" of a resume), and the jobs of a run
 * differ in cost by orders of magnitude.  The work done is the thread time
 * the driver measured so far (finished groups and the running ones' part);
 * the work to come is each unfinished group's predicted cost (ob_job_cost,
 * the model `--shard` balances with) in the run's own units: the ratio of
 * measured to predicted time of the groups finished so far, per method.
 * The ETA is a list schedule of that work on the run's threads at the
 * speed measured over the latest OB_PROGRESS_WINDOW_SECONDS: the running
 * groups where they run, then the pending ones in schedule order on the
 * earliest free thread, so the tail (a big group running alone while the
 * other threads have nothing left: the "ETA 1 s" with 65 s left) counts
 * for its length.  A group runs on one thread: the threads left without a
 * group help only with its chunks' fits and measurements, little where its
 * levels hold few pieces (meta.json's helped_seconds).
 */
#ifndef OB_PROGRESS_H
#define OB_PROGRESS_H

#include <stddef.h>

#include "methods/driver/driver.h"

enum { OB_PROGRESS_LOG_SECONDS = 10 };

/* Until groups have finished, predicted cost converts to thread time at the
 * model's own unit (ms of thread time on the development machine); the
 * groups finished take over as their cost passes this share of the run's. */
#define OB_PROGRESS_PRIOR_SHARE 0.01
/* Each method's groups are calibrated on their own (the model's figure is
 * per method, and on another machine some methods are several times off
 * where others are right); the run's unit weighs this share of the
 * method's predicted cost. */
#define OB_PROGRESS_KIND_PRIOR 0.05
/* Kinds at or past this are calibrated with the run's (not a method). */
enum { OB_PROGRESS_MAX_KINDS = 1024 };
/* The speed of work is measured over about this much of the latest wall
 * time: a machine shared with other jobs changes speed as they come and go,
 * and the ETA is of the speed now. */
enum { OB_PROGRESS_WINDOW_SECONDS = 20 };
/* A group at x times its predicted thread time is taken to need this x
 * times the time it has used again, at most as much again (measured on
 * random runs: groups past their prediction ran on to 1.3 to 1.4 times
 * where they were, those past 4 times to 2 to 3 times).  Not 0: a group
 * still running is not done, and the ETA must not say 0 s while it runs. */
#define OB_PROGRESS_OVERRUN 0.25

/* What the estimator reads (ob_progress_estimate).  The speed it assumes
 * is the window's where there is one: thread time per wall time of the
 * groups' threads (whole_groups) or of the run (not). */
typedef struct {
    const ob_work_group *g; /* the run's share groups in schedule order */
    size_t n;
    int threads;            /* >= 1 */
    int whole_groups;       /* as ob_progress_info.whole_groups: 1, the list
                               schedule of groups on threads; 0, the work
                               left at the run's rate of work */
    double elapsed_s;       /* the run's wall time so far */
    /* the work measured over the latest wall time, the groups' wall time
     * and the run's elapsed time in that window (ob_progress keeps them);
     * all 0: the speed over the whole run, from g and elapsed_s */
    double win_work_ns, win_wall_ns, win_s;
} ob_progress_in;

/* The estimator's answer. */
typedef struct {
    double done_ns;     /* work done: thread time measured so far */
    double left_ns;     /* work to come: predicted thread time */
    double fraction;    /* done / (done + left); 0 before any work */
    double eta_s;       /* wall seconds left; < 0: not known (no rate yet) */
} ob_progress_est;

/* Purpose: how far a run is and how long it has left, from its share
 *          groups: a pure function (the same inputs, the same answer), so
 *          it is tested on synthetic runs, not timed ones.
 * Inputs:  in (see ob_progress_in).
 * Outputs: *e; eta_s < 0 while no rate of work is known (nothing measured).
 * Returns: 0, or -1 without memory (then e->eta_s < 0). */
int ob_progress_estimate(const ob_progress_in *in, ob_progress_est *e);

/* Purpose: the progress line's text, without the bar: "D/T jobs (P %),
 *          work W %, E s elapsed, ETA X s" (a log line, tty = 0) or "D/T
 *          jobs, work W %, E s, ETA X s" (the bar's, tty = 1); "ETA ?"
 *          while e->eta_s < 0.
 * Outputs: buf (len bytes, cut if short). */
void ob_progress_format(char *buf, size_t len, size_t done, size_t total, const ob_progress_est *e, double elapsed_s,
                        int tty);

/* Purpose: a pass's line (ob_progress.what set: run --certify's), without
 *          the bar: "WHAT D/T jobs, E s elapsed, ETA X s" (a log line) or
 *          "WHAT D/T jobs, E s, ETA X s" (the bar's); "ETA ?" while
 *          e->eta_s < 0.
 * Outputs: buf (len bytes, cut if short). */
void ob_progress_format_pass(char *buf, size_t len, const char *what, size_t done, size_t total,
                             const ob_progress_est *e, double elapsed_s, int tty);

typedef struct {
    const char *what;   /* NULL: the run's line; else a pass's, named so
                           (ob_progress_format_pass; set after init) */
    int tty;            /* stderr is a terminal */
    int drawn;          /* something is on the line */
    int width;          /* columns drawn */
    double t0, last;    /* start, last redraw or line (s) */
    double shown;       /* the work done as last shown (it never goes back) */
    ob_progress_est est; /* the latest estimate, refreshed once a second */
    double est_at;      /* its time (s since t0) */
    int estimated;      /* est is set */
    ob_work_group *buf; /* the groups, read when redrawing */
    size_t cap;
    /* the latest samples of (elapsed, work, the groups' wall time), one a
     * second at most, oldest first: the window's speed */
    struct { double t, work_ns, wall_ns; } samp[OB_PROGRESS_WINDOW_SECONDS + 4];
    int nsamp;
} ob_progress;

/* Purpose: a progress display starting now (the run's elapsed time counts
 *          from here).  Free it with ob_progress_end. */
void ob_progress_init(ob_progress *p);
/* Purpose: the driver's progress callback (ctx: an ob_progress*): redraws
 *          the bar at most ten times a second, or writes a log line every
 *          OB_PROGRESS_LOG_SECONDS; estimates once a second (the groups are
 *          read under the engine's lock), the ETA counting down between. */
void ob_progress_cb(void *ctx, const ob_progress_info *pi);
/* Purpose: clear the bar's line and free what the display holds. */
void ob_progress_end(ob_progress *p);

#endif
