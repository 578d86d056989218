/*
 * test_bspline_lsq.c - what the bspline-lsq method (methods/bspline_lsq.c)
 * claims, checked with the test library's own Bernstein sums and a
 * Cox-de Boor recursion written here (never the method's code):
 *  - its pieces are the spans of one clamped cubic B-spline with uniform
 *    knots: k - 3 pieces over t_i = i/(k - 3), C2 where they meet, k the
 *    control points it reports;
 *  - the spline is the least-squares optimum for its knots: the residuals
 *    at the M = samples k parameters t_j = j/(M - 1) are orthogonal to every
 *    basis function (the normal equations sum_j N_i(t_j) (A(t_j) - O(t_j)) =
 *    0), and it interpolates nothing (the residuals are not all zero);
 *  - its per-span Elber-Cohen bound met the tolerance, so the error sampled
 *    densely (radial: | |A(t) - C(t)| - |d| |) is within it, on random
 *    cubics, a rational arc and both signs of d;
 *  - a spline of more than 16 spans comes back whole (one spline, not two);
 *    a piece it cannot fit with at most OB_MAX_PIECES spans asks for a smaller
 *    piece (OB_FIT_RETRY_SMALLER), and a tighter tolerance never gets fewer points.
 */
#include <stdlib.h>
#include <string.h>

#include "methods/method.h"
#include "tests/check.h"
#include "tests/testlib.h"

static const ob_method *method(void)
{
    const ob_method *m = ob_method_find("bspline-lsq");
    CHECK(m != NULL, "bspline-lsq is registered");
    return m;
}

typedef struct {
    ob_fit_status st;
    ob_fit f;
    char msg[200];
} result;

static result run(const ob_method *m, const ob_bez *b, double d, double tol)
{
    result r;
    memset(&r, 0, sizeof r);
    double par[OB_MAX_PARAMS];
    ob_param_defaults(m, par);
    void *work = m->work_size ? malloc(m->work_size) : NULL;
    const ob_fit_args a = {d, tol, par};
    r.st = m->fit(b, &a, work, &r.f, r.msg, sizeof r.msg);
    free(work);
    return r;
}

/* Cox-de Boor by its recursive definition (0/0 = 0), knots U. */
static double basis(const double *U, int i, int p, double t)
{
    if (p == 0) {
        /* the last non-empty span is closed at the right end */
        const int last = U[i + 1] == 1.0 && U[i] < 1.0;
        return (U[i] <= t && (t < U[i + 1] || (last && t == 1.0))) ? 1.0 : 0.0;
    }
    double v = 0.0;
    if (U[i + p] > U[i])
        v += (t - U[i]) / (U[i + p] - U[i]) * basis(U, i, p - 1, t);
    if (U[i + p + 1] > U[i + 1])
        v += (U[i + p + 1] - t) / (U[i + p + 1] - U[i + 1]) * basis(U, i + 1, p - 1, t);
    return v;
}

/* One B-spline: uniform breakpoints and C2 joins (derivatives scaled by the
 * span lengths). */
static void check_structure(const char *what, const ob_fit *f)
{
    const long k = f->ctrl_points;
    CHECK(k >= 4 && f->n == k - 3, "%s: %ld control points, %d pieces (want k - 3)", what, k, f->n);
    double worst = 0.0;
    for (int i = 0; i <= f->n; i++)
        worst = fmax(worst, fabs(f->t[i] - (double)i / f->n));
    CHECK(worst < 1e-15, "%s: breakpoints not uniform (off by %g)", what, worst);
    double jump = 0.0, size = 1.0;
    for (int i = 1; i < f->n; i++) {
        double l[3][2], r[3][2];
        ref_eval(&f->seg[i - 1], 1.0, 2, l);
        ref_eval(&f->seg[i], 0.0, 2, r);
        const double h = f->t[i] - f->t[i - 1];
        for (int q = 0; q < 3; q++)
            for (int c = 0; c < 2; c++) {
                jump = fmax(jump, fabs(l[q][c] - r[q][c]) * pow(h, q));
                size = fmax(size, fabs(l[q][c]) * pow(h, q));
            }
    }
    CHECK(jump <= 1e-11 * size, "%s: not C2 at the knots (jump %g)", what, jump);
}

