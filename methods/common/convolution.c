/*
 * convolution.c - offsets through a normal field with derivative parallel to
 * C' (see convolution.h).  Shared by ahn.c (alpha cubic) and kim2018.c (alpha
 * linear).
 */
#include "methods/common/convolution.h"

#include <math.h>

#include "methods/core/bernstein.h"

/* Forward differences Delta b_j = b_{j+1} - b_j of the control polygon. */
static void differences(const ob_bez *base, double db[][2])
{
    double b[OB_MAX_DEG + 1][2];
    const int n = base->deg;
    for (int j = 0; j <= n; j++)
        ob_bez_ctrl(base, j, b[j]);
    for (int j = 0; j < n; j++) {
        db[j][0] = b[j + 1][0] - b[j][0];
        db[j][1] = b[j + 1][1] - b[j][1];
    }
}

void ob_conv_moments(const ob_bez *base, int p, double w[][2])
{
    const int n = base->deg;
    double db[OB_MAX_DEG][2];
    differences(base, db);
    for (int i = 0; i <= p; i++) {
        w[i][0] = w[i][1] = 0.0;
        for (int j = 0; j < n; j++) {
            double c = n * ob_binom(n - 1, j) * ob_binom(p, i) / ob_binom(n + p - 1, i + j) / (n + p);
            w[i][0] += c * db[j][0];
            w[i][1] += c * db[j][1];
        }
    }
}

int ob_conv_solve2(const double v1[2], const double v2[2], const double v[2], double *a1,
                   double *a2)
{
    const double det = v1[0] * v2[1] - v1[1] * v2[0];
    const double n1 = sqrt(v1[0] * v1[0] + v1[1] * v1[1]), n2 = sqrt(v2[0] * v2[0] + v2[1] * v2[1]);
    if (fabs(det) > 1e-12 * n1 * n2) {
        *a1 = (v[0] * v2[1] - v[1] * v2[0]) / det;
        *a2 = (v1[0] * v[1] - v1[1] * v[0]) / det;
        return 0;
    }
    /* rank <= 1: project on the common direction e of v1 and v2 */
    const double *big = n1 >= n2 ? v1 : v2, nb = n1 >= n2 ? n1 : n2;
    const double nv = sqrt(v[0] * v[0] + v[1] * v[1]);
    if (nb == 0.0) {
        *a1 = *a2 = 0.0;
        return nv <= 1e-12 ? 0 : -1;
    }
    const double e[2] = {big[0] / nb, big[1] / nb};
    const double p1 = v1[0] * e[0] + v1[1] * e[1], p2 = v2[0] * e[0] + v2[1] * e[1];
    const double pv = v[0] * e[0] + v[1] * e[1];
    *a1 = pv * p1 / (p1 * p1 + p2 * p2);
    *a2 = pv * p2 / (p1 * p1 + p2 * p2);
    /* consistency: the residual must vanish (v is a difference of unit normals) */
    const double r[2] = {v[0] - *a1 * v1[0] - *a2 * v2[0], v[1] - *a1 * v1[1] - *a2 * v2[1]};
    return sqrt(r[0] * r[0] + r[1] * r[1]) <= 1e-10 * (1.0 + nv) ? 0 : -1;
}

int ob_conv_offset(const ob_bez *base, const double *alpha, int p, const double N0[2], double d,
                   ob_bez *out)
{
    const int n = base->deg, m = n + p;
    if (m > OB_MAX_DEG || n < 1 || p < 0)
        return -1;
    double db[OB_MAX_DEG][2];
    differences(base, db);
    /* C' alpha in Bernstein form of degree n+p-1, then integrate to degree n+p */
    double Na[OB_MAX_DEG + 1][2];
    Na[0][0] = N0[0];
    Na[0][1] = N0[1];
    for (int k = 0; k <= m - 1; k++) {
        double c[2] = {0.0, 0.0};
        for (int i = 0; i <= p; i++) {
            int j = k - i;
            if (j < 0 || j > n - 1)
                continue;
            double f = n * alpha[i] * ob_binom(n - 1, j) * ob_binom(p, i) / ob_binom(m - 1, k);
            c[0] += f * db[j][0];
            c[1] += f * db[j][1];
        }
        Na[k + 1][0] = Na[k][0] + c[0] / m;
        Na[k + 1][1] = Na[k][1] + c[1] / m;
    }
    ob_bez up;
    if (ob_bez_elevate(base, m, &up) != 0)
        return -1;
    for (int k = 0; k <= m; k++) {
        up.h[k][0] += d * Na[k][0];
        up.h[k][1] += d * Na[k][1];
    }
    *out = up;
    return 0;
}

ob_fit_status ob_conv_prepare(const ob_bez *base, int out_deg, double N0[2], double N1[2], char *msg,
                              size_t msglen)
{
    if (base->rational) {
        ob_method_msg(msg, msglen, "rational input is not supported (polynomial method)");
        return OB_FIT_SKIP;
    }
    if (base->deg < 1 || out_deg > OB_MAX_DEG) {
        ob_method_msg(msg, msglen, "degree %d: output degree %d outside %d..%d", base->deg, out_deg,
                      out_deg - base->deg + 1, OB_MAX_DEG);
        return OB_FIT_SKIP;
    }
    double e0[2][2], e1[2][2];
    ob_bez_eval(base, 0.0, 1, e0);
    ob_bez_eval(base, 1.0, 1, e1);
    if ((e0[1][0] == 0.0 && e0[1][1] == 0.0) || (e1[1][0] == 0.0 && e1[1][1] == 0.0)) {
        ob_method_msg(msg, msglen, "C' vanishes at an end of the piece (cusp)");
        return OB_FIT_FAIL;
    }
    ob_bez_normal(base, 0.0, N0);
    ob_bez_normal(base, 1.0, N1);
    return OB_FIT_OK;
}
