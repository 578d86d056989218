/*
 * coquillart.c - Coquillart 1987, "Computing offsets of B-spline curves",
 * CAD 19(6):305-309, as Liu & Wang 2002 describe it (§1):
 * Cobb's method improved by the curvature: each control point P_j is moved
 * along N(xi_j) by the distance d (1 + kappa_j D_j), where xi_j is the
 * parameter of the curve point nearest to P_j, D_j the distance from P_j to
 * C(xi_j) and kappa_j the curvature there.
 *
 * Nearest point: global sampling of |C(t) - P_j| at 16 n + 65 parameters, then
 * safeguarded Newton on (C - P_j).C' = 0 inside the bracket of the best sample
 * (bisection whenever a Newton step leaves the bracket); the ends are samples,
 * so the end control points get xi = 0, 1 and D = 0.
 *
 * Signs (not spelled out in the seed; parameter `reading`).  With our left
 * normal N, kappa = (x'y'' - y'x'')/|C'|^3 and the signed distance
 * D_j = |P_j - C(xi_j)| sign((P_j - C(xi_j)).N(xi_j)):
 *   0  d (1 - kappa D)      default: exact for circular arcs.  A control point
 *                           of a convex arc lies on the convex side, away from
 *                           the centre: for a counterclockwise circle of radius
 *                           r, N points to the centre, kappa = 1/r, D = -(rho - r)
 *                           for a control point at distance rho from the centre;
 *                           the exact offset (radius r - d) is the control
 *                           polygon scaled about the centre by (r - d)/r, which
 *                           moves P_j by d (rho/r) N = d (1 - kappa D) N.  A
 *                           clockwise circle flips the signs of kappa and D
 *                           (N points outwards), giving the same formula.
 *   1  d (1 + kappa D)      the printed formula read with these signed kappa, D
 *   2  d (1 + |kappa| |D|)  unsigned magnitudes (the same as 0 where the
 *                           control point lies on the convex side)
 *   3  d (1 - |kappa| |D|)  unsigned, opposite sign (the same as 1 there)
 * Foot point (parameter `foot`): 0 = the nearest point, as Liu-Wang describe
 * it (default); 1 = the Greville abscissa xi_j = j/n, the form in which cobb
 * reproduces the Cob column of Lee, Kim & Elber 1996 (Liu-Wang's [13]),
 * for comparison.
 * No combination of foot and sign readings reproduces the published Coq
 * columns (Liu-Wang Table 1: 10, 28, 88, 295, 817 under bound/mid, a little
 * below Cob): on liu2002_ex1 the readings 0/2 give 10, 13, 28, 52, 106 (foot
 * 1: 10, 16, 43, 106, 364) and 1/3 give 13, 40, 133, 394, 1369 (foot 1: 13,
 * 46, 139, 418, 1429).
 * Rational input: the Euclidean point is moved and its weight kept (as cobb),
 * so the rational quadratic form of a circular arc is offset exactly.
 */
#include "methods/method.h"

#include <math.h>

static const ob_param coquillart_params[] = {
    {"reading", 0.0,
     "sign convention of d(1 + kappa D): 0 = d(1 - kappa D) with signed kappa and D "
     "(left normal; exact on circular arcs: the default, the geometric reading), "
     "1 = d(1 + kappa D) signed, 2 = d(1 + |kappa||D|), 3 = d(1 - |kappa||D|)", 0, 3, 1},
    {"foot", 0.0,
     "the curve point associated with P_j: 0 = the nearest point (Liu-Wang's description: "
     "the default), 1 = the Greville abscissa xi_j = j/n (the form in which cobb reproduces "
     "Lee-Kim-Elber's Cob column); D_j is the signed distance from P_j to C(xi_j) either way", 0, 1, 1},
};

/* Nearest parameter: the best of S samples of |C(t) - P|, then safeguarded
 * Newton on f(t) = (C(t) - P).C'(t) = 0 inside the bracket of that sample
 * (f < 0 moves the bracket's lower end up, f > 0 its upper end down; a step
 * that leaves the bracket is replaced by bisection).  The iteration stops on
 * the root of f, not on the smallest sampled distance, which is flat to
 * round-off over sqrt(eps) of the parameter.  A bracket that closes on 0 or 1
 * gives that end. */
