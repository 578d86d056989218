/*
 * test_metrics.c - the CPU error metrics (methods/metric*.c): bound, radial,
 * normal and hausdorff, and the ob_measure dispatcher.
 *
 * Why: every number in the result tables is one of these errors, and the
 * OpenCL kernels are checked against this CPU code, so it has to be right on
 * its own terms.  The checks use cases with known answers (a straight segment
 * and its translated offset line, the rational quarter circle and its exact
 * offset circle), the properties that define each metric (the bound bounds the
 * radial error; normal and hausdorff do not depend on the approximation's
 * parameterization; hausdorff does not depend on its direction), convergence in
 * the sample count, and an independent brute-force Hausdorff distance on
 * 4000 x 4000 dense samples.  Points, derivatives and the exact offset are
 * evaluated here by direct Bernstein sums, not by the library.
 */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernels/metric_core.h"
#include "methods/core/curve.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"
#include "tests/check.h"
#include "tests/testlib.h"

/* ---- independent helpers (the shared ones are in testlib.h) ---------------- */

/* Bernstein product written here (binomial formula). */
static void bmul(const double *a, int m, const double *b, int n, double *c)
{
    for (int k = 0; k <= m + n; k++) {
        double s = 0.0;
        for (int i = 0; i <= m; i++)
            if (k - i >= 0 && k - i <= n)
                s += binom(m, i) * binom(n, k - i) * a[i] * b[k - i];
        c[k] = s / binom(m + n, k);
    }
}

/* A(phi(s)) with phi(s) = s + alpha s (1-s), a monotone map of [0,1] onto
 * itself for |alpha| < 1; phi = (0, (1+alpha)/2, 1) in Bernstein form.  The
 * homogeneous coordinates compose exactly: sum_i h_i C(m,i) phi^i (1-phi)^(m-i),
 * a Bézier segment of degree 2m. */
static ob_bez reparam(const ob_bez *a, double alpha)
{
    const int m = a->deg;
    const double phi[3] = {0, (1 + alpha) / 2, 1}, psi[3] = {1, (1 - alpha) / 2, 0};
    double pw[OB_MAX_DEG + 1][2 * OB_MAX_DEG + 1], qw[OB_MAX_DEG + 1][2 * OB_MAX_DEG + 1];
    pw[0][0] = qw[0][0] = 1.0;
    for (int i = 1; i <= m; i++) {
        bmul(pw[i - 1], 2 * (i - 1), phi, 2, pw[i]);
        bmul(qw[i - 1], 2 * (i - 1), psi, 2, qw[i]);
    }
    ob_bez r;
    memset(&r, 0, sizeof r);
    r.deg = 2 * m;
    r.rational = a->rational;
    for (int i = 0; i <= m; i++) {
        double term[2 * OB_MAX_DEG + 1];
        bmul(pw[i], 2 * i, qw[m - i], 2 * (m - i), term);
        for (int k = 0; k <= 2 * m; k++)
            for (int c = 0; c < 3; c++)
                r.h[k][c] += binom(m, i) * a->h[i][c] * term[k];
    }
    return r;
}

/* Degree elevation written here: q_k = sum_i C(m,i) C(r-m,k-i)/C(r,k) p_i. */
static ob_bez elevate_ref(const ob_bez *a, int r)
{
    ob_bez e;
    memset(&e, 0, sizeof e);
    e.deg = r;
    e.rational = a->rational;
    const int m = a->deg;
    for (int k = 0; k <= r; k++)
        for (int i = 0; i <= m; i++)
            for (int c = 0; c < 3; c++)
                e.h[k][c] += binom(m, i) * binom(r - m, k - i) / binom(r, k) * a->h[i][c];
    return e;
}

/* A random base cubic, gently curved, and a signed distance d with
 * |d kappa| < 0.5 everywhere (no cusps in the offset). */
static ob_bez random_base(int rational, double *d)
{
    for (;;) {
        double xy[4][2] = {{0, 0},
                           {urange(0.15, 0.45), urange(-0.4, 0.4)},
                           {urange(0.55, 0.85), urange(-0.4, 0.4)},
                           {1 + urange(-0.1, 0.1), urange(-0.2, 0.2)}};
        double w[4] = {1, urange(0.6, 1.6), urange(0.6, 1.6), 1};
        ob_bez b = make(3, (const double (*)[2])xy, rational ? w : NULL);
        *d = (urand() < 0.5 ? -1 : 1) * urange(0.03, 0.12);
        double kmax = 0;
        for (int k = 0; k <= 200; k++)
            kmax = fmax(kmax, fabs(ob_bez_curvature(&b, k / 200.0)));
        if (kmax * fabs(*d) < 0.5)
            return b;
    }
}

/* An approximation of the d-offset of `base` of degree m: the elevated base
 * with each control point moved by d N at its Greville parameter, plus noise;
 * optionally rational (weights perturbed). */
