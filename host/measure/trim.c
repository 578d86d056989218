/*
 * trim.c - the trimmed offset (trim.h): split points of the untrimmed
 * offset located to round-off, then each arc between two of them kept or
 * removed by its midpoint's distance to the base curve; at each corner
 * (G0 joint) on its convex side the circle arc about the corner, split
 * and decided the same way.
 */
#include "host/measure/trim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { BLOCK = 32, BASE_SCAN = 256 };

typedef ob_trim_corner corner;

typedef struct {
    const ob_curve *c;
    double d, size;
    int closed;
    int M;             /* chords per segment polyline */
    double *poly;      /* [side][seg][M + 1][2]: side 0 is O_d, side 1 O_-d */
    double *box;       /* per block of BLOCK chords: x0, y0, x1, y1 */
    int nblk;          /* blocks per side */
    ob_trim_split *sp;
    int nsp, capsp;
    corner *cn;        /* the corners, by seg */
    int ncn;
    char *g0;          /* [nseg]: 1 when the joint at the start of the segment is a corner */
    double *ang;       /* scratch: a corner arc's split points, as parameters u in (0, 1) */
    int nang, capang;
} trimmer;

/* O(t) = C(t) + dd N(t) on segment b and its derivative C'(1 - dd kappa). */
static void opoint(const ob_bez *b, double t, double dd, double p[2], double dp[2])
{
    double e[3][2];
    ob_bez_eval(b, t, 2, e);
    const double L = hypot(e[1][0], e[1][1]);
    if (!(L > 0.0)) {
        ob_bez_offset_point(b, t, dd, p);
        dp[0] = dp[1] = 0.0;
        return;
    }
    const double k = (e[1][0] * e[2][1] - e[1][1] * e[2][0]) / (L * L * L), f = 1.0 - dd * k;
    p[0] = e[0][0] - dd * e[1][1] / L, p[1] = e[0][1] + dd * e[1][0] / L;
    dp[0] = e[1][0] * f, dp[1] = e[1][1] * f;
}

/* The size of the curve: the diagonal of its control points' box, plus |d|. */
double ob_trim_curve_size(const ob_curve *c, double d)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, p[2];
    for (int k = 0; k < c->nseg; k++)
        for (int i = 0; i <= c->seg[k].deg; i++) {
            ob_bez_ctrl(&c->seg[k], i, p);
            x0 = fmin(x0, p[0]), y0 = fmin(y0, p[1]), x1 = fmax(x1, p[0]), y1 = fmax(y1, p[1]);
        }
    return hypot(x1 - x0, y1 - y0) + fabs(d);
}

static int add_split(trimmer *w, int seg, double t, ob_split_kind kind)
{
    if (w->nsp == w->capsp) {
        const int cap = w->capsp ? 2 * w->capsp : 16;
        ob_trim_split *nv = realloc(w->sp, (size_t)cap * sizeof *nv);
        if (!nv)
            return -1;
        w->sp = nv, w->capsp = cap;
    }
    w->sp[w->nsp++] = (ob_trim_split){seg, t, kind};
    return 0;
}

static double *vertex(const trimmer *w, int side, int seg, int i)
{
    return w->poly + 2 * (((size_t)side * w->c->nseg + seg) * (size_t)(w->M + 1) + i);
}

/* The polylines of O_d and O_-d and the boxes of their blocks of chords. */
static void build_poly(trimmer *w)
{
    const int bps = w->M / BLOCK;
    for (int s = 0; s < 2; s++)
        for (int k = 0; k < w->c->nseg; k++) {
            for (int i = 0; i <= w->M; i++) {
                double dp[2];
                opoint(&w->c->seg[k], (double)i / w->M, s ? -w->d : w->d, vertex(w, s, k, i), dp);
            }
            for (int b = 0; b < bps; b++) {
                double *bx = w->box + 4 * ((size_t)s * w->nblk + (size_t)k * bps + b);
                bx[0] = bx[1] = INFINITY, bx[2] = bx[3] = -INFINITY;
                for (int i = b * BLOCK; i <= (b + 1) * BLOCK; i++) {
                    const double *p = vertex(w, s, k, i);
                    bx[0] = fmin(bx[0], p[0]), bx[1] = fmin(bx[1], p[1]);
                    bx[2] = fmax(bx[2], p[0]), bx[3] = fmax(bx[3], p[1]);
                }
            }
        }
}

