/*
 * test_hausdorff_ref.c - offbench's `hausdorff` metric against an independent
 * two-sided Hausdorff reference, on jobs run through the real pipeline.
 *
 * Why: the metric finds each nearest foot by a coarse scan and a local descent;
 * near the cusps and swallowtails of an untrimmed offset a local search can
 * settle on the wrong branch and report a distance that is not the nearest
 * one.  A reference that shares none of its code (no kernels/, no ob_measure,
 * no ob_bez_eval: curves are evaluated here from the homogeneous control
 * points) and searches globally tells whether the reported maxima are right.
 *
 * The reference, for one approximating piece A(u) and the untrimmed offset
 * O(t) = C(t) + d N(t) of its base piece (u, t in [0, 1], N the left normal):
 *   H(A, O) = max( sup_u dist(A(u), O), sup_t dist(O(t), A) ),
 * each one-sided term in two stages:
 *   stage 1  the target curve as a polyline of 400 segments; for each of the
 *            4001 query samples the exact point-segment distance to the
 *            segments (a global scan, no descent; blocks of 10 segments whose
 *            bounding circle is provably too far are skipped, which changes
 *            nothing but the work);
 *   stage 2  every run of consecutive segments within best + 4 x (the largest
 *            chord-to-curve deviation) of the best is refined on the true
 *            curve by nested grids (10 points per segment over the run widened
 *            by half a segment each side, then 21 points over the best point
 *            +- 1 spacing, 10-fold narrower per level, down to a spacing below
 *            1e-10); the minimum over the runs.  The result is the distance to
 *            a true curve point, so it never lies below the true distance.
 * Then the maximum over the query samples, refined the same way (nested grid
 * on the query parameter over +- one sample spacing) around each local
 * maximum that can still beat the largest (within speed x half a spacing of
 * it), at most MAX_PEAKS of them, the largest first.  Queries whose polyline
 * distance + margin is below the largest polyline distance - margin skip
 * stage 2: the curve is within the margin of its polyline, so they are below
 * the sampled maximum, and skipping them changes no result.
 *
 * The reference's floor (its error estimate, reported as `floor`): the final
 * grid spacings (< 1e-10 in each parameter) times the speeds of the two
 * curves, plus 1e-14 for rounding: 1e-10 to 1e-9 on the curves here.  That
 * holds when the nested grids start in the right basin (the inner grids' first
 * spacing is a tenth of a polyline segment); a worst-case Lipschitz bound
 * would be speed x 1.25e-4, far looser than what the brute-force self-checks
 * observe.  The self-checks compare the reference with 401 x 40001
 * point-to-point distances (testlib's evaluator): brute force over-estimates
 * each nearest distance by at most the target's speed x half its spacing.
 *
 * What is checked, per job: reported max_err (the run's maximum over its
 * accepted pieces) <= 1.05 x reference + floor and >= reference - floor, the
 * reference being the maximum over the job's pieces (host/view/jobview.h refits
 * them exactly as the run measured them); and the same for every piece, as
 * ob_measure measures it (a piece over-reported below the job's maximum
 * still decides where the driver splits).  Run with -v for the whole table
 * and the self-check figures.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/view/jobview.h"
#include "methods/metrics/metric.h"
#include "tests/testlib.h"

enum {
    NSEG = 400,      /* stage-1 polyline segments */
    NQ = 4000,       /* query sample intervals: NQ + 1 samples */
    SUB = NQ / NSEG, /* query samples per polyline segment */
    BLK = 10,        /* polyline segments per culling block */
    NBLK = NSEG / BLK,
    NGRID = 21,      /* points of each nested-grid level after the first */
    MAX_PEAKS = 16,  /* local maxima refined per one-sided term */
    BF_Q = 400,      /* brute force: query intervals */
    BF_T = 40000     /* brute force: target intervals */
};
static const double MARGIN = 4.0; /* candidate margin, in chord-to-curve deviations */
static const double STOP = 1e-10; /* nested grids stop below this spacing */

static int verbose;

/* ---- independent evaluation ----------------------------------------------------- */

