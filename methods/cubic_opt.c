/*
 * cubic_opt.c - optimal G1 cubic offsets: a method beyond the seed papers
 * (issue 19).  Not from a paper of 1984-2023: the construction used by
 * today's vector-graphics and font tools (kurbo 0.11, 2022: area and moment
 * matching; kurbo 0.13, 2025: refinement of the handles against the error
 * along normals; R. Levien, "Parallel curves of cubic Béziers", 2022,
 * raphlinus.github.io), implemented here from that description, with one step of our
 * own: the handles are driven to the minimax (equioscillation) of the error
 * along the normals, not only matched to two integrals.
 *
 * One cubic per piece between offset cusps:
 *   A(u) = P0 B0 + (P0 + a T0) B1 + (P3 - b T1) B2 + P3 B3,
 * P0, P3 the exact offset points O(0), O(1) and T0, T1 the unit tangents of
 * the offset there (the base's, reversed where 1 - d kappa < 0: the offset
 * runs backwards), so consecutive pieces meet G1 wherever the offset is G1.
 * The two handle lengths a, b >= 0 are chosen in three steps:
 *  1. candidates: in the chord frame (P0 at the origin, P3 at (1, 0)) the
 *     signed area and the first moment (about the y axis) of the region
 *     between the curve and the chord equal the offset's.  Green's theorem
 *     makes both integrals along the curve; the offset's are taken by
 *     16-point Gauss-Legendre quadrature.  The cubic's area is
 *     (Ka a + Kb b + Kab a b) / 2 (no constant, a^2, b^2 terms: the chord
 *     frame and the vanishing end basis make them zero), so b = p(a) / q(a)
 *     with p, q linear; the cubic's moment has no a^3, b^3 terms (integrals
 *     of B^2 B' over [0,1] of basis functions vanishing at both ends), so
 *     the moment condition times q(a)^2 is a quartic in a: up to four
 *     candidates with a, b in [AMIN, AMAX].  The circular-arc guess
 *     (4/3) tan(theta/4) joins them, so a candidate always exists.
 *  2. scoring: each candidate's error along the base's normals, e(t) =
 *     (A(u) - C(t)) . N(t) - d where A(u) lies on the normal line of C at t
 *     (Newton on (A(u) - C(t)) . T(t) = 0, continued from sample to sample),
 *     at `samples` interior parameters, the largest sample refined by a
 *     parabola through it and its neighbours: the method's own cheap error
 *     estimate (the driver's metric measures every accepted piece anyway).
 *  3. refinement (parameter `refine`): Remez-like Newton steps on (a, b, E)
 *     that make three consecutive alternating extrema of e equal to +-E
 *     (two parameters: three alternation points at the minimax), with the
 *     exact derivatives de/da, de/db along the normal lines; a step is kept
 *     only when the estimate falls (halved up to four times), so the result
 *     is never worse than the best candidate.
 * Offset cusps (1 - d kappa changes sign inside the piece, ob_bez_offset_cusps)
 * split the piece: one cubic per stretch between them (a fit of several
 * pieces, joined G0 at the cusps).  The method asks the driver to cut its
 * initial pieces there too (OB_CAP_CUSP_BREAKS): a greedy prefix that ends
 * just before a cusp, where the offset's curvature is unbounded, fails
 * while one that reaches it passes, and greedy bisection assumes the
 * error grows with the prefix.
 * Degenerate input: a point-like base fails; an offset whose end points
 * coincide (a closed piece) asks for a smaller piece (OB_FIT_RETRY_SMALLER); an
 * offset that collapses to a point (a circle offset by its radius) is that
 * point.  Where no candidate can be scored (the base's tangent reverses
 * between two samples: a cusp of the base, where the offset jumps by 2d,
 * or a hook below the sampling; a normal line that misses every
 * candidate) and on a piece with more offset cusps than a fit holds (the
 * curvature of a sliver is round-off), the fit is the Hermite-like cubic
 * with handles of a third of the chord along the offset's end tangents:
 * the driver measures it and splits or, where the error stops falling,
 * ends the job with status limit, as for the other methods (asking for a
 * smaller piece there made 2^12 retries of a 1e-8 sliver, 0.4 s per job).
 * No loop runs more than a fixed count, and every output is checked
 * finite.
 * The output is polynomial (rational bases are sampled like any other) and
 * not in the base's parameter (normal or hausdorff metric).  The fit reads
 * the tolerance only with split = 1 (its own split: split_stretch).
 */
#include "methods/method.h"

#include <math.h>
#include <string.h>

#include "methods/core/bernstein.h"

enum { CP_SAMPLES, CP_REFINE, CP_SPLIT, CP_COUNT };
enum { CO_MAX_SAMPLES = 128, CO_MAX_ITER = 40 };

/* handle lengths in chord units beyond this are not candidates (a cubic
 * with longer handles loops) */
static const double AMAX = 4.0;
/* and never shorter than this: a handle of length 0 would leave the end
 * tangent to the next control point, not the offset's (a kink at the
 * joint); the minimax next to a cusp of the offset wants it near 0 */
static const double AMIN = 1e-6;

static const ob_param cubic_opt_params[CP_COUNT] = {
    {"samples", 24,
     "interior parameters of the base at which the error along the normals is estimated (scoring "
     "and refinement); 24: about five per hump of the error of a quartic-matched cubic", 8, CO_MAX_SAMPLES, 1},
    {"refine", 1,
     "1: refine the handle lengths to the minimax of the error along the normals (default); "
     "0: the best area-and-moment candidate as it is (kurbo 0.11's construction)", 0, 1, 1},
    {"split", 0,
     "0: one cubic per stretch between offset cusps, the driver's split rule finds the pieces "
     "(default); 1: the fit splits each stretch itself, the longest pieces whose own estimate "
     "meets the job's tolerance (kurbo's model: the driver measures only the result; under "
     "--split greedy its first probe, the whole piece, then passes at once, and where the metric "
     "rejects a result greedy finds the longest prefix the fit can cover)", 0, 1, 1},
};

