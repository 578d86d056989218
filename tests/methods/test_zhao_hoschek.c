/*
 * test_zhao_hoschek.c - the methods zhao, zhao-rational (Zhao & Zhou 2017) and
 * hoschek (Hoschek 1988), reached through the registry.
 *
 * zhao / zhao-rational:
 *  - exact where the offset lies in the approximation space: a straight
 *    segment (polynomial offset, any polynomial parameterization) for both,
 *    circular arcs given as rational quadratics (also Möbius-reparameterized)
 *    for the rational form;
 *  - parameterization: degree elevation of the base (same curve, same
 *    parameter, output degree held at n) gives the same approximation; a
 *    Möbius reparameterization of a rational base changes the error along the
 *    normal only moderately (the rational space is Möbius invariant, only the
 *    nodes move); the numbers are printed;
 *  - the accelerated iteration: the largest error at the nodes (ratlsq's
 *    nodes, recomputed here) never grows with the number of iterations (the
 *    best iterate is kept), the error along the normal alternates in sign at
 *    least k times (polynomial, k = n+1) or k-1 times (rational, k =
 *    floor((3n+3)/2)), and the iteration evens out the rational extrema;
 *  - polynomial zhao beats cobb on a circle-like cubic; rational outputs have a
 *    positive denominator; a denominator with a root is OB_FIT_FAIL;
 *  - the septic of Zhao-Zhou section 4 is reported, not checked.
 * hoschek:
 *  - end points are the offset's end points; the sum of squared distances of
 *    the samples to the fit does not grow with the parameter corrections and
 *    falls overall; exact on a straight segment; fixed end tangents when asked.
 * Errors along the normal are computed here independently (Zhao-Zhou's e(t) =
 * (R(t) - C(t) - d N(t)) . N(t), testlib evaluation), besides the library's
 * OB_METRIC_NORMAL.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "methods/core/curve.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"
#include "tests/testlib.h"

enum { MSGLEN = 160 };

static const ob_method *ZP, *ZR, *HO, *COBB;
static void *work;

/* ---- helpers ------------------------------------------------------------ */

/* Fit with the defaults, except the parameters named in `set` ("name=value"
 * pairs, NULL-terminated). */
static ob_fit_status fit_with(const ob_method *m, const ob_bez *b, double d, ob_fit *f, char *msg,
                              const char *const *set)
{
    double par[OB_MAX_PARAMS];
    ob_param_defaults(m, par);
    for (int i = 0; set && set[i]; i++) {
        char name[32];
        const char *eq = strchr(set[i], '=');
        size_t len = (size_t)(eq - set[i]);
        memcpy(name, set[i], len);
        name[len] = '\0';
        int k = ob_param_find(m, name);
        if (k < 0) {
            CHECK(0, "%s has no parameter %s", m->name, name);
            exit(2);
        }
        par[k] = atof(eq + 1);
    }
    const ob_fit_args a = {d, 1e-3, par};
    msg[0] = '\0';
    return m->fit(b, &a, work, f, msg, MSGLEN);
}

static ob_fit_status fit1(const ob_method *m, const ob_bez *b, double d, ob_fit *f, char *msg)
{
    return fit_with(m, b, d, f, msg, NULL);
}

/* Independent normal: (-y', x') / |C'| from testlib's evaluation. */
static void ref_normal(const ob_bez *b, double t, double p[2], double n[2])
{
    double o[2][2];
    ref_eval(b, t, 1, o);
    const double s = hypot(o[1][0], o[1][1]);
    p[0] = o[0][0];
    p[1] = o[0][1];
    n[0] = -o[1][1] / s;
    n[1] = o[1][0] / s;
}

/* Zhao-Zhou's e(t) = (R(t) - C(t) - d N(t)) . N(t) and the cross component. */
static double paper_e(const ob_bez *C, const ob_bez *R, double d, double t, double *cross)
{
    double p[2], n[2], r[2];
    ref_normal(C, t, p, n);
    ref_point(R, t, r);
    const double v[2] = {r[0] - p[0] - d * n[0], r[1] - p[1] - d * n[1]};
    if (cross)
        *cross = v[0] * n[1] - v[1] * n[0];
    return v[0] * n[0] + v[1] * n[1];
}

/* Sign runs of e(t) on a dense grid: their count, the largest |e| and the
 * smallest run maximum over the largest (1 = equal extrema). */
typedef struct {
    int runs;
    double emax, ratio, crossmax;
} osc;

