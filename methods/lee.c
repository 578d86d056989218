/*
 * lee.c - Lee, Kim & Elber 1996, "Planar curve offset based on circle
 * approximation", Computer-Aided Design 28(8):617-630 ("M2" in Ahn 2023,
 * Tables 1-2; "Lee's" in Zhao & Zhou 2017, Table 1).
 *
 * The offset C + d N is the convolution of C with the circle of radius |d|.
 * The circle is replaced by quadratic (polynomial) Bézier arcs Q within the
 * tolerance, and each part of C is convolved with the arc that covers its
 * normal directions: for the arc Q(s) = q0 (1-s)^2 + 2 q1 s (1-s) + q2 s^2 the
 * point with tangent parallel to C'(t) solves (1-s) a + s b = 0 with
 * a = (q1-q0) x C'(t), b = (q2-q1) x C'(t), i.e. s(t) = a / (a - b), and the
 * approximation is
 *     A(t) = C(t) + Q(s(t)) = [C (a-b)^2 + q0 b^2 - 2 q1 a b + q2 a^2] / (a-b)^2.
 * For a polynomial C of degree n, a and b have degree n-1 and A is a rational
 * Bézier of degree 3n-2 (7 for a cubic: Ahn's Table 1 counts 7k+1).  For a
 * rational C = P/w the direction of C' is P'w - Pw' (degree 2n-2) and
 * A = [P (a-b)^2 + w (q0 b^2 - 2 q1 a b + q2 a^2)] / [w (a-b)^2], degree 5n-4.
 * A shares C's parameter t, and |A(t) - C(t)| = |Q(s(t))|, so the offset error
 * (radial) is at most the circle approximation error.
 *
 * Pieces: the fit splits its base piece at the parameters where d N(t)
 * crosses an arc boundary (roots of C'(t) . u_j for the boundary direction
 * u_j, kept where d N points along +u_j) and writes one rational piece per
 * part, with its t breakpoints; more than OB_SPLIT_PIECES parts give
 * OB_FIT_RETRY_SMALLER.  The error does not depend on the size of the base piece,
 * only on the circle approximation, which depends on the tolerance.
 *
 * Readings (the paper itself is not among the sources here; see the params):
 *  - arcs of the circle: the quadratic that interpolates the circle at the
 *    arc's ends with the intersection of the end tangents as middle control
 *    point (Ahn 2023 describes Lee's quadratics as interpolating the normal
 *    field); its radius grows from r at the ends to r (1 + e) at the middle,
 *    e = (1 - cos h)^2 / (2 cos h) for the half angle h;
 *  - the whole circle is cut into the fewest equal arcs whose error r e is at
 *    most tol_frac * tol, the first boundary at angle `start` (0: the x axis);
 *  - tol_frac = 1: the circle error is the offset error (our choice);
 *  - clip = 0: a part is convolved with its whole arc, also where the piece
 *    ends inside the arc.  Then the piece's end point is C + Q(s) with Q(s)
 *    the arc point whose tangent is parallel to C', which is off the offset's
 *    end C + d N along the tangent by up to about 0.19 |d| h^3, while the
 *    radial error is |d| h^4/8: the radial and bound metrics (the papers'
 *    measures) see the circle error, the per-piece hausdorff metric sees the
 *    end shift, which no subdivision removes (the driver ends at its limits).
 *    clip = 1 uses the sub-arc that the part's normals cover instead, so
 *    every piece interpolates the offset at its ends: same breakpoints, error
 *    at most the circle error under every metric (regular offsets).
 */
#include "methods/method.h"

#include <math.h>
#include <string.h>

#include "methods/core/bernstein.h"

enum { P_FRAC, P_ARC, P_ARCS_ON, P_START, P_CLIP, NPARAM };

