/*
 * cert_feet.c - nearest points in floating point (see cert_feet.h).
 */
#include "methods/metrics/cert_feet.h"

#include <math.h>

/* A polynomial segment moved so that its first control point is the
 * origin (*o0 holds it), its weights left 1.  Why: a de Casteljau
 * derivative is a difference of nearby level points, whose rounding is
 * eps times their size; at the origin that is the size of the segment, not
 * of its position, so a piece 1e-6 long at 0.5 keeps its tangent to ~eps
 * instead of 1e-9 (an offset point then 2e-10 off, feet 1e-5 off in t, and
 * the bound stuck above that).  The differences P_i - P_0 of nearby points
 * are exact (Sterbenz).  A rational segment is evaluated as it is. */
static const ob_bez *at_origin(const ob_bez *b, ob_bez *tmp, double o0[2])
{
    o0[0] = o0[1] = 0.0;
    if (b->rational)
        return b;
    o0[0] = b->h[0][0], o0[1] = b->h[0][1];
    tmp->deg = b->deg, tmp->rational = 0;
    for (int i = 0; i <= b->deg; i++)
        tmp->h[i][0] = b->h[i][0] - o0[0], tmp->h[i][1] = b->h[i][1] - o0[1], tmp->h[i][2] = 1.0;
    return tmp;
}

void ob_cert_eval(const ob_cv *c, double t, double p[2], double d1[2])
{
    double o[3][2], o0[2];
    ob_bez tmp;
    const ob_bez *b = at_origin(c->b, &tmp, o0);
    ob_bez_eval(b, t, c->offset ? 2 : 1, o);
    p[0] = o[0][0] + o0[0], p[1] = o[0][1] + o0[1], d1[0] = o[1][0], d1[1] = o[1][1];
    if (!c->offset)
        return;
    const double sp = hypot(o[1][0], o[1][1]);
    if (!(sp > 0)) {  /* the limit normal (curve.h); no derivative */
        ob_bez_offset_point(b, t, c->d, p);
        p[0] += o0[0], p[1] += o0[1];
        d1[0] = d1[1] = 0.0;
        return;
    }
    const double f = 1.0 - c->d * (o[1][0] * o[2][1] - o[1][1] * o[2][0]) / (sp * sp * sp);
    p[0] -= c->d * o[1][1] / sp, p[1] += c->d * o[1][0] / sp;
    d1[0] *= f, d1[1] *= f;
}

void ob_cert_table(const ob_cv *c, int M, double (*tab)[2])
{
    double d1[2];
    for (int k = 0; k < M; k++)
        ob_cert_eval(c, (double)k / (M - 1), tab[k], d1);
}

static double dist_at(const ob_cv *q, const double p[2], double t)
{
    double x[2], d1[2];
    ob_cert_eval(q, t, x, d1);
    return hypot(p[0] - x[0], p[1] - x[1]);
}

/* (p - q(t)) . q'(t): > 0 where the distance falls as t grows */
static double slope_at(const ob_cv *q, const double p[2], double t)
{
    double x[2], d1[2];
    ob_cert_eval(q, t, x, d1);
    return (p[0] - x[0]) * d1[0] + (p[1] - x[1]) * d1[1];
}

/* Golden section on [a, b]: the bracket left around the minimum. */
static void golden(const ob_cv *q, const double p[2], double *a, double *b)
{
    const double g = 0.6180339887498949;
    double x1 = *b - g * (*b - *a), x2 = *a + g * (*b - *a);
    double f1 = dist_at(q, p, x1), f2 = dist_at(q, p, x2);
    for (int it = 0; it < 30; it++) {
        if (f1 <= f2) {
            *b = x2, x2 = x1, f2 = f1;
            x1 = *b - g * (*b - *a), f1 = dist_at(q, p, x1);
        } else {
            *a = x1, x1 = x2, f1 = f2;
            x2 = *a + g * (*b - *a), f2 = dist_at(q, p, x2);
        }
    }
}

/* Regula falsi (Illinois) for the zero of slope_at in [a, b] where it
 * changes sign from + to -: the foot to full precision.  -1 if no sign change. */
