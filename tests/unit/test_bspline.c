/*
 * test_bspline.c - B-spline to Bézier conversion (methods/core/bspline.c).
 *
 * The reference is an independent evaluator built on the Cox-de Boor
 * recursion for the basis functions (not on knot insertion), applied to the
 * rational form sum w_i N_i P_i / sum w_i N_i.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "methods/core/bspline.h"

/* N_{i,q}(u) with the degree-0 functions chosen as 1 on span k only, so the
 * right end of the domain (a closed interval) is handled by picking k. */
static double basis(const double *U, int i, int q, double u, int k)
{
    if (q == 0)
        return i == k ? 1.0 : 0.0;
    double v = 0.0;
    double den = U[i + q] - U[i];
    if (den > 0)
        v += (u - U[i]) / den * basis(U, i, q - 1, u, k);
    den = U[i + q + 1] - U[i + 1];
    if (den > 0)
        v += (U[i + q + 1] - u) / den * basis(U, i + 1, q - 1, u, k);
    return v;
}

/* Point of the (rational) B-spline at u in span k (U[k] <= u <= U[k+1]). */
static void ref_point(int p, int npts, const double *U, const double (*P)[3], double u,
                      int k, double out[2])
{
    double s[3] = {0, 0, 0};
    for (int i = 0; i < npts; i++) {
        double b = basis(U, i, p, u, k) * P[i][2];
        s[0] += b * P[i][0];
        s[1] += b * P[i][1];
        s[2] += b;
    }
    out[0] = s[0] / s[2];
    out[1] = s[1] / s[2];
}

/* Converts, then compares the segments with the reference at `per` parameters
 * per span (ends included).  Returns the worst distance seen. */
static double compare_with_ref(const char *what, int p, int npts, const double *U,
                               const double (*P)[3], int per, int expect_nseg)
{
    ob_bez *seg = NULL;
    int nseg = -1;
    ob_err err = {""};
    int rc = ob_bspline_to_bezier(p, npts, U, P, &seg, &nseg, &err);
    CHECK(rc == 0, "%s: rc %d (%s)", what, rc, err.msg);
    CHECK(nseg == expect_nseg, "%s: %d segments, expected %d", what, nseg, expect_nseg);
    if (rc)
        return INFINITY;
    double worst = 0.0;
    int m = 0;
    for (int k = p; k < npts; k++) {
        if (!(U[k] < U[k + 1]))
            continue;
        CHECK(seg[m].deg == p, "%s: segment %d has degree %d", what, m, seg[m].deg);
        for (int j = 0; j <= per; j++) {
            double t = (double)j / per;
            double u = U[k] + t * (U[k + 1] - U[k]);
            double a[2], b[2];
            ref_point(p, npts, U, P, u, k, a);
            ob_bez_point(&seg[m], t, b);
            worst = fmax(worst, hypot(a[0] - b[0], a[1] - b[1]));
        }
        m++;
    }
    free(seg);
    return worst;
}

/* Deterministic pseudo-random numbers in [lo, hi). */
static unsigned long long rng_state = 88172645463325252ULL;
static double rnd(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) / 9007199254740992.0;
}

static const double ex2[7][3] = {
    {-3.01619, 2.34143, 1},   {-3.97193, -2.20842, 1}, {-1.07045, 0.0722807, 1},
    {0.319568, -2.77522, 1},  {-0.152767, 2.299, 1},   {2.92416, -0.939865, 1},
    {2.8027, 3.02775, 1},
};

