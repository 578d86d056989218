/*
 * test_normalfit.c - the Liu & Wang 2002 normal-curve family: liu (Legendre),
 * chebyshev and lstsq (methods/liu.c, chebyshev.c, lstsq.c, normalfit.c).
 *
 * What must hold (Liu & Wang 2002, §2.1-2.4):
 *  - the Gauss-Legendre rule integrates polynomials of degree <= 2M-1 exactly;
 *  - the end-constrained construction (eq. 6-7) reproduces every polynomial
 *    target of degree <= n (then f~ has degree <= n-2), for all three fits;
 *    hence a straight base segment (constant normal) is offset exactly, with
 *    D constant = d N, and a rational circular arc too (W d N is then a
 *    polynomial of degree n);
 *  - all three interpolate the offset at both ends;
 *  - liu's interior is the best L2 approximation of f~ (weight 1): compared
 *    with an independent brute-force least-squares fit on a dense grid, its
 *    L2 error agrees to quadrature accuracy and every perturbation of its
 *    coefficients increases it; its default node count is converged;
 *  - chebyshev and lstsq agree with liu to the expected order: normal-fit
 *    errors within a small factor of liu's, the same convergence rate
 *    (2^(n+1) per halving for cubics) when the piece is halved;
 *    chebyshev with n-1 nodes interpolates f~ at the Chebyshev points;
 *    lstsq of f~ with many samples tends to liu; lstsq of the normal
 *    samples has the smaller L2 error of the normal itself;
 *  - rational input keeps the weights, and the homogeneous shift c_i is the
 *    same fit applied to W(t) d N(t) (§2.4);
 *  - parameters out of range fail with a message.
 * Independent references: normals, weights and f~ from testlib's ref_eval and
 * bern; the brute-force fit by normal equations on the power-free Bernstein
 * basis of testlib.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "methods/core/curve.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"
#include "methods/common/normalfit.h"
#include "tests/testlib.h"

enum { MSGLEN = 160 };

extern const ob_method ob_method_liu, ob_method_chebyshev, ob_method_lstsq;

static const char *const NAMES[3] = {"liu", "chebyshev", "lstsq"};
static const ob_method *const M3[3] = {&ob_method_liu, &ob_method_chebyshev, &ob_method_lstsq};
static void *work;

/* ---- independent references ------------------------------------------------ */

static double ref_weight(const ob_bez *C, double t)
{
    double W = 0.0;
    for (int i = 0; i <= C->deg; i++)
        W += C->h[i][2] * bern(C->deg, i, t);
    return W;
}

/* f(t) = W(t) d N(t), N = (-y', x')/|C'| */
static void ref_f(const ob_bez *C, double d, double t, double f[2])
{
    double o[2][2];
    ref_eval(C, t, 1, o);
    double L = hypot(o[1][0], o[1][1]), W = ref_weight(C, t);
    f[0] = -W * d * o[1][1] / L;
    f[1] = W * d * o[1][0] / L;
}

static void ref_ftilde(const ob_bez *C, double d, double t, double g[2])
{
    double f[2], f0[2], f1[2];
    const int n = C->deg;
    ref_f(C, d, t, f);
    ref_f(C, d, 0.0, f0);
    ref_f(C, d, 1.0, f1);
    double b0 = bern(n, 0, t), bn = bern(n, n, t), q = t * (1.0 - t);
    g[0] = (f[0] - f0[0] * b0 - f1[0] * bn) / q;
    g[1] = (f[1] - f0[1] * b0 - f1[1] * bn) / q;
}

static void ref_bez_eval2(const double (*c)[2], int m, double t, double v[2])
{
    v[0] = v[1] = 0.0;
    for (int i = 0; i <= m; i++) {
        double b = bern(m, i, t);
        v[0] += c[i][0] * b;
        v[1] += c[i][1] * b;
    }
}

/* Gaussian elimination with partial pivoting, A[k][k] x = b (2 right-hand sides). */
static int solve(int k, double (*A)[OB_MAX_DEG + 1], double (*b)[2])
{
    for (int c = 0; c < k; c++) {
        int p = c;
        for (int r = c + 1; r < k; r++)
            if (fabs(A[r][c]) > fabs(A[p][c]))
                p = r;
        if (A[p][c] == 0.0)
            return -1;
        for (int q = 0; q < k; q++) {
            double t = A[c][q];
            A[c][q] = A[p][q];
            A[p][q] = t;
        }
        for (int e = 0; e < 2; e++) {
            double t = b[c][e];
            b[c][e] = b[p][e];
            b[p][e] = t;
        }
        for (int r = c + 1; r < k; r++) {
            double f = A[r][c] / A[c][c];
            for (int q = c; q < k; q++)
                A[r][q] -= f * A[c][q];
            b[r][0] -= f * b[c][0];
            b[r][1] -= f * b[c][1];
        }
    }
    for (int r = k - 1; r >= 0; r--)
        for (int e = 0; e < 2; e++) {
            double s = b[r][e];
            for (int q = r + 1; q < k; q++)
                s -= A[r][q] * b[q][e];
            b[r][e] = s / A[r][r];
        }
    return 0;
}

