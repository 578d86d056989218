/*
 * summary_impl.h - the pivot's helpers that summary.c shares with
 * summary_archive.c (not part of the summary's interface): the archive
 * adds columns to a built summary, so it needs the same lookups and the
 * same statistics as the build, not a copy of them.
 */
#ifndef OB_SUMMARY_IMPL_H
#define OB_SUMMARY_IMPL_H

#include "host/io/strmap.h"
#include "host/summary/summary.h"

/* The index of tol in s->tols, or -1. */
int ob_sum_find_tol(const ob_summary *s, double tol);

/* The index of name in v[0..n), or -1. */
int ob_sum_find_name(const char **v, int n, const char *name);

/* The pair map's value of row r's (curve, d) (put_val >= 0: add it as
 * that value when new; see ob_strmap_putn), or -2 when out of memory. */
long ob_sum_pair_lookup(ob_strmap *pairs, const ob_res_row *r, long put_val);

/* A side's arrays for s's shape; its statistics once its cells are
 * filled; freeing it.  0, or -1 when out of memory. */
int ob_sum_side_alloc(const ob_summary *s, ob_sum_side *side);
int ob_sum_side_stats(const ob_summary *s, ob_sum_side *side);
void ob_sum_side_free(ob_sum_side *side);

/* Frees what ob_summary_archive added (summary_archive.c). */
void ob_sum_archive_free(ob_summary *s);

#endif
