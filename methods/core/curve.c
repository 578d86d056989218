/*
 * curve.c - construction, evaluation, subdivision and degree elevation of
 * homogeneous Bézier segments.  See curve.h for the conventions.
 */
#include "methods/core/curve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/core/bernstein.h"
#include "kernels/metric_core.h"

void ob_bez_set(ob_bez *b, int i, double x, double y, double w)
{
    b->h[i][0] = w * x;
    b->h[i][1] = w * y;
    b->h[i][2] = w;
    if (w != 1.0)
        b->rational = 1;
}

void ob_bez_from_points(ob_bez *b, int deg, const double (*xy)[2])
{
    memset(b, 0, sizeof *b);
    b->deg = deg;
    for (int i = 0; i <= deg; i++)
        ob_bez_set(b, i, xy[i][0], xy[i][1], 1.0);
}

void ob_bez_ctrl(const ob_bez *b, int i, double p[2])
{
    p[0] = b->h[i][0] / b->h[i][2];
    p[1] = b->h[i][1] / b->h[i][2];
}

double ob_bez_weight(const ob_bez *b, int i) { return b->h[i][2]; }

void ob_bez_eval(const ob_bez *b, double t, int nder, double out[][2])
{
    long ops = 0; /* the metrics' work count, not wanted here */
    obc_eval(&b->h[0][0], b->deg, t, nder, out, &ops);
}

void ob_bez_point(const ob_bez *b, double t, double p[2])
{
    double o[1][2];
    ob_bez_eval(b, t, 0, o);
    p[0] = o[0][0];
    p[1] = o[0][1];
}

void ob_curve_free(ob_curve *c)
{
    if (!c)
        return;
    free(c->source);
    free(c->family);
    free(c->seg);
    free(c->d);
    memset(c, 0, sizeof *c);
}

long ob_count_ctrl_points(const int *degs, int k)
{
    long n = 1;
    for (int i = 0; i < k; i++)
        n += degs[i];
    return k > 0 ? n : 0;
}

/* ---- subdivision and degree ------------------------------------------- */

void ob_bez_split(const ob_bez *b, double t, ob_bez *left, ob_bez *right)
{
    const int n = b->deg;
    double q[OB_MAX_DEG + 1][3];
    memcpy(q, b->h, (size_t)(n + 1) * sizeof q[0]);
    ob_bez L = {.deg = n, .rational = b->rational}, R = L;
    const double s = 1.0 - t;
    memcpy(L.h[0], q[0], sizeof q[0]);
    memcpy(R.h[n], q[n], sizeof q[0]);
    for (int lev = 1; lev <= n; lev++) {
        for (int i = 0; i <= n - lev; i++)
            for (int k = 0; k < 3; k++)
                q[i][k] = s * q[i][k] + t * q[i + 1][k];
        memcpy(L.h[lev], q[0], sizeof q[0]);
        memcpy(R.h[n - lev], q[n - lev], sizeof q[0]);
    }
    if (left)
        *left = L;
    if (right)
        *right = R;
}

void ob_bez_subsegment(const ob_bez *src, double a, double b, ob_bez *out)
{
    ob_bez tmp;
    if (b < 1.0) {
        ob_bez_split(src, b, &tmp, NULL);
    } else {
        tmp = *src;
        b = 1.0;
    }
    if (a > 0.0)
        ob_bez_split(&tmp, a / b, NULL, out);
    else
        *out = tmp;
}

int ob_bez_elevate(const ob_bez *b, int to, ob_bez *out)
{
    if (to > OB_MAX_DEG || to < b->deg)
        return -1;
    ob_bez r = {.deg = to, .rational = b->rational};
    double a[OB_MAX_DEG + 1], c[OB_MAX_DEG + 1];
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i <= b->deg; i++)
            a[i] = b->h[i][k];
        ob_bern_elevate(a, b->deg, to, c);
        for (int i = 0; i <= to; i++)
            r.h[i][k] = c[i];
    }
    *out = r;
    return 0;
}

