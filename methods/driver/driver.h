/*
 * driver.h - adaptive subdivision shared by all methods.
 *
 * A job is (curve, d, method, metric, split, tol).  The driver first cuts each
 * base segment into pieces at inflections (and, for methods with max_turn, where
 * the tangent has turned by max_turn), then works level by level over the
 * pending pieces: fit every piece, measure every fit (in batches: the place
 * where the OpenCL kernel plugs in), then split the pieces whose error
 * exceeds tol.  Jobs that differ only in tol share pieces (a share group);
 * a group decides in its own fixed order, and an engine (ob_engine) only
 * decides when and where its work runs: all levels of all groups at once
 * (level, device) or one group at a time per thread (group).
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
 * job used more than the run's --job-timeout, or a fit passed a wall-clock
 * cap of its own (OB_FIT_TIMEOUT: sisl.wall_timeout).  Set by the driver only. */
typedef enum { OB_OK = 0, OB_LIMIT, OB_FAIL, OB_SKIP, OB_TIMEOUT } ob_status;
const char *ob_status_name(ob_status s);

typedef struct {
    /* inputs */
    const ob_curve *curve;
    double d;
    const ob_method *method;
    const double *params;  /* method parameter values, NULL for the defaults */
    double test_fit_repeat;/* test hook (0, 1: off): each fit is done this many
                              times on average (same input, the last result
                              kept), a real slowdown of the method for the
                              timing tests: ob_driver_opts.test_slow_method;
                              a fraction: ob_test_fit_times */
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
                            calls (CLOCK_THREAD_CPUTIME_ID) and what they had
                            spent in other processes (sisl's server), summed */
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
    /* set by the run command with --certify (host/run/certify.h), not the driver: */
    int cert_done;       /* OB_CERT_DONE: the certificate below was taken;
                            OB_CERT_TIMEOUT: it passed --job-timeout, no
                            verdict (only cert_ns: err_upper and err_lower
                            NAN, empty columns); OB_CERT_NONE: empty columns */
    double err_upper;    /* certified: the job's two-sided Hausdorff distance to the
                            exact offset is <= err_upper (+inf: a piece unbounded) */
    double err_lower;    /* ... and >= err_lower (a distance attained) */
    double cert_ns;      /* thread CPU time of the certificate */
    /* set by the run command with --time-fits (host/run/fittime.h), not the driver: */
    int fit_calls;       /* fits in one iteration of the job's workload (its
                            accepted pieces); 0: not timed (empty columns) */
    double method_ns;    /* the method's own time: thread CPU time of one fit of
                            each accepted piece, median over the rounds */
    double method_iqr_ns;/* the rounds' interquartile range (NAN: one round) */
    /* set by the run command with --trimmed (host/run/trimmed.h), not the driver: */
    int trimmed_done;    /* 1: trimmed_err and trimmed_cut were measured; 0: empty columns */
    double trimmed_err;  /* the approximation, trimmed by its own crossings, against
                            the exact trimmed offset: two-sided distance of the sets */
    int trimmed_cut;     /* arcs the trimming removed from the approximation */
} ob_job;

/* The test hook's count for one fit of base piece (seg, a, b) of job j
 * (ob_job.test_fit_repeat = f): floor(f) times, and once more for a share
 * f - floor(f) of the pieces, chosen by a hash of (seg, a, b), so that the
 * same piece is always done as often (any engine, thread count or pass)
 * and a method's many pieces take f times as long on average. */
int ob_test_fit_times(const ob_job *j, int seg, double a, double b);

/* ob_job.cert_done: no certificate, one, one stopped by --job-timeout. */
enum { OB_CERT_NONE = 0, OB_CERT_DONE = 1, OB_CERT_TIMEOUT = 2 };

/* Whether job j's certificate holds it within tol (results.csv's certified
 * = yes): certified, and err_upper <= tol.  The one place the rule is. */
static inline int ob_job_certified(const ob_job *j) { return j->cert_done == OB_CERT_DONE && j->err_upper <= j->tol; }

/* One measurement of a batch: an approximating piece against its base piece. */
typedef struct {
    const ob_bez *base;
    const ob_bez *approx;
    double d;
    ob_metric metric;   /* radial, normal or hausdorff (bound is always on the CPU) */
    double stop;        /* > 0: only whether the error exceeds stop matters where
                           it does (ob_measure_until); 0: the full measurement */
    ob_cert_src src;    /* where base was cut from (src.seg NULL: unknown): what
                           the certified metric encloses (ob_measure_src) */
} ob_measure_rec;

/* A backend that measures a whole batch at once (the OpenCL kernel): fills
 * out[0..n-1] exactly as ob_measure_until would (each record's stop).
 * Returns 0, or -1 if it could not, and then the driver measures that batch
 * on the CPU instead. */
typedef int (*ob_batch_fn)(void *ctx, const ob_measure_rec *recs, int n, int samples, ob_errval *out);

/* The same, asynchronous, for the device engine: submit starts measuring a
 * batch in slot 0 or 1 and returns at once (the records are copied); wait
 * finishes that slot's batch into out, with the device's own time for it
 * in *device_ns (0: unknown).  Each returns 0, or -1 and then the driver
 * measures that batch on the CPU. */
typedef int (*ob_batch_submit_fn)(void *ctx, int slot, const ob_measure_rec *recs, int n, int samples);
typedef int (*ob_batch_wait_fn)(void *ctx, int slot, ob_errval *out, double *device_ns);

/* One accepted piece of a job: base parameters [a, b] of base segment seg,
 * and the error the run measured for its fit (the largest of its pieces',
 * by the run's metric): what orders the certificate's work (host/run/
 * certify.c), read nowhere else. */
typedef struct {
    int seg;
    double a, b;
    double err;
} ob_span;

/* The accepted pieces of one job, in curve order (seg, then a) when the run
 * ends.  Free v with free(). */
typedef struct {
    ob_span *v;
    int n, cap;
    int oom;            /* a span could not be stored: the log is incomplete */
} ob_span_log;

/* How the work is scheduled (README "Engines"); no engine changes a result.
 *   level  every pending piece of every job, level by level, in chunks: the
 *          threads fit a chunk, one batch measures it, one thread decides
 *          (barriers between); a batch backend gets the chunk's records;
 *   group  the share groups (jobs that differ only in tol and share pieces)
 *          are the unit of work: threads take whole groups, largest
 *          predicted cost first, and run each to completion with no barrier
 *          between groups; threads left without a group help the groups
 *          still running (their fits and measurements as tasks);
 *   device the level engine's chunks in two cohorts of share groups, for an
 *          asynchronous batch backend (a GPU): the threads fit one cohort's
 *          chunk while the device measures the other's (double buffering);
 *   auto   group on the CPU; with a batch backend, device where the backend
 *          runs beside the CPU's threads (batch_overlap: a GPU), else level
 *          (a CPU device such as PoCL: overlapping only oversubscribes). */
typedef enum {
    OB_ENGINE_AUTO = 0, OB_ENGINE_LEVEL, OB_ENGINE_GROUP, OB_ENGINE_DEVICE, OB_ENGINE_COUNT
} ob_engine;
const char *ob_engine_name(ob_engine e);
int ob_engine_parse(const char *name, ob_engine *e);

/* What an engine did (ob_driver_hooks.stats): the figures of its
 * efficiency, (work_ns) / (threads x wall_ns). */
typedef struct {
    ob_engine engine;   /* the engine that ran (never auto) */
    int threads;        /* OpenMP threads it had */
    double wall_ns;     /* ob_driver_run's wall time */
    double work_ns;     /* thread time of the fits and measurements it ran,
                           a piece shared by several jobs counted once */
    double helped_ns;   /* group: of work_ns, what threads ran for a group
                           that another thread held (the tail) */
    long groups;        /* share groups */
    long launches;      /* batch backend calls */
    long records;       /* records the batch backend measured */
    double device_ns;   /* device: the kernels' own time (profiling events) */
    double blocked_ns;  /* device: the time the threads waited for the device
                           (device_ns - blocked_ns of it was hidden behind fits) */
    int chunk;          /* pieces per batch it used (ob_driver_opts.chunk) */
} ob_engine_stats;

/* A trace of a run's task times, to model other thread counts
 * (ob_trace_makespan): a sequence of phases, each some serial time then
 * tasks that threads take in order, grain at a time, as OpenMP's dynamic
 * schedule does.  The level engine's phases are each chunk's fits and its
 * measurements (the decisions and sorting serial).  The group engine's are
 * the planning, then each group's chunks in schedule order (group >= 0: a
 * chunk's items are its tasks, its decisions its serial time), modelled as
 * the engine runs them: a thread takes the next group and runs its chunks
 * one after the other; threads left without a group help with the tasks of
 * the chunks of the groups still running. */
typedef struct {
    size_t first, n;    /* tasks task[first .. first + n - 1] */
    int grain;
    double serial_ns;   /* before the tasks, on one thread */
    int group;          /* -1: a phase of all threads; >= 0: a chunk of the
                           group at that schedule position */
} ob_trace_phase;

typedef struct {
    double *task;
    size_t ntask, captask;
    ob_trace_phase *phase;
    size_t nphase, capphase;
    double work_ns;     /* as ob_engine_stats.work_ns */
    int oom;            /* a task or phase could not be stored */
} ob_trace;

/* Purpose: the modelled wall time of a traced run on `threads` threads: a
 *          list schedule of each phase's tasks (the earliest free thread
 *          takes the next grain), phases one after the other.
 * Returns: ns; 0 for an empty trace. */
double ob_trace_makespan(const ob_trace *t, int threads);

/* Purpose: list scheduling's step (the makespan model above, and the
 *          progress line's ETA, host/run/progress.c): h[0..n-1] a binary
 *          min-heap of the threads' free times, earliest at h[0]; restores
 *          the heap below position i after h[i] grew. */
void ob_sched_heap_down(double *h, size_t n, size_t i);
void ob_trace_free(ob_trace *t);

/* The group engine calls hooks.progress at most this often while groups
 * run (besides once per finished group): a display redraws about as often. */
enum { OB_PROGRESS_TICK_MS = 100 };

/* Pieces per batch without a batch backend that asks for more: the level
 * engine's chunk of all groups' pieces, the group engine's of one group's. */
enum { OB_CPU_CHUNK = 512 };

/* How the driver works: settings that decide results (samples, limits) and
 * the run's budgets.  A plain value: a run configuration holds one. */
typedef struct {
    int samples;        /* per segment, for the sampled metrics */
    int max_depth;      /* pieces are not split below 2^-max_depth */
    int max_segments;   /* per job */
    int inflections;    /* 1: split at inflections first (forced for OB_CAP_CONVEX) */
    int chunk;          /* pieces per fit/measure batch (bounds memory); 0:
                           the batch backend's batch_chunk, else OB_CPU_CHUNK */
    ob_engine engine;   /* how the work is scheduled (no result depends on it) */
    /* 1: measure every probe of the greedy and optimal searches in full.  By
     * default a probe whose error exceeds its level is measured only until a
     * sample shows that (ob_measure_until): the results are the same, bit for
     * bit, only the measuring time (eval_ns) differs; tests and bench set it
     * to show both */
    int full_probes;
    /* > 0: a job whose thread time (fit_ns + eval_ns) passes this ends with
     * status timeout.  A job's own clock is the thread time spent on it,
     * not the run's wall time (its work is interleaved with others'); a
     * single fit that never returns is not interrupted (SISL has its own
     * deadline).  Timeouts depend on the machine: a run where any job times
     * out is not reproducible across thread counts or machines. */
    double job_timeout_ns;
    /* test hook (0: off): after this many jobs have finished the driver
     * returns -1 as if memory had run out; set by `run` from the environment
     * variable OFFBENCH_TEST_OOM_AFTER (README "Testing"), read once before
     * any work, checked between jobs, never inside a timed section */
    long test_oom_after;
    /* test hook (NULL: off): the jobs of this method do each fit
     * test_slow_factor times on average (ob_job.test_fit_repeat), so that the method
     * is that much slower in its fits and in nothing else; set by `run` from
     * OFFBENCH_TEST_SLOW=METHOD:FACTOR (README "Testing"), recorded in
     * meta.json ("test_slow") */
    const ob_method *test_slow_method;
    double test_slow_factor;
} ob_driver_opts;

/* One share group's work as a progress display sees it (ob_progress_info):
 * the unit the group engine schedules, so the unit a truthful progress
 * counts in (jobs are told finished group by group in schedule order: a
 * count of finished jobs lags the work by as much as the largest group). */
typedef enum { OB_WORK_PENDING = 0, OB_WORK_RUNNING, OB_WORK_DONE } ob_work_state;
typedef struct {
    double cost;        /* predicted: ob_job_cost of its costliest job (ms;
                           the others share its pieces) */
    double spent_ns;    /* thread time of its fits and measurements so far
                           (a shared piece once, as ob_engine_stats.work_ns) */
    double wall_ns;     /* the group engine: wall time since a thread took
                           it (to its end once done); 0 with the others */
    ob_work_state state;
    int kind;           /* its method (ob_method_index; -1: none): the cost
                           model's figure is per method, and so are its
                           errors on another machine */
} ob_work_group;

/* What a progress callback is told (ob_driver_hooks.progress): the jobs
 * finished, and the run's share groups, read on demand. */
typedef struct ob_progress_info {
    size_t done, total;     /* jobs finished (told through job_done), jobs */
    int threads;            /* the run's OpenMP threads */
    int whole_groups;       /* 1: a thread runs a group to its end (the group
                               engine); 0: every thread works on every
                               group's pieces (the level and device engines) */
    size_t ngroups;         /* share groups */
    /* copies every group's state to out[0 .. ngroups - 1] in schedule order
     * (largest predicted cost first, ob_cost_order): O(ngroups), so a
     * display calls it only when it redraws; valid only inside the callback */
    void (*groups)(const struct ob_progress_info *pi, ob_work_group *out);
    const void *run;        /* the driver's, for groups */
} ob_progress_info;

/* What the caller plugs into one driver run: where the measurements go and
 * what it is told as the run goes.  Every member may be NULL (zeroed: none);
 * none of them changes a result. */
typedef struct {
    ob_batch_fn batch;  /* NULL: measure on the CPU with OpenMP */
    void *batch_ctx;
    ob_batch_submit_fn batch_submit; /* both or neither: the device engine */
    ob_batch_wait_fn batch_wait;
    int batch_overlap;  /* 1: the backend runs beside the CPU's threads (a
                           GPU): engine auto takes the device engine */
    int batch_chunk;    /* > 0: the pieces per batch the backend wants
                           (a GPU: tens of thousands of records per launch),
                           used when ob_driver_opts.chunk is 0 */
    long *batch_fallbacks; /* if not NULL: counts batches the backend gave back */
    /* if not NULL: called after every batch (the level and device engines)
     * or every finished group and, while groups run, at most
     * OB_PROGRESS_TICK_MS apart (the group engine: a long group alone in
     * the tail is not silent), with the jobs finished and the work so far;
     * from one thread at a time (the calling thread with the level engine;
     * under the engine's lock with the group engine) */
    void (*progress)(void *ctx, const ob_progress_info *pi);
    void *progress_ctx;
    /* if not NULL: njobs logs, zeroed by the caller; spans[i] receives the
     * accepted pieces of job i (draw and trace refit them to show the
     * approximation: fits are deterministic) */
    ob_span_log *spans;
    /* if not NULL: called as soon as job i is finished, its outputs final
     * (rows can be saved as jobs finish), from one thread at a time like
     * progress.  The order is stable for any thread count: the level
     * engine's decisions' order; the group engine's groups in its schedule
     * order (a group's jobs told once all groups before it are), each
     * group's jobs in the order they finished */
    void (*job_done)(void *ctx, size_t i);
    void *job_done_ctx;
    /* if not NULL: read between batches; once nonzero (a signal handler sets
     * it) the driver stops, and jobs not finished get status fail with the
     * message "interrupted" (job_done is not called for them) */
    const volatile sig_atomic_t *stop;
    ob_engine_stats *stats; /* if not NULL: what the engine did */
    ob_trace *trace;        /* if not NULL (zeroed by the caller): the task
                               times, for ob_trace_makespan */
} ob_driver_hooks;

/* Purpose: the estimated cost of a job, in milliseconds of thread time on the
 *          development machine: the method's median per job in the nightly
 *          baseline, scaled by the base curve's size (sum over its segments
 *          of degree + 1, relative to one cubic) and by tol^(-1/4) relative
 *          to 1e-3 (a fourth-order method's segment count).  An estimate for
 *          balancing only: --shard's partition, the group engine's
 *          schedule, the progress bar. */
double ob_job_cost(const ob_job *j);

/* Purpose: order[0..n-1]: the indices 0..n-1 by decreasing cost[], ties by
 *          increasing index (the same order every run: the longest first,
 *          as a list schedule wants).
 * Returns: 0, or -1 without memory. */
int ob_cost_order(const double *cost, size_t n, size_t *order);

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
