/*
 * test_certified.c - the certified Hausdorff enclosure (methods/metrics/
 * metric_certified.h): lower <= true distance <= upper by construction.
 *
 * Why: the enclosure is the claim a user cuts metal by; each test states what
 * the mathematics guarantees and checks exactly that:
 *   - exact offsets (a line, circles as rational quadratics, both senses):
 *     the bound collapses to round-off;
 *   - random pairs (random cubics, interpolants of their offsets, perturbed,
 *     some made rational) against a brute force written here (its own
 *     evaluation by Bernstein sums, testlib.h): the brute force's value is
 *     the max over dense samples of a distance to a found point, so it is at
 *     most the true sup plus its foot's refinement error, and at least the
 *     true sup less what the samples miss;
 *   - the sampled `hausdorff` metric at 256 samples (ob_metric_hausdorff):
 *     its value is a distance to a found foot, so at most the true distance
 *     plus its refinement error: sampled <= upper (1 + 1e-9);
 *   - a planted spike the 256 samples step over: the sampled value misses
 *     it, the upper bound does not;
 *   - jobs of pieces whose distances differ by orders of magnitude
 *     (cert_job.h): the job's enclosure holds the largest brute force and
 *     meets rtol.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "methods/core/curve.h"
#include "methods/metrics/metric.h"
#include "methods/metrics/cert_curve.h"
#include "methods/metrics/cert_job.h"
#include "methods/metrics/metric_certified.h"
#include "tests/check.h"
#include "tests/testlib.h"

/* ---- a brute force, independent of the library -------------------------- */

typedef struct {
    const ob_bez *b;
    double d;
    int offset;
} bcurve;

/* The offset of a polynomial with C' from its hodograph n sum (P_i+1 - P_i)
 * B_i^n-1, in long double: the sum of P_i B_i' cancels to C' and carries
 * eps |P| / |C'| of relative error into the normal, 2e-10 at the distance
 * of a piece with legs of 1e-7 (test_short_piece), more than the distance. */
static void hodo_offset(const ob_bez *b, double t, double d, double O[2])
{
    const int n = b->deg;
    long double C[2] = {0, 0}, D[2] = {0, 0};
    for (int i = 0; i <= n; i++)
        for (int c = 0; c < 2; c++) {
            C[c] += (long double)b->h[i][c] * bern(n, i, t);
            if (i < n)
                D[c] += n * ((long double)b->h[i + 1][c] - b->h[i][c]) * bern(n - 1, i, t);
        }
    const long double sp = sqrtl(D[0] * D[0] + D[1] * D[1]);
    O[0] = (double)(C[0] - d * D[1] / sp);
    O[1] = (double)(C[1] + d * D[0] / sp);
}

static void bpoint(const bcurve *c, double t, double p[2])
{
    if (c->offset && !c->b->rational)
        hodo_offset(c->b, t, c->d, p);
    else if (c->offset)
        ref_offset(c->b, t, c->d, p);
    else
        ref_point(c->b, t, p);
}

enum { BLK = 20 };

/* The rows of q's table: its spacing must be finer than the branches of
 * an offset's swallowtail are apart, or the golden section refines the
 * nearest row of the wrong branch (test_swallowtail sets it finer). */
static int tab_rows = 2000;

enum { NEAR_PAIRS = 4, NEAR_DEG = 7 };
#define NEAR_BEND 0.001
#define NEAR_WARP 0.4

typedef struct {
    const bcurve *q;
    int n;  /* rows 0 .. n, n a multiple of BLK */
    double (*tab)[2], (*cen)[2], *radius;
} btarget;

static void btarget_init(btarget *T, const bcurve *q)
{
    const int n = T->n = tab_rows;
    T->q = q;
    T->tab = malloc((size_t)(n + 1) * sizeof *T->tab);
    T->cen = malloc((size_t)(n / BLK) * sizeof *T->cen);
    T->radius = malloc((size_t)(n / BLK) * sizeof *T->radius);
    for (int k = 0; k <= n; k++)
        bpoint(q, (double)k / n, T->tab[k]);
    for (int b = 0; b < n / BLK; b++) {
        double cx = 0, cy = 0, r = 0;
        for (int k = b * BLK; k <= (b + 1) * BLK; k++)
            cx += T->tab[k][0] / (BLK + 1), cy += T->tab[k][1] / (BLK + 1);
        for (int k = b * BLK; k <= (b + 1) * BLK; k++)
            r = fmax(r, hypot(T->tab[k][0] - cx, T->tab[k][1] - cy));
        T->cen[b][0] = cx, T->cen[b][1] = cy, T->radius[b] = r;
    }
}

static void btarget_free(btarget *T)
{
    free(T->tab);
    free(T->cen);
    free(T->radius);
}

