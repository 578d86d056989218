/*
 * exact.c - exact rational offsets where they exist (San Segundo & Sendra,
 * "Algorithms for offset curves and surfaces", ICM 2006 poster: if
 * ||N(t)|| is rational in t, the offset P +- d N/||N|| is rational).
 *
 * Recognised inputs, each offset written as one rational Bézier segment that
 * shares the base's parameter (C(t) + d N(t) exactly, up to round-off):
 *  (a) circular arcs given as rational quadratics: the conic P0 P1 P2 with
 *      weights w0 w1 w2 is an arc of a circle iff the legs are equal,
 *      |P1-P0| = |P2-P1|, and w1/sqrt(w0 w2) = cos(alpha), alpha the angle
 *      between the leg P0P1 and the chord P0P2 (half the arc angle).  Centre c
 *      and radius R follow; the offset is the arc scaled about c by
 *      k = 1 - d kappa (kappa = +-1/R, + for a counterclockwise arc): control
 *      points c + k (P_i - c), the same weights.  Degree 2.
 *  (b) polynomial Pythagorean-hodograph curves: x'^2 + y'^2 = sigma(t)^2 with
 *      sigma a polynomial of degree n-1 (found by interpolating |C'| at n
 *      Chebyshev nodes and checked coefficient-wise: sigma^2 = x'^2 + y'^2 to
 *      the relative tolerance detect_tol), sigma > 0 on [0,1].  Then
 *      C + d (-y', x')/sigma = [sigma C + d (-y', x')] / sigma, numerator of
 *      degree 2n-1, denominator sigma elevated to 2n-1: one rational Bézier
 *      of degree 2n-1.  Straight polynomial segments are PH (sigma = |L(t)|
 *      |u| for C' = L(t) u) and land here.
 *  (c) rational straight segments (collinear control points, the point moving
 *      one way): the offset is the translate by d times the line's left
 *      normal, same degree and weights.
 * Everything else: OB_FIT_SKIP with the reason.
 * Output degree: 2n-1 for polynomial input, n for rational input (2 for the
 * arcs of (a)).
 */
#include "methods/method.h"

#include <math.h>
#include <string.h>

#include "methods/core/bernstein.h"

enum { P_DETECT, NPARAM };

static const ob_param exact_params[NPARAM] = {
    {"detect_tol", 1e-10,
     "relative tolerance of the tests that recognise a circular arc (equal legs, weight "
     "ratio = cos of the half angle), a straight segment and a PH curve (x'^2+y'^2 = "
     "sigma^2, coefficient-wise relative to the largest); round-off level, our choice", 0, 1e-2, 0},
};

static int exact_degree(int n, int rational_in, const double *par)
{
    (void)par;
    return rational_in ? n : 2 * n - 1;
}

static double cross2(const double u[2], const double v[2]) { return u[0] * v[1] - u[1] * v[0]; }

/* Solve the k x k system M x = y (row-major, overwritten) by Gaussian
 * elimination with partial pivoting.  Returns -1 if singular. */
static int solve(double *M, double *y, int k)
{
    for (int c = 0; c < k; c++) {
        int p = c;
        for (int i = c + 1; i < k; i++)
            if (fabs(M[i * k + c]) > fabs(M[p * k + c]))
                p = i;
        if (M[p * k + c] == 0.0)
            return -1;
        if (p != c) {
            for (int j = 0; j < k; j++) {
                double t = M[c * k + j];
                M[c * k + j] = M[p * k + j];
                M[p * k + j] = t;
            }
            double t = y[c];
            y[c] = y[p];
            y[p] = t;
        }
        for (int i = c + 1; i < k; i++) {
            double f = M[i * k + c] / M[c * k + c];
            for (int j = c; j < k; j++)
                M[i * k + j] -= f * M[c * k + j];
            y[i] -= f * y[c];
        }
    }
    for (int c = k - 1; c >= 0; c--) {
        double s = y[c];
        for (int j = c + 1; j < k; j++)
            s -= M[c * k + j] * y[j];
        y[c] = s / M[c * k + c];
    }
    return 0;
}

