/*
 * liu.c - Liu & Wang 2002, "Optimal approximation to curve offset based on
 * shifting control points", J. Software 13(3), 2002 (in Chinese), §2.2-2.4.
 *
 * Shift every control point P_i of the base segment by D_i, the Bernstein
 * coefficients of a degree-n polynomial D(t) that approximates the normal
 * curve N_d(t) = d N(t) (§2.1, eq. 1).  D is the end-point interpolating
 * near-best L2 approximation of §2.3 (eq. 6-7): D(0) = N_d(0), D(1) = N_d(1),
 * and the interior from the best L2 approximation (Legendre series, weight 1,
 * §2.2 eq. 3-5) of degree n-2 of f~(t) = (f(t) - f0 B_0^n - f1 B_n^n)/((1-t)t),
 * coefficient i = 1..n-1 = C(n-2,i-1)/C(n,i) s~_{i-1}.  The Legendre
 * coefficients are integrals computed by Gauss-Legendre quadrature (§2.4).
 * Rational input (§2.4): the same fit of W(t) N_d(t), W the weight polynomial,
 * and D_i = c_i / w_i with the weights kept, i.e. homogeneous points
 * w_i P_i + c_i.  Output: degree n, G0 (the ends interpolate the offset),
 * parameterized like the base.  The paper splits at inflections first (the
 * driver's default) and splits at the point of maximum error (Step 5: the
 * driver's `maxerr` rule).  Code shared with chebyshev and lstsq: normalfit.c.
 *
 * Readings: the paper gives no node count for its Gauss-Legendre rule; the
 * default 64 makes the quadrature error of the Legendre coefficients
 * negligible for smooth normals: on the whole liu2002_ex1 cubic (its normal
 * turns by 3 rad, the hardest piece the driver hands over) the coefficients
 * agree with a 1024-node rule to 1e-15 (32 nodes: 2e-10, 16: 1e-5; checked in
 * tests/methods/test_normalfit.c).  f~ is only evaluated at the Gauss nodes, inside
 * (0,1), so its end limits are never needed.  §2.3 states n > 3 but the
 * examples are cubic; the construction works for every n >= 2 (n = 1: D
 * interpolates the two ends).
 */
#include "methods/common/normalfit.h"

static const ob_param liu_params[] = {
    {"nodes", 64, "Gauss-Legendre nodes for the Legendre coefficients of f~ (1..1024). "
                  "Liu-Wang use Gauss-Legendre quadrature without giving a count; 64 "
                  "makes the quadrature error negligible for smooth normals (< 1e-14 on the whole "
                  "liu2002_ex1 cubic, whose normal turns by 3 rad)", 1, 1024, 1},
};

static ob_fit_status liu_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                             char *msg, size_t msglen)
{
    return ob_nf_method_fit(OB_NF_LEGENDRE, base, a, work, out, msg, msglen);
}

const ob_method ob_method_liu = {
    .name = "liu",
    .version = 1,
    .citation = "Liu & Wang 2002, J. Software (in Chinese) (Legendre, end-constrained)",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM | OB_CAP_INTERP_ENDS,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 1.95,
    .work_size = 4 * OB_NF_MAX_NODES * sizeof(double),
    .params = liu_params,
    .nparams = 1,
    .fit = liu_fit,
};