/* ---- helpers ------------------------------------------------------------------- */

static ob_fit_status fit_with(const ob_method *m, const ob_bez *C, double d, const double *par,
                              ob_fit *f, char *msg)
{
    double def[OB_MAX_PARAMS];
    ob_param_defaults(m, def);
    const ob_fit_args a = {d, 1e-3, par ? par : def};
    msg[0] = '\0';
    return m->fit(C, &a, work, f, msg, MSGLEN);
}

/* Homogeneous shift c_i = A.h[i] - C.h[i] (= D_i for polynomial input). */
static void shifts(const ob_bez *C, const ob_bez *A, double (*c)[2])
{
    for (int i = 0; i <= C->deg; i++) {
        c[i][0] = A->h[i][0] - C->h[i][0];
        c[i][1] = A->h[i][1] - C->h[i][1];
    }
}

/* Interior S~ of the fit: s~_{i-1} = c_i C(n,i)/C(n-2,i-1), i = 1..n-1. */
static void interior(const ob_bez *C, const ob_bez *A, double (*st)[2])
{
    double c[OB_MAX_DEG + 1][2];
    const int n = C->deg;
    shifts(C, A, c);
    for (int i = 1; i < n; i++) {
        double k = binom(n, i) / binom(n - 2, i - 1);
        st[i - 1][0] = c[i][0] * k;
        st[i - 1][1] = c[i][1] * k;
    }
}

/* max_t |c(t) - W(t) d N(t)| on a dense grid: the normal-fit error. */
static double normal_fit_error(const ob_bez *C, const ob_bez *A, double d)
{
    double c[OB_MAX_DEG + 1][2], e = 0.0;
    shifts(C, A, c);
    for (int k = 0; k <= 2000; k++) {
        double t = k / 2000.0, v[2], f[2];
        ref_bez_eval2((const double (*)[2])c, C->deg, t, v);
        ref_f(C, d, t, f);
        e = fmax(e, hypot(v[0] - f[0], v[1] - f[1]));
    }
    return e;
}