/* A homogeneous Bezier segment ready for O(n) evaluation: its control points
 * and its hodograph's (n (P_{i+1} - P_i), homogeneous), each pre-multiplied by
 * its binomial coefficient, so that a point is a plain sum of t^i (1-t)^(m-i)
 * terms. */
typedef struct {
    int n;
    double P[OB_MAX_DEG + 1][3];
    double D[OB_MAX_DEG][3];
} rbez;

static void rbez_init(rbez *r, const ob_bez *b)
{
    const int n = b->deg;
    r->n = n;
    for (int i = 0; i <= n; i++)
        for (int c = 0; c < 3; c++)
            r->P[i][c] = binom(n, i) * b->h[i][c];
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            r->D[i][c] = n * binom(n - 1, i) * (b->h[i + 1][c] - b->h[i][c]);
}

/* Purpose: Euclidean point of r at t, and (v != NULL) its derivative.
 * Method:  the homogeneous sums of the points (degree n) and of the hodograph
 *          (degree n - 1) in one pass over the powers of t and 1 - t, then
 *          the quotient rule x' = (X' W - X W') / W^2. */
static void rbez_eval(const rbez *r, double t, double p[2], double v[2])
{
    const int n = r->n;
    const double s = 1.0 - t;
    double sp[OB_MAX_DEG + 1], H[3] = {0.0, 0.0, 0.0}, H1[3] = {0.0, 0.0, 0.0}, tp = 1.0;
    sp[0] = 1.0;
    for (int i = 1; i <= n; i++)
        sp[i] = sp[i - 1] * s;
    for (int i = 0; i <= n; i++) {
        const double c = tp * sp[n - i];
        H[0] += c * r->P[i][0];
        H[1] += c * r->P[i][1];
        H[2] += c * r->P[i][2];
        if (v && i < n) {
            const double c1 = tp * sp[n - 1 - i];
            H1[0] += c1 * r->D[i][0];
            H1[1] += c1 * r->D[i][1];
            H1[2] += c1 * r->D[i][2];
        }
        tp *= t;
    }
    p[0] = H[0] / H[2];
    p[1] = H[1] / H[2];
    if (v) {
        v[0] = (H1[0] * H[2] - H[0] * H1[2]) / (H[2] * H[2]);
        v[1] = (H1[1] * H[2] - H[1] * H1[2]) / (H[2] * H[2]);
    }
}

/* One curve of a comparison: the segment itself, or its d-offset. */
typedef struct {
    rbez b;
    int offset;
    double d;
} rcurve;

/* Point of the curve at t.  The offset is C + d (-y', x') / |C'|; where C'
 * vanishes (a collapsed end leg) the one-sided limit of the normal is taken by
 * moving 1e-9 into the segment, where C' points along C'' (or -C'' at t = 1). */
static void rc_point(const rcurve *c, double t, double p[2])
{
    if (!c->offset) {
        rbez_eval(&c->b, t, p, NULL);
        return;
    }
    double v[2];
    rbez_eval(&c->b, t, p, v);
    double len = sqrt(v[0] * v[0] + v[1] * v[1]);
    if (!(len > 1e-13)) {
        double q[2];
        rbez_eval(&c->b, t < 0.5 ? t + 1e-9 : t - 1e-9, q, v);
        len = sqrt(v[0] * v[0] + v[1] * v[1]);
    }
    p[0] -= c->d * v[1] / len;
    p[1] += c->d * v[0] / len;
}

/* ---- the reference ------------------------------------------------------------ */

/* A curve sampled for the reference: NQ + 1 samples (the queries when it is
 * the query side), the polyline through every SUB-th of them (the stage-1
 * target when it is the target side: segment j from a[j] along v[j], il[j] =
 * 1 / |v[j]|^2), the polyline in blocks of BLK segments, each inside a circle
 * (bc, br), the largest deviation of the curve from a chord (estimated from
 * the SUB - 1 samples inside each) and the largest speed |dP/dt| (1.1 x the
 * longest sample chord x NQ). */
typedef struct {
    rcurve c;
    double q[NQ + 1][2];
    double a[NSEG][2], v[NSEG][2], il[NSEG];
    double bc[NBLK][2], br[NBLK];
    double maxdev, speed;
} side;