/* ---- differential geometry -------------------------------------------- */

/* The tangent direction and normal, with their one-sided limits at cusps and
 * -1 on point-like segments, are the metric core's (kernels/metric_core.h). */
static int tangent_dir(const ob_bez *b, double t, double v[2])
{
    long ops = 0;
    return obc_tangent(&b->h[0][0], b->deg, t, v, &ops);
}

int ob_bez_normal(const ob_bez *b, double t, double n[2])
{
    long ops = 0;
    return obc_normal(&b->h[0][0], b->deg, t, n, &ops);
}

double ob_bez_curvature(const ob_bez *b, double t)
{
    double o[3][2];
    ob_bez_eval(b, t, 2, o);
    double sp = sqrt(o[1][0] * o[1][0] + o[1][1] * o[1][1]);
    if (sp == 0.0)
        return 0.0;
    return (o[1][0] * o[2][1] - o[1][1] * o[2][0]) / (sp * sp * sp);
}

/* One evaluation gives the point and the derivatives its normal needs (the
 * point of obc_eval does not depend on nder): the bits of ob_bez_point and
 * ob_bez_normal called apart, at one de Casteljau pass instead of two. */
void ob_bez_offset_point(const ob_bez *b, double t, double d, double p[2])
{
    const double *h = &b->h[0][0];
    long ops = 0;
    double o[3][2], v[2], n[2] = {0.0, 0.0}, tiny;
    if (obc_tangent_scale(h, b->deg, &tiny) != 0) {
        obc_eval(h, b->deg, t, 0, o, &ops);
    } else {
        obc_eval(h, b->deg, t, 2, o, &ops);
        if (obc_tangent_from(h, b->deg, t, tiny, o, v, &ops) == 0)
            obc_unit_normal(v, n);
    }
    p[0] = o[0][0] + d * n[0];
    p[1] = o[0][1] + d * n[1];
}

void ob_bez_offset_point_d(const ob_bez *b, double t, double d, double p[2], double dp[2])
{
    double e[3][2];
    ob_bez_offset_point(b, t, d, p);
    ob_bez_eval(b, t, 2, e);
    const double L = hypot(e[1][0], e[1][1]);
    const double f = L > 0.0 ? 1.0 - d * (e[1][0] * e[2][1] - e[1][1] * e[2][0]) / (L * L * L) : 0.0;
    dp[0] = e[1][0] * f, dp[1] = e[1][1] * f;
}

/* ---- shape analysis --------------------------------------------------- */

enum { CUSP_SAMPLES = 64 };
/* |1 - d kappa| at or below this is round-off of zero, not a sign */
static const double CUSP_G_ZERO = 1e-12;

static double speed_factor(const ob_bez *b, double t, double d) { return 1.0 - d * ob_bez_curvature(b, t); }

int ob_bez_offset_cusps(const ob_bez *b, double d, double *ts, int max)
{
    int n = 0;
    if (d == 0.0)
        return 0;
    /* tp, gp: the last sample where |1 - d kappa| is more than round-off */
    double tp = 0.5 / CUSP_SAMPLES, gp = speed_factor(b, tp, d);
    for (int k = 1; k < CUSP_SAMPLES; k++) {
        const double t = (k + 0.5) / CUSP_SAMPLES, g = speed_factor(b, t, d);
        if (fabs(g) <= CUSP_G_ZERO)
            continue;
        if (fabs(gp) > CUSP_G_ZERO && (g < 0.0) != (gp < 0.0)) {
            double lo = tp, hi = t;
            for (int it = 0; it < 60 && hi - lo > 1e-15; it++) {
                const double mid = 0.5 * (lo + hi);
                if ((speed_factor(b, mid, d) < 0.0) == (gp < 0.0))
                    lo = mid;
                else
                    hi = mid;
            }
            if (n == max)
                return max + 1;
            ts[n++] = 0.5 * (lo + hi);
        }
        tp = t;
        gp = g;
    }
    return n;
}

