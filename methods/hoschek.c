/*
 * hoschek.c - Hoschek 1988, "Spline approximation of offset curves", CAGD
 * 5(1) 33-40 (the kind of method behind the "Lst" column of Ahn 2023, Tables 1-2,
 * which is Lee et al.'s extension of Hoschek-Wissel).  The paper itself was
 * not at hand; this follows its usual description (Ahn 2023, §5; Elber, Lee
 * & Kim 1997, IEEE CG&A 17(3)): sample the exact offset, fit by least squares
 * with the end points fixed, iterate parameter correction.
 *
 * The exact offset O(t) = C(t) + d N(t) is sampled at M points Q_j = O(t_j),
 * t_j = j/(M-1) (uniform in the base's parameter, both ends included).  A
 * Bézier A of degree m with A(0) = Q_0 and A(1) = Q_{M-1} (end points fixed to
 * the offset's) is fitted to the interior samples by least squares,
 * min sum_j |A(u_j) - Q_j|^2, starting from u_j = t_j.  Then the parameters
 * are corrected (Hoschek's intrinsic parameterization): each Q_j is projected
 * onto the current A (Newton on (A(u) - Q_j) . A'(u) = 0 from the previous
 * u_j, safeguarded so that |A(u) - Q_j| never grows, u kept in [0,1]), and A
 * is fitted again; repeated `iterations` times.  Since each projection and each
 * refit can only lower sum_j |A(u_j) - Q_j|^2, the residual is non-increasing.
 *
 * Readings taken (parameters):
 *  - samples M: default 0 = 8 (m + 1), i.e. 8 samples per coefficient of a
 *    coordinate, the oversampling of Numerical Recipes' least-squares fits
 *    (NPFAC = 8); 32 for a cubic.
 *  - iterations: parameter corrections, default 20.  The correction converges
 *    linearly and slowly (on the halves of liu2002_ex1 the sum of squares
 *    still falls by 1-3 % per correction after 20 of them, and keeps falling
 *    for hundreds), so any count is a cost compromise; 20 is where the first
 *    fast phase is over on the test curves (it takes 2-5 corrections on
 *    well-parameterized pieces) at about 20x the cost of one fit.
 *  - tangents: 0 (default, that description: end points fixed); 1 also fixes the
 *    end tangent directions to the offset's (A'(0) = alpha T_0,
 *    A'(1) = beta T_1, alpha, beta >= 0 (a negative least-squares value is
 *    set to 0 and the rest refitted): G1 Hermite ends), which needs m >= 3.
 *  - degree: 0 = the base's degree (a cubic for a cubic base, or degree n).
 * The output is polynomial; rational bases are sampled like any other.  The
 * parameter correction decouples A's parameter from the base's, so A is not
 * in the base's parameter (no OB_CAP_SAME_PARAM: measure it with the normal
 * or Hausdorff metric).  Output: one Bézier segment per piece (C0 joins);
 * a B-spline with interior knots, as in Hoschek-Wissel and Lee's "Lst",
 * would count fewer control points.
 */
#include "methods/method.h"

#include "methods/core/bernstein.h"

#include <math.h>
#include <string.h>

#include "methods/common/givens_ls.h"

enum { HP_SAMPLES, HP_ITER, HP_TANGENTS, HP_DEGREE, HP_COUNT };

enum {
    HOSCHEK_MAX_SAMPLES = 4096,
    HOSCHEK_MAX_ITER = 1000,
    HOSCHEK_MAX_UNK = 2 * (OB_MAX_DEG - 1),
};

typedef struct {
    double q[HOSCHEK_MAX_SAMPLES][2];  /* offset samples */
    double u[HOSCHEK_MAX_SAMPLES];     /* their parameters on the fit */
    double gls[HOSCHEK_MAX_UNK * (HOSCHEK_MAX_UNK + 1) + HOSCHEK_MAX_UNK];
    double x[HOSCHEK_MAX_UNK], row[HOSCHEK_MAX_UNK + 1];
} hoschek_work;