static const ob_param lee_params[NPARAM] = {
    {"tol_frac", 1.0,
     "the circle approximation error is at most tol_frac * tol (the job's tolerance); "
     "1 is our choice (no fraction is given in the sources here): the offset error is "
     "then at most tol", 1e-6, 1e6, 0},
    {"arc", 0.0,
     "0: each arc is the quadratic Bezier interpolating the circle at its ends, middle "
     "control point at the tangent intersection (error r(1-cos h)^2/(2 cos h), h the half "
     "angle; the natural reading, Ahn 2023 calls Lee's quadratics interpolating); 1: that "
     "quadratic scaled about the centre by 2/(2+e) so the radial error equioscillates "
     "(error r e/(2+e), the best radial approximation in this family)", 0, 1, 1},
    {"arcs_on", 0.0,
     "0: the whole circle is cut once into the fewest equal arcs meeting the tolerance, "
     "independent of the curve (our reading of approximating the circle); 1: each piece's "
     "own range of normal directions is cut into the fewest equal arcs, from its lowest "
     "normal angle (the arcs then differ between driver pieces; their ends interpolate the "
     "offset where the normal turns one way)", 0, 1, 1},
    {"start", 0.0,
     "arcs_on=0: angle in radians of the first arc boundary, for the offset vector d N "
     "(0 = the positive x direction; our choice)", -1e3, 1e3, 0},
    {"clip", 0.0,
     "arcs_on=0: 0: each part is convolved with its whole arc of the circle approximation "
     "(the circle approximated once: Lee, Kim & Elber 1996 as Ahn 2023 describes it, default); 1: with the interpolating quadratic of the sub-arc that the part's normals "
     "cover, so every piece interpolates the offset at its ends (with 0 a piece end inside an "
     "arc is off the offset's end by O(h^3) along the tangent, which the per-piece hausdorff "
     "metric sees and no subdivision removes)", 0, 1, 1},
};

static int lee_degree(int n, int rational_in, const double *par)
{
    (void)par;
    return rational_in ? 5 * n - 4 : 3 * n - 2;
}

static double cross2(const double u[2], const double v[2]) { return u[0] * v[1] - u[1] * v[0]; }

/* The relative radial error e of the interpolating quadratic for half angle h
 * (0 < h < pi/2), and of the scaled ("best") one. */
static double arc_error(double h, int best)
{
    const double s = sin(0.5 * h), omc = 2.0 * s * s, c = cos(h);  /* omc = 1 - cos h */
    const double e = omc * omc / (2.0 * c);
    return best ? e / (2.0 + e) : e;
}

/* The largest half angle h with arc_error(h) <= eps (relative to r). */
static double max_half_angle(double eps, int best)
{
    if (best) {
        if (eps >= 1.0)
            return OB_PI / 3.0;
        eps = 2.0 * eps / (1.0 - eps);  /* e/(2+e) <= eps  <=>  e <= 2 eps/(1-eps) */
    }
    /* (1-c)^2 = 2 eps c:  1 - c = sqrt(eps^2 + 2 eps) - eps = 2 eps/(sqrt(eps^2+2eps) + eps) */
    const double omc = 2.0 * eps / (sqrt(eps * eps + 2.0 * eps) + eps);
    double h = 2.0 * asin(sqrt(fmin(1.0, 0.5 * omc)));
    return fmin(h, OB_PI / 3.0);
}

/* Fewest equal arcs with half angle total/(2m) meeting eps; total in (0, 2 pi]. */
static long arc_count(double total, double eps, int best, long mmin)
{
    const double h = max_half_angle(eps, best);
    double est = ceil(0.5 * total / h);
    if (!(est < 2e6))
        return -1;
    long m = (long)est;
    if (m < mmin)
        m = mmin;
    while (arc_error(0.5 * total / m, best) > eps && m < 2000000)
        m++;
    while (m > mmin && 0.5 * total / (m - 1) <= OB_PI / 3.0 &&
           arc_error(0.5 * total / (m - 1), best) <= eps)
        m--;
    return m < 2000000 ? m : -1;
}

/* Direction of C' (any positive multiple) in Bernstein form; returns its degree.
 * Polynomial: n (P_{k+1} - P_k), degree n-1.  Rational: P'w - Pw', degree
 * 2n-2, by the exact formula sum_{i<j} (j-i) C(n,i) C(n,j)/C(2n-2,i+j-1)
 * (P_j w_i - P_i w_j) B_{i+j-1}^{2n-2} (homogeneous P, no cancellation). */