int ob_bez_inflections(const ob_bez *b, double *ts, int max)
{
    const int n = b->deg;
    if (n < 2)
        return 0;
    /* hodographs of the homogeneous coordinates */
    double d1[3][OB_MAX_DEG], d2[3][OB_MAX_DEG], h0[3][OB_MAX_DEG + 1];
    double m1 = 0, m2 = 0, m0 = 0;
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i <= n; i++) {
            h0[k][i] = b->h[i][k];
            m0 = fmax(m0, fabs(h0[k][i]));
        }
        for (int i = 0; i < n; i++) {
            d1[k][i] = n * (b->h[i + 1][k] - b->h[i][k]);
            m1 = fmax(m1, fabs(d1[k][i]));
        }
        for (int i = 0; i < n - 1; i++) {
            d2[k][i] = n * (n - 1) * (b->h[i + 2][k] - 2 * b->h[i + 1][k] + b->h[i][k]);
            m2 = fmax(m2, fabs(d2[k][i]));
        }
    }
    /* cross = P' x P'' componentwise, degree 2n-3 */
    const int dc = 2 * n - 3;
    double cr[3][2 * OB_MAX_DEG], t1[OB_BERN_MAX + 1], t2[OB_BERN_MAX + 1];
    static const int ax[3][2] = {{1, 2}, {2, 0}, {0, 1}};
    for (int k = 0; k < 3; k++) {
        ob_bern_mul(d1[ax[k][0]], n - 1, d2[ax[k][1]], n - 2, t1);
        ob_bern_mul(d1[ax[k][1]], n - 1, d2[ax[k][0]], n - 2, t2);
        for (int i = 0; i <= dc; i++)
            cr[k][i] = t1[i] - t2[i];
    }
    double det[3 * OB_MAX_DEG + 1];
    int dd;
    double mag;
    if (!b->rational) {
        dd = dc;  /* P = (x, y, 1), P' and P'' have w = 0: det = x'y'' - y'x'' */
        memcpy(det, cr[2], (size_t)(dd + 1) * sizeof *det);
        mag = m1 * m2;
    } else {
        dd = 3 * n - 3;
        for (int i = 0; i <= dd; i++)
            det[i] = 0.0;
        for (int k = 0; k < 3; k++) {
            ob_bern_mul(h0[k], n, cr[k], dc, t1);
            for (int i = 0; i <= dd; i++)
                det[i] += t1[i];
        }
        mag = m0 * m1 * m2;
    }
    /* round-off on a straight or nearly straight piece must not create roots */
    int nonzero = 0;
    for (int i = 0; i <= dd; i++) {
        if (fabs(det[i]) < 1e-13 * mag)
            det[i] = 0.0;
        nonzero |= det[i] != 0.0;
    }
    if (!nonzero)
        return 0;
    return ob_bern_roots(det, dd, ts, max);
}

static double tangent_angle(const ob_bez *b, double t)
{
    double v[2];
    if (tangent_dir(b, t, v) != 0)
        return 0.0;
    return atan2(v[1], v[0]);
}

/* Turning of the tangent over [t0,t1], summed over `samples` steps. */
static double turn_between(const ob_bez *b, double t0, double t1, int samples)
{
    double prev = tangent_angle(b, t0), total = 0.0;
    for (int i = 1; i <= samples; i++) {
        double a = tangent_angle(b, t0 + (t1 - t0) * i / samples);
        double da = a - prev;
        while (da > OB_PI)
            da -= 2 * OB_PI;
        while (da < -OB_PI)
            da += 2 * OB_PI;
        total += da;
        prev = a;
    }
    return total;
}

double ob_bez_turn(const ob_bez *b, int samples)
{
    return fabs(turn_between(b, 0.0, 1.0, samples > 0 ? samples : 64));
}

double ob_bez_turn_param(const ob_bez *b, double angle)
{
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi);
        if (fabs(turn_between(b, 0.0, mid, 64)) < angle)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}
