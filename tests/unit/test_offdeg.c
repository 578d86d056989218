/*
 * test_offdeg.c - the exact offset degree (methods/core/offdeg.c): the seed's
 * figures (generic cubic 10, circle 4, parabola 6, cuspidal cubic 8), the
 * Pythagorean-hodograph test, gcd edge cases (a common factor of X, Y, W;
 * gcd(X, Y) != 1), polynomial against rational input, the circle exception
 * d = r, and the degree formula against an independent count of the
 * offset's intersections with random lines on random curves.
 */
#include <string.h>

#include "methods/core/offdeg.h"
#include "tests/check.h"
#include "tests/testlib.h"

/* A Bézier segment from homogeneous control points. */
static ob_bez hbez(int deg, const double (*h)[3])
{
    ob_bez b;
    memset(&b, 0, sizeof b);
    b.deg = deg;
    for (int i = 0; i <= deg; i++) {
        memcpy(b.h[i], h[i], sizeof b.h[i]);
        if (h[i][2] != 1.0)
            b.rational = 1;
    }
    return b;
}

static ob_offdeg degree_of(const ob_bez *b, const char *what)
{
    ob_offdeg od = {-1, -1, -1, -1, -1};
    char msg[160] = "";
    CHECK(ob_offset_degree(b, &od, msg, sizeof msg) == 0, "%s: %s", what, msg);
    return od;
}

/* (1 - t^2, 2t, 1 + t^2) in Bernstein form: the unit circle with rational
 * weights (1, 1, 2). */
static const double circle[3][3] = {{1, 0, 1}, {1, 1, 1}, {0, 2, 2}};

static void test_known(void)
{
    const double ex1[4][3] = {{-0.785938, 0.891849, 1}, {-0.993306, -0.59695, 1}, {0.3, -2.5, 1}, {0.9, -0.2, 1}};
    ob_bez b = hbez(3, ex1);
    ob_offdeg od = degree_of(&b, "generic cubic");
    CHECK(od.offset_degree == 10 && od.degree == 3 && od.tau == 2 && od.mu == 0 && !od.rational,
          "generic cubic: offset degree %d (n %d, tau %d, mu %d), rational %d; want 10, not rational", od.offset_degree,
          od.degree, od.tau, od.mu, od.rational);
    const double ph[4][3] = {{0, 0, 1}, {1, 0, 1}, {2, 1, 1}, {2, 3, 1}};
    b = hbez(3, ph);
    od = degree_of(&b, "PH cubic");
    CHECK(od.rational == 1 && od.offset_degree == 10, "PH cubic: rational %d, degree %d (want yes, 10: two quintics)",
          od.rational, od.offset_degree);
    b = hbez(2, circle);
    od = degree_of(&b, "circle");
    CHECK(od.offset_degree == 4 && od.rational == 1, "circle: %d, rational %d (want 4, yes)", od.offset_degree,
          od.rational);
    const double par[3][3] = {{0, 0, 1}, {0.5, 0, 1}, {1, 1, 1}};
    b = hbez(2, par);
    od = degree_of(&b, "parabola");
    CHECK(od.offset_degree == 6 && !od.rational, "parabola (t, t^2): %d (want 6)", od.offset_degree);
    /* (t^2, t^3) times 3: gcd(X, Y) = t^2, gcd(N1, N2) = t */
    const double cusp[4][3] = {{0, 0, 3}, {0, 0, 3}, {1, 0, 3}, {3, 3, 3}};
    b = hbez(3, cusp);
    od = degree_of(&b, "cuspidal cubic");
    CHECK(od.offset_degree == 8 && od.mu == 2, "cuspidal cubic (t^2, t^3): %d, mu %d (want 8, 2)", od.offset_degree,
          od.mu);
    const double line[4][3] = {{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}};
    b = hbez(3, line);
    od = degree_of(&b, "line");
    CHECK(od.offset_degree == 2 && od.degree == 1 && od.rational, "a line: %d, n %d (want 2: two lines, n 1)",
          od.offset_degree, od.degree);
    /* a line as a cubic with uneven collinear control points (datasets' `line`):
     * an improper parameterization, still two lines */
    const double uneven[4][3] = {{0, 0, 1}, {0.1, 0.05, 1}, {0.7, 0.35, 1}, {1, 0.5, 1}};
    b = hbez(3, uneven);
    od = degree_of(&b, "uneven line");
    CHECK(od.offset_degree == 2, "a line with uneven control points: %d (want 2)", od.offset_degree);
    /* the circle traced twice, (1 - t^4, 2t^2, 1 + t^4) (x 6): refused */
    const double twice[5][3] = {{6, 0, 6}, {6, 0, 6}, {6, 2, 6}, {6, 6, 6}, {0, 12, 12}};
    b = hbez(4, twice);
    char why[160] = "";
    ob_offdeg od2;
    CHECK(ob_offset_degree(&b, &od2, why, sizeof why) == -1 && strstr(why, "improper") && strstr(why, "2 times"),
          "an improper parameterization is refused: '%s'", why);
    const double point[3][3] = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
    b = hbez(2, point);
    ob_offdeg dummy;
    char msg[160] = "";
    CHECK(ob_offset_degree(&b, &dummy, msg, sizeof msg) == -1 && strstr(msg, "point"), "a point is refused: '%s'",
          msg);
}