/* 1 when (seg a, t) and (seg b, u) are one point of the base (the trivial
 * root of O(s) = O(u)): one parameter, or a joint's two sides. */
static int same_place(const trimmer *w, int a, double t, int b, double u)
{
    const double e = 1e-9;
    const int n = w->c->nseg;
    if (a == b)
        return fabs(t - u) <= e;
    /* across a corner O has a gap: a root next to it is a real crossing
     * (the concave side's, |d| from the corner) */
    if ((a + 1 == b || (w->closed && a == n - 1 && b == 0)) && t >= 1.0 - e && u <= e)
        return !w->g0[b];
    return (b + 1 == a || (w->closed && b == n - 1 && a == 0)) && u >= 1.0 - e && t <= e && !w->g0[a];
}

/* 1 when global chords gi and gj of O_d share a vertex: neighbours on one
 * segment or across a smooth joint (a corner's two chords do not meet
 * there: their crossing, on the concave side, is looked for). */
static int chords_adjacent(const trimmer *w, long gi, long gj)
{
    const long last = (long)w->c->nseg * w->M - 1;
    long lo = gi < gj ? gi : gj, hi = gi < gj ? gj : gi;
    if (hi - lo == 1)
        return hi % w->M != 0 || !w->g0[hi / w->M];
    return w->closed && lo == 0 && hi == last && !w->g0[0];
}

/* Newton's method on O_d(s) on segment a = O_sd(u) on segment b (sd: d or
 * -d) from (*s, *u); 1 when it converged inside [0, 1]^2. */
static int newton2(const trimmer *w, int a, int b, double sd, double *s, double *u)
{
    double x = *s, y = *u;
    for (int it = 0; it < 40; it++) {
        double p[2], dp[2], q[2], dq[2];
        opoint(&w->c->seg[a], x, w->d, p, dp);
        opoint(&w->c->seg[b], y, sd, q, dq);
        const double fx = p[0] - q[0], fy = p[1] - q[1], det = -dp[0] * dq[1] + dp[1] * dq[0];
        if (!(fabs(det) > 0.0) || !isfinite(det))
            return 0;
        const double ds = (-fx * dq[1] + fy * dq[0]) / det, du = (dp[0] * fy - dp[1] * fx) / det;
        x -= ds, y -= du;
        if (!(x > -0.5 && x < 1.5 && y > -0.5 && y < 1.5))
            return 0;
        if (fabs(ds) <= 1e-16 && fabs(du) <= 1e-16)
            break;
    }
    double p[2], q[2], dp[2];
    opoint(&w->c->seg[a], x, w->d, p, dp);
    opoint(&w->c->seg[b], y, sd, q, dp);
    if (!(hypot(p[0] - q[0], p[1] - q[1]) <= 1e-12 * w->size))
        return 0;
    const double tol = 1e-12;
    if (x < -tol || x > 1.0 + tol || y < -tol || y > 1.0 + tol)
        return 0;
    *s = fmin(fmax(x, 0.0), 1.0), *u = fmin(fmax(y, 0.0), 1.0);
    return 1;
}

/* The parameters (alpha, beta) where chords p0 p1 and q0 q1 cross; 1 when
 * they do (ends included). */
static int chords_cross(const double *p0, const double *p1, const double *q0, const double *q1, double *al,
                        double *be)
{
    const double rx = p1[0] - p0[0], ry = p1[1] - p0[1], sx = q1[0] - q0[0], sy = q1[1] - q0[1];
    const double den = rx * sy - ry * sx, qx = q0[0] - p0[0], qy = q0[1] - p0[1];
    if (den == 0.0)
        return 0;
    *al = (qx * sy - qy * sx) / den, *be = (qx * ry - qy * rx) / den;
    const double e = 1e-9;
    return *al >= -e && *al <= 1.0 + e && *be >= -e && *be <= 1.0 + e;
}

