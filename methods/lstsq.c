/*
 * lstsq.c - the "Lst" column of Liu & Wang 2002 (J. Software 13(3), §3): their
 * control-point shifting with the normal curve approximated by least squares
 * on sampled normals.  The paper only names the variant; here it is the
 * end-constrained construction of §2.3 (D(0) = N_d(0), D(1) = N_d(1), fixed)
 * with the n-1 interior Bernstein coefficients fitted by discrete least
 * squares to M samples of the normal curve at the uniform parameters
 * t_j = j/(M+1), j = 1..M (solved by Givens QR).  Rational input as in §2.4:
 * fit W(t) N_d(t), keep the weights.  Output: degree n, G0, parameterized
 * like the base.  Shared code: normalfit.c.
 *
 * Readings (the paper gives neither): the samples are of the normal curve
 * itself ("采样最小二乘逼近法向", least-squares approximation of the normal
 * from samples); target = 1 fits the samples of f~ = (f - f0 B_0^n - f1
 * B_n^n)/((1-t)t) instead, the discrete analogue of liu's construction.  The
 * default M = 32 uniform samples is the harness's choice: many more than the
 * n - 1 unknowns of the pieces benchmarked (cubics), few enough to remain a
 * sampled fit.
 */
#include "methods/common/normalfit.h"

static const ob_param lstsq_params[] = {
    {"samples", 32, "uniform interior samples t_j = j/(M+1), j = 1..M, of the least-squares "
                    "fit (>= n-1, <= 1024).  Not given by Liu-Wang; 32 is the harness's choice", 1, 1024, 1},
    {"target", 0, "0: fit the samples of the normal curve d N (W d N for rational input) "
                  "with the ends fixed, the literal 'least squares on sampled normals' (default); "
                  "1: fit the samples of f~ = (f - f0 B_0^n - f1 B_n^n)/((1-t)t), the discrete "
                  "analogue of Liu-Wang's eq. (7)", 0, 1, 1},
};

static ob_fit_status lstsq_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                               char *msg, size_t msglen)
{
    return ob_nf_method_fit(OB_NF_LSTSQ, base, a, work, out, msg, msglen);
}

const ob_method ob_method_lstsq = {
    .name = "lstsq",
    .version = 1,
    .citation = "Liu & Wang 2002, J. Software (in Chinese) (\"Lst\": sampled least squares, end-constrained)",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 1.27,
    .work_size = 0,
    .params = lstsq_params,
    .nparams = 2,
    .fit = lstsq_fit,
};