static ob_bez rough_offset(const ob_bez *base, double d, int m, double noise, int rational)
{
    ob_bez e = elevate_ref(base, m), a;
    memset(&a, 0, sizeof a);
    a.deg = m;
    for (int i = 0; i <= m; i++) {
        double p[2], n[2], t = (double)i / m, w = e.h[i][2];
        ob_bez_ctrl(&e, i, p);
        ob_bez_normal(base, t, n);
        if (rational)
            w *= urange(0.85, 1.15);
        ob_bez_set(&a, i, p[0] + d * n[0] + noise * urange(-1, 1), p[1] + d * n[1] + noise * urange(-1, 1),
                   rational || base->rational ? w : 1.0);
    }
    if (rational || base->rational)
        a.rational = 1;
    return a;
}

static double measure(ob_metric m, const ob_bez *base, const ob_bez *approx, double d, int S, double *t)
{
    ob_errval e = {NAN, NAN, 0.0};
    int rc = ob_measure(m, base, approx, d, S, &e);
    if (t)
        *t = e.t;
    return rc == 0 ? e.err : NAN;
}

/* Independent normal-metric error at base parameter t: the intersections of
 * the normal line with A by a dense scan of (A(u)-P) x N over u in
 * [-0.25, 1.25] and bisection; the one nearest to t counts. */
static double ref_normal_err(const ob_bez *base, const ob_bez *approx, double d, double t)
{
    double o[2][2], q[2];
    ref_eval(base, t, 1, o);
    const double *P = o[0], *D = o[1];
    double sp = hypot(D[0], D[1]), N[2] = {-D[1] / sp, D[0] / sp};
    const int M = 3000;
    double best = INFINITY, ub = NAN, u0 = -0.25, g0;
    ref_point(approx, u0, q);
    g0 = (q[0] - P[0]) * N[1] - (q[1] - P[1]) * N[0];
    for (int j = 1; j <= M; j++) {
        double u1 = -0.25 + 1.5 * j / M, g1;
        ref_point(approx, u1, q);
        g1 = (q[0] - P[0]) * N[1] - (q[1] - P[1]) * N[0];
        if ((g0 <= 0) != (g1 <= 0)) {
            double lo = u0, hi = u1, glo = g0;
            for (int it = 0; it < 80; it++) {
                double mid = 0.5 * (lo + hi), gm;
                ref_point(approx, mid, q);
                gm = (q[0] - P[0]) * N[1] - (q[1] - P[1]) * N[0];
                if ((gm <= 0) == (glo <= 0))
                    lo = mid, glo = gm;
                else
                    hi = mid;
            }
            double r = 0.5 * (lo + hi);
            if (fabs(r - t) < best)
                best = fabs(r - t), ub = r;
        }
        u0 = u1, g0 = g1;
    }
    if (isnan(ub))
        return NAN;
    ref_point(approx, ub, q);
    return fabs((q[0] - P[0]) * N[0] + (q[1] - P[1]) * N[1] - d);
}

/* A densely sampled curve as a polyline, with bounding boxes of blocks of
 * samples so that the exhaustive nearest-sample search can skip blocks that
 * cannot contain a nearer sample (the result is that of the full scan). */
enum { NB = 4000, BLK = 40, NBLK = NB / BLK };
typedef struct {
    double x[NB], y[NB];
    double lo[NBLK][2], hi[NBLK][2];
} polyline;

static void poly_boxes(polyline *p)
{
    for (int b = 0; b < NBLK; b++) {
        /* a block covers samples [b*BLK, (b+1)*BLK] (shared end sample) */
        int j0 = b * BLK, j1 = (b + 1) * BLK < NB ? (b + 1) * BLK : NB - 1;
        p->lo[b][0] = p->hi[b][0] = p->x[j0];
        p->lo[b][1] = p->hi[b][1] = p->y[j0];
        for (int j = j0; j <= j1; j++) {
            p->lo[b][0] = fmin(p->lo[b][0], p->x[j]), p->hi[b][0] = fmax(p->hi[b][0], p->x[j]);
            p->lo[b][1] = fmin(p->lo[b][1], p->y[j]), p->hi[b][1] = fmax(p->hi[b][1], p->y[j]);
        }
    }
}

/* Distance from Q to the polyline: the nearest sample over all samples, then
 * the two segments next to it.  `hint` is a sample index to start from. */
static double poly_dist(const polyline *p, const double Q[2], int hint)
{
    double best = INFINITY;
    int jb = 0;
    for (int j = hint - BLK / 2; j <= hint + BLK / 2; j++) {  /* warm start */
        if (j < 0 || j >= NB)
            continue;
        double dx = p->x[j] - Q[0], dy = p->y[j] - Q[1], e = dx * dx + dy * dy;
        if (e < best)
            best = e, jb = j;
    }
    for (int b = 0; b < NBLK; b++) {
        double ex = fmax(0, fmax(p->lo[b][0] - Q[0], Q[0] - p->hi[b][0]));
        double ey = fmax(0, fmax(p->lo[b][1] - Q[1], Q[1] - p->hi[b][1]));
        if (ex * ex + ey * ey > best)
            continue;
        int j1 = (b + 1) * BLK < NB ? (b + 1) * BLK : NB - 1;
        for (int j = b * BLK; j <= j1; j++) {
            double dx = p->x[j] - Q[0], dy = p->y[j] - Q[1], e = dx * dx + dy * dy;
            if (e < best)
                best = e, jb = j;
        }
    }
    double dmin = sqrt(best);
    for (int s = jb - 1; s <= jb; s++) {
        if (s < 0 || s + 1 >= NB)
            continue;
        double vx = p->x[s + 1] - p->x[s], vy = p->y[s + 1] - p->y[s], wx = Q[0] - p->x[s], wy = Q[1] - p->y[s];
        double l2 = vx * vx + vy * vy, h = l2 > 0 ? (wx * vx + wy * vy) / l2 : 0;
        h = fmin(1, fmax(0, h));
        dmin = fmin(dmin, hypot(wx - h * vx, wy - h * vy));
    }
    return dmin;
}