/* distance from p to the table's nearest row (exact table min), its index */
static double table_min(const btarget *T, const double p[2], int *kbest)
{
    double best = INFINITY;
    for (int b = 0; b < T->n / BLK; b++) {
        if (hypot(p[0] - T->cen[b][0], p[1] - T->cen[b][1]) - T->radius[b] > best)
            continue;
        for (int k = b * BLK; k <= (b + 1) * BLK; k++) {
            const double dd = hypot(p[0] - T->tab[k][0], p[1] - T->tab[k][1]);
            if (dd < best)
                best = dd, *kbest = k;
        }
    }
    return best;
}

/* the distance to a point of q found by golden section around row k */
static double refine_min(const btarget *T, const double p[2], int k)
{
    const int n = T->n;
    double a = (double)(k > 0 ? k - 1 : 0) / n, b = (double)(k < n ? k + 1 : n) / n, x[2];
    const double g = 0.6180339887498949;
    for (int it = 0; it < 60; it++) {
        const double m1 = b - g * (b - a), m2 = a + g * (b - a);
        double p1[2], p2[2];
        bpoint(T->q, m1, p1);
        bpoint(T->q, m2, p2);
        if (hypot(p[0] - p1[0], p[1] - p1[1]) <= hypot(p[0] - p2[0], p[1] - p2[1]))
            b = m2;
        else
            a = m1;
    }
    bpoint(T->q, 0.5 * (a + b), x);
    return fmin(hypot(p[0] - x[0], p[1] - x[1]), hypot(p[0] - T->tab[k][0], p[1] - T->tab[k][1]));
}

/* max over n samples of p of the distance to a found point of q */
static double brute_side(const bcurve *p, const bcurve *q, long n)
{
    btarget T;
    btarget_init(&T, q);
    double best = 0.0;
    for (long i = 0; i < n; i++) {
        double x[2];
        int k = 0;
        bpoint(p, (double)i / (n - 1), x);
        if (table_min(&T, x, &k) > best)  /* refining only lowers it */
            best = fmax(best, refine_min(&T, x, k));
    }
    btarget_free(&T);
    return best;
}

static double brute(const ob_bez *base, const ob_bez *approx, double d, long n)
{
    const bcurve A = {approx, 0, 0}, O = {base, d, 1};
    return fmax(brute_side(&A, &O, n), brute_side(&O, &A, n));
}

/* The brute force's distance from the certificate's named point (side 0: a
 * point of A, 1: of the offset) to the other curve: one more sample of that
 * side's sup.  Where the certificate is tighter than the brute force's
 * sample spacing (test_swallowtail: its named point lies between the 20000
 * samples, 3e-5 relative above their max), this sample is what checks the
 * lower bound, a distance attained: lower <= this. */
static double brute_point(const ob_bez *base, const ob_bez *approx, double d, int side, double param)
{
    const bcurve A = {approx, 0, 0}, O = {base, d, 1};
    const bcurve *p = side ? &O : &A, *q = side ? &A : &O;
    btarget T;
    btarget_init(&T, q);
    double x[2];
    int k = 0;
    bpoint(p, param, x);
    table_min(&T, x, &k);
    const double r = refine_min(&T, x, k);
    btarget_free(&T);
    return r;
}

/* ---- curves -------------------------------------------------------------- */

/* Solve the n x n system M x = r (partial pivoting), r overwritten by x. */
static void solve(double *M, double (*r)[2], int n)
{
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int i = c + 1; i < n; i++)
            if (fabs(M[i * n + c]) > fabs(M[p * n + c]))
                p = i;
        for (int j = 0; j < n; j++) {
            const double t = M[c * n + j];
            M[c * n + j] = M[p * n + j], M[p * n + j] = t;
        }
        for (int j = 0; j < 2; j++) {
            const double t = r[c][j];
            r[c][j] = r[p][j], r[p][j] = t;
        }
        for (int i = c + 1; i < n; i++) {
            const double f = M[i * n + c] / M[c * n + c];
            for (int j = c; j < n; j++)
                M[i * n + j] -= f * M[c * n + j];
            r[i][0] -= f * r[c][0], r[i][1] -= f * r[c][1];
        }
    }
    for (int c = n - 1; c >= 0; c--) {
        for (int j = c + 1; j < n; j++)
            r[c][0] -= M[c * n + j] * r[j][0], r[c][1] -= M[c * n + j] * r[j][1];
        r[c][0] /= M[c * n + c], r[c][1] /= M[c * n + c];
    }
}

/* The degree-n polynomial through the offset at n + 1 Chebyshev-Lobatto
 * nodes s, taken at the base's parameter t = s + warp s (1 - s) (warp 0:
 * the same parameter; else A and O parameterized apart, as a fit that
 * does not keep the base's parameter). */
