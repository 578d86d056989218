/*
 * trim_approx.c - an approximation trimmed by its own crossings
 * (trim_approx.h).
 */
#include "host/measure/trim_approx.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/measure/trim.h"

enum { CH = OB_TRIMA_CHORDS, OCH = OB_TRIMA_OPP_CHORDS, BCH = 512, BLK = 16 };

/* One block of BLK chords: of A (kind 0: piece k) or of C - dN (kind 1:
 * base segment k); box x0, y0, x1, y1. */
typedef struct {
    int kind, k, i0;
    double box[4];
} block;

typedef struct {
    const ob_curve *c;
    const ob_approx *a;
    double d, size;
    int closed, n;
    double *pa;      /* [n][CH + 1][2]: A's polylines */
    double *po;      /* [nseg][OCH + 1][2]: C - dN's */
    block *blk;
    int nblk;
    double *tau;     /* the cuts, tau = k + u */
    int ntau, cap;
    double *pb;      /* [nseg][BCH + 1][2]: the base's polylines */
    double *bbox;    /* [nseg * BCH / BLK][4]: their blocks' boxes */
    double sag;      /* how far the base strays from its chords, at most (twice the largest sampled) */
} atrim;

static const double *va(const atrim *w, int k, int i) { return w->pa + 2 * ((size_t)k * (CH + 1) + i); }
static const double *vo(const atrim *w, int k, int i) { return w->po + 2 * ((size_t)k * (OCH + 1) + i); }

static int add_cut(atrim *w, int k, double u)
{
    if (w->ntau == w->cap) {
        const int cap = w->cap ? 2 * w->cap : 16;
        double *nv = realloc(w->tau, (size_t)cap * sizeof *nv);
        if (!nv)
            return -1;
        w->tau = nv, w->cap = cap;
    }
    w->tau[w->ntau++] = k + fmin(fmax(u, 0.0), 1.0);
    return 0;
}

static void box_of(const double *p, int m, double b[4])
{
    b[0] = b[1] = INFINITY, b[2] = b[3] = -INFINITY;
    for (int i = 0; i <= m; i++)
        b[0] = fmin(b[0], p[2 * i]), b[1] = fmin(b[1], p[2 * i + 1]), b[2] = fmax(b[2], p[2 * i]),
        b[3] = fmax(b[3], p[2 * i + 1]);
}

/* The polylines and their blocks; -1 when a point is not finite. */
static int build(atrim *w)
{
    int nb = 0;
    for (int k = 0; k < w->n; k++) {
        double *p = w->pa + 2 * (size_t)k * (CH + 1);
        for (int i = 0; i <= CH; i++) {
            ob_bez_point(&w->a->v[k].approx, (double)i / CH, p + 2 * i);
            if (!isfinite(p[2 * i]) || !isfinite(p[2 * i + 1]))
                return -1;
        }
        for (int b = 0; b < CH / BLK; b++, nb++) {
            w->blk[nb] = (block){0, k, b * BLK, {0}};
            box_of(p + 2 * b * BLK, BLK, w->blk[nb].box);
        }
    }
    for (int k = 0; k < w->c->nseg; k++) {
        double *p = w->po + 2 * (size_t)k * (OCH + 1);
        for (int i = 0; i <= OCH; i++)
            ob_bez_offset_point(&w->c->seg[k], (double)i / OCH, -w->d, p + 2 * i);
        for (int b = 0; b < OCH / BLK; b++, nb++) {
            w->blk[nb] = (block){1, k, b * BLK, {0}};
            box_of(p + 2 * b * BLK, BLK, w->blk[nb].box);
        }
    }
    w->nblk = nb;
    return 0;
}

/* Where chords p0 p1 and q0 q1 cross (ends included): 1 and (al, be). */
static int chords_meet(const double *p0, const double *p1, const double *q0, const double *q1, double *al, double *be)
{
    const double rx = p1[0] - p0[0], ry = p1[1] - p0[1], sx = q1[0] - q0[0], sy = q1[1] - q0[1];
    const double den = rx * sy - ry * sx, qx = q0[0] - p0[0], qy = q0[1] - p0[1];
    if (den == 0.0)
        return 0;
    *al = (qx * sy - qy * sx) / den, *be = (qx * ry - qy * rx) / den;
    return *al >= 0.0 && *al <= 1.0 && *be >= 0.0 && *be <= 1.0;
}

