/*
 * normalfit.c - Liu & Wang 2002 normal-curve approximation: Gauss-Legendre
 * rule, the end-constrained construction of §2.3 with a Legendre, Chebyshev
 * or least-squares fit of f~, and the control-point shift.  See normalfit.h.
 */
#include "methods/common/normalfit.h"

#include <math.h>
#include <string.h>

#include "methods/core/bernstein.h"

enum { K = OB_MAX_DEG + 1 };

/* Pascal's triangle up to OB_MAX_DEG, in caller storage (no static state). */
static void pascal(double (*bin)[K])
{
    for (int i = 0; i < K; i++) {
        bin[i][0] = bin[i][i] = 1.0;
        for (int j = 1; j < i; j++)
            bin[i][j] = bin[i - 1][j - 1] + bin[i - 1][j];
        for (int j = i + 1; j < K; j++)
            bin[i][j] = 0.0;
    }
}

int ob_nf_target_eval(const void *ctx, double t, double f[2])
{
    const ob_nf_target *g = ctx;
    double N[2];
    if (ob_bez_normal(g->base, t, N) != 0)
        return -1;
    double W = 1.0;
    if (g->base->rational) {
        double w[OB_MAX_DEG + 1];
        for (int i = 0; i <= g->base->deg; i++)
            w[i] = g->base->h[i][2];
        W = ob_bern_eval(w, g->base->deg, t);
    }
    f[0] = W * g->d * N[0];
    f[1] = W * g->d * N[1];
    return isfinite(f[0]) && isfinite(f[1]) ? 0 : -1;
}

