/*
 * test_curve.c - the curve core (methods/core/curve.c) and scalar Bernstein algebra
 * (methods/core/bernstein.c): evaluation, split, sub-segments, degree elevation,
 * normals, curvature, inflections, turning, products, elevation, roots,
 * binomials and control-point counting.
 *
 * Why: every method, the driver and every metric stand on these routines, so
 * each is compared with an independent computation written here: direct
 * Bernstein sums with binomials from Pascal's triangle (not de Casteljau), the
 * quotient rule in its own form, finite differences, closed forms (circle,
 * analytic inflection roots, polynomials with known roots converted from the
 * power basis).  Cases that could crash the library (buffer overruns) run in a
 * forked child so that a failure is counted instead of killing the program.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/core/bernstein.h"
#include "methods/core/curve.h"
#include "tests/check.h"
#include "tests/testlib.h"

/* ---- independent helpers (the shared ones are in testlib.h) ---------------- */

static double bsum(const double *a, int n, double t)
{
    double s = 0.0;
    for (int i = 0; i <= n; i++)
        s += a[i] * bern(n, i, t);
    return s;
}

static double ref_cross(const ob_bez *b, double t)  /* x'y'' - y'x'' */
{
    double o[3][2];
    ref_eval(b, t, 2, o);
    return o[1][0] * o[2][1] - o[1][1] * o[2][0];
}

static double ref_curvature(const ob_bez *b, double t)
{
    double o[3][2];
    ref_eval(b, t, 2, o);
    double sp = sqrt(o[1][0] * o[1][0] + o[1][1] * o[1][1]);
    return (o[1][0] * o[2][1] - o[1][1] * o[2][0]) / (sp * sp * sp);
}

static ob_bez random_bez(int deg, int rational)
{
    double xy[OB_MAX_DEG + 1][2], w[OB_MAX_DEG + 1];
    for (int i = 0; i <= deg; i++) {
        xy[i][0] = urange(-1, 1);
        xy[i][1] = urange(-1, 1);
        w[i] = rational ? urange(0.5, 2.0) : 1.0;
    }
    return make(deg, (const double (*)[2])xy, w);
}

/* Power-basis coefficients p[0..n] to Bernstein coefficients of degree n:
 * b_k = sum_{i<=k} C(k,i)/C(n,i) p_i. */
static void power_to_bern(const double *p, int n, double *b)
{
    for (int k = 0; k <= n; k++) {
        double s = 0.0;
        for (int i = 0; i <= k; i++)
            s += binom(k, i) / binom(n, i) * p[i];
        b[k] = s;
    }
}

/* prod (t - r_i) in the power basis; returns the degree. */
static int poly_from_roots(const double *r, int nr, double *p)
{
    p[0] = 1.0;
    for (int i = 0; i < nr; i++) {
        p[i + 1] = 0.0;
        for (int k = i + 1; k >= 1; k--)
            p[k] = p[k - 1] - r[i] * p[k];
        p[0] = -r[i] * p[0];
    }
    return nr;
}

/* Reference inflections: sign changes of x'y''-y'x'' from the reference
 * evaluator on a fine grid, refined by bisection. */
static int ref_inflections(const ob_bez *b, double *ts, int max)
{
    const int N = 20000;
    int n = 0;
    double t0 = 1e-9, f0 = ref_cross(b, t0);
    for (int k = 1; k <= N && n < max; k++) {
        double t1 = k == N ? 1.0 - 1e-9 : (double)k / N, f1 = ref_cross(b, t1);
        if ((f0 > 0) != (f1 > 0) && f0 != 0.0) {
            double lo = t0, hi = t1, flo = f0;
            for (int it = 0; it < 100 && hi - lo > 1e-16; it++) {
                double mid = 0.5 * (lo + hi), fm = ref_cross(b, mid);
                if ((fm > 0) == (flo > 0))
                    lo = mid, flo = fm;
                else
                    hi = mid;
            }
            ts[n++] = 0.5 * (lo + hi);
        }
        t0 = t1, f0 = f1;
    }
    return n;
}

/* ---- evaluation ------------------------------------------------------------ */

static void test_eval(void)
{
    static const double ts[] = {-0.05, -1e-3, 0.0, 0.1, 0.37, 0.5, 0.9, 1.0, 1.001, 1.05};
    const int nt = (int)(sizeof ts / sizeof ts[0]);
    for (int deg = 1; deg <= 10; deg++)
        for (int rat = 0; rat <= 1; rat++)
            for (int rep = 0; rep < 3; rep++) {
                ob_bez b = random_bez(deg, rat);
                double worst[3] = {0, 0, 0}, wt[3] = {0, 0, 0};
                int nder_ok = 1;
                for (int j = 0; j < nt; j++) {
                    double t = ts[j], o[3][2], r[3][2];
                    ob_bez_eval(&b, t, 2, o);
                    ref_eval(&b, t, 2, r);
                    for (int k = 0; k < 3; k++) {
                        double mag = 1.0 + hypot(r[k][0], r[k][1]);
                        double e = hypot(o[k][0] - r[k][0], o[k][1] - r[k][1]) / mag;
                        if (!(e <= worst[k]))
                            worst[k] = e, wt[k] = t;
                    }
                    /* lower nder gives the same leading values; ob_bez_point too */
                    double o0[1][2], o1[2][2], p[2];
                    ob_bez_eval(&b, t, 0, o0);
                    ob_bez_eval(&b, t, 1, o1);
                    ob_bez_point(&b, t, p);
                    if (o0[0][0] != o[0][0] || o0[0][1] != o[0][1] || o1[1][0] != o[1][0] ||
                        o1[1][1] != o[1][1] || p[0] != o[0][0] || p[1] != o[0][1])
                        nder_ok = 0;
                }
                /* tolerances relative to 1 + |value|; derivatives lose ~n, ~n^2 */
                const double tol[3] = {1e-13, 1e-13 * deg, 1e-13 * deg * deg};
                static const char *const what[3] = {"point", "1st derivative", "2nd derivative"};
                for (int k = 0; k < 3; k++)
                    CHECK(worst[k] <= tol[k], "deg %d %s: %s rel. error %.3g at t = %g", deg,
                          rat ? "rational" : "polynomial", what[k], worst[k], wt[k]);
                CHECK(nder_ok, "deg %d: nder = 0/1 and ob_bez_point disagree with nder = 2", deg);
            }

    /* the reference itself against central finite differences of its points */
    for (int deg = 2; deg <= 10; deg += 4)
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = random_bez(deg, rat);
            double worst1 = 0, worst2 = 0;
            for (double t = -0.05; t <= 1.05; t += 0.1) {
                const double h = 1e-4;
                double pm[2], p0[2], pp[2], o[3][2];
                ob_bez_point(&b, t - h, pm);
                ob_bez_point(&b, t, p0);
                ob_bez_point(&b, t + h, pp);
                ob_bez_eval(&b, t, 2, o);
                for (int c = 0; c < 2; c++) {
                    double d1 = (pp[c] - pm[c]) / (2 * h), d2 = (pp[c] - 2 * p0[c] + pm[c]) / (h * h);
                    worst1 = fmax(worst1, fabs(d1 - o[1][c]) / (1 + fabs(o[1][c])));
                    worst2 = fmax(worst2, fabs(d2 - o[2][c]) / (1 + fabs(o[2][c])));
                }
            }
            CHECK(worst1 < 1e-5 && worst2 < 1e-3, "deg %d rat %d: finite differences disagree (%.3g, %.3g)",
                  deg, rat, worst1, worst2);
        }

    /* closed form: the rational quarter circle is on the unit circle, also
     * slightly outside [0,1] */
    ob_bez q = quarter_circle(1.0, 0);
    double worst = 0;
    for (double t = -0.1; t <= 1.1; t += 0.01) {
        double p[2];
        ob_bez_point(&q, t, p);
        worst = fmax(worst, fabs(hypot(p[0], p[1]) - 1.0));
    }
    CHECK(worst < 1e-15 * 4, "quarter circle off the unit circle by %.3g", worst);
}