static osc oscillation(const ob_bez *C, const ob_bez *R, double d)
{
    enum { G = 4000 };
    osc o = {0, 0.0, 0.0, 0.0};
    double lo = INFINITY, runmax = 0.0;
    int sign = 0;
    for (int i = 0; i <= G; i++) {
        double cr, e = paper_e(C, R, d, (double)i / G, &cr);
        o.crossmax = fmax(o.crossmax, fabs(cr));
        int s = e >= 0.0 ? 1 : -1;
        if (s != sign) {
            if (sign != 0)
                lo = fmin(lo, runmax);
            o.runs++;
            sign = s;
            runmax = 0.0;
        }
        runmax = fmax(runmax, fabs(e));
        o.emax = fmax(o.emax, fabs(e));
    }
    lo = fmin(lo, runmax);
    o.ratio = o.emax > 0.0 ? lo / o.emax : 1.0;
    return o;
}

static double measure(ob_metric mt, const ob_bez *C, const ob_bez *A, double d)
{
    ob_errval e;
    ob_measure(mt, C, A, d, OB_DEFAULT_SAMPLES, &e);
    return e.err;
}

/* Euclidean size of a segment's control polygon. */
static double size_of(const ob_bez *b)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i <= b->deg; i++)
        for (int c = 0; c < 2; c++) {
            lo[c] = fmin(lo[c], b->h[i][c] / b->h[i][2]);
            hi[c] = fmax(hi[c], b->h[i][c] / b->h[i][2]);
        }
    return fmax(hi[0] - lo[0], hi[1] - lo[1]);
}

/* Möbius reparameterization: w_i -> w_i c^i (same curve). */
static ob_bez mobius(const ob_bez *b, double c)
{
    ob_bez r = *b;
    double f = 1.0;
    for (int i = 0; i <= b->deg; i++, f *= c)
        for (int k = 0; k < 3; k++)
            r.h[i][k] *= f;
    r.rational = 1;
    return r;
}

/* Product of Bernstein polynomials a (degree m) and b (degree n), by the
 * product formula with testlib's binomials. */
static void bmul(const double *a, int m, const double *b, int n, double *c)
{
    for (int k = 0; k <= m + n; k++) {
        c[k] = 0.0;
        for (int i = 0; i <= m; i++) {
            int j = k - i;
            if (j >= 0 && j <= n)
                c[k] += binom(m, i) * binom(n, j) / binom(m + n, k) * a[i] * b[j];
        }
    }
}

/* The base composed with t = phi(s) = (s + s^2)/2 (regular: phi' in [1/2, 3/2]),
 * exactly, as a Bézier of degree 2n in s. */
static ob_bez compose(const ob_bez *b)
{
    static const double phi[3] = {0.0, 0.25, 1.0}, omphi[3] = {1.0, 0.75, 0.0};
    const int n = b->deg;
    ob_bez r;
    memset(&r, 0, sizeof r);
    r.deg = 2 * n;
    r.rational = b->rational;
    for (int i = 0; i <= n; i++) {
        double p[2 * OB_MAX_DEG + 3] = {1.0}, q[2 * OB_MAX_DEG + 3];
        int pd = 0;
        for (int j = 0; j < n; j++) {
            bmul(p, pd, j < i ? phi : omphi, 2, q);
            pd += 2;
            memcpy(p, q, (size_t)(pd + 1) * sizeof *p);
        }
        for (int k = 0; k <= 2 * n; k++)
            for (int c = 0; c < 3; c++)
                r.h[k][c] += binom(n, i) * p[k] * b->h[i][c];
    }
    return r;
}

/* ratlsq's nodes (Numerical Recipes 5.13), recomputed: sin^2(pi/2 j/(npt-1)). */
static double node(int j, int npt) { return pow(sin(0.5 * OB_PI * j / (npt - 1)), 2); }

/* ---- test curves -------------------------------------------------------- */

static ob_bez CL, LIU, LH0, LH1, QZ, SEPTIC, LINE, RC;

