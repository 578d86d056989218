/*
 * meta_selection.h - meta.json's "selection": what a run set out to run.
 *
 * `compare` reads it from NEW's meta.json (host/compare/compare_subset.c):
 * a row of BASE outside NEW's selection was left out on purpose (a smaller
 * nightly), one inside it that NEW lacks was lost (a regression).  The
 * rows alone cannot tell the two apart.  One line (merge reads meta.json a
 * top-level key per line):
 *
 *   "selection": {"curves": {"ID": [d, ...], ...}, "random": {"n": N,
 *   "seed": S, "only": null | ["ID", ...]} | null, "methods": [...],
 *   "metrics": [...], "splits": [...], "tols": [...], "doc": "..."}
 *
 * curves: every curve from a file (datasets/, --curves) the run planned,
 * with its offsets d; the random curves by rule, not listed (a --random of
 * 10^7 curves would not fit): curves 0..N-1 of seed S, or "only" those ids
 * (--curve).  Numbers as results.csv writes them (numfmt.h), so that a d or
 * tol read back is the row's double.
 */
#ifndef OB_META_SELECTION_H
#define OB_META_SELECTION_H

#include <stdio.h>

#include "host/io/curvefile.h"
#include "host/run/options.h"

/* Purpose: write the "selection" line of meta.json (with its trailing comma
 *          and newline) for the run of options o over the curves set (as
 *          loaded, before --curve: ob_run_selects picks); set NULL writes
 *          "selection": null (nothing known). */
void ob_meta_write_selection(FILE *f, const ob_run_opts *o, const ob_curveset *set);

#endif
