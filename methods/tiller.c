/*
 * tiller.c - Tiller & Hanson 1984, "Offsets of two-dimensional profiles",
 * IEEE CG&A 4(9).  Translate every leg of the control polygon by d along the
 * leg's own unit left normal; the new interior control points are the
 * intersections of consecutive translated legs, the end points are the
 * translated ends of the first and last leg.  Weights are kept, so rational
 * input gives rational output of the same degree.  Exact for straight segments
 * (all legs parallel).
 */
#include "methods/method.h"

#include <math.h>

static ob_fit_status tiller_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                char *msg, size_t msglen)
{
    (void)work;
    const double d = a->d;
    const int n = base->deg;
    double P[OB_MAX_DEG + 1][2], u[OB_MAX_DEG][2], nrm[OB_MAX_DEG][2];
    for (int i = 0; i <= n; i++)
        ob_bez_ctrl(base, i, P[i]);
    /* leg directions; a collapsed leg borrows its neighbour's direction */
    int have = -1;
    for (int i = 0; i < n; i++) {
        double dx = P[i + 1][0] - P[i][0], dy = P[i + 1][1] - P[i][1], len = hypot(dx, dy);
        if (len > 0) {
            u[i][0] = dx / len;
            u[i][1] = dy / len;
            if (have < 0)
                for (int k = 0; k < i; k++)
                    u[k][0] = u[i][0], u[k][1] = u[i][1];
            have = i;
        } else if (have >= 0) {
            u[i][0] = u[have][0];
            u[i][1] = u[have][1];
        }
    }
    if (have < 0) {
        ob_method_msg(msg, msglen, "control polygon collapses to a point");
        return OB_FIT_FAIL;
    }
    for (int i = 0; i < n; i++) {
        nrm[i][0] = -u[i][1];
        nrm[i][1] = u[i][0];
    }
    ob_bez r = *base;
    double Q[2];
    Q[0] = P[0][0] + d * nrm[0][0];
    Q[1] = P[0][1] + d * nrm[0][1];
    ob_bez_set(&r, 0, Q[0], Q[1], ob_bez_weight(base, 0));
    for (int i = 1; i < n; i++) {
        /* line i-1: A + s u[i-1], line i: B + s u[i] */
        double A[2] = {P[i][0] + d * nrm[i - 1][0], P[i][1] + d * nrm[i - 1][1]};
        double B[2] = {P[i][0] + d * nrm[i][0], P[i][1] + d * nrm[i][1]};
        double cr = u[i - 1][0] * u[i][1] - u[i - 1][1] * u[i][0];
        if (fabs(cr) < 1e-12) {
            Q[0] = A[0];  /* parallel legs: the shared translated point */
            Q[1] = A[1];
        } else {
            double s = ((B[0] - A[0]) * u[i][1] - (B[1] - A[1]) * u[i][0]) / cr;
            Q[0] = A[0] + s * u[i - 1][0];
            Q[1] = A[1] + s * u[i - 1][1];
        }
        ob_bez_set(&r, i, Q[0], Q[1], ob_bez_weight(base, i));
    }
    Q[0] = P[n][0] + d * nrm[n - 1][0];
    Q[1] = P[n][1] + d * nrm[n - 1][1];
    ob_bez_set(&r, n, Q[0], Q[1], ob_bez_weight(base, n));
    ob_fit_single(out, &r);
    return OB_FIT_OK;
}

const ob_method ob_method_tiller = {
    .name = "tiller",
    .version = 1,
    .citation = "Tiller & Hanson 1984, IEEE CG&A 4(9):36-46",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM | OB_CAP_INTERP_ENDS,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 2.06,
    .work_size = 0,
    .fit = tiller_fit,
};