static void make_curves(void)
{
    const double k = 0.5522847498307936;
    static double cl[4][2] = {{1, 0}, {1, 0}, {0, 1}, {0, 1}};
    cl[1][1] = k;
    cl[2][0] = k;
    CL = make(3, (const double(*)[2])cl, NULL);
    static const double liu[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};
    LIU = make(3, liu, NULL);
    ob_bez_subsegment(&LIU, 0.0, 0.5, &LH0);
    ob_bez_subsegment(&LIU, 0.5, 1.0, &LH1);
    static const double qz[6][2] = {{3, -1}, {4, 2}, {4.5, 2}, {5.5, 1.5}, {6.5, 0}, {7, -1}};
    QZ = make(5, qz, NULL);
    static const double sep[8][2] = {{-0.8, 1.5}, {1, 0}, {2, 0.4}, {1.8, 2}, {0, 2.5}, {-1.2, 3.7}, {0, 1.5}, {1.5, 3.9}};
    SEPTIC = make(7, sep, NULL);
    static const double line[4][2] = {{0.1, -0.2}, {0.31, -0.06}, {1.9, 1.0}, {3.1, 1.8}};
    LINE = make(3, line, NULL);
    static const double w[4] = {1.0, 1.3, 0.8, 1.0};
    RC = make(3, (const double(*)[2])cl, w);
}

/* ---- zhao ------------------------------------------------------------------ */

static void test_zhao_structure(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    CHECK(ZP->caps & OB_CAP_POLY_OUT, "zhao: polynomial output");
    CHECK(ZR->caps & OB_CAP_RATIONAL_OUT, "zhao-rational: rational output");
    CHECK((ZP->caps & OB_CAP_SAME_PARAM) && (ZR->caps & OB_CAP_SAME_PARAM), "zhao: same parameter");
    CHECK(ob_method_out_degree(ZP, 3, 0, NULL) == 3 && ob_method_out_degree(ZR, 5, 1, NULL) == 5, "zhao: degree n");
    const ob_bez *bs[3] = {&CL, &QZ, &LH0};
    for (int i = 0; i < 3; i++) {
        ob_fit_status st = fit1(ZP, bs[i], 0.3, &f, msg);
        CHECK(st == OB_FIT_OK && f.n == 1 && f.seg[0].deg == bs[i]->deg && !f.seg[0].rational,
              "zhao: curve %d: %s (%s)", i, ob_fit_status_name(st), msg);
        int ones = 1;
        for (int j = 0; j <= f.seg[0].deg; j++)
            ones &= f.seg[0].h[j][2] == 1.0;
        CHECK(ones, "zhao: curve %d: weights not all 1", i);
        st = fit1(ZR, bs[i], 0.3, &f, msg);
        CHECK(st == OB_FIT_OK && f.n == 1 && f.seg[0].deg == bs[i]->deg && f.seg[0].rational,
              "zhao-rational: curve %d: %s (%s)", i, ob_fit_status_name(st), msg);
    }
    /* output degree as a parameter */
    ob_fit_status st = fit_with(ZP, &CL, 0.3, &f, msg, (const char *const[]){"degree=5", NULL});
    CHECK(st == OB_FIT_OK && f.seg[0].deg == 5, "zhao degree=5: %s, degree %d", msg, f.seg[0].deg);
    st = fit_with(ZP, &CL, 0.3, &f, msg, (const char *const[]){"degree=40", NULL});
    CHECK(st == OB_FIT_SKIP && msg[0], "zhao degree=40: %s (%s)", ob_fit_status_name(st), msg);
    st = fit_with(ZR, &CL, 0.3, &f, msg, (const char *const[]){"npfac=0", NULL});
    CHECK(st == OB_FIT_SKIP && msg[0], "zhao npfac=0: %s (%s)", ob_fit_status_name(st), msg);
}

/* Offsets that lie in the approximation space come out exact. */
static void test_zhao_exact(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_bez lc = compose(&LINE);
    const ob_bez *lines[2] = {&LINE, &lc};
    for (int l = 0; l < 2; l++)
        for (int r = 0; r < 2; r++)
            for (int s = -1; s <= 1; s += 2) {
                const ob_method *m = r ? ZR : ZP;
                double d = 0.7 * s;
                ob_fit_status st = fit1(m, lines[l], d, &f, msg);
                CHECK(st == OB_FIT_OK, "%s line %d d %g: %s", m->name, l, d, msg);
                if (st != OB_FIT_OK)
                    continue;
                osc o = oscillation(lines[l], &f.seg[0], d);
                CHECK(o.emax < 1e-12 && o.crossmax < 1e-12, "%s line %d d %g: e %g cross %g",
                      m->name, l, d, o.emax, o.crossmax);
                double h = measure(OB_METRIC_HAUSDORFF, lines[l], &f.seg[0], d);
                CHECK(h < 1e-12, "%s line %d d %g: hausdorff %g", m->name, l, d, h);
            }
    /* circular arcs as rational quadratics, also Möbius-reparameterized */
    const double cs[3] = {1.0, 0.5, 2.0};
    for (int cw = 0; cw < 2; cw++)
        for (int i = 0; i < 3; i++)
            for (int s = -1; s <= 1; s += 2) {
                ob_bez qc = quarter_circle(2.0, cw), b = i ? mobius(&qc, cs[i]) : qc;
                double d = 0.6 * s;
                ob_fit_status st = fit1(ZR, &b, d, &f, msg);
                CHECK(st == OB_FIT_OK, "zhao-rational circle c %g d %g: %s", cs[i], d, msg);
                if (st != OB_FIT_OK)
                    continue;
                osc o = oscillation(&b, &f.seg[0], d);
                double bd = measure(OB_METRIC_BOUND, &b, &f.seg[0], d);
                double nm = measure(OB_METRIC_NORMAL, &b, &f.seg[0], d);
                CHECK(o.emax < 1e-12 && bd < 1e-12 && nm < 1e-12, "zhao-rational circle cw %d c %g "
                      "d %g: e %g bound %g normal %g", cw, cs[i], d, o.emax, bd, nm);
            }
}

