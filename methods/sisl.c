/*
 * sisl.c - SINTEF's SISL library (Debian libsisl-dev, 4.6) as a baseline:
 * s1360 "create a curve approximating the offset of a B-spline curve within
 * a tolerance".  It is what many C users would call instead of a method from
 * the literature; offbench measures its true error with its own metrics and
 * does not trust SISL's tolerance.
 *
 * What is done, and every reading taken:
 *  - The base segment (degree n, polynomial or rational) becomes a SISL curve
 *    by newCurve(n+1 vertices, order n+1, clamped knots 0^(n+1) 1^(n+1),
 *    ikind 1 with Euclidean (x, y) or ikind 2 with homogeneous (w x, w y, w)
 *    vertices, dimension 2, icopy 1 = SISL copies the arrays).
 *  - s1360(curve, d, tol, enorm, max_step, 2, &offset, &status) with the job's
 *    tolerance (ob_fit_args.tol).  enorm only matters in 3D.
 *  - Orientation: in 2D SISL offsets a positive distance towards (-y', x'),
 *    the left normal, which is ours (checked in tests/methods/test_sisl.c), so d is
 *    passed unchanged.
 *  - The result is a polynomial cubic B-spline (order 4, ikind 1) for every
 *    input seen, rational input included: s1360 samples the exact offset
 *    (points and tangent directions at parameters of the base, SISL choosing
 *    the steps) and joins them by cubic Hermite segments: interior knots of
 *    multiplicity 3, tangent directions matched at the knots but not their
 *    lengths, so G1 (not C1) there and at the ends.  Its domain is the
 *    base's [0,1] and its knots are BASE parameters: at each knot u the
 *    result passes through C(u) + d N(u) (to round-off, tested).  So the
 *    breakpoints t[] of the pieces are exactly the knots.  Inside a span,
 *    though, SISL's tangent lengths are not those of C + d N in the base
 *    parameter (only the directions are matched), so the result is NOT
 *    parameterized like the base: at tol 1e-3 on liu2002_ex1 (d = 1),
 *    |A(t) - O(t)| reaches 0.0085 where the hausdorff error is 0.0023.
 *    Hence no OB_CAP_SAME_PARAM: bound/radial jobs are skipped by the
 *    driver; hausdorff and normal apply.
 *  - Output pieces: one Bezier cubic per non-empty knot span, extracted by
 *    blossoming (de Boor's algorithm with the span's end knots as arguments),
 *    in fixed-size local arrays.  ctrl_points = the B-spline's own number of
 *    control points (README "Output": a B-spline counts its control points).
 *    More spans than OB_SPLIT_PIECES: OB_FIT_RETRY_SMALLER (the driver splits the
 *    piece and SISL starts again on each half).
 *  - SISL's tolerance is not a bound under our metrics (tests/methods/test_sisl.c
 *    prints the measurement): on liu2002_ex1 the hausdorff error of its
 *    whole-curve result reaches 18x the tolerance at the cusps of the d = 1
 *    offset and about 3x on the smooth d = -1 offset (in the last span), so
 *    the driver's splitting, not SISL's tolerance, decides the counts.
 *  - Capabilities: OB_CAP_TOL_DRIVEN (the number of spans follows the
 *    tolerance, so a half piece gets about as large an error as the whole);
 *    OB_CAP_ORIENTED (s1360 marches from the start of the parameter, so the
 *    reversed curve gets other Hermite points and another error).
 *  - s1360's status < 0: OB_FIT_FAIL with that status in msg (e.g. -184 for a
 *    tolerance <= 0).  A result that is not a polynomial cubic B-spline on
 *    [0,1] would break the readings above: OB_FIT_FAIL saying so.
 *
 * Allocation: newCurve/s1360/freeCurve allocate inside the library (malloc);
 * the no-allocation rule is for our own code in the timed path, which here
 * uses only stack arrays.  Every SISL curve is freed with freeCurve on every
 * path.
 *
 * Thread safety: the driver calls fit() from several OpenMP threads at once.
 * The objects of libsisl.a that s1360 can reach (its call closure, found with
 * nm: construct, destruct, s1219-s1221, s1227, s1307, s1311, s1325, s1359,
 * s1360-s1362, s6*, sh1992, sh6*, tstcyclknt) have empty .data and .bss: no
 * static mutable state (the library's only statics are in s1613bez and sh1762,
 * which s1360 does not reach), and they call only malloc/free and libm.  So no
 * lock is taken around s1360.  tests/methods/test_sisl.c also compares fits made on
 * several threads at once with serial ones.
 *
 * Printing: SISL reports every error through s6err, which writes three lines
 * to stderr.  Methods never print, and the status is returned anyway, so the
 * server (methods/sisl/server.c, where s1360 runs) defines s6err as a no-op; with the static libsisl.a the linker then
 * takes ours and leaves SISL's out (SISL's error codes still reach the
 * caller through s1360's status).
 *
 * Timing: the server measures its CPU time in newCurve and s1360 and sends
 * it with the reply; the fit adds it to the calling thread's foreign time
 * (ob_fit_foreign_add), which the job's fit_ns (and so --job-timeout) and
 * `run --time-fits` count as the method's own.  A server that ends without
 * answering has what it spent unreported counted when it is reaped.
 *
 * Isolation: s1360 does not always return.  On some inputs (found with
 * --random 500:7: a degenerate cubic cut down to a piece 7e-7 long) it
 * loops, growing an array by realloc without end (4 GB and counting, inside
 * s1360).  A library call cannot be stopped from outside, so s1360 runs in
 * a server process, one per calling thread and process, started on first
 * use (methods/sisl/client.c: who owns a server, forks and threads; the
 * server, methods/sisl/server.c: how it is started and what it checks).
 * The fit sends the segment and the arguments and reads the result
 * (status, order, knots, vertices) with two limits:
 *  - a CPU deadline, enforced by the kernel in the server (RLIMIT_CPU, whole
 *    seconds rounded up): sisl.timeout (default 20 s), or the job's
 *    remaining --job-timeout budget when that is smaller (the server's CPU
 *    time counts as the fit's: ob_fit_budget_ns, method.h).  Past it the server
 *    ends; the fit fails "did not finish" (sisl.timeout), or ends
 *    OB_FIT_TIMEOUT "job timeout" (the budget: the row other methods get).
 *  - a wall-clock cap (sisl.wall_timeout; default 0 = 3 x (deadline + 1)
 *    seconds): the CPU deadline alone, on a loaded machine where the server
 *    got 5 % of a CPU, kept a fit waiting for minutes (issue 46).  Why that
 *    default: RLIMIT_CPU counts whole seconds rounded up, so a call may run
 *    up to deadline + 1 CPU seconds, and with three times that the server
 *    reaches its CPU deadline first whenever it gets at least a third of a
 *    CPU; no fit that finishes is affected.  Past the cap the server is
 *    killed and the fit ends OB_FIT_TIMEOUT (the job's status `timeout`,
 *    the message naming the cap): the load decided, not the input.
 * Outside the sanitizer builds each s1360 call may grow the server's data
 * by 1 GiB, so a runaway allocation ends at once.  Both limits are the
 * call's own, not the server's history (issue 35: which fits a server
 * serves depends on the threads and the engine).  A runaway meets the CPU
 * deadline or the memory cap first depending on the load, so both read
 * alike ("did not finish ... within 1 GiB"): results.csv must not depend on
 * the load.  A server that ends otherwise (killed by a signal from outside,
 * an unexpected exit status) fails the fit saying so, and a fresh server
 * serves the next fit.  A fork per fit cost 0.6 ms of system time (a
 * 500-curve run spent 2 of its 4 minutes in fork); a round trip costs
 * microseconds.
 *
 * Parameter: max_step, s1360's "maximal step length" amax; 0 (the default)
 * leaves the step to SISL (its manual: the longest side of the curve's
 * bounding box).  The installed headers carry no documentation; measured on
 * liu2002_ex1 (d 1, tol 1e-3): amax 0, 1, 3, 10 give 49 vertices, 0.5 gives
 * 43, 0.1 gives 85, 1e-4 gives 7375 (so amax <= tol is not ignored).
 */