/* ---- split, sub-segment, elevation ----------------------------------------- */

static void test_split(void)
{
    static const int degs[] = {1, 2, 3, 5, 7, 10};
    static const double splits[] = {0.3, 0.5, 0.77, 1e-3};
    static const double ab[][2] = {{0, 1}, {0, 0.4}, {0.6, 1}, {0.25, 0.75}, {0.1, 0.11}, {0, 1e-3}};
    for (size_t di = 0; di < sizeof degs / sizeof degs[0]; di++)
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = random_bez(degs[di], rat);
            for (size_t si = 0; si < sizeof splits / sizeof splits[0]; si++) {
                const double t = splits[si];
                ob_bez L, R, L2;
                ob_bez_split(&b, t, &L, &R);
                ob_bez_split(&b, t, &L2, NULL);
                ob_bez_split(&b, t, NULL, NULL);  /* both outputs optional */
                double worst = 0;
                for (int k = 0; k <= 20; k++) {
                    double s = k / 20.0, pl[2], pr[2], rl[2], rr[2];
                    ob_bez_point(&L, s, pl);
                    ob_bez_point(&R, s, pr);
                    ref_point(&b, t * s, rl);
                    ref_point(&b, t + (1 - t) * s, rr);
                    worst = fmax(worst, fmax(dist2d(pl, rl), dist2d(pr, rr)));
                }
                CHECK(worst <= 1e-13, "split deg %d rat %d at %g: pieces off by %.3g", b.deg, rat, t, worst);
                CHECK(L.deg == b.deg && R.deg == b.deg && L.rational == b.rational && R.rational == b.rational,
                      "split keeps degree and rational flag");
                CHECK(memcmp(L.h[L.deg], R.h[0], sizeof L.h[0]) == 0, "split pieces share the joint exactly");
                CHECK(memcmp(&L, &L2, sizeof L) == 0, "left piece independent of the right pointer");
            }
            for (size_t ai = 0; ai < sizeof ab / sizeof ab[0]; ai++) {
                const double a = ab[ai][0], c = ab[ai][1];
                ob_bez S;
                ob_bez_subsegment(&b, a, c, &S);
                double worst = 0;
                for (int k = 0; k <= 20; k++) {
                    double s = k / 20.0, p[2], r[2];
                    ob_bez_point(&S, s, p);
                    ref_point(&b, a + (c - a) * s, r);
                    worst = fmax(worst, dist2d(p, r));
                }
                CHECK(worst <= 1e-13, "subsegment deg %d rat %d [%g,%g]: off by %.3g", b.deg, rat, a, c, worst);
                CHECK(S.deg == b.deg && S.rational == b.rational, "subsegment keeps degree and flag");
            }
        }
}

static void test_elevate(void)
{
    for (int deg = 1; deg <= 8; deg++)
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = random_bez(deg, rat);
            const int tos[3] = {deg, deg + 1, OB_MAX_DEG};
            for (int i = 0; i < 3; i++) {
                ob_bez e;
                int rc = ob_bez_elevate(&b, tos[i], &e);
                CHECK(rc == 0 && e.deg == tos[i] && e.rational == b.rational, "elevate %d -> %d: rc %d deg %d",
                      deg, tos[i], rc, e.deg);
                double worst = 0;
                for (int k = 0; k <= 40; k++) {
                    double t = -0.05 + 1.1 * k / 40.0, p[2], r[2];
                    ob_bez_point(&e, t, p);
                    ref_point(&b, t, r);
                    if (t >= 0 && t <= 1)
                        worst = fmax(worst, dist2d(p, r));
                }
                CHECK(worst <= 1e-13, "elevate %s %d -> %d: points off by %.3g", rat ? "rational" : "polynomial",
                      deg, tos[i], worst);
                /* end points are interpolated exactly (up to one rounding) */
                double p0[2], r0[2], p1[2], r1[2];
                ob_bez_ctrl(&e, 0, p0);
                ob_bez_ctrl(&b, 0, r0);
                ob_bez_ctrl(&e, e.deg, p1);
                ob_bez_ctrl(&b, b.deg, r1);
                CHECK(dist2d(p0, r0) <= 1e-15 && dist2d(p1, r1) <= 1e-15, "elevate keeps end points");
            }
            ob_bez out, before;
            memset(&out, 0x5a, sizeof out);
            before = out;
            CHECK(ob_bez_elevate(&b, OB_MAX_DEG + 1, &out) == -1, "elevate past OB_MAX_DEG must fail");
            CHECK(ob_bez_elevate(&b, deg - 1, &out) == -1, "elevate to a lower degree must fail");
            CHECK(memcmp(&out, &before, sizeof out) == 0, "failed elevate leaves out untouched");
        }
}