/* P_M(z) and P_M'(z) by the three-term recurrence (eq. 2). */
static double legendre_pd(int M, double z, double *dp)
{
    double p0 = 1.0, p1 = z;   /* P_{k-1}, P_k */
    for (int k = 1; k < M; k++) {
        double p2 = ((2.0 * k + 1.0) * z * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
    }
    *dp = M * (z * p1 - p0) / (z * z - 1.0);
    return p1;
}

void ob_nf_gauss_legendre(int M, double *x, double *w)
{
    for (int i = 0; i < (M + 1) / 2; i++) {
        /* the i-th largest root of P_M on [-1,1]; Newton converges quadratically,
         * so a step below 1e-15 leaves the root exact to round-off */
        double z = cos(OB_PI * (i + 0.75) / (M + 0.5)), dp;
        for (int it = 0; it < 100; it++) {
            double dz = legendre_pd(M, z, &dp) / dp;
            z -= dz;
            if (fabs(dz) <= 1e-15)
                break;
        }
        if (2 * i + 1 == M)
            z = 0.0;   /* the middle node of an odd rule */
        legendre_pd(M, z, &dp);
        /* weight 2/((1-z^2) P_M'(z)^2) on [-1,1], halved for [0,1] */
        const double wi = 1.0 / ((1.0 - z * z) * dp * dp);
        /* t = (1 -+ z)/2: node i from the left and its mirror from the right */
        x[i] = 0.5 * (1.0 - z);
        w[i] = wi;
        x[M - 1 - i] = 0.5 * (1.0 + z);
        w[M - 1 - i] = wi;
    }
}

size_t ob_nf_work_legendre(int M) { return (size_t)M * 4 * sizeof(double); }
size_t ob_nf_work_chebyshev(int M) { return (size_t)M * 2 * sizeof(double); }

/* f0 = f(0), f1 = f(1) and f~(t) = (f(t) - f0 (1-t)^n - f1 t^n) / ((1-t) t), 0 < t < 1. */
static int ends(ob_nf_fn f, const void *ctx, double f0[2], double f1[2])
{
    return f(ctx, 0.0, f0) || f(ctx, 1.0, f1) ? -1 : 0;
}

static int ftilde(ob_nf_fn f, const void *ctx, int n, const double f0[2], const double f1[2],
                  double t, double g[2])
{
    double v[2];
    if (f(ctx, t, v) != 0)
        return -1;
    const double u = 1.0 - t, b0 = pow(u, n), bn = pow(t, n), q = u * t;
    g[0] = (v[0] - f0[0] * b0 - f1[0] * bn) / q;
    g[1] = (v[1] - f0[1] * b0 - f1[1] * bn) / q;
    return 0;
}

/* Eq. (7): s_0 = f0, s_i = C(n-2,i-1)/C(n,i) s~_{i-1}, s_n = f1. */
static void place(int n, const double f0[2], const double f1[2], const double (*st)[2],
                  const double (*bin)[K], double (*s)[2])
{
    s[0][0] = f0[0];
    s[0][1] = f0[1];
    for (int i = 1; i < n; i++) {
        double c = bin[n - 2][i - 1] / bin[n][i];
        s[i][0] = c * st[i - 1][0];
        s[i][1] = c * st[i - 1][1];
    }
    s[n][0] = f1[0];
    s[n][1] = f1[1];
}

/* st += a * (b of degree k elevated to degree m). */
static void add_elevated(const double *b, int k, int m, const double a[2], const double (*bin)[K],
                         double (*st)[2])
{
    for (int r = 0; r <= m; r++) {
        double c = 0.0;
        int lo = r - (m - k) > 0 ? r - (m - k) : 0, hi = r < k ? r : k;
        for (int i = lo; i <= hi; i++)
            c += bin[k][i] * bin[m - k][r - i] * b[i];
        c /= bin[m][r];
        st[r][0] += a[0] * c;
        st[r][1] += a[1] * c;
    }
}

/* What both fits do first: check the sizes, and for n = 1 (no interior)
 * interpolate the ends.  Returns -1 on an error, 1 when s is done (n = 1),
 * 0 with the binomials and the ends f0, f1 ready for the projection. */
static int begin_fit(ob_nf_fn f, const void *ctx, int n, int M, double (*s)[2], double bin[K][K],
                     double f0[2], double f1[2])
{
    if (n < 1 || n > OB_MAX_DEG || M < 1 || M > OB_NF_MAX_NODES)
        return -1;
    if (n == 1)
        return ends(f, ctx, s[0], s[1]) ? -1 : 1;
    pascal(bin);
    return ends(f, ctx, f0, f1) ? -1 : 0;
}

int ob_nf_fit_legendre(ob_nf_fn f, const void *ctx, int n, int M, void *work, double (*s)[2])
{
    double bin[K][K], f0[2], f1[2];
    const int begun = begin_fit(f, ctx, n, M, s, bin, f0, f1);
    if (begun != 0)
        return begun < 0 ? -1 : 0;
    double *x = work, *w = x + M, (*g)[2] = (double (*)[2])(w + M);
    ob_nf_gauss_legendre(M, x, w);
    for (int j = 0; j < M; j++)
        if (ftilde(f, ctx, n, f0, f1, x[j], g[j]))
            return -1;
    const int m = n - 2;
    double st[K][2] = {{0}}, b[K];
    /* a_k = (2k+1) int_0^1 f~(t) P_k(2t-1) dt   (eq. 5 on [0,1]), k = 0..m */
    double a[K][2] = {{0}};
    for (int j = 0; j < M; j++) {
        const double z = 2.0 * x[j] - 1.0;
        double p0 = 1.0, p1 = z;
        for (int k = 0; k <= m; k++) {
            const double pk = k == 0 ? 1.0 : p1;
            a[k][0] += w[j] * g[j][0] * pk;
            a[k][1] += w[j] * g[j][1] * pk;
            if (k >= 1) {
                const double p2 = ((2.0 * k + 1.0) * z * p1 - k * p0) / (k + 1.0);
                p0 = p1;
                p1 = p2;
            }
        }
    }
    for (int k = 0; k <= m; k++) {
        a[k][0] *= 2.0 * k + 1.0;
        a[k][1] *= 2.0 * k + 1.0;
        /* P_k(2t-1) = sum_i (-1)^(k+i) C(k,i) B_i^k(t)   (§2.2) */
        for (int i = 0; i <= k; i++)
            b[i] = ((k + i) % 2 ? -1.0 : 1.0) * bin[k][i];
        add_elevated(b, k, m, a[k], (const double (*)[K])bin, st);
    }
    place(n, f0, f1, (const double (*)[2])st, (const double (*)[K])bin, s);
    return 0;
}

int ob_nf_fit_chebyshev(ob_nf_fn f, const void *ctx, int n, int M, void *work, double (*s)[2])
{
    double bin[K][K], f0[2], f1[2];
    const int begun = begin_fit(f, ctx, n, M, s, bin, f0, f1);
    if (begun != 0)
        return begun < 0 ? -1 : 0;
    double (*g)[2] = work;
    /* Gauss-Chebyshev nodes x_j = cos(theta_j), theta_j = (j + 1/2) pi / M, t = (1 + x)/2 */
    for (int j = 0; j < M; j++)
        if (ftilde(f, ctx, n, f0, f1, 0.5 * (1.0 + cos(OB_PI * (j + 0.5) / M)), g[j]))
            return -1;
    const int m = n - 2;
    double st[K][2] = {{0}}, b[K];
    for (int k = 0; k <= m; k++) {
        /* c_k = (2/pi) int_{-1}^{1} f~ T_k / sqrt(1-x^2) dx ~ (2/M) sum_j f~(x_j) cos(k theta_j);
         * c_0 halved, so that f~ ~ sum_k c_k T_k(2t-1) */
        double a[2] = {0.0, 0.0};
        for (int j = 0; j < M; j++) {
            double ck = cos(k * OB_PI * (j + 0.5) / M);
            a[0] += g[j][0] * ck;
            a[1] += g[j][1] * ck;
        }
        double sc = (k == 0 ? 1.0 : 2.0) / M;
        a[0] *= sc;
        a[1] *= sc;
        /* T_k(2t-1) = sum_i (-1)^(k-i) C(2k,2i)/C(k,i) B_i^k(t) */
        for (int i = 0; i <= k; i++)
            b[i] = ((k - i) % 2 ? -1.0 : 1.0) * ob_binom(2 * k, 2 * i) / bin[k][i];
        add_elevated(b, k, m, a, (const double (*)[K])bin, st);
    }
    place(n, f0, f1, (const double (*)[2])st, (const double (*)[K])bin, s);
    return 0;
}

int ob_nf_fit_lstsq(ob_nf_fn f, const void *ctx, int n, int M, int ftilde_rows, double (*s)[2])
{
    double bin[K][K], f0[2], f1[2];
    const int begun = begin_fit(f, ctx, n, M, s, bin, f0, f1);
    if (begun != 0)
        return begun < 0 ? -1 : 0;
    /* unknowns s_1..s_{n-1}; row j: sum_i s_i B_i^n(t_j) = f(t_j) - f0 B_0^n - f1 B_n^n,
     * times 1/(t(1-t)) for rows of f~.  Givens QR, one row at a time. */
    const int nu = n - 1;
    double R[K][K] = {{0}}, qb[K][2] = {{0}};
    for (int j = 1; j <= M; j++) {
        const double t = (double)j / (M + 1), u = 1.0 - t;
        double v[2], B[K + 1], row[K], y[2];
        if (f(ctx, t, v) != 0)
            return -1;
        B[0] = 1.0;
        for (int q = 1; q <= n; q++) {
            B[q] = t * B[q - 1];
            for (int i = q - 1; i >= 1; i--)
                B[i] = u * B[i] + t * B[i - 1];
            B[0] *= u;
        }
        const double rw = ftilde_rows ? 1.0 / (t * u) : 1.0;
        for (int i = 0; i < nu; i++)
            row[i] = rw * B[i + 1];
        y[0] = rw * (v[0] - f0[0] * B[0] - f1[0] * B[n]);
        y[1] = rw * (v[1] - f0[1] * B[0] - f1[1] * B[n]);
        for (int i = 0; i < nu; i++) {
            if (row[i] == 0.0)
                continue;
            const double h = hypot(R[i][i], row[i]), c = R[i][i] / h, sn = row[i] / h;
            for (int q = i; q < nu; q++) {
                const double a = R[i][q], b = row[q];
                R[i][q] = c * a + sn * b;
                row[q] = -sn * a + c * b;
            }
            for (int e = 0; e < 2; e++) {
                const double a = qb[i][e], b = y[e];
                qb[i][e] = c * a + sn * b;
                y[e] = -sn * a + c * b;
            }
        }
    }
    double big = 0.0;
    for (int i = 0; i < nu; i++)
        big = fmax(big, fabs(R[i][i]));
    for (int i = 0; i < nu; i++)
        if (!(fabs(R[i][i]) > 1e-13 * big))
            return -1;
    s[0][0] = f0[0];
    s[0][1] = f0[1];
    s[n][0] = f1[0];
    s[n][1] = f1[1];
    for (int i = nu - 1; i >= 0; i--)
        for (int e = 0; e < 2; e++) {
            double r = qb[i][e];
            for (int q = i + 1; q < nu; q++)
                r -= R[i][q] * s[q + 1][e];
            s[i + 1][e] = r / R[i][i];
        }
    return 0;
}

ob_fit_status ob_nf_method_fit(ob_nf_kind kind, const ob_bez *base, const ob_fit_args *a, void *work,
                               ob_fit *out, char *msg, size_t msglen)
{
    static const char *const what[] = {"Gauss-Legendre nodes", "Gauss-Chebyshev nodes", "samples"};
    const int n = base->deg;
    const double pm = a->par[0];
    if (!(pm >= 1 && pm <= OB_NF_MAX_NODES && pm == floor(pm))) {
        ob_method_msg(msg, msglen, "%s = %g: must be an integer in 1..%d", what[kind], pm,
                      OB_NF_MAX_NODES);
        return OB_FIT_FAIL;
    }
    const int M = (int)pm;
    if (n < 1) {
        ob_method_msg(msg, msglen, "degree 0 segment: no normal");
        return OB_FIT_FAIL;
    }
    int ft = 0;
    if (kind == OB_NF_LSTSQ) {
        if (a->par[1] != 0.0 && a->par[1] != 1.0) {
            ob_method_msg(msg, msglen, "target = %g: must be 0 (normal) or 1 (f~)", a->par[1]);
            return OB_FIT_FAIL;
        }
        ft = a->par[1] == 1.0;
        if (M < n - 1) {
            ob_method_msg(msg, msglen, "%d samples for %d unknowns: underdetermined", M, n - 1);
            return OB_FIT_FAIL;
        }
    }
    const ob_nf_target tg = {base, a->d};
    double s[OB_MAX_DEG + 1][2];
    int r = kind == OB_NF_LEGENDRE    ? ob_nf_fit_legendre(ob_nf_target_eval, &tg, n, M, work, s)
            : kind == OB_NF_CHEBYSHEV ? ob_nf_fit_chebyshev(ob_nf_target_eval, &tg, n, M, work, s)
                                      : ob_nf_fit_lstsq(ob_nf_target_eval, &tg, n, M, ft, s);
    if (r != 0) {
        ob_method_msg(msg, msglen, kind == OB_NF_LSTSQ
                                       ? "no normal somewhere on the piece, or singular least-squares system"
                                       : "no normal somewhere on the piece (point-like segment)");
        return OB_FIT_FAIL;
    }
    ob_bez res = *base;
    for (int i = 0; i <= n; i++) {
        res.h[i][0] += s[i][0];   /* w_i (P_i + D_i) = w_i P_i + s_i, D_i = s_i / w_i (§2.4) */
        res.h[i][1] += s[i][1];
    }
    ob_fit_single(out, &res);
    return OB_FIT_OK;
}
