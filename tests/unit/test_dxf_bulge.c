/*
 * test_dxf_bulge.c - the DXF reader's arcs against the analytic circle or
 * line they stand for (issue 48 class 7): a polyline segment's bulge from
 * 0 and the denormals through 1e-200, 1e-16, 1e-8, 0.1, +-1 (a half
 * circle) to 1e3 (nearly the whole circle), either sign, each on chords
 * at the origin and far from it; and ARCs of a huge radius over a tiny
 * angle.  The built pieces must lie on the true arc to a few ulps of the
 * figure's size, start and end at the vertices, and pass through the
 * arc's middle (so the right one of the two arcs of that circle).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/approx_read.h"
#include "tests/check.h"

/* Signed distance of X to the arc's circle (to the line when b = 0),
 * to first order, without its centre: with M the chord's middle, u the
 * chord P->Q, n its left normal (u rotated a quarter turn), L = |u|, the
 * circle is b (|X - M|^2 - L^2/4) = (L/2)(1 - b^2) (X - M).n / L scaled by
 * 2 / (L (1 + b^2)) (the gradient's length on the circle).  Long double:
 * the test's own round-off stays under the reader's. */
static long double circle_dist(const double P[2], const double Q[2], double b, const double X[2])
{
    const long double ux = (long double)Q[0] - P[0], uy = (long double)Q[1] - P[1];
    const long double L2 = ux * ux + uy * uy, L = sqrtl(L2);
    const long double mx = X[0] - ((long double)P[0] + Q[0]) / 2, my = X[1] - ((long double)P[1] + Q[1]) / 2;
    const long double lb = b, dn = (-uy * mx + ux * my) / L; /* (X - M).n */
    const long double f = lb * (mx * mx + my * my - L2 / 4) / L - (1 - lb * lb) * dn / 2;
    return f * 2 / (1 + lb * lb);
}

static double bez_at(const ob_bez *z, double t, int k)
{
    double p[2];
    ob_bez_point(z, t, p);
    return p[k];
}

/* Reads an LWPOLYLINE from P to Q with bulge b; checks its pieces. */
static void check_bulge(const double P[2], const double Q[2], double b)
{
    char text[512];
    snprintf(text, sizeof text, "0\nLWPOLYLINE\n90\n2\n10\n%.17g\n20\n%.17g\n42\n%.17g\n10\n%.17g\n20\n%.17g\n", P[0],
             P[1], b, Q[0], Q[1]);
    ob_approx a = {0};
    ob_err err = {""};
    const int rc = ob_approx_read_dxf(text, strlen(text), "b.dxf", &a, &err);
    CHECK(rc == 0 && a.n >= 1 && a.n <= 4, "bulge %g: %d pieces (%s)", b, a.n, err.msg);
    if (rc != 0 || a.n < 1) {
        ob_approx_free(&a);
        return;
    }
    const double L = hypot(Q[0] - P[0], Q[1] - P[1]);
    const double size = fmax(fmax(fmax(fabs(P[0]), fabs(P[1])), fmax(fabs(Q[0]), fabs(Q[1]))),
                             L * fmax(1.0, fabs(b)));
    const double tol = 8.0 * DBL_EPSILON * size;
    long double worst = 0.0L;
    for (int k = 0; k < a.n; k++)
        for (int i = 0; i <= 64; i++) {
            const double X[2] = {bez_at(&a.v[k].approx, i / 64.0, 0), bez_at(&a.v[k].approx, i / 64.0, 1)};
            worst = fmaxl(worst, fabsl(circle_dist(P, Q, b, X)));
        }
    CHECK(worst <= tol, "bulge %.17g, chord (%g,%g)-(%g,%g): %d pieces off the arc by %Lg (tol %g)", b, P[0], P[1],
          Q[0], Q[1], a.n, worst, tol);
    const ob_bez *first = &a.v[0].approx, *last = &a.v[a.n - 1].approx;
    CHECK(bez_at(first, 0, 0) == P[0] && bez_at(first, 0, 1) == P[1] && bez_at(last, 1, 0) == Q[0] &&
              bez_at(last, 1, 1) == Q[1],
          "bulge %g: the pieces start and end at the vertices", b);
    /* the arc's middle: the chord's middle moved right of P->Q by the
     * sagitta L b / 2 (left for b < 0) */
    const double apex[2] = {(P[0] + Q[0]) / 2 + (Q[1] - P[1]) * b / 2, (P[1] + Q[1]) / 2 - (Q[0] - P[0]) * b / 2};
    double mid[2];
    if (a.n % 2)
        ob_bez_point(&a.v[a.n / 2].approx, 0.5, mid);
    else
        ob_bez_point(&a.v[a.n / 2].approx, 0.0, mid);
    CHECK(hypot(mid[0] - apex[0], mid[1] - apex[1]) <= 4 * tol, "bulge %g: middle (%.17g, %.17g), want (%.17g, %.17g)", b,
          mid[0], mid[1], apex[0], apex[1]);
    ob_approx_free(&a);
}

static void test_bulges(void)
{
    static const double bulges[] = {0.1, 1e-8, 1e-16, 1e-20, 1e-200, 0.0, 4.9406564584124654e-324, 2.2250738585072014e-310,
                                    -0.3, -1e-16, 1.0, -1.0, 0.41421356237309503, 0.5, 1.5, -1.5, 3.0, 1e3, -1e3};
    static const double chords[][4] = {{0, 0, 1, 0}, {1.5, -2, -0.25, 3}, {1e6, 1e6 + 1, 1e6 + 3, 1e6 - 2},
                                       {-7, 5e-3, -7 + 1e-9, 5e-3 + 2e-9}};
    for (size_t c = 0; c < sizeof chords / sizeof *chords; c++)
        for (size_t i = 0; i < sizeof bulges / sizeof *bulges; i++)
            check_bulge(chords[c], chords[c] + 2, bulges[i]);
}

/* An ARC of radius 1e12 over 1e-9 degrees, centred far below: close to a
 * line, its points within a few ulps of 1e12 of the true arc. */
static void test_huge_arc(void)
{
    static const double radii[] = {1e12, 1e15};
    for (size_t i = 0; i < sizeof radii / sizeof *radii; i++) {
        const double r = radii[i];
        char text[256];
        snprintf(text, sizeof text, "0\nARC\n10\n0\n20\n%.17g\n40\n%.17g\n50\n90\n51\n90.000000001\n", -r, r);
        ob_approx a = {0};
        ob_err err = {""};
        const int rc = ob_approx_read_dxf(text, strlen(text), "a.dxf", &a, &err);
        CHECK(rc == 0 && a.n == 1, "ARC of radius %g: %d pieces (%s)", r, a.n, err.msg);
        long double worst = 0.0L;
        for (int k = 0; rc == 0 && k < a.n; k++)
            for (int j = 0; j <= 64; j++) {
                const long double x = bez_at(&a.v[k].approx, j / 64.0, 0), y = bez_at(&a.v[k].approx, j / 64.0, 1);
                worst = fmaxl(worst, fabsl(sqrtl(x * x + (y + r) * (y + r)) - r));
            }
        CHECK(worst <= 8 * DBL_EPSILON * r, "ARC of radius %g: off the circle by %Lg", r, worst);
        ob_approx_free(&a);
    }
}

int main(void)
{
    test_bulges();
    test_huge_arc();
    return check_done();
}