static ob_bez interp_offset_warp(const ob_bez *base, double d, int n, double warp)
{
    double M[(OB_MAX_DEG + 1) * (OB_MAX_DEG + 1)], r[OB_MAX_DEG + 1][2];
    for (int i = 0; i <= n; i++) {
        const double t = 0.5 - 0.5 * cos(OB_PI * i / n);
        for (int j = 0; j <= n; j++)
            M[i * (n + 1) + j] = bern(n, j, t);
        ref_offset(base, t + warp * t * (1 - t), d, r[i]);
    }
    solve(M, r, n + 1);
    return make(n, (const double (*)[2])r, NULL);
}

static ob_bez interp_offset(const ob_bez *base, double d, int n) { return interp_offset_warp(base, d, n, 0.0); }

static ob_bez random_cubic(void)
{
    double xy[4][2];
    for (int i = 0; i < 4; i++)
        xy[i][0] = i / 3.0 + urange(-0.2, 0.2), xy[i][1] = urange(-0.5, 0.5);
    return make(3, (const double (*)[2])xy, NULL);
}

static double size_of(const ob_bez *b)
{
    double m = 0;
    for (int i = 0; i <= b->deg; i++)
        m = fmax(m, fmax(fabs(b->h[i][0] / b->h[i][2]), fabs(b->h[i][1] / b->h[i][2])));
    return m;
}

/* ---- tests --------------------------------------------------------------- */

static void check_exact(const char *what, const ob_bez *base, const ob_bez *approx, double d)
{
    ob_certified c;
    ob_cert_opts o;
    ob_cert_defaults(&o);
    o.budget = 200000;
    const int rc = ob_certify_hausdorff_opts(base, approx, d, 256, &o, &c);
    const double size = size_of(base) + fabs(d);
    CHECK(rc == 0 && c.lower >= 0 && c.lower <= c.upper, "%s: rc %d lower %g upper %g", what, rc, c.lower, c.upper);
    CHECK(c.upper < 1e-12 * size, "%s: upper %.3g not round-off (size %g, %ld leaves)", what, c.upper, size,
          c.leaves);
    printf("exact %-28s upper %.3g lower %.3g leaves %ld\n", what, c.upper, c.lower, c.leaves);
}

static void test_exact(void)
{
    const double line[2][2] = {{0, 0}, {2, 1}}, off[2][2] = {{-0.2, 0.4}, {1.8, 1.4}};
    const ob_bez L = make(1, line, NULL), LO = make(1, off, NULL);
    check_exact("line d = 0.2 sqrt 5", &L, &LO, 0.2 * sqrt(5.0));
    const ob_bez C = quarter_circle(1.0, 0), Cin = quarter_circle(0.75, 0), Cout = quarter_circle(1.5, 0);
    check_exact("circle ccw d = 0.25", &C, &Cin, 0.25);
    check_exact("circle ccw d = -0.5", &C, &Cout, -0.5);
    const ob_bez W = quarter_circle(1.0, 1), Wout = quarter_circle(1.25, 1);
    check_exact("circle cw d = 0.25", &W, &Wout, 0.25);
}

/* The third derivatives the third-order Taylor form reads (cert_curve.h:
 * A''' from the control points, O''' from kappa''): by the mean value
 * theorem, each component of (X''(b) - X''(a)) / (b - a) is X''' at some
 * point of [a, b], so the enclosure of X''' over [a, b] must meet the
 * enclosure of that quotient (from the point enclosures of X'', no slack
 * needed).  On [a, a + 1e-4] the enclosures are 0.05 .. 1 % wide (the
 * offset's by interval evaluation), the quotient ~1e-12, so a
 * wrong term (a factor 2, a sign) misses by O(1). */
static void test_third_derivative(void)
{
    int bad = 0, n = 0;
    for (int p = 0; p < 12; p++) {
        ob_bez C = random_cubic();
        if (p % 3 == 2)  /* rational */
            for (int i = 0; i <= C.deg; i++)
                ob_bez_set(&C, i, C.h[i][0], C.h[i][1], urange(0.7, 1.4));
        for (int off = 0; off < 2; off++) {
            const ob_cv cv = {&C, urange(-0.2, 0.2), off};
            const double a = urange(0.05, 0.9), b = a + 1e-4;
            ob_iv pa[2], da[2], sa[2], pb[2], db[2], sb[2], r3[2];
            if (ob_cv_point2(&cv, a, pa, da, sa) || ob_cv_point2(&cv, b, pb, db, sb) ||
                ob_cv_range(&cv, a, b, 3, r3)) {
                bad++;
                continue;
            }
            const ob_iv w = ob_iv_sub(ob_iv_pt(b), ob_iv_pt(a));
            for (int c = 0; c < 2; c++) {
                const ob_iv q = ob_iv_div(ob_iv_sub(sb[c], sa[c]), w);
                n++;
                if (q.hi < r3[c].lo || q.lo > r3[c].hi || r3[c].hi - r3[c].lo > 0.05 * (1 + ob_iv_mag(r3[c]))) {
                    bad++;
                    printf("third derivative %d%s off %d c %d: quotient [%.9g, %.9g] enclosure [%.9g, %.9g]\n", p,
                           C.rational ? "r" : "", off, c, q.lo, q.hi, r3[c].lo, r3[c].hi);
                }
            }
        }
    }
    CHECK(bad == 0, "third derivative: %d of %d enclosures miss the mean-value quotient (or are wide)", bad, n);
}

