/*
 * interp.c - offset interpolation, the Klass / Pham family (Klass 1983, CAD
 * 15(5); Pham 1988, CAD 20(8); as Liu-Wang section 1 and Elber-Lee-Kim 1997
 * classify them): the degree-n Bézier curve A that interpolates the exact
 * offset points
 *     A(t*_j) = C(t*_j) + d N(t*_j),   t*_j = j/n,  j = 0..n
 * (the Greville abscissae of the Bézier segment).  The Bernstein collocation
 * system sum_i B_i^n(t*_j) Q_i = O_j is solved by Gaussian elimination with
 * partial pivoting, in the caller's scratch space, for x and y at once.
 * Rational input: the approximation keeps the base's weights w_i (a rational
 * curve with the same weights through the offset points), i.e. the homogeneous
 * system sum_i B_i^n(t*_j) (w_i Q_i) = W(t*_j) O_j with W = sum w_i B_i^n.
 * Properties: interpolates the offset at both ends and at the interior nodes,
 * shares the base's parameter at the nodes; exact wherever the offset is a
 * (rational, with the base's weights) curve of degree <= n, e.g. a straight
 * segment with any parameterization.
 * Readings: Klass fits cubic Hermite pieces and Pham a cubic B-spline through
 * sampled offset points; the per-segment node interpolation at t*_j = j/n is
 * the form of the Klass / Pham interpolation family we take.
 */
#include "methods/method.h"

#include <math.h>

#include "methods/core/bernstein.h"

enum { IP_N = OB_MAX_DEG + 1 };

/* scratch: the (n+1) x (n+1) matrix and the two right-hand sides (x, y) */
typedef struct {
    double A[IP_N][IP_N];
    double b[IP_N][2];
} ip_work;

static ob_fit_status interp_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                char *msg, size_t msglen)
{
    ip_work *wk = work;
    const double d = a->d;
    const int n = base->deg;
    if (n < 1) {
        ob_method_msg(msg, msglen, "degree %d: nothing to interpolate", n);
        return OB_FIT_SKIP;
    }
    for (int j = 0; j <= n; j++) {
        const double t = (double)j / n;
        double O[2];
        double N[2];
        if (ob_bez_normal(base, t, N) != 0) {
            ob_method_msg(msg, msglen, "no normal at t = %d/%d (point-like segment)", j, n);
            return OB_FIT_FAIL;
        }
        ob_bez_point(base, t, O);
        O[0] += d * N[0];
        O[1] += d * N[1];
        /* row j: B_i^n(t*_j) (exactly 1 and 0 at the end nodes) */
        double W = 0.0;
        for (int i = 0; i <= n; i++) {
            double bi = ob_binom(n, i) * pow(t, i) * pow(1.0 - t, n - i);
            wk->A[j][i] = bi;
            W += bi * base->h[i][2];
        }
        if (!base->rational)
            W = 1.0;
        wk->b[j][0] = W * O[0];
        wk->b[j][1] = W * O[1];
    }
    /* Gaussian elimination with partial pivoting */
    int perm[IP_N];
    for (int i = 0; i <= n; i++)
        perm[i] = i;
    for (int k = 0; k <= n; k++) {
        int p = k;
        for (int r = k + 1; r <= n; r++)
            if (fabs(wk->A[perm[r]][k]) > fabs(wk->A[perm[p]][k]))
                p = r;
        int tmp = perm[k];
        perm[k] = perm[p];
        perm[p] = tmp;
        const double piv = wk->A[perm[k]][k];
        if (!(fabs(piv) > 1e-300)) {
            ob_method_msg(msg, msglen, "singular collocation matrix at column %d", k);
            return OB_FIT_FAIL;
        }
        for (int r = k + 1; r <= n; r++) {
            double *row = wk->A[perm[r]];
            const double f = row[k] / piv;
            if (f == 0.0)
                continue;
            for (int c = k; c <= n; c++)
                row[c] -= f * wk->A[perm[k]][c];
            for (int c = 0; c < 2; c++)
                wk->b[perm[r]][c] -= f * wk->b[perm[k]][c];
        }
    }
    ob_bez r = *base;
    for (int k = n; k >= 0; k--) {
        const double *row = wk->A[perm[k]];
        double x[2] = {wk->b[perm[k]][0], wk->b[perm[k]][1]};
        for (int c = k + 1; c <= n; c++) {
            x[0] -= row[c] * r.h[c][0];
            x[1] -= row[c] * r.h[c][1];
        }
        /* homogeneous (w Q): the weight column is the base's own */
        r.h[k][0] = x[0] / row[k];
        r.h[k][1] = x[1] / row[k];
        r.h[k][2] = base->h[k][2];
    }
    for (int k = 0; k <= n; k++)
        if (!isfinite(r.h[k][0]) || !isfinite(r.h[k][1])) {
            ob_method_msg(msg, msglen, "collocation solve gave non-finite control points");
            return OB_FIT_FAIL;
        }
    ob_fit_single(out, &r);
    return OB_FIT_OK;
}

const ob_method ob_method_interp = {
    .name = "interp",
    .version = 1,
    .citation = "Klass 1983 (CAD 15(5)) / Pham 1988 (CAD 20(8)): interpolation of offset points",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM | OB_CAP_INTERP_ENDS,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 1.3,
    .work_size = sizeof(ip_work),
    .fit = interp_fit,
};