static int hodograph(const ob_bez *b, double (*H)[2])
{
    const int n = b->deg;
    if (!b->rational) {
        for (int k = 0; k < n; k++) {
            H[k][0] = n * (b->h[k + 1][0] - b->h[k][0]);
            H[k][1] = n * (b->h[k + 1][1] - b->h[k][1]);
        }
        return n - 1;
    }
    const int m = 2 * n - 2;
    for (int k = 0; k <= m; k++)
        H[k][0] = H[k][1] = 0.0;
    for (int i = 0; i <= n; i++)
        for (int j = i + 1; j <= n; j++) {
            const int k = i + j - 1;
            const double f = (j - i) * ob_binom(n, i) * ob_binom(n, j) / ob_binom(m, k);
            for (int c = 0; c < 2; c++)
                H[k][c] += f * (b->h[j][c] * b->h[i][2] - b->h[i][c] * b->h[j][2]);
        }
    return m;
}

static void hod_eval(const double (*H)[2], int m, double t, double v[2])
{
    double x[OB_BERN_MAX + 1], y[OB_BERN_MAX + 1];
    for (int k = 0; k <= m; k++) {
        x[k] = H[k][0];
        y[k] = H[k][1];
    }
    v[0] = ob_bern_eval(x, m, t);
    v[1] = ob_bern_eval(y, m, t);
}

/* Angle of the offset vector sign(d) (-y', x') at t. */
static double offset_angle(const double (*H)[2], int m, double t, double sd)
{
    double v[2];
    hod_eval(H, m, t, v);
    return atan2(sd * v[0], -sd * v[1]);
}

/* A(t) = C(t) + Q(s(t)) for the arc q[0..2] (see the header).  Returns 0, or -1
 * if a - b vanishes on [0,1] (the normal leaves the arc's range). */
static int convolve(const ob_bez *b, const double q[3][2], ob_bez *out)
{
    double H[2 * OB_MAX_DEG + 1][2];
    const int n = b->deg, mh = hodograph(b, H), m2 = 2 * mh, deg = n + m2;
    double A[OB_BERN_MAX + 1], B[OB_BERN_MAX + 1], C[OB_BERN_MAX + 1];
    const double e0[2] = {q[1][0] - q[0][0], q[1][1] - q[0][1]};
    const double e1[2] = {q[2][0] - q[1][0], q[2][1] - q[1][1]};
    for (int k = 0; k <= mh; k++) {
        A[k] = cross2(e0, H[k]);
        B[k] = cross2(e1, H[k]);
        C[k] = A[k] - B[k];
    }
    double roots[4];
    const double c0 = ob_bern_eval(C, mh, 0.0), c1 = ob_bern_eval(C, mh, 1.0);
    if (!(c0 * c1 > 0.0) || ob_bern_roots(C, mh, roots, 4) > 0)
        return -1;
    double CC[OB_BERN_MAX + 1], AA[OB_BERN_MAX + 1], AB[OB_BERN_MAX + 1], BB[OB_BERN_MAX + 1];
    ob_bern_mul(C, mh, C, mh, CC);
    ob_bern_mul(A, mh, A, mh, AA);
    ob_bern_mul(A, mh, B, mh, AB);
    ob_bern_mul(B, mh, B, mh, BB);
    double num[2][OB_BERN_MAX + 1];
    for (int k = 0; k <= m2; k++)
        for (int c = 0; c < 2; c++)
            num[c][k] = q[0][c] * BB[k] - 2.0 * q[1][c] * AB[k] + q[2][c] * AA[k];
    double X[3][OB_BERN_MAX + 1], tmp[OB_BERN_MAX + 1], P[OB_MAX_DEG + 1];
    for (int c = 0; c < 2; c++) {
        for (int i = 0; i <= n; i++)
            P[i] = b->h[i][c];
        ob_bern_mul(P, n, CC, m2, X[c]);
        if (b->rational) {
            for (int i = 0; i <= n; i++)
                P[i] = b->h[i][2];
            ob_bern_mul(P, n, num[c], m2, tmp);
        } else {
            ob_bern_elevate(num[c], m2, deg, tmp);
        }
        for (int k = 0; k <= deg; k++)
            X[c][k] += tmp[k];
    }
    if (b->rational) {
        for (int i = 0; i <= n; i++)
            P[i] = b->h[i][2];
        ob_bern_mul(P, n, CC, m2, X[2]);
    } else {
        ob_bern_elevate(CC, m2, deg, X[2]);
    }
    double big = 0.0;
    for (int k = 0; k <= deg; k++)
        big = fmax(big, fabs(X[2][k]));
    if (!(big > 0.0) || !isfinite(big))
        return -1;
    memset(out, 0, sizeof *out);
    out->deg = deg;
    out->rational = 1;
    for (int k = 0; k <= deg; k++)
        for (int c = 0; c < 3; c++)
            out->h[k][c] = X[c][k] / big;
    return 0;
}

