/*
 * test_shift.c - coquillart, elber, interp and kim2018.
 *
 * What each paper (or its description in Liu-Wang 2002 / Ahn 2023) claims, or
 * what must hold by construction:
 *   coquillart  P_j moved along N(xi_j) by d(1 - kappa_j D_j) (the default
 *               reading), xi_j the nearest curve point (checked against an
 *               independent brute-force projection); exact on circular arcs
 *               (rational quadratic and degree-elevated forms, both
 *               orientations, d = +-0.3) and on straight segments; the other
 *               sign reading is not exact on circles.
 *   elber       iterations = 0 is Cobb's polygon; the node errors fall with
 *               the iterations and converge to 0 (the limit is interp); the
 *               normal-only update converges along the normals; exact on lines.
 *               Adaptive variant: one B-spline (simple knots, C1 joints checked,
 *               n + 1 + k control points), every node of ||A - C||^2 within
 *               the tolerance, Cobb's segment for a loose tolerance, refinement
 *               growing with the tolerance, OB_FIT_RETRY_SMALLER past 16 pieces.
 *   interp      interpolates the exact offset at t*_j = j/n to 1e-12
 *               (polynomial and rational input), keeps the base's weights, is
 *               exact on a straight segment (any parameterization) and on a
 *               rational circular arc.
 *   kim2018     degree n+1 polynomial; N^a = (A - C)/d has N^a(0) = N(0),
 *               N^a(1) = N(1), (N^a)' parallel to C' with a linear factor
 *               alpha; G1 with the offset at both ends; exact on straight
 *               pieces; rational input skipped.
 * Reference values come from testlib.h (independent evaluation), not from
 * the library routines under test.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "methods/core/curve.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"
#include "tests/testlib.h"

extern const ob_method ob_method_coquillart, ob_method_elber, ob_method_interp, ob_method_kim2018,
    ob_method_cobb;

enum { MSGLEN = 160 };

/* ---- helpers ---------------------------------------------------------------- */

/* Fit with the method's defaults, parameter k overridden by v when k >= 0. */
static ob_fit_status fitp(const ob_method *m, const ob_bez *C, double d, int k, double v, ob_fit *f)
{
    double par[OB_MAX_PARAMS];
    ob_param_defaults(m, par);
    if (k >= 0)
        par[k] = v;
    void *work = malloc(m->work_size ? m->work_size : 1);
    char msg[MSGLEN] = "";
    const ob_fit_args a = {d, 1e-3, par};
    ob_fit_status st = m->fit(C, &a, work, f, msg, MSGLEN);
    if (st != OB_FIT_OK)
        fprintf(stderr, "  (%s: %s: %s)\n", m->name, ob_fit_status_name(st), msg);
    free(work);
    return st;
}

static ob_fit_status fit(const ob_method *m, const ob_bez *C, double d, ob_fit *f)
{
    return fitp(m, C, d, -1, 0.0, f);
}

/* Independent normal, curvature and offset point. */
static void ref_normal(const ob_bez *b, double t, double N[2], double *kappa)
{
    double o[3][2];
    ref_eval(b, t, 2, o);
    double s = hypot(o[1][0], o[1][1]);
    N[0] = -o[1][1] / s;
    N[1] = o[1][0] / s;
    if (kappa)
        *kappa = (o[1][0] * o[2][1] - o[1][1] * o[2][0]) / (s * s * s);
}

static void ctrl(const ob_bez *b, int i, double p[2])
{
    p[0] = b->h[i][0] / b->h[i][2];
    p[1] = b->h[i][1] / b->h[i][2];
}

static double hausdorff(const ob_bez *C, const ob_bez *A, double d)
{
    ob_errval e;
    ob_metric_hausdorff(C, A, d, 512, &e);
    return e.err;
}

static double radial(const ob_bez *C, const ob_bez *A, double d)
{
    ob_errval e;
    ob_metric_radial(C, A, d, 512, &e);
    return e.err;
}

/* Largest distance between A(j/n) and the exact offset at the nodes. */
static double node_error(const ob_bez *C, const ob_bez *A, double d)
{
    double worst = 0.0;
    for (int j = 0; j <= C->deg; j++) {
        double t = (double)j / C->deg, O[2], P[2];
        ref_offset(C, t, d, O);
        ref_point(A, t, P);
        worst = fmax(worst, dist2d(O, P));
    }
    return worst;
}

/* A circular arc of radius r about (cx, cy) from angle a0 to a1 (|a1 - a0| <
 * pi) as a rational quadratic; counterclockwise when a1 > a0. */
