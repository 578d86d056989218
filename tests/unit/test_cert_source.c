/*
 * test_cert_source.c - the certificate is of the curve as stored (issue 47,
 * item 0): a job's base piece is a stored segment over the exact parameter
 * range [a + (b - a) t0, a + (b - a) t1], not the piece cut out of it in
 * floating point.  On a piece with legs near 1e-13 the cut's rounding
 * (eps |P| ~ 1e-16 per control point) turns its tangent by ~1e-3, so the
 * offset of the cut swings through a fan (d x 1e-3 wide) the true offset
 * does not have; a zero of C' (a cusp, a collapsed end leg) can be rounded
 * away, and the enclosure then "proves" a bound that is false.
 *
 * Every case is checked against a brute force written here that shares no
 * code with the library: the stored segment in binary128 (__float128, 113
 * bits: a leg of 1e-13 keeps 1e-21 of its direction), its hodograph for C',
 * the parameter mapped exactly, points moved to a local origin before they
 * are rounded to double, then dense two-sided sampling with golden-section
 * refinement of both the inner minimum and the outer supremum.  Its value B
 * is a distance attained by a refined point, so up to the refinement it is
 * at most the true H, and it misses the sup by what the samples miss.
 * Checked: B <= err_upper (1 + 1e-9) (never a false bound), err_lower <=
 * B (1 + 1e-6) (never a lower bound above an attained distance, beyond the
 * brute force's own refinement), and where C' vanishes on the piece,
 * err_upper = +inf (no bound exists: the offset is not continuous there).
 * Each case in both modes: tight (rtol) and verdict (a tol to decide).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/core/curve.h"
#include "methods/metrics/cert_curve.h"
#include "methods/metrics/cert_job.h"
#include "methods/metrics/metric_certified.h"
#include "tests/check.h"

/* ---- the brute force: binary128, no library code ----------------------- */

typedef __float128 qd;

static qd qsqrt(qd x)
{
    if (!(x > 0))
        return 0;
    qd y = (qd)sqrt((double)x);
    for (int i = 0; i < 3; i++)
        y = 0.5Q * (y + x / y);
    return y;
}

/* Bernstein sum of coordinate c of the n + 1 values v[i][c] at u */
static qd bsum(int n, const double (*v)[3], int c, qd u)
{
    qd w[16] = {0};
    for (int i = 0; i <= n; i++)
        w[i] = v[i][c];
    for (int r = 1; r <= n; r++)
        for (int i = 0; i <= n - r; i++)
            w[i] = (1 - u) * w[i] + u * w[i + 1];
    return w[0];
}

/* the stored segment at u: point and first derivative (quotient rule on the
 * homogeneous hodograph) */
static void seg_jet(const ob_bez *b, qd u, qd P[2], qd D[2])
{
    const int n = b->deg;
    qd X[3], dX[3];
    for (int c = 0; c < 3; c++) {
        X[c] = b->rational || c < 2 ? bsum(n, b->h, c, u) : 1;
        /* n (h[i+1] - h[i]) in binary128: exact for binary64 inputs */
        qd w[16] = {0};
        for (int i = 0; i < n; i++)
            w[i] = ((qd)b->h[i + 1][c] - (qd)b->h[i][c]) * n;
        if (!b->rational && c == 2)
            for (int i = 0; i < n; i++)
                w[i] = 0;
        for (int r = 1; r < n; r++)
            for (int i = 0; i < n - r; i++)
                w[i] = (1 - u) * w[i] + u * w[i + 1];
        dX[c] = n > 0 ? w[0] : 0;
    }
    for (int c = 0; c < 2; c++) {
        P[c] = X[c] / X[2];
        D[c] = (dX[c] * X[2] - X[c] * dX[2]) / (X[2] * X[2]);
    }
}

typedef struct {
    const ob_bez *seg;  /* offset: the stored segment; else NULL */
    const ob_bez *A;    /* not offset: the approximation */
    qd u0, du, d;
    qd org[2];          /* the local origin */
} qcurve;