/* Distance from Q to the curve u -> X(u), X = A (d = 0) or the exact
 * d-offset of A, u in [0,1]: nearest of 2001 samples, then golden-section
 * minimization of |Q - X(u)|^2 between its neighbours (accurate to round-off,
 * unlike a polyline). */
static void curve_at(const ob_bez *b, double d, double u, double X[2])
{
    if (d == 0)
        ref_point(b, u, X);
    else
        ref_offset(b, u, d, X);
}
static double curve_dist(const ob_bez *b, double d, const double Q[2])
{
    const int M = 2000;
    double best = INFINITY;
    int jb = 0;
    for (int j = 0; j <= M; j++) {
        double X[2];
        curve_at(b, d, (double)j / M, X);
        double e = hypot(X[0] - Q[0], X[1] - Q[1]);
        if (e < best)
            best = e, jb = j;
    }
    const double g = 0.6180339887498949;
    double lo = (double)(jb > 0 ? jb - 1 : 0) / M, hi = (double)(jb < M ? jb + 1 : M) / M;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), X[2], f1, f2;
    curve_at(b, d, x1, X);
    f1 = hypot(X[0] - Q[0], X[1] - Q[1]);
    curve_at(b, d, x2, X);
    f2 = hypot(X[0] - Q[0], X[1] - Q[1]);
    for (int it = 0; it < 80; it++) {
        if (f1 < f2) {
            hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo);
            curve_at(b, d, x1, X);
            f1 = hypot(X[0] - Q[0], X[1] - Q[1]);
        } else {
            lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo);
            curve_at(b, d, x2, X);
            f2 = hypot(X[0] - Q[0], X[1] - Q[1]);
        }
    }
    return fmin(best, fmin(f1, f2));
}

static polyline pla, plo;

/* Brute-force two-sided Hausdorff distance between A and the exact offset,
 * both sampled at NB uniform parameters, distances to the other polyline. */
static double brute_hausdorff(const ob_bez *base, const ob_bez *approx, double d)
{
    for (int k = 0; k < NB; k++) {
        double t = (double)k / (NB - 1), p[2];
        ref_point(approx, t, p);
        pla.x[k] = p[0], pla.y[k] = p[1];
        ref_offset(base, t, d, p);
        plo.x[k] = p[0], plo.y[k] = p[1];
    }
    poly_boxes(&pla);
    poly_boxes(&plo);
    double h = 0;
    for (int k = 0; k < NB; k++) {
        double Q[2] = {pla.x[k], pla.y[k]}, R[2] = {plo.x[k], plo.y[k]};
        h = fmax(h, fmax(poly_dist(&plo, Q, k), poly_dist(&pla, R, k)));
    }
    return h;
}

/* The certified metric is an enclosure's upper end: never below the true
 * distance, within its relative target (1e-3) above it; near 0 (an exact
 * offset) the default budget leaves up to a few 1e-9 (a rational line's
 * exact offset: 2e-9, size 3.4), so 1e-8 absolute (metric_certified.h).  1 when e
 * is such an upper end of `truth` (known to within tol); for the other
 * metrics |e - truth| <= tol. */
static int near_truth(int m, double e, double truth, double tol)
{
    if (m == OB_METRIC_CERTIFIED)
        return e >= truth - tol && e <= truth * (1 + 2e-3) + 1e-8 + tol;
    return fabs(e - truth) <= tol;
}

/* Two measurements of the same distance agree: to tol, or for certified
 * to both enclosures' width. */
static int same_measure(int m, double e0, double e1, double tol)
{
    if (m == OB_METRIC_CERTIFIED)
        return fabs(e0 - e1) <= 2e-3 * fmax(e0, e1) + 1e-8 + tol;
    return fabs(e0 - e1) <= tol;
}

static const double straight[4][2] = {{0, 0}, {1, 0.5}, {2.5, 1.25}, {3, 1.5}};

/* ---- known answers ---------------------------------------------------------- */