static void test_single_span(void)
{
    /* clamped, one span: the control points are the Bézier points */
    for (int p = 1; p <= 7; p += 2) {
        double U[2 * 8], P[8][3];
        for (int i = 0; i <= p; i++) {
            U[i] = -1.5;
            U[p + 1 + i] = 2.0;
            P[i][0] = rnd(-5, 5);
            P[i][1] = rnd(-5, 5);
            P[i][2] = (p == 5) ? rnd(0.5, 2) : 1.0;
        }
        ob_bez *seg = NULL;
        int nseg = 0;
        ob_err err = {""};
        int rc = ob_bspline_to_bezier(p, p + 1, U, (const double(*)[3])P, &seg, &nseg, &err);
        CHECK(rc == 0 && nseg == 1, "single span p=%d: rc %d nseg %d", p, rc, nseg);
        if (rc)
            continue;
        CHECK(seg[0].deg == p, "degree %d", seg[0].deg);
        CHECK(seg[0].rational == (p == 5), "rational flag %d for p=%d", seg[0].rational, p);
        for (int i = 0; i <= p; i++) {
            double c[2];
            ob_bez_ctrl(&seg[0], i, c);
            CHECK_NEAR(c[0], P[i][0], 1e-14, "single span x");
            CHECK_NEAR(c[1], P[i][1], 1e-14, "single span y");
            CHECK_NEAR(ob_bez_weight(&seg[0], i), P[i][2], 1e-14, "single span w");
        }
        free(seg);
    }
}

static void test_uniform_cubic(void)
{
    const double U[11] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    double worst = compare_with_ref("uniform cubic", 3, 7, U, ex2, 250, 4);
    CHECK(worst <= 1e-12, "uniform cubic: max deviation %g", worst);

    /* the closed form of a uniform cubic span, as a second reference */
    ob_bez *seg = NULL;
    int nseg = 0;
    ob_err err = {""};
    CHECK(ob_bspline_to_bezier(3, 7, U, ex2, &seg, &nseg, &err) == 0, "%s", err.msg);
    for (int s = 0; s < nseg; s++) {
        const double *P0 = ex2[s], *P1 = ex2[s + 1], *P2 = ex2[s + 2], *P3 = ex2[s + 3];
        CHECK(!seg[s].rational, "uniform cubic segment %d marked rational", s);
        for (int c = 0; c < 2; c++) {
            double want[4] = {(P0[c] + 4 * P1[c] + P2[c]) / 6, (2 * P1[c] + P2[c]) / 3,
                              (P1[c] + 2 * P2[c]) / 3, (P1[c] + 4 * P2[c] + P3[c]) / 6};
            for (int i = 0; i < 4; i++) {
                CHECK_NEAR(seg[s].h[i][c], want[i], 1e-14, "uniform cubic closed form");
                CHECK(seg[s].h[i][2] == 1.0, "weight not exactly 1");
            }
        }
    }

    /* C2 at the joints: equal span lengths, so the control polygons'
     * first and second differences must agree */
    for (int s = 0; s + 1 < nseg; s++) {
        const double(*a)[3] = seg[s].h, (*b)[3] = seg[s + 1].h;
        for (int c = 0; c < 2; c++) {
            CHECK_NEAR(a[3][c], b[0][c], 1e-14, "C0 at joint");
            CHECK_NEAR(a[3][c] - a[2][c], b[1][c] - b[0][c], 1e-14, "C1 at joint");
            CHECK_NEAR(a[3][c] - 2 * a[2][c] + a[1][c], b[2][c] - 2 * b[1][c] + b[0][c], 1e-14,
                       "C2 at joint");
        }
    }
    free(seg);
}

