/*
 * elber.c - Elber & Cohen 1992, "Offset approximation improvement by control
 * points perturbation" (Mathematical Methods in CAGD II, 229-237), as Liu &
 * Wang 2002 describe it (§1): start from Cobb's control
 * polygon and use the error at the curve points associated with the control
 * points to adjust the offset at P_j, iterating so that the approximation
 * converges to the true offset.  (The paper itself was not at hand.)
 *
 * Update rule.  Nodes t*_j = j/n (the Greville abscissae: the curve points of
 * Cobb's form, see cobb.c), exact offset points O_j = C(t*_j) + d N(t*_j):
 *   Q_j^0     = P_j + d N(t*_j)                          (Cobb's polygon)
 *   e_j^k     = O_j - A^k(t*_j)                          (node error vector)
 *   Q_j^{k+1} = Q_j^k + e_j^k                (update 0, the default), or
 *   Q_j^{k+1} = Q_j^k + (e_j^k . N(t*_j)) N(t*_j)        (update 1)
 * for k = 0 .. iterations-1, A^k the Bézier curve with control points Q^k
 * (rational input: the base's weights, the Euclidean points moved, as cobb).
 * Update 0 moves each control point by the error at its own node: this is the
 * Jacobi iteration for the node interpolation system, whose iteration matrix
 * I - [B_i^n(t*_j)] has the eigenvalues 1 - n!/((n-k)! n^k), k = 0..n, all in
 * [0, 1) (those of the Bernstein operator), so for polynomial input the node
 * errors converge to 0 and A^k converges to the interpolant of the offset at
 * the nodes (interp.c); the tests check the same for a rational arc.
 * Update 1 reads "adjust the offset amount at P_j" literally: only the
 * displacement along N(t*_j) is corrected, by the error along that normal.
 *
 * Iteration count (parameter `iterations`): neither Liu-Wang nor the other papers we follow give
 * Elber-Cohen's count.  Default 5: a few passes, after which every node-error
 * mode of a cubic but the slowest is reduced below 0.5 % (the factors per pass
 * are 0, 0, 1/3, 7/9), while the method stays a perturbation of Cobb's polygon
 * rather than its limit (for large counts it becomes interp).  0 gives cobb.
 *
 * Adaptive variant (parameter variant = 1; Elber's own scheme, Elber & Cohen
 * 1991, IJCGA 1(1) 67-78, as Elber, Lee & Kim 1997, IEEE CG&A 17(3), compare it):
 * the base segment is a B-spline of degree n (knots 0^(n+1), 1^(n+1)); its
 * offset approximation A moves each control point by d N at its Greville
 * abscissa (Cobb); D(t) = ||A(t) - C(t)||^2 is a spline of degree 2n whose
 * interior knots have multiplicity n + 1; D is evaluated at the Greville node
 * t* of each of its coefficients, and where |sqrt(D(t*)) - |d|| > tol (the
 * job's tolerance, in the distance units of the bound metric) a knot is
 * inserted into the base at t*, or at the midpoints between t* and its
 * neighbouring knots when t* is already a knot; re-offset; repeat until no
 * node fails or `rounds` rounds are done.  The result is one B-spline with
 * simple interior knots: its Bézier pieces are the output (over the knot
 * intervals of the base's parameter) and ob_fit.ctrl_points counts its
 * n + 1 + k control points.  More than OB_SPLIT_PIECES pieces: OB_FIT_RETRY_SMALLER.
 */
#include "methods/method.h"

#include <math.h>

static const ob_param elber_params[] = {
    {"iterations", 5.0,
     "perturbation passes after Cobb's polygon (integer 0..100000; 0 = cobb).  Default 5: "
     "the papers we follow give no count; 5 passes reduce all node-error modes of a cubic but the "
     "slowest (7/9 per pass) below 0.5 %, large counts converge to interp", 0, 100000, 1},
    {"update", 0.0,
     "0 = move Q_j by the node error vector O_j - A(j/n) (Jacobi step for the node "
     "interpolation: the default); 1 = move Q_j along N(j/n) by the error component "
     "along that normal (adjust only the offset amount)", 0, 1, 1},
    {"variant", 0.0,
     "0 = control point perturbation of one Bezier segment (Liu-Wang's description of "
     "Elber-Cohen 1992: the default); 1 = Elber's adaptive variant (Elber & Cohen 1991): refine the "
     "base as a B-spline by knot insertion where the node errors of ||A - C||^2 exceed the "
     "tolerance, re-offset (Cobb at the Greville abscissae), repeat; one B-spline, counted by "
     "its control points", 0, 1, 1},
    {"rounds", 20.0,
     "variant 1: most refinement rounds (integer 1..100); default 20 (the scheme as described: at most "
     "~20 rounds)", 1, 100, 1},
};