static void test_straight(void)
{
    const double Nl = sqrt(5.0), N[2] = {-1 / Nl, 2 / Nl};  /* left of (2,1) */
    static const double ds[2] = {0.3, -0.3}, deltas[3] = {0.0, 0.01, -0.02};
    const double w[4] = {1, 1.6, 0.7, 1};
    for (int rat = 0; rat <= 1; rat++)
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 3; j++) {
                const double d = ds[i], delta = deltas[j] * (d > 0 ? 1 : -1);
                double xy[4][2];
                for (int k = 0; k < 4; k++) {
                    xy[k][0] = straight[k][0] + (d + delta) * N[0];
                    xy[k][1] = straight[k][1] + (d + delta) * N[1];
                }
                ob_bez base = make(3, straight, rat ? w : NULL), app = make(3, (const double (*)[2])xy, rat ? w : NULL);
                for (int m = 0; m < OB_METRIC_COUNT; m++) {
                    double t, e = measure((ob_metric)m, &base, &app, d, 256, &t);
                    double tol = m == OB_METRIC_HAUSDORFF ? 1e-9 : 1e-12;
                    if (delta == 0)
                        tol = 1e-12;
                    CHECK(near_truth(m, e, fabs(delta), tol),
                          "straight %s d = %g, offset line moved by %g: %s = %.17g, expected %g",
                          rat ? "rational" : "polynomial", d, delta, ob_metric_name(m), e, fabs(delta));
                    CHECK(t >= 0 && t <= 1, "%s: t = %g outside [0,1]", ob_metric_name(m), t);
                }
                /* the approximation elevated (mixed degrees): same answers */
                ob_bez app5;
                ob_bez_elevate(&app, 5, &app5);
                for (int m = 0; m < OB_METRIC_COUNT; m++) {
                    double e = measure((ob_metric)m, &base, &app5, d, 256, NULL);
                    double tol = m == OB_METRIC_HAUSDORFF && delta != 0 ? 1e-9 : 1e-12;
                    CHECK(near_truth(m, e, fabs(delta), tol), "straight, quintic approximation: %s = %.17g, expected %g",
                          ob_metric_name(m), e, fabs(delta));
                }
            }
}

static void test_circle(void)
{
    ob_bez c = quarter_circle(1.0, 0);
    static const double ds[2] = {0.5, -0.5};
    for (int i = 0; i < 2; i++) {
        const double d = ds[i];
        /* counterclockwise travel: the left normal points to the centre, so the
         * exact offset is the circle of radius 1 - d (0.5, resp. 1.5) */
        double worst = 0;
        for (int k = 0; k <= 50; k++) {
            double O[2];
            ref_offset(&c, k / 50.0, d, O);
            worst = fmax(worst, fabs(hypot(O[0], O[1]) - (1 - d)));
        }
        CHECK(worst < 1e-15, "test setup: offset of the quarter circle has radius 1 - d (off by %g)", worst);
        ob_bez a = quarter_circle(1 - d, 0);
        for (int m = 0; m < OB_METRIC_COUNT; m++) {
            double t, e = measure((ob_metric)m, &c, &a, d, 256, &t);
            CHECK(near_truth(m, e, 0.0, 1e-12), "quarter circle, exact offset (radius %g) at d = %g: %s = %.3g", 1 - d, d,
                  ob_metric_name(m), e);
        }
        /* the wrong side (radius 1 + d) is off by 2|d| in every metric */
        ob_bez wrong = quarter_circle(1 + d, 0);
        for (int m = 0; m < OB_METRIC_COUNT; m++) {
            double e = measure((ob_metric)m, &c, &wrong, d, 256, NULL);
            double expect = m <= OB_METRIC_RADIAL ? 0.0 : 2 * fabs(d);
            /* bound and radial only see the distance |d| from C: the circle of
             * radius 1 + d is at distance |d| too, so they report 0 */
            CHECK(near_truth(m, e, expect, 1e-9), "quarter circle, offset on the wrong side at d = %g: %s = %.17g, "
                  "expected %g", d, ob_metric_name(m), e, expect);
        }
    }
}

/* ---- properties -------------------------------------------------------------- */

static void test_bound_dominates(void)
{
    int bad = 0, badt = 0, nonfinite = 0;
    double worst = 0;
    for (int k = 0; k < 200; k++) {
        const int base_rat = (k % 4) >= 2, app_rat = k % 2, m = 3 + k % 4;
        double d;
        ob_bez base = random_base(base_rat, &d);
        ob_bez app = rough_offset(&base, d, m, 0.02, app_rat);
        double tb, tr;
        double eb = measure(OB_METRIC_BOUND, &base, &app, d, 256, &tb);
        double er = measure(OB_METRIC_RADIAL, &base, &app, d, 1024, &tr);
        if (!isfinite(eb) || !isfinite(er))
            nonfinite++;
        if (!(eb >= er - 1e-12)) {
            if (bad++ < 3)
                fprintf(stderr, "  pair %d (base %s, approx degree %d %s): bound %.17g < radial %.17g\n", k,
                        base_rat ? "rational" : "polynomial", m, app_rat ? "rational" : "polynomial", eb, er);
        }
        worst = fmax(worst, er - eb);
        if (!(tb >= 0 && tb <= 1 && tr >= 0 && tr <= 1))
            badt++;
    }
    CHECK(nonfinite == 0, "%d pairs with a non-finite bound or radial error", nonfinite);
    CHECK(bad == 0, "bound < radial on %d of 200 random pairs (worst radial - bound = %g)", bad, worst);
    CHECK(badt == 0, "%d pairs report t outside [0,1]", badt);
}

