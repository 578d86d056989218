/*
 * driver.h - adaptive subdivision shared by all methods.
 *
 * A job is (curve, d, method, metric, split, tol).  The driver first cuts each
 * base segment into pieces at inflections (and, for methods with max_turn, where
 * the tangent has turned by max_turn), then works level by level over all
 * pending pieces of all jobs at once: fit every piece (OpenMP threads), measure
 * every fit (one batch: the place where the OpenCL kernel plugs in), then split
 * the pieces whose error exceeds tol.
 *
 * Split rules:
 *   mid     at the parametric midpoint;
 *   maxerr  at the parameter of the largest error (Liu-Wang, Step 5), kept
 *           within [5 %, 95 %] of the piece so no sliver is made;
 *   greedy  the longest prefix that passes, by bisection on its end parameter
 *           (to 1e-4 of the stretch still to cover), then the rest likewise: the
 *           fewest segments the method can reach;
 *   optimal the fewest pieces whose errors all meet tol at a common error
 *           level: greedy at tol gives the count n of each initial piece
 *           (between the inflections, and the offset's cusps for methods
 *           that ask), then greedy passes at a level bisected geometrically
 *           (to 2 %, at most 12 passes) find the lowest level that n pieces
 *           reach, and a last greedy pass at that level is accepted: at
 *           most greedy's count (fewer where a method's error does not grow
 *           with the prefix), the errors equalized (max_err at most
 *           greedy's), at about ten times greedy's fits.
 * A piece narrower than 2^-max_depth, or a job past max_segments, or a piece
 * whose error stops falling under subdivision (below 90 % of its parent's over
 * 4 successive splits: an error floor of the method), is accepted as it is and
 * the job ends with status `limit` (its max_err then exceeds tol); after an
 * error floor the job's other pending pieces are kept as they are (the job
 * cannot reach tol); greedy ends likewise when not even a sliver passes.
 * A method that still asks for a smaller piece (OB_FIT_RETRY_SMALLER) 12
 * halvings below the initial piece ends the job with status fail.  With a job
 * timeout (job_timeout_ns), a job that has used more thread time than that
 * ends with status timeout.
 *
 * Counting: k segments of degrees m_i joined end to end count 1 + sum m_i
 * control points (shared end points once), as the papers count, plus one for
 * every joint whose ends are apart (joints.h: farther than 1e-12 of the
 * curve's size): there the end points are not shared.  A fit with its own
 * representation (ob_fit.ctrl_points > 0, e.g. a B-spline) counts that, and
 * the joints between fits are counted the same way.
 *
 * Joints: after the fits, the driver measures every joint of a job (between
 * the pieces of a fit, between consecutive accepted fits in curve order, and
 * across base segments where the base is G1; joints.h): the largest gap and
 * kink and the continuity reached.  Per accepted fit it keeps only its two
 * ends (point and tangent direction) until the job is finalized.
 */
#ifndef OB_DRIVER_H
#define OB_DRIVER_H

#include <signal.h>
#include <stddef.h>

#include "methods/driver/joints.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"

typedef enum { OB_SPLIT_MID = 0, OB_SPLIT_MAXERR, OB_SPLIT_GREEDY, OB_SPLIT_OPTIMAL, OB_SPLIT_COUNT } ob_split;
const char *ob_split_name(ob_split s);
int ob_split_parse(const char *name, ob_split *s);

/* What a job ends with: results.csv's `status` column, by name
 * (ob_status_name: "ok", "limit", "fail", "skip", "timeout").  OB_LIMIT: a
 * limit was reached and what was accepted is kept (max_err may exceed tol);
 * OB_FAIL / OB_SKIP: a fit failed or did not apply (the method's
 * OB_FIT_FAIL / OB_FIT_SKIP), or the driver could not go on; OB_TIMEOUT: the
 * job used more than the run's --job-timeout.  Set by the driver only. */
typedef enum { OB_OK = 0, OB_LIMIT, OB_FAIL, OB_SKIP, OB_TIMEOUT } ob_status;
const char *ob_status_name(ob_status s);

typedef struct {
    /* inputs */
    const ob_curve *curve;
    double d;
    const ob_method *method;
    const double *params;  /* method parameter values, NULL for the defaults */
    ob_metric metric;
    ob_split split;
    double tol;
    /* outputs */
    ob_status status;
    long ctrl_points;
    int segments;
    int out_degree;      /* largest degree among the output segments */
    double max_err;      /* largest measured error over the accepted segments */
    double fit_ns;       /* CPU time of the calling thread in the method's fit
                            calls (CLOCK_THREAD_CPUTIME_ID), summed */
    double eval_ns;      /* measuring: on the CPU, the thread CPU time of each
                            measurement, summed; with a batch backend (one
                            launch measures many records), the launch's wall
                            time shared among its records by the work each
                            took (ob_errval.work), summed */
    char message[160];
    /* joints (joints.h), for jobs that produced an approximation: */
    double max_gap;      /* largest gap at a measured joint; NAN: none measured */
    double max_kink;     /* largest angle (rad) between end tangents there; NAN: none */
    ob_cont continuity;  /* measured: open, G0, G1; OB_CONT_NONE without joints */
    int joints;          /* joints measured */
    int open_joints;     /* joints counted twice in ctrl_points (measured open,
                            or not measured with their ends apart) */
    /* set by the run command with --reps N (host/run/spread.h), not the driver: */
    int time_reps;       /* repetitions the spread is over; < 2: none (empty columns) */
    double time_iqr_ns;  /* IQR of the per-repetition fit_ns + eval_ns */
    double time_cv;      /* their coefficient of variation, sd / mean */
} ob_job;

