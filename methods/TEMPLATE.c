/*
 * TEMPLATE.c - a small, working method to start a new one from (README "How
 * to add a method"; the rules every method keeps: methods/CONTRACT.md).
 *
 * To add a method:
 *   1. copy this file to methods/NAME.c; rename ob_method_template to
 *      ob_method_NAME (NAME with '_' where the CLI name has '-') and
 *      template_* to NAME_*; set .name, .citation, .version = 1;
 *   2. replace template_fit() by the method, and say here, in this header,
 *      what the method is, where it comes from, and every reading of the
 *      paper it takes (a choice the paper leaves open is a parameter);
 *   3. add the line OB_METHOD(NAME) at the end of methods/registry.def;
 *   4. run `make check-method M=NAME` until it passes (each failure names
 *      the rule, what was seen and what to do);
 *   5. add tests/methods/test_NAME.c with what the paper claims.
 *
 * This file is compiled into the library and checked by the contract test
 * (`make check-method M=template`; tests/methods/test_methods.c runs it with
 * every registered method) but it is not in registry.def: `--methods all`,
 * `list methods` and every run leave it out.
 *
 * The method: a cubic through the offset's end points, tangent there to the
 * offset, and through the offset's point at t = 1/2.  With O(t) = C(t) +
 * d N(t) and T0, T1 the offset's unit tangents at the ends (C' turned back
 * where 1 - d kappa < 0: the offset runs backwards there), the control
 * points are
 *     Q0 = O(0),  Q1 = O(0) + L0 T0,  Q2 = O(1) - L1 T1,  Q3 = O(1),
 * and A(1/2) = (O(0) + O(1)) / 2 + 3/8 (L0 T0 - L1 T1) = O(1/2) is a 2x2
 * linear system for the handle lengths L0, L1.  Where it has no solution
 * with both lengths positive (a nearly straight piece, a turn near pi), or
 * with the parameter midpoint = 0, the circular-arc rule
 * L0 = L1 = chord / (3 cos^2(theta / 4)) is taken (theta: the angle between
 * T0 and T1; exact on lines, the usual cubic of a circular arc).  The error
 * falls at least like h^4 with the piece's length h (the cubic Hermite with
 * the offset's own end derivatives does too, but not at the first halving
 * of one of the contract's test cubics: methods/CONTRACT.md, `halving`);
 * pieces meet with matching tangent directions (G1) where 1 - d kappa > 0
 * at the joint.  Rational input works the same way; the output is
 * always a polynomial cubic, not in the base's parameter (no
 * OB_CAP_SAME_PARAM: the bound and radial metrics do not apply).
 */
#include "methods/method.h"

#include <math.h>

/* The method's parameters: choices the method (or its paper) leaves open.
 * Each has a default (the paper's reading), a documented range that
 * `--param template.midpoint=V` is checked against before any job runs, and
 * `integer` for whole numbers only.  A method without parameters leaves
 * .params NULL and .nparams 0. */
static const ob_param template_params[] = {
    {.name = "midpoint",
     .def = 1,
     .doc = "1 = handle lengths that put the cubic through the offset's point at t = 1/2 (the default); "
            "0 = the circular-arc rule alone",
     .min = 0,
     .max = 1,
     .integer = 1},
};

/* One end of the Hermite data: the offset's point O(t) = C(t) + d N(t) and
 * unit tangent T (t = 0 or 1): C' turned back where 1 - d kappa < 0 (the
 * offset runs backwards there).  Returns 0, or -1 when the segment has no
 * tangent there (it is point-like). */
static int offset_end(const ob_bez *base, double t, double d, double O[2], double T[2])
{
    double N[2];
    if (ob_bez_normal(base, t, N) != 0)
        return -1;
    ob_bez_offset_point(base, t, d, O);
    const double g = 1.0 - d * ob_bez_curvature(base, t);
    T[0] = g < 0 ? -N[1] : N[1]; /* the unit tangent is N turned right */
    T[1] = g < 0 ? N[0] : -N[0];
    return 0;
}

static double cross2(const double a[2], const double b[2])
{
    return a[0] * b[1] - a[1] * b[0];
}

/* The handle lengths L[0], L[1] of the cubic from O0 (tangent T0) to O1
 * (tangent T1) through the point Om at t = 1/2, when both come out positive
 * (midpoint != 0); else those of the circular-arc rule. */
