/*
 * output.h - results.csv and meta.json of a run.
 */
#ifndef OB_OUTPUT_H
#define OB_OUTPUT_H

#include <stdio.h>

#include "methods/driver/driver.h"
#include "host/run/options.h"
#include "host/run/record.h"

/* Purpose: write one row per job, in job order, to f.  Returns 0 or -1 on a
 * write error. */
int ob_write_results(FILE *f, const ob_job *jobs, size_t njobs);

/* Purpose: write one job's row (no header) to f.  Returns 0 or -1. */
int ob_write_result_row(FILE *f, const ob_job *j);

/* Purpose: write field col (host/io/columns.h: ob_col) of job j's row, as
 *          ob_write_result_row writes it (no separator), e.g. the
 *          certificate's columns that `certify` fills in after the run. */
void ob_write_result_field(FILE *f, const ob_job *j, int col);

/* The samples.csv header line (no newline). */
extern const char OB_SAMPLES_HEADER[];

/* Purpose: write samples.csv of a run with --reps: one row per job and
 * repetition (job-major, rep = 1..reps), the key columns of results.csv and
 * that repetition's fit_ns and eval_ns, taken from fit[r * njobs + i] and
 * eval[r * njobs + i].  Returns 0 or -1 on a write error. */
int ob_write_samples(FILE *f, const ob_job *jobs, size_t njobs, int reps, const double *fit, const double *eval);

/* Purpose: one job's samples.csv rows (no header): repetition r's timings
 *          at fit[r * stride], eval[r * stride].  Returns 0 or -1. */
int ob_write_job_samples(FILE *f, const ob_job *j, int reps, const double *fit, const double *eval, size_t stride);

/* fits.csv (run --time-fits, host/run/fittime.h): every round of every
 * timed job, curve,d,method,metric,split,tol,round,fit_calls,method_ns
 * (round 1..rounds; method_ns that round's ns per pass over the job's
 * accepted pieces).  round_ns[r * njobs + i]: job i's time in round r. */
extern const char OB_FITS_HEADER[];
int ob_write_fits(FILE *f, const ob_job *jobs, size_t njobs, int rounds, const double *round_ns);

/* Purpose: write meta.json: what makes two runs comparable (build, backend,
 * threads, samples, limits, argv, time): the configuration o and what the
 * run recorded in rec.  Returns 0 or -1. */
int ob_write_meta(FILE *f, const ob_run_opts *o, const ob_run_record *rec, const char *data_source, size_t njobs,
                  double wall_seconds);

/* Purpose: meta.json's "certify" line: the certificate's settings and the
 *          pass's wall time when certified, else null (run --certify, and
 *          `certify` after the fact). */
void ob_write_meta_certify(FILE *f, int mode, double wall_seconds);

/* Writes s as a CSV field (quoted when it holds a comma, quote or newline). */
void ob_csv_field(FILE *f, const char *s);
/* Writes s as a JSON string literal, always valid UTF-8 JSON: a byte that
 * is no UTF-8 (utf8.h) as U+FFFD, control characters and DEL escaped. */
void ob_json_string(FILE *f, const char *s);

#endif