enum { EL_MAXK = OB_SPLIT_PIECES - 1,                     /* interior knots */
       EL_MAXCP = OB_MAX_DEG * OB_SPLIT_PIECES + 1,         /* control points */
       EL_MAXV = 2 * (2 * OB_MAX_DEG + 1) + EL_MAXK * (OB_MAX_DEG + 1) };

/* scratch of the adaptive variant */
typedef struct {
    double U[EL_MAXCP + OB_MAX_DEG + 1];  /* knots of the base / offset B-spline */
    double H[EL_MAXCP][3];                /* refined base, homogeneous */
    double Q[EL_MAXCP][3];                /* offset control points, homogeneous */
    double V[EL_MAXV];                    /* knots of D = ||A - C||^2 */
    double ins[EL_MAXV];                  /* knots to insert */
} el_work;

/* Insert knot u once into the degree-p B-spline (U[0..ncp+p], P[0..ncp-1]). */
static void insert_knot(double *U, double (*P)[3], int p, int *ncp, double u)
{
    const int m = *ncp + p;  /* last knot index */
    int k = p;
    while (k < *ncp - 1 && U[k + 1] <= u)
        k++;
    /* U[k] <= u < U[k+1] */
    for (int i = *ncp; i > k; i--)
        for (int c = 0; c < 3; c++)
            P[i][c] = P[i - 1][c];
    for (int i = k; i >= k - p + 1; i--) {
        const double al = (u - U[i]) / (U[i + p] - U[i]);
        for (int c = 0; c < 3; c++)
            P[i][c] = al * P[i][c] + (1.0 - al) * P[i - 1][c];
    }
    for (int i = m + 1; i > k + 1; i--)
        U[i] = U[i - 1];
    U[k + 1] = u;
    (*ncp)++;
}

/* Euclidean point of the degree-p B-spline at t (de Boor, homogeneous). */
static void deboor(const double *U, const double (*P)[3], int p, int ncp, double t, double out[2])
{
    int k = p;
    while (k < ncp - 1 && U[k + 1] <= t)
        k++;
    double d[OB_MAX_DEG + 1][3];
    for (int j = 0; j <= p; j++)
        for (int c = 0; c < 3; c++)
            d[j][c] = P[k - p + j][c];
    for (int r = 1; r <= p; r++)
        for (int j = p; j >= r; j--) {
            const int i = k - p + j;
            const double den = U[i + p - r + 1] - U[i];
            const double al = den > 0.0 ? (t - U[i]) / den : 0.0;
            for (int c = 0; c < 3; c++)
                d[j][c] = (1.0 - al) * d[j - 1][c] + al * d[j][c];
        }
    out[0] = d[p][0] / d[p][2];
    out[1] = d[p][1] / d[p][2];
}

/* Cobb on the refined base (w->U, w->H, ncp control points of degree p):
 * each control point moved by d N at its Greville abscissa, into w->Q.
 * OB_FIT_OK, or OB_FIT_FAIL where there is no normal. */
static ob_fit_status el_cobb(const ob_bez *base, double d, int p, int ncp, el_work *w, char *msg, size_t msglen)
{
    for (int i = 0; i < ncp; i++) {
        double xi = 0.0, N[2];
        for (int k = 1; k <= p; k++)
            xi += w->U[i + k];
        xi /= p;
        if (ob_bez_normal(base, xi, N) != 0) {
            ob_method_msg(msg, msglen, "no normal at t = %.17g (point-like segment)", xi);
            return OB_FIT_FAIL;
        }
        w->Q[i][0] = w->H[i][0] + w->H[i][2] * d * N[0];
        w->Q[i][1] = w->H[i][1] + w->H[i][2] * d * N[1];
        w->Q[i][2] = w->H[i][2];
    }
    return OB_FIT_OK;
}

/* The knots of D = ||A - C||^2 into w->V: the ends 2p+1 times, each of the
 * k_int interior knots of the base p+1 times; returns their count. */
static int el_d_knots(el_work *w, int p, int k_int)
{
    int nv = 0;
    for (int r = 0; r <= 2 * p; r++)
        w->V[nv++] = 0.0;
    for (int k = 0; k < k_int; k++)
        for (int r = 0; r <= p; r++)
            w->V[nv++] = w->U[p + 1 + k];
    for (int r = 0; r <= 2 * p; r++)
        w->V[nv++] = 1.0;
    return nv;
}

/* A failing node ts: the knots to insert for it (ts itself, or the
 * midpoints to its neighbouring knots when it is already a knot or an end)
 * appended to w->ins[0..*nins-1], leaving out those already there or at a
 * knot. */
