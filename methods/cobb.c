/*
 * cobb.c - Cobb 1984 (PhD thesis, Utah) as implemented in Elber, Lee & Kim's
 * comparison (IEEE CG&A 17(1), 1997): move each control point P_j by d N(t*_j)
 * at its Greville abscissa t*_j = j/n.  (Liu & Wang describe the parameter of
 * the curve point nearest to P_j; the Greville form is the one behind the
 * published Cob column of Liu & Wang 2002, Table 1, which Lee, Kim & Elber
 * 1996 measured: README "Published figures this version reproduces exactly".)  Rational input: the Euclidean point is
 * moved and its weight kept, i.e. w_j (P_j + d N) in homogeneous form.
 */
#include "methods/method.h"

static ob_fit_status cobb_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                              char *msg, size_t msglen)
{
    (void)work;
    const double d = a->d;
    const int n = base->deg;
    ob_bez r = *base;
    for (int j = 0; j <= n; j++) {
        double P[2], N[2];
        ob_bez_ctrl(base, j, P);
        if (ob_bez_normal(base, (double)j / n, N) != 0) {
            ob_method_msg(msg, msglen, "no normal at t = %d/%d (point-like segment)", j, n);
            return OB_FIT_FAIL;
        }
        ob_bez_set(&r, j, P[0] + d * N[0], P[1] + d * N[1], ob_bez_weight(base, j));
    }
    ob_fit_single(out, &r);
    return OB_FIT_OK;
}

const ob_method ob_method_cobb = {
    .name = "cobb",
    .version = 1,
    .citation = "Cobb 1984, PhD thesis, Univ. of Utah (Greville form of Elber-Lee-Kim 1997)",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM | OB_CAP_INTERP_ENDS,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 2.5,
    .work_size = 0,
    .fit = cobb_fit,
};