static void test_non_uniform(void)
{
    /* cubic, unclamped, interior multiplicities 1..3: spans [1,2], [2,3.5],
     * [3.5,4], [4,6]; two empty spans at 3.5 */
    const double U[13] = {0, 0.5, 1, 1, 2, 3.5, 3.5, 3.5, 4, 6, 7, 7.25, 9};
    double P[9][3];
    for (int i = 0; i < 9; i++) {
        P[i][0] = rnd(-3, 3);
        P[i][1] = rnd(-3, 3);
        P[i][2] = 1.0;
    }
    double worst = compare_with_ref("non-uniform cubic", 3, 9, U, (const double(*)[3])P, 200, 4);
    CHECK(worst <= 1e-12, "non-uniform cubic: max deviation %g", worst);

    /* the same with weights */
    for (int i = 0; i < 9; i++)
        P[i][2] = rnd(0.3, 3.0);
    worst = compare_with_ref("non-uniform rational cubic", 3, 9, U, (const double(*)[3])P, 200, 4);
    CHECK(worst <= 1e-12, "non-uniform rational cubic: max deviation %g", worst);

    /* clamped quintic with distinct random interior knots, random weights */
    double V[20], Q[14][3];
    for (int i = 0; i <= 5; i++) {
        V[i] = -2.0;
        V[14 + i] = 5.0;
    }
    double u = -2.0;
    for (int i = 6; i < 14; i++) {
        u += rnd(0.1, 1.0) * 7.0 / 9.0;
        V[i] = u;
    }
    for (int i = 0; i < 14; i++) {
        Q[i][0] = rnd(-10, 10);
        Q[i][1] = rnd(-10, 10);
        Q[i][2] = rnd(0.5, 2.0);
    }
    worst = compare_with_ref("clamped rational quintic", 5, 14, V, (const double(*)[3])Q, 100, 9);
    CHECK(worst <= 1e-12, "clamped rational quintic: max deviation %g", worst);

    /* unclamped quadratic, non-uniform, polynomial */
    const double W[9] = {-1, 0, 0.25, 1, 3, 3.1, 4, 4, 8};
    double R[6][3];
    for (int i = 0; i < 6; i++) {
        R[i][0] = rnd(-1, 1);
        R[i][1] = rnd(-1, 1);
        R[i][2] = 1.0;
    }
    worst = compare_with_ref("unclamped quadratic", 2, 6, W, (const double(*)[3])R, 300, 4);
    CHECK(worst <= 1e-12, "unclamped quadratic: max deviation %g", worst);

    /* C2 of a non-uniform cubic with simple knots: derivatives scale with
     * the span lengths h (C' = 3 dP / h, C'' = 6 d2P / h^2) */
    const double K[11] = {0, 0.3, 1, 1.7, 2, 3.2, 3.6, 5, 5.5, 6, 7.5};
    ob_bez *seg = NULL;
    int nseg = 0;
    ob_err err = {""};
    CHECK(ob_bspline_to_bezier(3, 7, K, ex2, &seg, &nseg, &err) == 0 && nseg == 4,
          "non-uniform C2 conversion: %s", err.msg);
    for (int s = 0; s + 1 < nseg; s++) {
        double ha = K[3 + s + 1] - K[3 + s], hb = K[3 + s + 2] - K[3 + s + 1];
        const double(*a)[3] = seg[s].h, (*b)[3] = seg[s + 1].h;
        for (int c = 0; c < 2; c++) {
            CHECK_NEAR(a[3][c], b[0][c], 1e-13, "non-uniform C0");
            CHECK_NEAR(3 * (a[3][c] - a[2][c]) / ha, 3 * (b[1][c] - b[0][c]) / hb, 1e-12,
                       "non-uniform C1");
            CHECK_NEAR(6 * (a[3][c] - 2 * a[2][c] + a[1][c]) / (ha * ha),
                       6 * (b[2][c] - 2 * b[1][c] + b[0][c]) / (hb * hb), 1e-11,
                       "non-uniform C2");
        }
    }
    free(seg);
}

static void test_rational_circle(void)
{
    /* the full unit circle as a 9-point rational quadratic (weights 1, 1/sqrt2) */
    const double r = sqrt(0.5);
    const double P[9][3] = {{1, 0, 1},  {1, 1, r},   {0, 1, 1},  {-1, 1, r}, {-1, 0, 1},
                            {-1, -1, r}, {0, -1, 1}, {1, -1, r}, {1, 0, 1}};
    const double U[12] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
    double worst = compare_with_ref("circle", 2, 9, U, P, 100, 4);
    CHECK(worst <= 1e-12, "circle: max deviation %g", worst);
    ob_bez *seg = NULL;
    int nseg = 0;
    ob_err err = {""};
    CHECK(ob_bspline_to_bezier(2, 9, U, P, &seg, &nseg, &err) == 0, "%s", err.msg);
    for (int s = 0; s < nseg; s++) {
        CHECK(seg[s].rational == 1, "circle segment %d not rational", s);
        for (int j = 0; j <= 64; j++) {
            double q[2];
            ob_bez_point(&seg[s], j / 64.0, q);
            CHECK_NEAR(hypot(q[0], q[1]), 1.0, 1e-15, "circle radius");
        }
    }
    free(seg);

    /* a rational curve whose first span has unit weights only: that segment
     * is polynomial with weights exactly 1 */
    const double Q[5][3] = {{0, 0, 1}, {1, 2, 1}, {2, -1, 1}, {3, 1, 4}, {4, 0, 1}};
    const double V[8] = {0, 0, 0, 1, 2, 3, 3, 3};
    CHECK(ob_bspline_to_bezier(2, 5, V, Q, &seg, &nseg, &err) == 0 && nseg == 3,
          "mixed weights: %s", err.msg);
    if (nseg != 3)
        return;
    CHECK(!seg[0].rational && seg[1].rational && seg[2].rational, "mixed flags %d %d %d",
          seg[0].rational, seg[1].rational, seg[2].rational);
    for (int i = 0; i <= 2; i++)
        CHECK(seg[0].h[i][2] == 1.0, "unit weight %d is %.17g", i, seg[0].h[i][2]);
    free(seg);
}

