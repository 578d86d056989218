/*
 * bench_protocol.h - `bench`'s figures of the external-method protocol
 * (bench_protocol.c).
 */
#ifndef OB_BENCH_PROTOCOL_H
#define OB_BENCH_PROTOCOL_H

#include <stdio.h>

/* Purpose: time a fit call of tiller in process, through `offbench worker
 *          tiller` and through examples/external/tiller.py (when python3 and
 *          the file are there: bench run from the source tree), and the
 *          Python method with 1 and N threads on --random 100:7 (10 curves
 *          with quick) beside the built-in; print the figures and write the
 *          rows protocol/... to csv (bench.csv's columns).  Registers the
 *          external methods tiller_w and tiller_py: call it after every
 *          section that runs "all methods".
 * Returns: 0; -1 when the random set cannot be made. */
int ob_bench_protocol(FILE *csv, int N, int quick);

#endif