/* A base with a cusp (C'(0) = 0: its first two control points coincide):
 * the offset's normal is undefined there, so no bound exists: rc -1 and
 * upper +inf, and the certified metric reports +inf (the driver splits such
 * a piece); the lower bound, a distance attained, is still valid. */
static void test_cusp(void)
{
    const double cusp[4][2] = {{0, 0}, {0, 0}, {1, 1}, {2, 0}};
    const ob_bez C = make(3, cusp, NULL);
    const ob_bez A = interp_offset(&C, 0.1, 5);
    ob_certified c;
    const int rc = ob_certify_hausdorff(&C, &A, 0.1, 256, &c);
    CHECK(rc == -1 && isinf(c.upper) && c.upper > 0, "cusp of C: rc %d, upper %g (no bound exists)", rc, c.upper);
    CHECK(c.lower >= 0 && isfinite(c.lower), "cusp of C: lower %g still a distance", c.lower);
    ob_errval e;
    CHECK(ob_measure(OB_METRIC_CERTIFIED, &C, &A, 0.1, 256, &e) == 0 && isinf(e.err) && e.t >= 0 && e.t <= 1,
          "cusp of C: the certified metric is +inf (%g) at t = %g", e.err, e.t);
}

/* A short piece of a septic (a leg of ~1e-7, coordinates ~0.5: what `sisl`
 * cuts near a sharp bend).  |C'| ~ 7e-7 is far from 0, but an enclosure
 * that subdivides the control points and then differences them carries
 * their rounding eps |P| / w^k, and de Casteljau steps a + t (b - a) grow
 * widths ~3x per level near t = 1: on such a `sisl` piece (rnd7_000130)
 * C' over [0.99460, 0.99466] was enclosed in [-5.5e-8, 1.6e-6] for a true
 * 7.5e-7, so |C'| reached 0 (+inf, rc -1); here 2 of the 6 pieces were
 * +inf and the others bounded at 0.06 .. 2.6 for distances of 2e-11.  The
 * hodograph subdivided in convex form encloses C' to ~1e-6 relative.  The
 * feet (floating point) took C' from the same cancellation, 1e-9 relative:
 * offset points 2e-10 off, feet 1e-5 off in t, the bound stuck at 2.5 ..
 * 4.6 times the distance; at the origin they are tight.  The certificate
 * must be within 1.01 of its lower bound and hold the brute force (whose offset takes C' from the
 * hodograph too: the sum of P_i B_i' cancels to 1e-9 relative, 2e-10 at
 * the offset, more than the distance). */
/* Certifies (base, A, d) at the defaults, prints it beside the brute force
 * (with the certificate's own point sampled too: the lower bound is that
 * point's distance) and checks that the enclosure holds it.  1 when it is
 * bounded within ratio of its lower bound. */
static int certified_within(const char *what, double at, const ob_bez *base, const ob_bez *A, double d, double ratio)
{
    ob_certified c;
    const int rc = ob_certify_hausdorff(base, A, d, 256, &c);
    const double b = fmax(brute(base, A, d, 20000), brute_point(base, A, d, c.lower_side, c.lower_param));
    printf("%s %.2f: brute %.6g certified [%.6g, %.6g] rc %d met %d, %ld leaves\n", what, at, b, c.lower, c.upper, rc,
           c.met, c.leaves);
    CHECK(b <= c.upper * (1 + 1e-9) + 1e-15 && c.lower <= b * (1 + 1e-7) + 1e-15, "%s %.2f: [%.17g, %.17g] misses %.17g",
          what, at, c.lower, c.upper, b);
    return rc == 0 && c.upper <= ratio * c.lower;
}

static void test_short_piece(void)
{
    double xy[8][2];
    for (int i = 0; i < 8; i++)
        xy[i][0] = i / 7.0 + urange(-0.1, 0.1), xy[i][1] = urange(0.2, 0.8);
    const ob_bez C7 = make(7, (const double (*)[2])xy, NULL);
    int bounded = 0, n = 0;
    for (int p = 0; p < 6; p++) {
        const double a = 0.15 + 0.12 * p, d = p % 2 ? 0.2 : -0.15;
        ob_bez base;
        ob_bez_subsegment(&C7, a, a + 1e-6, &base);
        ob_bez A = interp_offset(&base, d, 3);
        for (int i = 0; i <= A.deg; i++)  /* an error of ~1e-12, well above round-off */
            ob_bez_set(&A, i, A.h[i][0] + urange(-1e-12, 1e-12), A.h[i][1] + urange(-1e-12, 1e-12), 1.0);
        bounded += certified_within("short piece", a, &base, &A, d, 1.01);
        n++;
    }
    CHECK(bounded == n, "short pieces: %d of %d bounded within 1.01 of the lower bound", bounded, n);
}

