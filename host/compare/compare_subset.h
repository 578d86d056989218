/*
 * compare_subset.h - rows of BASE that NEW left out on purpose.
 *
 * A smaller run (a nightly over fewer curves, offsets, methods, metrics,
 * splits or tolerances, or a smaller --random N of the same seed) lacks
 * most rows of a full baseline.  Its rows cannot say whether a row was left
 * out or lost; NEW's meta.json "selection" (host/io/meta_selection.h) says
 * what NEW set out to run:
 *   - a row of BASE missing from NEW and outside that selection is "left
 *     out": counted, listed (kind left_out), summed up in one line, never a
 *     regression;
 *   - one inside it is "missing", a regression, as always.
 * The random curves: curve i of a seed is a function of (seed, i) alone
 * (random.h; tests/unit/test_compare_subset.c checks it), so --random N:S
 * runs the first N curves of --random M:S, the same ids and geometry: a
 * smaller N of the same seed is a subset.  Another seed makes other curves:
 * not comparable (exit 3: the "seed" key of meta.json, or, for a BASE
 * without meta.json, the seed in its random curves' ids).
 * Without NEW's meta.json, or a selection there (a run of an older
 * offbench, or one that cannot be read), every missing row is a regression,
 * as before, and a note says why.
 */
#ifndef OB_COMPARE_SUBSET_H
#define OB_COMPARE_SUBSET_H

#include "host/compare/compare.h"

/* Purpose: read NEW's selection into r->subset (after the comparability
 *          checks of ob_cmp_context, which calls it); a BASE without
 *          meta.json whose random curves are of another seed than NEW's
 *          random set goes into r->incomparable.
 * Errors:  returns 0, -1 out of memory. */
int ob_cmp_subset_load(const ob_cmp_side *b, const ob_cmp_side *n, ob_cmp_result *r);

/* Purpose: row b of BASE is missing from NEW: 1 when it lies outside NEW's
 *          selection (then counted in r->n_left_out and in the summary: the
 *          caller lists it as OB_CH_LEFT_OUT), 0 when inside or when NEW
 *          records no selection (missing), -1 out of memory. */
int ob_cmp_subset_left_out(ob_cmp_result *r, const ob_res_row *b);

/* Purpose: after the join: the note that NEW records no selection (when
 *          rows are missing), the one-line summary of what was left out.
 * Errors:  returns 0, -1 out of memory. */
int ob_cmp_subset_finish(ob_cmp_result *r);

/* The summary, e.g. "248 random curves (rnd2026_000002 ... rnd2026_000249),
 * methods cobb, ahn, tol 1e-05: 33,120 rows left out", or NULL when no row
 * was left out. */
const char *ob_cmp_left_out_text(const ob_cmp_result *r);

/* What NEW set out to run, e.g. "2 curves from files (4 offsets), random
 * 20:2026, 18 methods, metric hausdorff, split mid, 5 tols", or NULL
 * without a selection. */
const char *ob_cmp_selection_text(const ob_cmp_result *r);

/* Always safe (NULL too). */
void ob_cmp_subset_free(struct ob_cmp_subset *s);

#endif