/* ---- normals and curvature --------------------------------------------------- */

static void test_normal(void)
{
    /* regular points: left of travel, unit length */
    for (int deg = 1; deg <= 7; deg += 2)
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = random_bez(deg, rat);
            double worst = 0, worst_len = 0;
            for (int k = 0; k <= 20; k++) {
                double t = k / 20.0, n[2], o[3][2];
                int rc = ob_bez_normal(&b, t, n);
                ref_eval(&b, t, 2, o);
                double sp = hypot(o[1][0], o[1][1]);
                double r[2] = {-o[1][1] / sp, o[1][0] / sp};
                worst = fmax(worst, rc == 0 ? dist2d(n, r) : INFINITY);
                worst_len = fmax(worst_len, fabs(hypot(n[0], n[1]) - 1.0));
            }
            CHECK(worst <= 1e-12, "normal deg %d rat %d: off (-y',x')/|C'| by %.3g", deg, rat, worst);
            CHECK(worst_len <= 4e-16, "normal deg %d rat %d: not unit (%.3g)", deg, rat, worst_len);
        }
    /* left of travel, concretely: going +x, the normal is +y */
    {
        double xy[2][2] = {{0, 0}, {2, 0}}, n[2];
        ob_bez b = make(1, (const double (*)[2])xy, NULL);
        ob_bez_normal(&b, 0.5, n);
        CHECK(fabs(n[0]) < 1e-16 && fabs(n[1] - 1) < 1e-16, "normal of +x travel is (%g,%g), not (0,1)", n[0], n[1]);
    }

    /* collapsed end legs: the limit direction from inside the segment */
    {
        double xy[4][2] = {{0, 0}, {0, 0}, {1, 0.5}, {2, -0.3}};
        double w[4] = {1, 2, 0.7, 1};
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = make(3, (const double (*)[2])xy, rat ? w : NULL);
            double n0[2], ne[2];
            int rc = ob_bez_normal(&b, 0.0, n0);
            ob_bez_normal(&b, 1e-7, ne);
            CHECK(rc == 0 && dist2d(n0, ne) < 1e-6, "collapsed start leg (rat %d): n(0) = (%g,%g), n(1e-7) = (%g,%g)",
                  rat, n0[0], n0[1], ne[0], ne[1]);
            /* the limit tangent at a collapsed start is P2 - P0 */
            double l = hypot(1, 0.5), r[2] = {-0.5 / l, 1 / l};
            CHECK(dist2d(n0, r) < 1e-12, "collapsed start (rat %d): expected left of P2-P0", rat);
        }
        double ye[4][2] = {{0, 0}, {1, 0.5}, {2, -0.3}, {2, -0.3}};
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = make(3, (const double (*)[2])ye, rat ? w : NULL);
            double n1[2], ne[2];
            int rc = ob_bez_normal(&b, 1.0, n1);
            ob_bez_normal(&b, 1.0 - 1e-7, ne);
            CHECK(rc == 0 && dist2d(n1, ne) < 1e-6, "collapsed end leg (rat %d): n(1) = (%g,%g), n(1-1e-7) = (%g,%g)",
                  rat, n1[0], n1[1], ne[0], ne[1]);
            double l = hypot(1, 0.8), r[2] = {0.8 / l, 1 / l};  /* left of P3 - P1 = (1,-0.8) */
            CHECK(dist2d(n1, r) < 1e-12, "collapsed end (rat %d): expected left of P3-P1", rat);
        }
    }

    /* point-like segments: no direction anywhere */
    {
        double xy[4][2] = {{0.1, 0.3}, {0.1, 0.3}, {0.1, 0.3}, {0.1, 0.3}};
        double w[4] = {1, 2, 0.7, 1.3};
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = make(3, (const double (*)[2])xy, rat ? w : NULL);
            static const double ts[] = {0.0, 0.1, 0.37, 0.5, 0.9, 1.0};
            for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) {
                double n[2] = {7, 7};
                int rc = ob_bez_normal(&b, ts[i], n);
                CHECK(rc == -1 && n[0] == 0 && n[1] == 0,
                      "point-like %s segment at t = %g: rc %d, n = (%.17g,%.17g); expected -1 and (0,0)",
                      rat ? "rational" : "polynomial", ts[i], rc, n[0], n[1]);
            }
        }
    }
}

static void test_curvature(void)
{
    ob_bez q = quarter_circle(1.0, 0), qc = quarter_circle(1.0, 1);
    double w1 = 0, w2 = 0;
    for (int k = 0; k <= 20; k++) {
        double t = k / 20.0;
        w1 = fmax(w1, fabs(ob_bez_curvature(&q, t) - 1.0));
        w2 = fmax(w2, fabs(ob_bez_curvature(&qc, t) + 1.0));
    }
    CHECK(w1 <= 1e-12, "quarter circle curvature off 1 by %.3g", w1);
    CHECK(w2 <= 1e-12, "clockwise quarter circle curvature off -1 by %.3g", w2);
    static const double rs[] = {2.5, 0.01, 300.0};
    for (int i = 0; i < 3; i++) {
        ob_bez s = quarter_circle(rs[i], 0);
        double w = 0;
        for (int k = 0; k <= 20; k++)
            w = fmax(w, fabs(ob_bez_curvature(&s, k / 20.0) * rs[i] - 1.0));
        CHECK(w <= 1e-12, "circle of radius %g: relative curvature error %.3g", rs[i], w);
    }
    /* offset point of the circle: left normal points to the centre */
    double p[2];
    ob_bez_offset_point(&q, 0.3, 0.25, p);
    CHECK_NEAR(hypot(p[0], p[1]), 0.75, 1e-15, "offset point of the unit quarter circle at d = 0.25");
    /* general curves against the reference */
    for (int deg = 2; deg <= 9; deg++)
        for (int rat = 0; rat <= 1; rat++) {
            ob_bez b = random_bez(deg, rat);
            double w = 0;
            for (int k = 0; k <= 20; k++) {
                double t = k / 20.0, r = ref_curvature(&b, t);
                w = fmax(w, fabs(ob_bez_curvature(&b, t) - r) / (1 + fabs(r)));
            }
            CHECK(w <= 1e-10, "curvature deg %d rat %d: relative error %.3g", deg, rat, w);
        }
    /* a straight line has zero curvature */
    double xy[4][2] = {{0, 0}, {1, 0.5}, {2.5, 1.25}, {3, 1.5}};
    ob_bez l = make(3, (const double (*)[2])xy, NULL);
    CHECK(fabs(ob_bez_curvature(&l, 0.3)) < 1e-15, "straight cubic curvature %g", ob_bez_curvature(&l, 0.3));
}