/* Squared distance from p to segment j of s. */
static double seg_d2(const side *s, int j, const double p[2])
{
    const double dx = p[0] - s->a[j][0], dy = p[1] - s->a[j][1];
    double w = (dx * s->v[j][0] + dy * s->v[j][1]) * s->il[j];
    w = w < 0 ? 0 : w > 1 ? 1 : w;
    const double ex = dx - w * s->v[j][0], ey = dy - w * s->v[j][1];
    return ex * ex + ey * ey;
}

/* The polyline's segments, their blocks' bounding circles (centre: the mean
 * of the block's vertices; radius: the farthest of them, so the segments,
 * convex combinations of the vertices, lie inside) and the deviation. */
static void side_polyline(side *s)
{
    for (int j = 0; j < NSEG; j++) {
        const double *p = s->q[j * SUB], *r = s->q[(j + 1) * SUB];
        s->a[j][0] = p[0];
        s->a[j][1] = p[1];
        s->v[j][0] = r[0] - p[0];
        s->v[j][1] = r[1] - p[1];
        const double L = s->v[j][0] * s->v[j][0] + s->v[j][1] * s->v[j][1];
        s->il[j] = L > 0 ? 1.0 / L : 0.0;
    }
    for (int b = 0; b < NBLK; b++) {
        double c[2] = {0.0, 0.0}, r = 0.0;
        for (int j = b * BLK; j <= (b + 1) * BLK; j++) {
            c[0] += s->q[j * SUB][0] / (BLK + 1);
            c[1] += s->q[j * SUB][1] / (BLK + 1);
        }
        for (int j = b * BLK; j <= (b + 1) * BLK; j++)
            r = fmax(r, dist2d(c, s->q[j * SUB]));
        s->bc[b][0] = c[0];
        s->bc[b][1] = c[1];
        s->br[b] = r * (1.0 + 1e-12) + 1e-300; /* rounding must not cut a segment off */
    }
    double dev = 0.0;
    for (int j = 0; j < NSEG; j++)
        for (int i = 1; i < SUB; i++)
            dev = fmax(dev, seg_d2(s, j, s->q[j * SUB + i]));
    s->maxdev = sqrt(dev);
}

/* Purpose: sample curve b (or its d-offset), build its polyline, and estimate
 * its deviation and speed. */
static void side_init(side *s, const ob_bez *b, int offset, double d)
{
    rbez_init(&s->c.b, b);
    s->c.offset = offset;
    s->c.d = d;
    for (int k = 0; k <= NQ; k++)
        rc_point(&s->c, (double)k / NQ, s->q[k]);
    side_polyline(s);
    double ch = 0.0;
    for (int k = 0; k < NQ; k++)
        ch = fmax(ch, dist2d(s->q[k], s->q[k + 1]));
    s->speed = 1.1 * ch * NQ;
}

typedef double (*objfn)(const void *ctx, double t);

/* Purpose: the minimum of f over [a, b] by nested grids.
 * Method:  npts equally spaced points over [a, b]; then, level by level, NGRID
 *          points over the best point +- 1 spacing (clamped to [a, b]): where
 *          f is unimodal between the best point's neighbours its minimum lies
 *          there.  Each level is at least 10 times narrower; stops once the
 *          spacing is below STOP.  The best value is kept across levels, so it
 *          never increases; returns it. */
static double nested_min(objfn f, const void *ctx, double a, double b, int npts)
{
    double lo = a, hi = b, bt = a, bv = INFINITY;
    for (int m = npts;; m = NGRID) {
        const double h = (hi - lo) / (m - 1);
        for (int i = 0; i < m; i++) {
            const double t = i == m - 1 ? hi : lo + h * i;
            const double v = f(ctx, t);
            if (v < bv) {
                bv = v;
                bt = t;
            }
        }
        if (!(h >= STOP))
            break;
        lo = bt - h > a ? bt - h : a;
        hi = bt + h < b ? bt + h : b;
    }
    return bv;
}

typedef struct {
    const rcurve *c;
    const double *q;
} near_ctx;