/* (b) polynomial PH curve. */
static ob_fit_status exact_ph(const ob_bez *b, double d, double tol, ob_bez *o, char *msg,
                              size_t msglen)
{
    const int n = b->deg, m = n - 1, deg = 2 * n - 1;
    double hx[OB_MAX_DEG], hy[OB_MAX_DEG];
    for (int k = 0; k < n; k++) {
        hx[k] = n * (b->h[k + 1][0] - b->h[k][0]);
        hy[k] = n * (b->h[k + 1][1] - b->h[k][1]);
    }
    /* S = x'^2 + y'^2, degree 2m */
    double S[2 * OB_MAX_DEG + 1], t1[2 * OB_MAX_DEG + 1];
    ob_bern_mul(hx, m, hx, m, S);
    ob_bern_mul(hy, m, hy, m, t1);
    double smax = 0.0;
    for (int k = 0; k <= 2 * m; k++) {
        S[k] += t1[k];
        smax = fmax(smax, fabs(S[k]));
    }
    if (!(smax > 0.0)) {
        ob_method_msg(msg, msglen, "the segment is a point (C' = 0)");
        return OB_FIT_SKIP;
    }
    /* sigma: interpolate |C'| at m+1 Chebyshev nodes */
    double M[OB_MAX_DEG * OB_MAX_DEG], sig[OB_MAX_DEG];
    for (int i = 0; i <= m; i++) {
        const double t = 0.5 * (1.0 - cos((2.0 * i + 1.0) * OB_PI / (2.0 * (m + 1))));
        for (int k = 0; k <= m; k++) {
            double e[OB_MAX_DEG] = {0};
            e[k] = 1.0;
            M[i * (m + 1) + k] = ob_bern_eval(e, m, t);
        }
        sig[i] = hypot(ob_bern_eval(hx, m, t), ob_bern_eval(hy, m, t));
    }
    if (solve(M, sig, m + 1) != 0) {
        ob_method_msg(msg, msglen, "singular interpolation of |C'|");
        return OB_FIT_FAIL;
    }
    double S2[2 * OB_MAX_DEG + 1], defect = 0.0;
    ob_bern_mul(sig, m, sig, m, S2);
    for (int k = 0; k <= 2 * m; k++)
        defect = fmax(defect, fabs(S2[k] - S[k]));
    defect /= smax;
    if (!(defect <= tol)) {
        ob_method_msg(msg, msglen, "not a Pythagorean-hodograph curve: x'^2+y'^2 != sigma^2, "
                      "deg sigma %d (defect %.2g)", m, defect);
        return OB_FIT_SKIP;
    }
    /* sigma > 0 on [0,1] */
    double smin = INFINITY, sbig = 0.0;
    int allpos = 1;
    for (int k = 0; k <= m; k++) {
        allpos &= sig[k] > 0.0;
        sbig = fmax(sbig, fabs(sig[k]));
    }
    if (!allpos)
        for (int i = 0; i <= 1000; i++)
            smin = fmin(smin, ob_bern_eval(sig, m, i / 1000.0));
    double rts[OB_MAX_DEG];
    if (!allpos && (smin <= 1e-9 * sbig || ob_bern_roots(sig, m, rts, OB_MAX_DEG) > 0)) {
        ob_method_msg(msg, msglen, "PH curve whose |C'| = sigma vanishes on [0,1] (a cusp or "
                      "a stationary point)");
        return OB_FIT_SKIP;
    }
    /* [sigma C + d (-y', x')] / sigma, degree 2n-1 */
    double X[3][2 * OB_MAX_DEG + 1], P[OB_MAX_DEG + 1], e[2 * OB_MAX_DEG + 1];
    for (int c = 0; c < 2; c++) {
        for (int i = 0; i <= n; i++)
            P[i] = b->h[i][c];
        ob_bern_mul(sig, m, P, n, X[c]);
        ob_bern_elevate(c == 0 ? hy : hx, m, deg, e);
        for (int k = 0; k <= deg; k++)
            X[c][k] += (c == 0 ? -d : d) * e[k];
    }
    ob_bern_elevate(sig, m, deg, X[2]);
    double big = 0.0;
    for (int k = 0; k <= deg; k++)
        big = fmax(big, fabs(X[2][k]));
    memset(o, 0, sizeof *o);
    o->deg = deg;
    o->rational = 1;
    for (int k = 0; k <= deg; k++)
        for (int c = 0; c < 3; c++)
            o->h[k][c] = X[c][k] / big;
    return OB_FIT_OK;
}

