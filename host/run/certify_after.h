/*
 * certify_after.h - `offbench certify RUN_DIR`: a finished run certified
 * after the fact (issue 47), with what `run --certify` would have given it
 * (certify.h: the same err_upper, err_lower and certified; cert_ns is the
 * certificate's own time).
 *
 * What a finished run keeps is its rows and its fingerprint (journal.h:
 * DIR/results.fingerprint, every option that decides its results, the
 * curves' content hash and the build), not its pieces.  The pieces are had
 * as `draw` has them: the run's driver runs again on the jobs to certify
 * (fits and measurements are deterministic: any thread count, engine or
 * backend gives the same rows), each job's rerun must repeat its row
 * (status, counts, max_err, joints: else the job is not certified and the
 * command exits 1), and its span log is certified by ob_certify_run.  A run
 * whose fingerprint differs from what this binary computes for the run's
 * own options (another build, other curve data, another kernel), or whose
 * meta.json has another plan hash, is refused as `run --resume` refuses it;
 * a directory without results.fingerprint (a merged or MPI run, an older
 * build) cannot be checked and is refused too.
 *
 * Written: results.csv with the four certificate columns of the jobs
 * certified (every other byte as it was: the rows are edited in the file's
 * own text, not written again), meta.json's "certify" object (wall_seconds
 * summed over the passes) and, once every job with an approximation is
 * certified, the fingerprint and plan hash of a run with --certify (so
 * merge, resume and compare treat it as one); all through temporary files
 * and renames, results.csv last (fsutil.h).
 *
 * Resumable: each job certified is appended to DIR/certify.journal.csv as
 * `run --certify` journals it (first line "#offbench-certify-journal 1
 * FINGERPRINT", the run's fingerprint with certify=no whatever the run's,
 * so that a pass killed between writing its files and removing its journal
 * leaves one the next pass still reads; the header, rows).  A stop (SIGINT, SIGTERM) ends the pass
 * between jobs and writes what was certified; after a kill, the next pass
 * takes the journal's certificates first.  A job already certified is
 * never certified again.
 */
#ifndef OB_CERTIFY_AFTER_H
#define OB_CERTIFY_AFTER_H

#include "host/run/options.h"

/* The cells to certify: each list NULL (n 0) for all. */
typedef struct {
    char **methods;
    int nmethods;
    double *tols;
    int ntols;
    char **curves;
    int ncurves;
    int mode;  /* OB_CERTIFY_VERDICT or OB_CERTIFY_TIGHT (host/run/options.h) */
} ob_cert_select;

/* Purpose: certify the finished run in o->resume_dir (o: run options as
 *          parsed, with --threads, --backend, --device, --engine at most:
 *          the run's own are taken from its fingerprint, resume_opts.h),
 *          the jobs of sel that have an approximation and no certificate.
 * Returns: the exit status: 0; 1 a job not certified (its rerun did not
 *          repeat its row, no memory) or a file not written; 2 refused
 *          (not a run, another build or data, malformed files, a
 *          selection that names no cell of the run); 128 + signal when
 *          stopped (what was certified is written). */
int ob_certify_after(ob_run_opts *o, const ob_cert_select *sel);

#endif