static double nearest_param(const ob_bez *b, const double P[2])
{
    const int S = 16 * b->deg + 65;
    int best = 0;
    double gbest = INFINITY;
    for (int k = 0; k < S; k++) {
        double c[2];
        ob_bez_point(b, (double)k / (S - 1), c);
        double g = (c[0] - P[0]) * (c[0] - P[0]) + (c[1] - P[1]) * (c[1] - P[1]);
        if (g < gbest) {
            gbest = g;
            best = k;
        }
    }
    double t = (double)best / (S - 1);
    if (gbest == 0.0)
        return t;
    double lo = best > 0 ? (double)(best - 1) / (S - 1) : 0.0;
    double hi = best < S - 1 ? (double)(best + 1) / (S - 1) : 1.0;
    for (int it = 0; it < 200; it++) {
        double e[3][2];
        ob_bez_eval(b, t, 2, e);
        const double r[2] = {e[0][0] - P[0], e[0][1] - P[1]};
        const double f = r[0] * e[1][0] + r[1] * e[1][1];
        const double fp = e[1][0] * e[1][0] + e[1][1] * e[1][1] + r[0] * e[2][0] + r[1] * e[2][1];
        if (f > 0.0)
            hi = t;
        else if (f < 0.0)
            lo = t;
        else
            break;
        double tn = fp > 0.0 ? t - f / fp : 0.5 * (lo + hi);
        const int newton = fp > 0.0 && tn >= lo && tn <= hi;
        if (!newton)
            tn = 0.5 * (lo + hi);
        if ((newton && fabs(tn - t) <= 1e-15) || hi - lo <= 1e-16) {
            t = tn;
            break;
        }
        t = tn;
    }
    return t;
}

static ob_fit_status coquillart_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                    char *msg, size_t msglen)
{
    (void)work;
    const double d = a->d;
    const int n = base->deg;
    const int reading = (int)a->par[0];
    if (reading < 0 || reading > 3 || a->par[0] != reading) {
        ob_method_msg(msg, msglen, "reading must be 0, 1, 2 or 3 (got %g)", a->par[0]);
        return OB_FIT_FAIL;
    }
    const int foot = (int)a->par[1];
    if ((foot != 0 && foot != 1) || a->par[1] != foot) {
        ob_method_msg(msg, msglen, "foot must be 0 or 1 (got %g)", a->par[1]);
        return OB_FIT_FAIL;
    }
    ob_bez r = *base;
    for (int j = 0; j <= n; j++) {
        double P[2], C[2], N[2];
        ob_bez_ctrl(base, j, P);
        const double xi = foot ? (double)j / n : nearest_param(base, P);
        if (ob_bez_normal(base, xi, N) != 0) {
            ob_method_msg(msg, msglen, "no normal at t = %.17g (point-like segment)", xi);
            return OB_FIT_FAIL;
        }
        ob_bez_point(base, xi, C);
        const double v[2] = {P[0] - C[0], P[1] - C[1]};
        const double dist = hypot(v[0], v[1]);
        const double D = v[0] * N[0] + v[1] * N[1] >= 0.0 ? dist : -dist;
        const double kappa = ob_bez_curvature(base, xi);
        double s;
        switch (reading) {
        case 0: s = 1.0 - kappa * D; break;
        case 1: s = 1.0 + kappa * D; break;
        case 2: s = 1.0 + fabs(kappa) * dist; break;
        default: s = 1.0 - fabs(kappa) * dist; break;
        }
        ob_bez_set(&r, j, P[0] + d * s * N[0], P[1] + d * s * N[1], ob_bez_weight(base, j));
    }
    ob_fit_single(out, &r);
    return OB_FIT_OK;
}

const ob_method ob_method_coquillart = {
    .name = "coquillart",
    .version = 1,
    .citation = "Coquillart 1987, CAD 19(6):305-309 (as described by Liu & Wang 2002)",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 2.04,
    .work_size = 0,
    .params = coquillart_params,
    .nparams = 2,
    .fit = coquillart_fit,
};