/* Near-exact pairs (docs/certified.md, Limits): a piece 1e-10 .. 1e-9 from
 * the offset of a nearly straight base, parameterized apart from it, as
 * `sisl` and `cubic-opt` give on a `degenerate` curve (rnd7_000087: a
 * cubic 2.27e-10 from the offset, bounded at 1.29e-9 before).  A line
 * t(s) through the ends' feet slips along O by ~f'' w^2 / 8 (f the foot
 * map, curved by the warp), and the slip enters the bound as
 * slip^2 / (2 distance): at 1e-10 the intervals must be ~1e-5 wide, past
 * the budget (before: [6.18e-11, 2.30e-8], 1.2e-9 at 2.33e-8, ... ratios
 * 10 .. 370, 40000 leaves each); the quadratic correspondence slips
 * O(w^3).  Each pair must be certified within 1.1 (met: 1.001) at the
 * default budget and hold the brute force (with the certificate's point
 * sampled: the lower bound is that point's distance). */
static void test_near_exact(void)
{
    int tight = 0, n = 0;
    for (int p = 0; p < NEAR_PAIRS; p++) {
        double xy[4][2];
        for (int i = 0; i < 4; i++)
            xy[i][0] = i / 3.0 + urange(-0.1, 0.1), xy[i][1] = NEAR_BEND * urange(-1, 1);
        const ob_bez base = make(3, (const double (*)[2])xy, NULL);
        const double d = (p % 2 ? 1 : -1) * urange(0.05, 0.15);
        const ob_bez A = interp_offset_warp(&base, d, NEAR_DEG, NEAR_WARP);
        tight += certified_within("near-exact pair", p, &base, &A, d, 1.1);
        n++;
    }
    CHECK(tight == n, "near-exact pairs: %d of %d within 1.1 of the lower bound", tight, n);
}

/* A `zhao-rational` piece of rnd7_000170 (d = 0.0737; A rational of degree
 * 7 with weights of both signs) whose offset has a swallowtail near
 * t = 0.475 .. 0.515 (1 - d kappa near 0, |O'| ~ 0.004): there the table's
 * nearest row lies on another branch, the feet of A(0.48) and A(0.52) land
 * 2e-5 and 4e-5 away (the true distance ~3e-6), and halving an interval
 * kept such a foot at both ends of a half: certified [3.7456e-6, 1.447e-5]
 * (met 0), the lower bound the sampled maximum, 5 percent below the truth.
 * With the parent's line passed to the halves and the feet searched around
 * it too, the certificate must meet rtol and hold the brute force (on a
 * table fine enough for the swallowtail: on the usual 2000 rows it takes
 * the wrong branch too, 5.17e-6 against 3.93908e-6 with every row). */
static void test_swallowtail(void)
{
    static const double hb[8][3] = {
        {0.45853556339992607, 0.59091083196669691, 1},
        {0.40478799611199445, 0.6387526674675843, 1},
        {0.35496701552651239, 0.683099365893854, 1},
        {0.31208075690168047, 0.71294952166728098, 1},
        {0.27852682727664185, 0.72073933890834074, 1},
        {0.25557985900562674, 0.70486190876044463, 1},
        {0.24370546855481834, 0.66956517641812452, 1},
        {0.24601355553670157, 0.62304897715393981, 1}};
    static const double ha[8][3] = {
        {0.40953506189514793, 0.53585890764813482, 1},
        {0.11153843648476422, 0.26415836824850697, 0.40364491581116352},
        {-0.00050236119421603193, 0.054878675478518865, 0.06039323617996871},
        {0.01385827349911717, -0.016804977442377828, 0.0048421170420011265},
        {-0.004122584968004034, 0.020851571153866693, 0.0082761223136027899},
        {0.01863119272236341, 0.020079162754029132, 0.050256635739877105},
        {-0.02122985158470635, -0.033437282874730356, -0.065313848885418524},
        {0.085162552645748152, 0.16698322894253018, 0.26644871506355716}};
    const double d = 0.073700000000000002;
    ob_bez base, A;
    memset(&base, 0, sizeof base);
    memset(&A, 0, sizeof A);
    base.deg = A.deg = 7, A.rational = 1;
    memcpy(base.h, hb, sizeof hb);
    memcpy(A.h, ha, sizeof ha);
    ob_certified c;
    const int rc = ob_certify_hausdorff(&base, &A, d, 256, &c);
    tab_rows = 40000;  /* rows 2.5e-5 apart: |O'| ~ 0.004 there, 1e-7 against 4e-6 */
    const double b = fmax(brute(&base, &A, d, 20000), brute_point(&base, &A, d, c.lower_side, c.lower_param));
    tab_rows = 2000;
    printf("swallowtail: brute %.9g certified [%.9g, %.9g] rc %d met %d, %ld leaves\n", b, c.lower, c.upper, rc, c.met,
           c.leaves);
    CHECK(b <= c.upper * (1 + 1e-9) && c.lower <= b * (1 + 1e-7), "swallowtail: [%.17g, %.17g] misses %.17g", c.lower,
          c.upper, b);
    CHECK(rc == 0 && c.met && c.upper <= 1.001 * c.lower, "swallowtail: [%g, %g] rc %d met %d", c.lower, c.upper, rc,
          c.met);
}