static ob_bez arc(double cx, double cy, double r, double a0, double a1)
{
    const double h = 0.5 * (a1 - a0), c = cos(h);
    double xy[3][2] = {{cx + r * cos(a0), cy + r * sin(a0)},
                       {cx + r / c * cos(a0 + h), cy + r / c * sin(a0 + h)},
                       {cx + r * cos(a1), cy + r * sin(a1)}};
    double w[3] = {1.0, c, 1.0};
    return make(2, (const double (*)[2])xy, w);
}

/* Degree elevation by one, written out (homogeneous). */
static ob_bez elevate1(const ob_bez *b)
{
    ob_bez e;
    memset(&e, 0, sizeof e);
    const int n = b->deg;
    e.deg = n + 1;
    e.rational = b->rational;
    for (int i = 0; i <= n + 1; i++)
        for (int c = 0; c < 3; c++) {
            double a = i > 0 ? (double)i / (n + 1) * b->h[i - 1][c] : 0.0;
            double z = i <= n ? (1.0 - (double)i / (n + 1)) * b->h[i][c] : 0.0;
            e.h[i][c] = a + z;
        }
    return e;
}

static const double liu_pts[4][2] = {
    {-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};

/* Convex quintic on a widening spiral (as test_methods.c). */
static ob_bez quintic(void)
{
    double q[6][2];
    for (int i = 0; i <= 5; i++) {
        double r = 2.5 + 0.25 * i, th = 0.45 * i;
        q[i][0] = r * cos(th);
        q[i][1] = r * sin(th);
    }
    return make(5, (const double (*)[2])q, NULL);
}

/* A straight segment of degree n with uneven spacing. */
static ob_bez line(int n)
{
    static const double s[] = {0.0, 0.07, 0.2, 0.6, 0.61, 0.9, 1.0};
    double p[8][2];
    for (int i = 0; i <= n; i++) {
        double u = i == n ? 1.0 : s[i];
        p[i][0] = 0.1 + 3.0 * u;
        p[i][1] = -0.2 + 2.0 * u;
    }
    return make(n, (const double (*)[2])p, NULL);
}

static const double DS[] = {0.3, -0.3, 1.0, -1.0};

/* ---- coquillart ---------------------------------------------------------------- */

/* Brute-force nearest parameter: dense scan plus golden-section refinement. */
static double ref_nearest(const ob_bez *b, const double P[2])
{
    const int S = 20001;
    int best = 0;
    double gb = INFINITY;
    for (int k = 0; k < S; k++) {
        double c[2];
        ref_point(b, (double)k / (S - 1), c);
        double g = dist2d(c, P);
        if (g < gb)
            gb = g, best = k;
    }
    double lo = fmax(0.0, (best - 1.0) / (S - 1)), hi = fmin(1.0, (best + 1.0) / (S - 1));
    const double phi = (sqrt(5.0) - 1.0) / 2.0;
    for (int it = 0; it < 80; it++) {
        double a = hi - phi * (hi - lo), bb = lo + phi * (hi - lo), ca[2], cb[2];
        ref_point(b, a, ca);
        ref_point(b, bb, cb);
        if (dist2d(ca, P) < dist2d(cb, P))
            hi = bb;
        else
            lo = a;
    }
    double t = 0.5 * (lo + hi), c[2];
    ref_point(b, t, c);
    return dist2d(c, P) < gb ? t : (double)best / (S - 1);
}

static void check_coquillart_rule(const char *cn, const ob_bez *C, double d, int foot)
{
    const ob_method *m = &ob_method_coquillart;
    static ob_fit f;
    if (fitp(m, C, d, 1, foot, &f) != OB_FIT_OK || f.n != 1) {
        CHECK(0, "coquillart %s %g: fit failed", cn, d);
        return;
    }
    CHECK(f.seg[0].deg == C->deg, "coquillart %s: degree %d", cn, f.seg[0].deg);
    for (int j = 0; j <= C->deg; j++) {
        double P[2], c[2], N[2], kap, Q[2];
        ctrl(C, j, P);
        double xi = foot ? (double)j / C->deg : ref_nearest(C, P);
        ref_point(C, xi, c);
        ref_normal(C, xi, N, &kap);
        double v[2] = {P[0] - c[0], P[1] - c[1]}, D = hypot(v[0], v[1]);
        if (v[0] * N[0] + v[1] * N[1] < 0.0)
            D = -D;
        double s = d * (1.0 - kap * D);
        ctrl(&f.seg[0], j, Q);
        double want[2] = {P[0] + s * N[0], P[1] + s * N[1]};
        CHECK(dist2d(Q, want) < 1e-7, "coquillart %s %g: Q_%d %.17g,%.17g vs %.17g,%.17g "
              "(xi %.9f)", cn, d, j, Q[0], Q[1], want[0], want[1], xi);
        CHECK(f.seg[0].h[j][2] == C->h[j][2], "coquillart %s: weight %d kept", cn, j);
    }
}

static void test_coquillart(void)
{
    const ob_method *m = &ob_method_coquillart;
    static ob_fit f;
    CHECK(m->nparams == 2 && ob_param_find(m, "reading") == 0 && m->params[0].def == 0.0 &&
          ob_param_find(m, "foot") == 1 && m->params[1].def == 0.0,
          "coquillart: parameters reading and foot, defaults 0");
    CHECK(ob_method_out_degree(m, 3, 0, NULL) == 3 && ob_method_out_degree(m, 2, 1, NULL) == 2, "coquillart: degree n");

    /* the rule itself, against an independent nearest-point search */
    ob_bez liu = make(3, liu_pts, NULL), q5 = quintic();
    for (int k = 0; k < 4; k++) {
        for (int foot = 0; foot < 2; foot++) {
            check_coquillart_rule("liu2002_ex1", &liu, DS[k], foot);
            check_coquillart_rule("quintic", &q5, DS[k], foot);
        }
    }

    /* the brief's arc: (1,0),(1,1),(0,1), w = 1, sqrt(2)/2, 1; the exact offset
     * is the polygon scaled by 1 - d about the origin (N points inwards) */
    ob_bez qc = quarter_circle(1.0, 0);
    for (int k = 0; k < 2; k++) {
        double d = DS[k];
        if (fit(m, &qc, d, &f) != OB_FIT_OK) {
            CHECK(0, "coquillart quarter circle %g: fit failed", d);
            continue;
        }
        for (int j = 0; j <= 2; j++) {
            double P[2], Q[2];
            ctrl(&qc, j, P);
            ctrl(&f.seg[0], j, Q);
            CHECK(dist2d(Q, (double[2]){(1 - d) * P[0], (1 - d) * P[1]}) < 1e-14,
                  "coquillart quarter circle %g: Q_%d = %.17g,%.17g not (1-d) P", d, j, Q[0], Q[1]);
            CHECK(f.seg[0].h[j][2] == qc.h[j][2], "coquillart quarter circle: weight %d kept", j);
        }
        double e = hausdorff(&qc, &f.seg[0], d), er = radial(&qc, &f.seg[0], d);
        CHECK(e < 1e-13 && er < 1e-13, "coquillart quarter circle %g: hausdorff %g radial %g", d, e,
              er);
        /* the literal-sign reading is not exact: the test can tell them apart */
        if (fitp(m, &qc, d, 0, 1.0, &f) == OB_FIT_OK)
            CHECK(hausdorff(&qc, &f.seg[0], d) > 1e-3, "coquillart reading 1 exact on a circle?");
    }
    /* other arcs: both orientations, off-centre, degree-elevated forms */
    struct { double cx, cy, r, a0, a1; } arcs[] = {
        {0.3, -0.7, 2.0, 0.2, 2.1}, {0.3, -0.7, 2.0, 2.1, 0.2}, {-1.0, 2.0, 0.8, -2.5, -1.0},
        {5.0, 1.0, 3.0, 1.0, 3.9}};
    for (size_t a = 0; a < sizeof arcs / sizeof arcs[0]; a++) {
        ob_bez A2 = arc(arcs[a].cx, arcs[a].cy, arcs[a].r, arcs[a].a0, arcs[a].a1);
        ob_bez A3 = elevate1(&A2), A4 = elevate1(&A3);
        const ob_bez *forms[3] = {&A2, &A3, &A4};
        for (int fm = 0; fm < 3; fm++)
            for (int k = 0; k < 2; k++) {
                double d = DS[k] * arcs[a].r;
                if (fit(m, forms[fm], d, &f) != OB_FIT_OK) {
                    CHECK(0, "coquillart arc %zu: fit failed", a);
                    continue;
                }
                double e = hausdorff(forms[fm], &f.seg[0], d);
                CHECK(e < 1e-12 * arcs[a].r, "coquillart arc %zu degree %d d %g: error %g", a,
                      forms[fm]->deg, d, e);
            }
    }
    /* straight segments: kappa = 0, every reading is the exact translation */
    for (int n = 1; n <= 6; n++) {
        ob_bez L = line(n);
        for (int reading = 0; reading < 4; reading++)
            for (int k = 0; k < 4; k++) {
                if (fitp(m, &L, DS[k], 0, reading, &f) != OB_FIT_OK) {
                    CHECK(0, "coquillart line: fit failed");
                    continue;
                }
                double e = hausdorff(&L, &f.seg[0], DS[k]), er = radial(&L, &f.seg[0], DS[k]);
                CHECK(e < 1e-12 && er < 1e-12, "coquillart line deg %d reading %d d %g: %g %g", n,
                      reading, DS[k], e, er);
            }
    }
    CHECK(fitp(m, &liu, 1.0, 0, 4.0, &f) == OB_FIT_FAIL, "coquillart: reading 4 rejected");
    CHECK(fitp(m, &liu, 1.0, 0, 0.5, &f) == OB_FIT_FAIL, "coquillart: reading 0.5 rejected");
    CHECK(fitp(m, &liu, 1.0, 1, 2.0, &f) == OB_FIT_FAIL, "coquillart: foot 2 rejected");
}

/* ---- elber ------------------------------------------------------------------------ */

static void test_elber(void)
{
    const ob_method *m = &ob_method_elber;
    static ob_fit f, g;
    CHECK(m->nparams == 4 && ob_param_find(m, "iterations") == 0 &&
          ob_param_find(m, "update") == 1 && m->params[1].def == 0.0 &&
          ob_param_find(m, "variant") == 2 && m->params[2].def == 0.0 &&
          ob_param_find(m, "rounds") == 3, "elber: parameters iterations, update, variant, rounds");
    ob_bez liu = make(3, liu_pts, NULL), q5 = quintic(), qc = quarter_circle(2.5, 0);
    const ob_bez *cs[3] = {&liu, &q5, &qc};
    const char *cn[3] = {"liu2002_ex1", "quintic", "quarter circle r 2.5"};
    static const int iters[] = {0, 1, 3, 10, 40, 2000};
    enum { NI = sizeof iters / sizeof iters[0] };
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 4; k++) {
            double d = DS[k];
            /* iterations = 0 is Cobb's polygon, bit for bit */
            if (fitp(m, cs[c], d, 0, 0.0, &f) == OB_FIT_OK && fit(&ob_method_cobb, cs[c], d, &g) == OB_FIT_OK)
                CHECK(memcmp(f.seg[0].h, g.seg[0].h, sizeof f.seg[0].h) == 0,
                      "elber %s %g: 0 iterations is not cobb", cn[c], d);
            double e[NI];
            for (int i = 0; i < NI; i++) {
                e[i] = INFINITY;
                if (fitp(m, cs[c], d, 0, iters[i], &f) == OB_FIT_OK)
                    e[i] = node_error(cs[c], &f.seg[0], d);
            }
            for (int i = 1; i < NI; i++)
                CHECK(e[i] < e[i - 1] || e[i] < 1e-13, "elber %s %g: node error %g after %d, %g "
                      "after %d iterations", cn[c], d, e[i - 1], iters[i - 1], e[i], iters[i]);
            CHECK(e[0] > 1e-4, "elber %s %g: Cobb's node error %g (nothing to improve?)", cn[c], d,
                  e[0]);
            CHECK(e[NI - 1] < 1e-12, "elber %s %g: not converged: node error %g", cn[c], d,
                  e[NI - 1]);
            /* the limit is the node interpolant */
            if (fitp(m, cs[c], d, 0, 2000, &f) == OB_FIT_OK && fit(&ob_method_interp, cs[c], d, &g) == OB_FIT_OK)
                for (int j = 0; j <= cs[c]->deg; j++) {
                    double a[2], b[2];
                    ctrl(&f.seg[0], j, a);
                    ctrl(&g.seg[0], j, b);
                    CHECK(dist2d(a, b) < 1e-10, "elber %s %g: limit Q_%d differs from interp by %g",
                          cn[c], d, j, dist2d(a, b));
                }
            /* the default improves on Cobb at the nodes and on the whole */
            if (fit(m, cs[c], d, &f) == OB_FIT_OK && fit(&ob_method_cobb, cs[c], d, &g) == OB_FIT_OK) {
                CHECK(node_error(cs[c], &f.seg[0], d) < e[0], "elber %s %g: default no better at "
                      "the nodes", cn[c], d);
                CHECK(f.seg[0].deg == cs[c]->deg, "elber: degree n");
            }
            /* update 1: the error along the node normals converges to 0 */
            double par[OB_MAX_PARAMS];
            ob_param_defaults(m, par);
            par[0] = 2000;
            par[1] = 1;
            char msg[MSGLEN];
            const ob_fit_args a = {d, 1e-3, par};
            if (m->fit(cs[c], &a, NULL, &f, msg, MSGLEN) == OB_FIT_OK) {
                double worst = 0.0;
                for (int j = 0; j <= cs[c]->deg; j++) {
                    double t = (double)j / cs[c]->deg, O[2], P[2], N[2];
                    ref_offset(cs[c], t, d, O);
                    ref_point(&f.seg[0], t, P);
                    ref_normal(cs[c], t, N, NULL);
                    worst = fmax(worst, fabs((O[0] - P[0]) * N[0] + (O[1] - P[1]) * N[1]));
                }
                CHECK(worst < 1e-12, "elber update 1 %s %g: normal node error %g", cn[c], d, worst);
            } else {
                CHECK(0, "elber update 1 %s %g: %s", cn[c], d, msg);
            }
        }
    for (int n = 1; n <= 6; n++) {
        ob_bez L = line(n);
        for (int k = 0; k < 4; k++)
            if (fitp(m, &L, DS[k], 0, 20, &f) == OB_FIT_OK)
                CHECK(hausdorff(&L, &f.seg[0], DS[k]) < 1e-12, "elber: line deg %d d %g", n, DS[k]);
    }
    CHECK(fitp(m, &liu, 1.0, 0, -1.0, &f) == OB_FIT_FAIL, "elber: iterations -1 rejected");
    CHECK(fitp(m, &liu, 1.0, 1, 2.0, &f) == OB_FIT_FAIL, "elber: update 2 rejected");
}

