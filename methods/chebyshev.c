/*
 * chebyshev.c - the "Che" column of Liu & Wang 2002 (J. Software 13(3), §3): their
 * control-point shifting with the normal curve approximated by Chebyshev
 * polynomials instead of Legendre ones.  The paper only names the variant;
 * here it is the construction of liu.c (§2.3, eq. 6-7: D interpolates
 * N_d(0) and N_d(1), the interior comes from a degree n-2 approximation of
 * f~(t) = (f - f0 B_0^n - f1 B_n^n)/((1-t)t)) with the truncated Chebyshev
 * series of f~ (weight 1/sqrt(1-x^2), x = 2t-1) in place of the Legendre
 * series.  Its coefficients are computed by Gauss-Chebyshev quadrature on M
 * nodes (inside (0,1), so the end limits of f~ are never needed).  Rational
 * input as in §2.4: fit W(t) N_d(t), keep the weights.  Output: degree n, G0,
 * parameterized like the base.  Shared code: normalfit.c.
 *
 * Reading: the node count is not given; the default 64 makes the quadrature
 * (aliasing) error of the coefficients negligible for smooth normals (below
 * 1e-12 on the whole liu2002_ex1 cubic), so the result is the truncated
 * series itself.  nodes = n-1 gives instead the
 * interpolant of f~ at the Chebyshev points.
 */
#include "methods/common/normalfit.h"

static const ob_param chebyshev_params[] = {
    {"nodes", 64, "Gauss-Chebyshev nodes for the Chebyshev coefficients of f~ (1..1024). "
                  "Not given by Liu-Wang; 64 makes the quadrature error negligible (the "
                  "truncated Chebyshev series); n-1 gives Chebyshev interpolation", 1, 1024, 1},
};

static ob_fit_status chebyshev_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                   char *msg, size_t msglen)
{
    return ob_nf_method_fit(OB_NF_CHEBYSHEV, base, a, work, out, msg, msglen);
}

const ob_method ob_method_chebyshev = {
    .name = "chebyshev",
    .version = 1,
    .citation = "Liu & Wang 2002, J. Software (in Chinese) (\"Che\": Chebyshev, end-constrained)",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 1.56,
    .work_size = 2 * OB_NF_MAX_NODES * sizeof(double),
    .params = chebyshev_params,
    .nparams = 1,
    .fit = chebyshev_fit,
};