/* lower <= brute + what samples miss; brute <= upper + its refinement error;
 * the sampled metric likewise <= upper. */
/* opts.decide: a tolerance inside the enclosure c (no verdict at rtol) is
 * decided, upper <= tol or lower > tol, and the answer still holds the
 * brute force b: the tolerance 3e-4 above, then below, the brute force's
 * value (both verdicts asked for, each a third of rtol from the truth). */
static void check_decide(const ob_bez *base, const ob_bez *A, double d, const ob_certified *c, double b, int p)
{
    for (int side = 0; side < 2; side++) {
        const double tol = b * (side ? 1 - 3e-4 : 1 + 3e-4);
        if (!(c->lower <= tol && tol < c->upper))
            continue;  /* decided without it */
        ob_cert_opts o;
        ob_cert_defaults(&o);
        o.decide = tol;
        ob_certified r;
        const int rc = ob_certify_hausdorff_opts(base, A, d, 256, &o, &r);
        CHECK(rc == 0 && (r.upper <= tol || r.lower > tol), "pair %d, decide %.17g: [%.17g, %.17g] undecided", p, tol,
              r.lower, r.upper);
        CHECK(r.lower <= b * (1 + 1e-7) + 1e-15 && b <= r.upper * (1 + 1e-9) + 1e-15,
              "pair %d, decide: [%.17g, %.17g] misses the brute force %.17g", p, r.lower, r.upper, b);
        CHECK(r.upper <= c->upper * (1 + 1e-12) || r.lower >= c->lower, "pair %d, decide: no tighter side", p);
    }
}

static void test_random_pairs(int npairs, long nbrute)
{
    double worst_ratio = 1.0;
    for (int p = 0; p < npairs; p++) {
        const ob_bez base = random_cubic();
        const double d = (p % 2 ? 1 : -1) * urange(0.03, 0.2);
        ob_bez A = interp_offset(&base, d, 3 + p % 5);
        for (int i = 0; i <= A.deg; i++)
            ob_bez_set(&A, i, A.h[i][0] + urange(-1e-4, 1e-4), A.h[i][1] + urange(-1e-4, 1e-4),
                       p % 3 == 2 ? urange(0.8, 1.25) : 1.0);
        ob_certified c;
        ob_errval s;
        const int rc = ob_certify_hausdorff(&base, &A, d, 256, &c);
        ob_metric_hausdorff(&base, &A, d, 256, &s);
        const double b = brute(&base, &A, d, nbrute);
        CHECK(c.lower <= c.upper, "pair %d: lower %.17g > upper %.17g", p, c.lower, c.upper);
        CHECK(b <= c.upper * (1 + 1e-9) + 1e-15, "pair %d: brute %.17g > upper %.17g", p, b, c.upper);
        CHECK(c.lower <= b * (1 + 1e-7) + 1e-15, "pair %d: lower %.17g > brute %.17g", p, c.lower, b);
        CHECK(s.err <= c.upper * (1 + 1e-9) + 1e-15, "pair %d: sampled %.17g > upper %.17g", p, s.err, c.upper);
        if (rc == 0)
            worst_ratio = fmax(worst_ratio, c.upper / c.lower);
        printf("pair %2d deg %d%s: lower %.9g sampled %.9g brute %.9g upper %.9g (rc %d, %ld leaves)\n", p, A.deg,
               A.rational ? "r" : " ", c.lower, s.err, b, c.upper, rc, c.leaves);
        if (rc == 0 && c.upper > c.lower * (1 + 1e-6))
            check_decide(&base, &A, d, &c, b, p);
    }
    printf("random pairs: worst upper / lower %.6f\n", worst_ratio);
}

/* ---- a planted spike ------------------------------------------------------ */

/* c = a (degree p) times b (degree q), Bernstein coefficients. */
static void bprod(const double *a, int p, const double *b, int q, double *c)
{
    for (int k = 0; k <= p + q; k++)
        c[k] = 0.0;
    for (int i = 0; i <= p; i++)
        for (int j = 0; j <= q; j++)
            c[i + j] += a[i] * b[j] * binom(p, i) * binom(q, j) / binom(p + q, i + j);
}