/* The error record of a cubic: signed errors at the samples (0 at the
 * ends), the parameters u of the intersections, the alternants (the
 * largest |e| of each run of one sign, at the vertex of the parabola
 * through its sample and their neighbours), and the estimate. */
typedef struct {
    int n;                             /* samples + 2 (the ends) */
    double e[CO_MAX_SAMPLES + 2], u[CO_MAX_SAMPLES + 2];
    double ja[CO_MAX_SAMPLES + 2], jb[CO_MAX_SAMPLES + 2];  /* de/da, de/db */
    int nalt;
    double ae[CO_MAX_SAMPLES], aja[CO_MAX_SAMPLES], ajb[CO_MAX_SAMPLES];
    double max;                        /* the estimate; +inf: a normal line missed the cubic */
} co_err;

/* Scratch of one fit: the base, its points and unit tangents at the sample
 * parameters, and the error records of the current, best and trial cubics. */
typedef struct {
    const ob_bez *base;
    double t[CO_MAX_SAMPLES + 2], C[CO_MAX_SAMPLES + 2][2], T[CO_MAX_SAMPLES + 2][2];
    co_err cur, best, trial;
} co_work;

/* One cubic candidate in world coordinates, with its chord-frame handles. */
typedef struct {
    double P0[2], P3[2], T0[2], T1[2], L;  /* ends, unit end tangents, chord */
    double a, b;                           /* handle lengths / L */
} co_cubic;

/* 16-point Gauss-Legendre nodes on [0,1] (upper half; the lower half is
 * 1 - x) and weights (summing to 1 over all 16). */
static const double GL16[8][2] = {
    {0.54750625491881877, 0.094725305227534251}, {0.64080177538962946, 0.091301707522461792},
    {0.72900838882861374, 0.084578259697501268}, {0.80893812220132189, 0.074797994408288368},
    {0.87770220417750155, 0.062314485627766938}, {0.93281560119391582, 0.047579255841246393},
    {0.9722875115366163, 0.031126761969323947},  {0.99470046749582497, 0.013576229705877048},
};


/* Node i (0..15, ascending) of the 16-point rule on [0,1], its weight in *w. */
static double gl16(int i, double *w)
{
    const int k = i < 8 ? 7 - i : i - 8;
    *w = GL16[k][1];
    return i < 8 ? 1.0 - GL16[k][0] : GL16[k][0];
}

static double dot2(const double a[2], const double b[2]) { return a[0] * b[0] + a[1] * b[1]; }
static double cross2(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }

/* 1 - d kappa: the factor by which the offset's derivative is the base's. */
static double speed_factor(const ob_bez *base, double t, double d) { return 1.0 - d * ob_bez_curvature(base, t); }

/* Unit tangent of the base at t (the limit at a vanishing derivative), from
 * the normal N = (-T_y, T_x).  Returns -1 on a point-like segment. */
static int base_tangent(const ob_bez *base, double t, double T[2])
{
    double N[2];
    if (ob_bez_normal(base, t, N) != 0)
        return -1;
    T[0] = N[1];
    T[1] = -N[0];
    return 0;
}

/* The cubic's control points. */
static void cubic_points(const co_cubic *c, double P[4][2])
{
    for (int k = 0; k < 2; k++) {
        P[0][k] = c->P0[k];
        P[1][k] = c->P0[k] + c->a * c->L * c->T0[k];
        P[2][k] = c->P3[k] - c->b * c->L * c->T1[k];
        P[3][k] = c->P3[k];
    }
}

/* Point and derivative of the cubic with control points P at u. */
static void cubic_eval(const double P[4][2], double u, double A[2], double dA[2])
{
    const double v = 1.0 - u, b0 = v * v * v, b1 = 3 * v * v * u, b2 = 3 * v * u * u, b3 = u * u * u;
    const double d0 = -3 * v * v, d1 = 3 * v * (1 - 3 * u), d2 = 3 * u * (2 - 3 * u), d3 = 3 * u * u;
    for (int k = 0; k < 2; k++) {
        A[k] = b0 * P[0][k] + b1 * P[1][k] + b2 * P[2][k] + b3 * P[3][k];
        dA[k] = d0 * P[0][k] + d1 * P[1][k] + d2 * P[2][k] + d3 * P[3][k];
    }
}

/* ---- 1. candidates from area and moment ----------------------------------- */

/* Purpose: signed area and first moment, in the chord frame of c, of the
 *          region between the d-offset of base and its chord.
 * Method:  Green: A = 1/2 int (x y' - y x'), M = int x^2 y' / 2 along the
 *          offset (the chord, on the x axis, adds nothing), with
 *          O' = C' (1 - d kappa), by 16-point Gauss-Legendre. */
static void offset_moments(const ob_bez *base, double d, const co_cubic *c, double *area, double *moment)
{
    const double e[2] = {(c->P3[0] - c->P0[0]) / c->L, (c->P3[1] - c->P0[1]) / c->L};
    double A = 0.0, M = 0.0;
    for (int i = 0; i < 16; i++) {
        double w;
        const double t = gl16(i, &w);
        double o[3][2], N[2];
        ob_bez_eval(base, t, 2, o);
        const double sp = hypot(o[1][0], o[1][1]);
        if (!(sp > 0.0))
            continue;  /* O' = 0 there: nothing to add (N is bounded) */
        N[0] = -o[1][1] / sp;
        N[1] = o[1][0] / sp;
        const double g = 1.0 - d * cross2(o[1], o[2]) / (sp * sp * sp);
        const double r[2] = {(o[0][0] + d * N[0] - c->P0[0]) / c->L, (o[0][1] + d * N[1] - c->P0[1]) / c->L};
        const double dr[2] = {o[1][0] * g / c->L, o[1][1] * g / c->L};
        const double x = dot2(r, e), y = cross2(e, r), dx = dot2(dr, e), dy = cross2(e, dr);
        A += w * 0.5 * (x * dy - y * dx);
        M += w * 0.5 * x * x * dy;
    }
    *area = A;
    *moment = M;
}