/* A's point on piece k at u and its derivative. */
static void apoint(const atrim *w, int k, double u, double p[2], double dp[2])
{
    double e[2][2];
    ob_bez_eval(&w->a->v[k].approx, u, 1, e);
    p[0] = e[0][0], p[1] = e[0][1], dp[0] = e[1][0], dp[1] = e[1][1];
}

/* The other curve of a crossing: A's piece k (kind 0) or C - dN on base
 * segment k (kind 1). */
static void other_point(const atrim *w, int kind, int k, double u, double p[2], double dp[2])
{
    if (kind == 0)
        apoint(w, k, u, p, dp);
    else
        ob_bez_offset_point_d(&w->c->seg[k], u, -w->d, p, dp);
}

/* Newton's method on A_ka(s) = X_kb(u) (X: other_point's kind) from the
 * chords' estimate; the estimate stays where it does not converge in
 * [0, 1]^2 (a cut only has to fall between the arcs it parts). */
static void refine(const atrim *w, int ka, int kind, int kb, double *s, double *u)
{
    double x = *s, y = *u;
    for (int it = 0; it < 30; it++) {
        double p[2], dp[2], q[2], dq[2];
        apoint(w, ka, x, p, dp);
        other_point(w, kind, kb, y, q, dq);
        const double fx = p[0] - q[0], fy = p[1] - q[1], det = -dp[0] * dq[1] + dp[1] * dq[0];
        if (!(fabs(det) > 0.0) || !isfinite(det))
            return;
        const double ds = (-fx * dq[1] + fy * dq[0]) / det, du = (dp[0] * fy - dp[1] * fx) / det;
        x -= ds, y -= du;
        if (!(x >= 0.0 && x <= 1.0 && y >= 0.0 && y <= 1.0))
            return;
        if (fabs(ds) <= 1e-15 && fabs(du) <= 1e-15)
            break;
    }
    *s = x, *u = y;
}

/* 1 when global chords g and h of A are neighbours (they share an end,
 * also across the wrap of a closed curve). */
static int neighbours(const atrim *w, long g, long h)
{
    const long last = (long)w->n * CH - 1;
    return labs(g - h) <= 1 || (w->closed && ((g == 0 && h == last) || (h == 0 && g == last)));
}

/* The crossings of the chords of blocks x (of A) and y (of A or C - dN). */
static int cross_blocks(atrim *w, const block *x, const block *y)
{
    for (int i = x->i0; i < x->i0 + BLK; i++)
        for (int j = y->i0; j < y->i0 + BLK; j++) {
            const long g = (long)x->k * CH + i, h = (long)y->k * CH + j;
            if (y->kind == 0 && (h <= g || neighbours(w, g, h)))
                continue;
            const double *q0 = y->kind ? vo(w, y->k, j) : va(w, y->k, j);
            const double *q1 = y->kind ? vo(w, y->k, j + 1) : va(w, y->k, j + 1);
            double al, be;
            if (!chords_meet(va(w, x->k, i), va(w, x->k, i + 1), q0, q1, &al, &be))
                continue;
            const int m = y->kind ? OCH : CH;
            double s = (i + al) / CH, u = (j + be) / m;
            refine(w, x->k, y->kind, y->k, &s, &u);
            if (add_cut(w, x->k, s) || (y->kind == 0 && add_cut(w, y->k, u)))
                return -1;
        }
    return 0;
}

static int cmp_x0(const void *p, const void *q)
{
    const block *a = p, *b = q;
    if (a->box[0] != b->box[0])
        return a->box[0] < b->box[0] ? -1 : 1;
    if (a->kind != b->kind)
        return a->kind - b->kind;
    return a->k != b->k ? a->k - b->k : a->i0 - b->i0;
}

/* Every crossing of A with itself and with C - dN: the blocks swept in x
 * (sorted by their boxes' left sides, a total order: the cuts do not depend
 * on the sort's ties). */
static int crossings(atrim *w)
{
    qsort(w->blk, (size_t)w->nblk, sizeof *w->blk, cmp_x0);
    for (int i = 0; i < w->nblk; i++)
        if (w->blk[i].kind == 0 && cross_blocks(w, &w->blk[i], &w->blk[i]))
            return -1; /* a small loop inside one block */
    for (int i = 0; i < w->nblk; i++)
        for (int j = i + 1; j < w->nblk && w->blk[j].box[0] <= w->blk[i].box[2]; j++) {
            const block *x = &w->blk[i], *y = &w->blk[j];
            if (x->kind && y->kind)
                continue;
            if (!(x->box[1] <= y->box[3] && y->box[1] <= x->box[3]))
                continue;
            if (x->kind)
                x = &w->blk[j], y = &w->blk[i];
            if (y->kind == 0 && (y->k < x->k || (y->k == x->k && y->i0 < x->i0)))
                x = &w->blk[j], y = &w->blk[i]; /* x first along A: cross_blocks takes h > g */
            if (cross_blocks(w, x, y))
                return -1;
        }
    return 0;
}

