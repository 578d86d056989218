/*
 * zhao.c - Zhao & Zhou 2017, "A Novel Method of Offset Approximation along the
 * Normal Direction with High Precision" (Algorithms 10(3), MDPI, 2017), sections 2-3:
 * polynomial ("zhao") or rational ("zhao-rational") approximation R(A,t)
 * of degree n of the offset C_r(t) = C(t) + r N(t) whose error along the
 * normal, e(t) = (R(t) - C_r(t)) . N(t), is driven towards equioscillation.
 *
 * Equation (2): at each node t_i, R(t_i) = C(t_i) + (r +- e) N(t_i), split into
 *   [R(t_i) - C(t_i)] x N(t_i) = 0            (direction)
 *   [R(t_i) - C(t_i)] . N(t_i) = r +- e       (magnitude),
 * multiplied through by the denominator q(t) = 1 + b_1 t + ... + b_n t^n so
 * that both are linear in the coefficients once e is fixed (the paper's
 * matrices A, Abar).  Unknowns: 2n+2 numerator coefficients, plus n
 * denominator coefficients for the rational form (3n+2), plus e.  Two
 * equations per node, so the paper's count of nodes is k = (3n+2)/2 (n even)
 * or (3n+3)/2 (n odd), i.e. k = floor((3n+3)/2); for the polynomial form the
 * same count gives k = floor((2n+3)/2) = n+1 (2n+2 equations: square in the
 * coefficients once e is fixed, one short of the 2n+3 unknowns with e).
 *
 * Readings taken (parameters where the paper leaves a choice):
 *  - The accelerated algorithm of section 3 (fixed t_i; e = the average
 *    |error| at the t_i; the value at t_i replaced by C_r(t_i) + sigma_i e N,
 *    sigma_i the sign of the current error there; first solve with e = 0).
 *    It is the loop of Press et al.'s program ratlsq (Numerical Recipes 3rd
 *    ed. section 5.13, pp. 247-250, the paper's [17]), which the paper says
 *    it follows for the initial t_i.  With exactly k nodes the accelerated
 *    loop is void (the fit interpolates its targets, so the error at the
 *    nodes, hence e, stays 0), so ratlsq's sampling is taken as well: NPFAC = 8
 *    nodes per coefficient count, i.e. npt = 8k.  This matches the paper's
 *    "96 sample points" for the septic (n = 7, k = 12) and "less than
 *    4(3n+3)" sample points.  The 2 npt equations exceed the unknowns, so
 *    they are solved in the least-squares sense (ratlsq uses an SVD; here a
 *    Givens QR, which detects rank deficiency: then OB_FIT_FAIL).
 *  - The nodes are ratlsq's: t_j = sin^2(pi/2 j/(npt-1)), j = 0..npt-1 (the
 *    second half computed as 1 - sin^2(...) of the mirrored index, as in
 *    ratlsq), i.e. the Chebyshev-Gauss-Lobatto points (extrema of
 *    T_{npt-1}, both ends included) mapped to [0,1].
 *  - ratlsq weights each equation by the |error| of the previous solve at its
 *    node (the paper's steps do not mention weights): parameter `weighted`,
 *    default 1 (the program the paper follows); both equations of a node get
 *    its weight.  Unweighted, the later iterates rarely beat the first on our
 *    test curves (the paper reports an improvement, 0.0428 to 0.0363);
 *    weighted, they do on most rational fits.
 *  - Iterations: the paper says "iterate to convergence" and shows the 1st,
 *    2nd (septic) and 4th (quintic) iterates; ratlsq runs MAXIT = 5 and keeps
 *    the iterate with the smallest maximum error at the nodes.  Default 5,
 *    best kept.  Iteration 1 is the plain least-squares fit (e = 0).  The loop
 *    stops early when the fit is exact to round-off.
 *  - The paper's solutions must have 1 + b_1 t + ... + b_n t^n != 0 on [0,1];
 *    the linearized least squares (eq. 2 multiplied by the denominator) does
 *    not ensure it, and on gentle curves it often returns a denominator with
 *    a root in [0,1] (a near pole-zero pair).  Such an iterate is never
 *    returned, but, as in ratlsq, its errors at the nodes still drive the next
 *    iterate.  No valid iterate at all: OB_FIT_RETRY_SMALLER, so the driver splits
 *    the piece (parameter on_pole = 0: OB_FIT_FAIL instead).  A singular rational
 *    system on the first solve (the denominator undetermined: on small pieces
 *    the offset is nearly polynomial): the polynomial member of the family
 *    (denominator 1), which the paper counts as the degenerate rational case.
 *    A singular polynomial system: OB_FIT_FAIL on the first solve; on later solves
 *    the loop ends (best valid iterate kept).
 *  - The normalization q(0) = 1 makes the least-squares solution, hence the
 *    rational result, depend on the direction of the parameter (the reversed
 *    curve gives a different curve); the polynomial result does not.
 *  - Degree: the base's (parameter `degree`, 0 = the base's; "our method can
 *    approximate the offset with an arbitrary degree").
 * Implementation: the unknowns are the Bernstein coefficients of numerator and
 * denominator, an exact linear change of variables of the paper's power
 * coefficients with the same normalization (the denominator's first Bernstein
 * coefficient is q(0) = 1 = the power form's constant term), so the least-
 * squares solution is the same curve; the output needs no basis conversion
 * and is the homogeneous Bézier (P_i, beta_i).  Coordinates are taken relative
 * to the centroid of the base's control points (the equations are translation
 * invariant; this only avoids cancellation).  A rational iterate is valid when
 * its denominator is proved positive on [0,1] (its Bernstein coefficients,
 * refined by subdivision until all are positive); its weights may still be
 * negative.
 * The fit is in the base's parameter: R(t_i) lies on the normal line at C(t_i),
 * so the radial and bound metrics apply (OB_CAP_SAME_PARAM).
 *
 * End points: the paper's R(A,t) does not interpolate the offset's end points,
 * and its construction does not share end points between pieces.  Every
 * unknown goes to the equioscillation conditions: "Suppose there are k
 * parameters, t_1 < t_2 < ... < t_k, which satisfy R(A,t_i) - C_r(t_i) =
 * +-e N(t_i)" and "the number of extrema k could be (3n+2)/2 or (3n+3)/2 to
 * obtain consistent equations" (section 3): no equation is left for the ends,
 * and in a Chebyshev (minimax) fit the error at the interval's ends is
 * typically +-e itself.  The accelerated algorithm the paper uses takes
 * ratlsq's nodes, both ends included, with targets C_r(t_i) + sigma_i e N(t_i):
 * again +-e at t = 0 and 1, not 0.  Where the paper subdivides (Table 1: C_1,
 * C_2), each half is fitted on its own ("The advantage is more obvious after
 * the curve is subdivided"), with nothing said about joining them.  So the
 * pieces of a subdivided zhao / zhao-rational approximation are about the
 * error apart at their joints (measured on liu2002_ex1: up to 1.3 tol for
 * zhao, 0.8 tol for zhao-rational), and the driver counts both ends of each
 * such joint (methods/driver/joints.h); the method does not claim any continuity
 * at joints ("none" below).  Forcing the ends to interpolate would be
 * another method than the paper's, so it is not done here.
 */