/* gcd edge cases and polynomial vs rational input. */
static void test_gcd_and_rational(void)
{
    /* the circle times (1 + t): X, Y, W share a factor, removed first
     * (3 x the Bernstein coefficients of (1 - t^2)(1 + t), 2t(1 + t),
     * (1 + t^2)(1 + t): integers, so exact) */
    const double shared[4][3] = {{3, 0, 3}, {4, 2, 4}, {4, 6, 6}, {0, 12, 12}};
    ob_bez b = hbez(3, shared);
    ob_offdeg od = degree_of(&b, "circle with a common factor");
    CHECK(od.offset_degree == 4 && od.degree == 2, "circle x (1 + t): degree %d, n %d (want 4, 2)", od.offset_degree,
          od.degree);
    /* the same polynomial cubic with all weights 2: still polynomial */
    const double ex1w[4][3] = {{-2 * 0.785938, 2 * 0.891849, 2}, {-2 * 0.993306, -2 * 0.59695, 2}, {0.6, -5, 2},
                               {1.8, -0.4, 2}};
    b = hbez(3, ex1w);
    od = degree_of(&b, "cubic, weights 2");
    CHECK(od.offset_degree == 10, "polynomial cubic written with weights 2: %d (want 10)", od.offset_degree);
    /* a rational cubic in general position: n 3, tau 4, mu 0 */
    const double rat[4][3] = {{0, 0, 1}, {2, 2, 2}, {6, 0, 3}, {3, 1, 1}};
    b = hbez(3, rat);
    od = degree_of(&b, "rational cubic");
    CHECK(od.offset_degree == 14 && od.tau == 4, "rational cubic: %d, tau %d (want 14, 4)", od.offset_degree, od.tau);
}

/* The circle exception: at d = r the inner offset collapses to the centre. */
static void test_circle_exception(void)
{
    ob_bez b = hbez(2, circle);
    const long generic = ob_offset_degree_by_lines(&b, 1, 2, 7), at_r = ob_offset_degree_by_lines(&b, 1, 1, 7);
    CHECK(generic == 4, "circle, d = 1/2, by lines: %ld (want 4)", generic);
    CHECK(at_r == 2, "circle, d = r = 1, by lines: %ld (want 2: the offset is the circle of radius 2 and a point)",
          at_r);
}

/* The formula against the line count on random curves (dyadic coordinates,
 * polynomial and rational, degrees 2 to 5). */
static void test_against_lines(void)
{
    int bad = 0, n = 0;
    for (int c = 0; c < 40; c++) {
        double h[6][3];
        const int deg = 2 + c % 4, rational = c % 3 == 0;
        for (int i = 0; i <= deg; i++) {
            const double w = rational ? (double)(1 + (int)(urand() * 4)) : 1.0;
            h[i][0] = w * (double)((int)(urand() * 64) - 32) / 8.0;
            h[i][1] = w * (double)((int)(urand() * 64) - 32) / 8.0;
            h[i][2] = w;
        }
        ob_bez b = hbez(deg, (const double(*)[3])h);
        ob_offdeg od;
        char msg[160];
        if (ob_offset_degree(&b, &od, msg, sizeof msg) != 0)
            continue;
        n++;
        const long lines = ob_offset_degree_by_lines(&b, 3, 7, (unsigned long)c);
        if (lines != od.offset_degree && bad++ < 5)
            fprintf(stderr, "curve %d (degree %d%s): formula %d, lines %ld\n", c, deg, rational ? ", rational" : "",
                    od.offset_degree, lines);
    }
    CHECK(bad == 0 && n >= 35, "formula = intersection count on %d random curves: %d differ", n, bad);
}

int main(void)
{
    testlib_seed(0x0FF5E7DE6ULL);
    test_known();
    test_gcd_and_rational();
    test_circle_exception();
    test_against_lines();
    return check_done();
}