/* Elber's adaptive variant: one B-spline with simple knots. */
static ob_fit_status fit_adaptive(const ob_bez *C, double d, double tol, int rounds, ob_fit *f)
{
    const ob_method *m = &ob_method_elber;
    double par[OB_MAX_PARAMS];
    ob_param_defaults(m, par);
    par[2] = 1;
    par[3] = rounds;
    void *work = malloc(m->work_size);
    char msg[MSGLEN] = "";
    const ob_fit_args a = {d, tol, par};
    ob_fit_status st = m->fit(C, &a, work, f, msg, MSGLEN);
    free(work);
    return st;
}

static void check_adaptive(const char *cn, const ob_bez *C, double d, double tol)
{
    static ob_fit f, g;
    const int p = C->deg;
    ob_fit_status st = fit_adaptive(C, d, tol, 100, &f);
    CHECK(st == OB_FIT_OK || st == OB_FIT_RETRY_SMALLER, "elber adaptive %s %g %g: %s", cn, d, tol,
          ob_fit_status_name(st));
    if (st != OB_FIT_OK)
        return;
    const int np = f.n, k = np - 1;
    CHECK(np >= 1 && np <= OB_SPLIT_PIECES && f.t[0] == 0.0 && f.t[np] == 1.0,
          "elber adaptive %s: %d pieces", cn, np);
    if (np < 1 || np > OB_SPLIT_PIECES)
        return;
    CHECK(f.ctrl_points == p + 1 + k, "elber adaptive %s: %ld control points, %d pieces of degree "
          "%d", cn, f.ctrl_points, np, p);
    for (int s = 0; s < np; s++)
        CHECK(f.t[s] < f.t[s + 1] && f.seg[s].deg == p, "elber adaptive %s: piece %d", cn, s);
    /* C^(p-1) at the joints (checked to first order): one B-spline, simple knots */
    for (int s = 0; s + 1 < np; s++) {
        double a[2][2], b[2][2];
        ref_eval(&f.seg[s], 1.0, 1, a);
        ref_eval(&f.seg[s + 1], 0.0, 1, b);
        double ha = f.t[s + 1] - f.t[s], hb = f.t[s + 2] - f.t[s + 1];
        double da[2] = {a[1][0] / ha, a[1][1] / ha}, db[2] = {b[1][0] / hb, b[1][1] / hb};
        CHECK(dist2d(a[0], b[0]) < 1e-12 && dist2d(da, db) < 1e-9 * (1.0 + hypot(da[0], da[1])),
              "elber adaptive %s: joint %d not C1 (%g, %g)", cn, s, dist2d(a[0], b[0]),
              dist2d(da, db));
    }
    /* every node of D = ||A - C||^2 (Greville abscissae of degree 2p on the
     * knots 0^(2p+1), u_k^(p+1), 1^(2p+1)) passes the tolerance */
    double V[2 * (2 * OB_MAX_DEG + 1) + OB_SPLIT_PIECES * (OB_MAX_DEG + 1)];
    int nv = 0, worst_ok = 1;
    for (int r = 0; r <= 2 * p; r++)
        V[nv++] = 0.0;
    for (int s = 1; s < np; s++)
        for (int r = 0; r <= p; r++)
            V[nv++] = f.t[s];
    for (int r = 0; r <= 2 * p; r++)
        V[nv++] = 1.0;
    for (int i = 0; i + 2 * p + 1 < nv; i++) {
        double ts = 0.0;
        for (int q = 1; q <= 2 * p; q++)
            ts += V[i + q];
        ts /= 2 * p;
        int s = 0;
        while (s < np - 1 && f.t[s + 1] <= ts)
            s++;
        double A[2], Cp[2];
        ref_point(&f.seg[s], (ts - f.t[s]) / (f.t[s + 1] - f.t[s]), A);
        ref_point(C, ts, Cp);
        double e = fabs(dist2d(A, Cp) - fabs(d));
        if (!(e <= tol * (1 + 1e-9)))
            worst_ok = 0, fprintf(stderr, "  node %g error %g\n", ts, e);
    }
    CHECK(worst_ok, "elber adaptive %s %g %g: a node of D fails the tolerance", cn, d, tol);
    /* a tolerance the whole segment meets at its nodes: Cobb's segment */
    if (fit_adaptive(C, d, 10.0, 20, &f) == OB_FIT_OK && fit(&ob_method_cobb, C, d, &g) == OB_FIT_OK) {
        int same = f.n == 1 && f.ctrl_points == p + 1;
        for (int i = 0; same && i <= p; i++)
            for (int c = 0; c < 3; c++)
                same &= fabs(f.seg[0].h[i][c] - g.seg[0].h[i][c]) <= 1e-14 * (1.0 + fabs(g.seg[0].h[i][c]));
        CHECK(same, "elber adaptive %s: loose tolerance is not Cobb's segment", cn);
    }
}