/* Purpose: the cubic's area and moment as polynomials in (a, b).
 * Inputs:  t0, t1: the unit end tangents in the chord frame.
 * Outputs: K[0..2] = Ka, Kb, Kab (area = (Ka a + Kb b + Kab a b) / 2);
 *          m[i][j]: the coefficient of a^i b^j of the moment (i + j <= 3).
 * Method:  x = X0 + a Xa + b Xb, y = a Ya + b Yb with cubic Bernstein
 *          basis functions; the integrals of their products (degree <= 8)
 *          are exact with the 16-point rule. */
static void cubic_moments(const double t0[2], const double t1[2], double K[3], double m[4][4])
{
    memset(m, 0, 16 * sizeof m[0][0]);
    K[0] = K[1] = K[2] = 0.0;
    for (int i = 0; i < 16; i++) {
        double w;
        const double s = gl16(i, &w);
        const double v = 1.0 - s, B1 = 3 * v * v * s, B2 = 3 * v * s * s, B3 = s * s * s;
        const double D1 = 3 * v * (1 - 3 * s), D2 = 3 * s * (2 - 3 * s), D3 = 3 * s * s;
        /* index 0: the part without a or b, 1: times a, 2: times b */
        const double X[3] = {B2 + B3, t0[0] * B1, -t1[0] * B2}, dX[3] = {D2 + D3, t0[0] * D1, -t1[0] * D2};
        const double Y[3] = {0.0, t0[1] * B1, -t1[1] * B2}, dY[3] = {0.0, t0[1] * D1, -t1[1] * D2};
        K[0] += w * (X[0] * dY[1] - Y[1] * dX[0]);
        K[1] += w * (X[0] * dY[2] - Y[2] * dX[0]);
        K[2] += w * (X[1] * dY[2] + X[2] * dY[1] - Y[1] * dX[2] - Y[2] * dX[1]);
        for (int k = 0; k < 3; k++)
            for (int l = 0; l < 3; l++)
                for (int n = 1; n < 3; n++) {
                    const int ea = (k == 1) + (l == 1) + (n == 1), eb = (k == 2) + (l == 2) + (n == 2);
                    m[ea][eb] += w * 0.5 * X[k] * X[l] * dY[n];
                }
    }
}

/* c = a * b for power-basis polynomials of degrees na, nb (c: na + nb). */
static void poly_mul(const double *a, int na, const double *b, int nb, double *c)
{
    for (int k = 0; k <= na + nb; k++)
        c[k] = 0.0;
    for (int i = 0; i <= na; i++)
        for (int j = 0; j <= nb; j++)
            c[i + j] += a[i] * b[j];
}

/* Purpose: the handle lengths a in (0, AMAX) where the moment of the cubic
 *          whose area matches equals the offset's.
 * Inputs:  K, m from cubic_moments; At, Mt the offset's area and moment.
 * Outputs: as[], bs[] (b = p(a) / q(a)), up to 4 pairs with b in [0, AMAX].
 * Method:  F(a) = sum m_ij a^i p^j q^(2-j) - Mt q^2 (j <= 2; the a^3, b^3
 *          terms vanish), a quartic, in Bernstein form on [0, AMAX]:
 *          its sign changes (ob_bern_roots). */
static int quartic_candidates(const double K[3], double m[4][4], double At, double Mt, double *as, double *bs)
{
    const double p[2] = {2 * At, -K[0]}, q[2] = {K[1], K[2]};
    double F[5] = {0}, pw[3][3], qw[3][3], tmp[5], term[5];
    pw[0][0] = qw[0][0] = 1.0;  /* pw[j]: p^j, qw[j]: q^j, degree j */
    for (int j = 1; j <= 2; j++) {
        poly_mul(pw[j - 1], j - 1, p, 1, pw[j]);
        poly_mul(qw[j - 1], j - 1, q, 1, qw[j]);
    }
    for (int i = 0; i <= 2; i++)
        for (int j = 0; j <= 2 && i + j <= 3; j++) {
            poly_mul(pw[j], j, qw[2 - j], 2 - j, tmp);  /* degree 2 */
            for (int k = 0; k <= 2; k++)
                F[k + i] += m[i][j] * tmp[k];
        }
    for (int k = 0; k <= 2; k++)
        F[k] -= Mt * qw[2][k];
    /* power basis in s = a / AMAX, then Bernstein coefficients of degree 4 */
    double beta[5];
    for (int k = 0; k <= 4; k++)
        term[k] = F[k] * pow(AMAX, k);
    for (int i = 0; i <= 4; i++) {
        beta[i] = 0.0;
        for (int k = 0; k <= i; k++)
            beta[i] += ob_binom(i, k) / ob_binom(4, k) * term[k];
    }
    double roots[4];
    const int nr = ob_bern_roots(beta, 4, roots, 4);
    int n = 0;
    for (int r = 0; r < nr; r++) {
        const double a = AMAX * roots[r], qa = q[0] + q[1] * a;
        if (!(fabs(qa) > 1e-300))
            continue;
        const double b = (p[0] + p[1] * a) / qa;
        if (b >= 0.0 && b <= AMAX && isfinite(b)) {
            as[n] = fmax(a, AMIN);
            bs[n] = fmax(b, AMIN);
            n++;
        }
    }
    return n;
}

