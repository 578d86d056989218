/*
 * plan.h - what a run runs: the curves its options select, its jobs (curve x
 * d x method x tol, in that nesting), the hashes that identify them, and the
 * jobs of this process's shard.
 */
#ifndef OB_PLAN_H
#define OB_PLAN_H

#include <stddef.h>
#include <stdint.h>

#include "host/io/curvefile.h"
#include "host/run/options.h"

/* Purpose: load the curves a run's options select: --curves FILE, then the
 *          --random curves; the default set (datasets/ or the embedded copy)
 *          when neither is given; checks that every --curve ID exists.
 * Outputs: set; where: names the source for messages and meta.json.
 * Returns: 0, or -1 after ob_error(). */
int ob_load_run_curves(const ob_run_opts *o, ob_curveset *set, char *where, size_t wlen);

/* Purpose: the --d of draw, trace and measure against curve c's own limits:
 *          the one offset check (ob_offset_check) a curve file's `offset`
 *          line gets, so no command takes a d the file would refuse.
 * Returns: 0; -1 after ob_error() naming --d, the curve and where it was
 *          defined (the command exits 2). */
int ob_check_option_d(const char *cmd, const ob_curve *c, double d);

/* Purpose: 1 if the run uses the curve of this id (--curve), else 0. */
int ob_run_selects(const ob_run_opts *o, const char *id);

/* Purpose: FNV-1a over the content of the curves the run uses (id,
 *          segments' degrees and homogeneous control points, offsets): a
 *          resume of a run whose curve file changed is refused (journal.h). */
uint64_t ob_curves_hash(const ob_run_opts *o, const ob_curveset *set);

/* Purpose: the exact offset degree of every curve the run uses, once per
 *          curve, in parallel (offdeg.h); a curve whose degree cannot be
 *          computed keeps offset_known 0. */
void ob_offset_degrees(const ob_run_opts *o, ob_curveset *set);

/* Purpose: the run's jobs, in job order (curve, d, method, tol).
 * Returns: a malloc'd array of *njobs jobs (*njobs may be 0), or NULL
 *          without memory. */
ob_job *ob_plan_jobs(const ob_run_opts *o, const ob_curveset *set, size_t *njobs);

/* Purpose: keep the jobs of shard shard_k of shard_n (cost-balanced,
 *          shard.h), in job order.
 * Outputs: *jobs compacted, *njobs their count, *idx (malloc'd) each kept
 *          job's index in the whole run's job list.
 * Returns: 0, or -1 after ob_error() (memory). */
int ob_select_shard(int shard_k, int shard_n, ob_job **jobs, size_t *njobs, size_t **idx);

#endif