/* One measurement of a batch: an approximating piece against its base piece. */
typedef struct {
    const ob_bez *base;
    const ob_bez *approx;
    double d;
    ob_metric metric;   /* radial, normal or hausdorff (bound is always on the CPU) */
    double stop;        /* > 0: only whether the error exceeds stop matters where
                           it does (ob_measure_until); 0: the full measurement */
} ob_measure_rec;

/* A backend that measures a whole batch at once (the OpenCL kernel): fills
 * out[0..n-1] exactly as ob_measure_until would (each record's stop).
 * Returns 0, or -1 if it could not, and then the driver measures that batch
 * on the CPU instead. */
typedef int (*ob_batch_fn)(void *ctx, const ob_measure_rec *recs, int n, int samples, ob_errval *out);

/* One accepted piece of a job: base parameters [a, b] of base segment seg. */
typedef struct {
    int seg;
    double a, b;
} ob_span;

/* The accepted pieces of one job, in curve order (seg, then a) when the run
 * ends.  Free v with free(). */
typedef struct {
    ob_span *v;
    int n, cap;
    int oom;            /* a span could not be stored: the log is incomplete */
} ob_span_log;

/* How the driver works: settings that decide results (samples, limits) and
 * the run's budgets.  A plain value: a run configuration holds one. */
typedef struct {
    int samples;        /* per segment, for the sampled metrics */
    int max_depth;      /* pieces are not split below 2^-max_depth */
    int max_segments;   /* per job */
    int inflections;    /* 1: split at inflections first (forced for OB_CAP_CONVEX) */
    int chunk;          /* pieces per fit/measure batch (bounds memory) */
    /* 1: measure every probe of the greedy and optimal searches in full.  By
     * default a probe whose error exceeds its level is measured only until a
     * sample shows that (ob_measure_until): the results are the same, bit for
     * bit, only the measuring time (eval_ns) differs; tests and bench set it
     * to show both */
    int full_probes;
    /* > 0: a job whose thread time (fit_ns + eval_ns) passes this ends with
     * status timeout.  The driver works level by level over all jobs, so a
     * job's own clock is the time spent on it, not the run's wall time; a
     * single fit that never returns is not interrupted (SISL has its own
     * deadline).  Timeouts depend on the machine: a run where any job times
     * out is not reproducible across thread counts or machines. */
    double job_timeout_ns;
    /* test hook (0: off): after this many jobs have finished the driver
     * returns -1 as if memory had run out; set by `run` from the environment
     * variable OFFBENCH_TEST_OOM_AFTER (README "Testing"), read once before
     * any work, checked between jobs, never inside a timed section */
    long test_oom_after;
} ob_driver_opts;

/* What the caller plugs into one driver run: where the measurements go and
 * what it is told as the run goes.  Every member may be NULL (zeroed: none);
 * none of them changes a result. */
typedef struct {
    ob_batch_fn batch;  /* NULL: measure on the CPU with OpenMP */
    void *batch_ctx;
    long *batch_fallbacks; /* if not NULL: counts batches the backend gave back */
    /* if not NULL: called from the calling thread after every batch with the
     * number of finished jobs */
    void (*progress)(void *ctx, size_t done, size_t total);
    void *progress_ctx;
    /* if not NULL: njobs logs, zeroed by the caller; spans[i] receives the
     * accepted pieces of job i (draw and trace refit them to show the
     * approximation: fits are deterministic) */
    ob_span_log *spans;
    /* if not NULL: called from the calling thread as soon as job i is
     * finished, its outputs final (rows can be saved as jobs finish) */
    void (*job_done)(void *ctx, size_t i);
    void *job_done_ctx;
    /* if not NULL: read between batches; once nonzero (a signal handler sets
     * it) the driver stops, and jobs not finished get status fail with the
     * message "interrupted" (job_done is not called for them) */
    const volatile sig_atomic_t *stop;
} ob_driver_hooks;

void ob_driver_defaults(ob_driver_opts *o);

/* Purpose: run every job to completion, filling its outputs.
 * Inputs:  jobs with their input fields set; opts (NULL for defaults);
 *          hooks (NULL: none: the CPU measures, nothing is told).
 * Returns: 0; -1 if memory ran out (jobs not finished get status fail and
 *          the message "out of memory"); 1 if stopped through hooks->stop.  Per-job problems never fail the run:
 *          they end that job with status fail / skip / limit and a message.
 * Deterministic: outputs other than the timings do not depend on the number of
 * threads.  Timings: see ob_job's fit_ns and eval_ns. */
int ob_driver_run(ob_job *jobs, size_t njobs, const ob_driver_opts *opts, const ob_driver_hooks *hooks);

#endif