static double polish(const ob_cv *q, const double p[2], double a, double b)
{
    double fa = slope_at(q, p, a), fb = slope_at(q, p, b);
    if (!(fa > 0 && fb < 0))
        return -1.0;
    int side = 0;
    for (int it = 0; it < 80; it++) {
        double c = a + (b - a) * (fa / (fa - fb));  /* no cancellation: a step from a */
        if (!(c > a && c < b))
            c = 0.5 * (a + b);
        if (!(c > a && c < b))  /* a and b adjacent doubles */
            break;
        const double fc = slope_at(q, p, c);
        if (fc == 0)
            return c;
        if (fc > 0) {
            a = c, fa = fc;
            if (side == -1)
                fb *= 0.5;
            side = -1;
        } else {
            b = c, fb = fc;
            if (side == 1)
                fa *= 0.5;
            side = 1;
        }
    }
    return 0.5 * (a + b);
}

/* The nearest point to p on q in [a, b]: regula falsi on the slope where
 * it changes sign once, golden section first where it does not, then the
 * best of that, the bracket's middle and its ends at 0 or 1.  *bd, *tb: the
 * best so far (distance, parameter), lowered if this finds a nearer one. */
static void nearest_in(const ob_cv *q, const double p[2], double a, double b, double *bd, double *tb)
{
    double tp = polish(q, p, a, b);
    if (tp < 0.0) {
        golden(q, p, &a, &b);
        tp = polish(q, p, a, b);
    }
    const double cands[4] = {tp, 0.5 * (a + b), a == 0.0 ? 0.0 : -1.0, b == 1.0 ? 1.0 : -1.0};
    for (int i = 0; i < 4; i++)
        if (cands[i] >= 0.0 && cands[i] <= 1.0) {
            const double dd = dist_at(q, p, cands[i]);
            if (dd < *bd)
                *bd = dd, *tb = cands[i];
        }
}

double ob_cert_nearest_hint(const ob_cv *q, const double p[2], const double (*tab)[2], int M, double hint, double *t)
{
    int best = 0;
    double bd = INFINITY;
    for (int k = 0; k < M; k++) {  /* squared: the scan only ranks rows */
        const double dx = p[0] - tab[k][0], dy = p[1] - tab[k][1], dd = dx * dx + dy * dy;
        if (dd < bd)
            bd = dd, best = k;
    }
    bd = hypot(p[0] - tab[best][0], p[1] - tab[best][1]);
    double tb = (double)best / (M - 1);
    /* the bracket of the nearest row's two spans usually holds one sign
     * change of the slope: regula falsi straight away; golden section first
     * only where it does not (a foot at an end, or two minima) */
    nearest_in(q, p, (double)(best > 0 ? best - 1 : 0) / (M - 1), (double)(best < M - 1 ? best + 1 : M - 1) / (M - 1),
               &bd, &tb);
    /* the nearest row can lie on another branch of a self-intersecting
     * offset (a swallowtail) than the nearest point: search the hint's
     * spans too (the correspondence's continuation) */
    if (hint >= 0.0 && hint <= 1.0) {
        const double w = 1.0 / (M - 1);
        nearest_in(q, p, fmax(0.0, hint - w), fmin(1.0, hint + w), &bd, &tb);
    }
    *t = tb;
    return bd;
}

double ob_cert_nearest(const ob_cv *q, const double p[2], const double (*tab)[2], int M, double *t)
{
    return ob_cert_nearest_hint(q, p, tab, M, -1.0, t);
}

double ob_cert_foot_hint(const ob_cv *p, const ob_cv *q, double u, const double (*tab)[2], int M, double hint,
                         double *t, double *slope)
{
    double x[2], dp[2], y[2], dq[2];
    ob_cert_eval(p, u, x, dp);
    const double dist = ob_cert_nearest_hint(q, x, tab, M, hint, t);
    ob_cert_eval(q, *t, y, dq);
    const double qq = dq[0] * dq[0] + dq[1] * dq[1];
    const int end = *t <= 0.0 || *t >= 1.0;
    *slope = end || !(qq > 0) ? 0.0 : (dp[0] * dq[0] + dp[1] * dq[1]) / qq;
    return dist;
}

double ob_cert_foot(const ob_cv *p, const ob_cv *q, double u, const double (*tab)[2], int M, double *t,
                    double *slope)
{
    return ob_cert_foot_hint(p, q, u, tab, M, -1.0, t, slope);
}

void ob_cert_feet(const ob_cv *p, const ob_cv *q, int S, const double (*tab)[2], double *foot, double *dist,
                  double *slope)
{
    for (int j = 0; j < S; j++)
        dist[j] = ob_cert_foot(p, q, (double)j / (S - 1), tab, S, &foot[j], &slope[j]);
}