static int boxes_meet(const double *a, const double *b)
{
    return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3];
}

/* The crossings of the chords of block ba (side 0) with those of block bb
 * (side sb), refined; 0, or -1 out of memory. */
static int cross_blocks(trimmer *w, int ba, int sb, int bb)
{
    const int bps = w->M / BLOCK, ka = ba / bps, kb = bb / bps;
    const double sd = sb ? -w->d : w->d;
    for (int i = (ba % bps) * BLOCK; i < (ba % bps + 1) * BLOCK; i++)
        for (int j = (bb % bps) * BLOCK; j < (bb % bps + 1) * BLOCK; j++) {
            const long gi = (long)ka * w->M + i, gj = (long)kb * w->M + j;
            if (sb == 0 && (gi == gj || chords_adjacent(w, gi, gj)))
                continue;
            if (sb == 0 && gj < gi)
                continue; /* each pair once */
            double al, be;
            if (!chords_cross(vertex(w, 0, ka, i), vertex(w, 0, ka, i + 1), vertex(w, sb, kb, j),
                              vertex(w, sb, kb, j + 1), &al, &be))
                continue;
            double s = (i + al) / w->M, u = (j + be) / w->M;
            if (!newton2(w, ka, kb, sd, &s, &u) || (sb == 0 && same_place(w, ka, s, kb, u)))
                continue;
            if (add_split(w, ka, s, sb ? OB_SPLIT_OPPOSITE : OB_SPLIT_SELF) ||
                (sb == 0 && add_split(w, kb, u, OB_SPLIT_SELF)))
                return -1;
        }
    return 0;
}

/* Every crossing of O_d with itself and with O_-d. */
static int crossings(trimmer *w)
{
    for (int ba = 0; ba < w->nblk; ba++)
        for (int sb = 0; sb < 2; sb++)
            for (int bb = sb ? 0 : ba; bb < w->nblk; bb++)
                if (boxes_meet(w->box + 4 * (size_t)ba, w->box + 4 * ((size_t)sb * w->nblk + bb)) &&
                    cross_blocks(w, ba, sb, bb))
                    return -1;
    return 0;
}

static double circ_f(const trimmer *w, int k, double t, double dd, const double E[2])
{
    double p[2];
    ob_bez_offset_point(&w->c->seg[k], t, dd, p);
    return (p[0] - E[0]) * (p[0] - E[0]) + (p[1] - E[1]) * (p[1] - E[1]) - w->d * w->d;
}

static int add_ang(trimmer *w, double u)
{
    if (w->nang == w->capang) {
        const int cap = w->capang ? 2 * w->capang : 16;
        double *nv = realloc(w->ang, (size_t)cap * sizeof *nv);
        if (!nv)
            return -1;
        w->ang = nv, w->capang = cap;
    }
    w->ang[w->nang++] = u;
    return 0;
}

/* The parameter u of point X on the arc of corner k (X - P at angle
 * a0 + sweep u), when it lies inside the arc (0 < u < 1); else -1. */
static double arc_param(const corner *k, const double X[2])
{
    const double s = k->sweep < 0.0 ? -1.0 : 1.0, twopi = 2.0 * OB_PI;
    double rel = s * (atan2(X[1] - k->P[1], X[0] - k->P[0]) - k->a0);
    rel -= twopi * floor(rel / twopi);
    const double u = rel / fabs(k->sweep);
    return u > 0.0 && u < 1.0 ? u : -1.0;
}

/* The crossings of O on side `side` (0: O_d, 1: O_-d) with the circle of
 * radius |d| about E: sign changes of |O - E|^2 - d^2 between the
 * polyline's vertices (values within round-off of 0 have no sign),
 * bisected to the last bit; each added as a split of O_d (cn NULL) or, as
 * a parameter, of corner cn's arc (outside the arc: dropped). */
