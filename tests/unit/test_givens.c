/*
 * test_givens.c - the Givens least squares of methods/common/givens_ls.c:
 * solutions of known systems, and the banded, several-right-hand-side
 * path (ob_gls_add_band, bspline-lsq's fits) giving each right-hand side
 * exactly the bits of a dense one-right-hand-side problem of its own, with
 * rows in band order and in any order.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "methods/common/givens_ls.h"
#include "tests/check.h"

enum { N = 24, ROWS = 200, BAND = 4 };

static uint64_t rng = 0x9e3779b97f4a7c15u;
static double urand(void)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) * 0x1p-53;
}

/* An exactly solvable overdetermined system: the rows' residuals vanish. */
static void test_exact_solution(void)
{
    double mem[64], a[3], x[3];
    ob_gls g;
    ob_gls_init(&g, 3, mem);
    const double want[3] = {1.5, -2.0, 0.25};
    for (int i = 0; i < 10; i++) {
        a[0] = 1.0, a[1] = i, a[2] = (double)i * i;
        const double b = want[0] + want[1] * i + want[2] * i * i;
        ob_gls_add(&g, a, b, 1.0 + 0.1 * i);
    }
    CHECK(ob_gls_solve(&g, x, 1e-13) == 0, "the quadratic fit solves");
    for (int k = 0; k < 3; k++)
        CHECK(fabs(x[k] - want[k]) < 1e-12, "coefficient %d: %.17g, want %g", k, x[k], want[k]);
    CHECK(g.rss < 1e-20, "residual %.3g of an exact fit", g.rss);
    double mem2[64];
    ob_gls_init(&g, 3, mem2);
    a[0] = 1, a[1] = 2, a[2] = 0;
    ob_gls_add(&g, a, 1.0, 1.0);
    a[0] = 2, a[1] = 4, a[2] = 0;
    ob_gls_add(&g, a, 2.0, 1.0);
    CHECK(ob_gls_solve(&g, x, 1e-13) == -1, "a rank-deficient system is refused");
}

/* A random banded row: BAND nonzeros from column lo. */
static int band_row(double *a, int lo)
{
    memset(a, 0, N * sizeof *a);
    for (int r = 0; r < BAND; r++)
        a[lo + r] = urand() - 0.5;
    return lo;
}

/* Banded with two right-hand sides against two dense problems, bit for bit. */
static void test_band_matches_dense(int sorted)
{
    static double mb[N * (N + 2) + N], m0[N * (N + 1) + N], m1[N * (N + 1) + N];
    ob_gls gb, g0, g1;
    ob_gls_init_rhs(&gb, N, 2, mb);
    ob_gls_init(&g0, N, m0);
    ob_gls_init(&g1, N, m1);
    for (int i = 0; i < ROWS; i++) {
        double a[N], ad[N], b[2] = {urand(), urand() - 0.25};
        const int lo = sorted ? i * (N - BAND + 1) / ROWS : (int)(urand() * (N - BAND + 1));
        band_row(a, lo);
        const double w = 0.5 + urand();
        memcpy(ad, a, sizeof a);
        ob_gls_add(&g0, ad, b[0], w);
        memcpy(ad, a, sizeof a);
        ob_gls_add(&g1, ad, b[1], w);
        ob_gls_add_band(&gb, a, lo, lo + BAND - 1, b, w);
    }
    double x0[N], x1[N], y0[N], y1[N];
    const int r0 = ob_gls_solve(&g0, x0, 1e-13), r1 = ob_gls_solve(&g1, x1, 1e-13);
    const int s0 = ob_gls_solve_rhs(&gb, 0, y0, 1e-13), s1 = ob_gls_solve_rhs(&gb, 1, y1, 1e-13);
    CHECK(r0 == 0 && r1 == 0 && s0 == 0 && s1 == 0, "%s rows: all four solve (%d %d %d %d)",
          sorted ? "sorted" : "shuffled", r0, r1, s0, s1);
    int same = 1;
    for (int k = 0; k < N; k++)
        same &= memcmp(&x0[k], &y0[k], sizeof x0[k]) == 0 && memcmp(&x1[k], &y1[k], sizeof x1[k]) == 0;
    CHECK(same, "%s rows: the banded two-right-hand-side solutions have the dense ones' bits",
          sorted ? "sorted" : "shuffled");
    CHECK(fabs(gb.rss - (g0.rss + g1.rss)) <= 1e-12 * (g0.rss + g1.rss), "%s rows: rss %.17g is the sum of the two (%.17g)", sorted ? "sorted" : "shuffled",
          gb.rss, g0.rss + g1.rss);
}

int main(void)
{
    test_exact_solution();
    for (int rep = 0; rep < 20; rep++) {
        test_band_matches_dense(1);
        test_band_matches_dense(0);
    }
    return check_done();
}