static void test_elber_adaptive(void)
{
    static ob_fit f;
    ob_bez liu = make(3, liu_pts, NULL), q5 = quintic(), qc = quarter_circle(2.5, 0);
    for (int k = 0; k < 4; k++) {
        check_adaptive("liu2002_ex1", &liu, DS[k], 1e-2);
        check_adaptive("quintic", &q5, DS[k], 1e-3);
        check_adaptive("quarter circle", &qc, DS[k], 1e-3);
    }
    /* refinement grows as the tolerance shrinks, and runs out of pieces */
    int prev = 0, grows = 1;
    for (double tol = 1.0; tol >= 1e-3; tol /= 10) {
        ob_fit_status st = fit_adaptive(&liu, 1.0, tol, 20, &f);
        int np = st == OB_FIT_OK ? f.n : st == OB_FIT_RETRY_SMALLER ? OB_SPLIT_PIECES + 1 : -1;
        grows &= np >= prev;
        prev = np;
    }
    CHECK(grows && prev > 1, "elber adaptive: pieces %d do not grow with the tolerance", prev);
    CHECK(fit_adaptive(&liu, 1.0, 1e-9, 20, &f) == OB_FIT_RETRY_SMALLER,
          "elber adaptive: a tolerance past 16 pieces asks for a smaller piece");
    ob_bez L = line(3);
    CHECK(fit_adaptive(&L, 0.3, 1e-9, 20, &f) == OB_FIT_OK && f.n == 1 &&
          hausdorff(&L, &f.seg[0], 0.3) < 1e-12, "elber adaptive: a line is exact in one piece");
}