static double circ_f(const atrim *w, int k, double u, const double E[2])
{
    double p[2];
    ob_bez_point(&w->a->v[k].approx, u, p);
    return (p[0] - E[0]) * (p[0] - E[0]) + (p[1] - E[1]) * (p[1] - E[1]) - w->d * w->d;
}

/* A's crossings of the circle of radius |d| about E, bisected. */
static int end_circle(atrim *w, const double E[2])
{
    const double zero = 1e-11 * w->size * w->size;
    for (int k = 0; k < w->n; k++) {
        double f0 = circ_f(w, k, 0.0, E);
        for (int i = 1; i <= CH; i++) {
            const double f1 = circ_f(w, k, (double)i / CH, E);
            if (fabs(f0) > zero && fabs(f1) > zero && (f0 < 0.0) != (f1 < 0.0)) {
                double lo = (double)(i - 1) / CH, hi = (double)i / CH;
                const int neg = f0 < 0.0;
                for (int it = 0; it < 60; it++) {
                    const double m = 0.5 * (lo + hi);
                    if (m <= lo || m >= hi)
                        break;
                    *((circ_f(w, k, m, E) < 0.0) == neg ? &lo : &hi) = m;
                }
                if (add_cut(w, k, 0.5 * (lo + hi)))
                    return -1;
            }
            f0 = f1;
        }
    }
    return 0;
}

static int cmp_double(const void *p, const void *q)
{
    const double a = *(const double *)p, b = *(const double *)q;
    return (a > b) - (a < b);
}

/* A's point at tau. */
static void point_at(const atrim *w, double tau, double p[2])
{
    int k = (int)tau;
    if (k > w->n - 1)
        k = w->n - 1;
    ob_bez_point(&w->a->v[k].approx, tau - k, p);
}

/* The base's polylines, their blocks' boxes and their sag (sampled at the
 * chords' middles, doubled): a query's distance to them is the base's
 * within sag. */
static int build_base(atrim *w)
{
    const int ns = w->c->nseg, nb = BCH / BLK;
    w->pb = malloc(2 * (size_t)ns * (BCH + 1) * sizeof *w->pb);
    w->bbox = malloc(4 * (size_t)ns * nb * sizeof *w->bbox);
    if (!w->pb || !w->bbox)
        return -1;
    for (int k = 0; k < ns; k++) {
        double *p = w->pb + 2 * (size_t)k * (BCH + 1);
        for (int i = 0; i <= BCH; i++)
            ob_bez_point(&w->c->seg[k], (double)i / BCH, p + 2 * i);
        for (int i = 0; i < BCH; i++) {
            double m[2];
            ob_bez_point(&w->c->seg[k], (i + 0.5) / BCH, m);
            w->sag = fmax(w->sag, 2.0 * hypot(m[0] - 0.5 * (p[2 * i] + p[2 * i + 2]), m[1] - 0.5 * (p[2 * i + 1] + p[2 * i + 3])));
        }
        for (int b = 0; b < nb; b++)
            box_of(p + 2 * b * BLK, BLK, w->bbox + 4 * ((size_t)k * nb + b));
    }
    return isfinite(w->sag) ? 0 : -1;
}

static double seg_dist(const double *a, const double *b, const double p[2])
{
    const double vx = b[0] - a[0], vy = b[1] - a[1], l2 = vx * vx + vy * vy;
    double u = l2 > 0.0 ? ((p[0] - a[0]) * vx + (p[1] - a[1]) * vy) / l2 : 0.0;
    u = fmin(fmax(u, 0.0), 1.0);
    return hypot(p[0] - a[0] - u * vx, p[1] - a[1] - u * vy);
}

/* The distance from p to the base's polylines (blocks whose box is farther
 * than the best so far skipped). */