/* Squared distance from the context's point to the curve point at t. */
static double near_obj(const void *ctx, double t)
{
    const near_ctx *n = ctx;
    double p[2];
    rc_point(n->c, t, p);
    const double dx = p[0] - n->q[0], dy = p[1] - n->q[1];
    return dx * dx + dy * dy;
}

/* Purpose: stage 1: the squared distances from q to the polyline segments
 *          into d2[]; returns the smallest.
 * Method:  exact point-segment distances over the whole polyline.  A block
 *          whose bounding circle is farther than ub + margin (ub: the nearest
 *          block middle vertex, a polyline point) is skipped and its d2 set to
 *          +inf: each of its segments is provably farther than the nearest
 *          one + margin, so neither the result nor the set of segments within
 *          margin of it changes; only the work does. */
static double poly_scan(const side *s, const double q[2], double margin, double d2[NSEG])
{
    double c2[NBLK], ub2 = INFINITY, best = INFINITY;
    for (int b = 0; b < NBLK; b++) {
        const double cx = q[0] - s->bc[b][0], cy = q[1] - s->bc[b][1];
        const double *m = s->q[(b * BLK + BLK / 2) * SUB], mx = q[0] - m[0], my = q[1] - m[1];
        c2[b] = cx * cx + cy * cy;
        const double m2 = mx * mx + my * my;
        ub2 = m2 < ub2 ? m2 : ub2;
    }
    const double lim = sqrt(ub2) + margin;
    for (int b = 0; b < NBLK; b++) {
        const double far = lim + s->br[b]; /* |q - centre| - radius > lim */
        const int skip = c2[b] > far * far;
        for (int j = b * BLK; j < (b + 1) * BLK; j++) {
            d2[j] = skip ? INFINITY : seg_d2(s, j, q);
            best = d2[j] < best ? d2[j] : best;
        }
    }
    return best;
}

/* Purpose: distance from q to the curve of side s.
 * Method:  stage 1 (poly_scan), then stage 2: every run of consecutive
 *          segments within sqrt(best) + MARGIN x maxdev is refined on the true
 *          curve by nested grids over the run widened by half a segment each
 *          side (10 points per segment at the first level); the minimum over
 *          the runs.  The window overlap lets a foot near a vertex be found
 *          from either side. */
static double nearest(const side *s, const double q[2])
{
    double d2[NSEG];
    const double margin = MARGIN * s->maxdev;
    const double lim = sqrt(poly_scan(s, q, margin, d2)) + margin, lim2 = lim * lim;
    const near_ctx ctx = {&s->c, q};
    double res = INFINITY;
    for (int j = 0; j < NSEG;) {
        if (d2[j] > lim2) {
            j++;
            continue;
        }
        int k = j;
        while (k + 1 < NSEG && d2[k + 1] <= lim2)
            k++;
        const double a = fmax(0.0, (j - 0.5) / NSEG), b = fmin(1.0, (k + 1.5) / NSEG);
        const double r = nested_min(near_obj, &ctx, a, b, 10 * (k - j + 2) + 1);
        res = r < res ? r : res;
        j = k + 1;
    }
    return sqrt(res);
}

typedef struct {
    const side *q, *t;
} far_ctx;

/* Minus the distance from the query curve's point at u to the target curve
 * (nested_min then maximises the distance). */
static double far_obj(const void *ctx, double u)
{
    const far_ctx *f = ctx;
    double p[2];
    rc_point(&f->q->c, u, p);
    return -nearest(f->t, p);
}

/* Indices of the local maxima of f[0..NQ] (skipped samples are -inf) within
 * slack of fmax, largest first, at most MAX_PEAKS; returns their count. */
static int find_peaks(const double *f, double fmx, double slack, int *pk)
{
    int np = 0;
    for (int k = 0; k <= NQ; k++) {
        const double l = k > 0 ? f[k - 1] : -INFINITY, r = k < NQ ? f[k + 1] : -INFINITY;
        if (!(f[k] >= fmx - slack && f[k] >= l && f[k] >= r))
            continue;
        if (np == MAX_PEAKS && f[pk[np - 1]] >= f[k])
            continue; /* full, and no larger than the smallest kept */
        int i = np < MAX_PEAKS ? np++ : np - 1; /* insertion by value */
        while (i > 0 && f[pk[i - 1]] < f[k]) {
            pk[i] = pk[i - 1];
            i--;
        }
        pk[i] = k;
    }
    return np;
}