/* (c) rational straight segment: returns OB_FIT_OK (o written), OB_FIT_SKIP with msg
 * if it reverses, or -1 (as int) if the points are not collinear. */
static int exact_line(const ob_bez *b, double d, double tol, ob_bez *o, char *msg, size_t msglen)
{
    const int n = b->deg;
    double P[OB_MAX_DEG + 1][2];
    for (int i = 0; i <= n; i++)
        ob_bez_ctrl(b, i, P[i]);
    int far = 0;
    double L = 0.0;
    for (int i = 1; i <= n; i++) {
        double l = hypot(P[i][0] - P[0][0], P[i][1] - P[0][1]);
        if (l > L)
            L = l, far = i;
    }
    if (!(L > 0.0))
        return -1;
    const double u[2] = {(P[far][0] - P[0][0]) / L, (P[far][1] - P[0][1]) / L};
    for (int i = 1; i <= n; i++) {
        const double v[2] = {P[i][0] - P[0][0], P[i][1] - P[0][1]};
        if (fabs(cross2(u, v)) > tol * L)
            return -1;
    }
    /* speed along u: (P'w - Pw') . u, degree 2n-2 (exact formula, see lee.c) */
    const int m = 2 * n - 2;
    double f[2 * OB_MAX_DEG + 1] = {0};
    for (int i = 0; i <= n; i++)
        for (int j = i + 1; j <= n; j++) {
            const double c = (j - i) * ob_binom(n, i) * ob_binom(n, j) / ob_binom(m, i + j - 1);
            for (int k = 0; k < 2; k++)
                f[i + j - 1] += c * u[k] * (b->h[j][k] * b->h[i][2] - b->h[i][k] * b->h[j][2]);
        }
    double rts[2 * OB_MAX_DEG + 1];
    if (!(ob_bern_eval(f, m, 0.0) > 0.0) || !(ob_bern_eval(f, m, 1.0) > 0.0) ||
        ob_bern_roots(f, m, rts, 2 * OB_MAX_DEG + 1) > 0) {
        ob_method_msg(msg, msglen, "straight segment whose point reverses direction: no "
                      "regular offset");
        return OB_FIT_SKIP;
    }
    const double v[2] = {-d * u[1], d * u[0]};
    *o = *b;
    for (int i = 0; i <= n; i++) {
        o->h[i][0] += b->h[i][2] * v[0];
        o->h[i][1] += b->h[i][2] * v[1];
    }
    return OB_FIT_OK;
}