/* The normal equations at the samples, and the residuals not all zero. */
static void check_normal_equations(const char *what, const ob_bez *b, double d, const ob_fit *f, int factor)
{
    const int k = (int)f->ctrl_points, M = factor * k;
    double U[OB_MAX_PIECES + 8];
    for (int i = 0; i < k + 4; i++)
        U[i] = i < 4 ? 0.0 : i >= k ? 1.0 : (double)(i - 3) / (k - 3);
    double worst = 0.0, res = 0.0, scale = 0.0;
    for (int i = 0; i < k; i++) {
        double g[2] = {0.0, 0.0};
        for (int j = 0; j < M; j++) {
            const double t = j == M - 1 ? 1.0 : (double)j / (M - 1);
            double a[2], o[2];
            fit_point(f, t, a);
            ref_offset(b, t, d, o);
            const double Ni = basis(U, i, 3, t);
            g[0] += Ni * (a[0] - o[0]);
            g[1] += Ni * (a[1] - o[1]);
            res = fmax(res, hypot(a[0] - o[0], a[1] - o[1]));
            scale = fmax(scale, hypot(o[0], o[1]));
        }
        worst = fmax(worst, hypot(g[0], g[1]));
    }
    CHECK(worst <= 1e-10 * M * scale, "%s: normal equations violated by %g (k %d, M %d)", what, worst, k, M);
    CHECK(res > 0.0, "%s: every sample interpolated (a least-squares fit interpolates nothing)", what);
}

/* The densely sampled radial error is within the tolerance the bound met. */
static void check_bound(const char *what, const ob_bez *b, double d, double tol, const ob_fit *f)
{
    double e = 0.0;
    for (int j = 0; j <= 4000; j++) {
        const double t = j / 4000.0;
        double a[2], c[2];
        fit_point(f, t, a);
        ref_point(b, t, c);
        e = fmax(e, fabs(hypot(a[0] - c[0], a[1] - c[1]) - fabs(d)));
    }
    CHECK(e <= tol, "%s: sampled error %g above the tolerance %g the bound met", what, e, tol);
}

static ob_bez random_cubic(void)
{
    double xy[4][2];
    for (int i = 0; i < 4; i++) {
        xy[i][0] = i + urange(-0.4, 0.4);
        xy[i][1] = urange(-1.0, 1.0);
    }
    return make(3, (const double(*)[2])xy, NULL);
}

static void test_random(const ob_method *m)
{
    const int factor = (int)m->params[ob_param_find(m, "samples")].def;
    int ok = 0, tried = 0;
    for (int c = 0; c < 24; c++) {
        const ob_bez b = c < 20 ? random_cubic() : quarter_circle(urange(1.0, 3.0), c % 2);
        const double d = (c % 2 ? -1.0 : 1.0) * urange(0.05, 0.3), tol = pow(10.0, -1.0 - c % 3);
        char what[64];
        snprintf(what, sizeof what, "curve %d (d %.3f, tol %g)", c, d, tol);
        const result r = run(m, &b, d, tol);
        tried++;
        if (r.st == OB_FIT_RETRY_SMALLER)
            continue;
        CHECK(r.st == OB_FIT_OK, "%s: status %d: %s", what, r.st, r.msg);
        if (r.st != OB_FIT_OK)
            continue;
        ok++;
        check_structure(what, &r.f);
        check_normal_equations(what, &b, d, &r.f, factor);
        check_bound(what, &b, d, tol, &r.f);
        const result tight = run(m, &b, d, tol / 10.0);
        CHECK(tight.st == OB_FIT_RETRY_SMALLER || tight.f.ctrl_points >= r.f.ctrl_points,
              "%s: a tenth of the tolerance gets fewer control points (%ld < %ld)", what, tight.f.ctrl_points,
              r.f.ctrl_points);
    }
    CHECK(ok >= tried * 3 / 4, "%d of %d random fits ok", ok, tried);
}

/* Liu-Wang's Example 1 at 1e-1: a handful of control points; at 1e-9 no
 * spline of OB_MAX_PIECES spans is close enough: a smaller piece is asked for. */
static void test_example1(const ob_method *m)
{
    const double xy[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};
    const ob_bez b = make(3, xy, NULL);
    const result r = run(m, &b, 1.0, 1e-1);
    CHECK(r.st == OB_FIT_OK && r.f.ctrl_points >= 4 && r.f.ctrl_points <= 10, "example 1 at 1e-1: status %d, %ld points",
          r.st, r.f.ctrl_points);
    /* one spline of more than 16 spans: returned whole, not split (the spans
     * fit in an ob_fit; splitting would make two splines of it) */
    const result f = run(m, &b, 1.0, 1e-5);
    CHECK(f.st == OB_FIT_OK && f.f.n > 16 && f.f.n == f.f.ctrl_points - 3,
          "example 1 at 1e-5: one spline (status %d, %d spans, %ld points: %s)", f.st, f.f.n, f.f.ctrl_points, f.msg);
    const result t = run(m, &b, 1.0, 1e-9);
    CHECK(t.st == OB_FIT_RETRY_SMALLER && strstr(t.msg, "control points"), "example 1 at 1e-9: status %d (%s)", t.st,
          t.msg);
}

int main(void)
{
    testlib_seed(0xB5711E5ULL);
    const ob_method *m = method();
    if (m) {
        test_random(m);
        test_example1(m);
    }
    return check_done();
}