/* Purpose: sup over u of dist(Q(u), T), Q the query side, T the target side.
 * Method:  stage 1 for every sample; stage 2 for those whose polyline bound
 *          reaches the largest lower bound (the others are below the
 *          sampled maximum: skipping them changes nothing); the maximum over
 *          the samples, then the nested grid on u over +- one spacing around
 *          each peak that can still beat it: between samples the distance can
 *          exceed a sample by at most slack = speed x half a spacing. */
static double one_sided(const side *q, const side *t)
{
    static double p[NQ + 1], f[NQ + 1];
    const double margin = MARGIN * t->maxdev, slack = 0.5 * q->speed / NQ;
    double d2[NSEG], lb = -INFINITY, fmx = -INFINITY;
    for (int k = 0; k <= NQ; k++) {
        p[k] = sqrt(poly_scan(t, q->q[k], 0.0, d2));
        lb = fmax(lb, p[k] - margin);
    }
    for (int k = 0; k <= NQ; k++) {
        f[k] = p[k] + margin >= lb ? nearest(t, q->q[k]) : -INFINITY;
        fmx = f[k] > fmx ? f[k] : fmx;
    }
    int pk[MAX_PEAKS];
    const int np = find_peaks(f, fmx, slack, pk);
    const far_ctx ctx = {q, t};
    for (int i = 0; i < np; i++) {
        if (f[pk[i]] + slack <= fmx)
            continue; /* cannot beat the maximum found so far */
        const double u = (double)pk[i] / NQ, a = fmax(0.0, u - 1.0 / NQ), b = fmin(1.0, u + 1.0 / NQ);
        fmx = fmax(fmx, -nested_min(far_obj, &ctx, a, b, NGRID));
    }
    return fmx;
}

/* The reference's error estimate for a one-sided term with these sides. */
static double side_floor(const side *q, const side *t) { return (q->speed + t->speed) * STOP + 1e-14; }

/* Purpose: the reference two-sided Hausdorff distance between approx and the
 * untrimmed d-offset of base over [0, 1]; *floor gets its error estimate. */
static double ref_hausdorff(const ob_bez *base, const ob_bez *approx, double d, double *floor)
{
    static side A, O;
    side_init(&A, approx, 0, 0.0);
    side_init(&O, base, 1, d);
    *floor = side_floor(&A, &O);
    return fmax(one_sided(&A, &O), one_sided(&O, &A));
}

/* ---- self-checks of the reference ---------------------------------------------- */

/* liu2002_ex1's control points (datasets/published.curves). */
static const double liu_ex1[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};

/* The evaluator here agrees with testlib's (a different formula) on a
 * rational and a polynomial segment. */
static void test_evaluator(void)
{
    static const double w[4] = {1.0, 0.7, 1.6, 1.0};
    const ob_bez bs[2] = {make(3, liu_ex1, NULL), make(3, liu_ex1, w)};
    double dev = 0.0;
    for (int k = 0; k < 2; k++) {
        rcurve c = {.offset = 1, .d = 0.75};
        rbez_init(&c.b, &bs[k]);
        for (int i = 0; i <= 50; i++) {
            const double t = i / 50.0;
            double a[2], b[2], pa[2], v[2], e[2][2];
            rc_point(&c, t, a);
            ref_offset(&bs[k], t, 0.75, b);
            rbez_eval(&c.b, t, pa, v);
            ref_eval(&bs[k], t, 1, e);
            dev = fmax(dev, fmax(dist2d(a, b), fmax(dist2d(pa, e[0]), dist2d(v, e[1]))));
        }
    }
    CHECK(dev < 1e-12, "point, derivative and offset agree with testlib's evaluator (off by %g)", dev);
}

/* Concentric arcs with the same angular span are exactly e apart: the
 * d = 0.5 offset of the counterclockwise unit quarter circle (the left normal
 * points to the centre) is the radius-0.5 arc; approx is the radius 0.5 + e arc. */
