/*
 * random.h - the random test families of `--random N[:SEED]`.
 *
 * Curve i of a seed is a pure function of (SEED, i): it depends neither on N
 * nor on thread scheduling, so curve i of `--random 100:7` equals curve i of
 * `--random 1000:7`.  The numbers come from a counter-based generator
 * (splitmix64 of a per-curve key and a draw counter); there is no global state.
 *
 * Family of curve i: i mod 8, in the order of ob_random_family_names:
 *   cubic, quintic, septic   polynomial Bézier curves of degree 3, 5, 7
 *   rational                 rational quadratics and cubics, weights in [0.5, 2]
 *   inflection               cubics and quintics with an inflection in [0.05, 0.95]
 *   tight                    cubics with |d| = 0.9..0.99 of the smallest radius of
 *                            curvature, on the concave side (the offset nearly cusps)
 *   loop                     the same with |d| = 1.1..2 of it (the offset has cusps
 *                            where 1 - d kappa changes sign)
 *   degenerate               nearly degenerate control polygons, kind (i / 8) mod 3:
 *                            two consecutive points within 1e-6, a nearly straight
 *                            polygon, or one very short leg (1e-5..1e-3)
 * Every control point lies in the unit box [0,1]^2.  Offsets: d > 0 is on the
 * left, N = (-y', x')/|C'|; see random.c for the exact definitions.
 * Ids are `rnd<SEED>_<i>` with i zero-padded to 6 digits (e.g. rnd7_000042);
 * the source reads "random family F, seed S, index i".
 */
#ifndef OB_RANDOM_H
#define OB_RANDOM_H

#include <stddef.h>
#include <stdint.h>

#include "methods/core/curve.h"
#include "host/io/curvefile.h"
#include "methods/core/err.h"

enum { OB_RND_NFAMILIES = 8 };
enum {
    OB_RND_CUBIC = 0, OB_RND_QUINTIC, OB_RND_SEPTIC, OB_RND_RATIONAL,
    OB_RND_INFLECTION, OB_RND_TIGHT, OB_RND_LOOP, OB_RND_DEGENERATE
};
/* Kinds of the degenerate family: curve i has kind (i / 8) mod 3. */
enum { OB_RND_DEGEN_COINCIDENT = 0, OB_RND_DEGEN_STRAIGHT, OB_RND_DEGEN_SHORT_LEG };

#define OB_RND_MAX_N 10000000L

extern const char *const ob_random_family_names[OB_RND_NFAMILIES];

/* Family index of curve i (i mod 8), and the degenerate kind ((i / 8) mod 3). */
int ob_random_family(long index);
int ob_random_degenerate_kind(long index);

/* Purpose: parse a `N[:SEED]` spec: N a whole number 1..OB_RND_MAX_N, SEED a
 *          whole number 0..2^64-1 (default 1), digits only.
 * Errors:  returns 0; -1 after ob_error() naming `opt`. */
int ob_random_parse(const char *opt, const char *spec, long *n, uint64_t *seed);

/* The id of curve `index` of `seed`: "rnd<SEED>_<index, 6 digits or more>". */
void ob_random_id(uint64_t seed, long index, char *buf, size_t len);

/* Purpose: read an id back: 0 with its seed and index when id is exactly
 *          ob_random_id(seed, index) (the canonical spelling, index below
 *          10^9), else -1 (compare asks whether a row's curve is one of a
 *          random set: host/compare/compare_subset.c). */
int ob_random_id_parse(const char *id, uint64_t *seed, long *index);

/* Purpose: generate curve `index` (>= 0) of `seed` into *c (overwritten; the
 *          caller frees it with ob_curve_free).  One polynomial or rational
 *          Bézier segment, one or two offsets.  Takes microseconds.
 * Errors:  0, or -1 when out of memory or index < 0 (*c is then empty). */
int ob_random_curve(uint64_t seed, long index, ob_curve *c);

/* Purpose: append curves 0..n-1 of `seed` to *set in index order (generated in
 *          parallel, the result does not depend on the threads).  With ids
 *          (nids > 0), only the curves whose ids are listed are generated; ids
 *          that are not random ids of this set are ignored.
 * Errors:  0; -1 with a message in err->msg on a duplicate id against the curves
 *          already in *set, or out of memory (*set is then as before). */
int ob_random_append(ob_curveset *set, uint64_t seed, long n, char *const *ids, int nids,
                     ob_err *err);

#endif