static void el_mark(el_work *w, int p, int k_int, double ts, int *nins)
{
    int at = -1;
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < k_int; k++) {
        const double u = w->U[p + 1 + k];
        if (fabs(u - ts) <= 1e-12)
            at = k;
        else if (u < ts)
            lo = u;
        else if (u < hi)
            hi = u;
    }
    double cand[2];
    int nc = 0;
    if (at < 0 && ts > 1e-12 && ts < 1.0 - 1e-12) {
        cand[nc++] = ts;
    } else {
        cand[nc++] = 0.5 * (lo + ts);
        cand[nc++] = 0.5 * (ts + hi);
    }
    for (int c = 0; c < nc; c++) {
        int dup = cand[c] - lo < 1e-9 || hi - cand[c] < 1e-9;
        for (int k = 0; k < *nins && !dup; k++)
            dup = fabs(w->ins[k] - cand[c]) < 1e-9;
        if (!dup)
            w->ins[(*nins)++] = cand[c];
    }
}

/* The knots to insert after one round, into w->ins: those of every node of
 * D (Greville abscissae of degree 2p) where | |A - C| - |d| | > tol.
 * Returns their count. */
static int el_marks(const ob_bez *base, double d, double tol, int p, int ncp, el_work *w)
{
    const int k_int = ncp - p - 1;
    const int nv = el_d_knots(w, p, k_int);
    int nins = 0;
    for (int i = 0; i + 2 * p + 1 < nv; i++) {
        double ts = 0.0;
        for (int k = 1; k <= 2 * p; k++)
            ts += w->V[i + k];
        ts /= 2 * p;
        double A[2], C[2];
        deboor(w->U, (const double(*)[3])w->Q, p, ncp, ts, A);
        ob_bez_point(base, ts, C);
        const double e = fabs(hypot(A[0] - C[0], A[1] - C[1]) - fabs(d));
        if (e > tol)
            el_mark(w, p, k_int, ts, &nins);
    }
    return nins;
}

/* The offset B-spline w->U, w->Q (ncp control points) as its Bézier pieces
 * into out (every interior knot raised to multiplicity p), counted by its
 * ncp control points.  OB_FIT_OK, or OB_FIT_FAIL for non-finite control points. */
static ob_fit_status el_pieces(const ob_bez *base, int p, int ncp, el_work *w, ob_fit *out, char *msg,
                               size_t msglen)
{
    const int k_int = ncp - p - 1;
    const long cp = ncp;
    double knots[EL_MAXK + 2];
    knots[0] = 0.0;
    for (int k = 0; k < k_int; k++)
        knots[k + 1] = w->U[p + 1 + k];
    knots[k_int + 1] = 1.0;
    for (int k = 0; k < k_int; k++)
        for (int r = 1; r < p; r++)
            insert_knot(w->U, w->Q, p, &ncp, knots[k + 1]);
    out->n = k_int + 1;
    out->ctrl_points = cp;
    for (int s = 0; s <= k_int; s++) {
        out->t[s] = knots[s];
        ob_bez *b = &out->seg[s];
        b->deg = p;
        b->rational = base->rational;
        for (int i = 0; i <= p; i++)
            for (int c = 0; c < 3; c++)
                b->h[i][c] = w->Q[s * p + i][c];
        for (int i = p + 1; i <= OB_MAX_DEG; i++)
            b->h[i][0] = b->h[i][1] = b->h[i][2] = 0.0;
    }
    out->t[k_int + 1] = 1.0;
    for (int s = 0; s <= k_int; s++)
        for (int i = 0; i <= p; i++)
            if (!isfinite(out->seg[s].h[i][0]) || !isfinite(out->seg[s].h[i][1])) {
                ob_method_msg(msg, msglen, "non-finite control points");
                return OB_FIT_FAIL;
            }
    return OB_FIT_OK;
}

/* The adaptive variant (see the top): refine, re-offset, repeat, for at most
 * `rounds` rounds; the offset B-spline's pieces into out.  OB_FIT_OK, OB_FIT_FAIL
 * or OB_FIT_RETRY_SMALLER (more than OB_SPLIT_PIECES pieces), reason in msg. */
