/*
 * ahn.c - Ahn 2023, "G2/C1 Hermite interpolation of offset curves of
 * parametric regular curves", AIMS Mathematics (AIMS Press), 2023.
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
 * on circular arcs.  The moments, the 2x2 solve and the construction of
 * C + d N^a are shared with kim2018.c (convolution.c).
 */
#include "methods/method.h"

#include <math.h>
#include <string.h>

#include "methods/common/convolution.h"

static int ahn_degree(int n, int rational_in, const double *par)
{
    (void)par;
    (void)rational_in;
    return n + 3;
}

static ob_fit_status ahn_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                             char *msg, size_t msglen)
{
    (void)work;
    const double d = a->d;
    const int n = base->deg;
    double N0[2], N1[2];
    const ob_fit_status pre = ob_conv_prepare(base, n + 3, N0, N1, msg, msglen);
    if (pre != OB_FIT_OK)
        return pre;
    double alpha[4];
    alpha[0] = -ob_bez_curvature(base, 0.0);
    alpha[3] = -ob_bez_curvature(base, 1.0);

    /* w_i = int_0^1 C'(t) B_i^3(t) dt (eq. 3.3) */
    double w[4][2];
    ob_conv_moments(base, 3, w);
    double v[2] = {N1[0] - N0[0] - alpha[0] * w[0][0] - alpha[3] * w[3][0],
                   N1[1] - N0[1] - alpha[0] * w[0][1] - alpha[3] * w[3][1]};
    if (ob_conv_solve2(w[1], w[2], v, &alpha[1], &alpha[2]) != 0) {
        ob_method_msg(msg, msglen, "singular, inconsistent system for alpha_1, alpha_2 "
                      "(v1 x v2 = %g): the piece is not convex", w[1][0] * w[2][1] - w[1][1] * w[2][0]);
        return OB_FIT_FAIL;
    }

    /* C + d N^a, N^a = N(0) + int C' alpha: degree n+3 (section 3.2) */
    ob_bez up;
    ob_conv_offset(base, alpha, 3, N0, d, &up);
    ob_fit_single(out, &up);
    return OB_FIT_OK;
}

const ob_method ob_method_ahn = {
    .name = "ahn",
    .version = 1,
    .citation = "Ahn 2023, G2/C1 Hermite interpolation of offset curves (AIMS Press)",
    .continuity = "C1/G2",
    .caps = OB_CAP_POLY_OUT | OB_CAP_CONVEX | OB_CAP_SAME_PARAM | OB_CAP_INTERP_ENDS,
    .max_turn = OB_PI,
    .out_degree = ahn_degree,
    .cost_ms = 1.24,
    .work_size = 0,
    .fit = ahn_fit,
};
