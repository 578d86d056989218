/*
 * files.h - the files a run leaves in its directory: results.csv,
 * meta.json, results.fingerprint, and samples.csv (--reps), fits.csv
 * (--time-fits) and shard.csv (--shard) where they apply; written all or none (fsutil.h).
 */
#ifndef OB_FILES_H
#define OB_FILES_H

#include <stddef.h>

#include "host/run/options.h"
#include "host/run/record.h"

/* What a finished run writes. */
typedef struct {
    const ob_run_opts *o;
    const ob_run_record *rec;
    const ob_job *jobs;          /* this process's jobs, in job order */
    size_t njobs;
    const size_t *shard_idx;     /* --shard: each job's index in the whole run */
    const char *where;           /* the curves' source (meta.json "data") */
    double wall;                 /* seconds (the median of the timed runs with --reps) */
    const double *rep_fit, *rep_eval;  /* --reps: reps x njobs timings */
    const double *fit_round;     /* --time-fits: rounds x njobs method times (fits.csv) */
} ob_run_files;

/* Purpose: write the run's files into o->out_dir, results.csv last.
 * Returns: 0, or -1 after ob_error() (and every file as it was). */
int ob_write_run_files(const ob_run_files *r);

/* Purpose: under mpirun, every rank sends its rows to rank 0, which writes
 *          the files of the whole run (drc: this rank's driver status).
 * Returns: the exit status, the same on every rank. */
int ob_mpi_write_run_files(const ob_run_files *r, int drc);

/* Purpose: the run's closing line on stderr: jobs by status, wall time,
 *          whether results.csv was written. */
void ob_run_summary(const ob_run_files *r, int written);

#endif