#include "methods/method.h"
#include "methods/sisl/proto.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

enum { SISL_OUT_DEG = 3 };

static const ob_param sisl_params[] = {
    {"max_step", 0.0,
     "s1360's maximal step length amax; 0 (default) = SISL's own choice, which its manual "
     "gives as the longest side of the curve's bounding box", 0, 1e12, 0},
    {"timeout", 20.0,
     "CPU seconds one s1360 call may take, counted in whole seconds rounded up (it runs in a child "
     "process, ended past this; the fit then fails): s1360 loops without end on some inputs.  Our "
     "choice; 0.1..3600", 0.1, 3600, 0},
    {"wall_timeout", 0.0,
     "wall-clock seconds one s1360 call may take; 0 (default) = 3 x (timeout + 1), which a server "
     "that gets at least a third of a CPU never reaches before its CPU deadline.  Past it the "
     "server is stopped and the job's status is timeout (the machine was too loaded), not fail.  "
     "Our choice; 0..36000", 0, 36000, 0},
};

#if !defined(__SANITIZE_ADDRESS__)
#define SERVER_MEMORY_NOTE "1 GiB of data, without crashing"
#else
#define SERVER_MEMORY_NOTE "its memory, without crashing"
#endif

/* A test hook's seconds (docs/contributing.md "Testing"): the variable's
 * value when it is a number in (0, 1e6], else 0.  OFFBENCH_TEST_SISL_SLEEP:
 * the server sleeps that long before each s1360 call (a server that gets no
 * CPU); OFFBENCH_TEST_SISL_SPIN: it burns that much CPU time (a runaway). */
