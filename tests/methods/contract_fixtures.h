/*
 * contract_fixtures.h - deliberately broken methods for the method contract
 * test (tests/methods/test_methods.c, methods/CONTRACT.md).  Each one is
 * cobb with one rule broken, so that the test shows it catches that rule and
 * names it; one breaks a rule and declares the exception, and must pass.
 * Test-only: included by test_methods.c alone, never registered, not in the
 * library.  `make check-method M=broken-halving` (etc.) shows what a failing
 * method's report looks like.
 */
#ifndef OB_CONTRACT_FIXTURES_H
#define OB_CONTRACT_FIXTURES_H

#include <math.h>

#include "methods/core/curve.h"
#include "methods/method.h"

extern const ob_method ob_method_cobb;

/* cobb at a distance that grows as the piece shrinks (by 0.5 / chord):
 * halving a piece raises its error. */
static ob_fit_status fixture_halving_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                         char *msg, size_t msglen)
{
    double p0[2], pn[2];
    ob_bez_ctrl(base, 0, p0);
    ob_bez_ctrl(base, base->deg, pn);
    const double chord = hypot(pn[0] - p0[0], pn[1] - p0[1]);
    if (!(chord > 0)) {
        ob_method_msg(msg, msglen, "closed or point-like segment");
        return OB_FIT_SKIP;
    }
    const ob_fit_args far = {a->d + copysign(0.5 / chord, a->d), a->tol, a->par};
    return ob_method_cobb.fit(base, &far, work, out, msg, msglen);
}

/* cobb raised by one degree that out_degree does not report. */
static ob_fit_status fixture_degree_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                        char *msg, size_t msglen)
{
    const ob_fit_status st = ob_method_cobb.fit(base, a, work, out, msg, msglen);
    ob_bez up;
    if (st == OB_FIT_OK && ob_bez_elevate(&out->seg[0], out->seg[0].deg + 1, &up) == 0)
        out->seg[0] = up;
    return st;
}

/* cobb with a 1e-13 nudge on every other call: state kept between calls. */
static ob_fit_status fixture_state_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                       char *msg, size_t msglen)
{
    static unsigned calls;
    const ob_fit_status st = ob_method_cobb.fit(base, a, work, out, msg, msglen);
    if (st == OB_FIT_OK)
        out->seg[0].h[0][0] += (double)(calls++ & 1u) * 1e-13;
    return st;
}

#define FIXTURE(nm, f, extra_caps, uses_tol)                                                                  \
    {.name = nm, .citation = "test fixture (tests/methods/contract_fixtures.h)", .version = 1,               \
     .continuity = "G0", .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM | (extra_caps), .max_turn = 0.0,         \
     .out_degree = ob_degree_same, .cost_ms = 1.0, .work_size = 0, .fit_uses_tol = (uses_tol), .params = NULL, \
     .nparams = 0, .fit = (f)}

static const ob_method fixture_methods[] = {
    FIXTURE("broken-halving", fixture_halving_fit, 0u, NULL),
    FIXTURE("broken-halving-declared", fixture_halving_fit, (unsigned)OB_CAP_NONMONOTONE, NULL),
    FIXTURE("broken-degree", fixture_degree_fit, 0u, NULL),
    FIXTURE("broken-state", fixture_state_fit, 0u, ob_fit_uses_tol_always),
};
enum { NFIXTURES = sizeof fixture_methods / sizeof fixture_methods[0] };

#undef FIXTURE

#endif