static ob_fit_status elber_adaptive(const ob_bez *base, double d, double tol, int rounds,
                                    el_work *w, ob_fit *out, char *msg, size_t msglen)
{
    const int p = base->deg;
    int ncp = p + 1;
    for (int i = 0; i <= p; i++) {
        w->U[i] = 0.0;
        w->U[p + 1 + i] = 1.0;
        for (int c = 0; c < 3; c++)
            w->H[i][c] = base->h[i][c];
    }
    for (int round = 1;; round++) {
        const ob_fit_status st = el_cobb(base, d, p, ncp, w, msg, msglen);
        if (st != OB_FIT_OK)
            return st;
        if (round > rounds)
            break;
        const int nins = el_marks(base, d, tol, p, ncp, w);
        if (nins == 0)
            break;
        if (ncp - p - 1 + nins > EL_MAXK) {
            ob_method_msg(msg, msglen, "adaptive refinement needs more than %d pieces",
                          OB_SPLIT_PIECES);
            return OB_FIT_RETRY_SMALLER;
        }
        for (int k = 0; k < nins; k++)
            insert_knot(w->U, w->H, p, &ncp, w->ins[k]);
    }
    return el_pieces(base, p, ncp, w, out, msg, msglen);
}

static ob_fit_status elber_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                               char *msg, size_t msglen)
{
    const double d = a->d;
    const int n = base->deg;
    const int iters = (int)a->par[0], update = (int)a->par[1];
    if (!(a->par[0] >= 0.0 && a->par[0] <= 100000.0) || a->par[0] != iters) {
        ob_method_msg(msg, msglen, "iterations must be an integer in 0..100000 (got %g)",
                      a->par[0]);
        return OB_FIT_FAIL;
    }
    if ((update != 0 && update != 1) || a->par[1] != update) {
        ob_method_msg(msg, msglen, "update must be 0 or 1 (got %g)", a->par[1]);
        return OB_FIT_FAIL;
    }
    const int variant = (int)a->par[2], rounds = (int)a->par[3];
    if ((variant != 0 && variant != 1) || a->par[2] != variant) {
        ob_method_msg(msg, msglen, "variant must be 0 or 1 (got %g)", a->par[2]);
        return OB_FIT_FAIL;
    }
    if (!(a->par[3] >= 1.0 && a->par[3] <= 100.0) || a->par[3] != rounds) {
        ob_method_msg(msg, msglen, "rounds must be an integer in 1..100 (got %g)", a->par[3]);
        return OB_FIT_FAIL;
    }
    if (variant == 1)
        return elber_adaptive(base, d, a->tol, rounds, work, out, msg, msglen);
    double N[OB_MAX_DEG + 1][2], O[OB_MAX_DEG + 1][2], Q[OB_MAX_DEG + 1][2];
    ob_bez r = *base;
    for (int j = 0; j <= n; j++) {
        const double t = (double)j / n;
        if (ob_bez_normal(base, t, N[j]) != 0) {
            ob_method_msg(msg, msglen, "no normal at t = %d/%d (point-like segment)", j, n);
            return OB_FIT_FAIL;
        }
        ob_bez_point(base, t, O[j]);
        O[j][0] += d * N[j][0];
        O[j][1] += d * N[j][1];
        ob_bez_ctrl(base, j, Q[j]);
        Q[j][0] += d * N[j][0];
        Q[j][1] += d * N[j][1];
        ob_bez_set(&r, j, Q[j][0], Q[j][1], ob_bez_weight(base, j));
    }
    for (int k = 0; k < iters; k++) {
        double e[OB_MAX_DEG + 1][2];
        for (int j = 0; j <= n; j++) {
            double A[2];
            ob_bez_point(&r, (double)j / n, A);
            e[j][0] = O[j][0] - A[0];
            e[j][1] = O[j][1] - A[1];
            if (update == 1) {
                const double s = e[j][0] * N[j][0] + e[j][1] * N[j][1];
                e[j][0] = s * N[j][0];
                e[j][1] = s * N[j][1];
            }
        }
        for (int j = 0; j <= n; j++) {
            Q[j][0] += e[j][0];
            Q[j][1] += e[j][1];
            ob_bez_set(&r, j, Q[j][0], Q[j][1], ob_bez_weight(base, j));
        }
    }
    for (int j = 0; j <= n; j++)
        if (!isfinite(Q[j][0]) || !isfinite(Q[j][1])) {
            ob_method_msg(msg, msglen, "perturbation diverged (non-finite control points)");
            return OB_FIT_FAIL;
        }
    ob_fit_single(out, &r);
    return OB_FIT_OK;
}

/* Only the adaptive variant refines to the tolerance. */
static int elber_uses_tol(const double *par) { return par[2] != 0.0; }

const ob_method ob_method_elber = {
    .name = "elber",
    .version = 1,
    .citation = "Elber & Cohen 1992, Math. Methods in CAGD II, 229-237 (as described by Liu & Wang 2002)",
    .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM,
    .max_turn = 0.0,
    .out_degree = ob_degree_same,
    .cost_ms = 1.42,
    .work_size = sizeof(el_work),
    .params = elber_params,
    .nparams = 4,
    .fit_uses_tol = elber_uses_tol,
    .fit = elber_fit,
};