#include "methods/method.h"

#include "methods/core/bernstein.h"

#include <math.h>
#include <string.h>

#include "methods/common/givens_ls.h"

enum { ZP_ITER, ZP_NPFAC, ZP_WEIGHT, ZP_DEGREE, ZP_POLE, ZP_COUNT };

enum {
    ZHAO_MAX_NPFAC = 16,
    ZHAO_MAX_K = (3 * OB_MAX_DEG + 3) / 2,
    ZHAO_MAX_NODES = ZHAO_MAX_NPFAC * ZHAO_MAX_K,
    ZHAO_MAX_UNK = 3 * OB_MAX_DEG + 2,
    ZHAO_MAX_ITER = 100,
};

typedef struct {
    double t[ZHAO_MAX_NODES];
    double c[ZHAO_MAX_NODES][2];   /* C(t_j) relative to the origin v */
    double nn[ZHAO_MAX_NODES][2];  /* N(t_j) */
    double e[ZHAO_MAX_NODES];      /* error along the normal at t_j */
    double gls[ZHAO_MAX_UNK * (ZHAO_MAX_UNK + 1) + ZHAO_MAX_UNK];
    double x[ZHAO_MAX_UNK], best[ZHAO_MAX_UNK], row[ZHAO_MAX_UNK + 1];
} zhao_work;