/* Same curve, same parameter: the fit does not see degree elevation. */
static void test_zhao_elevation(void)
{
    static ob_fit f0, f1;
    char msg[MSGLEN];
    const ob_bez *bs[3] = {&CL, &LH0, &RC};
    const double ds[3] = {0.3, 1.0, -0.3};
    for (int i = 0; i < 3; i++)
        for (int r = 0; r < 2; r++)
            for (int up = 1; up <= 4; up += 3) {
                const ob_method *m = r ? ZR : ZP;
                ob_bez E;
                ob_bez_elevate(bs[i], bs[i]->deg + up, &E);
                ob_fit_status s0 = fit_with(m, bs[i], ds[i], &f0, msg, (const char *const[]){"degree=3", NULL});
                ob_fit_status s1 = fit_with(m, &E, ds[i], &f1, msg, (const char *const[]){"degree=3", NULL});
                CHECK(s0 == s1, "%s curve %d elevated +%d: status %s vs %s", m->name, i, up,
                      ob_fit_status_name(s0), ob_fit_status_name(s1));
                if (s0 != OB_FIT_OK || s1 != OB_FIT_OK)
                    continue;
                double diff = 0.0, sz = size_of(&f0.seg[0]);
                for (int j = 0; j <= 3; j++)
                    for (int c = 0; c < 3; c++)
                        diff = fmax(diff, fabs(f0.seg[0].h[j][c] - f1.seg[0].h[j][c]));
                CHECK(diff < 1e-11 * fmax(1.0, sz), "%s curve %d elevated +%d: control points differ "
                      "by %g", m->name, i, up, diff);
                osc o0 = oscillation(bs[i], &f0.seg[0], ds[i]), o1 = oscillation(&E, &f1.seg[0], ds[i]);
                CHECK(fabs(o0.emax - o1.emax) <= 1e-9 * o0.emax, "%s curve %d elevated +%d: error "
                      "%.12g vs %.12g", m->name, i, up, o0.emax, o1.emax);
            }
}

/* Möbius reparameterization of a rational base (zhao-rational) and the
 * polynomial reparameterization t = (s + s^2)/2: printed; the Möbius case is
 * also checked to stay within a factor 2 (it is not invariant: the nodes
 * move). */
static void test_zhao_reparam(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    const ob_bez *bs[3] = {&RC, &LH0, &CL};
    const char *names[3] = {"rational cubic", "liu2002_ex1 [0,.5]", "circle-like cubic"};
    const double ds[3] = {0.3, 1.0, 0.3};
    for (int i = 0; i < 3; i++) {
        printf("zhao reparameterization, %s, d %g, normal metric:\n", names[i], ds[i]);
        for (int r = 0; r < 2; r++) {
            const ob_method *m = r ? ZR : ZP;
            double e0 = NAN;
            if (fit1(m, bs[i], ds[i], &f, msg) == OB_FIT_OK)
                e0 = measure(OB_METRIC_NORMAL, bs[i], &f.seg[0], ds[i]);
            printf("  %-13s original %.4g", m->name, e0);
            for (double c = 0.5; c <= 2.0; c *= 4) {
                ob_bez M = mobius(bs[i], c);
                ob_fit_status st = fit1(m, &M, ds[i], &f, msg);
                double e = st == OB_FIT_OK ? measure(OB_METRIC_NORMAL, &M, &f.seg[0], ds[i]) : NAN;
                printf("  Moebius w_i c^i, c = %g: %.4g", c, e);
                if (r == 1 && i < 2) {
                    CHECK(st == OB_FIT_OK && e < 2.0 * e0 && e > 0.5 * e0, "zhao-rational %s Moebius "
                          "c %g: %s, error %g vs %g", names[i], c, msg, e, e0);
                }
            }
            ob_bez P = compose(bs[i]);
            ob_fit_status st = fit1(m, &P, ds[i], &f, msg);
            double e = st == OB_FIT_OK ? measure(OB_METRIC_NORMAL, &P, &f.seg[0], ds[i]) : NAN;
            printf("  t=(s+s^2)/2 (degree %d): %.4g\n", P.deg, e);
        }
    }
}