/* A translate C + v of b, written with degree deg (a zero-angle arc). */
static void translate(const ob_bez *b, const double v[2], int deg, ob_bez *out)
{
    ob_bez_elevate(b, deg, out);
    for (int k = 0; k <= deg; k++) {
        out->h[k][0] += out->h[k][2] * v[0];
        out->h[k][1] += out->h[k][2] * v[1];
    }
    out->rational = 1;
}

/* Lowest and highest unwrapped offset angle over [0,1], relative to t = 0:
 * samples plus the inflections (where the angle turns back). */
static void angle_range(const ob_bez *b, const double (*H)[2], int mh, double sd, double *lo,
                        double *hi)
{
    enum { NS = 256 };
    double ts[NS + 1 + 64];
    int nt = 0;
    for (int k = 0; k <= NS; k++)
        ts[nt++] = (double)k / NS;
    double inf[64];
    int ni = ob_bez_inflections(b, inf, 64);
    for (int i = 0; i < ni; i++) {  /* insert in order */
        int p = nt++;
        while (p > 0 && ts[p - 1] > inf[i]) {
            ts[p] = ts[p - 1];
            p--;
        }
        ts[p] = inf[i];
    }
    double prev = offset_angle(H, mh, 0.0, sd), acc = 0.0;
    *lo = *hi = 0.0;
    for (int i = 1; i < nt; i++) {
        double a = offset_angle(H, mh, ts[i], sd), da = a - prev;
        da -= 2.0 * OB_PI * floor((da + OB_PI) / (2.0 * OB_PI));
        acc += da;
        prev = a;
        *lo = fmin(*lo, acc);
        *hi = fmax(*hi, acc);
    }
}

enum { MAXCROSS = 4 * OB_SPLIT_PIECES };

/* What one fit reads of its inputs, once: the distance, the parameters and
 * the direction of C' (H, degree mh: hodograph). */
typedef struct {
    double r, sd;              /* |d|, sign(d) */
    int outdeg;
    double start, eps;         /* eps: the circle's error allowed, relative to r */
    int best, on_piece, clip;
    double H[2 * OB_MAX_DEG + 1][2];
    int mh;
} lee_in;

/* The arcs of one fit: m arcs of angle delta from psi0; the boundaries
 * psi0 + j delta, j = jlo..jhi-1, are the ones tested for crossings.
 * straight: the piece's normal does not turn (arcs_on=1) and the fit, the
 * exact translate, is already written. */
typedef struct {
    long m, jlo, jhi;
    double psi0, delta, width;
    int straight;
} lee_arcs;

/* The parameters and inputs checked and read into L.  OB_FIT_OK, or OB_FIT_SKIP /
 * OB_FIT_FAIL with the reason in msg. */
