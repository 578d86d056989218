/*
 * trimmed.h - `run --trimmed`: each job's approximation measured against
 * the trimmed offset (issue 50, docs/export-measure.md "Trimmed offsets").
 *
 * A CAD kernel ships the trimmed offset, the set of points at distance |d|
 * from the curve (host/measure/trim.h), made from the approximation of the
 * untrimmed C + dN that a method gives, cut by its own crossings
 * (host/measure/trim_approx.h).  So after the driver, every job with an
 * approximation (status ok or limit) has its pieces refitted from its span
 * log (as --export and --certify have them), trimmed that way with a margin
 * of twice the larger of tol and max_err, and measured against the exact
 * trimmed offset of its (curve, d) (computed once for all the jobs that
 * share it) by trimmed-hausdorff, the two-sided distance of the two point
 * sets (ob_trimmed_hausdorff, the run's --samples per piece).  The rows gain
 * trimmed_err and trimmed_cut (the regions removed); every other column is
 * what the run gives without --trimmed, bit for bit.
 *
 * The driver still decides every split by the run's --metric against the
 * untrimmed offset: the methods approximate C + dN, and the tables keep
 * that protocol.  trimmed_err is what a CAD user gets after trimming.
 * Where the offset has no loop and no part nearer than |d| to the curve,
 * the trimmed offset is all of C + dN and trimmed_err is at most the
 * untrimmed hausdorff distance (set distance, no parameter match).
 */
#ifndef OB_TRIMMED_H
#define OB_TRIMMED_H

#include <stddef.h>

#include "methods/driver/driver.h"

/* Whether job j is measured by --trimmed: it has an approximation. */
int ob_trimmed_wants(const ob_job *j);

/* Purpose: the margin job j's approximation is trimmed with
 *          (ob_trim_approx): 2 max_err (tol where max_err is not finite),
 *          the largest deviation of its points' distance to the curve from
 *          |d| that its error allows, twice over, plus the exact trim's
 *          round-off allowance (OB_TRIM_REL of the curve's size). */
double ob_trimmed_margin(const ob_job *j);

/* Purpose: measure every job of jobs that has an approximation against the
 *          trimmed offset (above), OpenMP threads taking whole jobs; each
 *          job's numbers depend on the job alone (any thread count).
 * Inputs:  samples: the run's samples per piece; spans: the jobs' span logs
 *          (the driver's hooks.spans), one per job.
 * Outputs: each such job's trimmed_done, trimmed_err (+inf where one of
 *          the two trimmed sets is empty and the other is not; 0 where both
 *          are), trimmed_cut; *seconds: the pass's wall time.
 * Returns: 0 (a job that cannot be measured keeps trimmed_done 0, with a
 *          warning naming it); 1 when a stop signal came (trimmed_done 0
 *          everywhere); -1 after ob_error() when memory ran out. */
int ob_trimmed_run(int samples, ob_job *jobs, size_t njobs, const ob_span_log *spans, double *seconds);

#endif