/* the curve at s in [0, 1], relative to the origin, rounded to double */
static void qpoint(const qcurve *q, qd s, double p[2])
{
    qd P[2], D[2];
    if (q->seg) {
        qd u = q->u0 + q->du * s;
        seg_jet(q->seg, u, P, D);
        qd sp = qsqrt(D[0] * D[0] + D[1] * D[1]);
        if (!(sp > 0)) {  /* an exact zero of C': the limit from inside the piece */
            u = q->u0 + q->du * (s > 0.5Q ? s - 1e-25Q : s + 1e-25Q);
            seg_jet(q->seg, u, P, D);
            sp = qsqrt(D[0] * D[0] + D[1] * D[1]);
        }
        P[0] -= q->d * D[1] / sp;
        P[1] += q->d * D[0] / sp;
    } else {
        seg_jet(q->A, s, P, D);
    }
    p[0] = (double)(P[0] - q->org[0]);
    p[1] = (double)(P[1] - q->org[1]);
}

enum { NS = 4000, TOPS = 10 };

/* min over the table of |p - Q(t_i)|, and its row */
static double table_min(const double (*tab)[2], const double p[2], int *k)
{
    double best = INFINITY;
    for (int i = 0; i <= NS; i++) {
        const double e = hypot(p[0] - tab[i][0], p[1] - tab[i][1]);
        if (e < best)
            best = e, *k = i;
    }
    return best;
}

/* distance from p to the chord q0 q1 */
static double chord_dist(const double p[2], const double q0[2], const double q1[2])
{
    const double vx = q1[0] - q0[0], vy = q1[1] - q0[1], l2 = vx * vx + vy * vy;
    double t = l2 > 0 ? ((p[0] - q0[0]) * vx + (p[1] - q0[1]) * vy) / l2 : 0.0;
    t = fmin(fmax(t, 0.0), 1.0);
    return hypot(p[0] - q0[0] - t * vx, p[1] - q0[1] - t * vy);
}

/* min over t of |p - Q(t)|, to rank the candidates: the polygon of the
 * table near its nearest row (off by the chords' sagitta, ~h^2 kappa / 8) */
static double polygon_min(const double (*tab)[2], const double p[2])
{
    int k = 0;
    double best = table_min(tab, p, &k);
    if (k > 0)
        best = fmin(best, chord_dist(p, tab[k - 1], tab[k]));
    if (k < NS)
        best = fmin(best, chord_dist(p, tab[k], tab[k + 1]));
    return best;
}

/* min over t of |p - Q(t)|: the nearest of the table, refined by golden
 * section over its two neighbouring intervals */
static double inner_min(const qcurve *Q, const double (*tab)[2], const double p[2])
{
    int k = 0;
    const double best = table_min(tab, p, &k);
    qd a = (qd)(k > 0 ? k - 1 : 0) / NS, b = (qd)(k < NS ? k + 1 : NS) / NS;
    const qd g = 0.6180339887498948482045868343656Q;
    qd x1 = b - g * (b - a), x2 = a + g * (b - a);
    double q1[2], q2[2];
    qpoint(Q, x1, q1), qpoint(Q, x2, q2);
    double f1 = hypot(p[0] - q1[0], p[1] - q1[1]), f2 = hypot(p[0] - q2[0], p[1] - q2[1]);
    for (int it = 0; it < 64; it++) {
        if (f1 <= f2) {
            b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a);
            qpoint(Q, x1, q1), f1 = hypot(p[0] - q1[0], p[1] - q1[1]);
        } else {
            a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a);
            qpoint(Q, x2, q2), f2 = hypot(p[0] - q2[0], p[1] - q2[1]);
        }
    }
    return fmin(best, fmin(f1, f2));
}

/* sup over s of min over t |P(s) - Q(t)|: the samples, then golden section
 * around the TOPS largest */
static double one_side(const qcurve *P, const qcurve *Q)
{
    double(*tab)[2] = malloc((NS + 1) * sizeof *tab);
    double *f = malloc((NS + 1) * sizeof *f);
    for (int i = 0; i <= NS; i++)
        qpoint(Q, (qd)i / NS, tab[i]);
    for (int i = 0; i <= NS; i++) {
        double p[2];
        qpoint(P, (qd)i / NS, p);
        f[i] = polygon_min((const double(*)[2])tab, p);  /* ranks the candidates */
    }
    double B = 0;
    for (int top = 0; top < TOPS; top++) {
        int j = 0;
        for (int i = 1; i <= NS; i++)
            if (f[i] > f[j])
                j = i;
        if (!(f[j] >= 0))
            break;
        double pj[2];
        qpoint(P, (qd)j / NS, pj);
        B = fmax(B, inner_min(Q, (const double(*)[2])tab, pj));
        qd a = (qd)(j > 0 ? j - 1 : 0) / NS, b = (qd)(j < NS ? j + 1 : NS) / NS;
        const qd g = 0.6180339887498948482045868343656Q;
        for (int it = 0; it < 40; it++) {
            const qd x1 = b - g * (b - a), x2 = a + g * (b - a);
            double p1[2], p2[2];
            qpoint(P, x1, p1), qpoint(P, x2, p2);
            const double f1 = inner_min(Q, (const double(*)[2])tab, p1), f2 = inner_min(Q, (const double(*)[2])tab, p2);
            B = fmax(B, fmax(f1, f2));
            if (f1 >= f2)
                b = x2;
            else
                a = x1;
        }
        f[j] = -1;
        for (int i = j - 2; i <= j + 2; i++)  /* the neighbours are the same peak */
            if (i >= 0 && i <= NS)
                f[i] = -1;
    }
    free(tab);
    free(f);
    return B;
}