/* ---- inflections ----------------------------------------------------------------- */

static void rotate(double (*xy)[2], int n, double ang)
{
    const double c = cos(ang), s = sin(ang);
    for (int i = 0; i < n; i++) {
        double x = xy[i][0], y = xy[i][1];
        xy[i][0] = c * x - s * y + 0.3;
        xy[i][1] = s * x + c * y - 0.2;
    }
}

/* Quintic graph (5t, y(t)) with y'' = c (t-a)(t-b)(t+1.5): x'y''-y'x'' = 5 y''. */
static ob_bez quintic_with_ypp_roots(double a, double b, double ang)
{
    double r[3] = {a, b, -1.5}, q[4], p[6] = {0}, yb[6], xy[6][2];
    poly_from_roots(r, 3, q);
    for (int i = 0; i <= 3; i++)
        p[i + 2] = 4.0 * q[i] / ((i + 1.0) * (i + 2.0));
    power_to_bern(p, 5, yb);
    for (int i = 0; i <= 5; i++)
        xy[i][0] = i, xy[i][1] = yb[i];
    rotate(xy, 6, ang);
    return make(5, (const double (*)[2])xy, NULL);
}

static int cmp_roots(const double *got, int ng, const double *exp, int ne, double tol)
{
    if (ng != ne)
        return 0;
    for (int i = 0; i < ng; i++)
        if (!(fabs(got[i] - exp[i]) <= tol))
            return 0;
    return 1;
}

static int child_rational_high_degree(int deg)
{
    double xy[4][2] = {{0, 0}, {1, 1}, {2, -1}, {3, 0}}, w[4] = {1, 2, 0.5, 1};
    ob_bez b = make(3, (const double (*)[2])xy, w), e;
    if (ob_bez_elevate(&b, deg, &e) != 0)
        return 3;
    double exp[8], got[8];
    int ne = ref_inflections(&b, exp, 8);
    int ng = ob_bez_inflections(&e, got, 8);
    return cmp_roots(got, ng, exp, ne, 1e-8) ? 0 : 2;
}
static int child_rat22(void) { return child_rational_high_degree(22); }
static int child_rat24(void) { return child_rational_high_degree(24); }
static int child_rat32(void) { return child_rational_high_degree(OB_MAX_DEG); }

/* inflections of cubics: symmetric and asymmetric S (one), convex (none). */
static void inflections_cubics(void)
{
    double ts[16];
    /* symmetric S cubic: y = 3t(1-t)(1-2t), x = 3t: y'' = 0 at t = 1/2 */
    {
        double xy[4][2] = {{0, 0}, {1, 1}, {2, -1}, {3, 0}};
        ob_bez b = make(3, (const double (*)[2])xy, NULL);
        int n = ob_bez_inflections(&b, ts, 16);
        CHECK(n == 1 && fabs(ts[0] - 0.5) < 1e-14, "S cubic: %d inflections, first %.17g (expected 0.5)", n,
              n ? ts[0] : NAN);
    }
    /* asymmetric S cubic: root of 6(x2y3-x3y2)t^2 + 6(x1y3-x3y1)t + 2(x1y2-x2y1)
     * with the power coefficients x1 = 3(P1-P0), x2 = 3(P0-2P1+P2), x3 = P3-3P2+3P1-P0 */
    {
        double xy[4][2] = {{0, 0}, {1, 2}, {3, -1}, {4, 1}};
        double pc[2][4];
        for (int c = 0; c < 2; c++) {
            pc[c][1] = 3 * (xy[1][c] - xy[0][c]);
            pc[c][2] = 3 * (xy[0][c] - 2 * xy[1][c] + xy[2][c]);
            pc[c][3] = xy[3][c] - 3 * xy[2][c] + 3 * xy[1][c] - xy[0][c];
        }
        double A = 6 * (pc[0][2] * pc[1][3] - pc[0][3] * pc[1][2]);
        double B = 6 * (pc[0][1] * pc[1][3] - pc[0][3] * pc[1][1]);
        double Cc = 2 * (pc[0][1] * pc[1][2] - pc[0][2] * pc[1][1]);
        double disc = sqrt(B * B - 4 * A * Cc), qq = -0.5 * (B + copysign(disc, B));
        double r1 = qq / A, r2 = Cc / qq, exp[2];
        int ne = 0;
        if (r1 > 0 && r1 < 1)
            exp[ne++] = r1;
        if (r2 > 0 && r2 < 1)
            exp[ne++] = r2;
        if (ne == 2 && exp[0] > exp[1]) {
            double tmp = exp[0];
            exp[0] = exp[1], exp[1] = tmp;
        }
        ob_bez b = make(3, (const double (*)[2])xy, NULL);
        int n = ob_bez_inflections(&b, ts, 16);
        CHECK(ne == 1, "test setup: asymmetric S cubic should have one inflection (%d)", ne);
        CHECK(cmp_roots(ts, n, exp, ne, 1e-13), "asymmetric S cubic: %d inflections, first %.17g, expected %.17g", n,
              n ? ts[0] : NAN, exp[0]);
    }
    /* convex cubic: none */
    {
        double xy[4][2] = {{0, 0}, {1, 1}, {2, 1}, {3, 0}};
        ob_bez b = make(3, (const double (*)[2])xy, NULL);
        CHECK(ob_bez_inflections(&b, ts, 16) == 0, "convex cubic has no inflection");
    }
}