static const ob_param zhao_params[ZP_COUNT] = {
    {"iterations", 5,
     "solves of eq. (2) in the accelerated algorithm (the first with e = 0); the iterate with the "
     "smallest maximum error at the nodes is kept. Default 5 = MAXIT of Press et al.'s ratlsq, "
     "the program the paper follows (the paper: 'iterate to convergence'; it shows iterations 1, 2, 4)", 1, ZHAO_MAX_ITER, 1},
    {"npfac", 8,
     "node multiplier: npt = npfac * k nodes, k = floor((3n+3)/2) (rational) or n+1 "
     "(polynomial). Default 8 = NPFAC of ratlsq; gives the paper's 96 sample points for its septic; "
     "1..16; 1 = exactly k nodes (the fit then interpolates its targets where the system is square, "
     "so e stays 0)", 1, ZHAO_MAX_NPFAC, 1},
    {"weighted", 1,
     "1: weight the equations of each node by the |error| there from the previous solve, as "
     "ratlsq does (default: the program the paper follows); 0: unweighted (the paper's steps as "
     "written do not mention weights)", 0, 1, 1},
    {"degree", 0,
     "output degree; 0 = the base's degree (the paper's examples; 'an arbitrary degree' is allowed)", 0, OB_MAX_DEG, 1},
    {"on_pole", 1,
     "no iterate with a denominator positive on [0,1] (zhao-rational): 1 = ask the driver to split "
     "the piece (OB_FIT_RETRY_SMALLER, as if the error were too large; default: the paper requires a "
     "pole-free solution and says nothing of what to do without one, and a smaller piece usually "
     "has one), 0 = fail", 0, 1, 1},
};

/* 1 if the Bernstein polynomial b (degree n, b[0] > 0) is positive on [0,1]:
 * all coefficients positive, else subdivide; an end value <= 0, or no proof
 * after 40 halvings (a near-double root), counts as not positive. */
static int bern_positive(const double *b, int n, int depth)
{
    int all = 1;
    for (int i = 0; i <= n; i++)
        all &= b[i] > 0.0;
    if (all)
        return 1;
    if (!(b[0] > 0.0) || !(b[n] > 0.0) || depth >= 40)
        return 0;
    double l[OB_MAX_DEG + 1], r[OB_MAX_DEG + 1], w[OB_MAX_DEG + 1];
    memcpy(w, b, (size_t)(n + 1) * sizeof *w);
    for (int k = 0; k <= n; k++) {
        l[k] = w[0];
        r[n - k] = w[n - k];
        for (int i = 0; i < n - k; i++)
            w[i] = 0.5 * (w[i] + w[i + 1]);
    }
    return bern_positive(l, n, depth + 1) && bern_positive(r, n, depth + 1);
}

/* The unknowns x = (px_0..px_n, py_0..py_n, beta_1..beta_n) (the betas only
 * when rational) as Bernstein coefficients: P_i and beta_i (beta_0 = 1). */
static void unpack(const double *x, int n, int rational, int i, double P[2], double *beta)
{
    P[0] = x[i];
    P[1] = x[n + 1 + i];
    *beta = (!rational || i == 0) ? 1.0 : x[2 * n + 1 + i];
}

/* What one fit reads of its parameters: output degree n, solves, node
 * multiplier, weights; k nodes per npfac, npt nodes, nunk unknowns. */
typedef struct {
    int n, iters, npfac, weighted, rational;
    int k, npt, nunk;
} zhao_cfg;

/* The parameters checked and read into z.  OB_FIT_OK, or OB_FIT_SKIP with the reason
 * in msg. */