static const ob_param hoschek_params[HP_COUNT] = {
    {"samples", 0,
     "offset samples M (both ends included), uniform in the base parameter; 0 = 8 (m + 1) for "
     "output degree m (8 per coefficient, the oversampling NPFAC = 8 of Numerical Recipes' fits)", 0, HOSCHEK_MAX_SAMPLES, 1},
    {"iterations", 20,
     "parameter corrections (projection of every sample onto the fit, then a new fit); 0 = plain "
     "least squares in the base parameter. Default 20: a cost compromise, the correction "
     "converges linearly and slowly (see hoschek.c)", 0, HOSCHEK_MAX_ITER, 1},
    {"tangents", 0,
     "0: only the end points are fixed to the offset's (Hoschek 1988 as usually described); 1: also the end tangent "
     "directions (G1 ends, needs degree >= 3)", 0, 1, 1},
    {"degree", 0, "output degree; 0 = the base's degree", 0, OB_MAX_DEG, 1},
};

static double dist2(const double a[2], const double b[2])
{
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]);
}

/* Project Q onto A from the parameter u: Newton on (A(u) - Q) . A'(u) = 0
 * (Gauss-Newton where the Hessian term is not positive), steps halved until
 * |A(u) - Q| does not grow, u clamped to [0,1]. */
static double project(const ob_bez *A, const double Q[2], double u)
{
    double o[3][2];
    ob_bez_eval(A, u, 2, o);
    double f = dist2(o[0], Q);
    for (int it = 0; it < 30; it++) {
        const double r[2] = {o[0][0] - Q[0], o[0][1] - Q[1]};
        const double g = r[0] * o[1][0] + r[1] * o[1][1];
        const double a2 = o[1][0] * o[1][0] + o[1][1] * o[1][1];
        double h = a2 + r[0] * o[2][0] + r[1] * o[2][1];
        if (!(h > 0.0))
            h = a2;
        if (!(h > 0.0))
            break;
        double du = -g / h, un = u, fn = f;
        double on[3][2];
        int moved = 0;
        for (int half = 0; half < 30; half++, du *= 0.5) {
            un = fmin(1.0, fmax(0.0, u + du));
            if (un == u)
                break;
            ob_bez_eval(A, un, 2, on);
            fn = dist2(on[0], Q);
            if (fn <= f) {
                moved = 1;
                break;
            }
        }
        if (!moved)
            break;
        const double step = fabs(un - u);
        u = un;
        f = fn;
        memcpy(o, on, sizeof o);
        if (step < 1e-15)
            break;
    }
    return u;
}

/* What one fit reads of its parameters: output degree m, M samples,
 * corrections, fixed end tangents; the free control points (nfree per
 * coordinate) and the unknowns (nunk). */
typedef struct {
    int m, M, iters, tangents, nfree, nunk;
} hoschek_cfg;

/* The parameters checked and read into h.  OB_FIT_OK, or OB_FIT_SKIP with the reason
 * in msg. */
static ob_fit_status hoschek_read(const ob_bez *base, const ob_fit_args *a, hoschek_cfg *h, char *msg, size_t msglen)
{
    const double pd = a->par[HP_DEGREE], ps = a->par[HP_SAMPLES], pi = a->par[HP_ITER];
    const int m = ob_degree_or_param(base->deg, pd);
    const int tangents = a->par[HP_TANGENTS] != 0.0;
    if (!(pd < OB_MAX_DEG + 0.5) || m < 1 || m > OB_MAX_DEG) {
        ob_method_msg(msg, msglen, "output degree out of range 1..%d", OB_MAX_DEG);
        return OB_FIT_SKIP;
    }
    if (tangents && m < 3) {
        ob_method_msg(msg, msglen, "fixed end tangents need degree >= 3 (degree %d)", m);
        return OB_FIT_SKIP;
    }
    if (!(ps >= 0.0 && ps <= HOSCHEK_MAX_SAMPLES) || !(pi >= 0.0 && pi <= HOSCHEK_MAX_ITER)) {
        ob_method_msg(msg, msglen, "parameters out of range: samples 0..%d, iterations 0..%d",
                      HOSCHEK_MAX_SAMPLES, HOSCHEK_MAX_ITER);
        return OB_FIT_SKIP;
    }
    const int M = ps >= 0.5 ? (int)lround(ps) : 8 * (m + 1);
    /* unknowns: P_1..P_{m-1} (x then y), or alpha, beta, P_2..P_{m-2} */
    const int nfree = tangents ? m - 3 : m - 1;
    if (M - 2 < (tangents ? nfree + 1 : nfree) || M < 2) {
        ob_method_msg(msg, msglen, "%d samples are too few for degree %d", M, m);
        return OB_FIT_SKIP;
    }
    h->m = m;
    h->M = M;
    h->iters = (int)lround(pi);
    h->tangents = tangents;
    h->nfree = nfree;
    h->nunk = 2 * nfree + (tangents ? 2 : 0);
    return OB_FIT_OK;
}