static ob_fit_status lee_read(const ob_bez *base, const ob_fit_args *a, lee_in *L, char *msg, size_t msglen)
{
    const double d = a->d, r = fabs(d), sd = d > 0 ? 1.0 : -1.0;
    const int n = base->deg, outdeg = lee_degree(n, base->rational, a->par);
    const double frac = a->par[P_FRAC], start = a->par[P_START];
    const int best = a->par[P_ARC] != 0.0, on_piece = a->par[P_ARCS_ON] != 0.0;
    const int clip = !on_piece && a->par[P_CLIP] != 0.0;
    if (!(r > 0.0) || !isfinite(d)) {
        ob_method_msg(msg, msglen, "offset distance d = %g: no circle to approximate", d);
        return OB_FIT_SKIP;
    }
    if (n < 1 || outdeg > OB_MAX_DEG || outdeg > OB_BERN_MAX) {
        ob_method_msg(msg, msglen, "output degree %d for input degree %d exceeds %d", outdeg, n,
                      OB_MAX_DEG);
        return OB_FIT_SKIP;
    }
    if (!(a->tol > 0.0) || !(frac > 0.0) || !isfinite(start)) {
        ob_method_msg(msg, msglen, "needs tol > 0 and tol_frac > 0 (tol %g, tol_frac %g)",
                      a->tol, frac);
        return OB_FIT_FAIL;
    }
    L->r = r;
    L->sd = sd;
    L->outdeg = outdeg;
    L->start = start;
    L->best = best;
    L->on_piece = on_piece;
    L->clip = clip;
    L->eps = frac * a->tol / r;
    L->mh = hodograph(base, L->H);
    return OB_FIT_OK;
}

/* The arcs: the whole circle from `start` (arcs_on=0), or the piece's own
 * range of normal angles (arcs_on=1; a straight piece gets its translate in
 * out at once).  OB_FIT_OK, OB_FIT_RETRY_SMALLER (the normal turns by 2 pi or more)
 * or OB_FIT_FAIL (too many arcs), with the reason in msg. */
static ob_fit_status lee_plan_arcs(const ob_bez *base, double tol, const lee_in *L, lee_arcs *A, ob_fit *out,
                                   char *msg, size_t msglen)
{
    const double (*H)[2] = (const double (*)[2])L->H;
    A->width = 2.0 * OB_PI;
    A->straight = 0;
    if (!L->on_piece) {
        A->m = arc_count(2.0 * OB_PI, L->eps, L->best, 3);
        A->psi0 = L->start;
        A->jlo = 0;
        A->jhi = A->m;
    } else {
        double lo, hi;
        angle_range(base, H, L->mh, L->sd, &lo, &hi);
        A->width = hi - lo;
        if (A->width >= 2.0 * OB_PI - 1e-9) {
            ob_method_msg(msg, msglen, "the normal turns by %.3g >= 2 pi in this piece", A->width);
            return OB_FIT_RETRY_SMALLER;
        }
        A->psi0 = offset_angle(H, L->mh, 0.0, L->sd) + lo;
        if (A->width < 1e-12) {  /* straight: a zero-angle arc, the exact translate */
            const double v[2] = {L->r * cos(A->psi0), L->r * sin(A->psi0)};
            ob_bez t;
            translate(base, v, L->outdeg, &t);
            ob_fit_single(out, &t);
            A->straight = 1;
            return OB_FIT_OK;
        }
        A->m = arc_count(A->width, L->eps, L->best, 1);
        A->jlo = 1;
        A->jhi = A->m;
    }
    if (A->m < 1) {
        ob_method_msg(msg, msglen, "tolerance %g too small for |d| = %g (2e6 arcs or more)", tol, L->r);
        return OB_FIT_FAIL;
    }
    A->delta = A->width / (double)A->m;
    return OB_FIT_OK;
}

/* The parameters in (0,1) where d N crosses a tested arc boundary (along
 * +u_j), ascending, into cut[0..*nc-1].  OB_FIT_OK, or OB_FIT_RETRY_SMALLER past
 * MAXCROSS crossings. */
