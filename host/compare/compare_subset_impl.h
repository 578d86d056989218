/*
 * compare_subset_impl.h - what compare_subset.c and compare_subset_text.c
 * share (not for other callers: compare_subset.h is the interface).
 */
#ifndef OB_COMPARE_SUBSET_IMPL_H
#define OB_COMPARE_SUBSET_IMPL_H

#include <stdint.h>

#include "host/compare/compare.h"
#include "host/io/strmap.h"

/* The parts of a selection a row of BASE can fall outside, in the order the
 * summary names them: curves from files, random curves, offsets of selected
 * curves, methods, metrics, splits, tolerances. */
enum { SUB_CURVE, SUB_RANDOM, SUB_OFFSET, SUB_METHOD, SUB_METRIC, SUB_SPLIT, SUB_TOL, SUB_NDIMS };

struct ob_cmp_subset {
    int has;                     /* NEW's selection was read */
    char why[320];               /* else why not (the note) */
    const ob_json_flat *meta;    /* NEW's meta.json: selection.curves.ID is looked up there */
    ob_strmap sel[SUB_NDIMS];    /* methods, metrics, splits selected (SUB_METHOD...) */
    int nmethods, nmetrics, nsplits;
    double tols[64];             /* run takes at most OB_MAX_TOLS (64) */
    int ntols;
    int ncurves, noffsets;       /* curves from files and their offsets */
    int random, has_only;        /* a random set: curves 0..n-1 of seed, or only those in `only` */
    uint64_t seed;
    long n;
    ob_strmap only;
    char random_text[64];        /* "N:SEED" */
    ob_strmap seen[SUB_NDIMS];   /* what was left out: each value once ... */
    ob_strlist out[SUB_NDIMS];   /* ... in the order of BASE's rows */
    char text[1024], sel_text[512];
};

typedef struct ob_cmp_subset ob_cmp_subset;

/* Purpose: value of part dim was left out: listed once (s->out), *out set.
 * Returns 0, -1 out of memory. */
int ob_cmp_subset_note(ob_cmp_subset *s, int dim, const char *value, int *out);

#endif