/* The accelerated iteration. */
static void test_zhao_iteration(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    const ob_bez *bs[4] = {&CL, &CL, &LH0, &QZ};
    const double ds[4] = {0.3, -0.3, 1.0, 0.5};
    for (int i = 0; i < 4; i++)
        for (int r = 0; r < 2; r++) {
            const ob_method *m = r ? ZR : ZP;
            const int n = bs[i]->deg, k = r ? (3 * n + 3) / 2 : n + 1, npt = 8 * k;
            /* the largest error at the nodes never grows with the iteration count */
            double prev = INFINITY;
            osc first = {0}, conv = {0};
            for (int it = 1; it <= 8; it++) {
                char set[32];
                snprintf(set, sizeof set, "iterations=%d", it);
                ob_fit_status st = fit_with(m, bs[i], ds[i], &f, msg, (const char *const[]){set, NULL});
                CHECK(st == OB_FIT_OK, "%s curve %d it %d: %s", m->name, i, it, msg);
                if (st != OB_FIT_OK)
                    break;
                double dev = 0.0;
                for (int j = 0; j < npt; j++)
                    dev = fmax(dev, fabs(paper_e(bs[i], &f.seg[0], ds[i], node(j, npt), NULL)));
                CHECK(dev <= prev * (1.0 + 1e-12), "%s curve %d: node error %g after %d iterations, "
                      "%g before", m->name, i, dev, it, prev);
                prev = dev;
                if (it == 1)
                    first = oscillation(bs[i], &f.seg[0], ds[i]);
            }
            ob_fit_status st = fit_with(m, bs[i], ds[i], &f, msg, (const char *const[]){"iterations=30", NULL});
            CHECK(st == OB_FIT_OK, "%s curve %d, 30 iterations: %s", m->name, i, msg);
            if (st != OB_FIT_OK)
                continue;
            conv = oscillation(bs[i], &f.seg[0], ds[i]);
            printf("%s curve %d d %g: k %d; iteration 1: %d sign runs, max %.4g, min/max extremum "
                   "%.2f; 30 iterations: %d runs, max %.4g, min/max %.2f\n", m->name, i, ds[i], k,
                   first.runs, first.emax, first.ratio, conv.runs, conv.emax, conv.ratio);
            CHECK(conv.runs >= (r ? k - 1 : k), "%s curve %d: %d alternating extrema, k = %d", m->name,
                  i, conv.runs, k);
            CHECK(conv.emax <= 1.01 * first.emax, "%s curve %d: error %g after 30 iterations, %g "
                  "after 1", m->name, i, conv.emax, first.emax);
            if (r)
                CHECK(conv.ratio > first.ratio, "zhao-rational curve %d: "
                      "extrema ratio %.3f after 30 iterations, %.3f after 1", i, conv.ratio, first.ratio);
        }
}

