/*
 * test_param_ref.c - the `param` metric (Zhao & Zhou 2017, section 3: the
 * error at the given parameter, e(t) = (R(t) - C_r(t)) . N(t)) against an
 * independent dense brute force.
 *
 * The reference shares no code with the metric (no kernels/, no ob_measure,
 * no ob_bez_eval, no ob_bez_subsegment): the base and the pieces are
 * evaluated from their homogeneous control points by testlib's power-basis
 * Bernstein sums, and a piece over [t_i, t_{i+1}] is compared with the base at
 * t = t_i + (t_{i+1} - t_i) u (the linear map the driver uses), the normal being
 * that of the whole base (its direction does not depend on the scale of the
 * parameter).  Per piece: |(A(u) - C(t) - d N(t)) . N(t)| on 20001 parameters,
 * then nested grids (201 points over +- one spacing of the best, 20-fold
 * narrower per level, 6 levels: final spacing < 1e-13) around every local
 * maximum within 1 % of the largest.  Its floor: the final spacing times the
 * speed of e (< 1e-12 here), plus rounding, taken as 1e-13 + 1e-10 x error.
 *
 * Checked per piece, on several methods (tiller, cobb, lee, zhao-rational,
 * hoschek, bspline-lsq, lstsq) and curves (Liu-Wang's Example 1 cubic, Zhao-
 * Zhou's quintic and septic, a rational quarter circle, random quintics), both
 * signs of d, tolerance 1e-3 (pieces the method cannot fit are halved, as
 * the driver would): the metric (256 samples, refined) is within 1e-8
 * relative (or 1e-13 absolute) of the reference, and never below it by more
 * than the reference's floor (the worst figures seen are printed: 288 pieces,
 * 1.2e-13 absolute, 4.4e-9 relative).  Then the figures that define it: a
 * tangential drift along a straight offset reads 0 (radial does not), a
 * normal one reads exactly its size.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/method.h"
#include "methods/metrics/metric.h"
#include "tests/check.h"
#include "tests/testlib.h"

/* Reference error at piece parameter u of piece (A over [a, b] of base C). */
static double ref_err(const ob_bez *C, const ob_bez *A, double a, double b, double d, double u)
{
    double O[2], N[2], p[2];
    ref_offset_normal(C, a + (b - a) * u, d, O, N);
    ref_point(A, u, p);
    return fabs((p[0] - O[0]) * N[0] + (p[1] - O[1]) * N[1]);
}

enum { NDENSE = 20001, NFINE = 201, LEVELS = 6 };

/* Nested grids around u0 (half-width w) on [0,1]: the largest value found. */
static double ref_refine(const ob_bez *C, const ob_bez *A, double a, double b, double d, double u0, double w)
{
    double best = ref_err(C, A, a, b, d, u0), ub = u0;
    for (int lv = 0; lv < LEVELS; lv++) {
        const double c = ub;
        for (int k = 0; k < NFINE; k++) {
            const double u = fmin(1.0, fmax(0.0, c - w + 2.0 * w * k / (NFINE - 1)));
            const double e = ref_err(C, A, a, b, d, u);
            if (e > best) {
                best = e;
                ub = u;
            }
        }
        w /= 20.0;
    }
    return best;
}

/* The reference maximum over one piece. */
static double ref_piece_max(const ob_bez *C, const ob_bez *A, double a, double b, double d)
{
    static double e[NDENSE];
    double top = 0.0;
    for (int k = 0; k < NDENSE; k++) {
        e[k] = ref_err(C, A, a, b, d, (double)k / (NDENSE - 1));
        top = fmax(top, e[k]);
    }
    double best = top;
    const double h = 1.0 / (NDENSE - 1);
    for (int k = 0; k < NDENSE; k++) {
        const int peak = (k == 0 || e[k] >= e[k - 1]) && (k == NDENSE - 1 || e[k] >= e[k + 1]);
        if (peak && e[k] >= 0.99 * top)
            best = fmax(best, ref_refine(C, A, a, b, d, (double)k / (NDENSE - 1), h));
    }
    return best;
}