/* (a) circular arc as a rational quadratic.  Returns OB_FIT_OK or OB_FIT_SKIP. */
static ob_fit_status exact_arc(const ob_bez *b, double d, double tol, ob_bez *o, char *msg,
                               size_t msglen)
{
    double P[3][2];
    for (int i = 0; i < 3; i++)
        ob_bez_ctrl(b, i, P[i]);
    const double w0 = b->h[0][2], w1 = b->h[1][2], w2 = b->h[2][2];
    const double v0[2] = {P[1][0] - P[0][0], P[1][1] - P[0][1]};
    const double v1[2] = {P[2][0] - P[1][0], P[2][1] - P[1][1]};
    const double ch[2] = {P[2][0] - P[0][0], P[2][1] - P[0][1]};
    const double L0 = hypot(v0[0], v0[1]), L1 = hypot(v1[0], v1[1]), Lc = hypot(ch[0], ch[1]);
    const double cr = cross2(v0, v1);
    const double cosa = (v0[0] * ch[0] + v0[1] * ch[1]) / (L0 * Lc);
    const double sina = fabs(cross2(v0, ch)) / (L0 * Lc);
    const double rho = w1 / sqrt(w0 * w2);
    if (!(L0 > 0.0 && L1 > 0.0 && Lc > 0.0) || !(fabs(L0 - L1) <= tol * fmax(L0, L1)) ||
        !(fabs(rho - cosa) <= tol) || !(sina > 0.0) || !(w0 > 0.0 && w1 > 0.0 && w2 > 0.0)) {
        ob_method_msg(msg, msglen, "not a circular arc: legs %.4g %.4g, w1/sqrt(w0 w2) %.6g vs "
                      "cos(half angle) %.6g", L0, L1, rho, cosa);
        return OB_FIT_SKIP;
    }
    /* centre: from P0 along the normal of the first leg, towards P2, at R = L0/tan(alpha) */
    const double R = L0 * cosa / sina, s = cr > 0.0 ? 1.0 : -1.0;
    const double nrm[2] = {-s * v0[1] / L0, s * v0[0] / L0};
    const double c[2] = {P[0][0] + R * nrm[0], P[0][1] + R * nrm[1]};
    const double k = 1.0 - d * s / R;
    *o = *b;
    for (int i = 0; i < 3; i++) {
        const double w = b->h[i][2];
        o->h[i][0] = w * (c[0] + k * (P[i][0] - c[0]));
        o->h[i][1] = w * (c[1] + k * (P[i][1] - c[1]));
    }
    return OB_FIT_OK;
}

static ob_fit_status exact_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                               char *msg, size_t msglen)
{
    (void)work;
    const double d = a->d, tol = a->par[P_DETECT];
    const int n = base->deg;
    ob_bez o;
    if (n < 1) {
        ob_method_msg(msg, msglen, "a segment of degree 0 is a point");
        return OB_FIT_SKIP;
    }
    if (exact_degree(n, base->rational, a->par) > OB_MAX_DEG) {
        ob_method_msg(msg, msglen, "output degree %d exceeds %d",
                      exact_degree(n, base->rational, a->par), OB_MAX_DEG);
        return OB_FIT_SKIP;
    }
    ob_fit_status st;
    if (base->rational) {
        int r = exact_line(base, d, tol, &o, msg, msglen);
        if (r >= 0) {
            st = (ob_fit_status)r;
        } else if (n == 2) {
            st = exact_arc(base, d, tol, &o, msg, msglen);
        } else {
            ob_method_msg(msg, msglen, "rational degree %d: exact only for circular arcs "
                          "(quadratics) and straight segments", n);
            st = OB_FIT_SKIP;
        }
    } else {
        st = exact_ph(base, d, tol, &o, msg, msglen);
    }
    if (st == OB_FIT_OK)
        ob_fit_single(out, &o);
    return st;
}

const ob_method ob_method_exact = {
    .name = "exact",
    .version = 1,
    .citation = "San Segundo & Sendra, Algorithms for offset curves and surfaces (ICM 2006): "
                "rational offsets of circular arcs and PH curves",
    .continuity = "exact",
    .caps = OB_CAP_RATIONAL_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM,
    .max_turn = 0.0,
    .out_degree = exact_degree,
    .cost_ms = 0.35,
    .work_size = 0,
    .params = exact_params,
    .nparams = NPARAM,
    .fit = exact_fit,
};
