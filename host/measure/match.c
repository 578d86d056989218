/*
 * match.c - base links for pieces that came without one (measure.h,
 * ob_approx_match): the nearest point of the exact offset to each end.
 */
#include "host/measure/measure.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { SCAN = 512, GOLDEN_STEPS = 100, CROSS_SCAN = 256, CROSS_STEPS = 200 };

typedef struct {
    int seg;
    double t, dist;
} nearpt;

static double dist_at(const ob_bez *b, double d, double t, const double p[2])
{
    double o[2];
    ob_bez_offset_point(b, t, d, o);
    const double r = hypot(o[0] - p[0], o[1] - p[1]);
    return isnan(r) ? INFINITY : r;
}

/* The nearest offset point to p on segment s: scan, then golden section
 * between the best sample's neighbours. */
static nearpt nearest_on(const ob_curve *c, int s, double d, const double p[2])
{
    const ob_bez *b = &c->seg[s];
    int best = 0;
    double bd = INFINITY;
    for (int k = 0; k <= SCAN; k++) {
        const double r = dist_at(b, d, (double)k / SCAN, p);
        if (r < bd) {
            bd = r;
            best = k;
        }
    }
    double lo = best > 0 ? (double)(best - 1) / SCAN : 0.0, hi = best < SCAN ? (double)(best + 1) / SCAN : 1.0;
    const double g = 0.5 * (sqrt(5.0) - 1.0);
    for (int i = 0; i < GOLDEN_STEPS && hi - lo > 1e-16; i++) {
        const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (dist_at(b, d, m1, p) < dist_at(b, d, m2, p))
            hi = m2;
        else
            lo = m1;
    }
    nearpt n = {s, (double)best / SCAN, bd};
    const double t = 0.5 * (lo + hi), r = dist_at(b, d, t, p);
    if (r < n.dist)
        n = (nearpt){s, t, r};
    /* the ends themselves, where a piece usually starts and stops */
    const double e0 = dist_at(b, d, 0.0, p), e1 = dist_at(b, d, 1.0, p);
    if (e0 <= n.dist)
        n = (nearpt){s, 0.0, e0};
    if (e1 <= n.dist)
        n = (nearpt){s, 1.0, e1};
    return n;
}

static nearpt nearest(const ob_curve *c, double d, const double p[2])
{
    nearpt n = {0, 0.0, INFINITY};
    for (int s = 0; s < c->nseg; s++) {
        const nearpt m = nearest_on(c, s, d, p);
        if (m.dist < n.dist)
            n = m;
    }
    return n;
}

static void reverse(ob_bez *b)
{
    for (int i = 0, j = b->deg; i < j; i++, j--)
        for (int k = 0; k < 3; k++) {
            const double x = b->h[i][k];
            b->h[i][k] = b->h[j][k];
            b->h[j][k] = x;
        }
}

/* The joint between base segments j and j2 (j + 1, or 0 after the last
 * of a closed curve): its point B and the unit
 * normal n of the line across it that separates the two segments' offsets
 * (the mean of their normals there: the bisector at a corner). */
static int joint_line(const ob_curve *c, int j, int j2, double B[2], double n[2])
{
    double nl[2], nr[2];
    ob_bez_point(&c->seg[j], 1.0, B);
    const int l = ob_bez_normal(&c->seg[j], 1.0, nl) == 0, r = ob_bez_normal(&c->seg[j2], 0.0, nr) == 0;
    n[0] = (l ? nl[0] : 0.0) + (r ? nr[0] : 0.0);
    n[1] = (l ? nl[1] : 0.0) + (r ? nr[1] : 0.0);
    const double len = hypot(n[0], n[1]);
    if (!(len > 1e-12))  /* no normal, or a turn back (a cusp of the base) */
        return -1;
    n[0] /= len;
    n[1] /= len;
    return 0;
}

/* Whether the base ends where it starts (a closed curve, whose offset a
 * CAD system may start anywhere: its segments are then taken cyclically). */
static int closed(const ob_curve *c)
{
    double p[2], q[2];
    ob_bez_point(&c->seg[0], 0.0, p);
    ob_bez_point(&c->seg[c->nseg - 1], 1.0, q);
    return hypot(p[0] - q[0], p[1] - q[1]) <= 1e-12 * (1.0 + hypot(p[0], p[1]));
}

/* How far p is past the line through B across n, along the base's forward
 * tangent (n rotated clockwise). */
static double past(const double B[2], const double n[2], const double p[2])
{
    return (p[0] - B[0]) * n[1] - (p[1] - B[1]) * n[0];
}

/* The parameter u in (0, 1) where piece b first crosses the joint's line
 * forwards on the offset's side of the base (d's side), by a scan and
 * bisection; -1 when it does not. */