/* The offset's unit tangent directions T0, T1 at the ends of base (C' (1 - d
 * kappa), direction only).  OB_FIT_OK, or OB_FIT_FAIL where there is none. */
static ob_fit_status hoschek_end_tangents(const ob_bez *base, double d, double T0[2], double T1[2], char *msg,
                                          size_t msglen)
{
    for (int e = 0; e < 2; e++) {
        double o[2][2];
        ob_bez_eval(base, e, 1, o);
        const double s = hypot(o[1][0], o[1][1]), g = 1.0 - d * ob_bez_curvature(base, e);
        if (!(s > 0.0) || g == 0.0) {
            ob_method_msg(msg, msglen, "no offset tangent at t = %d (C' = 0 or 1 - d kappa = 0)", e);
            return OB_FIT_FAIL;
        }
        double *T = e ? T1 : T0;
        T[0] = (g > 0 ? 1.0 : -1.0) * o[1][0] / s;
        T[1] = (g > 0 ? 1.0 : -1.0) * o[1][1] / s;
    }
    return OB_FIT_OK;
}

/* The least-squares system of the interior samples at their parameters
 * W->u, ends fixed to Q0, Q1 (and with tangents: P_1 = Q0 + alpha T0,
 * P_{m-1} = Q1 - beta T1; fixa / fixb: alpha / beta held at 0), into g. */
static void hoschek_system(const hoschek_cfg *h, hoschek_work *W, const double T0[2], const double T1[2],
                           int fixa, int fixb, ob_gls *g)
{
    const int m = h->m, M = h->M, nfree = h->nfree, nunk = h->nunk;
    const double *Q0 = W->q[0], *Q1 = W->q[M - 1];
    ob_gls_init(g, nunk, W->gls);
    for (int j = 1; j < M - 1; j++) {
        double B[OB_MAX_DEG + 1];
        ob_bern_basis(m, W->u[j], B);
        for (int c = 0; c < 2; c++) {
            double *row = W->row, rhs = W->q[j][c] - B[0] * Q0[c] - B[m] * Q1[c];
            memset(row, 0, (size_t)nunk * sizeof *row);
            if (h->tangents) {
                /* P_1 = Q0 + alpha T0, P_{m-1} = Q1 - beta T1 */
                rhs -= B[1] * Q0[c] + B[m - 1] * Q1[c];
                row[2 * nfree] = fixa ? 0.0 : B[1] * T0[c];
                row[2 * nfree + 1] = fixb ? 0.0 : -B[m - 1] * T1[c];
                for (int i = 0; i < nfree; i++)
                    row[c * nfree + i] = B[i + 2];
            } else {
                for (int i = 0; i < nfree; i++)
                    row[c * nfree + i] = B[i + 1];
            }
            ob_gls_add(g, row, rhs, 1.0);
        }
    }
    for (int e = 0; e < 2; e++)
        if (e ? fixb : fixa) {
            double *row = W->row;
            memset(row, 0, (size_t)nunk * sizeof *row);
            row[2 * nfree + e] = 1.0;
            ob_gls_add(g, row, 0.0, 1.0);
        }
}

/* One least-squares fit at the parameters W->u, into W->x: with fixed
 * tangents, a negative alpha or beta (a reversed end tangent) is set to 0 and
 * the rest fitted again (at most twice).  0, or -1 (singular system). */
