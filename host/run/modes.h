/*
 * modes.h - the ways a run runs its jobs through the driver: once (with its
 * progress bar), journaled (rows saved as jobs finish; --resume restores
 * them), and with --reps timed repetitions after a warm-up.  SIGINT and
 * SIGTERM stop a run between batches (the driver reads ob_stop_flag(),
 * signals.h).
 *
 * Every mode returns the driver's status: 0; -1 out of memory; 1 stopped by
 * a signal; ob_run_journaled also 2 when the journal cannot be used (said
 * through ob_error()).
 */
#ifndef OB_MODES_H
#define OB_MODES_H

#include <signal.h>
#include <stddef.h>

#include "host/run/journal.h"
#include "host/run/options.h"
#include "host/run/record.h"

/* One run's setting for its modes: the configuration, the record the run
 * fills, and the driver's hooks (the backend, the stop flag). */
typedef struct {
    const ob_run_opts *o;
    ob_run_record *rec;
    ob_driver_hooks hooks;
} ob_run_ctx;

/* Purpose: one driver run of the jobs with a progress bar (what: a line said
 *          first, or NULL).  Outputs: the jobs; *wall: its wall time. */
int ob_run_plain(const ob_run_ctx *c, ob_job *jobs, size_t njobs, const char *what, double *wall);

/* Purpose: --reps N, after the warm-up run (ob_run_plain) that gave the
 *          jobs their results: N timed runs, whose per-job timings go to
 *          fit/eval (N x njobs, rep-major) and whose medians replace the
 *          jobs' timing columns.  A timed run whose results differ from the
 *          warm-up's is nondeterminism: counted in c->rec->rep_mismatches and
 *          said on stderr; the warm-up's results are kept.
 * Outputs: *wall: the median wall time of the timed runs. */
int ob_run_reps(const ob_run_ctx *c, ob_job *jobs, size_t njobs, double *fit, double *eval, double *wall);

/* Purpose: the run without repetitions: rows saved to the journal jr as
 *          jobs finish; with --resume, the jobs the journal (or a finished
 *          results.csv) already has are restored instead of run.
 * Outputs: *restored_n: how many jobs were restored; *wall. */
int ob_run_journaled(const ob_run_ctx *c, ob_job *jobs, size_t njobs, const char *where, ob_journal *jr, double *wall,
                     size_t *restored_n);

#endif