static void test_param_independence(void)
{
    int param_moved = 0, param_pairs = 0;
    for (int trial = 0; trial < 6; trial++) {
        const int app_rat = trial % 2;
        double d;
        ob_bez base = random_base(trial >= 4, &d);
        ob_bez app = rough_offset(&base, d, 3 + trial % 3, 0.01, app_rat);
        static const double alphas[2] = {0.4, -0.3};
        for (int ai = 0; ai < 2; ai++) {
            ob_bez rp = reparam(&app, alphas[ai]);
            /* test setup: the composition is exact */
            double w = 0;
            for (int k = 0; k <= 30; k++) {
                double s = k / 30.0, u = s + alphas[ai] * s * (1 - s), p[2], q[2];
                ref_point(&rp, s, p);
                ref_point(&app, u, q);
                w = fmax(w, hypot(p[0] - q[0], p[1] - q[1]));
            }
            CHECK(w < 1e-13, "test setup: reparameterized approximation off by %g", w);
            for (int m = 0; m < OB_METRIC_COUNT; m++) {
                double e0 = measure((ob_metric)m, &base, &app, d, 256, NULL);
                double e1 = measure((ob_metric)m, &base, &rp, d, 256, NULL);
                if (m == OB_METRIC_PARAM)
                    /* param sees a drift along the offset only to second
                     * order, not at all where its maximum sits at an end
                     * (the reparameterization keeps the ends): counted */
                    param_moved += fabs(e0 - e1) > 1e-4, param_pairs++;
                else if (ob_metric_reads_param((ob_metric)m))
                    CHECK(fabs(e0 - e1) > 1e-4, "%s should see the reparameterization: %.17g vs %.17g",
                          ob_metric_name(m), e0, e1);
                else
                    CHECK(same_measure(m, e0, e1, 1e-8), "%s changed under reparameterization (alpha %g, %s approx): "
                          "%.17g vs %.17g", ob_metric_name(m), alphas[ai], app_rat ? "rational" : "polynomial", e0, e1);
            }
        }
        /* hausdorff does not depend on the direction of the approximation */
        ob_bez rev = reversed(&app);
        double h0 = measure(OB_METRIC_HAUSDORFF, &base, &app, d, 256, NULL);
        double h1 = measure(OB_METRIC_HAUSDORFF, &base, &rev, d, 256, NULL);
        CHECK(fabs(h0 - h1) <= 1e-8, "hausdorff changed when the approximation is reversed: %.17g vs %.17g", h0, h1);
    }
    CHECK(param_moved >= param_pairs / 2, "param saw the reparameterization in %d of %d pairs", param_moved,
          param_pairs);
}

static void test_samples(void)
{
    for (int trial = 0; trial < 4; trial++) {
        double d;
        ob_bez base = random_base(trial % 2, &d);
        ob_bez app = rough_offset(&base, d, 4, 0.01, trial >= 2);
        for (int m = OB_METRIC_RADIAL; m < OB_METRIC_COUNT; m++) {
            double e64 = measure((ob_metric)m, &base, &app, d, 64, NULL);
            double e256 = measure((ob_metric)m, &base, &app, d, 256, NULL);
            double e1024 = measure((ob_metric)m, &base, &app, d, 1024, NULL);
            CHECK(same_measure(m, e64, e1024, 1e-9) && same_measure(m, e256, e1024, 1e-9),
                  "%s (trial %d): S = 64, 256, 1024 give %.17g, %.17g, %.17g", ob_metric_name(m), trial, e64, e256,
                  e1024);
        }
        /* the refined maximum is at least every raw sample (computed here) */
        const int S = 64;
        double er = measure(OB_METRIC_RADIAL, &base, &app, d, S, NULL);
        double en = measure(OB_METRIC_NORMAL, &base, &app, d, S, NULL);
        double eh = measure(OB_METRIC_HAUSDORFF, &base, &app, d, S, NULL);
        double rawr = 0, rawn = 0, rawh = 0;
        for (int k = 0; k < S; k++) {
            double t = (double)k / (S - 1), p[2], q[2];
            ref_point(&base, t, p);
            ref_point(&app, t, q);
            rawr = fmax(rawr, fabs(hypot(q[0] - p[0], q[1] - p[1]) - fabs(d)));
            rawn = fmax(rawn, ref_normal_err(&base, &app, d, t));
        }
        /* raw one-sided hausdorff samples, distances to the true curves */
        for (int k = 0; k < S; k++) {
            double t = (double)k / (S - 1), Q[2], R[2];
            ref_point(&app, t, Q);
            ref_offset(&base, t, d, R);
            rawh = fmax(rawh, fmax(curve_dist(&base, d, Q), curve_dist(&app, 0.0, R)));
        }
        CHECK(er >= rawr - 1e-15, "radial %.17g below its raw sample maximum %.17g", er, rawr);
        CHECK(en >= rawn - 1e-12, "normal %.17g below its raw sample maximum %.17g", en, rawn);
        CHECK(eh >= rawh - 1e-12, "hausdorff %.17g below its raw sample maximum %.17g", eh, rawh);
    }
}

