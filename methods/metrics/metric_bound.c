/*
 * metric_bound.c - Elber, Lee & Kim's symbolic error bound (IEEE CG&A 17(1),
 * 1997): D(t) = ||A(t) - C(t)||^2 is a (rational) Bernstein polynomial whose
 * coefficients bound it, so no sampling is needed.
 *
 * For A = (Ax, Ay)/Aw and C = (Cx, Cy)/Cw in homogeneous form,
 *   D = ((Ax Cw - Cx Aw)^2 + (Ay Cw - Cy Aw)^2) / (Aw Cw)^2,
 * numerator and denominator of the same degree 2(deg A + deg C); with positive
 * weights min_k num_k/den_k <= D(t) <= max_k num_k/den_k.  For polynomial A and
 * C this is the plain product formula of degree 2 max(deg A, deg C).
 */
#include "methods/metrics/metric.h"

#include <math.h>

#include "methods/core/bernstein.h"

static void coords(const ob_bez *b, int k, double *out)
{
    for (int i = 0; i <= b->deg; i++)
        out[i] = b->h[i][k];
}

int ob_metric_bound(const ob_bez *base, const ob_bez *approx, double d, ob_errval *out)
{
    double num[OB_BERN_MAX + 1], den[OB_BERN_MAX + 1];
    double dx[OB_BERN_MAX + 1], dy[OB_BERN_MAX + 1], sq[OB_BERN_MAX + 1];
    int deg;
    if (!base->rational && !approx->rational) {
        int m = base->deg > approx->deg ? base->deg : approx->deg;
        ob_bez a, c;
        ob_bez_elevate(approx, m, &a);
        ob_bez_elevate(base, m, &c);
        for (int i = 0; i <= m; i++) {
            dx[i] = a.h[i][0] - c.h[i][0];
            dy[i] = a.h[i][1] - c.h[i][1];
        }
        deg = 2 * m;
        ob_bern_mul(dx, m, dx, m, num);
        ob_bern_mul(dy, m, dy, m, sq);
        for (int k = 0; k <= deg; k++) {
            num[k] += sq[k];
            den[k] = 1.0;
        }
    } else {
        const int ma = approx->deg, mc = base->deg, m = ma + mc;
        if (2 * m > OB_BERN_MAX) {
            out->err = INFINITY;
            out->t = 0.0;
            return -1;
        }
        double a[OB_MAX_DEG + 1], c[OB_MAX_DEG + 1], aw[OB_MAX_DEG + 1], cw[OB_MAX_DEG + 1];
        double p1[OB_BERN_MAX + 1], p2[OB_BERN_MAX + 1];
        coords(approx, 2, aw);
        coords(base, 2, cw);
        double *diff[2] = {dx, dy};
        for (int k = 0; k < 2; k++) {
            coords(approx, k, a);
            coords(base, k, c);
            ob_bern_mul(a, ma, cw, mc, p1);
            ob_bern_mul(c, mc, aw, ma, p2);
            for (int i = 0; i <= m; i++)
                diff[k][i] = p1[i] - p2[i];
        }
        deg = 2 * m;
        ob_bern_mul(dx, m, dx, m, num);
        ob_bern_mul(dy, m, dy, m, sq);
        for (int k = 0; k <= deg; k++)
            num[k] += sq[k];
        ob_bern_mul(aw, ma, cw, mc, p1);
        ob_bern_mul(p1, m, p1, m, den);
    }
    double dmin = INFINITY, dmax = -INFINITY;
    int kmin = 0, kmax = 0;
    for (int k = 0; k <= deg; k++) {
        double r = num[k] / den[k];
        if (isnan(r)) {  /* a NaN coefficient: nothing is bounded */
            out->err = INFINITY;
            out->t = (double)k / deg;
            return 0;
        }
        if (r < dmin) {
            dmin = r;
            kmin = k;
        }
        if (r > dmax) {
            dmax = r;
            kmax = k;
        }
    }
    const double ad = fabs(d);
    double elo = fabs(sqrt(fmax(dmin, 0.0)) - ad), ehi = fabs(sqrt(fmax(dmax, 0.0)) - ad);
    out->err = fmax(elo, ehi);
    out->t = (double)(elo > ehi ? kmin : kmax) / deg;
    if (!isfinite(out->err))
        out->err = INFINITY;
    return 0;
}
