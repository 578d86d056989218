/*
 * test_table_lanes.c - the metric core's lane-batched Hausdorff sample tables
 * (obc_fill_table: OBC_LANES samples at a time) against the scalar reference
 * kept for this purpose (obc_fill_table_ref: one obc_pc_eval per sample),
 * bit for bit; the inline fmin/fmax of the CPU build against libm's; and
 * obc_divw's shortcut (x / 1 = x) against the division.
 *
 * Why: the tables decide every hausdorff result.  The batched rows are meant
 * to run the same IEEE operations per sample in the same order, so any bit
 * that differs (a lane that takes another formula, a missed special case at
 * a non-regular point or at a cusp of the offset, the tail of S past a
 * multiple of the lane count, the work count) changes results.  The curves:
 * polynomial and rational, degrees 0..OBC_MAX_DEG, offsets 0 and on both
 * sides, past the radius of curvature (cusps), at exactly the radius of a
 * circle, curves with vanishing derivatives at a sample (non-regular points)
 * and a point-like curve; S = 2, 3, 5, 256, 257, 513.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "kernels/metric_core.h"
#include "tests/check.h"

enum { MAXS = 513 };

static double tab_a[OBC_TABLE_SIZE(MAXS)], tab_b[OBC_TABLE_SIZE(MAXS)];

/* Deterministic uniform in [lo, hi) (no libc rand: the same on every host). */
static uint64_t rng_state = 0x9e3779b97f4a7c15u;
static double urand(double lo, double hi)
{
    rng_state = rng_state * 6364136223846793005u + 1442695040888963407u;
    return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1p-53;
}

/* Homogeneous control points (w x, w y, w) of degree n: random, rational
 * when asked (weights in [0.3, 3]). */
static void random_curve(double *h, int n, int rational)
{
    for (int i = 0; i <= n; i++) {
        const double w = rational ? urand(0.3, 3.0) : 1.0;
        h[3 * i] = w * urand(-1.0, 1.0);
        h[3 * i + 1] = w * urand(-1.0, 1.0);
        h[3 * i + 2] = w;
    }
}

/* 1 when the two tables of S samples are equal bit for bit (else prints
 * the first difference). */
static int same_table(const char *what, int S)
{
    const size_t n = OBC_TABLE_SIZE(S);
    for (size_t i = 0; i < n; i++)
        if (memcmp(&tab_a[i], &tab_b[i], sizeof(double)) != 0) {
            fprintf(stderr, "%s S=%d: entry %zu (sample %zu, field %zu): %.17g vs %.17g\n", what, S, i,
                    i / OBC_REC, i % OBC_REC, tab_a[i], tab_b[i]);
            return 0;
        }
    return 1;
}

/* Both tables of (h, n) at offset d for every S; checks bits and work. */
static void check_curve(const char *what, const double *h, int n, double d)
{
    static const int Ss[] = {2, 3, 5, 256, 257, 513};
    for (size_t i = 0; i < sizeof Ss / sizeof Ss[0]; i++) {
        const int S = Ss[i];
        long oa = 0, ob = 0;
        memset(tab_a, 0xa5, sizeof tab_a);
        memset(tab_b, 0x5a, sizeof tab_b);
        obc_fill_table(h, n, d, S, tab_a, &oa);
        obc_fill_table_ref(h, n, d, S, tab_b, &ob);
        CHECK(same_table(what, S), "%s: degree %d, d = %g, S = %d: batched table differs", what, n, d, S);
        CHECK(oa == ob, "%s: degree %d, d = %g, S = %d: work %ld vs %ld", what, n, d, S, oa, ob);
    }
}

static void random_curves(void)
{
    static const double ds[] = {0.0, 0.05, -0.05, 0.7, -1.5};
    double h[3 * (OBC_MAX_DEG + 1)];
    for (int n = 0; n <= OBC_MAX_DEG; n++)
        for (int rational = 0; rational < 2; rational++)
            for (size_t k = 0; k < sizeof ds / sizeof ds[0]; k++) {
                random_curve(h, n, rational);
                check_curve(rational ? "rational" : "polynomial", h, n, ds[k]);
            }
}

/* Curves with non-regular points at samples: C'(0) = 0 (a repeated first
 * point), a cubic cusp at t = 1/2 (C'(1/2) = 0), a point-like curve; and
 * the rational quarter circle at d = radius (1 - d kappa = 0 up to round-off). */
static void special_curves(void)
{
    static const double ds[] = {0.0, 0.3, -0.3};
    const double rep[] = {0, 0, 1, 0, 0, 1, 1, 1, 1, 2, 0, 1};
    const double cusp[] = {0, 0, 1, 1, 1, 1, 0, 1, 1, 1, 0, 1};
    const double pt[] = {0.5, 0.5, 1, 0.5, 0.5, 1, 0.5, 0.5, 1};
    const double c = sqrt(0.5);
    const double quarter[] = {1, 0, 1, c, c, c, 0, 1, 1};
    for (size_t k = 0; k < sizeof ds / sizeof ds[0]; k++) {
        check_curve("repeated end point", rep, 3, ds[k]);
        check_curve("cusp at 1/2", cusp, 3, ds[k]);
        check_curve("point-like", pt, 2, ds[k]);
    }
    check_curve("quarter circle at its radius", quarter, 2, 1.0);
    check_curve("quarter circle inside out", quarter, 2, -1.0);
    check_curve("quarter circle past its radius", quarter, 2, 2.0);
}

/* The inline fmin/fmax of the CPU build give libm's bits (signed zeros,
 * infinities, NaN in either place). */
static void min_max(void)
{
    /* volatile: libm's calls, not the compiler's folding of constants */
    static volatile double v[] = {0.0, -0.0, 1.0, -1.0, 3.5, (double)INFINITY, -(double)INFINITY, (double)NAN};
    const int nv = sizeof v / sizeof v[0];
    int bad = 0;
    for (int i = 0; i < nv; i++)
        for (int j = 0; j < nv; j++) {
            const double a = OBC_FMIN(v[i], v[j]), b = fmin(v[i], v[j]);
            const double c = OBC_FMAX(v[i], v[j]), e = fmax(v[i], v[j]);
            if (memcmp(&a, &b, sizeof a) != 0 || memcmp(&c, &e, sizeof c) != 0) {
                bad++;
                fprintf(stderr, "min/max(%g, %g): %g %g vs libm %g %g\n", v[i], v[j], a, c, b, e);
            }
        }
    CHECK(bad == 0, "%d of %d pairs: OBC_FMIN/OBC_FMAX differ from fmin/fmax", bad, nv * nv);
}

/* obc_divw(x, 1) is x / 1 bit for bit (its shortcut for polynomial segments). */
static void div_by_one(void)
{
    static volatile double v[] = {0.0, -0.0, 1.0, -1.0, 0x1p-1074, 1e300, (double)INFINITY, -(double)INFINITY,
                                  (double)NAN, -(double)NAN};
    static volatile double one = 1.0;
    const int nv = sizeof v / sizeof v[0];
    int bad = 0;
    for (int i = 0; i < nv; i++) {
        const double a = obc_divw(v[i], one), b = v[i] / one;
        bad += memcmp(&a, &b, sizeof a) != 0;
    }
    CHECK(bad == 0, "%d of %d values: obc_divw(x, 1) differs from x / 1", bad, nv);
}

int main(void)
{
    div_by_one();
    random_curves();
    special_curves();
    min_max();
    return check_done();
}