static void test_reported_t(void)
{
    for (int trial = 0; trial < 8; trial++) {
        double d;
        ob_bez base = random_base(trial % 2, &d);
        ob_bez app = rough_offset(&base, d, 3 + trial % 4, 0.01, trial >= 4);
        double t, e;
        /* radial: | |A(t) - C(t)| - |d| | at the reported t */
        e = measure(OB_METRIC_RADIAL, &base, &app, d, 256, &t);
        double p[2], q[2];
        ref_point(&base, t, p);
        ref_point(&app, t, q);
        CHECK(t >= 0 && t <= 1, "radial t = %g", t);
        CHECK_NEAR(e, fabs(hypot(q[0] - p[0], q[1] - p[1]) - fabs(d)), 1e-13, "radial error at its reported t");
        /* normal: |s - d| on the normal line at the reported t */
        e = measure(OB_METRIC_NORMAL, &base, &app, d, 256, &t);
        CHECK(t >= 0 && t <= 1, "normal t = %g", t);
        CHECK_NEAR(e, ref_normal_err(&base, &app, d, t), 1e-10, "normal error at its reported t");
        /* hausdorff: t is the offset point farthest from A, or the foot of the
         * point of A farthest from the offset: either way dist(O(t), A) <= err */
        e = measure(OB_METRIC_HAUSDORFF, &base, &app, d, 256, &t);
        CHECK(t >= 0 && t <= 1, "hausdorff t = %g", t);
        double O[2];
        ref_offset(&base, t, d, O);
        double dO = curve_dist(&app, 0.0, O);
        CHECK(dO <= e + 1e-12, "hausdorff: the offset point at the reported t is %.17g from A, more than %.17g", dO, e);
        /* bound: t is a coefficient index / degree, in [0,1]; the bound holds there */
        e = measure(OB_METRIC_BOUND, &base, &app, d, 256, &t);
        ref_point(&base, t, p);
        ref_point(&app, t, q);
        CHECK(t >= 0 && t <= 1 && e >= fabs(hypot(q[0] - p[0], q[1] - p[1]) - fabs(d)) - 1e-13,
              "bound t = %g, err %g", t, e);
    }
}

static void test_hausdorff_brute(void)
{
    int bad = 0, below = 0;
    double worst = 0;
    for (int k = 0; k < 30; k++) {
        double d;
        ob_bez base = random_base(0, &d);
        ob_bez app = rough_offset(&base, d, 3, 0.01, 0);
        ob_errval e;
        ob_metric_hausdorff(&base, &app, d, 256, &e);
        double bf = brute_hausdorff(&base, &app, d);
        worst = fmax(worst, fabs(e.err - bf));
        if (!(fabs(e.err - bf) <= 1e-5)) {
            if (bad++ < 3)
                fprintf(stderr, "  pair %d: hausdorff %.17g, brute force %.17g\n", k, e.err, bf);
        }
        if (!(e.err >= bf - 1e-6)) {
            if (below++ < 3)
                fprintf(stderr, "  pair %d: hausdorff %.17g below brute force %.17g\n", k, e.err, bf);
        }
    }
    CHECK(bad == 0, "hausdorff disagrees with the 4000x4000 brute force on %d of 30 pairs (worst %g)", bad, worst);
    CHECK(below == 0, "hausdorff below the brute force on %d of 30 pairs", below);
}

/* ---- the dispatcher and bad input ----------------------------------------------- */

static const ob_bez *g_base, *g_app;
static double g_d;
static int child_radial_s1(void)
{
    ob_errval a, b;
    ob_metric_radial(g_base, g_app, g_d, 1, &a);
    ob_metric_radial(g_base, g_app, g_d, OB_MIN_SAMPLES, &b);
    return a.err == b.err ? 0 : 2;
}
static int child_hausdorff_big(void)
{
    ob_errval a, b;
    ob_metric_hausdorff(g_base, g_app, g_d, OB_MAX_SAMPLES + 1000, &a);
    ob_metric_hausdorff(g_base, g_app, g_d, OB_MAX_SAMPLES, &b);
    return a.err == b.err ? 0 : 2;
}

