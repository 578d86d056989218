/*
 * fittime.h - `run --time-fits`: each method's own time, measured as a
 * microbenchmark (issue 46, docs/output.md "The method's own time").
 *
 * What a user of a benchmark asks of "speed per method" is how long the
 * method takes to fit, not how long offbench takes to measure the fit: in
 * the default job the sampled metric is 90-99 % of fit_ns + eval_ns for most
 * methods, so a method twice as slow moved that sum by a few percent.  The
 * driver's fit_ns is one pass of short calls (a microsecond each for the
 * fastest methods), timed call by call, interleaved with the metric.
 *
 * So after the driver, every job with an approximation (status ok or limit)
 * has the pieces it accepted (its span log, as --export and --certify use)
 * fitted again, as Google Benchmark and pytest-benchmark time a function:
 *   - the workload: one fit of each accepted piece of the job, the base
 *     piece cut out beforehand (outside the clock), the method's parameters
 *     and the job's d and tol; the same every round and every run of a
 *     build (fits are deterministic);
 *   - warm-up and calibration, outside the measurements: the workload is run
 *     with 1, 10, 100, ... iterations until one run lasts at least a tenth of
 *     the minimum time, then the iteration count is scaled so that one
 *     measurement lasts about min_ns (at least 1 iteration);
 *   - rounds: `rounds` sweeps over all timed jobs, each sweep measuring every
 *     job once (so a burst of load touches every method in that sweep alike,
 *     and a sweep's per-method totals are comparable repetitions); one
 *     measurement is the calling thread's CPU time
 *     (CLOCK_THREAD_CPUTIME_ID) of the job's calibrated iterations, divided
 *     by the iterations;
 *   - the job's method_ns is the median over the rounds, method_iqr_ns their
 *     interquartile range; fits.csv holds every round.
 * A method that fits in another process (sisl's server) reports the CPU
 * time spent there (ob_fit_foreign_add, methods/method.h): it is counted.
 * Results (every other column) do not change: the fits' outputs are thrown
 * away.  The test hook OFFBENCH_TEST_SLOW (ob_job.test_fit_repeat) repeats
 * each fit here as in the driver, so a method made slower on purpose is
 * slower in this measurement by the same factor.
 */
#ifndef OB_FITTIME_H
#define OB_FITTIME_H

#include <stddef.h>

#include "methods/driver/driver.h"

/* --fit-reps and --fit-min-time: the defaults (docs/output.md). */
enum { OB_FITTIME_ROUNDS = 5 };
#define OB_FITTIME_MIN_NS 1e6

typedef struct {
    int rounds;         /* measurements per job (>= 1) */
    double min_ns;      /* each measurement lasts about this long (> 0) */
} ob_fittime_opts;

/* Whether job j is timed by --time-fits: it has an approximation. */
int ob_fittime_wants(const ob_job *j);

/* Purpose: time the fits of every job that has an approximation.
 * Inputs:  o: rounds and minimum time; spans: the jobs' span logs (the
 *          driver's hooks.spans), one per job.
 * Outputs: each such job's fit_calls, method_ns, method_iqr_ns (the others
 *          keep fit_calls 0: empty columns); round_ns[r * njobs + i]: job
 *          i's time in round r (ns per iteration of its workload; NAN for a
 *          job not timed); *seconds: the pass's wall time.
 * Returns: 0 (a job one of whose fits does not succeed again, e.g. sisl
 *          past its wall cap on a loaded machine, keeps fit_calls 0, with a
 *          warning: its row is kept, without a method time); 1 when a stop
 *          signal came (nothing is kept: fit_calls 0 everywhere); -1 after
 *          ob_error() when memory ran out. */
int ob_fittime_run(const ob_fittime_opts *o, ob_job *jobs, size_t njobs, const ob_span_log *spans, double *round_ns,
                   double *seconds);

#endif
