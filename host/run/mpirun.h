/*
 * mpirun.h - `mpirun -n P ./offbench run ...` (the build with `make MPI=1`):
 * rank r runs shard r/P of the job list (shard.h), with OpenMP and OpenCL
 * inside the rank, and rank 0 gathers every rank's rows and writes the one
 * results.csv (and samples.csv, meta.json) that a single process writes.
 *
 * Without MPI (the default build) the functions say: one process, rank 0.
 */
#ifndef OB_MPIRUN_H
#define OB_MPIRUN_H

#include <stddef.h>
#include <stdint.h>

#include "methods/driver/driver.h"

/* Purpose: start MPI when built with it (a no-op otherwise).  0, or -1. */
int ob_mpi_init(int *argc, char ***argv);
/* Purpose: end MPI; always safe. */
void ob_mpi_finalize(void);
/* This process's rank and the number of ranks (0 and 1 without MPI). */
int ob_mpi_rank(void);
int ob_mpi_size(void);

/* Purpose: 1 when every rank has the same 64-bit value (the plan hash:
 *          ranks started with other arguments disagree), 0 otherwise. */
int ob_mpi_all_equal(uint64_t v);

/* Purpose: the largest of v over the ranks, on every rank. */
double ob_mpi_max(double v);

/* Purpose: gather the text of every rank's rows at rank 0, in job order.
 * Inputs:  rows[i] / samples[i]: the text of local job i (a results.csv row
 *          with its newline; its samples.csv rows, or "" without --reps);
 *          idx[i] its index in the whole run; total the run's job count.
 * Outputs: on rank 0, *res and *smp: the rows and samples of all jobs in job
 *          order (malloc'd); NULL on the other ranks.
 * Errors:  returns 0; -1 (on every rank) when memory ran out or the ranks'
 *          indices do not cover 0..total-1 exactly once. */
int ob_mpi_gather(char *const *rows, char *const *samples, const size_t *idx, size_t n, size_t total, char **res,
                  char **smp);

#endif