/* ---- 2. the error along the base's normals --------------------------------- */


/* Purpose: the signed error e = (A(u) - C) . N - d where A(u) is on the
 *          normal line of the base point C (unit tangent T), and its
 *          derivatives in the handle lengths.
 * Inputs:  c, P (its control points), *u the starting parameter.
 * Outputs: *u, *e, *ja, *jb.  Returns 0, or -1 when Newton fails.
 * Method:  Newton on (A(u) - C) . T = 0 (at most 12 steps, u kept in
 *          [-0.5, 1.5]); de/dh = (A' x dA/dh) / (A' . T). */
static int normal_error(const co_cubic *c, const double P[4][2], const double C[2], const double T[2], double d,
                        double *u, double *e, double *ja, double *jb)
{
    double A[2], dA[2], uu = *u;
    for (int it = 0; it < 12; it++) {
        cubic_eval(P, uu, A, dA);
        const double f = (A[0] - C[0]) * T[0] + (A[1] - C[1]) * T[1], fp = dot2(dA, T);
        if (!(fabs(fp) > 1e-300))
            return -1;
        const double du = f / fp;
        uu -= du;
        if (!(uu > -0.5 && uu < 1.5))
            return -1;
        if (fabs(du) < 1e-9)
            break;  /* quadratic convergence: the next step would be below 1e-17 */
    }
    cubic_eval(P, uu, A, dA);
    const double N[2] = {-T[1], T[0]}, r[2] = {A[0] - C[0], A[1] - C[1]};
    const double den = dot2(dA, T), v = 1.0 - uu;
    if (!(fabs(den) > 1e-300))
        return -1;
    const double va[2] = {3 * v * v * uu * c->L * c->T0[0], 3 * v * v * uu * c->L * c->T0[1]};
    const double vb[2] = {-3 * v * uu * uu * c->L * c->T1[0], -3 * v * uu * uu * c->L * c->T1[1]};
    *u = uu;
    *e = dot2(r, N) - d;
    *ja = cross2(dA, va) / den;
    *jb = cross2(dA, vb) / den;
    return isfinite(*e) ? 0 : -1;
}

/* The alternating extrema of e over the samples: indices of the largest
 * |e| of each run of one sign. */
static int alternants(const co_err *E, int *idx)
{
    int n = 0;
    for (int j = 1; j + 1 < E->n; j++) {
        if (E->e[j] == 0.0)
            continue;
        if (n > 0 && (E->e[j] > 0) == (E->e[idx[n - 1]] > 0)) {
            if (fabs(E->e[j]) > fabs(E->e[idx[n - 1]]))
                idx[n - 1] = j;
        } else {
            idx[n++] = j;
        }
    }
    return n;
}

/* The error at sample j into E (Newton from near's parameter, else from
 * the previous sample's); 0, or -1 (E->max = +inf) when Newton fails. */
static int sample_error(const co_cubic *c, const double P[4][2], const co_work *W, int j, double d,
                        const co_err *near, co_err *E)
{
    E->u[j] = near ? near->u[j] : j == 1 ? W->t[1] : E->u[j - 1];
    if (normal_error(c, P, W->C[j], W->T[j], d, &E->u[j], &E->e[j], &E->ja[j], &E->jb[j])) {
        E->max = INFINITY;
        E->nalt = 0;
        return -1;
    }
    E->max = fmax(E->max, fabs(E->e[j]));
    return 0;
}

/* Purpose: the error of cubic c at the samples of W, its alternants and
 *          its estimate.
 * Inputs:  near: NULL, or the record of a nearby cubic (its intersection
 *          parameters start Newton); bound: the record is wanted only when
 *          its estimate is below this (+inf: always).
 * Outputs: *E; when the estimate reaches bound, E->max >= bound and the
 *          rest of E is incomplete (the caller discards it).
 * Method:  normal_error at each sample, from near's parameter or else
 *          continued from the previous intersection (with near, the samples
 *          where near's error is within half its estimate go first: each
 *          sample's result depends on near alone, so the order changes
 *          nothing but how soon a bound is seen); each alternant at the
 *          vertex of the parabola through its sample and the neighbours
 *          (the ends count, e = 0), evaluated there when that is larger. */
static void cubic_error(const co_cubic *c, const co_work *W, int ns, double d, const co_err *near, double bound,
                        co_err *E)
{
    double P[4][2];
    cubic_points(c, P);
    E->n = ns + 2;
    E->e[0] = E->e[ns + 1] = E->ja[0] = E->jb[0] = E->ja[ns + 1] = E->jb[ns + 1] = 0.0;
    E->u[0] = 0.0;
    E->u[ns + 1] = 1.0;
    E->max = 0.0;
    const double first = near ? 0.5 * near->max : INFINITY;
    for (int pass = near ? 0 : 1; pass < 2; pass++)
        for (int j = 1; j <= ns; j++) {
            if (near && (fabs(near->e[j]) >= first) != (pass == 0))
                continue;
            if (sample_error(c, P, W, j, d, near, E) || E->max >= bound)
                return;
        }
    int idx[CO_MAX_SAMPLES];
    E->nalt = alternants(E, idx);
    const double h = 1.0 / (ns + 1);
    for (int k = 0; k < E->nalt; k++) {
        const int j = idx[k];
        E->ae[k] = E->e[j];
        E->aja[k] = E->ja[j];
        E->ajb[k] = E->jb[j];
        const double em = E->e[j - 1], e0 = E->e[j], ep = E->e[j + 1], den = em - 2 * e0 + ep;
        const double s = den != 0.0 ? 0.5 * (em - ep) / den : 0.0;
        if (!(fabs(s) > 1e-3 && fabs(s) < 1.0))
            continue;
        double Ct[2], Tt[2], u = E->u[j], e, ja, jb;
        ob_bez_point(W->base, W->t[j] + s * h, Ct);
        if (base_tangent(W->base, W->t[j] + s * h, Tt) || normal_error(c, P, Ct, Tt, d, &u, &e, &ja, &jb) ||
            !(fabs(e) > fabs(e0)) || (e > 0) != (e0 > 0))
            continue;
        E->ae[k] = e;
        E->aja[k] = ja;
        E->ajb[k] = jb;
        E->max = fmax(E->max, fabs(e));
    }
}

