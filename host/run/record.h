/*
 * record.h - what one run finds out and does as it goes, kept apart from its
 * configuration (options.h: what the command line asked for, unchanged once
 * parsed).  The run command fills a record; meta.json and the resume
 * fingerprint read it.
 */
#ifndef OB_RECORD_H
#define OB_RECORD_H

#include <stddef.h>
#include <stdint.h>

#include "host/backend/select.h"
#include "host/run/backends.h"
#include "host/io/curvefile.h"
#include "host/run/hostinfo.h"
#include "methods/driver/driver.h"

typedef struct {
    uint64_t data_hash;          /* FNV-1a of the selected curves' content
                                    (journal.h: a resume over changed data is refused) */
    /* the whole run's job count and plan hash (shard.h), equal in every
     * shard of one run; plan_seed: ob_plan_seed(), merge recomputes plan_hash */
    size_t jobs_total;
    uint64_t plan_hash, plan_seed;
    int shard_k, shard_n;        /* the shard this process runs: --shard K/N, or
                                    its MPI rank of mpi_ranks; shard_n 0: all */
    int mpi_ranks;               /* > 1: run by that many MPI ranks (mpirun.h) */
    long rep_mismatches;         /* job results that differed between
                                    repetitions (nondeterminism) */
    ob_backend_info binfo;
    ob_backend_list backends;    /* every backend that computed rows of the run,
                                    across --resume (backends.h); empty: binfo's */
    ob_loadavg load;             /* the load average during the run (hostinfo.h) */
    ob_engine_stats engine;      /* what the driver's engine did (the last run
                                    of a --reps series) */
    double cert_seconds;         /* --certify: wall time of the certificate pass */
    double fit_seconds;          /* --time-fits: wall time of the fit timing pass */
    double trim_seconds;         /* --trimmed: wall time of the trimmed offset pass */
    const ob_curveset *curves;   /* the curves loaded (plan.h), for meta.json's
                                    "selection" (meta_selection.h); NULL: unknown */
} ob_run_record;

#endif