static const double LIU[4][2] = {{0, 0}, {2, 3}, {4, 3}, {6, 0}};
static const double QUINTIC[6][2] = {{3, -1}, {4, 2}, {4.5, 2}, {5.5, 1.5}, {6.5, 0}, {7, -1}};
static const double SEPTIC[8][2] = {{-0.8, 1.5}, {1, 0}, {2, 0.4}, {1.8, 2}, {0, 2.5}, {-1.2, 3.7}, {0, 1.5}, {1.5, 3.9}};

/* A random quintic whose control polygon turns gently. */
static ob_bez random_quintic(void)
{
    double p[6][2], x = urange(-1, 1), y = urange(-1, 1), ang = urange(0, 2 * OB_PI), turn = urange(-1.2, 1.2);
    for (int k = 0; k <= 5; k++) {
        p[k][0] = x, p[k][1] = y;
        const double a = ang + turn * k / 5, len = urange(0.3, 1.0);
        x += len * cos(a);
        y += len * sin(a);
    }
    return make(5, p, NULL);
}

static double worst_rel = 0.0, worst_abs = 0.0, worst_below = 0.0;
static int pieces_checked = 0;

/* Check the pieces of fit f of C's part [a0, b0] (f's parameters are that part's). */
static void check_pieces(const char *name, const ob_bez *C, const char *cname, double d, double a0, double b0,
                         const ob_fit *f)
{
    for (int i = 0; i < f->n; i++) {
        const double a = a0 + (b0 - a0) * f->t[i], b = a0 + (b0 - a0) * f->t[i + 1];
        ob_bez sub;
        ob_bez_subsegment(C, a, b, &sub);
        ob_errval e;
        ob_measure(OB_METRIC_PARAM, &sub, &f->seg[i], d, OB_DEFAULT_SAMPLES, &e);
        const double r = ref_piece_max(C, &f->seg[i], a, b, d);
        const double floor = 1e-13 + 1e-10 * r;
        pieces_checked++;
        worst_abs = fmax(worst_abs, fabs(e.err - r));
        if (r > 1e-7)
            worst_rel = fmax(worst_rel, fabs(e.err - r) / r);
        if (r - e.err > 0.0)
            worst_below = fmax(worst_below, r - e.err);
        CHECK(fabs(e.err - r) <= fmax(1e-8 * r, 1e-13), "%s on %s d %g piece [%g, %g]: param %.17g, reference %.17g",
              name, cname, d, a, b, e.err, r);
        CHECK(e.err >= r - floor, "%s on %s d %g piece [%g, %g]: param %.17g below the reference %.17g",
              name, cname, d, a, b, e.err, r);
        CHECK(e.t >= 0.0 && e.t <= 1.0, "%s on %s piece %d: t %g", name, cname, i, e.t);
    }
}

/* Fit C's part [a, b] with method m at d, tol, halving it where the method
 * asks for a smaller piece (as the driver would); check every piece. */
static void check_range(const ob_method *m, const ob_bez *C, const char *cname, double d, double tol, double a,
                        double b, int depth)
{
    double par[OB_MAX_PARAMS];
    ob_param_defaults(m, par);
    const ob_fit_args args = {d, tol, par};
    void *work = malloc(m->work_size ? m->work_size : 1);
    ob_fit *f = malloc(sizeof *f);
    char msg[256] = "";
    ob_bez part;
    ob_bez_subsegment(C, a, b, &part);
    const ob_fit_status st = work && f ? m->fit(&part, &args, work, f, msg, sizeof msg) : OB_FIT_FAIL;
    if (st == OB_FIT_OK)
        check_pieces(m->name, C, cname, d, a, b, f);
    free(work);
    free(f);
    if (st == OB_FIT_RETRY_SMALLER && depth < 4) {
        check_range(m, C, cname, d, tol, a, 0.5 * (a + b), depth + 1);
        check_range(m, C, cname, d, tol, 0.5 * (a + b), b, depth + 1);
    } else if (st != OB_FIT_OK) {
        printf("  %s on %s [%g, %g] d %g: %s (%s), not checked\n", m->name, cname, a, b, d, ob_fit_status_name(st), msg);
    }
}

static void check_method(const char *name, const ob_bez *C, const char *cname, double d, double tol)
{
    const ob_method *m = ob_method_find(name);
    CHECK(m != NULL, "method %s", name);
    if (m && !(C->rational && !(m->caps & OB_CAP_RATIONAL_IN)))
        check_range(m, C, cname, d, tol, 0.0, 1.0, 0);
}

