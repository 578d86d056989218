/*
 * shard.h - splitting a run's job list into N shards of about equal cost
 * (`run --shard K/N`, the MPI ranks), and the fingerprint that lets `merge`
 * check that shards belong to one run.
 *
 * The partition is a function of the job list alone (the same on every
 * machine and rank): jobs are taken in decreasing estimated cost (ties by job
 * index) and each goes to the shard with the least estimated cost so far
 * (ties to the lowest shard): longest-processing-time-first, within 4/3 of
 * the best balance for the estimates.  Each shard runs its jobs in job order
 * and writes them in that order, with their job indices in DIR/shard.csv.
 */
#ifndef OB_SHARD_H
#define OB_SHARD_H

#include <stddef.h>
#include <stdint.h>

#include "methods/driver/driver.h"

/* Purpose: the shard of every job: shard_of[i] in 0..n-1 for jobs[0..njobs).
 * Returns 0, or -1 without memory. */
int ob_shard_assign(const ob_job *jobs, size_t njobs, int n, int *shard_of);

/* Purpose: parse "K/N" (0 <= K < N <= 100000) for option opt; 0, or -1
 *          after ob_error() naming the option. */
int ob_shard_parse(const char *opt, const char *spec, int *k, int *n);

/* Purpose: a 64-bit FNV-1a hash of the job list (every job's key, in job
 *          order) and of the options fingerprint `fp`: equal for the shards of
 *          one run, different for another run. */
uint64_t ob_plan_hash(const ob_job *jobs, size_t njobs, const char *fp);

/* Purpose: the pieces of ob_plan_hash, for `merge` to recompute it from the
 *          rows: the hash of the fingerprint alone (meta.json "plan_seed"),
 *          then one step per job over its key as results.csv writes it
 *          (curve, d, method, metric, split, tol).  ob_key_step(FNV offset
 *          basis, key) alone is a job's key hash (shard.csv "key"). */
uint64_t ob_plan_seed(const char *fp);
uint64_t ob_key_step(uint64_t h, const char *const key[6]);
uint64_t ob_job_key_step(uint64_t h, const ob_job *j);
#define OB_FNV_BASIS 14695981039346656037ULL

/* One FNV-1a step over n bytes at p, from the hash h (OB_FNV_BASIS to
 * start): the hash of every fingerprint and key above. */
uint64_t ob_fnv1a(uint64_t h, const void *p, size_t n);

#endif