/* no spurious inflections on straight segments of degree 2..5, both kinds. */
static void inflections_straight(void)
{
    double ts[16];
    /* straight segments (round-off off the line): none */
    {
        static const double s[6] = {0, 0.37, 1.21, 2.0, 2.9, 3.3};
        for (int deg = 2; deg <= 5; deg++)
            for (int trial = 0; trial < 8; trial++) {
                double ang = 0.1 + 0.7 * trial, dx = cos(ang) * 1.7, dy = sin(ang) * 1.7, xy[6][2];
                for (int i = 0; i <= deg; i++)
                    xy[i][0] = 0.31 + s[i] * dx, xy[i][1] = -0.77 + s[i] * dy;
                double w[6] = {1, 1.7, 0.6, 1.2, 0.9, 1};
                for (int rat = 0; rat <= 1; rat++) {
                    ob_bez b = make(deg, (const double (*)[2])xy, rat ? w : NULL);
                    int n = ob_bez_inflections(&b, ts, 16);
                    CHECK(n == 0, "straight deg %d rat %d angle %g: %d spurious inflections (first %.17g)", deg, rat,
                          ang, n, n ? ts[0] : NAN);
                }
            }
    }
}

/* a quintic's two inflections found in several orientations. */
static void inflections_quintic(void)
{
    double ts[16];
    /* quintic with two inflections at 0.25 and 0.6, in several orientations */
    for (int k = 0; k < 5; k++) {
        ob_bez b = quintic_with_ypp_roots(0.25, 0.6, 1.3 * k);
        double exp[2] = {0.25, 0.6};
        int n = ob_bez_inflections(&b, ts, 16);
        CHECK(cmp_roots(ts, n, exp, 2, 1e-12), "quintic (rotation %d): %d inflections (%.17g, %.17g)", k, n,
              n > 0 ? ts[0] : NAN, n > 1 ? ts[1] : NAN);
    }
}

/* a double root of the curvature (no sign change) is not an inflection. */
static void inflections_double_root(void)
{
    double ts[16];
    /* double root of the curvature (touches zero, no sign change): not reported.
     * y'' = K (t-r)^2 (t+3/2) integrated twice, scaled by K so that every
     * control point is an integer (computed exactly with rational arithmetic),
     * x = 5 s t: the curve is represented exactly, so its x'y''-y'x'' = 5 s y''
     * has an exact double root at r and never changes sign. */
    {
        static const struct {
            double r;
            double y[6];
            double s;
        } dbl[] = {
            {0.5, {0, 0, 9, 17, 18, 34}, 7},
            {0.625, {0, 0, 225, 485, 622, 894}, 179},
            {0.4, {0, 0, 36, 56, 43, 165}, 33},
            {0.3, {0, 0, 27, 27, 6, 230}, 46},
        };
        for (size_t i = 0; i < sizeof dbl / sizeof dbl[0]; i++) {
            double xy[6][2];
            for (int k = 0; k <= 5; k++)
                xy[k][0] = dbl[i].s * k, xy[k][1] = dbl[i].y[k];
            ob_bez b = make(5, (const double (*)[2])xy, NULL);
            /* test setup: the reference cross product touches zero at r */
            double cm = ref_cross(&b, dbl[i].r - 0.01), c0 = ref_cross(&b, dbl[i].r), cp = ref_cross(&b, dbl[i].r + 0.01);
            CHECK(cm > 0 && cp > 0 && fabs(c0) < 1e-9 * cm, "test setup: double root at %g", dbl[i].r);
            int n = ob_bez_inflections(&b, ts, 16);
            CHECK(n == 0, "exact double root of x'y''-y'x'' at %g: %d inflections reported (%.17g, %.17g)", dbl[i].r,
                  n, n > 0 ? ts[0] : NAN, n > 1 ? ts[1] : NAN);
            int far = 0;
            for (int k = 0; k < n; k++)
                if (fabs(ref_cross(&b, ts[k])) > 1e-6 * cm)
                    far++;
            CHECK(far == 0, "double root at %g: %d reported inflections where x'y''-y'x'' is far from 0 "
                  "(at %.17g: %g, vs %g at r - 0.01)", dbl[i].r, far, ts[n > 0 ? n - 1 : 0], ref_cross(&b, ts[n > 0 ? n - 1 : 0]), cm);
        }
    }
}

/* rational cubic and quintic: inflections where the reference's curvature changes sign. */
static void inflections_rational(void)
{
    double ts[16];
    /* rational: det(P,P',P'') against the sign changes of the curvature */
    {
        double xy[4][2] = {{0, 0}, {1, 1}, {2, -1}, {3, 0}}, w[4] = {1, 2, 0.5, 1};
        ob_bez b = make(3, (const double (*)[2])xy, w);
        double exp[16];
        int ne = ref_inflections(&b, exp, 16), n = ob_bez_inflections(&b, ts, 16);
        CHECK(ne == 1, "test setup: rational S cubic has one inflection (%d)", ne);
        CHECK(cmp_roots(ts, n, exp, ne, 1e-10), "rational S cubic: %d inflections, first %.17g, expected %.17g", n,
              n ? ts[0] : NAN, ne ? exp[0] : NAN);
        /* the weights move the inflection: it is not the polynomial one (0.5) */
        CHECK(ne == 1 && fabs(exp[0] - 0.5) > 1e-3, "rational weights move the inflection");
    }
    {
        ob_bez p = quintic_with_ypp_roots(0.25, 0.6, 0.4), b;
        memset(&b, 0, sizeof b);
        b.deg = 5;
        const double w[6] = {1, 1.3, 0.8, 1.5, 0.9, 1};
        for (int i = 0; i <= 5; i++) {
            double c[2];
            ob_bez_ctrl(&p, i, c);
            ob_bez_set(&b, i, c[0], c[1], w[i]);
        }
        double exp[16];
        int ne = ref_inflections(&b, exp, 16), n = ob_bez_inflections(&b, ts, 16);
        CHECK(ne == 2, "test setup: rational quintic has two inflections (%d)", ne);
        CHECK(cmp_roots(ts, n, exp, ne, 1e-10), "rational quintic: %d inflections (%.17g, %.17g) expected (%.17g, %.17g)",
              n, n > 0 ? ts[0] : NAN, n > 1 ? ts[1] : NAN, exp[0], exp[1]);
    }
}