static ob_bez liu_ex1(void)
{
    static const double P[4][2] = {
        {-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};
    return make(3, P, NULL);
}

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

static ob_bez rational_cubic(void)
{
    static const double P[4][2] = {{0, 0}, {1, 1.5}, {2.5, 1.8}, {3.5, 0.6}};
    static const double w[4] = {1.0, 2.0, 0.5, 1.3};
    return make(3, P, w);
}

/* ---- 1: the Gauss-Legendre rule ---------------------------------------------- */

static void test_gauss_legendre(void)
{
    double x[OB_NF_MAX_NODES], w[OB_NF_MAX_NODES];
    for (int M = 1; M <= 40; M++) {
        ob_nf_gauss_legendre(M, x, w);
        int ok = 1;
        for (int j = 0; j < M; j++)
            ok &= x[j] > 0.0 && x[j] < 1.0 && w[j] > 0.0 && (j == 0 || x[j] > x[j - 1]) &&
                  x[j] + x[M - 1 - j] == 1.0 && w[j] == w[M - 1 - j];
        CHECK(ok, "GL %d: nodes ascending in (0,1), symmetric, positive weights", M);
        double worst = 0.0, e2m = 0.0;
        for (int k = 0; k <= 2 * M; k++) {
            double q = 0.0;
            for (int j = 0; j < M; j++)
                q += w[j] * pow(x[j], k);
            if (k <= 2 * M - 1)
                worst = fmax(worst, fabs(q - 1.0 / (k + 1)) * (k + 1));
            else
                e2m = 1.0 / (k + 1) - q;
        }
        CHECK(worst < 1e-13, "GL %d: t^k integrated exactly for k <= 2M-1 (rel err %g)", M, worst);
        if (M <= 6) {
            /* the error of t^(2M) is (M!)^4 / ((2M+1) ((2M)!)^2) on [0,1]: the degree is sharp */
            double fm = 1.0, f2m = 1.0;
            for (int i = 2; i <= M; i++)
                fm *= i;
            for (int i = 2; i <= 2 * M; i++)
                f2m *= i;
            double want = fm * fm * fm * fm / ((2 * M + 1) * f2m * f2m);
            CHECK(fabs(e2m - want) <= 1e-6 * want + 1e-16, "GL %d: error on t^2M %.6g, theory %.6g",
                  M, e2m, want);
        }
    }
    /* a smooth non-polynomial integrand: int_0^1 exp(t) cos(3t) dt */
    ob_nf_gauss_legendre(20, x, w);
    double q = 0.0;
    for (int j = 0; j < 20; j++)
        q += w[j] * exp(x[j]) * cos(3 * x[j]);
    double exact = (exp(1.0) * (cos(3.0) + 3 * sin(3.0)) - 1.0) / 10.0;
    CHECK_NEAR(q, exact, 1e-14, "GL 20: int exp(t) cos(3t)");
}

/* ---- 2: exactness on polynomial targets ------------------------------------------ */

typedef struct {
    int m;
    double c[OB_MAX_DEG + 1][2];
} polyfn;

static int eval_poly(const void *ctx, double t, double f[2])
{
    const polyfn *p = ctx;
    ref_bez_eval2((const double (*)[2])p->c, p->m, t, f);
    return 0;
}

static void test_polynomial_targets(void)
{
    double s[OB_MAX_DEG + 1][2];
    for (int n = 1; n <= 12; n++) {
        polyfn p;
        p.m = n;
        double scale = 0.0;
        for (int i = 0; i <= n; i++) {
            p.c[i][0] = urange(-2, 2);
            p.c[i][1] = urange(-2, 2);
            scale = fmax(scale, fmax(fabs(p.c[i][0]), fabs(p.c[i][1])));
        }
        for (int kind = 0; kind < 4; kind++) {
            int r = kind == 0   ? ob_nf_fit_legendre(eval_poly, &p, n, n > 2 ? n - 1 : 1, work, s)
                    : kind == 1 ? ob_nf_fit_chebyshev(eval_poly, &p, n, n > 2 ? n - 1 : 1, work, s)
                    : ob_nf_fit_lstsq(eval_poly, &p, n, n + 5, kind == 3, s);
            CHECK(r == 0, "poly n %d kind %d: fit failed", n, kind);
            double e = 0.0;
            for (int i = 0; i <= n; i++)
                e = fmax(e, hypot(s[i][0] - p.c[i][0], s[i][1] - p.c[i][1]));
            /* Legendre/Chebyshev to Bernstein conversion amplifies round-off by ~C(n-2,(n-2)/2) */
            CHECK(e < 1e-13 * scale * binom(n, n / 2), "poly degree %d, %s, fewest nodes: "
                  "reproduced to %g", n, kind < 3 ? NAMES[kind] : "lstsq f~", e);
        }
        /* a degree n+1 target is NOT reproduced: the check above can fail */
        polyfn q = p;
        q.m = n + 1;
        for (int i = 0; i <= n + 1; i++) {
            q.c[i][0] = urange(-2, 2);
            q.c[i][1] = urange(-2, 2);
        }
        ob_nf_fit_legendre(eval_poly, &q, n, 64, work, s);
        double e = 0.0;
        for (int k = 0; k <= 50; k++) {
            double v[2], f[2], t = k / 50.0;
            ref_bez_eval2((const double (*)[2])s, n, t, v);
            eval_poly(&q, t, f);
            e = fmax(e, hypot(v[0] - f[0], v[1] - f[1]));
        }
        CHECK(e > 1e-6, "poly degree %d target, degree %d fit: error %g > 0", n + 1, n, e);
    }
}

/* ---- 3: straight segments and circular arcs are exact --------------------------- */

static void test_exact_cases(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    const double P0[2] = {0.1, -0.2}, dir[2] = {3.0, 2.0};
    const double len = hypot(dir[0], dir[1]), nrm[2] = {-dir[1] / len, dir[0] / len};
    static const double s3[] = {0, 0.07, 0.6, 1}, s5[] = {0, 0.1, 0.15, 0.5, 0.8, 1};
    for (int which = 0; which < 2; which++) {
        int n = which ? 5 : 3;
        const double *sp = which ? s5 : s3;
        double p[6][2];
        for (int i = 0; i <= n; i++)
            p[i][0] = P0[0] + sp[i] * dir[0], p[i][1] = P0[1] + sp[i] * dir[1];
        ob_bez C = make(n, (const double (*)[2])p, NULL);
        for (int mi = 0; mi < 3; mi++)
            for (int sg = -1; sg <= 1; sg += 2) {
                double d = 0.7 * sg;
                ob_fit_status st = fit_with(M3[mi], &C, d, NULL, &f, msg);
                CHECK(st == OB_FIT_OK, "%s line deg %d: %s", NAMES[mi], n, msg);
                if (st != OB_FIT_OK)
                    continue;
                double worst = 0.0;
                for (int i = 0; i <= n; i++) {
                    double q[2];
                    ob_bez_ctrl(&f.seg[0], i, q);
                    worst = fmax(worst, hypot(q[0] - p[i][0] - d * nrm[0], q[1] - p[i][1] - d * nrm[1]));
                }
                /* round-off only: f~ divides by t(1-t) >= 1.5e-4 at the outer nodes */
                CHECK(worst < 1e-12, "%s line deg %d d %g: D_i = d N for all i (off by %g)",
                      NAMES[mi], n, d, worst);
                ob_errval e;
                ob_measure(OB_METRIC_HAUSDORFF, &C, &f.seg[0], d, 256, &e);
                CHECK(e.err < 1e-12, "%s line deg %d d %g: hausdorff %g", NAMES[mi], n, d, e.err);
            }
    }
    /* rational quarter circles: W d N is a polynomial of degree 2, reproduced */
    for (int cw = 0; cw < 2; cw++) {
        ob_bez qc = quarter_circle(2.5, cw);
        for (int mi = 0; mi < 3; mi++)
            for (int sg = -1; sg <= 1; sg += 2) {
                double d = 0.8 * sg;
                ob_fit_status st = fit_with(M3[mi], &qc, d, NULL, &f, msg);
                CHECK(st == OB_FIT_OK, "%s circle: %s", NAMES[mi], msg);
                if (st != OB_FIT_OK)
                    continue;
                CHECK(f.seg[0].rational && f.seg[0].deg == 2, "%s circle: rational quadratic", NAMES[mi]);
                for (int i = 0; i <= 2; i++)
                    CHECK(f.seg[0].h[i][2] == qc.h[i][2], "%s circle: weight %d kept", NAMES[mi], i);
                for (ob_metric mt = OB_METRIC_RADIAL; mt < OB_METRIC_COUNT; mt++) {
                    ob_errval e;
                    ob_measure(mt, &qc, &f.seg[0], d, 256, &e);
                    CHECK(e.err < testlib_exact_tol(mt), "%s circle cw %d d %g: %s error %g", NAMES[mi], cw, d,
                          ob_metric_name(mt), e.err);
                }
            }
    }
}

/* ---- 4: end-point interpolation -------------------------------------------------- */

static void test_end_interpolation(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_bez cs[4] = {liu_ex1(), quintic(), rational_cubic(), quarter_circle(1.5, 1)};
    static const double ds[] = {1.0, -1.0, 0.3, -0.05};
    for (int c = 0; c < 4; c++)
        for (int mi = 0; mi < 3; mi++)
            for (int k = 0; k < 4; k++) {
                ob_fit_status st = fit_with(M3[mi], &cs[c], ds[k], NULL, &f, msg);
                CHECK(st == OB_FIT_OK && f.n == 1 && f.seg[0].deg == cs[c].deg, "%s curve %d: %s",
                      NAMES[mi], c, msg);
                if (st != OB_FIT_OK)
                    continue;
                for (int e = 0; e <= 1; e++) {
                    double o[2], a[2], N[2];
                    ref_point(&cs[c], e, o);
                    double fv[2];
                    ref_f(&cs[c], 1.0, e, fv);
                    double W = ref_weight(&cs[c], e);
                    N[0] = fv[0] / W;
                    N[1] = fv[1] / W;
                    o[0] += ds[k] * N[0];
                    o[1] += ds[k] * N[1];
                    ref_point(&f.seg[0], e, a);
                    CHECK(dist2d(o, a) < 1e-13, "%s curve %d d %g: end %d off the offset by %g",
                          NAMES[mi], c, ds[k], e, dist2d(o, a));
                }
            }
}

/* ---- 5: L2 optimality of liu's interior ------------------------------------------ */

enum { GRID = 4000, FINE = 20000 };

/* L2 norm over [0,1] of f~ - S~ (midpoint rule on FINE points, precomputed f~). */
static double l2err(const double (*g)[2], const double (*st)[2], int m)
{
    double s = 0.0;
    for (int k = 0; k < FINE; k++) {
        double t = (k + 0.5) / FINE, v[2];
        ref_bez_eval2(st, m, t, v);
        s += (v[0] - g[k][0]) * (v[0] - g[k][0]) + (v[1] - g[k][1]) * (v[1] - g[k][1]);
    }
    return sqrt(s / FINE);
}

static void check_l2_optimal(const char *cn, const ob_bez *C, double d)
{
    static ob_fit f;
    static double g[FINE][2];
    char msg[MSGLEN];
    const int n = C->deg, m = n - 2;
    ob_fit_status st = fit_with(M3[0], C, d, NULL, &f, msg);
    CHECK(st == OB_FIT_OK, "liu %s: %s", cn, msg);
    if (st != OB_FIT_OK)
        return;
    double sl[OB_MAX_DEG + 1][2];
    interior(C, &f.seg[0], sl);

    /* brute force: least squares of f~ on GRID midpoints, Bernstein basis of degree m */
    double A[OB_MAX_DEG + 1][OB_MAX_DEG + 1] = {{0}}, b[OB_MAX_DEG + 1][2] = {{0}};
    for (int k = 0; k < GRID; k++) {
        double t = (k + 0.5) / GRID, gv[2], B[OB_MAX_DEG + 1];
        ref_ftilde(C, d, t, gv);
        for (int i = 0; i <= m; i++)
            B[i] = bern(m, i, t);
        for (int i = 0; i <= m; i++) {
            for (int j = 0; j <= m; j++)
                A[i][j] += B[i] * B[j];
            b[i][0] += B[i] * gv[0];
            b[i][1] += B[i] * gv[1];
        }
    }
    CHECK(solve(m + 1, A, b) == 0, "brute force %s: singular", cn);
    for (int k = 0; k < FINE; k++)
        ref_ftilde(C, d, (k + 0.5) / FINE, g[k]);
    const double el = l2err((const double (*)[2])g, (const double (*)[2])sl, m);
    const double eb = l2err((const double (*)[2])g, (const double (*)[2])b, m);
    double dc = 0.0, sc = 0.0;
    for (int i = 0; i <= m; i++) {
        dc = fmax(dc, hypot(sl[i][0] - b[i][0], sl[i][1] - b[i][1]));
        sc = fmax(sc, hypot(sl[i][0], sl[i][1]));
    }
    CHECK(fabs(el - eb) <= 1e-9 * eb, "liu %s d %g: L2 error of f~ %.15g, brute force %.15g", cn, d,
          el, eb);
    CHECK(dc <= 1e-6 * sc, "liu %s d %g: coefficients differ from brute force by %g (scale %g)", cn,
          d, dc, sc);
    /* every perturbation of a coefficient (either component, either sign) increases it */
    int all_up = 1;
    double least = INFINITY;
    for (int i = 0; i <= m; i++)
        for (int e = 0; e < 2; e++)
            for (int sg = -1; sg <= 1; sg += 2) {
                double p[OB_MAX_DEG + 1][2];
                memcpy(p, sl, sizeof p);
                p[i][e] += sg * 1e-3 * fmax(sc, 1e-3);
                double ep = l2err((const double (*)[2])g, (const double (*)[2])p, m);
                all_up &= ep > el;
                least = fmin(least, ep - el);
            }
    CHECK(all_up, "liu %s d %g: some perturbation lowers the L2 error (least change %g)", cn, d, least);
}

static void test_l2_optimality(void)
{
    ob_bez C = liu_ex1(), H, Q = quintic();
    check_l2_optimal("liu2002_ex1", &C, 1.0);
    ob_bez_subsegment(&C, 0.2, 0.6, &H);
    check_l2_optimal("liu2002_ex1[0.2,0.6]", &H, -0.4);
    check_l2_optimal("quintic", &Q, 0.7);

    /* the default node count is converged: 64 vs 1024 Gauss-Legendre nodes on the
     * whole liu2002_ex1 (normal turning by 3 rad) */
    ob_nf_target tg = {&C, 1.0};
    double s64[OB_MAX_DEG + 1][2], s1k[OB_MAX_DEG + 1][2], s16[OB_MAX_DEG + 1][2];
    double par[OB_MAX_PARAMS];
    ob_param_defaults(M3[0], par);
    CHECK(par[0] == 64, "liu: default nodes %g", par[0]);
    ob_nf_fit_legendre(ob_nf_target_eval, &tg, 3, 64, work, s64);
    ob_nf_fit_legendre(ob_nf_target_eval, &tg, 3, 1024, work, s1k);
    ob_nf_fit_legendre(ob_nf_target_eval, &tg, 3, 16, work, s16);
    double e64 = 0.0, e16 = 0.0;
    for (int i = 0; i <= 3; i++) {
        e64 = fmax(e64, hypot(s64[i][0] - s1k[i][0], s64[i][1] - s1k[i][1]));
        e16 = fmax(e16, hypot(s16[i][0] - s1k[i][0], s16[i][1] - s1k[i][1]));
    }
    CHECK(e64 < 1e-13, "liu ex1: 64 vs 1024 nodes differ by %g", e64);
    CHECK(e16 > 1e-8, "liu ex1: 16 vs 1024 nodes differ by %g (the node count matters)", e16);
}

/* ---- 6: chebyshev and lstsq against liu; convergence -------------------------------- */

/* the three methods agree on pieces of a cubic, and converge O(h^4). */
static void agreement_cubic(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_bez C = liu_ex1();
    const double d = 1.0;
    double err[3][7];
    for (int l = 0; l < 7; l++) {
        double h = 0.5 / (1 << l), a = 0.25;
        ob_bez P;
        ob_bez_subsegment(&C, a, a + h, &P);
        for (int mi = 0; mi < 3; mi++) {
            ob_fit_status st = fit_with(M3[mi], &P, d, NULL, &f, msg);
            CHECK(st == OB_FIT_OK, "%s piece h %g: %s", NAMES[mi], h, msg);
            err[mi][l] = st == OB_FIT_OK ? normal_fit_error(&P, &f.seg[0], d) : NAN;
        }
    }
    for (int l = 0; l < 7; l++)
        for (int mi = 1; mi < 3; mi++) {
            double r = err[mi][l] / err[0][l];
            CHECK(r > 1.0 / 3 && r < 3, "%s vs liu at h = %g: normal-fit errors %.3g vs %.3g",
                  NAMES[mi], 0.5 / (1 << l), err[mi][l], err[0][l]);
        }
    /* cubic: end-interpolating degree-3 fit, error O(h^4): ratio -> 16 per halving
     * (21.2, 18.1, 16.9, 16.4 from h = 1/8 on) */
    for (int l = 3; l < 6; l++)
        for (int mi = 0; mi < 3; mi++) {
            double r = err[mi][l] / err[mi][l + 1];
            CHECK(r > 14 && r < 19.5, "%s: halving from h = %g: error ratio %.3g (expected ~16)",
                  NAMES[mi], 0.5 / (1 << l), r);
        }
}

/* the same for a quintic: O(h^6), and agreement with liu. */
static void agreement_quintic(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    /* the same for a quintic: O(h^6), ratio -> 64 */
    ob_bez Q = quintic();
    double eq[3][4];
    for (int l = 0; l < 4; l++) {
        ob_bez P;
        ob_bez_subsegment(&Q, 0.3, 0.3 + 0.5 / (1 << l), &P);
        for (int mi = 0; mi < 3; mi++) {
            ob_fit_status st = fit_with(M3[mi], &P, 0.5, NULL, &f, msg);
            eq[mi][l] = st == OB_FIT_OK ? normal_fit_error(&P, &f.seg[0], 0.5) : NAN;
        }
    }
    for (int mi = 0; mi < 3; mi++) {
        double r = eq[mi][2] / eq[mi][3];
        CHECK(r > 48 && r < 80, "%s quintic: last halving error ratio %.3g (expected ~64)", NAMES[mi], r);
        CHECK(eq[mi][3] / eq[0][3] > 1.0 / 3 && eq[mi][3] / eq[0][3] < 3, "%s quintic vs liu: %.3g vs %.3g",
              NAMES[mi], eq[mi][3], eq[0][3]);
    }
}

/* chebyshev with n-1 nodes interpolates f~ at the Chebyshev points. */
static void chebyshev_interpolates(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_bez Q = quintic();
    /* chebyshev with n-1 nodes interpolates f~ at the Chebyshev points */
    ob_bez P;
    ob_bez_subsegment(&Q, 0.1, 0.9, &P);
    double par[OB_MAX_PARAMS] = {4};
    ob_fit_status st = fit_with(M3[1], &P, 0.5, par, &f, msg);
    CHECK(st == OB_FIT_OK, "chebyshev 4 nodes: %s", msg);
    if (st == OB_FIT_OK) {
        double sq[OB_MAX_DEG + 1][2], worst = 0.0;
        interior(&P, &f.seg[0], sq);
        for (int j = 0; j < 4; j++) {
            double t = 0.5 * (1 + cos(OB_PI * (j + 0.5) / 4)), v[2], g[2];
            ref_bez_eval2((const double (*)[2])sq, 3, t, v);
            ref_ftilde(&P, 0.5, t, g);
            worst = fmax(worst, hypot(v[0] - g[0], v[1] - g[1]));
        }
        CHECK(worst < 1e-12, "chebyshev, n-1 nodes: interpolates f~ at the Chebyshev points (%g)", worst);
    }
}

/* lstsq against liu: of f~ samples it tends to liu, of normal samples it beats liu on the normal. */
static void lstsq_against_liu(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_bez C = liu_ex1(), P;
    const double d = 1.0;
    ob_fit_status st;
    /* lstsq of f~ samples tends to liu as the samples grow (discrete -> continuous L2) */
    ob_bez_subsegment(&C, 0.1, 0.7, &P);
    static ob_fit fl;
    fit_with(M3[0], &P, d, NULL, &fl, msg);
    double prev = INFINITY;
    for (int M = 16; M <= 1024; M *= 4) {
        double pl[OB_MAX_PARAMS] = {M, 1};
        st = fit_with(M3[2], &P, d, pl, &f, msg);
        CHECK(st == OB_FIT_OK, "lstsq f~ %d samples: %s", M, msg);
        double dv = 0.0;
        for (int i = 0; i <= 3; i++)
            dv = fmax(dv, hypot(f.seg[0].h[i][0] - fl.seg[0].h[i][0], f.seg[0].h[i][1] - fl.seg[0].h[i][1]));
        /* uniform samples j/(M+1): a rectangle rule, so the distance is O(1/M) */
        if (M > 16)
            CHECK(dv / prev > 0.2 && dv / prev < 0.3, "lstsq f~ %d samples: distance to liu %g, "
                  "with a quarter of the samples %g: not O(1/M)", M, dv, prev);
        prev = dv;
    }
    CHECK(prev < 1e-3, "lstsq f~ 1024 samples: distance to liu %g", prev);

    /* lstsq of the normal samples minimises the (sampled) L2 error of the normal
     * itself with the ends fixed: it beats liu there, and liu beats it on f~ */
    double pl[OB_MAX_PARAMS] = {1024, 0};
    st = fit_with(M3[2], &P, d, pl, &f, msg);
    CHECK(st == OB_FIT_OK, "lstsq normal 1024: %s", msg);
    double en_l = 0, en_s = 0;
    double cl[OB_MAX_DEG + 1][2], cs[OB_MAX_DEG + 1][2];
    shifts(&P, &fl.seg[0], cl);
    shifts(&P, &f.seg[0], cs);
    for (int k = 0; k < FINE; k++) {
        double t = (k + 0.5) / FINE, v[2], u[2], fv[2];
        ref_f(&P, d, t, fv);
        ref_bez_eval2((const double (*)[2])cl, 3, t, v);
        ref_bez_eval2((const double (*)[2])cs, 3, t, u);
        en_l += (v[0] - fv[0]) * (v[0] - fv[0]) + (v[1] - fv[1]) * (v[1] - fv[1]);
        en_s += (u[0] - fv[0]) * (u[0] - fv[0]) + (u[1] - fv[1]) * (u[1] - fv[1]);
    }
    CHECK(en_s < en_l, "lstsq (normal samples) L2 error of the normal %g < liu's %g", sqrt(en_s / FINE),
          sqrt(en_l / FINE));
}

/* liu, chebyshev and lstsq: agreement, convergence, and how they differ. */
static void test_agreement_convergence(void)
{
    agreement_cubic();
    agreement_quintic();
    chebyshev_interpolates();
    lstsq_against_liu();
}


/* ---- 7: rational input (§2.4) --------------------------------------------------------- */

typedef struct {
    const ob_bez *C;
    double d;
} reftarget;

static int eval_reftarget(const void *ctx, double t, double f[2])
{
    const reftarget *r = ctx;
    ref_f(r->C, r->d, t, f);
    return 0;
}

static void test_rational(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_bez R = rational_cubic();
    CHECK(R.rational, "rational cubic is rational");
    for (int mi = 0; mi < 3; mi++) {
        const double d = 0.25;
        ob_fit_status st = fit_with(M3[mi], &R, d, NULL, &f, msg);
        CHECK(st == OB_FIT_OK, "%s rational cubic: %s", NAMES[mi], msg);
        if (st != OB_FIT_OK)
            continue;
        int kept = f.seg[0].rational && f.seg[0].deg == 3;
        for (int i = 0; i <= 3; i++)
            kept &= f.seg[0].h[i][2] == R.h[i][2];
        CHECK(kept, "%s rational cubic: weights kept", NAMES[mi]);
        /* the homogeneous shift is the same fit applied to W(t) d N(t) */
        reftarget rt = {&R, d};
        double s[OB_MAX_DEG + 1][2], c[OB_MAX_DEG + 1][2];
        double par[OB_MAX_PARAMS];
        ob_param_defaults(M3[mi], par);
        int r = mi == 0   ? ob_nf_fit_legendre(eval_reftarget, &rt, 3, (int)par[0], work, s)
                : mi == 1 ? ob_nf_fit_chebyshev(eval_reftarget, &rt, 3, (int)par[0], work, s)
                          : ob_nf_fit_lstsq(eval_reftarget, &rt, 3, (int)par[0], (int)par[1], s);
        CHECK(r == 0, "%s: fit of W d N", NAMES[mi]);
        shifts(&R, &f.seg[0], c);
        double dv = 0.0;
        for (int i = 0; i <= 3; i++)
            dv = fmax(dv, hypot(c[i][0] - s[i][0], c[i][1] - s[i][1]));
        CHECK(dv < 1e-12, "%s rational: shift c_i vs fit of W d N: %g", NAMES[mi], dv);
        /* D_i = c_i / w_i: the Euclidean control points move by c_i / w_i */
        double worst = 0.0;
        for (int i = 0; i <= 3; i++) {
            double p[2], q[2];
            ob_bez_ctrl(&R, i, p);
            ob_bez_ctrl(&f.seg[0], i, q);
            worst = fmax(worst, hypot(q[0] - p[0] - c[i][0] / R.h[i][2], q[1] - p[1] - c[i][1] / R.h[i][2]));
        }
        CHECK(worst < 1e-13, "%s rational: P_i^a = P_i + c_i / w_i (%g)", NAMES[mi], worst);
        /* halving the piece: the offset error drops like a degree-3 fit */
        ob_errval e0, e1;
        ob_measure(OB_METRIC_HAUSDORFF, &R, &f.seg[0], d, 256, &e0);
        ob_bez H;
        ob_bez_subsegment(&R, 0.0, 0.25, &H);
        fit_with(M3[mi], &H, d, NULL, &f, msg);
        ob_measure(OB_METRIC_HAUSDORFF, &H, &f.seg[0], d, 256, &e1);
        CHECK(e1.err < e0.err / 20, "%s rational: error %g on the quarter piece vs %g whole",
              NAMES[mi], e1.err, e0.err);
    }
}

/* ---- 8: parameters --------------------------------------------------------------------- */

static void test_params(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_bez C = liu_ex1();
    static const double badn[] = {0, -3, 2.5, 1025, NAN};
    for (int mi = 0; mi < 3; mi++) {
        CHECK(M3[mi]->nparams >= 1 && M3[mi]->params[0].doc && M3[mi]->params[0].doc[0],
              "%s: documented parameters", NAMES[mi]);
        CHECK(ob_method_out_degree(M3[mi], 3, 0, NULL) == 3 && ob_method_out_degree(M3[mi], 6, 1, NULL) == 6, "%s: degree n",
              NAMES[mi]);
        CHECK((M3[mi]->caps & (OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM)) ==
                  (OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM) &&
                  !(M3[mi]->caps & OB_CAP_CONVEX),
              "%s: capabilities", NAMES[mi]);
        for (size_t k = 0; k < sizeof badn / sizeof badn[0]; k++) {
            double par[OB_MAX_PARAMS];
            ob_param_defaults(M3[mi], par);
            par[0] = badn[k];
            ob_fit_status st = fit_with(M3[mi], &C, 1.0, par, &f, msg);
            CHECK(st == OB_FIT_FAIL && msg[0], "%s: parameter %g: %s (%s)", NAMES[mi], badn[k],
                  ob_fit_status_name(st), msg);
        }
    }
    double par[OB_MAX_PARAMS] = {32, 2};
    CHECK(fit_with(M3[2], &C, 1.0, par, &f, msg) == OB_FIT_FAIL && msg[0], "lstsq target 2: %s", msg);
    ob_bez Q = quintic();
    double p3[OB_MAX_PARAMS] = {3, 0};
    CHECK(fit_with(M3[2], &Q, 1.0, p3, &f, msg) == OB_FIT_FAIL && msg[0],
          "lstsq: 3 samples for 4 unknowns: %s", msg);
    p3[0] = 4;
    CHECK(fit_with(M3[2], &Q, 1.0, p3, &f, msg) == OB_FIT_OK, "lstsq: 4 samples for 4 unknowns: %s", msg);
}

int main(void)
{
    testlib_seed(0x51A0F17ULL);
    size_t ws = 0;
    for (int i = 0; i < 3; i++) {
        CHECK(strcmp(M3[i]->name, NAMES[i]) == 0, "method %d is called %s", i, M3[i]->name);
        if (M3[i]->work_size > ws)
            ws = M3[i]->work_size;
    }
    CHECK(ws >= ob_nf_work_legendre(OB_NF_MAX_NODES) && M3[1]->work_size >= ob_nf_work_chebyshev(OB_NF_MAX_NODES),
          "work_size covers the largest node count");
    work = malloc(ws > 0 ? ws : 1);
    if (!work)
        return 2;
    test_gauss_legendre();
    test_polynomial_targets();
    test_exact_cases();
    test_end_interpolation();
    test_l2_optimality();
    test_agreement_convergence();
    test_rational();
    test_params();
    free(work);
    return check_done();
}