static double test_hook(const char *name)
{
    const char *v = getenv(name);
    char *end;
    const double s = v && *v ? strtod(v, &end) : 0.0;
    return v && *v && !*end && s > 0 && s <= 1e6 ? s : 0.0;
}

/* The fit's status after the server ended during the call (wait status
 * ws), the message in msg.  cpu: the call's CPU deadline, by_budget: 1 when
 * that was the job's remaining --job-timeout budget. */
static ob_fit_status server_ended(int ws, double cpu, int by_budget, char *msg, size_t msglen)
{
    const int deadline = ws != -1 && WIFEXITED(ws) && WEXITSTATUS(ws) == 3;  /* server.c: SIGXCPU */
    const int sig = ws != -1 && WIFSIGNALED(ws) ? WTERMSIG(ws) : 0;
    if (deadline && by_budget) {
        ob_method_msg(msg, msglen, "job timeout: SISL s1360 used the job's remaining %.3g s of CPU time "
                      "(--job-timeout; stopped)", cpu);
        return OB_FIT_TIMEOUT;
    }
    if (deadline || sig == SIGSEGV || sig == SIGBUS || sig == SIGABRT) {
        /* a runaway meets the deadline or the memory cap first by the load: one message */
        ob_method_msg(msg, msglen, "SISL s1360 did not finish in %g s within %s (stopped; it loops on some inputs)",
                      cpu, SERVER_MEMORY_NOTE);
        return OB_FIT_FAIL;
    }
    char how[80];
    ob_sisl_describe_wait(ws, how, sizeof how);
    ob_method_msg(msg, msglen, "the SISL server died during s1360: %s; a fresh one serves the next fit", how);
    return OB_FIT_FAIL;
}

/* Purpose: s1360 on q in this thread's server, with its limits (the file's
 *          comment).  Returns OB_FIT_OK with *r filled (free r->et,
 *          r->ecoef), else the fit's status with the reason in msg. */
static ob_fit_status guarded_s1360(sisl_request *q, const ob_fit_args *a, sisl_result *r, char *msg, size_t msglen)
{
    const double timeout = a->par[1], wall_par = a->par[2];
    const double budget = ob_fit_budget_ns() > 0.0 ? 1e-9 * ob_fit_budget_ns() : INFINITY;
    const int by_budget = budget < timeout;
    q->timeout = by_budget ? budget : timeout;
    q->test_sleep = test_hook("OFFBENCH_TEST_SISL_SLEEP");
    q->test_spin = test_hook("OFFBENCH_TEST_SISL_SPIN");
    const double wall = wall_par > 0.0 ? wall_par : 3.0 * (q->timeout + 1.0);  /* why: the file's comment */
    int ws = -1;
    const ob_sisl_outcome o = ob_sisl_call(q, wall, r, &ws, msg, msglen);
    if (o == OB_SISL_WALL) {
        /* short: the driver keeps 100 characters of it before the piece's place */
        ob_method_msg(msg, msglen, "SISL s1360 stopped at its wall-clock cap of %g s (sisl.wall_timeout; CPU "
                      "deadline %g s)", wall, q->timeout);
        return OB_FIT_TIMEOUT;
    }
    if (o == OB_SISL_DIED)
        return server_ended(ws, q->timeout, by_budget, msg, msglen);
    if (o != OB_SISL_OK)
        return OB_FIT_FAIL;
    if (r->stat <= OB_SISL_BAD_REQUEST) {
        ob_method_msg(msg, msglen, "the SISL server refused the request: bad %s",
                      ob_sisl_field_name(OB_SISL_BAD_REQUEST - r->stat));
        return OB_FIT_FAIL;
    }
    return OB_FIT_OK;
}

/* Bezier segment of span [et[j], et[j+1]] of a non-rational B-spline of degree
 * p (coefficients ecoef, 2 per vertex): control point k is the blossom with
 * p-k arguments a = et[j] and k arguments b = et[j+1] (de Boor). */
