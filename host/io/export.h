/*
 * export.h - `run --export DIR` and `draw --export DIR`: each job's
 * approximation in the base curve's coordinates, in four forms (README
 * "Export and measure"):
 *   STEM.json    degree, weights, knots, control points (Euclidean and
 *                homogeneous) of every Bézier piece, the base piece each
 *                approximates, the job key and its max_err;
 *   STEM.curves  one `curve` block per piece (homogeneous `hpoint`s, exact),
 *                read back by offbench's own reader (host/io/curvefile.c);
 *   STEM.dxf     one DXF SPLINE entity per piece (AC1015, R2000);
 *   STEM.svg     one <path> per piece: native L / Q / C commands for
 *                polynomial pieces of degree 1 to 3, a polyline of 64
 *                chords for the others (SVG paths have no rational or
 *                higher-degree commands);
 * and DIR/index.csv, one row per job (its key, status, max_err, STEM; an
 * empty STEM for a job without an approximation: fail, skip, timeout); a
 * shard writes index.shardK-of-N.csv instead, which `merge` combines.
 * What else DIR may hold, and what the export removes: export_dir.h.
 * STEM is CURVE__dD__METHOD__tolT with every '/' of the curve id written
 * as '~' (ids never hold '~', so stems of distinct jobs differ).
 */
#ifndef OB_EXPORT_H
#define OB_EXPORT_H

#include <stdio.h>

#include "host/io/approx.h"
#include "host/run/options.h"

/* The header of index.csv (and of a shard's index). */
#define OB_EXPORT_INDEX_HEADER "curve,d,method,tol,status,max_err,segments,stem"

/* The file stem of job j (see above). */
void ob_export_stem(char *buf, size_t len, const ob_job *j);

/* A number as every export writes it: the shortest round-trip text; "null"
 * for a non-finite one when json, else "nan"/"inf". */
void ob_export_num(FILE *f, double x, int json);

/* Where piece p sits, in the words `measure` reads back from a .curves
 * source line or a DXF comment (approx.h): "span A B fit T0 T1". */
void ob_export_span(FILE *f, const ob_apiece *p);

/* The writers: each returns 0, or -1 when writing failed.  samples: what
 * the run's sampled metrics used (recorded in the JSON). */
int ob_export_write_json(FILE *f, const ob_job *j, int samples, const ob_approx *a);
int ob_export_write_curves(FILE *f, const ob_job *j, const ob_approx *a);
int ob_export_write_dxf(FILE *f, const ob_job *j, const ob_approx *a);
int ob_export_write_svg(FILE *f, const ob_job *j, const ob_approx *a);

/* Purpose: the four files of job j (an approximation: status ok or limit)
 *          into directory dir (which exists), from its span log.
 * Returns: 0; -1 after ob_error() (a refit that does not repeat the run, a
 *          file that cannot be written). */
int ob_export_job(const char *dir, const ob_job *j, int samples, const ob_span_log *log);

/* Purpose: for `draw` and `trace`: create dir and write job j's files (if
 *          it has an approximation) and index.csv; every other file of the
 *          export's names in dir goes first (export_dir.h: dir then holds
 *          this job's export only).
 * Returns: 0, or 1 after ob_error(). */
int ob_export_single(const char *dir, const ob_job *j, int samples, const ob_span_log *log);

/* Purpose: for `run`: check --export against the other options (not with
 *          --resume, --reps or MPI ranks: their jobs' pieces are not all
 *          logged by this process), refuse a DIR that would make the
 *          export input (ob_export_check_dir: a curve directory, or one
 *          holding the --curves file), and make a span log per job for the driver's
 *          hooks (*spans; NULL without --export).
 * Returns: 0, or the exit status after ob_error(): 2 (bad input), 1 (out
 *          of memory). */
int ob_export_prepare(const ob_run_opts *o, int mpi_ranks, size_t njobs, ob_span_log **spans);

/* Purpose: for `run`, once results.csv is written (status 0): create
 *          o->export_dir, remove its index and the files of the export's
 *          names this run does not write (export_dir.h: a plain run every
 *          other job's, a shard its own jobs' without an approximation),
 *          export every job of jobs (the jobs the span logs were made for),
 *          then index.csv (a shard: index.shardK-of-N.csv).  Nothing to do
 *          without logs.
 * Returns: status, or 1 after ob_error() when the export failed. */
int ob_export_finish(const ob_run_opts *o, const ob_span_log *spans, const ob_job *jobs, int status);

/* Purpose: njobs zeroed span logs for the driver's hooks (--export and
 *          --certify), with the end mark ob_export_finish and
 *          ob_export_free count by.  NULL when out of memory. */
ob_span_log *ob_span_logs_new(size_t njobs);

/* Frees the logs of ob_export_prepare or ob_span_logs_new (NULL is fine). */
void ob_export_free(ob_span_log *spans);

#endif