static int circle_cross(trimmer *w, int side, const double E[2], const corner *cn)
{
    const double zero = 1e-11 * w->size * w->size, dd = side ? -w->d : w->d;
    for (int k = 0; k < w->c->nseg; k++) {
        const double *v = vertex(w, side, k, 0);
        double f0 = (v[0] - E[0]) * (v[0] - E[0]) + (v[1] - E[1]) * (v[1] - E[1]) - w->d * w->d;
        for (int i = 1; i <= w->M; i++) {
            v = vertex(w, side, k, i);
            const double f1 = (v[0] - E[0]) * (v[0] - E[0]) + (v[1] - E[1]) * (v[1] - E[1]) - w->d * w->d;
            if (fabs(f0) > zero && fabs(f1) > zero && (f0 < 0.0) != (f1 < 0.0)) {
                double lo = (double)(i - 1) / w->M, hi = (double)i / w->M, X[2];
                const int neg = f0 < 0.0;
                for (int it = 0; it < 80 && lo < hi; it++) {
                    const double m = 0.5 * (lo + hi);
                    if (m <= lo || m >= hi)
                        break;
                    if ((circ_f(w, k, m, dd, E) < 0.0) == neg)
                        lo = m;
                    else
                        hi = m;
                }
                ob_bez_offset_point(&w->c->seg[k], 0.5 * (lo + hi), dd, X);
                const double u = cn ? arc_param(cn, X) : 0.0;
                if (cn ? u > 0.0 && add_ang(w, u) : add_split(w, k, 0.5 * (lo + hi), OB_SPLIT_END))
                    return -1;
            }
            f0 = f1;
        }
    }
    return 0;
}

/* The crossings of corner cn's arc with the circle of radius |d| about Q
 * (another corner, an open base's end point): the two points at |d| from
 * both, on the perpendicular bisector of P Q. */
static int circle_circle(trimmer *w, const corner *cn, const double Q[2])
{
    const double dx = Q[0] - cn->P[0], dy = Q[1] - cn->P[1], D = hypot(dx, dy), r = fabs(w->d);
    if (!(D > 0.0 && D < 2.0 * r))
        return 0;
    const double h = sqrt(r * r - 0.25 * D * D), mx = cn->P[0] + 0.5 * dx, my = cn->P[1] + 0.5 * dy;
    for (int s = -1; s <= 1; s += 2) {
        const double X[2] = {mx - s * h * dy / D, my + s * h * dx / D}, u = arc_param(cn, X);
        if (u > 0.0 && add_ang(w, u))
            return -1;
    }
    return 0;
}

static int cusps(trimmer *w)
{
    for (int k = 0; k < w->c->nseg; k++) {
        double ts[65];
        const int n = ob_bez_offset_cusps(&w->c->seg[k], w->d, ts, 64);
        for (int i = 0; i < n && i < 64; i++)
            if (add_split(w, k, ts[i], OB_SPLIT_CUSP))
                return -1;
    }
    return 0;
}

static int cmp_split(const void *x, const void *y)
{
    const ob_trim_split *a = x, *b = y;
    if (a->seg != b->seg)
        return a->seg < b->seg ? -1 : 1;
    return (a->t > b->t) - (a->t < b->t);
}

/* One split for each crossing that several chords found (sorted splits of
 * one kind and segment within 1e-13 of each other). */
static void dedupe(trimmer *w)
{
    int n = 0;
    for (int i = 0; i < w->nsp; i++) {
        int dup = 0;
        for (int j = n - 1; j >= 0 && w->sp[j].seg == w->sp[i].seg && w->sp[i].t - w->sp[j].t <= 1e-13; j--)
            dup |= w->sp[j].kind == w->sp[i].kind;
        if (!dup)
            w->sp[n++] = w->sp[i];
    }
    w->nsp = n;
}