/* ---- 3. refinement to the minimax -------------------------------------- */

/* Solve the 3x3 system M x = r by Gaussian elimination with partial
 * pivoting; returns -1 when singular. */
static int solve3(double M[3][3], double r[3], double x[3])
{
    for (int k = 0; k < 3; k++) {
        int p = k;
        for (int i = k + 1; i < 3; i++)
            if (fabs(M[i][k]) > fabs(M[p][k]))
                p = i;
        for (int c = 0; c < 3; c++) {
            const double t = M[k][c];
            M[k][c] = M[p][c];
            M[p][c] = t;
        }
        const double t = r[k];
        r[k] = r[p];
        r[p] = t;
        if (!(fabs(M[k][k]) > 1e-300))
            return -1;
        for (int i = k + 1; i < 3; i++) {
            const double f = M[i][k] / M[k][k];
            for (int c = k; c < 3; c++)
                M[i][c] -= f * M[k][c];
            r[i] -= f * r[k];
        }
    }
    for (int k = 2; k >= 0; k--) {
        x[k] = r[k];
        for (int c = k + 1; c < 3; c++)
            x[k] -= M[k][c] * x[c];
        x[k] /= M[k][k];
    }
    return 0;
}

/* Purpose: one Remez-Newton step for (a, b).
 * Outputs: step[2].  Returns -1 when no step can be formed.
 * Method:  with three consecutive alternants j1 < j2 < j3 around the
 *          largest |e|, solve e_j + J_j . step = s_j E (s alternating);
 *          with two, zero both; with one, the least-norm step zeroing it. */
static int remez_step(const co_err *E, double step[2])
{
    const int n = E->nalt;
    if (n == 0)
        return -1;
    if (n >= 3) {
        int best = 0;  /* the window of three with the largest smallest |e| */
        double bestmin = -1.0;
        for (int w = 0; w + 2 < n; w++) {
            const double mn = fmin(fabs(E->ae[w]), fmin(fabs(E->ae[w + 1]), fabs(E->ae[w + 2])));
            if (mn > bestmin) {
                bestmin = mn;
                best = w;
            }
        }
        double M[3][3], r[3], x[3];
        for (int k = 0; k < 3; k++) {
            const int j = best + k;
            M[k][0] = E->aja[j];
            M[k][1] = E->ajb[j];
            M[k][2] = E->ae[j] > 0 ? -1.0 : 1.0;  /* e_j + J.step = sign(e_j) E */
            r[k] = -E->ae[j];
        }
        if (solve3(M, r, x))
            return -1;
        step[0] = x[0];
        step[1] = x[1];
        return 0;
    }
    if (n == 2) {
        const double det = E->aja[0] * E->ajb[1] - E->ajb[0] * E->aja[1];
        if (!(fabs(det) > 1e-300))
            return -1;
        step[0] = (-E->ae[0] * E->ajb[1] + E->ae[1] * E->ajb[0]) / det;
        step[1] = (-E->ae[1] * E->aja[0] + E->ae[0] * E->aja[1]) / det;
        return 0;
    }
    const double nn = E->aja[0] * E->aja[0] + E->ajb[0] * E->ajb[0];
    if (!(nn > 1e-300))
        return -1;
    step[0] = -E->ae[0] * E->aja[0] / nn;
    step[1] = -E->ae[0] * E->ajb[0] / nn;
    return 0;
}

/* Try handle lengths (a + da, b + db) (kept in [AMIN, AMAX]); keeps them in
 * c, E when the estimate falls.  Returns the fall (0: not kept). */
static double try_step(co_cubic *c, const co_work *W, int ns, double d, co_err *E, co_err *trial, double da,
                       double db)
{
    co_cubic t = *c;
    t.a = fmin(AMAX, fmax(AMIN, c->a + da));
    t.b = fmin(AMAX, fmax(AMIN, c->b + db));
    if (t.a == c->a && t.b == c->b)
        return 0.0;
    cubic_error(&t, W, ns, d, E, E->max, trial);
    if (!(trial->max < E->max))
        return 0.0;
    const double gain = E->max - trial->max;
    *c = t;
    *E = *trial;
    return gain;
}

/* Purpose: refine the handle lengths of c towards the minimax of the error
 *          along the normals.
 * Method:  a trust region of radius r (chord units) around (a, b): the
 *          Remez step (remez_step) cut to length r; when it does not lower
 *          the estimate, the four moves by r along a and b (a pattern
 *          search: far from the minimax the linearized alternation can
 *          point anywhere); r doubles after a kept Remez step and shrinks
 *          by 4 when nothing is kept.  Stops after CO_MAX_ITER rounds, after
 *          a full Remez step shorter than 1e-8 (converging quadratically:
 *          the next would be below round-off) or when r < 1e-9. */