static void test_zhao_misc(void)
{
    static ob_fit f, g;
    char msg[MSGLEN];
    /* polynomial zhao against cobb on a circle-like cubic, same degree */
    for (int s = -1; s <= 1; s += 2) {
        double d = 0.3 * s;
        ob_fit_status a = fit1(ZP, &CL, d, &f, msg), b = fit1(COBB, &CL, d, &g, msg);
        CHECK(a == OB_FIT_OK && b == OB_FIT_OK, "zhao / cobb on the circle-like cubic");
        if (a == OB_FIT_OK && b == OB_FIT_OK) {
            double ez = measure(OB_METRIC_NORMAL, &CL, &f.seg[0], d);
            double ec = measure(OB_METRIC_NORMAL, &CL, &g.seg[0], d);
            printf("circle-like cubic d %g: zhao %.4g, cobb %.4g (normal metric)\n", d, ez, ec);
            CHECK(ez < ec, "zhao %g not below cobb %g, d %g", ez, ec, d);
        }
    }
    /* rational outputs: denominators positive on [0,1] */
    const ob_bez *bs[5] = {&CL, &LH0, &QZ, &QZ, &RC};
    const double ds[5] = {-0.3, 1.0, 0.25, 1.0, 0.3};
    for (int i = 0; i < 5; i++) {
        ob_fit_status st = fit1(ZR, bs[i], ds[i], &f, msg);
        CHECK(st == OB_FIT_OK, "zhao-rational curve %d: %s", i, msg);
        if (st != OB_FIT_OK)
            continue;
        double qmin = INFINITY;
        for (int j = 0; j <= 2000; j++) {
            double t = j / 2000.0, q = 0.0;
            for (int l = 0; l <= f.seg[0].deg; l++)
                q += f.seg[0].h[l][2] * bern(f.seg[0].deg, l, t);
            qmin = fmin(qmin, q);
        }
        CHECK(qmin > 0.0, "zhao-rational curve %d: denominator down to %g", i, qmin);
    }
    /* a denominator with a root in [0,1] on every iterate: by default the
     * piece goes back to the driver to be split, on_pole=0 fails with a reason:
     * liu2002_ex1 as a whole (d = 1) */
    ob_fit_status st = fit1(ZR, &LIU, 1.0, &f, msg);
    CHECK(st == OB_FIT_RETRY_SMALLER && strstr(msg, "denominator"), "zhao-rational liu2002_ex1: %s (%s)",
          ob_fit_status_name(st), msg);
    st = fit_with(ZR, &LIU, 1.0, &f, msg, (const char *const[]){"on_pole=0", NULL});
    CHECK(st == OB_FIT_FAIL && strstr(msg, "denominator"), "zhao-rational liu2002_ex1, "
          "on_pole=0: %s (%s)", ob_fit_status_name(st), msg);
    /* the polynomial form: symmetric under reversal (no normalization) */
    ob_bez rv = reversed(&LH0);
    ob_fit_status s0 = fit1(ZP, &LH0, 1.0, &f, msg), s1 = fit1(ZP, &rv, -1.0, &g, msg);
    if (s0 == OB_FIT_OK && s1 == OB_FIT_OK) {
        double diff = 0.0;
        for (int j = 0; j <= 3; j++)
            for (int c = 0; c < 2; c++)
                diff = fmax(diff, fabs(f.seg[0].h[j][c] - g.seg[0].h[3 - j][c]));
        CHECK(diff < 1e-12, "zhao: reversed curve gives control points differing by %g", diff);
    }
}

/* Zhao-Zhou section 4: the septic, d = 0.5 (and -0.5), after 1 and 2
 * iterations, next to the paper's 0.0428 / 0.0363 (96 sample points). */
static void report_septic(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    for (int s = 1; s >= -1; s -= 2)
        for (int r = 0; r < 2; r++) {
            const ob_method *m = r ? ZR : ZP;
            printf("septic (Zhao-Zhou sec. 4) %s d %g:", m->name, 0.5 * s);
            for (int it = 1; it <= 2; it++) {
                char set[32];
                snprintf(set, sizeof set, "iterations=%d", it);
                ob_fit_status st = fit_with(m, &SEPTIC, 0.5 * s, &f, msg, (const char *const[]){set, NULL});
                if (st != OB_FIT_OK) {
                    printf("  iteration %d: %s (%s)", it, ob_fit_status_name(st), msg);
                    continue;
                }
                double dev = 0.0;
                for (int j = 0; j < 96; j++)
                    dev = fmax(dev, fabs(paper_e(&SEPTIC, &f.seg[0], 0.5 * s, node(j, 96), NULL)));
                printf("  iteration %d: normal metric %.4g, e(t) at the %d nodes %.4g, dense e(t) %.4g", it,
                       measure(OB_METRIC_NORMAL, &SEPTIC, &f.seg[0], 0.5 * s), 8 * (r ? 12 : 8), dev,
                       oscillation(&SEPTIC, &f.seg[0], 0.5 * s).emax);
            }
            printf("  (paper, rational: 0.0428 / 0.0363)\n");
        }
}

/* ---- hoschek ---------------------------------------------------------------- */

/* Sum over the interior samples Q_j = O(j/(M-1)) of the squared distance to
 * A: nearest point by a scan of A and golden-section refinement. */