/* The brute force H of approximation A against the offset at d of seg over
 * u = a + (b - a) (t0 + (t1 - t0) s). */
static double brute(const ob_bez *seg, const ob_cert_src *src, const ob_bez *A, double d)
{
    qcurve O = {seg, NULL, 0, 0, d, {0, 0}}, Ac = {NULL, A, 0, 0, 0, {0, 0}};
    const qd w = (qd)src->b - (qd)src->a;
    O.u0 = (qd)src->a + w * (qd)src->t0;
    O.du = w * ((qd)src->t1 - (qd)src->t0);
    qd P[2], D[2];
    seg_jet(A, 0.5Q, P, D);  /* the origin: a point of A, exact in binary128 */
    O.org[0] = Ac.org[0] = P[0], O.org[1] = Ac.org[1] = P[1];
    return fmax(one_side(&Ac, &O), one_side(&O, &Ac));
}

/* ---- the cases ---------------------------------------------------------- */

static ob_bez poly(int n, const double (*p)[2])
{
    ob_bez b = {n, 0, {{0}}};
    for (int i = 0; i <= n; i++)
        b.h[i][0] = p[i][0], b.h[i][1] = p[i][1], b.h[i][2] = 1.0;
    return b;
}

/* A line from p to q (degree 1). */
static ob_bez line(const double p[2], const double q[2])
{
    const double v[2][2] = {{p[0], p[1]}, {q[0], q[1]}};
    return poly(1, v);
}

/* The cubic through the offset of the cut piece at s = 0, 1/3, 2/3, 1 (as
 * a fit of the cut piece would be; in double, from the library's own
 * offset point: what the method saw). */
static ob_bez interp_cut(const ob_bez *cut, double d)
{
    double P[4][2];
    for (int k = 0; k < 4; k++)
        ob_bez_offset_point(cut, k / 3.0, d, P[k]);
    /* Bezier control points of the interpolating cubic at 0, 1/3, 2/3, 1 */
    double c[4][2];
    for (int x = 0; x < 2; x++) {
        c[0][x] = P[0][x], c[3][x] = P[3][x];
        const double r1 = P[1][x] - (8 * P[0][x] + P[3][x]) / 27.0, r2 = P[2][x] - (P[0][x] + 8 * P[3][x]) / 27.0;
        /* 4/9 c1 + 2/9 c2 = r1, 2/9 c1 + 4/9 c2 = r2 */
        c[1][x] = (18 * r1 - 9 * r2) / 6.0;
        c[2][x] = (18 * r2 - 9 * r1) / 6.0;
    }
    return poly(3, (const double(*)[2])c);
}

static int ncases, nbad_upper, nbad_lower;

/* Certifies A against the offset of seg over src (the cut `cut` guiding),
 * in both modes, and checks the enclosure against the brute force.
 * must_inf: C' vanishes on the piece: no bound may be claimed. */