enum { SPK_K = 16, SPK_J = 4, SPK_DEG = SPK_K + 4 };

/* The exact offset of the unit quarter circle at d = 0.25 (the circle of
 * radius 0.75) scaled radially by rho(t) = 1 + 4 c0 t (1 - t) + h phi(s(t)):
 * A(t) = rho(t) Q(t), Q the rational quadratic quarter circle.
 *   - 4 c0 t (1 - t): a broad error, largest at t = 1/2, that the samples see;
 *   - phi(s) = B_j^k(s) / B_j^k(j / k): a bump of height 1 at s = j / k, read
 *     through the Moebius map s(t) = r t / ((1 - t) + r t): then phi(s(t)) =
 *     Phi(t) / m(t), m = ((1 - t) + r t)^k, Phi with the coefficients of phi
 *     times r^i (Farin, ch. 13).  With r = 1000 the map sends (0, 1/255) onto
 *     (0, 0.8): the bump, s in about (0.1, 0.45), lies between the first two
 *     samples, at t ~ 1e-4 .. 8e-4, an arc of ~ 6e-4 (a needle h tall; O's
 *     samples at t = 0 and 1/255 step over it too, both sides sharing t).
 * A = (R Q_xy) / (m Q_w), R = m (1 + 4 c0 t (1 - t)) + h Phi: degree k + 4,
 * weights m Q_w (x (1, 1, 1) to the same degree), all positive. */
static ob_bez spike_curve(double r, double c0, double h)
{
    double m[SPK_K + 1], Phi[SPK_K + 1], R[SPK_K + 3], tmp[SPK_K + 3], W[SPK_K + 3];
    double H[SPK_DEG + 1][3], q[3][3];
    const double broad[3] = {1.0, 1.0 + 2.0 * c0, 1.0}, one[3] = {1.0, 1.0, 1.0};
    const ob_bez Q = quarter_circle(0.75, 0);
    for (int i = 0; i <= SPK_K; i++)
        m[i] = pow(r, i - SPK_K / 2), Phi[i] = 0.0;  /* scaled by r^-k/2: one homogeneous factor */
    Phi[SPK_J] = h * m[SPK_J] / bern(SPK_K, SPK_J, (double)SPK_J / SPK_K);
    bprod(m, SPK_K, broad, 2, R);
    bprod(Phi, SPK_K, one, 2, tmp);
    for (int i = 0; i <= SPK_K + 2; i++)
        R[i] += tmp[i];
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < 3; i++)
            q[c][i] = Q.h[i][c];
        double col[SPK_DEG + 1];
        if (c < 2)
            bprod(R, SPK_K + 2, q[c], 2, col);
        else {
            bprod(m, SPK_K, q[c], 2, W);
            bprod(W, SPK_K + 2, one, 2, col);
        }
        for (int i = 0; i <= SPK_DEG; i++)
            H[i][c] = col[i];
    }
    ob_bez A;
    memset(&A, 0, sizeof A);
    A.deg = SPK_DEG;
    for (int i = 0; i <= SPK_DEG; i++)
        ob_bez_set(&A, i, H[i][0] / H[i][2], H[i][1] / H[i][2], H[i][2]);
    return A;
}

/* | |A(t)| - 0.75 |: A(t) lies on the ray of Q(t), inside the quarter, so
 * this is its distance to the arc O; and |O(t) - A(t)| is the same number,
 * so O's side is no larger: H(A, O) = sup_t of it. */
static double spike_dist(const ob_bez *A, double t)
{
    double p[2];
    ref_point(A, t, p);
    return fabs(hypot(p[0], p[1]) - 0.75);
}