static double resid(const ob_bez *C, double d, const ob_bez *A, int M)
{
    enum { G = 1000 };
    static double pts[G + 1][2];
    for (int i = 0; i <= G; i++)
        ref_point(A, (double)i / G, pts[i]);
    double s = 0.0;
    for (int j = 1; j < M - 1; j++) {
        double p[2], n[2], Q[2];
        ref_normal(C, (double)j / (M - 1), p, n);
        Q[0] = p[0] + d * n[0];
        Q[1] = p[1] + d * n[1];
        int bi = 0;
        for (int i = 1; i <= G; i++)
            if (dist2d(pts[i], Q) < dist2d(pts[bi], Q))
                bi = i;
        double lo = fmax(0.0, (bi - 1.0) / G), hi = fmin(1.0, (bi + 1.0) / G);
        const double gr = 0.5 * (sqrt(5.0) - 1.0);
        for (int it = 0; it < 80; it++) {
            double a = hi - gr * (hi - lo), b = lo + gr * (hi - lo), pa[2], pb[2];
            ref_point(A, a, pa);
            ref_point(A, b, pb);
            if (dist2d(pa, Q) < dist2d(pb, Q))
                hi = b;
            else
                lo = a;
        }
        double q[2];
        ref_point(A, 0.5 * (lo + hi), q);
        double dd = dist2d(q, Q);
        if (bi == 0 || bi == G) {
            ref_point(A, bi ? 1.0 : 0.0, q);
            dd = fmin(dd, dist2d(q, Q));
        }
        s += dd * dd;
    }
    return s;
}