static double crossing(const ob_bez *b, double d, const double B[2], const double n[2])
{
    double p[2];
    ob_bez_point(b, 0.0, p);
    double u0 = 0.0, f0 = past(B, n, p);
    for (int k = 1; k <= CROSS_SCAN; k++) {
        const double u1 = (double)k / CROSS_SCAN;
        ob_bez_point(b, u1, p);
        const double f1 = past(B, n, p);
        if (f0 <= 0.0 && f1 > 0.0) {
            double a = u0, z = u1;
            for (int i = 0; i < CROSS_STEPS && z - a > 1e-16; i++) {
                const double m = 0.5 * (a + z);
                ob_bez_point(b, m, p);
                if (past(B, n, p) > 0.0)
                    z = m;
                else
                    a = m;
            }
            ob_bez_point(b, z, p);
            const double side = (p[0] - B[0]) * n[0] + (p[1] - B[1]) * n[1];
            if (side * d > 0.0 && z > 0.0 && z < 1.0)
                return z;
        }
        u0 = u1;
        f0 = f1;
    }
    return -1.0;
}

/* Whether piece b's point at u, where it crosses the line across the joint
 * of segments s and s2, approximates the offset there: it is no farther
 * from the offset's point(s) at the joint (two at a corner) than twice its
 * distance from the whole offset.  On a line normal to the offset the two
 * are equal; a piece near a loop or cusp of the offset can cross the line
 * elsewhere, near another part of the offset (seen: 1e-3 from the joint's
 * point, 2e-6 from the offset: liu2002_ex2 at d = 0.5), and its parts would
 * be measured against offsets they do not approximate. */
static int on_offset_at_joint(const ob_curve *c, double d, int s, int s2, const ob_bez *b, double u)
{
    double X[2], O[2], O2[2];
    ob_bez_point(b, u, X);
    ob_bez_offset_point(&c->seg[s], 1.0, d, O);
    ob_bez_offset_point(&c->seg[s2], 0.0, d, O2);
    const double away = fmin(hypot(X[0] - O[0], X[1] - O[1]), hypot(X[0] - O2[0], X[1] - O2[1]));
    const double slack = 1e-9 * (1.0 + fabs(d) + hypot(X[0], X[1]));
    return away <= 2.0 * nearest(c, d, X).dist + slack;
}

/* Cuts piece k of a (running with the base from n0 to n1, over `parts`
 * segments from n0.seg on, cyclically on a closed curve) where it crosses
 * each joint's line between them: pieces linked to their segments in
 * order, the first [n0.t, 1], whole segments between, the last [0, n1.t].
 * An exact subdivision (de Casteljau), so the pieces are the file's piece. */
static int cut_at_joints(const ob_curve *c, double d, ob_approx *a, int k, nearpt n0, nearpt n1, int parts,
                         const char *name, ob_err *err)
{
    const int line = a->v[k].line;
    const ob_apiece named = a->v[k]; /* its entity, handle and id, for every part */
    ob_bez rest = a->v[k].approx;
    for (int i = 1; i < parts; i++)
        if (!ob_approx_add(a))
            return ob_fail(err, "out of memory");
    memmove(&a->v[k + parts], &a->v[k + 1], (size_t)(a->n - parts - k) * sizeof a->v[0]);
    for (int i = 0; i < parts; i++) {
        const int s = (n0.seg + i) % c->nseg, s2 = (s + 1) % c->nseg;
        ob_apiece *p = &a->v[k + i];
        *p = (ob_apiece){1, s, i == 0 ? n0.t : 0.0, i == parts - 1 ? n1.t : 1.0, 0.0, 1.0, 0, line, rest, 1, i,
                         "", "", ""};
        ob_apiece_names(p, &named);
        if (i == parts - 1)
            break;
        double B[2], n[2];
        const double x = joint_line(c, s, s2, B, n) == 0 ? crossing(&rest, d, B, n) : -1.0;
        if (x < 0.0)
            return ob_fail(err, "%s:%d: piece %d runs from base segment %d to %d and does not cross the normal "
                           "line of the offset where segments %d and %d join: cut it there", name, line,
                           ob_approx_file_piece(a, k), n0.seg, n1.seg, s, s2);
        if (!on_offset_at_joint(c, d, s, s2, &rest, x))
            return ob_fail(err, "%s:%d: piece %d runs from base segment %d to %d and crosses the normal line where "
                           "segments %d and %d join away from the offset's point there, near another part of the "
                           "offset (a loop or cusp of the offset: projection cannot tell which part the piece "
                           "approximates; a file with base links, as --export writes, is matched exactly)", name,
                           line, ob_approx_file_piece(a, k), n0.seg, n1.seg, s, s2);
        ob_bez_split(&rest, x, &p->approx, &rest);
    }
    if (!(a->v[k].a < a->v[k].b) || !(a->v[k + parts - 1].a < a->v[k + parts - 1].b))
        return ob_fail(err, "%s:%d: piece %d: an end lies on a joint of the base it runs past", name, line,
                       ob_approx_file_piece(a, k));
    return 0;
}