/* inflections: max limits the output; high rational degrees are right and safe. */
static void inflections_limits(void)
{
    /* max limits the output */
    {
        ob_bez b = quintic_with_ypp_roots(0.25, 0.6, 0.0);
        double one[1];
        CHECK(ob_bez_inflections(&b, one, 1) == 1 && fabs(one[0] - 0.25) < 1e-12, "max = 1 gives the first one");
    }
    /* degrees the segment type allows (up to OB_MAX_DEG), rational: same
     * inflection as the cubic they were elevated from; run in a child because a
     * buffer overrun would take the whole program down */
    CHECK(in_child(child_rat22) == 0, "rational degree 22 inflections wrong or crashed");
    int rc24 = in_child(child_rat24), rc32 = in_child(child_rat32);
    CHECK(rc24 == 0, "rational degree 24 (elevated S cubic): child status %d (2 = wrong result, "
                     "1/>=128 = crash or sanitizer report)", rc24);
    CHECK(rc32 == 0, "rational degree %d (elevated S cubic): child status %d", OB_MAX_DEG, rc32);
}

/* ob_bez_inflections, case by case. */
static void test_inflections(void)
{
    inflections_cubics();
    inflections_straight();
    inflections_quintic();
    inflections_double_root();
    inflections_rational();
    inflections_limits();
}


/* ---- turning ------------------------------------------------------------------- */

static double tangent_angle_ref(const ob_bez *b, double t)
{
    double o[3][2];
    ref_eval(b, t, 2, o);
    return atan2(o[1][1], o[1][0]);
}

static void test_turn(void)
{
    ob_bez q = quarter_circle(1.0, 0), qc = quarter_circle(1.0, 1);
    CHECK_NEAR(ob_bez_turn(&q, 64), OB_PI / 2, 1e-9, "quarter circle turn");
    CHECK_NEAR(ob_bez_turn(&q, 0), OB_PI / 2, 1e-9, "quarter circle turn, default samples");
    CHECK_NEAR(ob_bez_turn(&qc, 64), OB_PI / 2, 1e-9, "clockwise quarter circle turn (>= 0)");
    double t = ob_bez_turn_param(&q, OB_PI / 4);
    CHECK_NEAR(t, 0.5, 1e-9, "quarter circle: 45 degrees at the symmetric parameter");
    CHECK_NEAR(tangent_angle_ref(&q, t) - tangent_angle_ref(&q, 0), OB_PI / 4, 1e-9,
               "quarter circle: tangent turned by 45 degrees at turn_param");
    double tcw = ob_bez_turn_param(&qc, OB_PI / 4);
    CHECK_NEAR(tcw, 0.5, 1e-9, "clockwise quarter circle: turn_param");
    /* asymmetric convex cubic: turn = difference of end tangent angles */
    double xy[4][2] = {{0, 0}, {0.2, 1}, {1.5, 1.6}, {3, 1.2}};
    ob_bez b = make(3, (const double (*)[2])xy, NULL);
    double a0 = tangent_angle_ref(&b, 0), a1 = tangent_angle_ref(&b, 1);
    CHECK_NEAR(ob_bez_turn(&b, 64), fabs(a1 - a0), 1e-9, "convex cubic turn");
    static const double angs[] = {0.1, 0.5, 1.0, 1.5};
    for (int i = 0; i < 4; i++) {
        double tp = ob_bez_turn_param(&b, angs[i]);
        CHECK(tp > 0 && tp < 1, "turn_param in (0,1)");
        CHECK_NEAR(fabs(tangent_angle_ref(&b, tp) - a0), angs[i], 1e-9, "convex cubic: tangent turn at turn_param");
    }
}

/* ---- Bernstein algebra ------------------------------------------------------------ */

/* ob_binom against Pascal's triangle and a few known values. */
static void bernstein_binomials(void)
{
    /* binomials against Pascal's triangle */
    int bad = 0;
    for (int n = 0; n <= 40; n++)
        for (int k = -1; k <= n + 1; k++)
            if (ob_binom(n, k) != binom(n, k))
                bad++;
    CHECK(bad == 0, "ob_binom differs from Pascal's triangle in %d entries (n <= 40)", bad);
    CHECK(ob_binom(0, 0) == 1 && ob_binom(5, 2) == 10 && ob_binom(10, 5) == 252 && ob_binom(4, 5) == 0 &&
              ob_binom(4, -1) == 0, "small binomials");
}

/* ob_bern_mul, ob_bern_eval and ob_bern_elevate against pointwise values. */
static void bernstein_products_elevation(void)
{
    /* products and elevation against pointwise values */
    for (int m = 0; m <= 12; m += 1)
        for (int n = 0; n <= 12; n += 3) {
            double a[16], b[16], c[32];
            for (int i = 0; i <= m; i++)
                a[i] = urange(-2, 2);
            for (int i = 0; i <= n; i++)
                b[i] = urange(-2, 2);
            ob_bern_mul(a, m, b, n, c);
            double w = 0, we = 0;
            for (int k = 0; k <= 40; k++) {
                double t = -0.05 + 1.1 * k / 40;
                double ref = bsum(a, m, t) * bsum(b, n, t);
                w = fmax(w, fabs(bsum(c, m + n, t) - ref) / (1 + fabs(ref)));
                we = fmax(we, fabs(ob_bern_eval(a, m, t) - bsum(a, m, t)));
            }
            CHECK(w <= 1e-13, "ob_bern_mul deg %d x %d: relative error %.3g", m, n, w);
            CHECK(we <= 1e-13, "ob_bern_eval deg %d: error %.3g", m, we);
            int r = m + n;
            double e[32];
            ob_bern_elevate(a, m, r, e);
            double wl = 0;
            for (int k = 0; k <= 40; k++) {
                double t = k / 40.0;
                wl = fmax(wl, fabs(bsum(e, r, t) - bsum(a, m, t)));
            }
            CHECK(wl <= 1e-13, "ob_bern_elevate %d -> %d: error %.3g", m, r, wl);
            CHECK(e[0] == a[0] && e[r] == a[m], "ob_bern_elevate keeps the end coefficients");
        }
}