/* ---- interp ---------------------------------------------------------------------- */

static void test_interp(void)
{
    const ob_method *m = &ob_method_interp;
    static ob_fit f;
    CHECK(m->work_size > 0, "interp: uses scratch space");
    ob_bez liu = make(3, liu_pts, NULL), q5 = quintic(), qc = quarter_circle(2.5, 0);
    /* a degree-9 polynomial and a rational cubic */
    double p9[10][2], p3[4][2] = {{0, 0}, {1, 2}, {3, 2.5}, {4, 0.5}}, w3[4] = {1, 0.6, 1.7, 1};
    for (int i = 0; i <= 9; i++) {
        p9[i][0] = i + 0.3 * sin(i);
        p9[i][1] = 0.4 * i * i / 9.0;
    }
    ob_bez b9 = make(9, (const double (*)[2])p9, NULL), r3 = make(3, (const double (*)[2])p3, w3);
    const ob_bez *cs[5] = {&liu, &q5, &qc, &b9, &r3};
    const char *cn[5] = {"liu2002_ex1", "quintic", "quarter circle", "degree 9", "rational cubic"};
    for (int c = 0; c < 5; c++)
        for (int k = 0; k < 4; k++) {
            double d = DS[k];
            if (fit(m, cs[c], d, &f) != OB_FIT_OK || f.n != 1) {
                CHECK(0, "interp %s %g: fit failed", cn[c], d);
                continue;
            }
            CHECK(f.seg[0].deg == cs[c]->deg && f.seg[0].rational == cs[c]->rational,
                  "interp %s: degree %d rational %d", cn[c], f.seg[0].deg, f.seg[0].rational);
            double e = node_error(cs[c], &f.seg[0], d);
            CHECK(e < 1e-12, "interp %s %g: node error %g", cn[c], d, e);
            for (int j = 0; j <= cs[c]->deg; j++)
                CHECK(f.seg[0].h[j][2] == cs[c]->h[j][2], "interp %s: weight %d not the base's",
                      cn[c], j);
            if (!cs[c]->rational) {
                int poly = 1;
                for (int j = 0; j <= cs[c]->deg; j++)
                    poly &= f.seg[0].h[j][2] == 1.0;
                CHECK(poly, "interp %s: polynomial output", cn[c]);
            }
        }
    /* exact where the offset has the form of the base: lines, circular arcs */
    for (int n = 1; n <= 6; n++) {
        ob_bez L = line(n);
        for (int k = 0; k < 4; k++)
            if (fit(m, &L, DS[k], &f) == OB_FIT_OK) {
                double e = hausdorff(&L, &f.seg[0], DS[k]), er = radial(&L, &f.seg[0], DS[k]);
                CHECK(e < 1e-12 && er < 1e-12, "interp line deg %d d %g: %g %g", n, DS[k], e, er);
            }
    }
    for (int k = 0; k < 4; k++) {
        ob_bez A = arc(0.3, -0.7, 2.0, 2.1, 0.2);
        if (fit(m, &A, DS[k], &f) == OB_FIT_OK)
            CHECK(hausdorff(&A, &f.seg[0], DS[k]) < 1e-12, "interp arc d %g: %g", DS[k],
                  hausdorff(&A, &f.seg[0], DS[k]));
    }
    /* a curved polynomial is not exact (the check can fail) */
    if (fit(m, &liu, 1.0, &f) == OB_FIT_OK)
        CHECK(hausdorff(&liu, &f.seg[0], 1.0) > 1e-3, "interp liu2002_ex1 exact?");
}