static double poly_dist(const atrim *w, const double p[2])
{
    const int nb = BCH / BLK;
    double best = INFINITY;
    for (int k = 0; k < w->c->nseg; k++)
        for (int b = 0; b < nb; b++) {
            const double *bx = w->bbox + 4 * ((size_t)k * nb + b);
            const double dx = fmax(fmax(bx[0] - p[0], p[0] - bx[2]), 0.0), dy = fmax(fmax(bx[1] - p[1], p[1] - bx[3]), 0.0);
            if (dx * dx + dy * dy >= best * best)
                continue;
            const double *q = w->pb + 2 * ((size_t)k * (BCH + 1) + (size_t)b * BLK);
            for (int i = 0; i < BLK; i++)
                best = fmin(best, seg_dist(q + 2 * i, q + 2 * i + 2, p));
        }
    return best;
}

/* 1 when p is nearer to the base than lim: from the polylines where they
 * decide it beyond their sag, else by ob_trim_base_dist. */
static int nearer(const atrim *w, const double p[2], double lim)
{
    const double e = poly_dist(w, p);
    if (e < lim - w->sag)
        return 1;
    if (e > lim + w->sag)
        return 0;
    return ob_trim_base_dist(w->c, p) < lim;
}

/* Whether the arc [t0, t1] of A stays at |d| - margin or farther from the
 * base: its middle and OB_TRIMA_ARC_SAMPLES points a piece it covers
 * (inside the arc: its ends are cuts, on the boundary), stopping at the
 * first nearer one. */
static int arc_kept(const atrim *w, double t0, double t1, double margin)
{
    const double lim = fabs(w->d) - margin;
    const int n = (int)ceil((t1 - t0) * OB_TRIMA_ARC_SAMPLES);
    double p[2];
    point_at(w, 0.5 * (t0 + t1), p);
    if (nearer(w, p, lim))
        return 0;
    for (int i = 0; i < n; i++) {
        point_at(w, t0 + (t1 - t0) * (i + 0.5) / n, p);
        if (nearer(w, p, lim))
            return 0;
    }
    return 1;
}

/* The parts of the arc [t0, t1] (t0 < t1) appended to kept, piece by piece. */
static int keep_arc(const atrim *w, double t0, double t1, ob_approx *kept)
{
    for (int k = (int)t0; k < w->n && k < t1; k++) {
        const double u0 = fmax(t0 - k, 0.0), u1 = fmin(t1 - k, 1.0);
        if (!(u1 > u0))
            continue;
        ob_apiece *p = ob_approx_add(kept);
        if (!p)
            return -1;
        if (u0 == 0.0 && u1 == 1.0)
            p->approx = w->a->v[k].approx;
        else
            ob_bez_subsegment(&w->a->v[k].approx, u0, u1, &p->approx);
        ob_apiece_names(p, &w->a->v[k]);
    }
    return 0;
}

/* Every arc between consecutive cuts kept or removed (arc_kept); *cut:
 * the runs of removed arcs (one across a closed curve's wrap). */
static int decide(const atrim *w, double margin, ob_approx *kept, int *cut)
{
    double t0 = 0.0;
    int first = -1, last = 0; /* whether the first and the last arc were kept */
    for (int i = 0; i <= w->ntau; i++) {
        const double t1 = i < w->ntau ? w->tau[i] : (double)w->n;
        if (!(t1 > t0))
            continue;
        const int keep = arc_kept(w, t0, t1, margin);
        if (keep && keep_arc(w, t0, t1, kept))
            return -1;
        *cut += !keep && (first < 0 || last);
        if (first < 0)
            first = keep;
        last = keep;
        t0 = t1;
    }
    if (w->closed && *cut > 1 && first == 0 && last == 0)
        --*cut; /* one run across the wrap */
    return 0;
}

static int trim_filled(const ob_curve *c, double d, const ob_approx *a, double size, int closed, double margin,
                       ob_approx *kept, int *cut, ob_err *err);

/* Appends to out corner cn's arc (|d| about P from angle a0 by sweep) as
 * rational quadratics of at most a quarter turn each. */
static int add_corner_arc(const ob_trim_corner *cn, double d, ob_approx *out)
{
    const int n = (int)ceil(fabs(cn->sweep) / (0.5 * OB_PI) - 1e-12);
    const double r = fabs(d), ph = cn->sweep / (n > 0 ? n : 1);
    for (int i = 0; i < n; i++) {
        const double a0 = cn->a0 + i * ph, am = a0 + 0.5 * ph, a1 = a0 + ph, w = cos(0.5 * ph);
        ob_apiece *p = ob_approx_add(out);
        if (!p)
            return -1;
        p->approx.deg = 2;
        ob_bez_set(&p->approx, 0, cn->P[0] + r * cos(a0), cn->P[1] + r * sin(a0), 1.0);
        ob_bez_set(&p->approx, 1, cn->P[0] + r / w * cos(am), cn->P[1] + r / w * sin(am), w);
        ob_bez_set(&p->approx, 2, cn->P[0] + r * cos(a1), cn->P[1] + r * sin(a1), 1.0);
        snprintf(p->entity, sizeof p->entity, "corner");
    }
    return 0;
}