static void test_measure(void)
{
    double d;
    ob_bez base = random_base(0, &d);
    ob_bez app = rough_offset(&base, d, 4, 0.01, 0);
    /* unknown metric ids */
    static const int bad_ids[3] = {OB_METRIC_COUNT, 99, -1};
    for (int i = 0; i < 3; i++) {
        ob_errval e = {0, 0, 0};
        int rc = ob_measure((ob_metric)bad_ids[i], &base, &app, d, 256, &e);
        CHECK(rc == -1 && isinf(e.err) && e.err > 0, "unknown metric %d: rc %d err %g", bad_ids[i], rc, e.err);
    }
    /* sample counts are clamped */
    static const int low[4] = {0, 1, -5, INT_MIN}, high[3] = {1000000000, INT_MAX, OB_MAX_SAMPLES + 1};
    for (int m = OB_METRIC_RADIAL; m < OB_METRIC_COUNT; m++) {
        double ref_lo = measure((ob_metric)m, &base, &app, d, OB_MIN_SAMPLES, NULL);
        double ref_hi = measure((ob_metric)m, &base, &app, d, OB_MAX_SAMPLES, NULL);
        for (int i = 0; i < 4; i++) {
            double e = measure((ob_metric)m, &base, &app, d, low[i], NULL);
            CHECK(e == ref_lo, "%s with %d samples: %.17g, expected the %d-sample value %.17g", ob_metric_name(m), low[i],
                  e, OB_MIN_SAMPLES, ref_lo);
        }
        for (int i = 0; i < 3; i++) {
            double e = measure((ob_metric)m, &base, &app, d, high[i], NULL);
            CHECK(e == ref_hi, "%s with %d samples: %.17g, expected the %d-sample value %.17g", ob_metric_name(m),
                  high[i], e, OB_MAX_SAMPLES, ref_hi);
        }
    }
    /* metric.h: the individual metrics have "the same contract", i.e. clamp S
     * too; run in a child since an unclamped S may overrun a buffer */
    g_base = &base, g_app = &app, g_d = d;
    int rc1 = in_child(child_radial_s1), rc2 = in_child(child_hausdorff_big);
    CHECK(rc1 == 0, "ob_metric_radial with S = 1 is not the clamped (S = %d) result: child status %d", OB_MIN_SAMPLES,
          rc1);
    CHECK(rc2 == 0, "ob_metric_hausdorff with S = %d is not the clamped result: child status %d "
          "(1 or >= 128: crashed or sanitizer report)", OB_MAX_SAMPLES + 1000, rc2);

    /* NaN control points: +inf, never NaN, never a crash */
    for (int which = 0; which < 2; which++)
        for (int idx = 0; idx < 3; idx++)
            for (int rat = 0; rat <= 1; rat++) {
                ob_bez b = base, a = app;
                if (rat)
                    b.h[1][2] = 1.3, b.rational = 1, a.h[2][2] = 0.8, a.rational = 1;
                ob_bez *victim = which ? &b : &a;
                int i = idx == 0 ? 0 : idx == 1 ? victim->deg / 2 : victim->deg;
                victim->h[i][0] = NAN;
                for (int m = 0; m < OB_METRIC_COUNT; m++) {
                    ob_errval e = {0, 0, 0};
                    ob_measure((ob_metric)m, &b, &a, d, 256, &e);
                    CHECK(isinf(e.err) && e.err > 0, "%s: NaN in the %s's control point %d (%s): err = %g, expected +inf",
                          ob_metric_name(m), which ? "base" : "approximation", i, rat ? "rational" : "polynomial",
                          e.err);
                }
            }

    /* names */
    for (int m = 0; m < OB_METRIC_COUNT; m++) {
        ob_metric back = OB_METRIC_COUNT;
        const char *name = ob_metric_name((ob_metric)m);
        CHECK(ob_metric_parse(name, &back) == 0 && back == (ob_metric)m, "metric name '%s' does not round-trip", name);
    }
    ob_metric x = OB_METRIC_RADIAL;
    CHECK(ob_metric_parse("nope", &x) == -1 && x == OB_METRIC_RADIAL, "unknown name is rejected, *m untouched");
    CHECK(ob_metric_parse("", &x) == -1 && ob_metric_parse("Radial", &x) == -1, "empty / wrong case rejected");
    CHECK(strcmp(ob_metric_name(OB_METRIC_BOUND), "bound") == 0 && strcmp(ob_metric_name(OB_METRIC_RADIAL), "radial") == 0 &&
              strcmp(ob_metric_name(OB_METRIC_NORMAL), "normal") == 0 &&
              strcmp(ob_metric_name(OB_METRIC_HAUSDORFF), "hausdorff") == 0 &&
              strcmp(ob_metric_name(OB_METRIC_PARAM), "param") == 0,
          "metric names as in the README (the contract; param added at the end)");
    CHECK(ob_metric_same_param(OB_METRIC_BOUND) && ob_metric_same_param(OB_METRIC_RADIAL) &&
              !ob_metric_same_param(OB_METRIC_NORMAL) && !ob_metric_same_param(OB_METRIC_HAUSDORFF) &&
              !ob_metric_same_param(OB_METRIC_PARAM),
          "same-parameter metrics (the driver skips other methods) are bound and radial");
    CHECK(ob_metric_reads_param(OB_METRIC_BOUND) && ob_metric_reads_param(OB_METRIC_RADIAL) &&
              ob_metric_reads_param(OB_METRIC_PARAM) && !ob_metric_reads_param(OB_METRIC_NORMAL) &&
              !ob_metric_reads_param(OB_METRIC_HAUSDORFF),
          "metrics that read A at the base's parameter: bound, radial, param");
    for (int m = 0; m < OB_METRIC_COUNT; m++)
        CHECK(strcmp(ob_metric_doc((ob_metric)m), "?") != 0, "%s has a definition", ob_metric_name(m));
}