static ob_fit_status lee_crossings(const lee_in *L, const lee_arcs *A, double *cut, int *nc, char *msg,
                                   size_t msglen)
{
    const double (*H)[2] = (const double (*)[2])L->H;
    const int mh = L->mh;
    *nc = 0;
    for (long j = A->jlo; j < A->jhi; j++) {
        const double ang = A->psi0 + (double)j * A->delta, u[2] = {cos(ang), sin(ang)};
        double p[2 * OB_MAX_DEG + 1];
        int pos = 0, neg = 0;
        for (int k = 0; k <= mh; k++) {
            p[k] = H[k][0] * u[0] + H[k][1] * u[1];
            pos |= p[k] > 0.0;
            neg |= p[k] < 0.0;
        }
        if (!(pos && neg))
            continue;
        double rt[2 * OB_MAX_DEG + 1];
        int nr = ob_bern_roots(p, mh, rt, 2 * OB_MAX_DEG + 1);
        for (int i = 0; i < nr; i++) {
            if (rt[i] < 1e-9 || rt[i] > 1.0 - 1e-9)
                continue;
            double v[2];
            hod_eval(H, mh, rt[i], v);
            if (L->sd * (v[0] * u[1] - v[1] * u[0]) <= 0.0)  /* d N = sd (-v_y, v_x)/|v| along -u */
                continue;
            if (*nc == MAXCROSS) {
                ob_method_msg(msg, msglen, "the normal crosses more than %d arc boundaries "
                              "(%ld arcs)", MAXCROSS, A->m);
                return OB_FIT_RETRY_SMALLER;
            }
            int q = (*nc)++;  /* insertion, ascending */
            while (q > 0 && cut[q - 1] > rt[i]) {
                cut[q] = cut[q - 1];
                q--;
            }
            cut[q] = rt[i];
        }
    }
    return OB_FIT_OK;
}

/* Breakpoints 0 = tb[0] < ... < tb[k] = 1 from the crossings cut[0..nc-1],
 * dropping near duplicates; returns k + 1. */
static int lee_breakpoints(const double *cut, int nc, double *tb)
{
    int nt = 0;
    tb[nt++] = 0.0;
    for (int i = 0; i < nc; i++)
        if (cut[i] - tb[nt - 1] > 1e-12 && 1.0 - cut[i] > 1e-12)
            tb[nt++] = cut[i];
    tb[nt++] = 1.0;
    return nt;
}

/* The index of the arc that holds the offset angle at tm. */
static long lee_arc_index(const lee_in *L, const lee_arcs *A, double tm)
{
    double x = offset_angle((const double (*)[2])L->H, L->mh, tm, L->sd) - A->psi0;
    x -= 2.0 * OB_PI * floor(x / (2.0 * OB_PI));   /* [0, 2 pi) */
    if (L->on_piece && x > 0.5 * (A->width + 2.0 * OB_PI))
        x -= 2.0 * OB_PI;                           /* just below the range */
    long j = (long)floor(x / A->delta);
    if (j < 0)
        j = 0;
    if (j > A->m - 1)
        j = A->m - 1;
    return j;
}

/* clip=1: the part [*a0, *a1] of the arc (radius rr at its ends, *rmid at
 * its middle control point) that the normals of sub cover.  Returns 1 when
 * that is a zero-angle arc, and then writes sub's translate into seg. */
static int lee_clip_arc(const ob_bez *sub, const lee_in *L, double delta, double rr, double *a0, double *a1,
                        double *rmid, ob_bez *seg)
{
    double Hs[2 * OB_MAX_DEG + 1][2], lo, hi;
    const int ms = hodograph(sub, Hs);
    angle_range(sub, (const double (*)[2])Hs, ms, L->sd, &lo, &hi);
    double x0 = offset_angle((const double (*)[2])Hs, ms, 0.0, L->sd) - *a0;
    x0 -= 2.0 * OB_PI * floor((x0 + OB_PI) / (2.0 * OB_PI));  /* [-pi, pi) */
    const double b0 = fmax(0.0, x0 + lo), b1 = fmin(delta, x0 + hi);
    if (!(b1 - b0 > 1e-12)) {  /* a zero-angle arc: the translate */
        const double am = *a0 + 0.5 * (b0 + b1), v[2] = {rr * cos(am), rr * sin(am)};
        translate(sub, v, L->outdeg, seg);
        return 1;
    }
    *a1 = *a0 + b1;
    *a0 += b0;
    *rmid = rr / cos(0.5 * (*a1 - *a0));
    return 0;
}