static int hoschek_solve(const hoschek_cfg *h, hoschek_work *W, const double T0[2], const double T1[2])
{
    const int nfree = h->nfree;
    int fixa = 0, fixb = 0, solved = 0;
    for (;;) {
        ob_gls g;
        hoschek_system(h, W, T0, T1, fixa, fixb, &g);
        if (h->nunk > 0 && ob_gls_solve(&g, W->x, 1e-13) != 0)
            return -1;
        if (h->tangents && solved++ < 2 &&
            ((W->x[2 * nfree] < 0.0 && !fixa) || (W->x[2 * nfree + 1] < 0.0 && !fixb))) {
            fixa |= W->x[2 * nfree] < 0.0;
            fixb |= W->x[2 * nfree + 1] < 0.0;
            continue;
        }
        return 0;
    }
}

/* The control points of A from the solution W->x and the fixed ends. */
static void hoschek_curve(const hoschek_cfg *h, const hoschek_work *W, const double T0[2], const double T1[2],
                          ob_bez *A)
{
    const int m = h->m, nfree = h->nfree;
    const double *Q0 = W->q[0], *Q1 = W->q[h->M - 1];
    for (int c = 0; c < 2; c++) {
        A->h[0][c] = Q0[c];
        A->h[m][c] = Q1[c];
        if (h->tangents) {
            A->h[1][c] = Q0[c] + W->x[2 * nfree] * T0[c];
            A->h[m - 1][c] = Q1[c] - W->x[2 * nfree + 1] * T1[c];
            for (int i = 0; i < nfree; i++)
                A->h[i + 2][c] = W->x[c * nfree + i];
        } else {
            for (int i = 0; i < nfree; i++)
                A->h[i + 1][c] = W->x[c * nfree + i];
        }
    }
    for (int i = 0; i <= m; i++)
        A->h[i][2] = 1.0;
}

static ob_fit_status hoschek_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                 char *msg, size_t msglen)
{
    hoschek_work *W = work;
    const double d = a->d;
    hoschek_cfg h;
    ob_fit_status st = hoschek_read(base, a, &h, msg, msglen);
    if (st != OB_FIT_OK)
        return st;
    const int M = h.M;
    for (int j = 0; j < M; j++) {
        const double t = j == M - 1 ? 1.0 : (double)j / (M - 1);
        ob_bez_offset_point(base, t, d, W->q[j]);
        W->u[j] = t;
    }
    double T0[2] = {0.0, 0.0}, T1[2] = {0.0, 0.0};
    if (h.tangents && (st = hoschek_end_tangents(base, d, T0, T1, msg, msglen)) != OB_FIT_OK)
        return st;
    ob_bez A;
    memset(&A, 0, sizeof A);
    A.deg = h.m;
    for (int it = 0; it <= h.iters; it++) {
        if (it > 0)
            for (int j = 1; j < M - 1; j++)
                W->u[j] = project(&A, W->q[j], W->u[j]);
        if (hoschek_solve(&h, W, T0, T1) != 0) {
            if (it == 0) {
                ob_method_msg(msg, msglen, "singular least-squares system (%d samples, degree %d)", M, h.m);
                return OB_FIT_FAIL;
            }
            break;  /* keep the previous fit */
        }
        hoschek_curve(&h, W, T0, T1, &A);
    }
    ob_fit_single(out, &A);
    return OB_FIT_OK;
}

/* The degree parameter's, else the base's. */
static int hoschek_degree(int n, int rational_in, const double *par)
{
    (void)rational_in;
    return ob_degree_or_param(n, par[HP_DEGREE]);
}

const ob_method ob_method_hoschek = {
    .name = "hoschek",
    .version = 1,
    .citation = "Hoschek 1988, Spline approximation of offset curves (CAGD 5:33-40)",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN,
    .max_turn = 0.0,
    .out_degree = hoschek_degree,
    .cost_ms = 9.03,
    .work_size = sizeof(hoschek_work),
    .params = hoschek_params,
    .nparams = HP_COUNT,
    .fit = hoschek_fit,
};