static void span_bezier(const double *et, const double *ecoef, int p, int j, ob_bez *out)
{
    const double a = et[j], b = et[j + 1];
    out->deg = p;
    out->rational = 0;
    for (int k = 0; k <= p; k++) {
        double q[OB_MAX_DEG + 1][2];
        for (int i = 0; i <= p; i++) {
            q[i][0] = ecoef[2 * (j - p + i)];
            q[i][1] = ecoef[2 * (j - p + i) + 1];
        }
        for (int r = 1; r <= p; r++) {
            const double x = r <= p - k ? a : b;
            for (int i = p; i >= r; i--) {
                const int idx = j - p + i;
                const double alpha = (x - et[idx]) / (et[idx + p + 1 - r] - et[idx]);
                q[i][0] = (1.0 - alpha) * q[i - 1][0] + alpha * q[i][0];
                q[i][1] = (1.0 - alpha) * q[i - 1][1] + alpha * q[i][1];
            }
        }
        out->h[k][0] = q[p][0];
        out->h[k][1] = q[p][1];
        out->h[k][2] = 1.0;
    }
}

static ob_fit_status sisl_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                              char *msg, size_t msglen)
{
    (void)work;
    const double timeout = a->par[1], wall_par = a->par[2];
    if (!(timeout >= 0.1 && timeout <= 3600) || !(a->par[0] >= 0.0 && a->par[0] <= 1e12) ||
        !(wall_par >= 0.0 && wall_par <= 36000)) {
        /* --param refuses these; a caller that bypasses it gets no silent substitute */
        ob_method_msg(msg, msglen, "timeout %g (0.1..3600), max_step %g (0..1e12) or wall_timeout %g (0..36000) "
                      "out of range", timeout, a->par[0], wall_par);
        return OB_FIT_FAIL;
    }
    sisl_request q;
    memset(&q, 0, sizeof q);
    q.magic = OB_SISL_REQ_MAGIC;
    q.n = base->deg;
    q.rational = base->rational;
    q.d = a->d;
    q.tol = a->tol;
    q.amax = a->par[0];
    const int dim = base->rational ? 3 : 2;
    for (int i = 0; i <= q.n; i++)
        for (int c = 0; c < dim; c++)
            q.coef[dim * i + c] = base->h[i][c];  /* polynomial: w = 1, h = (x, y) */
    sisl_result res;
    const ob_fit_status gs = guarded_s1360(&q, a, &res, msg, msglen);
    if (gs != OB_FIT_OK)
        return gs;
    const sisl_result *rc = &res;
    if (res.stat < 0 || !res.et) {
        ob_method_msg(msg, msglen, "SISL s1360 failed with status %d", res.stat);
        free(res.et);
        free(res.ecoef);
        return OB_FIT_FAIL;
    }

    ob_fit_status st = OB_FIT_OK;
    const int p = rc->ik - 1, nv = rc->in;
    const double *et = rc->et;
    if (p != SISL_OUT_DEG || rc->idim != 2 || rc->ikind != 1 || nv < rc->ik) {
        ob_method_msg(msg, msglen, "SISL s1360 returned order %d, kind %d, dimension %d, %d "
                      "vertices: not a polynomial cubic B-spline", rc->ik, rc->ikind, rc->idim, nv);
        st = OB_FIT_FAIL;
        goto done;
    }
    const double lo = et[p], hi = et[nv];
    if (!(fabs(lo) <= 1e-12 && fabs(hi - 1.0) <= 1e-12)) {
        ob_method_msg(msg, msglen, "SISL s1360 returned the domain [%.17g, %.17g], not the "
                      "base's [0, 1]", lo, hi);
        st = OB_FIT_FAIL;
        goto done;
    }
    int spans = 0;
    for (int j = p; j < nv; j++)
        spans += et[j] < et[j + 1];
    if (spans > OB_SPLIT_PIECES) {
        ob_method_msg(msg, msglen, "SISL's offset has %d spans, more than %d pieces", spans,
                      OB_SPLIT_PIECES);
        st = OB_FIT_RETRY_SMALLER;
        goto done;
    }
    out->n = 0;
    out->ctrl_points = nv;
    out->t[0] = 0.0;
    for (int j = p; j < nv; j++) {
        if (!(et[j] < et[j + 1]))
            continue;
        span_bezier(et, rc->ecoef, p, j, &out->seg[out->n]);
        out->n++;
        out->t[out->n] = out->n == spans ? 1.0 : et[j + 1];
    }

done:
    free(res.et);
    free(res.ecoef);
    return st;
}

const ob_method ob_method_sisl = {
    .name = "sisl",
    .version = 1,
    .citation = "SINTEF SISL 4.6, s1360 (offset of a B-spline curve within a tolerance)",
    .continuity = "G1",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_ORIENTED | OB_CAP_TOL_DRIVEN,
    .max_turn = 0.0,
    .out_degree = ob_degree_three, /* SISL_OUT_DEG */
    .cost_ms = 4.48,
    .work_size = 0,
    .params = sisl_params,
    .nparams = 3,
    .fit_uses_tol = ob_fit_uses_tol_always, /* s1360 offsets to tol */
    .fit = sisl_fit,
};