/* Piece i of np, over [tb[i], tb[i+1]]: the part of base convolved with the
 * arc that covers its normals (radius rr, middle control point at rm), into
 * seg.  OB_FIT_OK, or OB_FIT_RETRY_SMALLER where the normal leaves the arc. */
static ob_fit_status lee_piece(const ob_bez *base, const lee_in *L, const lee_arcs *A, const double *tb, int i,
                               int np, double rr, double rm, ob_bez *seg, char *msg, size_t msglen)
{
    const double tm = 0.5 * (tb[i] + tb[i + 1]);
    const long j = lee_arc_index(L, A, tm);
    double a0 = A->psi0 + (double)j * A->delta, a1 = a0 + A->delta, rmid = rm;
    ob_bez sub;
    if (np == 1)
        sub = *base;
    else
        ob_bez_subsegment(base, tb[i], tb[i + 1], &sub);
    if (L->clip && lee_clip_arc(&sub, L, A->delta, rr, &a0, &a1, &rmid, seg))
        return OB_FIT_OK;
    const double am = 0.5 * (a0 + a1);
    const double q[3][2] = {{rr * cos(a0), rr * sin(a0)},
                            {rmid * cos(am), rmid * sin(am)},
                            {rr * cos(a1), rr * sin(a1)}};
    if (convolve(&sub, q, seg) != 0) {
        ob_method_msg(msg, msglen, "the normal leaves arc %ld within t in [%.6g, %.6g] "
                      "(a cusp?)", j, tb[i], tb[i + 1]);
        return OB_FIT_RETRY_SMALLER;
    }
    return OB_FIT_OK;
}

static ob_fit_status lee_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                             char *msg, size_t msglen)
{
    (void)work;
    lee_in L;
    lee_arcs A;
    ob_fit_status st = lee_read(base, a, &L, msg, msglen);
    if (st != OB_FIT_OK)
        return st;
    st = lee_plan_arcs(base, a->tol, &L, &A, out, msg, msglen);
    if (st != OB_FIT_OK || A.straight)
        return st;
    double cut[MAXCROSS + 2], tb[MAXCROSS + 2];
    int nc;
    st = lee_crossings(&L, &A, cut, &nc, msg, msglen);
    if (st != OB_FIT_OK)
        return st;
    const int np = lee_breakpoints(cut, nc, tb) - 1;
    if (np > OB_SPLIT_PIECES) {
        ob_method_msg(msg, msglen, "%d arcs of the circle meet this piece (at most %d pieces)",
                      np, OB_SPLIT_PIECES);
        return OB_FIT_RETRY_SMALLER;
    }
    const double lam = L.best ? 2.0 / (2.0 + arc_error(0.5 * A.delta, 0)) : 1.0;
    const double rr = lam * L.r, rm = rr / cos(0.5 * A.delta);
    out->n = np;
    out->ctrl_points = 0;
    for (int i = 0; i <= np; i++)
        out->t[i] = tb[i];
    for (int i = 0; i < np; i++) {
        st = lee_piece(base, &L, &A, tb, i, np, rr, rm, &out->seg[i], msg, msglen);
        if (st != OB_FIT_OK)
            return st;
    }
    return OB_FIT_OK;
}

const ob_method ob_method_lee = {
    .name = "lee",
    .version = 1,
    .citation = "Lee, Kim & Elber 1996, Planar curve offset based on circle approximation, "
                "CAD 28(8):617-630",
    .continuity = "G1",
    .caps = OB_CAP_RATIONAL_OUT | OB_CAP_RATIONAL_IN | OB_CAP_SAME_PARAM | OB_CAP_TOL_DRIVEN,
    .max_turn = 0.0,
    .out_degree = lee_degree,
    .cost_ms = 8.02,
    .work_size = 0,
    .params = lee_params,
    .nparams = NPARAM,
    .fit_uses_tol = ob_fit_uses_tol_always, /* the circle is approximated to tol */
    .fit = lee_fit,
};