static void handle_lengths(const double O0[2], const double T0[2], const double O1[2], const double T1[2],
                           const double Om[2], int midpoint, double L[2])
{
    const double chord = hypot(O1[0] - O0[0], O1[1] - O0[1]);
    const double theta = acos(fmax(-1.0, fmin(1.0, T0[0] * T1[0] + T0[1] * T1[1])));
    const double c = cos(theta / 4);
    L[0] = L[1] = chord / (3 * c * c);
    const double det = cross2(T0, T1);
    if (!midpoint || fabs(det) < 1e-6)
        return;
    /* L0 T0 - L1 T1 = v, by Cramer's rule */
    const double v[2] = {8.0 / 3.0 * (Om[0] - 0.5 * (O0[0] + O1[0])), 8.0 / 3.0 * (Om[1] - 0.5 * (O0[1] + O1[1]))};
    const double l0 = cross2(v, T1) / det, l1 = -cross2(T0, v) / det;
    if (l0 > 0 && l1 > 0 && isfinite(l0) && isfinite(l1)) {
        L[0] = l0;
        L[1] = l1;
    }
}

/* Purpose: approximate the d-offset of base over [0,1] (method.h, fit).
 * Keeps no static state, allocates nothing, never prints: the result goes
 * into out, a reason for a failure into msg. */
static ob_fit_status template_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out, char *msg,
                                  size_t msglen)
{
    (void)work; /* work_size is 0: no scratch space */
    double O0[2], T0[2], O1[2], T1[2], Om[2], L[2];
    if (offset_end(base, 0.0, a->d, O0, T0) != 0 || offset_end(base, 1.0, a->d, O1, T1) != 0) {
        ob_method_msg(msg, msglen, "no tangent at an end (point-like segment)");
        return OB_FIT_FAIL;
    }
    ob_bez_offset_point(base, 0.5, a->d, Om);
    handle_lengths(O0, T0, O1, T1, Om, a->par[0] != 0, L);
    const double Q[4][2] = {{O0[0], O0[1]},
                            {O0[0] + L[0] * T0[0], O0[1] + L[0] * T0[1]},
                            {O1[0] - L[1] * T1[0], O1[1] - L[1] * T1[1]},
                            {O1[0], O1[1]}};
    for (int i = 0; i < 4; i++)
        if (!isfinite(Q[i][0]) || !isfinite(Q[i][1])) {
            ob_method_msg(msg, msglen, "non-finite control point %d", i);
            return OB_FIT_FAIL;
        }
    ob_bez r;
    ob_bez_from_points(&r, 3, Q);
    ob_fit_single(out, &r); /* one piece over the whole [0,1] */
    return OB_FIT_OK;
}

const ob_method ob_method_template = {
    /* the name in --methods, --param, list methods and results.csv: lower
     * case letters, digits and '-', unique among the methods */
    .name = "template",
    /* a short reference: authors, year, where it was published */
    .citation = "cubic Hermite interpolation of the offset's end points and derivatives (the template method)",
    /* 1 at first; + 1 whenever its output changes on purpose, so that runs of
     * two versions are not compared for regressions (compare exits 3) */
    .version = 1,
    /* what the method claims at the joints of its pieces: "G0", "G1",
     * "C1/G2", "none"; a run measures what it reaches */
    .continuity = "G1",
    /* capability flags (method.h): polynomial output; rational input taken;
     * it passes through the offset's end points (the contract test checks
     * it).  Not OB_CAP_SAME_PARAM: the cubic does not follow the base's
     * parameter, so bound and radial jobs are skipped.  The exceptions a
     * method may declare are in methods/CONTRACT.md. */
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_INTERP_ENDS,
    /* > 0: the driver first splits pieces whose tangent turns by this
     * (radians) or more; 0: no such limit */
    .max_turn = 0.0,
    /* the degree of every output piece for input degree n: here always 3
     * (ob_degree_same: n; or a function of n, rational_in and par) */
    .out_degree = ob_degree_three,
    /* median thread ms per job on the nightly's random set, the cost model of
     * --shard (method.h): measure it once the method works */
    .cost_ms = 1.0,
    /* bytes of scratch space the driver hands to every fit() */
    .work_size = 0,
    /* NULL: fit() never reads a->tol (fits are shared between tolerances);
     * ob_fit_uses_tol_always when it does */
    .fit_uses_tol = NULL,
    .params = template_params,
    .nparams = (int)(sizeof template_params / sizeof template_params[0]),
    .fit = template_fit,
};
