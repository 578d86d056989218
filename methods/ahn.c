/*
 * ahn.c - Ahn 2023, "G2/C1 Hermite interpolation of offset curves of
 * parametric regular curves", AIMS Press (seed 002).
 *
 * The unit normal N is approximated by N^a(t) = N(0) + int_0^t C'(u) alpha(u) du
 * with alpha a cubic in Bernstein form (eq. 3.1).  Since (N^a)' is parallel to C',
 * C + d N^a is the convolution of C and d N^a: a polynomial of degree n+3 for a
 * polynomial C of degree n (section 3.2).
 *   alpha_0, alpha_3: Hermite curvature conditions (eq. 3.8).  Ahn's N is the
 *     clockwise rotation of the tangent, for which N' = kappa C'; ours is the
 *     left normal, for which N' = -kappa C', hence alpha_{0,3} = -kappa(0), -kappa(1).
 *   alpha_1, alpha_2: N^a(1) = N(1), a 2x2 system solved by Cramer (eq. 3.2-3.4),
 *     regular when the piece is convex and its normal turns by less than pi
 *     (Proposition 3.1); the driver guarantees that (OB_CAP_CONVEX, max_turn).
 * Result: C1 and G2 Hermite interpolation of the offset at both ends, exact
 * on circular arcs.
 */
#include "method.h"

#include <math.h>
#include <string.h>

#include "bernstein.h"

static int ahn_degree(int n, int rational_in)
{
    (void)rational_in;
    return n + 3;
}

/* Solve v1 a1 + v2 a2 = v (eq. 3.2-3.4).  Regular case: Cramer's rule.  When v1
 * and v2 are parallel (a straight piece, where C' keeps one direction) the system
 * is singular but consistent when v is parallel to them too; then take the
 * minimum-norm solution, which for a straight piece is a1 = a2 = 0 and gives the
 * exact offset.  Returns -1 if the system is singular and inconsistent. */
static int solve_alpha12(const double v1[2], const double v2[2], const double v[2], double *a1, double *a2)
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

static ob_status ahn_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                         char *msg, size_t msglen)
{
    (void)work;
    const double d = a->d;
    const int n = base->deg;
    if (base->rational) {
        ob_method_msg(msg, msglen, "rational input is not supported (polynomial method)");
        return OB_SKIP;
    }
    if (n + 3 > OB_MAX_DEG) {
        ob_method_msg(msg, msglen, "output degree %d exceeds %d", n + 3, OB_MAX_DEG);
        return OB_SKIP;
    }
    double b[OB_MAX_DEG + 1][2], db[OB_MAX_DEG][2];
    for (int j = 0; j <= n; j++)
        ob_bez_ctrl(base, j, b[j]);
    for (int j = 0; j < n; j++) {
        db[j][0] = b[j + 1][0] - b[j][0];
        db[j][1] = b[j + 1][1] - b[j][1];
    }
    double e0[2][2], e1[2][2], N0[2], N1[2];
    ob_bez_eval(base, 0.0, 1, e0);
    ob_bez_eval(base, 1.0, 1, e1);
    if ((e0[1][0] == 0.0 && e0[1][1] == 0.0) || (e1[1][0] == 0.0 && e1[1][1] == 0.0)) {
        ob_method_msg(msg, msglen, "C' vanishes at an end of the piece (cusp)");
        return OB_FAIL;
    }
    ob_bez_normal(base, 0.0, N0);
    ob_bez_normal(base, 1.0, N1);
    double alpha[4];
    alpha[0] = -ob_bez_curvature(base, 0.0);
    alpha[3] = -ob_bez_curvature(base, 1.0);

    /* w_i = int_0^1 C'(t) B_i^3(t) dt = n/(n+3) sum_j C(n-1,j) C(3,i)/C(n+2,i+j) db_j */
    double w[4][2];
    for (int i = 0; i < 4; i++) {
        w[i][0] = w[i][1] = 0.0;
        for (int j = 0; j < n; j++) {
            double c = n * ob_binom(n - 1, j) * ob_binom(3, i) / ob_binom(n + 2, i + j) / (n + 3);
            w[i][0] += c * db[j][0];
            w[i][1] += c * db[j][1];
        }
    }
    double v[2] = {N1[0] - N0[0] - alpha[0] * w[0][0] - alpha[3] * w[3][0],
                   N1[1] - N0[1] - alpha[0] * w[0][1] - alpha[3] * w[3][1]};
    if (solve_alpha12(w[1], w[2], v, &alpha[1], &alpha[2]) != 0) {
        ob_method_msg(msg, msglen, "singular, inconsistent system for alpha_1, alpha_2 "
                      "(v1 x v2 = %g): the piece is not convex", w[1][0] * w[2][1] - w[1][1] * w[2][0]);
        return OB_FAIL;
    }

    /* C' alpha in Bernstein form of degree n+2, then integrate to degree n+3 */
    const int m = n + 3;
    double Na[OB_MAX_DEG + 1][2];
    Na[0][0] = N0[0];
    Na[0][1] = N0[1];
    for (int k = 0; k <= n + 2; k++) {
        double c[2] = {0.0, 0.0};
        for (int i = 0; i < 4; i++) {
            int j = k - i;
            if (j < 0 || j > n - 1)
                continue;
            double f = n * alpha[i] * ob_binom(n - 1, j) * ob_binom(3, i) / ob_binom(n + 2, k);
            c[0] += f * db[j][0];
            c[1] += f * db[j][1];
        }
        Na[k + 1][0] = Na[k][0] + c[0] / m;
        Na[k + 1][1] = Na[k][1] + c[1] / m;
    }
    ob_bez up;
    ob_bez_elevate(base, m, &up);
    for (int k = 0; k <= m; k++) {
        up.h[k][0] += d * Na[k][0];
        up.h[k][1] += d * Na[k][1];
    }
    ob_fit_single(out, &up);
    return OB_OK;
}

const ob_method ob_method_ahn = {
    .name = "ahn",
    .citation = "Ahn 2023, G2/C1 Hermite interpolation of offset curves (AIMS Press)",
    .continuity = "C1/G2",
    .caps = OB_CAP_POLY_OUT | OB_CAP_CONVEX | OB_CAP_SAME_PARAM,
    .max_turn = OB_PI,
    .out_degree = ahn_degree,
    .work_size = 0,
    .fit = ahn_fit,
};
