/*
 * joints.c - gaps and kinks where pieces meet.  See joints.h.
 */
#include "methods/driver/joints.h"

#include <math.h>
#include <string.h>

void ob_bez_end(const ob_bez *b, int at_end, ob_end *e)
{
    const int n = b->deg;
    const int i0 = at_end ? n : 0;
    const double *h0 = b->h[i0];
    e->p[0] = h0[0] / h0[2];
    e->p[1] = h0[1] / h0[2];
    e->t[0] = e->t[1] = 0.0;
    /* The extent of the control polygon: a leg shorter than 1e-12 of it is
     * a collapsed one (round-off), as obc_tangent judges it. */
    double ext = 0.0;
    for (int i = 0; i <= n; i++)
        for (int k = 0; k < 2; k++)
            ext = fmax(ext, fabs(b->h[i][k] / b->h[i][2] - e->p[k]));
    if (!(ext > 0.0) || !isfinite(ext))
        return;
    /* C(t) - C(0) = sum_i (H_i w_0 - H_0 w_i) B_i(t) / (W(t) w_0), and
     * W(t) w_0 > 0 near t = 0: the first non-vanishing v_k = H_k w_0 -
     * H_0 w_k is the direction leaving the start.  At the end, mirrored, with
     * the sign turned so the tangent points along the travel. */
    for (int k = 1; k <= n; k++) {
        const int i = at_end ? n - k : k;
        const double *hk = b->h[i];
        const double dx = hk[0] / hk[2] - e->p[0], dy = hk[1] / hk[2] - e->p[1];
        if (!(hypot(dx, dy) > 1e-12 * ext))
            continue;
        double v[2] = {hk[0] * h0[2] - h0[0] * hk[2], hk[1] * h0[2] - h0[1] * hk[2]};
        if (at_end)
            v[0] = -v[0], v[1] = -v[1];
        const double len = hypot(v[0], v[1]);
        if (!(len > 0.0) || !isfinite(len))
            return;
        e->t[0] = v[0] / len;
        e->t[1] = v[1] / len;
        return;
    }
}

const char *ob_cont_name(ob_cont c)
{
    switch (c) {
    case OB_CONT_OPEN: return "open";
    case OB_CONT_G0: return "G0";
    case OB_CONT_G1: return "G1";
    default: return "";
    }
}

int ob_cont_parse(const char *s, ob_cont *c)
{
    static const ob_cont all[] = {OB_CONT_NONE, OB_CONT_OPEN, OB_CONT_G0, OB_CONT_G1};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (strcmp(s, ob_cont_name(all[i])) == 0) {
            *c = all[i];
            return 0;
        }
    return -1;
}

double ob_joint_size(const ob_curve *c, double d)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int s = 0; s < c->nseg; s++)
        for (int i = 0; i <= c->seg[s].deg; i++) {
            double p[2];
            ob_bez_ctrl(&c->seg[s], i, p);
            for (int k = 0; k < 2; k++) {
                lo[k] = fmin(lo[k], p[k]);
                hi[k] = fmax(hi[k], p[k]);
            }
        }
    if (!(hi[0] >= lo[0]) || !(hi[1] >= lo[1]))
        return 2.8284271247461903 * fabs(d);  /* no control points: the box of d alone */
    return hypot(hi[0] - lo[0] + 2.0 * fabs(d), hi[1] - lo[1] + 2.0 * fabs(d));
}

double ob_joint_gap_tol(const ob_curve *c, double d) { return OB_JOINT_GAP_REL * ob_joint_size(c, d); }

/* The angle between two unit directions, or -1 when one is missing. */
static double kink_of(const double a[2], const double b[2])
{
    if ((a[0] == 0.0 && a[1] == 0.0) || (b[0] == 0.0 && b[1] == 0.0))
        return -1.0;
    return atan2(fabs(a[0] * b[1] - a[1] * b[0]), a[0] * b[0] + a[1] * b[1]);
}

int ob_joint_measure(ob_joint_stats *s, const ob_end *left, const ob_end *right, double gap_tol)
{
    const double gap = hypot(right->p[0] - left->p[0], right->p[1] - left->p[1]);
    const double kink = kink_of(left->t, right->t);
    const int open = !(gap <= gap_tol);  /* a NaN or infinite end is open */
    s->joints++;
    s->open += open;
    if (!(gap <= s->max_gap))
        s->max_gap = gap;
    if (kink > s->max_kink)
        s->max_kink = kink;
    if (!open && !(kink >= 0.0 && kink <= OB_JOINT_KINK_RAD))
        s->kinked++;
    return open;
}

void ob_joint_merge(ob_joint_stats *a, const ob_joint_stats *b)
{
    if (!(b->max_gap <= a->max_gap))
        a->max_gap = b->max_gap;
    if (b->max_kink > a->max_kink)
        a->max_kink = b->max_kink;
    a->joints += b->joints;
    a->open += b->open;
    a->kinked += b->kinked;
    a->excluded += b->excluded;
    a->excluded_open += b->excluded_open;
}

int ob_base_joint_smooth(const ob_curve *c, int s, double gap_tol)
{
    if (s < 0 || s + 1 >= c->nseg)
        return 0;
    ob_end l, r;
    ob_bez_end(&c->seg[s], 1, &l);
    ob_bez_end(&c->seg[s + 1], 0, &r);
    const double k = kink_of(l.t, r.t);
    return hypot(r.p[0] - l.p[0], r.p[1] - l.p[1]) <= gap_tol && k >= 0.0 && k <= OB_JOINT_KINK_RAD;
}

int ob_joint_between(ob_joint_stats *s, const ob_curve *c, double gap_tol, int sl, const ob_end *left, int sr,
                     const ob_end *right)
{
    if (sl == sr || (sr == sl + 1 && ob_base_joint_smooth(c, sl, gap_tol)))
        return ob_joint_measure(s, left, right, gap_tol);
    const int apart = !(hypot(right->p[0] - left->p[0], right->p[1] - left->p[1]) <= gap_tol);
    s->excluded++;
    s->excluded_open += apart;
    return apart;
}

ob_cont ob_joint_continuity(const ob_joint_stats *s)
{
    if (s->joints == 0)
        return OB_CONT_NONE;
    if (s->open > 0)
        return OB_CONT_OPEN;
    return s->kinked > 0 ? OB_CONT_G0 : OB_CONT_G1;
}