/* ob_bern_roots on polynomials with known roots, also scaled and negated. */
static void bernstein_known_roots(void)
{
    /* roots of polynomials with known roots */
    static const struct {
        int nr;
        double r[8];
        int ne;
        double e[8];
        double tol;
        const char *what;
    } cases[] = {
        {3, {0.2, 0.5, 0.8}, 3, {0.2, 0.5, 0.8}, 1e-14, "three simple roots (one at the midpoint)"},
        {3, {0.25, 0.75, 0.125}, 3, {0.125, 0.25, 0.75}, 1e-14, "roots at subdivision points"},
        {2, {0.3, 0.3 + 1e-6}, 2, {0.3, 0.3 + 1e-6}, 1e-9, "two roots 1e-6 apart"},
        {4, {0.61, 0.61 + 1e-6, 0.1, 0.9}, 4, {0.1, 0.61, 0.61 + 1e-6, 0.9}, 1e-9, "close pair among others"},
        {2, {1e-6, 1 - 1e-6}, 2, {1e-6, 1 - 1e-6}, 1e-13, "roots near 0 and 1"},
        {3, {1e-9, 0.5 + 1e-3, 1 - 1e-9}, 3, {1e-9, 0.501, 1 - 1e-9}, 1e-13, "roots very near 0 and 1"},
        {3, {-0.5, 0.4, 1.5}, 1, {0.4}, 1e-14, "roots outside (0,1) are not reported"},
        {3, {0.4, 0.4, 0.7}, 1, {0.7}, 1e-12, "a double root (no sign change) is not reported"},
        {3, {0.3, 0.3, 0.3}, 1, {0.3}, 1e-4, "a triple root is reported once"},
        {7, {0.05, 0.15, 0.33, 0.47, 0.52, 0.71, 0.96}, 7, {0.05, 0.15, 0.33, 0.47, 0.52, 0.71, 0.96}, 1e-12,
         "seven roots"},
        {2, {0.0, 1.0}, 0, {0}, 0, "roots at the ends are not in the open interval"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double p[16], bc[16], got[16];
        int n = poly_from_roots(cases[i].r, cases[i].nr, p);
        power_to_bern(p, n, bc);
        int ng = ob_bern_roots(bc, n, got, 16);
        CHECK(cmp_roots(got, ng, cases[i].e, cases[i].ne, cases[i].tol),
              "ob_bern_roots, %s: %d roots (%.17g, %.17g, ...), expected %d", cases[i].what, ng,
              ng > 0 ? got[0] : NAN, ng > 1 ? got[1] : NAN, cases[i].ne);
        /* the same polynomial scaled and negated has the same roots */
        for (int k = 0; k <= n; k++)
            bc[k] *= -1e-7;
        int ng2 = ob_bern_roots(bc, n, got, 16);
        CHECK(cmp_roots(got, ng2, cases[i].e, cases[i].ne, cases[i].tol), "ob_bern_roots (scaled), %s: %d roots",
              cases[i].what, ng2);
    }
}

/* ob_bern_roots reports no root at an exact double root (no sign change). */
static void bernstein_double_roots(void)
{
    /* exact double roots: K (t-r)^2 (t+3/2) with integer Bernstein coefficients
     * (computed with rational arithmetic), degree 3 and the same elevated to 7.
     * The polynomial is >= 0 on [0,1]: no sign change, so no root; anything
     * reported must at least be a zero of the polynomial. */
    {
        static const struct {
            double r;
            int n;
            double b[8];
        } dr[] = {
            {0.625, 3, {225, 35, -123, 135}},
            {0.625, 7, {7875, 5025, 2335, 189, -1029, -935, 855, 4725}},
            {0.375, 3, {27, -15, -25, 125}},
            {0.375, 7, {945, 315, -155, -337, -103, 675, 2125, 4375}},
            {0.5, 3, {9, -1, -7, 15}},
            {0.5, 7, {315, 165, 35, -51, -69, 5, 195, 525}},
            {0.4, 3, {36, -16, -33, 135}},
            {0.4, 7, {252, 96, -25, -81, -42, 122, 441, 945}},
            {0.3, 3, {27, -27, -21, 245}},
            {0.3, 7, {189, 27, -75, -77, 61, 379, 917, 1715}},
            {0.7, 3, {441, 119, -183, 135}},
            {0.7, 7, {3087, 2121, 1175, 369, -177, -343, -9, 945}},
        };
        for (size_t i = 0; i < sizeof dr / sizeof dr[0]; i++) {
            double got[8], mag = 0;
            int ng = ob_bern_roots(dr[i].b, dr[i].n, got, 8), notzero = 0;
            for (int k = 0; k <= dr[i].n; k++)
                mag = fmax(mag, fabs(dr[i].b[k]));
            for (int k = 0; k < ng; k++)
                if (fabs(bsum(dr[i].b, dr[i].n, got[k])) > 1e-9 * mag)
                    notzero++;
            CHECK(ng == 0, "exact double root at %g (degree %d): %d roots reported (%.17g, %.17g)", dr[i].r, dr[i].n,
                  ng, ng > 0 ? got[0] : NAN, ng > 1 ? got[1] : NAN);
            CHECK(notzero == 0, "exact double root at %g (degree %d): %d reported roots are not zeros (p(%.17g) = %g)",
                  dr[i].r, dr[i].n, notzero, got[ng > 0 ? ng - 1 : 0], bsum(dr[i].b, dr[i].n, got[ng > 0 ? ng - 1 : 0]));
        }
    }
}

/* the test's own power-to-Bernstein conversion; max and degenerate inputs of ob_bern_roots. */
static void bernstein_roots_limits(void)
{
    /* the reference conversion itself */
    {
        double r[3] = {0.2, 0.5, 0.8}, p[4], bc[4];
        poly_from_roots(r, 3, p);
        power_to_bern(p, 3, bc);
        CHECK(fabs(bsum(bc, 3, 0.2)) < 1e-16 && fabs(bsum(bc, 3, 0.9) - 0.7 * 0.4 * 0.1) < 1e-15,
              "test setup: power-to-Bernstein conversion");
    }
    /* max limits the output; constant and degree 0 have none */
    {
        double r[3] = {0.2, 0.5, 0.8}, p[4], bc[4], got[2];
        poly_from_roots(r, 3, p);
        power_to_bern(p, 3, bc);
        int ng = ob_bern_roots(bc, 3, got, 2);
        CHECK(ng == 2 && fabs(got[0] - 0.2) < 1e-14 && fabs(got[1] - 0.5) < 1e-14, "max = 2: %d roots", ng);
        double c1[1] = {3.0}, cz[4] = {0, 0, 0, 0};
        CHECK(ob_bern_roots(c1, 0, got, 2) == 0, "degree 0 has no roots");
        CHECK(ob_bern_roots(cz, 3, got, 2) == 0, "the zero polynomial reports no roots");
    }
}

/* ob_bern_roots on random polynomials with known roots, within their condition. */
static void bernstein_random_roots(void)
{
    /* random polynomials with random known roots, degree up to 12, built as
     * products of the linear factors (-r)B0 + (1-r)B1 (Bernstein products by
     * the binomial formula written here); each root is compared within its
     * condition number: |p|_B(r) / |p'(r)| with p'(r_i) = prod_{j != i} (r_i - r_j) */
    int badr = 0;
    for (int trial = 0; trial < 300; trial++) {
        int nr = 1 + trial % 12;
        double r[16], bc[16], tmp[16], got[16], e[16];
        int ne = 0;
        for (int i = 0; i < nr; i++) {
            r[i] = urange(-0.5, 1.5);
            if (r[i] > 1e-6 && r[i] < 1 - 1e-6)
                e[ne++] = r[i];
        }
        for (int i = 1; i < ne; i++)  /* insertion sort */
            for (int j = i; j > 0 && e[j - 1] > e[j]; j--) {
                double sw = e[j];
                e[j] = e[j - 1], e[j - 1] = sw;
            }
        bc[0] = 1.0;
        for (int i = 0; i < nr; i++) {  /* multiply degree i by degree 1 */
            const double f[2] = {-r[i], 1.0 - r[i]};
            for (int k = 0; k <= i + 1; k++) {
                double s = 0.0;
                for (int j = 0; j <= 1; j++)
                    if (k - j >= 0 && k - j <= i)
                        s += binom(i, k - j) * binom(1, j) * bc[k - j] * f[j];
                tmp[k] = s / binom(i + 1, k);
            }
            memcpy(bc, tmp, (size_t)(i + 2) * sizeof *bc);
        }
        int ng = ob_bern_roots(bc, nr, got, 16), ok = ng == ne;
        for (int i = 0; ok && i < ne; i++) {
            double dp = 1.0, mag = 0.0;
            for (int j = 0; j < nr; j++)
                if (r[j] != e[i])
                    dp *= e[i] - r[j];
            for (int k = 0; k <= nr; k++)
                mag += fabs(bc[k]) * bern(nr, k, e[i]);
            double tol = 1e-13 + 100.0 * (nr + 1) * 2.2e-16 * mag / fabs(dp);
            if (!(fabs(got[i] - e[i]) <= tol))
                ok = 0;
        }
        if (!ok && badr++ < 3) {
            fprintf(stderr, "  random roots trial %d: degree %d, %d roots expected, %d found\n", trial, nr, ne, ng);
            for (int q = 0; q < ng && q < ne; q++)
                fprintf(stderr, "    got %.17g expected %.17g\n", got[q], e[q]);
        }
    }
    CHECK(badr == 0, "ob_bern_roots wrong on %d random polynomials with known roots", badr);
}

/* Bernstein arithmetic and roots, case by case (urange draws in the same order). */
static void test_bernstein(void)
{
    bernstein_binomials();
    bernstein_products_elevation();
    bernstein_known_roots();
    bernstein_double_roots();
    bernstein_roots_limits();
    bernstein_random_roots();
}


static void test_count(void)
{
    int d3[8] = {3, 3, 3, 3, 3, 3, 3, 3}, d7[4] = {7, 7, 7, 7}, mixed[3] = {2, 3, 5};
    for (int k = 1; k <= 8; k++)
        CHECK(ob_count_ctrl_points(d3, k) == 3L * k + 1, "%d cubic segments count %ld", k, ob_count_ctrl_points(d3, k));
    CHECK(ob_count_ctrl_points(d7, 4) == 29, "4 segments of degree 7 count 29");
    CHECK(ob_count_ctrl_points(mixed, 3) == 11, "degrees 2,3,5 count 11");
    CHECK(ob_count_ctrl_points(d3, 0) == 0, "0 segments count 0");
    CHECK(ob_count_ctrl_points(NULL, 0) == 0, "0 segments (NULL) count 0");
}

/* ob_bez_offset_point (one evaluation) has the bits of ob_bez_point plus d
 * times ob_bez_normal (two), on random curves, collapsed legs, a cusp of
 * the base and a point-like segment. */
static void test_offset_point(void)
{
    ob_bez v[40];
    int nv = 0;
    for (int deg = 1; deg <= 9; deg++)
        for (int rat = 0; rat <= 1; rat++)
            v[nv++] = random_bez(deg, rat);
    double legs[4][2] = {{0, 0}, {0, 0}, {1, 0.5}, {2, 2}}, cusp[4][2] = {{0, 0}, {1, 1}, {0, 1}, {1, 0}};
    double dot[3][2] = {{1, 1}, {1, 1 + 1e-15}, {1, 1}};
    v[nv++] = make(3, (const double (*)[2])legs, NULL);
    v[nv++] = make(3, (const double (*)[2])cusp, NULL);
    v[nv++] = make(2, (const double (*)[2])dot, NULL);
    int bad = 0, runs = 0;
    for (int i = 0; i < nv; i++)
        for (int k = 0; k <= 64; k++) {
            const double t = k / 64.0, d = k % 2 ? -0.75 : 0.3;
            double p[2], c[2], n[2];
            ob_bez_offset_point(&v[i], t, d, p);
            ob_bez_point(&v[i], t, c);
            ob_bez_normal(&v[i], t, n);
            const double q[2] = {c[0] + d * n[0], c[1] + d * n[1]};
            bad += memcmp(p, q, sizeof p) != 0;
            runs++;
        }
    CHECK(bad == 0, "ob_bez_offset_point differs from point + d normal at %d of %d parameters", bad, runs);
}

int main(void)
{
    testlib_seed(0x9E3779B97F4A7C15ULL);
    test_eval();
    test_split();
    test_elevate();
    test_normal();
    test_offset_point();
    test_curvature();
    test_inflections();
    test_turn();
    test_bernstein();
    test_count();
    return check_done();
}