static void test_against_reference(void)
{
    static const char *methods[] = {"tiller", "cobb", "lee", "zhao-rational", "hoschek", "bspline-lsq", "lstsq"};
    ob_bez curves[8];
    const char *names[8] = {"liu2002_ex1", "zhao2017_quintic", "zhao2017_septic", "quarter circle"};
    curves[0] = make(3, LIU, NULL);
    curves[1] = make(5, QUINTIC, NULL);
    curves[2] = make(7, SEPTIC, NULL);
    curves[3] = quarter_circle(2.0, 0);
    int nc = 4;
    testlib_seed(0x9A7A3ULL);
    for (; nc < 7; nc++) {
        curves[nc] = random_quintic();
        names[nc] = "random quintic";
    }
    static const double ds[2] = {0.3, -0.2};
    for (int c = 0; c < nc; c++)
        for (int k = 0; k < 2; k++)
            for (size_t m = 0; m < sizeof methods / sizeof *methods; m++)
                check_method(methods[m], &curves[c], names[c], ds[k] * (c == 3 ? 2.0 : 1.0), 1e-3);
    printf("  %d pieces: worst difference %.3g (relative %.3g where the error is over 1e-7), worst shortfall "
           "below the reference %.3g\n", pieces_checked, worst_abs, worst_rel, worst_below);
    CHECK(pieces_checked >= 200, "%d pieces checked", pieces_checked);
}

/* A straight base: A shifted along the offset reads 0 (radial reads the
 * drift), shifted along the normal reads the shift. */
static void test_definition(void)
{
    const double P[2][2] = {{0.0, 0.0}, {2.0, 1.0}};
    const double len = hypot(2.0, 1.0), T[2] = {2.0 / len, 1.0 / len}, N[2] = {-T[1], T[0]};
    const double d = 0.4, drift = 0.05, lift = 0.01;
    double q[2][2];
    for (int i = 0; i < 2; i++)
        for (int c = 0; c < 2; c++)
            q[i][c] = P[i][c] + d * N[c] + drift * T[c];
    ob_bez C, A;
    ob_bez_from_points(&C, 1, P);
    ob_bez_from_points(&A, 1, q);
    ob_errval e;
    ob_measure(OB_METRIC_PARAM, &C, &A, d, OB_DEFAULT_SAMPLES, &e);
    CHECK(e.err < 1e-15, "tangential drift: param %g", e.err);
    ob_measure(OB_METRIC_RADIAL, &C, &A, d, OB_DEFAULT_SAMPLES, &e);
    CHECK_NEAR(e.err, hypot(d, drift) - d, 1e-14, "tangential drift: radial");
    for (int i = 0; i < 2; i++)
        for (int c = 0; c < 2; c++)
            q[i][c] = P[i][c] + (d + lift) * N[c];
    ob_bez_from_points(&A, 1, q);
    ob_measure(OB_METRIC_PARAM, &C, &A, d, OB_DEFAULT_SAMPLES, &e);
    CHECK_NEAR(e.err, lift, 1e-15, "normal lift: param");
    /* the offset of a circle by the same parameter reads 0; another radius its difference */
    ob_bez circ = quarter_circle(1.0, 0), big = quarter_circle(1.3, 0);
    ob_measure(OB_METRIC_PARAM, &circ, &big, -0.3, OB_DEFAULT_SAMPLES, &e);
    CHECK(e.err < 1e-14, "circle offset (left normal points in): param %g", e.err);
    ob_measure(OB_METRIC_PARAM, &circ, &big, -0.25, OB_DEFAULT_SAMPLES, &e);
    CHECK_NEAR(e.err, 0.05, 1e-14, "circle, radius off by 0.05");
    CHECK(strcmp(ob_metric_name(OB_METRIC_PARAM), "param") == 0 && !ob_metric_same_param(OB_METRIC_PARAM),
          "name param, run on every method");
    ob_metric back;
    CHECK(ob_metric_parse("param", &back) == 0 && back == OB_METRIC_PARAM, "parse param");
}

int main(void)
{
    test_definition();
    test_against_reference();
    return check_done();
}