static void test_hoschek(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    CHECK(!(HO->caps & OB_CAP_SAME_PARAM) && (HO->caps & OB_CAP_POLY_OUT), "hoschek caps");
    /* end points interpolated; end tangents when asked */
    ob_bez qc = quarter_circle(2.0, 0);
    const ob_bez *bs[6] = {&CL, &LH0, &LH1, &QZ, &RC, &qc};
    const double ds[6] = {0.3, 1.0, 1.0, 0.5, -0.3, 0.6};
    for (int i = 0; i < 6; i++)
        for (int tg = 0; tg < 2; tg++) {
            ob_fit_status st = fit_with(HO, bs[i], ds[i], &f, msg,
                                        (const char *const[]){tg ? "tangents=1" : "tangents=0", NULL});
            if (tg && bs[i]->deg < 3) {
                CHECK(st == OB_FIT_SKIP && msg[0], "hoschek tangents=1, degree %d: %s", bs[i]->deg,
                      ob_fit_status_name(st));
                continue;
            }
            CHECK(st == OB_FIT_OK && f.n == 1, "hoschek curve %d tangents %d: %s", i, tg, msg);
            if (st != OB_FIT_OK)
                continue;
            const ob_bez *A = &f.seg[0];
            CHECK(A->deg == bs[i]->deg && !A->rational, "hoschek curve %d: degree %d", i, A->deg);
            for (int e = 0; e < 2; e++) {
                double p[2], n[2], a[2][2];
                ref_normal(bs[i], e, p, n);
                ref_eval(A, e, 1, a);
                double o[2] = {p[0] + ds[i] * n[0], p[1] + ds[i] * n[1]};
                CHECK(dist2d(a[0], o) <= 1e-14 * (1.0 + size_of(bs[i])), "hoschek curve %d end %d: "
                      "%g from the offset", i, e, dist2d(a[0], o));
                if (tg) {
                    /* the offset's tangent is C' (1 - d kappa): parallel to C', reversed
                     * where 1 - d kappa < 0 (liu2002_ex1 at t = 0.5, d = 1) */
                    double c[3][2];
                    ref_eval(bs[i], e, 2, c);
                    double sp = hypot(c[1][0], c[1][1]);
                    double kap = (c[1][0] * c[2][1] - c[1][1] * c[2][0]) / (sp * sp * sp);
                    /* a zero end leg (tangent length clamped at 0) is allowed: it
                     * happens at the start of liu2002_ex1 [0.5,1], d = 1, where
                     * 1 - d kappa = 0.03 (the offset is nearly cusped) */
                    double na = hypot(a[1][0], a[1][1]);
                    double cr = na > 0.0 ? (a[1][0] * c[1][1] - a[1][1] * c[1][0]) / (na * sp) : 0.0;
                    double dt = (a[1][0] * c[1][0] + a[1][1] * c[1][1]) * (1.0 - ds[i] * kap);
                    CHECK(fabs(cr) < 1e-12 && (dt > 0.0 || na == 0.0), "hoschek curve %d end %d: "
                          "tangent cross %g, dot %g", i, e, cr, dt);
                }
            }
        }
    /* the residual falls with the parameter corrections */
    const ob_bez *rs[4] = {&LH0, &LH1, &QZ, &CL};
    const double rd[4] = {1.0, 1.0, 0.5, 0.3};
    static const int its[] = {0, 1, 2, 3, 5, 10, 20, 40};
    for (int i = 0; i < 4; i++) {
        const int M = 8 * (rs[i]->deg + 1);
        double prev = INFINITY, r0 = NAN, rl = NAN;
        printf("hoschek curve %d d %g: residual", i, rd[i]);
        for (size_t k = 0; k < sizeof its / sizeof its[0]; k++) {
            char set[32];
            snprintf(set, sizeof set, "iterations=%d", its[k]);
            ob_fit_status st = fit_with(HO, rs[i], rd[i], &f, msg, (const char *const[]){set, NULL});
            CHECK(st == OB_FIT_OK, "hoschek curve %d iterations %d: %s", i, its[k], msg);
            if (st != OB_FIT_OK)
                break;
            double r = resid(rs[i], rd[i], &f.seg[0], M);
            printf(" %d:%.4g", its[k], r);
            CHECK(r <= prev * (1.0 + 1e-9) + 1e-28, "hoschek curve %d: residual %.17g after %d "
                  "corrections, %.17g before", i, r, its[k], prev);
            if (k == 0)
                r0 = r;
            rl = r;
            prev = r;
        }
        printf(" (hausdorff %.4g)\n", measure(OB_METRIC_HAUSDORFF, rs[i], &f.seg[0], rd[i]));
        CHECK(rl < 0.9 * r0, "hoschek curve %d: residual %g after 40 corrections, %g without", i, rl, r0);
    }
    /* exact on a straight segment (non-uniform speed) */
    for (int tg = 0; tg < 2; tg++)
        for (int k = 0; k < 2; k++) {
            const char *set[3] = {tg ? "tangents=1" : "tangents=0", k ? "iterations=0" : "iterations=20", NULL};
            ob_fit_status st = fit_with(HO, &LINE, 0.7, &f, msg, set);
            CHECK(st == OB_FIT_OK, "hoschek line: %s", msg);
            if (st == OB_FIT_OK) {
                double h = measure(OB_METRIC_HAUSDORFF, &LINE, &f.seg[0], 0.7);
                CHECK(h < 1e-12, "hoschek line tangents %d %s: hausdorff %g", tg, set[1], h);
            }
        }
    /* degree as a parameter: a quintic fit of a cubic's offset is closer */
    ob_fit_status st = fit_with(HO, &LH0, 1.0, &f, msg, (const char *const[]){"degree=5", NULL});
    CHECK(st == OB_FIT_OK && f.seg[0].deg == 5, "hoschek degree=5: %s", msg);
    if (st == OB_FIT_OK) {
        double e5 = measure(OB_METRIC_HAUSDORFF, &LH0, &f.seg[0], 1.0);
        fit1(HO, &LH0, 1.0, &f, msg);
        double e3 = measure(OB_METRIC_HAUSDORFF, &LH0, &f.seg[0], 1.0);
        CHECK(e5 < e3, "hoschek: degree 5 error %g, degree 3 %g", e5, e3);
    }
    st = fit_with(HO, &LH0, 1.0, &f, msg, (const char *const[]){"samples=3", NULL});
    CHECK(st == OB_FIT_SKIP && msg[0], "hoschek samples=3: %s (%s)", ob_fit_status_name(st), msg);
}

int main(void)
{
    ZP = ob_method_find("zhao");
    ZR = ob_method_find("zhao-rational");
    HO = ob_method_find("hoschek");
    COBB = ob_method_find("cobb");
    CHECK(ZP && ZR && HO && COBB, "zhao, zhao-rational, hoschek and cobb registered");
    if (!(ZP && ZR && HO && COBB))
        return check_done();
    size_t ws = ZP->work_size;
    ws = ws > ZR->work_size ? ws : ZR->work_size;
    ws = ws > HO->work_size ? ws : HO->work_size;
    work = malloc(ws);
    if (!work)
        return 2;
    make_curves();
    test_zhao_structure();
    test_zhao_exact();
    test_zhao_elevation();
    test_zhao_reparam();
    test_zhao_iteration();
    test_zhao_misc();
    report_septic();
    test_hoschek();
    free(work);
    return check_done();
}