static void check_case(const char *what, const ob_bez *seg, const ob_cert_src *src, const ob_bez *A, double d,
                       int must_inf)
{
    ob_bez cut, sub;
    ob_bez_subsegment(seg, src->a, src->b, &sub);
    ob_bez_subsegment(&sub, src->t0, src->t1, &cut);
    const double B = brute(seg, src, A, d);
    static const char *const name[3] = {"tight", "verdict over", "verdict within"};
    for (int mode = 0; mode < 3; mode++) {
        ob_cert_opts o;
        ob_cert_defaults(&o);
        o.verdict = mode > 0;
        /* a tol it is over (the lower end decides), one it is within */
        o.decide = mode == 1 ? fmax(B * 0.5, 1e-300) : mode == 2 ? fmax(B * 2, 1e-300) : 0.0;
        ob_cert_job j;
        ob_certify_job_src(1, &cut, getenv("OB_TEST_OLD_CUT") ? NULL : src, A, d, 256, &o, NULL, &j, NULL);
        ncases++;
        const int up_ok = B <= j.upper * (1 + 1e-9) + 1e-300;
        const int lo_ok = j.lower <= B * (1 + 1e-6) + 1e-300;
        nbad_upper += !up_ok, nbad_lower += !lo_ok;
        CHECK(up_ok, "%s (%s): brute %.9g above err_upper %.9g", what, name[mode], B, j.upper);
        CHECK(lo_ok, "%s (%s): err_lower %.9g above brute %.9g", what, name[mode], j.lower, B);
        if (must_inf)
            CHECK(isinf(j.upper), "%s (%s): C' vanishes on the piece, yet err_upper %.9g", what,
                  name[mode], j.upper);
        if (getenv("OB_TEST_VERBOSE"))
            fprintf(stderr, "%-44s %-14s brute %.9g  [%.9g, %.9g] met %d\n", what, name[mode], B,
                    j.lower, j.upper, j.met);
    }
}

static const double GENERIC[4][2] = {{0.1, 0.2}, {0.35, 0.9}, {0.75, -0.1}, {1.0, 0.6}};

/* Pieces of a generic cubic with legs 1e-8 .. 1e-13 (spans that short),
 * against (a) the offset of the cut piece (what a method fitting it sees:
 * the cut's own offset, off by the fan), (b) a line through the true
 * offset's ends. */
static void test_short_spans(void)
{
    const ob_bez seg = poly(3, GENERIC);
    const double widths[] = {1e-8, 1e-10, 1e-11, 1e-12, 3e-13, 1e-13};
    const double d = 0.1;
    for (size_t k = 0; k < sizeof widths / sizeof *widths; k++) {
        const double a = 0.4137, b = a + widths[k];
        const ob_cert_src src = {&seg, a, b, 0.0, 1.0};
        ob_bez cut;
        ob_bez_subsegment(&seg, a, b, &cut);
        char what[80];
        const ob_bez A1 = interp_cut(&cut, d);
        snprintf(what, sizeof what, "span %g, the cut's offset", widths[k]);
        check_case(what, &seg, &src, &A1, d, 0);
        /* (b) the true offset's ends (from the unrounded segment at a, b) */
        double e0[2], e1[2];
        ob_bez_offset_point(&seg, a, d, e0);
        ob_bez_offset_point(&seg, b, d, e1);
        const ob_bez A2 = line(e0, e1);
        snprintf(what, sizeof what, "span %g, the true ends", widths[k]);
        check_case(what, &seg, &src, &A2, d, 0);
    }
    /* a piece of a piece: the driver's span cut again at the fit's t */
    const ob_cert_src src = {&seg, 0.25, 0.75, 0.3, 0.3 + 2e-13};
    ob_bez sub, cut;
    ob_bez_subsegment(&seg, 0.25, 0.75, &sub);
    ob_bez_subsegment(&sub, 0.3, 0.3 + 2e-13, &cut);
    const ob_bez A = interp_cut(&cut, d);
    check_case("span [0.25, 0.75] at [0.3, 0.3 + 2e-13]", &seg, &src, &A, d, 0);
}

/* A collapsed end leg (P0 = P1: C'(0) = 0) and coincident interior points
 * with antiparallel legs (a cusp): no enclosure of the offset exists on a
 * piece that reaches the zero of C'. */