/* Golden-section minimum of |p - C(t)| on segment b over [lo, hi]. */
static double golden_min(const ob_bez *b, const double p[2], double lo, double hi)
{
    const double g = 0.6180339887498949;
    double q[2], x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1, f2;
    ob_bez_point(b, x1, q), f1 = hypot(p[0] - q[0], p[1] - q[1]);
    ob_bez_point(b, x2, q), f2 = hypot(p[0] - q[0], p[1] - q[1]);
    for (int it = 0; it < 80 && hi - lo > 1e-15; it++) {
        if (f1 < f2) {
            hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo);
            ob_bez_point(b, x1, q), f1 = hypot(p[0] - q[0], p[1] - q[1]);
        } else {
            lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo);
            ob_bez_point(b, x2, q), f2 = hypot(p[0] - q[0], p[1] - q[1]);
        }
    }
    return fmin(f1, f2);
}

double ob_trim_base_dist(const ob_curve *c, const double p[2])
{
    double best = INFINITY, f[BASE_SCAN + 1], q[2];
    for (int k = 0; k < c->nseg; k++) {
        for (int i = 0; i <= BASE_SCAN; i++) {
            ob_bez_point(&c->seg[k], (double)i / BASE_SCAN, q);
            f[i] = hypot(p[0] - q[0], p[1] - q[1]);
            best = fmin(best, f[i]); /* the ends too */
        }
        for (int i = 0; i <= BASE_SCAN; i++)
            if ((i == 0 || f[i] <= f[i - 1]) && (i == BASE_SCAN || f[i] <= f[i + 1]))
                best = fmin(best, golden_min(&c->seg[k], p, (double)(i > 0 ? i - 1 : 0) / BASE_SCAN,
                                             (double)(i < BASE_SCAN ? i + 1 : BASE_SCAN) / BASE_SCAN));
    }
    return best;
}

/* 1 when O_d on segment k at t is at distance |d| from the base. */
static int kept_at(const trimmer *w, int k, double t)
{
    double p[2];
    ob_bez_offset_point(&w->c->seg[k], t, w->d, p);
    return ob_trim_base_dist(w->c, p) >= fabs(w->d) - OB_TRIM_REL * w->size;
}

static int add_arc(ob_trim *tr, int *cap, ob_trim_arc a)
{
    ob_trim_arc *l = tr->n > 0 ? &tr->arc[tr->n - 1] : NULL;
    if (l && l->corner == a.corner && l->seg == a.seg && l->t1 == a.t0) {
        l->t1 = a.t1; /* continues the last */
        return 0;
    }
    if (tr->n == *cap) {
        const int nc = *cap ? 2 * *cap : 8;
        ob_trim_arc *nv = realloc(tr->arc, (size_t)nc * sizeof *nv);
        if (!nv)
            return -1;
        tr->arc = nv, *cap = nc;
    }
    tr->arc[tr->n++] = a;
    return 0;
}

/* Finds the corners: joints where the unit normals (ob_bez_normal: also
 * where C' vanishes) of the segment before and after differ by more than
 * OB_TRIM_CORNER radians. */
int ob_trim_corner_at(const ob_curve *c, double d, int k, int closed, ob_trim_corner *cn)
{
    const int n = c->nseg;
    if (k < 0 || k >= n || (k == 0 && !closed))
        return 0;
    const ob_bez *a = &c->seg[k ? k - 1 : n - 1], *b = &c->seg[k];
    double N1[2], N2[2];
    if (ob_bez_normal(a, 1.0, N1) || ob_bez_normal(b, 0.0, N2))
        return 0; /* a point-like segment: no direction to turn from */
    double th = atan2(N1[0] * N2[1] - N1[1] * N2[0], N1[0] * N2[0] + N1[1] * N2[1]);
    if (!(fabs(th) > OB_TRIM_CORNER))
        return 0;
    /* the arc's points P + d n(phi), n N1 turned by phi in (0, th),
     * have (Q - P).T1 = -d sin(phi): where d th > 0 (the concave
     * side) C before P comes nearer than |d| to each, no point of it
     * is kept.  A reversal (th = +-pi) is convex on both sides: the
     * arc round the front, (Q - P).T1 >= 0, turns against d. */
    if (fabs(th) >= OB_PI - OB_TRIM_CORNER)
        th = d > 0.0 ? -OB_PI : OB_PI;
    cn->seg = k, cn->convex = d * th < 0.0, cn->sweep = th;
    cn->a0 = atan2(d * N1[1], d * N1[0]);
    ob_bez_point(b, 0.0, cn->P);
    return 1;
}