static ob_fit_status zhao_read(const ob_bez *base, const ob_fit_args *a, int rational, zhao_cfg *z, char *msg,
                               size_t msglen)
{
    const double pd = a->par[ZP_DEGREE], pi = a->par[ZP_ITER], pf = a->par[ZP_NPFAC];
    const int n = ob_degree_or_param(base->deg, pd);
    const int iters = (int)lround(pi), npfac = (int)lround(pf);
    const int weighted = a->par[ZP_WEIGHT] != 0.0;
    if (!(pd < OB_MAX_DEG + 0.5) || n < 1 || n > OB_MAX_DEG) {
        ob_method_msg(msg, msglen, "output degree %g out of range 1..%d", n < 1 ? pd : (double)n,
                      OB_MAX_DEG);
        return OB_FIT_SKIP;
    }
    if (!(pi >= 0.5 && pi <= ZHAO_MAX_ITER) || !(pf >= 0.5 && pf <= ZHAO_MAX_NPFAC)) {
        ob_method_msg(msg, msglen, "parameters out of range: iterations 1..%d, npfac 1..%d",
                      ZHAO_MAX_ITER, ZHAO_MAX_NPFAC);
        return OB_FIT_SKIP;
    }
    z->n = n;
    z->iters = iters;
    z->npfac = npfac;
    z->weighted = weighted;
    z->rational = rational;
    z->k = rational ? (3 * n + 3) / 2 : n + 1;
    z->npt = npfac * z->k;
    z->nunk = 2 * (n + 1) + (rational ? n : 0);
    return OB_FIT_OK;
}

/* The origin v: the centroid of the base's control points; returns the scale
 * of the exactness test, |r| + the larger side of their bounding box. */
static double zhao_origin(const ob_bez *base, double r, double v[2])
{
    double lo[2], hi[2];
    v[0] = v[1] = 0.0;
    for (int i = 0; i <= base->deg; i++) {
        double p[2];
        ob_bez_ctrl(base, i, p);
        v[0] += p[0] / (base->deg + 1);
        v[1] += p[1] / (base->deg + 1);
        for (int c = 0; c < 2; c++) {
            lo[c] = i ? fmin(lo[c], p[c]) : p[c];
            hi[c] = i ? fmax(hi[c], p[c]) : p[c];
        }
    }
    return fabs(r) + fmax(hi[0] - lo[0], hi[1] - lo[1]);
}

/* ratlsq's npt nodes (Chebyshev-Gauss-Lobatto points on [0,1]) with C - v
 * and N there, errors 0, into W.  OB_FIT_OK, or OB_FIT_FAIL where there is no
 * normal. */
static ob_fit_status zhao_nodes(const ob_bez *base, const double v[2], int npt, zhao_work *W, char *msg,
                                size_t msglen)
{
    for (int j = 0; j < npt; j++) {
        double t;
        if (2 * j < npt - 1) {
            const double s = sin(0.5 * OB_PI * j / (npt - 1));
            t = s * s;
        } else {
            const double s = sin(0.5 * OB_PI * (npt - 1 - j) / (npt - 1));
            t = 1.0 - s * s;
        }
        double o[1][2];
        W->t[j] = t;
        ob_bez_eval(base, t, 0, o);
        W->c[j][0] = o[0][0] - v[0];
        W->c[j][1] = o[0][1] - v[1];
        if (ob_bez_normal(base, t, W->nn[j]) != 0) {
            ob_method_msg(msg, msglen, "no normal at t = %.17g (point-like segment)", t);
            return OB_FIT_FAIL;
        }
        W->e[j] = 0.0;
    }
    return OB_FIT_OK;
}

/* Eq. (2) at every node for solve `it` (1: e = 0, unweighted), the targets
 * at r + sigma_j e with the signs and weights of the errors in W->e, added to
 * g. */
