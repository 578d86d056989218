/*
 * bench_engines.h - `bench`'s engine figures (bench_engines.c).
 */
#ifndef OB_BENCH_ENGINES_H
#define OB_BENCH_ENGINES_H

#include <stddef.h>
#include <stdio.h>

#include "methods/driver/driver.h"

/* Purpose: run the jobs (inputs set; copied, not changed) through each
 *          engine on the CPU on all threads, and through each with the
 *          batch backend cl (NULL: none); print each run's efficiency,
 *          where the rest went and its model at 16 and 64 threads; write
 *          the rows WHAT/ENGINE[/model16|/model64] to csv (bench.csv's
 *          columns: items is the share groups, rate the efficiency).
 * Returns: 0; -1 when a run's rows differ from the level engine's on the
 *          CPU (timings aside) or memory ran out. */
int ob_bench_engines(FILE *csv, const ob_job *jobs, size_t n, const char *what, const ob_driver_hooks *cl);

#endif
