/*
 * kim2018.c - Kim, Lee & Ahn 2018, "A new method approximating offset curve by
 * Bézier curve using parallel derivative curves", Comp. Appl. Math. 37:2053-2064
 * (reference [26] of Ahn 2023, AIMS Mathematics; the paper itself was not at hand).
 *
 * As Ahn 2023 describes it (section 3, "a special case of our method"): the unit
 * normal N is approximated by
 *     N^a(t) = N(0) + int_0^t C'(u) alpha(u) du,   alpha(t) = a0 (1-t) + a1 t,
 * a normal field whose derivative is parallel to C', so that C + d N^a is the
 * convolution of C and d N^a: a polynomial of degree n+1 for a polynomial C of
 * degree n (C' alpha has degree n, its integral n+1).  The two coefficients are
 * fixed by N^a(1) = N(1):
 *     a0 w0 + a1 w1 = N(1) - N(0),   w_i = int_0^1 C'(t) B_i^1(t) dt,
 * the 2x2 system of Ahn's eq. 3.2-3.4 with alpha of degree 1, solved by
 * Cramer's rule.  It is regular when the piece is convex and its tangent turns
 * by less than pi (w0 x w1 = int int_{s<t} (t-s) C'(s) x C'(t) ds dt has one
 * sign there), which the driver guarantees (OB_CAP_CONVEX, max_turn = pi).  A
 * straight piece makes it singular but consistent (N(1) = N(0)): then
 * a0 = a1 = 0 and the result is the exact offset (as ahn's solve).
 * Result: N^a(0) = N(0), N^a(1) = N(1), so the approximation interpolates the
 * offset at both ends, and its tangent C'(1 + d alpha) is parallel to C' and
 * so to the offset's tangent C'(1 - d kappa): G1 Hermite interpolation
 * wherever 1 + d alpha > 0.  Polynomial input only.
 * Readings: the seed gives neither the paper's own equations nor its
 * end-curvature handling; alpha linear with only the end-normal condition is
 * Ahn's description, and the degree n+1 agrees with the 4k+1 counts of the
 * [26] column of Ahn's Table 1 for a cubic.
 */
#include "methods/method.h"

#include "methods/common/convolution.h"

static int kim2018_degree(int n, int rational_in, const double *par)
{
    (void)par;
    (void)rational_in;
    return n + 1;
}

static ob_fit_status kim2018_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                 char *msg, size_t msglen)
{
    (void)work;
    const double d = a->d;
    const int n = base->deg;
    double N0[2], N1[2];
    const ob_fit_status pre = ob_conv_prepare(base, n + 1, N0, N1, msg, msglen);
    if (pre != OB_FIT_OK)
        return pre;
    double w[2][2], alpha[2];
    ob_conv_moments(base, 1, w);
    const double v[2] = {N1[0] - N0[0], N1[1] - N0[1]};
    if (ob_conv_solve2(w[0], w[1], v, &alpha[0], &alpha[1]) != 0) {
        ob_method_msg(msg, msglen, "singular, inconsistent system for alpha_0, alpha_1 "
                      "(w0 x w1 = %g): the piece is not convex",
                      w[0][0] * w[1][1] - w[0][1] * w[1][0]);
        return OB_FIT_FAIL;
    }
    ob_bez r;
    if (ob_conv_offset(base, alpha, 1, N0, d, &r) != 0) {
        ob_method_msg(msg, msglen, "output degree %d exceeds %d", n + 1, OB_MAX_DEG);
        return OB_FIT_SKIP;
    }
    ob_fit_single(out, &r);
    return OB_FIT_OK;
}

const ob_method ob_method_kim2018 = {
    .name = "kim2018",
    .version = 1,
    .citation = "Kim, Lee & Ahn 2018, Comp. Appl. Math. 37:2053-2064 (as described by Ahn 2023)",
    .continuity = "G1",
    .caps = OB_CAP_POLY_OUT | OB_CAP_CONVEX | OB_CAP_SAME_PARAM | OB_CAP_INTERP_ENDS,
    .max_turn = OB_PI,
    .out_degree = kim2018_degree,
    .cost_ms = 1.72,
    .work_size = 0,
    .fit = kim2018_fit,
};