static void zhao_system(const zhao_cfg *z, zhao_work *W, double r, int it, double e, ob_gls *g)
{
    const int n = z->n, rational = z->rational;
    for (int j = 0; j < z->npt; j++) {
        double B[OB_MAX_DEG + 1];
        ob_bern_basis(n, W->t[j], B);
        const double nx = W->nn[j][0], ny = W->nn[j][1];
        const double cxn = W->c[j][0] * ny - W->c[j][1] * nx;
        const double sig = it == 1 ? 0.0 : (W->e[j] >= 0.0 ? 1.0 : -1.0);
        const double cdn = W->c[j][0] * nx + W->c[j][1] * ny + r + sig * e;
        const double w = (it > 1 && z->weighted) ? fabs(W->e[j]) : 1.0;
        const double q0 = rational ? B[0] : 1.0;
        /* direction: P x N - (q - 1) (C x N) = C x N  (times B_0 for rational) */
        double *row = W->row;
        for (int i = 0; i <= n; i++) {
            row[i] = B[i] * ny;
            row[n + 1 + i] = -B[i] * nx;
            if (rational && i > 0)
                row[2 * n + 1 + i] = -B[i] * cxn;
        }
        ob_gls_add(g, row, q0 * cxn, w);
        /* magnitude: P . N - (q - 1) (C . N + r + sigma e) = C . N + r + sigma e */
        for (int i = 0; i <= n; i++) {
            row[i] = B[i] * nx;
            row[n + 1 + i] = B[i] * ny;
            if (rational && i > 0)
                row[2 * n + 1 + i] = -B[i] * cdn;
        }
        ob_gls_add(g, row, q0 * cdn, w);
    }
}

/* 1 when the denominator of the rational iterate x is proved positive on
 * [0,1]. */
static int zhao_pole_free(const zhao_cfg *z, const double *x)
{
    const int n = z->n;
    double beta[OB_MAX_DEG + 1];
    beta[0] = 1.0;
    for (int i = 1; i <= n; i++)
        beta[i] = x[2 * n + 1 + i];
    return bern_positive(beta, n, 0);
}

/* The error along the normal of the iterate W->x at every node, into W->e;
 * returns the largest |error|, their sum in *sum. */
static double zhao_node_errors(const zhao_cfg *z, zhao_work *W, double r, double *sum)
{
    const int n = z->n;
    double dev = 0.0;
    *sum = 0.0;
    for (int j = 0; j < z->npt; j++) {
        double B[OB_MAX_DEG + 1], P[2] = {0.0, 0.0}, q = 0.0;
        ob_bern_basis(n, W->t[j], B);
        for (int i = 0; i <= n; i++) {
            double Pi[2], bi;
            unpack(W->x, n, z->rational, i, Pi, &bi);
            P[0] += B[i] * Pi[0];
            P[1] += B[i] * Pi[1];
            q += B[i] * bi;
        }
        const double ej = (P[0] / q - W->c[j][0]) * W->nn[j][0] +
                          (P[1] / q - W->c[j][1]) * W->nn[j][1] - r;
        W->e[j] = ej;
        dev = fmax(dev, fabs(ej));
        *sum += fabs(ej);
    }
    return dev;
}

/* The accelerated algorithm: up to z->iters solves, the valid iterate with
 * the smallest largest error at the nodes into W->best (that error in
 * *bestdev; INFINITY: none).  0, or -1 when the first system is singular. */
static int zhao_iterate(const zhao_cfg *z, zhao_work *W, double r, double scale, double *bestdev)
{
    double e = 0.0;
    *bestdev = INFINITY;
    for (int it = 1; it <= z->iters; it++) {
        ob_gls g;
        ob_gls_init(&g, z->nunk, W->gls);
        zhao_system(z, W, r, it, e, &g);
        if (ob_gls_solve(&g, W->x, 1e-13) != 0)
            return it == 1 ? -1 : 0;  /* later: the best valid iterate kept */
        const int valid = z->rational ? zhao_pole_free(z, W->x) : 1;
        double sum;
        const double dev = zhao_node_errors(z, W, r, &sum);
        if (!isfinite(dev))
            break;
        if (valid && dev < *bestdev) {
            *bestdev = dev;
            memcpy(W->best, W->x, (size_t)z->nunk * sizeof *W->x);
        }
        e = sum / z->npt;
        if (dev <= 1e-14 * scale)
            break;
    }
    return 0;
}