static void test_concentric(void)
{
    const double e = 1e-3;
    const ob_bez base = quarter_circle(1.0, 0), approx = quarter_circle(0.5 + e, 0);
    double floor;
    const double h = ref_hausdorff(&base, &approx, 0.5, &floor);
    CHECK(fabs(h - e) <= floor, "concentric quarter circles: %.17g vs %g (floor %g)", h, e, floor);
    if (verbose)
        printf("self-check concentric arcs: reference %.17g, exact %g, floor %.3g\n", h, e, floor);
}

/* Brute-force one-sided term: 401 query points to 40001 target points
 * (testlib's evaluator), and the reference's nearest distances at the same
 * 401 queries.  Returns the brute-force maximum; *lo_dev / *hi_dev get the
 * extreme pointwise (reference - brute force). */
static double brute_side(const rcurve *qc, const ob_bez *qb, const side *t, const ob_bez *tb,
                         double *lo_dev, double *hi_dev)
{
    double(*tp)[2] = malloc((BF_T + 1) * sizeof *tp);
    double bmax = 0.0;
    *lo_dev = INFINITY;
    *hi_dev = -INFINITY;
    for (int j = 0; j <= BF_T && tp; j++) {
        if (t->c.offset)
            ref_offset(tb, (double)j / BF_T, t->c.d, tp[j]);
        else
            ref_point(tb, (double)j / BF_T, tp[j]);
    }
    for (int i = 0; i <= BF_Q && tp; i++) {
        double q[2];
        if (qc->offset)
            ref_offset(qb, (double)i / BF_Q, qc->d, q);
        else
            ref_point(qb, (double)i / BF_Q, q);
        double best = INFINITY;
        for (int j = 0; j <= BF_T; j++) {
            const double dx = tp[j][0] - q[0], dy = tp[j][1] - q[1];
            best = fmin(best, dx * dx + dy * dy);
        }
        best = sqrt(best);
        const double r = nearest(t, q);
        *lo_dev = fmin(*lo_dev, r - best);
        *hi_dev = fmax(*hi_dev, r - best);
        bmax = fmax(bmax, best);
    }
    free(tp);
    return bmax;
}

/* What one brute-force comparison found: the reference h and the brute-force
 * maximum bh, the extreme pointwise (reference - brute force) lo and hi, and
 * the allowances: brute force over-estimates a nearest distance by at most
 * al (the target's speed x half its spacing), the 401 queries miss the
 * supremum by at most up (the query's speed x half theirs); fl the floor. */
typedef struct {
    double h, bh, lo, hi, al, up, fl;
} brute_res;

/* Purpose: the reference against brute force on one (base, approx, d), both
 * one-sided terms; the pointwise distances are checked here. */
static void brute_compare(const char *what, const ob_bez *base, const ob_bez *approx, double d, brute_res *r)
{
    static side A, O;
    double lo1, hi1, lo2, hi2;
    side_init(&A, approx, 0, 0.0);
    side_init(&O, base, 1, d);
    r->h = fmax(one_sided(&A, &O), one_sided(&O, &A));
    r->fl = side_floor(&A, &O);
    r->bh = fmax(brute_side(&A.c, approx, &O, base, &lo1, &hi1), brute_side(&O.c, base, &A, approx, &lo2, &hi2));
    const double al1 = O.speed * 0.5 / BF_T, al2 = A.speed * 0.5 / BF_T;
    CHECK(hi1 <= r->fl && hi2 <= r->fl && lo1 >= -al1 - r->fl && lo2 >= -al2 - r->fl,
          "%s: nearest distances, reference - brute force in [%g, %g] (A->O) and [%g, %g] (O->A), allowed "
          "[-%g, %g] and [-%g, %g]",
          what, lo1, hi1, lo2, hi2, al1, r->fl, al2, r->fl);
    r->lo = fmin(lo1, lo2);
    r->hi = fmax(hi1, hi2);
    r->al = fmax(al1, al2);
    r->up = fmax(A.speed, O.speed) * 0.5 / BF_Q;
}