static void refine(co_cubic *c, const co_work *W, int ns, double d, co_err *E, co_err *trial)
{
    double r = 0.25 * fmax(0.1, fmax(c->a, c->b));
    for (int it = 0; it < CO_MAX_ITER && E->max > 0.0; it++) {
        double step[2];
        if (remez_step(E, step) == 0 && isfinite(step[0]) && isfinite(step[1])) {
            const double len = hypot(step[0], step[1]), f = len > r ? r / len : 1.0;
            const double gain = try_step(c, W, ns, d, E, trial, f * step[0], f * step[1]);
            if (f == 1.0 && len < 1e-8)
                return;  /* converged: the next step would be below 1e-15 */
            if (gain > 0.0) {
                r = fmin(AMAX, 2.0 * r);
                continue;
            }
        }
        static const double dir[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        int kept = 0;
        for (int k = 0; k < 4 && !kept; k++)
            kept = try_step(c, W, ns, d, E, trial, r * dir[k][0], r * dir[k][1]) > 0.0;
        if (!kept && (r *= 0.25) < 1e-9)
            return;
    }
}

/* ---- one stretch, cusps, the method --------------------------------------- */

/* The base at the sample parameters t_j = j / (ns + 1), j = 0..ns+1, into
 * W.  Returns 0; -1 (msg) when the base is point-like; 1 when its tangent
 * reverses between two samples (a cusp of the base: the offset jumps). */
static int sample_base(const ob_bez *base, int ns, co_work *W, char *msg, size_t msglen)
{
    int reverses = 0;
    W->base = base;
    for (int j = 0; j <= ns + 1; j++) {
        double o[2][2];
        W->t[j] = j == ns + 1 ? 1.0 : (double)j / (ns + 1);
        ob_bez_eval(base, W->t[j], 1, o);
        W->C[j][0] = o[0][0];
        W->C[j][1] = o[0][1];
        const double sp = hypot(o[1][0], o[1][1]);
        if (sp > 0.0) {
            W->T[j][0] = o[1][0] / sp;
            W->T[j][1] = o[1][1] / sp;
        } else if (base_tangent(base, W->t[j], W->T[j])) {
            ob_method_msg(msg, msglen, "no tangent at t = %.6g (point-like base)", W->t[j]);
            return -1;
        }
        if (j > 0 && dot2(W->T[j - 1], W->T[j]) < 0.0)
            reverses = 1;
    }
    return reverses;
}

/* The largest distance of a control point of base from the first. */
static double base_size(const ob_bez *base)
{
    double p0[2], s = 0.0;
    ob_bez_ctrl(base, 0, p0);
    for (int i = 1; i <= base->deg; i++) {
        double p[2];
        ob_bez_ctrl(base, i, p);
        s = fmax(s, hypot(p[0] - p0[0], p[1] - p0[1]));
    }
    return s;
}

/* Purpose: the ends, end tangents and chord of the offset of a stretch.
 * Returns 0; 1 when the ends coincide (c->L = 0). */
static int offset_ends(const ob_bez *base, double d, co_cubic *c)
{
    double T0[2] = {0.0, 0.0}, T1[2] = {0.0, 0.0};  /* sample_base has checked both exist */
    ob_bez_offset_point(base, 0.0, d, c->P0);
    ob_bez_offset_point(base, 1.0, d, c->P3);
    base_tangent(base, 0.0, T0);
    base_tangent(base, 1.0, T1);
    /* no cusp inside the stretch: the offset's direction is the base's
     * wherever 1 - d kappa > 0, reversed elsewhere */
    const double sg = speed_factor(base, 0.5, d) < 0.0 ? -1.0 : 1.0;
    for (int k = 0; k < 2; k++) {
        c->T0[k] = sg * T0[k];
        c->T1[k] = sg * T1[k];
    }
    c->L = hypot(c->P3[0] - c->P0[0], c->P3[1] - c->P0[1]);
    c->a = c->b = 0.0;
    return c->L > 1e-12 * (base_size(base) + fabs(d)) ? 0 : 1;
}

/* Purpose: the candidates' handle lengths: the quartic's, then the arc
 *          guess (4/3) tan(theta/4) R for the turn theta between the end
 *          tangents, in chord units (1/3 for a straight stretch).
 * Returns the number of pairs (>= 1). */
static int candidates(const ob_bez *base, double d, const co_cubic *c, double *as, double *bs)
{
    const double e[2] = {(c->P3[0] - c->P0[0]) / c->L, (c->P3[1] - c->P0[1]) / c->L};
    const double t0[2] = {dot2(c->T0, e), cross2(e, c->T0)}, t1[2] = {dot2(c->T1, e), cross2(e, c->T1)};
    double K[3], m[4][4], At, Mt;
    cubic_moments(t0, t1, K, m);
    offset_moments(base, d, c, &At, &Mt);
    int n = quartic_candidates(K, m, At, Mt, as, bs);
    const double th = atan2(cross2(t0, t1), dot2(t0, t1)), h = fabs(th) > 1e-6
        ? 4.0 / 3.0 * tan(fabs(th) / 4) / (2 * sin(fabs(th) / 2)) : 1.0 / 3.0;
    as[n] = bs[n] = h;
    return n + 1;
}

/* Purpose: the G1 cubic for the d-offset of a stretch without offset cusps.
 * Inputs:  hermite: 1 to skip the candidates (the fallback cubic).
 * Outputs: *out (a cubic Bézier), *est its own error estimate (0 for an
 *          offset that is a point; +inf for the fallback cubic, which is
 *          not scored).  Returns OB_FIT_OK, OB_FIT_RETRY_SMALLER or
 *          OB_FIT_FAIL with the reason in msg. */
static ob_fit_status fit_stretch(const ob_bez *base, double d, int ns, int refine_on, int hermite, co_work *W,
                                 ob_bez *out, double *est, char *msg, size_t msglen)
{
    co_cubic c;
    *est = INFINITY;
    const int reverses = base_size(base) > 0.0 ? sample_base(base, ns, W, msg, msglen) : -1;
    if (reverses < 0) {
        ob_method_msg(msg, msglen, "the base piece is a point");
        return OB_FIT_FAIL;
    }
    if (offset_ends(base, d, &c)) {
        /* a closed stretch, or an offset that collapses to a point (a
         * circle offset by its radius): the point itself is exact */
        double worst = 0.0;
        for (int j = 1; j <= ns; j++) {
            double o[2];
            ob_bez_offset_point(base, W->t[j], d, o);
            worst = fmax(worst, hypot(o[0] - c.P0[0], o[1] - c.P0[1]));
        }
        if (worst > 1e-12 * (base_size(base) + fabs(d))) {
            ob_method_msg(msg, msglen, "the offset's end points coincide (a closed piece)");
            return OB_FIT_RETRY_SMALLER;
        }
        c.L = 0.0;
        *est = 0.0;
    } else if (reverses || hermite) {
        c.a = c.b = 1.0 / 3.0;
    } else {
        double as[5], bs[5];
        co_err *E = &W->cur, *best = &W->best;
        const int n = candidates(base, d, &c, as, bs);
        best->max = INFINITY;
        double ba = as[0], bb = bs[0];
        for (int k = 0; k < n; k++) {
            c.a = as[k];
            c.b = bs[k];
            cubic_error(&c, W, ns, d, NULL, best->max, E);
            if (E->max < best->max) {
                *best = *E;
                ba = as[k];
                bb = bs[k];
            }
        }
        c.a = best->max < INFINITY ? ba : 1.0 / 3.0;
        c.b = best->max < INFINITY ? bb : 1.0 / 3.0;
        if (refine_on && best->max < INFINITY)
            refine(&c, W, ns, d, best, &W->trial);
        *est = best->max;
    }
    double P[4][2];
    cubic_points(&c, P);
    for (int i = 0; i < 4; i++)
        if (!isfinite(P[i][0]) || !isfinite(P[i][1])) {
            ob_method_msg(msg, msglen, "non-finite control point");
            return OB_FIT_FAIL;
        }
    ob_bez_from_points(out, 3, (const double(*)[2])P);
    return OB_FIT_OK;
}

/* ---- the fit's own split (parameter split) --------------------------------- */

enum { SPLIT_PROBES = 12 };
/* a piece's end is searched to this fraction of the piece */
static const double SPLIT_PREC = 1e-3;
/* the level the pieces' estimates are held to, as a fraction of tol: the
 * estimate samples the error along the normals at `samples` parameters and
 * can read its maximum a little low; at 0.99 tol almost every piece then
 * passes the driver's metric at the first measurement (at 1.0 tol, on
 * --random 200:5 at 1e-5, 71 of 313 jobs needed more pieces than greedy,
 * at 0.99 20, at 0.97 23: pieces shorter than they need be) */
static const double SPLIT_LEVEL = 0.99;

/* The fit (fit_stretch) of the piece [a, b] of base, the whole base when
 * that is [0, 1]. */
static ob_fit_status fit_piece(const ob_bez *base, double a, double b, double d, int ns, int refine_on, co_work *W,
                               ob_bez *seg, double *est, char *msg, size_t msglen)
{
    ob_bez sub;
    if (a == 0.0 && b == 1.0)
        sub = *base;
    else
        ob_bez_subsegment(base, a, b, &sub);
    return fit_stretch(&sub, d, ns, refine_on, 0, W, seg, est, msg, msglen);
}

/* The search for one piece's end: the longest passing length lo (its
 * error elo; 0 while none passed), the shortest failing one hi (ehi; +inf
 * while none failed), and the last two probes (h1, e1 the latest). */
typedef struct {
    double lo, elo, hi, ehi;
    double h0, e0, h1, e1;
} co_probes;

static void probe_record(co_probes *p, double h, double e, double tau)
{
    if (e <= tau) {
        p->lo = h;
        p->elo = e;
    } else {
        p->hi = h;
        p->ehi = e;
    }
    p->h0 = p->h1;
    p->e0 = p->e1;
    p->h1 = h;
    p->e1 = e;
}

/* Whether the search is done: the latest probe passed within the window
 * (its error at least (1 - 6 SPLIT_PREC) tau: under the c h^6 model within
 * SPLIT_PREC of the longest passing length), or the passing and failing
 * lengths are within SPLIT_PREC of each other. */
static int probes_done(const co_probes *p, double tau)
{
    if (p->lo > 0.0 && p->h1 == p->lo && p->elo >= (1.0 - 6.0 * SPLIT_PREC) * tau)
        return 1;
    return p->lo > 0.0 && p->hi - p->lo <= SPLIT_PREC * p->lo;
}

/* The next length to probe, aimed at the middle of the window, (1 - 3
 * SPLIT_PREC) tau, with the error modelled as c h^p: a secant in log-log
 * through the last two probes (p the order they show, taken when it is
 * 0.5 ... 50: away from the asymptotic regime the error grows slower or
 * faster than the G1 cubic's h^6, and a fixed order crept towards the end
 * a few per cent per probe there), else log-log interpolation between the
 * longest passing and the shortest failing length, else p = 6 from the
 * shortest failing one.  Kept at least a twentieth of the bracket inside
 * it. */
static double next_length(const co_probes *p, double tau)
{
    const double aim = (1.0 - 3.0 * SPLIT_PREC) * tau;
    double h = 0.5 * (p->lo + p->hi), q = 0.0;
    const int two = p->h0 > 0.0 && p->h0 != p->h1 && p->e0 > 0.0 && p->e1 > 0.0 && isfinite(p->e0) &&
                    isfinite(p->e1);
    if (two)
        q = log(p->e1 / p->e0) / log(p->h1 / p->h0);
    if (q >= 0.5 && q <= 50.0)
        h = p->h1 * pow(aim / p->e1, 1.0 / q);
    else if (p->lo > 0.0 && p->elo > 0.0 && isfinite(p->ehi))
        h = p->lo * pow(p->hi / p->lo, log(aim / p->elo) / log(p->ehi / p->elo));
    else if (isfinite(p->ehi) && p->ehi > 0.0)
        h = p->hi * pow(aim / p->ehi, 1.0 / 6.0);
    const double w = p->hi - p->lo, h0 = p->lo + 0.05 * w, h1 = p->hi - 0.05 * w;
    return isfinite(h) ? fmin(h1, fmax(h0, h)) : 0.5 * (p->lo + p->hi);
}

/* Purpose: cover the stretch [t0, t1] of base (no offset cusp inside) with
 *          the longest pieces, one after the other, whose own estimate is at
 *          most tau, appended to out.
 * Method:  for each piece from s: the rest [s, t1] first, then lengths from
 *          next_length until probes_done or after SPLIT_PROBES fits (a
 *          probe that asks for a smaller piece fails);
 *          where none passes, or the piece would be the last that room
 *          allows, the rest is one piece as it is: the driver's metric
 *          rejects it, and the driver's rule splits it or ends the job at an
 *          error floor, as for any method.
 * Inputs:  room: the most pieces this stretch may append (>= 1).
 * Returns  OB_FIT_OK; OB_FIT_FAIL, or OB_FIT_RETRY_SMALLER when the rest
 *          as one piece asks for it (a closed piece), with msg. */
static ob_fit_status split_stretch(const ob_bez *base, double t0, double t1, double d, int ns, int refine_on,
                                   double tau, int room, co_work *W, ob_fit *out, char *msg, size_t msglen)
{
    for (double s = t0; s < t1; room--) {
        ob_bez seg, okseg;
        co_probes p = {0.0, 0.0, t1 - s, INFINITY, 0.0, 0.0, 0.0, 0.0};
        double h = t1 - s, e;
        for (int k = 0; k < SPLIT_PROBES && room > 1; k++) {
            const double b = h == t1 - s ? t1 : s + h;
            ob_fit_status st = fit_piece(base, s, b, d, ns, refine_on, W, &seg, &e, msg, msglen);
            if (st == OB_FIT_RETRY_SMALLER)
                e = INFINITY;
            else if (st != OB_FIT_OK)
                return st;
            probe_record(&p, h, e, tau);
            if (e <= tau)
                okseg = seg;
            if ((e <= tau && b == t1) || probes_done(&p, tau))
                break;
            h = next_length(&p, tau);
        }
        if (p.lo == 0.0) {
            const ob_fit_status st = fit_piece(base, s, t1, d, ns, refine_on, W, &okseg, &e, msg, msglen);
            if (st != OB_FIT_OK)
                return st;
        }
        const double b = p.lo == 0.0 || s + p.lo >= t1 ? t1 : s + p.lo;
        out->seg[out->n] = okseg;
        out->t[++out->n] = b;
        s = b;
    }
    return OB_FIT_OK;
}

static ob_fit_status cubic_opt_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out, char *msg,
                                   size_t msglen)
{
    const int ns = (int)lround(a->par[CP_SAMPLES]), refine_on = a->par[CP_REFINE] != 0.0;
    const int own_split = a->par[CP_SPLIT] != 0.0;
    if (base->deg < 1) {
        ob_method_msg(msg, msglen, "degree %d: the base is a point", base->deg);
        return OB_FIT_SKIP;
    }
    if (ns < 8 || ns > CO_MAX_SAMPLES) {
        ob_method_msg(msg, msglen, "samples must be 8..%d", CO_MAX_SAMPLES);
        return OB_FIT_SKIP;
    }
    double tc[OB_MAX_PIECES];
    int nc = ob_bez_offset_cusps(base, a->d, tc, OB_MAX_PIECES - 1);
    const int hermite = nc > OB_MAX_PIECES - 1;  /* more cusps than pieces: round-off */
    if (hermite)
        nc = 0;
    out->n = 0;
    out->ctrl_points = 0;
    out->t[0] = 0.0;
    for (int i = 0; i <= nc; i++) {
        const double t1 = i == nc ? 1.0 : tc[i];
        if (t1 - out->t[out->n] < 1e-9 && i < nc)
            continue;  /* a cusp at an end or next to another: no sliver */
        ob_fit_status st;
        if (own_split && !hermite) {
            /* leave a piece for each stretch still to come */
            const int room = OB_MAX_PIECES - out->n - (nc - i);
            st = split_stretch(base, out->t[out->n], t1, a->d, ns, refine_on, SPLIT_LEVEL * a->tol, room, work, out,
                               msg, msglen);
        } else {
            ob_bez sub;
            double est;
            if (out->t[out->n] == 0.0 && t1 == 1.0)
                sub = *base;
            else
                ob_bez_subsegment(base, out->t[out->n], t1, &sub);
            st = fit_stretch(&sub, a->d, ns, refine_on, hermite, work, &out->seg[out->n], &est, msg, msglen);
            if (st == OB_FIT_OK)
                out->t[++out->n] = t1;
        }
        if (st != OB_FIT_OK)
            return st;
    }
    return OB_FIT_OK;
}

static int cubic_opt_uses_tol(const double *par) { return par[CP_SPLIT] != 0.0; }

const ob_method ob_method_cubic_opt = {
    .name = "cubic-opt",
    .version = 1,
    .citation = "G1 cubic offsets, area/moment candidates (kurbo 0.11) refined to the minimax along normals "
                "(offbench issue 19)",
    .continuity = "G1",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_CUSP_BREAKS | OB_CAP_INTERP_ENDS,
    .max_turn = 0.0,
    .out_degree = ob_degree_three,
    .cost_ms = 1.4, /* tiller's 2.06 scaled by their ratio on --random 40:2026 */
    .work_size = sizeof(co_work),
    .params = cubic_opt_params,
    .nparams = CP_COUNT,
    .fit_uses_tol = cubic_opt_uses_tol,
    .fit = cubic_opt_fit,
};