/* The iterate x as the output Bézier, back from the origin v. */
static void zhao_result(const zhao_cfg *z, const double *x, const double v[2], ob_fit *out)
{
    const int n = z->n;
    ob_bez res;
    memset(&res, 0, sizeof res);
    res.deg = n;
    for (int i = 0; i <= n; i++) {
        double P[2], bi;
        unpack(x, n, z->rational, i, P, &bi);
        res.h[i][0] = P[0] + bi * v[0];
        res.h[i][1] = P[1] + bi * v[1];
        res.h[i][2] = bi;
        if (bi != 1.0)
            res.rational = 1;
    }
    ob_fit_single(out, &res);
}

static ob_fit_status zhao_fit_any(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                  char *msg, size_t msglen, int rational)
{
    zhao_work *W = work;
    const double r = a->d;
    zhao_cfg z;
    ob_fit_status st = zhao_read(base, a, rational, &z, msg, msglen);
    if (st != OB_FIT_OK)
        return st;
    double v[2];
    const double scale = zhao_origin(base, r, v);
    st = zhao_nodes(base, v, z.npt, W, msg, msglen);
    if (st != OB_FIT_OK)
        return st;
    double bestdev;
    if (zhao_iterate(&z, W, r, scale, &bestdev) != 0) {
        if (rational) {
            /* the denominator is not determined: on a small piece the
             * offset is nearly polynomial and the beta columns become
             * dependent on the others.  The paper counts a polynomial as
             * the degenerate rational case (denominator 1): fit that. */
            return zhao_fit_any(base, a, work, out, msg, msglen, 0);
        }
        ob_method_msg(msg, msglen, "singular least-squares system for eq. (2) (%d nodes, "
                      "%d unknowns)", z.npt, z.nunk);
        return OB_FIT_FAIL;
    }
    if (!(bestdev < INFINITY)) {
        ob_method_msg(msg, msglen, "no iterate with a denominator positive on [0,1] (%d iterations)", z.iters);
        return a->par[ZP_POLE] != 0.0 ? OB_FIT_RETRY_SMALLER : OB_FIT_FAIL;
    }
    zhao_result(&z, W->best, v, out);
    return OB_FIT_OK;
}

static ob_fit_status zhao_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                              char *msg, size_t msglen)
{
    return zhao_fit_any(base, a, work, out, msg, msglen, 0);
}

static ob_fit_status zhao_rational_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                                       char *msg, size_t msglen)
{
    return zhao_fit_any(base, a, work, out, msg, msglen, 1);
}

/* The degree parameter's, else the base's. */
static int zhao_degree(int n, int rational_in, const double *par)
{
    (void)rational_in;
    return ob_degree_or_param(n, par[ZP_DEGREE]);
}

const ob_method ob_method_zhao = {
    .name = "zhao",
    .version = 1,
    .citation = "Zhao & Zhou 2017, A novel method of offset approximation along the normal direction (MDPI), polynomial",
    .continuity = "none",  /* the ends are not interpolated: pieces do not meet (see the top) */
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM,
    .max_turn = 0.0,
    .out_degree = zhao_degree,
    .cost_ms = 2.33,
    .work_size = sizeof(zhao_work),
    .params = zhao_params,
    .nparams = ZP_COUNT,
    .fit = zhao_fit,
};

const ob_method ob_method_zhao_rational = {
    .name = "zhao-rational",
    .version = 1,
    .citation = "Zhao & Zhou 2017, A novel method of offset approximation along the normal direction (MDPI), rational",
    .continuity = "none",  /* the ends are not interpolated: pieces do not meet (see the top) */
    .caps = OB_CAP_RATIONAL_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM | OB_CAP_ORIENTED,
    .max_turn = 0.0,
    .out_degree = zhao_degree,
    .cost_ms = 2.83,
    .work_size = sizeof(zhao_work),
    .params = zhao_params,
    .nparams = ZP_COUNT,
    .fit = zhao_rational_fit,
};