/* The reference's maximum must lie within the brute force's allowances. */
static void check_brute_max(const char *what, const brute_res *r)
{
    CHECK(r->h >= r->bh - r->al - r->fl && r->h <= r->bh + r->up + r->fl,
          "%s: reference %.17g vs brute force %.17g (allowed -%g / +%g)", what, r->h, r->bh, r->al, r->up);
    if (verbose)
        printf("self-check %s: reference %.10g, brute force %.10g (allowed -%.2g / +%.2g); pointwise reference - "
               "brute force in [%.3g, %.3g] (allowed [-%.2g, %.2g]); floor %.3g\n",
               what, r->h, r->bh, r->al, r->up, r->lo, r->hi, r->al, r->fl, r->fl);
}

/* ---- jobs through the pipeline -------------------------------------------------- */

typedef struct {
    const char *random;   /* --random spec, or NULL for the embedded data */
    const char *curve;
    int have_d;
    double d;
    const char *method, *tol;
} job_spec;

/* Opens and runs one job; 0 when it produced an approximation. */
static int run_job(ob_jobview *v, const job_spec *j)
{
    char *argv[20];
    int argc = 0;
    argv[argc++] = (char *)"test";
    if (j->random) {
        argv[argc++] = (char *)"--random";
        argv[argc++] = (char *)j->random;
    }
    /* one thread: idle OpenMP workers would spin against the reference */
    const char *rest[] = {"--curve",   j->curve, "--methods", j->method, "--tols",    j->tol,    "--metric",
                          "hausdorff", "--split", "mid",      "--backend", "cpu",    "--threads", "1",
                          NULL};
    for (int i = 0; rest[i]; i++)
        argv[argc++] = (char *)rest[i];
    argv[argc] = NULL;
    memset(v, 0, sizeof *v);
    int rc = ob_run_opts_parse(argc, argv, &v->o) ? 2 : ob_jobview_open(v, "test", j->have_d, j->d);
    if (rc == 0)
        rc = ob_jobview_run(v);
    return rc == 0 && ob_jobview_has_approx(v) ? 0 : 1;
}

/* Purpose: one job: the reference over its pieces against the reported max_err. */
static void check_job(const job_spec *j)
{
    ob_jobview v;
    const int bad = run_job(&v, j);
    CHECK(!bad, "%s %s %s: the job runs and produces an approximation", j->curve, j->method, j->tol);
    if (bad) {
        ob_jobview_close(&v);
        return;
    }
    double ref = 0.0, floor = 0.0;
    int worst = 0, pieces_ok = 0;
    for (int i = 0; i < v.npieces; i++) {
        double fl;
        const double h = ref_hausdorff(&v.pieces[i].base, &v.pieces[i].approx, v.job.d, &fl);
        /* each piece as the driver measured it: a piece over-reported below
         * the job's maximum still decides a split */
        ob_errval e;
        ob_measure(OB_METRIC_HAUSDORFF, &v.pieces[i].base, &v.pieces[i].approx, v.job.d, v.samples, &e);
        const int pok = e.err <= 1.05 * h + fl && e.err >= h - fl;
        pieces_ok += pok;
        if (!pok)
            printf("  %s d = %g %s tol %s, piece %d [%.6g, %.6g]: measured %.6e, reference %.6e, ratio %.4f\n",
                   j->curve, v.job.d, j->method, j->tol, i, v.pieces[i].ta, v.pieces[i].tb, e.err, h, e.err / h);
        floor = fmax(floor, fl);
        if (h > ref) {
            ref = h;
            worst = i;
        }
    }
    const double rep = v.job.max_err, ratio = rep / ref;
    const int ok = rep <= 1.05 * ref + floor && rep >= ref - floor;
    CHECK(rep <= 1.05 * ref + floor && rep >= ref - floor,
          "%s d = %g %s tol %s: reported %.6g, reference %.6g, ratio %.4f (floor %.2g; the reference's largest on "
          "piece %d of %d)",
          j->curve, v.job.d, j->method, j->tol, rep, ref, ratio, floor, worst, v.npieces);
    CHECK(pieces_ok == v.npieces, "%s d = %g %s tol %s: %d of %d pieces measured within 5 %% of the reference",
          j->curve, v.job.d, j->method, j->tol, pieces_ok, v.npieces);
    if (verbose)
        printf("%-12s %10.6g %-14s %-6s %3d pieces  reported %.6e  reference %.6e  ratio %7.4f  %s\n", j->curve,
               v.job.d, j->method, j->tol, v.npieces, rep, ref, ratio, ok ? "ok" : "FAIL");
    ob_jobview_close(&v);
}