static void bad(const char *what, int p, int npts, const double *U, const double (*P)[3])
{
    ob_bez *seg = (ob_bez *)&seg; /* must be reset to NULL */
    int nseg = 99;
    ob_err err = {""};
    int rc = ob_bspline_to_bezier(p, npts, U, P, &seg, &nseg, &err);
    CHECK(rc == -1, "%s: rc %d", what, rc);
    CHECK(err.msg[0] != '\0', "%s: no message", what);
    CHECK(seg == NULL && nseg == 0, "%s: outputs not reset", what);
}

static void test_bad_args(void)
{
    const double U[11] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    double P[7][3];
    memcpy(P, ex2, sizeof P);
    const double(*cp)[3] = (const double(*)[3])P;
    bad("degree 0", 0, 7, U, cp);
    bad("degree -1", -1, 7, U, cp);
    bad("degree too high", OB_MAX_IN_DEG + 1, 30, U, cp);
    bad("too few points", 3, 3, U, cp);
    bad("no points", 1, 0, U, cp);
    bad("NULL knots", 3, 7, NULL, cp);
    bad("NULL points", 3, 7, U, NULL);

    double V[11];
    memcpy(V, U, sizeof V);
    V[5] = 3.5;
    bad("decreasing knots", 3, 7, V, cp);
    memcpy(V, U, sizeof V);
    V[9] = NAN;
    bad("NaN knot", 3, 7, V, cp);
    V[9] = INFINITY;
    bad("Inf knot", 3, 7, V, cp);
    const double E[11] = {0, 1, 2, 3, 3, 3, 3, 3, 8, 9, 10};
    bad("empty domain", 3, 7, E, cp);

    P[2][0] = NAN;
    bad("NaN point", 3, 7, U, cp);
    memcpy(P, ex2, sizeof P);
    P[4][1] = -INFINITY;
    bad("Inf point", 3, 7, U, cp);
    memcpy(P, ex2, sizeof P);
    P[3][2] = 0.0;
    bad("zero weight", 3, 7, U, cp);
    P[3][2] = -1.0;
    bad("negative weight", 3, 7, U, cp);
    P[3][2] = NAN;
    bad("NaN weight", 3, 7, U, cp);
    P[3][2] = INFINITY;
    bad("Inf weight", 3, 7, U, cp);
    memcpy(P, ex2, sizeof P);

    /* missing outputs, and no room for a message: still -1, no crash */
    CHECK(ob_bspline_to_bezier(3, 7, U, cp, NULL, NULL, NULL) == -1, "NULL outputs");
    ob_bez *seg = NULL;
    int nseg = 0;
    CHECK(ob_bspline_to_bezier(0, 7, U, cp, &seg, &nseg, NULL) == -1, "NULL err");
    ob_err e;
    char want[64];
    snprintf(want, sizeof want, "bspline degree 0 outside 1..%d", (int)OB_MAX_IN_DEG);
    CHECK(ob_bspline_to_bezier(0, 7, U, cp, &seg, &nseg, &e) == -1 && strcmp(e.msg, want) == 0,
          "message '%s'", e.msg);
}

int main(void)
{
    test_single_span();
    test_uniform_cubic();
    test_non_uniform();
    test_rational_circle();
    test_bad_args();
    return check_done();
}