/* Purpose: a's pieces with the arcs a CAD kernel's arc join adds: at each
 *          convex corner of c (ob_trim_corner_at) between the last piece
 *          over the segment before and the first over the segment after
 *          (pieces with has_base only; the wrap's arc last).
 * Returns: 0, or -1 out of memory. */
static int fill_corners(const ob_curve *c, double d, int closed, const ob_approx *a, ob_approx *out)
{
    ob_trim_corner cn;
    for (int k = 0; k < a->n; k++) {
        const ob_apiece *p = &a->v[k], *q = k + 1 < a->n ? &a->v[k + 1] : NULL;
        ob_apiece *o = ob_approx_add(out);
        if (!o)
            return -1;
        *o = *p;
        if (q && p->has_base && q->has_base && q->seg == p->seg + 1 &&
            ob_trim_corner_at(c, d, q->seg, closed, &cn) && cn.convex && add_corner_arc(&cn, d, out))
            return -1;
    }
    if (closed && a->n > 0 && a->v[0].has_base && a->v[0].seg == 0 && a->v[a->n - 1].seg == c->nseg - 1 &&
        ob_trim_corner_at(c, d, 0, closed, &cn) && cn.convex && add_corner_arc(&cn, d, out))
        return -1;
    return 0;
}

int ob_trim_approx(const ob_curve *c, double d, const ob_approx *a, double margin, ob_approx *kept, int *cut,
                   ob_err *err)
{
    memset(kept, 0, sizeof *kept);
    *cut = 0;
    if (a->n == 0)
        return 0;
    double s[2], e[2];
    const double size = ob_trim_curve_size(c, d);
    ob_bez_point(&c->seg[0], 0.0, s);
    ob_bez_point(&c->seg[c->nseg - 1], 1.0, e);
    const int closed = hypot(e[0] - s[0], e[1] - s[1]) <= 1e-12 * size;
    ob_approx f = {0};
    if (fill_corners(c, d, closed, a, &f) != 0) {
        ob_approx_free(&f);
        return ob_fail(err, "trimming the approximation: out of memory (%d pieces)", a->n);
    }
    const int rc = trim_filled(c, d, &f, size, closed, margin, kept, cut, err);
    ob_approx_free(&f);
    return rc;
}

/* ob_trim_approx on pieces whose corners are filled. */
static int trim_filled(const ob_curve *c, double d, const ob_approx *a, double size, int closed, double margin,
                       ob_approx *kept, int *cut, ob_err *err)
{
    atrim w = {c, a, d, size, closed, a->n, NULL, NULL, NULL, 0, NULL, 0, 0, NULL, NULL, 0.0};
    double s[2], e[2];
    ob_bez_point(&c->seg[0], 0.0, s);
    ob_bez_point(&c->seg[c->nseg - 1], 1.0, e);
    w.pa = malloc(2 * (size_t)w.n * (CH + 1) * sizeof *w.pa);
    w.po = malloc(2 * (size_t)c->nseg * (OCH + 1) * sizeof *w.po);
    w.blk = malloc(((size_t)w.n * (CH / BLK) + (size_t)c->nseg * (OCH / BLK)) * sizeof *w.blk);
    int rc = w.pa && w.po && w.blk ? 0 : -1;
    if (rc == 0 && build(&w) != 0) {
        free(w.pa), free(w.po), free(w.blk);
        return ob_fail(err, "trimming the approximation: a piece has a point that is not finite");
    }
    if (rc == 0)
        rc = build_base(&w) || crossings(&w) || (!w.closed && (end_circle(&w, s) || end_circle(&w, e))) ? -1 : 0;
    if (rc == 0) {
        if (w.ntau > 0)
            qsort(w.tau, (size_t)w.ntau, sizeof *w.tau, cmp_double);
        rc = decide(&w, margin, kept, cut);
    }
    free(w.pa), free(w.po), free(w.blk), free(w.tau), free(w.pb), free(w.bbox);
    return rc ? ob_fail(err, "trimming the approximation: out of memory (%d pieces)", a->n) : 0;
}