/* liu2002_ex1 at both signs (d = +1 has two offset cusps and a swallowtail),
 * seven methods at 1e-2 and 1e-3 and two at 1e-5 (the finest jobs cost the
 * most), and the tight and loop random families (curves i = 5, 6 mod 8) with
 * their first offsets. */
static void test_jobs(void)
{
    static const char *const methods[] = {"interp", "ahn", "tiller", "cobb", "zhao-rational", "lee", "hoschek"};
    static const char *const tols[] = {"1e-2", "1e-3"};
    static const char *const fine[] = {"zhao-rational", "ahn"}; /* 1e-5 costs: two methods */
    static const char *const rnd[] = {"rnd1_000005", "rnd1_000013", "rnd1_000021",
                                      "rnd1_000006", "rnd1_000014", "rnd1_000022"};
    static const char *const rmethods[] = {"interp", "tiller"};
    for (int s = 0; s < 2; s++) {
        const double d = s ? 1.0 : -1.0;
        for (size_t m = 0; m < sizeof methods / sizeof *methods; m++)
            for (size_t t = 0; t < sizeof tols / sizeof *tols; t++)
                check_job(&(job_spec){NULL, "liu2002_ex1", 1, d, methods[m], tols[t]});
        for (size_t m = 0; m < sizeof fine / sizeof *fine; m++)
            check_job(&(job_spec){NULL, "liu2002_ex1", 1, d, fine[m], "1e-5"});
    }
    for (size_t c = 0; c < sizeof rnd / sizeof *rnd; c++)
        for (size_t m = 0; m < sizeof rmethods / sizeof *rmethods; m++)
            check_job(&(job_spec){"24:1", rnd[c], 0, 0.0, rmethods[m], "1e-3"});
}

/* The brute-force self-checks: liu2002_ex1 against its own d = +1 offset
 * (the whole swallowtail and both cusps in the target), and every piece of a
 * d = +1 job that the metric over-reports (interp, 1e-3): the reference's
 * job maximum is the brute force's within its allowances. */
static void test_self(void)
{
    const ob_bez c = make(3, liu_ex1, NULL);
    brute_res r;
    brute_compare("liu2002_ex1 vs its d = +1 offset", &c, &c, 1.0, &r);
    check_brute_max("liu2002_ex1 vs its d = +1 offset", &r);
    ob_jobview v;
    const job_spec j = {NULL, "liu2002_ex1", 1, 1.0, "interp", "1e-3"};
    const int bad = run_job(&v, &j);
    CHECK(!bad, "the interp 1e-3 d = +1 job runs");
    brute_res all = {0.0, 0.0, INFINITY, -INFINITY, 0.0, 0.0, 0.0};
    for (int i = 0; i < v.npieces && !bad; i++) {
        char what[64];
        snprintf(what, sizeof what, "interp 1e-3 d = +1, piece %d", i);
        brute_compare(what, &v.pieces[i].base, &v.pieces[i].approx, 1.0, &r);
        all.h = fmax(all.h, r.h);
        all.bh = fmax(all.bh, r.bh);
        all.lo = fmin(all.lo, r.lo);
        all.hi = fmax(all.hi, r.hi);
        all.al = fmax(all.al, r.al);
        all.up = fmax(all.up, r.up);
        all.fl = fmax(all.fl, r.fl);
    }
    if (!bad)
        check_brute_max("interp 1e-3 d = +1, every piece", &all);
    ob_jobview_close(&v);
}

int main(int argc, char **argv)
{
    verbose = argc > 1 && strcmp(argv[1], "-v") == 0;
    test_evaluator();
    test_concentric();
    test_self();
    test_jobs();
    return check_done();
}