/* Whether the piece from n0 to n1 runs against the base.  On an open curve:
 * n1 before n0.  On a closed one either way round is a path: the one that
 * passes the nearest point to the piece's middle (m). */
static int runs_back(const ob_curve *c, nearpt n0, nearpt n1, nearpt m)
{
    const double p0 = n0.seg + n0.t, p1 = n1.seg + n1.t;
    if (!closed(c))
        return p0 > p1;
    const double N = c->nseg, ahead = fmod(p1 - p0 + N, N), mid = fmod(m.seg + m.t - p0 + N, N);
    return !(mid < ahead);
}

/* n0 and n1 (n0 first along the base) moved off a joint they sit on the
 * far side of: the end of a segment is the start of the next, and the
 * piece's part on the one it only touches would be empty. */
static void off_joints(const ob_curve *c, nearpt *n0, nearpt *n1)
{
    const int N = c->nseg, cyc = closed(c);
    if (n0->t >= 1.0 && (n0->seg != n1->seg || n1->t < n0->t) && (cyc || n0->seg + 1 < N))
        *n0 = (nearpt){(n0->seg + 1) % N, 0.0, n0->dist};
    if (n1->t <= 0.0 && (n1->seg != n0->seg || n1->t < n0->t) && (cyc || n1->seg > 0))
        *n1 = (nearpt){(n1->seg + N - 1) % N, 1.0, n1->dist};
}

/* Links piece k of a (its ends nearest to the offset at n0 and n1), cut at
 * the base's joints where it runs over several segments; *parts the number
 * of pieces it became. */
static int link_piece(const ob_curve *c, double d, ob_approx *a, int k, const char *name, int *parts,
                      ob_err *err)
{
    ob_apiece *p = &a->v[k];
    double q0[2], q1[2], qm[2];
    ob_bez_point(&p->approx, 0.0, q0);
    ob_bez_point(&p->approx, 1.0, q1);
    ob_bez_point(&p->approx, 0.5, qm);
    nearpt n0 = nearest(c, d, q0), n1 = nearest(c, d, q1);
    *parts = 1;
    if (n0.seg != n1.seg) {
        /* ends at a joint of the base may round onto the neighbour: both on
         * the one segment, if that is (nearly) as near */
        const nearpt a1 = nearest_on(c, n0.seg, d, q1), a0 = nearest_on(c, n1.seg, d, q0);
        const double slack = 1e-9 * (1.0 + fabs(d) + hypot(q0[0], q0[1]) + hypot(q1[0], q1[1]));
        if (a1.dist <= n1.dist + slack && a1.dist + n0.dist <= a0.dist + n1.dist)
            n1 = a1;
        else if (a0.dist <= n0.dist + slack)
            n0 = a0;
    }
    if (runs_back(c, n0, n1, nearest(c, d, qm))) {
        reverse(&p->approx);
        const nearpt x = n0;
        n0 = n1;
        n1 = x;
    }
    off_joints(c, &n0, &n1);
    const int N = c->nseg;
    if (n0.seg == n1.seg && n0.t == n1.t)
        return ob_fail(err, "%s:%d: piece %d: both its ends are nearest to one point of the offset (t = %.17g of "
                       "base segment %d)", name, p->line, ob_approx_file_piece(a, k), n0.t, n0.seg);
    if (n0.seg != n1.seg || n1.t < n0.t) {  /* the latter: once round a closed curve */
        *parts = (n1.seg - n0.seg + N) % N + 1 + (n0.seg == n1.seg ? N : 0);
        return cut_at_joints(c, d, a, k, n0, n1, *parts, name, err);
    }
    p->has_base = 1;
    p->matched = 1;
    p->seg = n0.seg;
    p->a = n0.t;
    p->b = n1.t;
    p->t0 = 0.0;
    p->t1 = 1.0;
    return 0;
}

int ob_approx_match(const ob_curve *c, double d, ob_approx *a, const char *name, ob_err *err)
{
    for (int k = 0; k < a->n;) {
        int parts = 1;
        if (!a->v[k].has_base) {
            a->same_param = 0;  /* a link by projection says nothing of the parameter */
            if (link_piece(c, d, a, k, name, &parts, err) != 0)
                return -1;
        }
        k += parts;
    }
    return 0;
}