/* ---- kim2018 ------------------------------------------------------------------------ */

static void check_kim(const char *cn, const ob_bez *C, double d0)
{
    const ob_method *m = &ob_method_kim2018;
    static ob_fit f;
    /* keep 1 - d kappa >= 0.5 at the ends, so the offset is regular there */
    double N0[2], N1[2], k0, k1;
    ref_normal(C, 0.0, N0, &k0);
    ref_normal(C, 1.0, N1, &k1);
    double d = d0 * fmin(1.0, 0.5 / fmax(fabs(k0), fabs(k1)));
    if (fit(m, C, d, &f) != OB_FIT_OK || f.n != 1) {
        CHECK(0, "kim2018 %s %g: fit failed", cn, d);
        return;
    }
    const ob_bez *A = &f.seg[0];
    const int n = C->deg;
    int poly = 1;
    for (int j = 0; j <= A->deg; j++)
        poly &= A->h[j][2] == 1.0;
    CHECK(A->deg == n + 1 && !A->rational && poly, "kim2018 %s: degree %d (want %d), rational %d",
          cn, A->deg, n + 1, A->rational);
    /* N^a(t) = (A(t) - C(t))/d, (N^a)'(t) = (A'(t) - C'(t))/d */
    double alpha[5];
    const double ts[5] = {0.0, 0.25, 0.5, 0.75, 1.0};
    for (int i = 0; i < 5; i++) {
        double a[2][2], c[2][2];
        ref_eval(A, ts[i], 1, a);
        ref_eval(C, ts[i], 1, c);
        double na[2] = {(a[0][0] - c[0][0]) / d, (a[0][1] - c[0][1]) / d};
        double dn[2] = {(a[1][0] - c[1][0]) / d, (a[1][1] - c[1][1]) / d};
        double c2 = c[1][0] * c[1][0] + c[1][1] * c[1][1];
        double cr = dn[0] * c[1][1] - dn[1] * c[1][0];
        CHECK(fabs(cr) <= 1e-10 * (hypot(dn[0], dn[1]) + 1.0) * sqrt(c2),
              "kim2018 %s %g: (N^a)' x C' = %g at t = %g", cn, d, cr, ts[i]);
        alpha[i] = (dn[0] * c[1][0] + dn[1] * c[1][1]) / c2;
        if (i == 0)
            CHECK(dist2d(na, N0) < 1e-12, "kim2018 %s %g: N^a(0) - N(0) = %g", cn, d,
                  dist2d(na, N0));
        if (i == 4)
            CHECK(dist2d(na, N1) < 1e-12, "kim2018 %s %g: N^a(1) - N(1) = %g", cn, d,
                  dist2d(na, N1));
    }
    /* alpha linear */
    double sc = fabs(alpha[0]) + fabs(alpha[4]) + 1.0;
    CHECK(fabs(alpha[2] - 0.5 * (alpha[0] + alpha[4])) < 1e-9 * sc &&
          fabs(alpha[1] - 0.75 * alpha[0] - 0.25 * alpha[4]) < 1e-9 * sc &&
          fabs(alpha[3] - 0.25 * alpha[0] - 0.75 * alpha[4]) < 1e-9 * sc,
          "kim2018 %s %g: alpha not linear: %g %g %g %g %g", cn, d, alpha[0], alpha[1], alpha[2],
          alpha[3], alpha[4]);
    /* G1 with the offset at the ends: A' = C'(1 + d alpha) parallel to
     * O' = C'(1 - d kappa), in the same direction where 1 + d alpha > 0 (alpha
     * is not matched to the curvature, so it may be reversed at an end of a
     * long piece) */
    for (int i = 0; i <= 1; i++) {
        double a[2][2], c[2][2], O[2], Ni[2], kap;
        ref_eval(A, i, 1, a);
        ref_eval(C, i, 1, c);
        ref_normal(C, i, Ni, &kap);
        ref_offset(C, i, d, O);
        double g = 1.0 - d * kap, dO[2] = {c[1][0] * g, c[1][1] * g};
        double cr = a[1][0] * dO[1] - a[1][1] * dO[0], dt = a[1][0] * dO[0] + a[1][1] * dO[1];
        CHECK(fabs(cr) <= 1e-10 * hypot(a[1][0], a[1][1]) * hypot(dO[0], dO[1]) &&
              (dt > 0.0) == (1.0 + d * alpha[4 * i] > 0.0),
              "kim2018 %s %g: A'(%d) not along the offset tangent (cross %g, dot %g, 1 + d alpha "
              "%g)", cn, d, i, cr, dt, 1.0 + d * alpha[4 * i]);
        double P[2];
        ref_point(A, i, P);
        CHECK(dist2d(P, O) < 1e-12, "kim2018 %s %g: A(%d) off the offset by %g", cn, d, i,
              dist2d(P, O));
    }
}