static void test_spike(void)
{
    const double r = 1000.0, c0 = 1e-4, h = 0.01;
    const ob_bez base = quarter_circle(1.0, 0), A = spike_curve(r, c0, h);
    /* the true distance, densely: 1e6 parameters over the first sample
     * interval, 1e5 over the whole */
    double truth = 0.0, tpeak = 0.0;
    for (long i = 0; i <= 1000000; i++) {
        const double t = (double)i / 1000000 / 255.0, e = spike_dist(&A, t);
        if (e > truth)
            truth = e, tpeak = t;
    }
    double broad_max = 0.0;
    for (long i = 0; i <= 100000; i++)
        broad_max = fmax(broad_max, spike_dist(&A, (double)i / 100000));
    truth = fmax(truth, broad_max);
    CHECK(truth > 0.74 * h && tpeak > 0 && tpeak < 1.0 / 255, "spike: true %g at t %g, not planted", truth, tpeak);
    /* what the samples see: the ends of the first interval, and the broad error */
    CHECK(spike_dist(&A, 1.0 / 255) < 0.1 * broad_max, "spike: %g at the second sample", spike_dist(&A, 1.0 / 255));

    ob_errval s;
    ob_certified c;
    ob_metric_hausdorff(&base, &A, 0.25, 256, &s);
    const int rc = ob_certify_hausdorff(&base, &A, 0.25, 256, &c);
    printf("spike: true %.9g at t %.3g (broad %.3g); sampled %.9g; certified [%.9g, %.9g] rc %d met %d, %ld leaves\n",
           truth, tpeak, broad_max, s.err, c.lower, c.upper, rc, c.met, c.leaves);
    CHECK(s.err < 0.1 * truth, "spike: the sampled value %g does not miss the spike %g", s.err, truth);
    CHECK(rc == 0 && c.upper >= truth, "spike: upper %.17g below the true %.17g (rc %d)", c.upper, truth, rc);
    CHECK(c.lower <= truth * (1 + 1e-9), "spike: lower %.17g above the true %.17g", c.lower, truth);
    CHECK(c.met && c.upper <= 1.01 * c.lower, "spike: [%g, %g] not tight (met %d)", c.lower, c.upper, c.met);

    /* no refinement at all (budget 1): the bound over the sample intervals
     * is looser but still a bound; the lower bound is the sampled one */
    ob_cert_opts o;
    ob_cert_defaults(&o);
    o.budget = 1;
    ob_certify_hausdorff_opts(&base, &A, 0.25, 256, &o, &c);
    printf("spike, budget 1: certified [%.9g, %.9g] met %d, %ld leaves\n", c.lower, c.upper, c.met, c.leaves);
    CHECK(c.upper >= truth && c.lower <= truth * (1 + 1e-9), "spike, budget 1: [%.17g, %.17g] misses %.17g",
          c.lower, c.upper, truth);
    CHECK(!c.met, "spike, budget 1: met without refining");
}

/* A job of pieces whose distances differ by orders of magnitude
 * (cert_job.h): the job's enclosure holds the brute force's largest piece,
 * and meets rtol, though its small pieces are only shown below it. */
static void test_job(int njobs)
{
    for (int jb = 0; jb < njobs; jb++) {
        enum { NP = 3 };
        ob_bez base[NP], A[NP];
        const double d = (jb % 2 ? 1 : -1) * urange(0.03, 0.2), scale[NP] = {1e-8, 1e-4, 1e-6};
        const int deg[NP] = {11, 3, 7};  /* interpolation errors far apart too */
        double truth = 0.0, hint[NP];
        for (int k = 0; k < NP; k++) {
            base[k] = random_cubic();
            A[k] = interp_offset(&base[k], d, deg[k]);
            for (int i = 0; i <= A[k].deg; i++)
                ob_bez_set(&A[k], i, A[k].h[i][0] + urange(-1, 1) * scale[k], A[k].h[i][1] + urange(-1, 1) * scale[k],
                           1.0);
            truth = fmax(truth, brute(&base[k], &A[k], d, 20000));
            ob_errval e;
            ob_metric_hausdorff(&base[k], &A[k], d, 256, &e);
            hint[k] = e.err;
        }
        ob_cert_job J, Jh;
        ob_certified piece[NP];
        const int rc = ob_certify_job(NP, base, A, d, 256, NULL, NULL, &J, piece);
        const int rch = ob_certify_job(NP, base, A, d, 256, NULL, hint, &Jh, NULL);
        printf("job %d: brute %.9g certified [%.9g, %.9g] met %d, %ld leaves (piece uppers %.3g %.3g %.3g)\n", jb,
               truth, J.lower, J.upper, J.met, J.leaves, piece[0].upper, piece[1].upper, piece[2].upper);
        CHECK(rc == 0 && rch == 0 && J.met && Jh.met, "job %d: rc %d %d met %d %d", jb, rc, rch, J.met, Jh.met);
        CHECK(truth <= J.upper * (1 + 1e-9) && J.lower <= truth * (1 + 1e-7), "job %d: [%.17g, %.17g] misses %.17g",
              jb, J.lower, J.upper, truth);
        CHECK(J.upper <= J.lower * (1 + 1e-3) && J.upper_piece >= 0 && J.upper == piece[J.upper_piece].upper,
              "job %d: upper %.17g lower %.17g piece %d", jb, J.upper, J.lower, J.upper_piece);
        CHECK(J.lower == Jh.lower && J.upper == Jh.upper, "job %d: the hint changed the result", jb);
        for (int k = 0; k < NP; k++)
            CHECK(piece[k].upper <= J.upper, "job %d: piece %d upper %g above the job's %g", jb, k, piece[k].upper,
                  J.upper);
    }
}

int main(int argc, char **argv)
{
    (void)argv;
    testlib_seed(0x41C3A7E5ULL);
    test_exact();
    test_third_derivative();
    test_cusp();
    test_short_piece();
    test_near_exact();
    test_swallowtail();
    test_spike();
    test_random_pairs(30, argc > 1 ? 1000000 : 20000);
    test_job(4);
    return check_done();
}