static int find_corners(trimmer *w)
{
    for (int k = w->closed ? 0 : 1; k < w->c->nseg; k++)
        if (ob_trim_corner_at(w->c, w->d, k, w->closed, &w->cn[w->ncn])) {
            w->g0[k] = 1;
            w->ncn++;
        }
    return 0;
}

static int cmp_double(const void *x, const void *y)
{
    const double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Corner k's arc (convex ones only): split where the offsets on both
 * sides, the circles about the other corners and about an open base's
 * ends cross it, each part kept when its midpoint is |d| from C. */
static int corner_arcs(trimmer *w, const corner *cn, ob_trim *tr, int *cap)
{
    if (!cn->convex)
        return 0;
    w->nang = 0;
    if (circle_cross(w, 0, cn->P, cn) || circle_cross(w, 1, cn->P, cn))
        return -1;
    for (int k = 0; k < w->ncn; k++)
        if (&w->cn[k] != cn && circle_circle(w, cn, w->cn[k].P))
            return -1;
    if (!w->closed) {
        double E[2];
        ob_bez_point(&w->c->seg[0], 0.0, E);
        if (circle_circle(w, cn, E))
            return -1;
        ob_bez_point(&w->c->seg[w->c->nseg - 1], 1.0, E);
        if (circle_circle(w, cn, E))
            return -1;
    }
    if (w->nang > 0)
        qsort(w->ang, (size_t)w->nang, sizeof *w->ang, cmp_double);
    const double r = fabs(w->d);
    double a = 0.0;
    for (int j = 0; j <= w->nang; j++) {
        const double b = j < w->nang ? w->ang[j] : 1.0;
        if (!(b > a))
            continue;
        const double m = cn->a0 + cn->sweep * 0.5 * (a + b), q[2] = {cn->P[0] + r * cos(m), cn->P[1] + r * sin(m)};
        const ob_trim_arc arc = {cn->seg, cn->a0 + cn->sweep * a, cn->a0 + cn->sweep * b, 1, {cn->P[0], cn->P[1]}, r};
        if (ob_trim_base_dist(w->c, q) >= r - OB_TRIM_REL * w->size && add_arc(tr, cap, arc))
            return -1;
        a = b;
    }
    return 0;
}

/* The arcs between the sorted split points, kept or removed by their
 * midpoints; each corner's arc before the segment it starts (the wrap's
 * last). */
static int decide(trimmer *w, ob_trim *tr)
{
    int cap = 0, j = 0, c = w->ncn > 0 && w->cn[0].seg == 0; /* the wrap's corner comes last */
    for (int k = 0; k < w->c->nseg; k++) {
        double a = 0.0;
        for (; c < w->ncn && w->cn[c].seg == k; c++)
            if (corner_arcs(w, &w->cn[c], tr, &cap))
                return -1;
        for (;; j++) {
            const int last = j >= w->nsp || w->sp[j].seg != k;
            const double b = last ? 1.0 : w->sp[j].t;
            if (b > a) {
                if (kept_at(w, k, 0.5 * (a + b)) && add_arc(tr, &cap, (ob_trim_arc){.seg = k, .t0 = a, .t1 = b}))
                    return -1;
                a = b;
            }
            if (last)
                break;
        }
    }
    if (w->ncn > 0 && w->cn[0].seg == 0 && corner_arcs(w, &w->cn[0], tr, &cap))
        return -1;
    return 0;
}

static void trimmer_free(trimmer *w)
{
    free(w->poly);
    free(w->box);
    free(w->sp);
    free(w->cn);
    free(w->g0);
    free(w->ang);
}

int ob_trim_offset(const ob_curve *c, double d, ob_trim *tr, ob_err *err)
{
    memset(tr, 0, sizeof *tr);
    trimmer w = {.c = c, .d = d, .size = ob_trim_curve_size(c, d), .M = OB_TRIM_POLY};
    double s[2], e[2];
    ob_bez_point(&c->seg[0], 0.0, s);
    ob_bez_point(&c->seg[c->nseg - 1], 1.0, e);
    w.closed = hypot(e[0] - s[0], e[1] - s[1]) <= 1e-12 * w.size;
    w.nblk = c->nseg * (w.M / BLOCK);
    w.poly = malloc(2 * (size_t)c->nseg * (size_t)(w.M + 1) * 2 * sizeof *w.poly);
    w.box = malloc(2 * (size_t)w.nblk * 4 * sizeof *w.box);
    w.cn = malloc((size_t)c->nseg * sizeof *w.cn);
    w.g0 = calloc((size_t)c->nseg, 1);
    int rc = !w.poly || !w.box || !w.cn || !w.g0 ? -1 : 0;
    if (rc == 0) {
        find_corners(&w);
        build_poly(&w);
        rc = cusps(&w) || crossings(&w) || (!w.closed && (circle_cross(&w, 0, s, NULL) || circle_cross(&w, 0, e, NULL)))
                 ? -1
                 : 0;
        /* the circles about the corners bound the |d|-neighbourhood of C
         * too (on one side or the other): where O_d crosses one its
         * distance to C can change */
        for (int k = 0; k < w.ncn && rc == 0; k++)
            rc = circle_cross(&w, 0, w.cn[k].P, NULL);
    }
    if (rc == 0) {
        if (w.nsp > 0) /* qsort takes no NULL, even for none */
            qsort(w.sp, (size_t)w.nsp, sizeof *w.sp, cmp_split);
        dedupe(&w);
        rc = decide(&w, tr);
    }
    if (rc == 0 && w.nsp > 0) {
        tr->split = w.sp, tr->nsplit = w.nsp;
        w.sp = NULL;
    }
    trimmer_free(&w);
    return rc ? ob_fail(err, "trimmed offset: out of memory (%d segments)", c->nseg) : 0;
}

void ob_trim_free(ob_trim *tr)
{
    free(tr->arc);
    free(tr->split);
    memset(tr, 0, sizeof *tr);
}

void ob_trim_arc_point(const ob_curve *c, double d, const ob_trim_arc *ar, double u, double p[2])
{
    const double t = ar->t0 + (ar->t1 - ar->t0) * u;
    if (ar->corner) {
        p[0] = ar->ctr[0] + ar->r * cos(t), p[1] = ar->ctr[1] + ar->r * sin(t);
        return;
    }
    ob_bez_offset_point(&c->seg[ar->seg], t, d, p);
}

static void dump_row(FILE *f, const char *kind, const ob_curve *c, double d, const ob_trim_arc *ar)
{
    double p[2], q[2];
    ob_trim_arc_point(c, d, ar, 0.0, p);
    ob_trim_arc_point(c, d, ar, 1.0, q);
    fprintf(f, "%s,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", kind, ar->seg, ar->t0, ar->t1, p[0], p[1], q[0], q[1]);
}

int ob_trim_dump(FILE *f, const ob_curve *c, double d, const ob_trim *tr)
{
    static const char *const kinds[] = {"cusp", "self", "opposite", "end"};
    fputs("kind,seg,t0,t1,x0,y0,x1,y1\n", f);
    for (int k = 0; k < tr->n; k++)
        dump_row(f, tr->arc[k].corner ? "corner" : "arc", c, d, &tr->arc[k]);
    for (int k = 0; k < tr->nsplit; k++) {
        const ob_trim_arc at = {.seg = tr->split[k].seg, .t0 = tr->split[k].t, .t1 = tr->split[k].t};
        dump_row(f, kinds[tr->split[k].kind], c, d, &at);
    }
    return fflush(f) != 0 || ferror(f) ? -1 : 0;
}