static void test_kim2018(void)
{
    const ob_method *m = &ob_method_kim2018;
    static ob_fit f;
    CHECK(ob_method_out_degree(m, 3, 0, NULL) == 4 && ob_method_out_degree(m, 5, 0, NULL) == 6, "kim2018: out_degree n+1");
    CHECK((m->caps & OB_CAP_CONVEX) && m->max_turn == OB_PI && !(m->caps & OB_CAP_RATIONAL_IN),
          "kim2018: convex pieces turning < pi, polynomial input");
    ob_bez liu = make(3, liu_pts, NULL), q5 = quintic();
    for (int k = 0; k < 4; k++) {
        check_kim("liu2002_ex1", &liu, DS[k]);
        check_kim("quintic", &q5, DS[k]);
        ob_bez H;
        ob_bez_subsegment(&liu, 0.2, 0.7, &H);
        check_kim("liu2002_ex1[0.2,0.7]", &H, DS[k]);
    }
    testlib_seed(0x5eed2018ULL);
    for (int c = 0; c < 20; c++) {
        /* random convex cubic: points on an arc of a circle, jittered */
        double p[4][2], r = urange(1.5, 4.0), th0 = urange(0, 6.28), span = urange(0.5, 2.5);
        for (int i = 0; i < 4; i++) {
            double th = th0 + span * (i / 3.0 + urange(-0.04, 0.04));
            p[i][0] = r * cos(th);
            p[i][1] = r * sin(th);
        }
        ob_bez b = make(3, (const double (*)[2])p, NULL);
        check_kim("random", &b, DS[c % 4]);
    }
    for (int n = 1; n <= 6; n++) {
        ob_bez L = line(n);
        for (int k = 0; k < 4; k++) {
            if (fit(m, &L, DS[k], &f) != OB_FIT_OK) {
                CHECK(0, "kim2018 line deg %d: fit failed", n);
                continue;
            }
            double e = hausdorff(&L, &f.seg[0], DS[k]), er = radial(&L, &f.seg[0], DS[k]);
            CHECK(e < 1e-12 && er < 1e-12, "kim2018 line deg %d d %g: %g %g", n, DS[k], e, er);
        }
    }
    char msg[MSGLEN] = "";
    double par[OB_MAX_PARAMS] = {0};
    const ob_fit_args a = {0.3, 1e-3, par};
    ob_bez qc = quarter_circle(1.0, 0);
    CHECK(m->fit(&qc, &a, NULL, &f, msg, MSGLEN) == OB_FIT_SKIP && msg[0],
          "kim2018: rational input skipped");
    /* halving: the radial error of a degree n+1 G1 scheme falls fast */
    if (fit(m, &liu, 1.0, &f) == OB_FIT_OK) {
        double whole = radial(&liu, &f.seg[0], 1.0);
        ob_bez L;
        ob_bez_subsegment(&liu, 0.0, 0.5, &L);
        if (fit(m, &L, 1.0, &f) == OB_FIT_OK)
            CHECK(radial(&L, &f.seg[0], 1.0) < 0.25 * whole, "kim2018: halving %g -> %g", whole,
                  radial(&L, &f.seg[0], 1.0));
    }
}

int main(void)
{
    test_coquillart();
    test_elber();
    test_elber_adaptive();
    test_interp();
    test_kim2018();
    return check_done();
}
