/*
 * match.c - base links for pieces that came without one (measure.h,
 * ob_approx_match): the nearest point of the exact offset to each end.
 */
#include "host/measure/measure.h"

#include <math.h>
#include <stdio.h>

enum { SCAN = 512, GOLDEN_STEPS = 100 };

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

/* Links piece p (its ends e0, e1 on one segment). */
static int link_piece(const ob_curve *c, double d, ob_apiece *p, int k, const char *name, ob_err *err)
{
    double q0[2], q1[2];
    ob_bez_point(&p->approx, 0.0, q0);
    ob_bez_point(&p->approx, 1.0, q1);
    nearpt n0 = nearest(c, d, q0), n1 = nearest(c, d, q1);
    if (n0.seg != n1.seg) {
        /* ends at a joint of the base may round onto the neighbour: both on
         * the one segment, if that is (nearly) as near */
        const nearpt a1 = nearest_on(c, n0.seg, d, q1), a0 = nearest_on(c, n1.seg, d, q0);
        const double slack = 1e-9 * (1.0 + fabs(d) + hypot(q0[0], q0[1]) + hypot(q1[0], q1[1]));
        if (a1.dist <= n1.dist + slack && a1.dist + n0.dist <= a0.dist + n1.dist)
            n1 = a1;
        else if (a0.dist <= n0.dist + slack)
            n0 = a0;
        else {
            ob_fail(err, "%s:%d: piece %d runs from base segment %d to %d: cut it where the base's "
                    "segments join (measure matches each piece to one base segment)", name, p->line, k, n0.seg,
                    n1.seg);
            return -1;
        }
    }
    if (n0.t == n1.t) {
        ob_fail(err, "%s:%d: piece %d: both its ends are nearest to one point of the offset (t = %.17g of "
                "base segment %d)", name, p->line, k, n0.t, n0.seg);
        return -1;
    }
    if (n0.t > n1.t) {
        reverse(&p->approx);
        const nearpt x = n0;
        n0 = n1;
        n1 = x;
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
    for (int k = 0; k < a->n; k++) {
        if (a->v[k].has_base)
            continue;
        a->same_param = 0;  /* a link by projection says nothing of the parameter */
        if (link_piece(c, d, &a->v[k], k, name, err) != 0)
            return -1;
    }
    return 0;
}