/* The normal metric's pointwise error is the nearest crossing: Newton from
 * u = t used to jump past nearer crossings to a far one on A's extension.
 * The case that showed it: Liu-Wang's Example 1, d = 1, halved, each half
 * approximated by `interp` (the normal metric then needed 3 segments at
 * tol 0.1 instead of 2); checked at the metric's own 256 sample parameters. */
static void test_normal_nearest_crossing(void)
{
    static const double ex1[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};
    const ob_method *m = ob_method_find("interp");
    CHECK(m != NULL, "interp is registered");
    if (!m)
        return;
    ob_bez c;
    ob_bez_from_points(&c, 3, ex1);
    const double d = 1.0;
    int bad = 0, n = 0;
    double worst = 0.0;
    for (int half = 0; half < 2; half++) {
        ob_bez b, a;
        ob_bez_subsegment(&c, 0.5 * half, 0.5 * half + 0.5, &b);
        double par[OB_MAX_PARAMS];
        ob_param_defaults(m, par);
        const ob_fit_args args = {d, 0.1, par};
        ob_fit fit;
        char msg[160];
        void *work = malloc(m->work_size ? m->work_size : 1);
        const ob_fit_status st = m->fit(&b, &args, work, &fit, msg, sizeof msg);
        free(work);
        CHECK(st == OB_FIT_OK && fit.n == 1, "interp fits half %d: %s", half, msg);
        if (st != OB_FIT_OK || fit.n != 1)
            continue;
        a = fit.seg[0];
        for (int k = 0; k < 256; k++, n++) {
            const double t = k / 255.0;
            long ops = 0;
            const double got = obc_normal_err(&b.h[0][0], b.deg, &a.h[0][0], a.deg, d, 256, NULL, NULL, &ops, t);
            const double want = ref_normal_err(&b, &a, d, t);
            if (isnan(want))  /* no crossing: the point mismatch, tested elsewhere */
                continue;
            const double e = fabs(got - want) / fmax(1e-3, want);
            if (e > 1e-6 && bad++ < 5)
                fprintf(stderr, "half %d, t %.3f: normal error %.12g, nearest crossing gives %.12g\n", half, t, got,
                        want);
            worst = fmax(worst, e);
        }
    }
    CHECK(bad == 0, "normal error is the nearest crossing's: %d of %d points differ (worst relative %.3g)", bad, n,
          worst);
}

/* ob_measure_until: where the full error is <= stop the result is the full
 * one bit for bit (error and parameter); where it is above, the result lies
 * in (stop, full], and the early end happens (less work) for stops well
 * under the error.  Every sampled metric, rough approximations of degrees 3
 * and 5, stops from a third of the error to twice it; a stop of 0 is the
 * full measurement; bound ignores the stop. */
static void test_measure_until(void)
{
    const ob_metric mets[4] = {OB_METRIC_RADIAL, OB_METRIC_NORMAL, OB_METRIC_HAUSDORFF, OB_METRIC_PARAM};
    const double frac[7] = {0.0, 0.3, 0.9, 0.999999, 1.0, 1.000001, 2.0};
    int same = 0, nsame = 0, inside = 0, ninside = 0, early = 0, nlow = 0;
    for (int c = 0; c < 40; c++) {
        double d;
        ob_bez base = random_base(c % 4 == 3, &d), a = rough_offset(&base, d, c % 2 ? 5 : 3, 2e-3, c % 5 == 4);
        for (int m = 0; m < 4; m++) {
            ob_errval full, u;
            ob_measure(mets[m], &base, &a, d, 128, &full);
            for (int f = 0; f < 7; f++) {
                const double stop = frac[f] * full.err;
                ob_measure_until(mets[m], &base, &a, d, 128, stop, &u);
                if (!(stop > 0.0) || full.err <= stop) {
                    nsame++;
                    same += memcmp(&u.err, &full.err, sizeof u.err) == 0 && memcmp(&u.t, &full.t, sizeof u.t) == 0 &&
                            u.work == full.work;
                } else {
                    ninside++;
                    inside += u.err > stop && u.err <= full.err && u.work <= full.work;
                    if (frac[f] <= 0.3) {
                        nlow++;
                        early += u.work < full.work;
                    }
                }
            }
        }
        ob_errval b1, b2;
        ob_measure(OB_METRIC_BOUND, &base, &a, d, 128, &b1);
        ob_measure_until(OB_METRIC_BOUND, &base, &a, d, 128, 0.3 * b1.err, &b2);
        same += memcmp(&b1.err, &b2.err, sizeof b1.err) == 0;
        nsame++;
    }
    CHECK(same == nsame, "measure_until: %d of %d at or under stop are the full result bit for bit", same, nsame);
    CHECK(inside == ninside && ninside > 0, "measure_until: %d of %d above stop in (stop, full]", inside, ninside);
    CHECK(early == nlow && nlow > 0, "measure_until: %d of %d at a third of the error end early", early, nlow);
}

int main(void)
{
    testlib_seed(0x2545F4914F6CDD1DULL);
    test_measure_until();
    test_normal_nearest_crossing();
    test_straight();
    test_circle();
    test_bound_dominates();
    test_param_independence();
    test_samples();
    test_reported_t();
    test_hausdorff_brute();
    test_measure();
    return check_done();
}