static void test_vanishing_derivative(void)
{
    const double collapsed[4][2] = {{0.2, 0.3}, {0.2, 0.3}, {0.7, 0.9}, {1.0, 0.2}};
    const ob_bez c1 = poly(3, collapsed);
    const double spans[][2] = {{0.0, 0.1}, {0.0, 1e-4}, {0.0, 1e-7}};
    for (int k = 0; k < 3; k++) {
        const ob_cert_src src = {&c1, spans[k][0], spans[k][1], 0.0, 1.0};
        ob_bez cut;
        ob_bez_subsegment(&c1, spans[k][0], spans[k][1], &cut);
        const ob_bez A = interp_cut(&cut, 0.05);
        char what[80];
        snprintf(what, sizeof what, "collapsed end leg, [0, %g]", spans[k][1]);
        check_case(what, &c1, &src, &A, 0.05, 1);
    }
    /* an exact cusp at u = 1/2: C'(1/2) = 0 (the legs (1, 1), (-1, 0), (1, -1)) */
    const double cusp[4][2] = {{0, 0}, {1, 1}, {0, 1}, {1, 0}};
    const ob_bez c2 = poly(3, cusp);
    const double cspans[][2] = {{0.4, 0.6}, {0.5, 0.6}, {0.3, 0.5}, {0.49, 0.51}};
    for (int k = 0; k < 4; k++) {
        const ob_cert_src src = {&c2, cspans[k][0], cspans[k][1], 0.0, 1.0};
        ob_bez cut;
        ob_bez_subsegment(&c2, cspans[k][0], cspans[k][1], &cut);
        const ob_bez A = interp_cut(&cut, -0.03);
        char what[80];
        snprintf(what, sizeof what, "exact cusp, [%g, %g]", cspans[k][0], cspans[k][1]);
        check_case(what, &c2, &src, &A, -0.03, 1);
    }
    /* coincident interior points, antiparallel outer legs (0.5, 0.5) and
     * (-0.25, -0.25): C' = 3 ((1 - u)^2 a + u^2 c) vanishes where
     * (1 - u) / u = sqrt(1/2), u = 0.5858 */
    const double coin[4][2] = {{0.0, 0.0}, {0.5, 0.5}, {0.5, 0.5}, {0.25, 0.25}};
    const ob_bez c3 = poly(3, coin);
    const ob_cert_src src = {&c3, 0.55, 0.62, 0.0, 1.0};
    ob_bez cut;
    ob_bez_subsegment(&c3, 0.55, 0.62, &cut);
    const ob_bez A = interp_cut(&cut, 0.02);
    check_case("coincident interior points, [0.55, 0.62]", &c3, &src, &A, 0.02, 1);
}

/* The random `degenerate` family's coincident kind: one leg 1e-8 .. 1e-6,
 * the others long (host/io/random.c).  Spans around the sharp turn at the
 * short leg, as a driver splitting there cuts them. */
static void test_coincident_leg(void)
{
    const double legs[] = {1e-8, 1e-7, 1e-6};
    for (int k = 0; k < 3; k++) {
        const double p[4][2] = {{0.1, 0.1}, {0.6, 0.7}, {0.6 + legs[k], 0.7 + 0.5 * legs[k]}, {0.2, 0.9}};
        const ob_bez seg = poly(3, p);
        const double spans[][2] = {{0.45, 0.55}, {0.499, 0.501}, {0.5, 0.5 + 1e-9}, {0.5 - 1e-12, 0.5}};
        for (int s = 0; s < 4; s++) {
            const ob_cert_src src = {&seg, spans[s][0], spans[s][1], 0.0, 1.0};
            ob_bez cut;
            ob_bez_subsegment(&seg, spans[s][0], spans[s][1], &cut);
            const ob_bez A = interp_cut(&cut, 0.08);
            char what[96];
            snprintf(what, sizeof what, "leg %g, [%.12g, %.12g]", legs[k], spans[s][0], spans[s][1]);
            check_case(what, &seg, &src, &A, 0.08, 0);
        }
    }
}

/* The cut itself (src NULL) must keep today's answers on an ordinary piece:
 * the source changes nothing where the cut is faithful. */
static void test_ordinary_same(void)
{
    const ob_bez seg = poly(3, GENERIC);
    const ob_cert_src src = {&seg, 0.2, 0.7, 0.0, 1.0};
    ob_bez cut;
    ob_bez_subsegment(&seg, 0.2, 0.7, &cut);
    const ob_bez A = interp_cut(&cut, 0.1);
    ob_cert_job j1, j2;
    ob_certify_job_src(1, &cut, NULL, &A, 0.1, 256, NULL, NULL, &j1, NULL);
    ob_certify_job_src(1, &cut, &src, &A, 0.1, 256, NULL, NULL, &j2, NULL);
    CHECK(fabs(j1.upper / j2.upper - 1) < 1e-6 && fabs(j1.lower / j2.lower - 1) < 1e-6,
          "ordinary piece: cut [%.12g, %.12g], stored [%.12g, %.12g]", j1.lower, j1.upper, j2.lower, j2.upper);
    check_case("ordinary piece [0.2, 0.7]", &seg, &src, &A, 0.1, 0);
}

int main(void)
{
    test_ordinary_same();
    test_short_spans();
    test_vanishing_derivative();
    test_coincident_leg();
    fprintf(stderr, "%d enclosures against the brute force: %d below it, %d lower bounds above it\n", ncases,
            nbad_upper, nbad_lower);
    return check_done();
}
