/*
 * diagnose.c - what a far file looks like instead (diagnose.h): the
 * offset at -d, or the offset under a similarity found by ICP.
 */
#include "host/measure/diagnose.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "methods/driver/joints.h"

enum { DIAG_POINTS = 400, DIAG_PER_SEG = 256, DIAG_ICP = 40 };

/* Polylines: points, and start[i] 1 where a new polyline begins at i. */
typedef struct {
    double (*p)[2];
    char *start;
    int n;
} poly;

static void poly_free(poly *q)
{
    free(q->p);
    free(q->start);
    memset(q, 0, sizeof *q);
}

static int poly_alloc(poly *q, int n)
{
    q->p = malloc((size_t)n * sizeof *q->p);
    q->start = calloc((size_t)n, 1);
    q->n = n;
    return q->p && q->start ? 0 : -1;
}

/* Each piece of a at k parameters (one polyline per piece). */
static int sample_file(const ob_approx *a, poly *q)
{
    const int k = a->n ? (int)fmax(2.0, fmin(32.0, (double)DIAG_POINTS / a->n)) : 0;
    if (a->n == 0 || poly_alloc(q, a->n * k))
        return -1;
    for (int i = 0; i < a->n; i++)
        for (int j = 0; j < k; j++) {
            ob_bez_point(&a->v[i].approx, (double)j / (k - 1), q->p[i * k + j]);
            q->start[i * k + j] = j == 0;
        }
    return 0;
}

/* The exact d-offset of c, each base segment at DIAG_PER_SEG + 1 parameters. */
static int sample_offset(const ob_curve *c, double d, poly *q)
{
    const int k = DIAG_PER_SEG + 1;
    if (poly_alloc(q, c->nseg * k))
        return -1;
    for (int s = 0; s < c->nseg; s++)
        for (int j = 0; j < k; j++) {
            ob_bez_offset_point(&c->seg[s], (double)j / (k - 1), d, q->p[s * k + j]);
            q->start[s * k + j] = j == 0;
        }
    return 0;
}

/* The point of segment [u, v] nearest to x, into y; its squared distance. */
static double seg_near(const double x[2], const double u[2], const double v[2], double y[2])
{
    const double ex = v[0] - u[0], ey = v[1] - u[1], l2 = ex * ex + ey * ey;
    double s = l2 > 0.0 ? ((x[0] - u[0]) * ex + (x[1] - u[1]) * ey) / l2 : 0.0;
    s = fmin(1.0, fmax(0.0, s));
    y[0] = u[0] + s * ex;
    y[1] = u[1] + s * ey;
    return (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]);
}

/* The distance of x to the polylines q, the nearest point into y. */
static double poly_dist(const double x[2], const poly *q, double y[2])
{
    double best = INFINITY, z[2];
    for (int i = 0; i < q->n; i++) {
        const int lone = q->start[i] && (i + 1 == q->n || q->start[i + 1]);
        if (!q->start[i] || lone) {
            const double e = seg_near(x, q->p[q->start[i] ? i : i - 1], q->p[i], z);
            if (e < best) {
                best = e;
                y[0] = z[0];
                y[1] = z[1];
            }
        }
    }
    return sqrt(best);
}

/* The largest distance of the points of p to the polylines q. */
static double one_sided(const poly *p, const poly *q)
{
    double worst = 0.0, y[2];
    for (int i = 0; i < p->n; i++)
        worst = fmax(worst, poly_dist(p->p[i], q, y));
    return worst;
}

/* p mapped by f, into m (allocated like p). */
static int poly_map(const poly *p, const ob_frame *f, poly *m)
{
    if (poly_alloc(m, p->n))
        return -1;
    memcpy(m->start, p->start, (size_t)p->n);
    for (int i = 0; i < p->n; i++)
        ob_frame_point(f, p->p[i], m->p[i]);
    return 0;
}

/* The two-sided distance between p mapped by f and q; INFINITY out of memory. */
static double residual(const poly *p, const ob_frame *f, const poly *q)
{
    poly m = {0};
    double r = INFINITY;
    if (poly_map(p, f, &m) == 0)
        r = fmax(one_sided(&m, q), one_sided(q, &m));
    poly_free(&m);
    return r;
}

/* Length-weighted centroid c and covariance (xx, yy, xy) of q's segments. */
static void moments(const poly *q, double c[2], double cov[3])
{
    double L = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
    for (int i = 1; i < q->n; i++) {
        if (q->start[i])
            continue;
        const double l = hypot(q->p[i][0] - q->p[i - 1][0], q->p[i][1] - q->p[i - 1][1]);
        const double x = 0.5 * (q->p[i][0] + q->p[i - 1][0]), y = 0.5 * (q->p[i][1] + q->p[i - 1][1]);
        L += l, sx += l * x, sy += l * y, sxx += l * x * x, syy += l * y * y, sxy += l * x * y;
    }
    L = L > 0.0 ? L : 1.0;
    c[0] = sx / L, c[1] = sy / L;
    cov[0] = sxx / L - c[0] * c[0], cov[1] = syy / L - c[1] * c[1], cov[2] = sxy / L - c[0] * c[1];
}

/* The similarity from moments: p's principal axis (reflected in y when r)
 * turned onto q's and k quarter turns more, the spreads' ratio as scale. */
static ob_frame from_moments(const double cp[2], const double vp[3], const double cq[2], const double vq[3], int r,
                             int k)
{
    const double sy = r ? -1.0 : 1.0;
    const double php = 0.5 * atan2(2.0 * sy * vp[2], vp[0] - vp[1]), phq = 0.5 * atan2(2.0 * vq[2], vq[0] - vq[1]);
    const double th = phq - php + k * (OB_PI / 2), s = sqrt((vq[0] + vq[1]) / fmax(vp[0] + vp[1], 1e-300));
    ob_frame f = {{s * cos(th), s * sin(th), -s * sin(th) * sy, s * cos(th) * sy, 0, 0}};
    f.m[4] = cq[0] - (f.m[0] * cp[0] + f.m[2] * cp[1]);
    f.m[5] = cq[1] - (f.m[1] * cp[0] + f.m[3] * cp[1]);
    return f;
}

/* Nearest-point ICP from f (reflected when r) of p onto q; 0 or -1. */
static int icp(const poly *p, const poly *q, int r, ob_frame *f)
{
    double(*near)[2] = malloc((size_t)p->n * sizeof *near);
    if (!near)
        return -1;
    for (int it = 0; it < DIAG_ICP; it++) {
        for (int i = 0; i < p->n; i++) {
            double x[2];
            ob_frame_point(f, p->p[i], x);
            poly_dist(x, q, near[i]);
        }
        ob_frame g;
        if (ob_similarity_fit((const double(*)[2])p->p, (const double(*)[2])near, p->n, r, &g))
            break;
        double change = 0.0;
        for (int k = 0; k < 6; k++)
            change = fmax(change, fabs(g.m[k] - f->m[k]));
        *f = g;
        if (change <= 1e-15 * (1.0 + fabs(f->m[4]) + fabs(f->m[5])))
            break;
    }
    free(near);
    return 0;
}

/* The unit factors of drawings (mm, cm, in, pt, px, m ...) a scale snaps to. */
static const double unit_scale[] = {1, 10, 100, 1000, 25.4, 2.54, 0.254, 72, 96, 12, 96 / 25.4, 72 / 25.4, 6, 16};

/* s snapped to a unit factor or its inverse within 2e-3, else s. */
static double snap_scale(double s)
{
    for (size_t i = 0; i < sizeof unit_scale / sizeof unit_scale[0]; i++)
        for (int inv = 0; inv < 2; inv++) {
            const double u = inv ? 1.0 / unit_scale[i] : unit_scale[i];
            if (fabs(s / u - 1.0) < 2e-3)
                return u;
        }
    return s;
}

/* The translation alone refitted by ICP, the linear part of f fixed. */
static int icp_translate(const poly *p, const poly *q, ob_frame *f)
{
    for (int it = 0; it < DIAG_ICP; it++) {
        double sx = 0.0, sy = 0.0, x[2], y[2];
        for (int i = 0; i < p->n; i++) {
            ob_frame_point(f, p->p[i], x);
            poly_dist(x, q, y);
            sx += y[0] - x[0];
            sy += y[1] - x[1];
        }
        f->m[4] += sx / p->n;
        f->m[5] += sy / p->n;
        if (hypot(sx, sy) / p->n <= 1e-15 * (1.0 + fabs(f->m[4]) + fabs(f->m[5])))
            break;
    }
    return 0;
}

/* The translation of f snapped: the file point the map takes to the base's
 * origin, o = -L^-1 t, rounded to a grid of the power of ten just above
 * 4 r in file units (a drawing's origin is a round number). */
static ob_frame snap_origin(const ob_frame *f, double r)
{
    const double det = ob_frame_det(f), *m = f->m;
    const double ox = -(m[3] * m[4] - m[2] * m[5]) / det, oy = -(-m[1] * m[4] + m[0] * m[5]) / det;
    const double g = pow(10.0, ceil(log10(4.0 * r / sqrt(fabs(det)))));
    const double rx = round(ox / g) * g, ry = round(oy / g) * g;
    ob_frame h = *f;
    h.m[4] = -(m[0] * rx + m[2] * ry);
    h.m[5] = -(m[1] * rx + m[3] * ry);
    return h;
}

/* f with its scale snapped to a unit factor and its turn to a quarter
 * turn within 0.05 degrees, its translation refitted, when that fits
 * about as well (residual at most twice r): a CAD frame's exact numbers
 * rather than the fit's, which the pieces' own error blurs. */
static void snap(const poly *p, const poly *q, ob_frame *f, double *r)
{
    const double det = ob_frame_det(f), sy = det < 0 ? -1.0 : 1.0;
    const double s = snap_scale(sqrt(fabs(det)));
    double th = atan2(f->m[1], f->m[0]);
    const double quarter = round(th / (OB_PI / 2));
    if (fabs(th - quarter * (OB_PI / 2)) < 0.05 * OB_PI / 180)
        th = quarter * (OB_PI / 2);
    const double c = fabs(th) == OB_PI / 2 ? 0.0 : cos(th), sn = fabs(th) == OB_PI || th == 0.0 ? 0.0 : sin(th);
    ob_frame g = {{s * c, s * sn, -s * sn * sy, s * c * sy, f->m[4], f->m[5]}};
    icp_translate(p, q, &g);
    const double rg = residual(p, &g, q);
    if (rg <= 2.0 * *r) {
        *f = g;
        *r = rg;
        if (!(rg > 0.0))
            return;
        const ob_frame h = snap_origin(&g, rg);
        const double rh = residual(p, &h, q);
        if (rh <= 2.0 * rg) {
            *f = h;
            *r = rh;
        }
    }
}

/* The best similarity of p onto q (8 starts), into *best; its residual. */
static double best_similarity(const poly *p, const poly *q, ob_frame *best)
{
    double cp[2], vp[3], cq[2], vq[3], rbest = INFINITY;
    moments(p, cp, vp);
    moments(q, cq, vq);
    for (int r = 0; r < 2; r++)
        for (int k = 0; k < 4; k++) {
            ob_frame f = from_moments(cp, vp, cq, vq, r, k);
            if (icp(p, q, r, &f))
                return INFINITY;
            double e = residual(p, &f, q);
            snap(p, q, &f, &e);
            if (e < rbest) {
                rbest = e;
                *best = f;
            }
        }
    return rbest;
}

int ob_diag_far(const ob_curve *c, double d, double err)
{
    return !(err <= OB_DIAG_FAR * ob_joint_size(c, d));
}

/* The map found (after the frame given) as a line into buf. */
static void say_similarity(const ob_frame *f, const ob_frame *given, double r, const char *name, char *buf,
                           size_t len)
{
    const ob_frame total = ob_frame_mul(f, given);
    char t[200];
    ob_frame_text(&total, t, sizeof t);
    const double det = ob_frame_det(f);
    snprintf(buf, len, "%s: a similarity maps it onto the offset within %.3g (scale %.6g, turn %.4g degrees%s): "
             "try --transform %s", name, r, sqrt(fabs(det)), atan2(f->m[1], f->m[0]) * 180.0 / OB_PI,
             det < 0 ? ", then y = -y" : "", t);
}

int ob_diagnose(const ob_curve *c, double d, const ob_approx *a, const ob_frame *given, const char *name, char *buf,
                size_t len)
{
    poly p = {0}, qp = {0}, qm = {0};
    int found = -1;
    buf[0] = '\0';
    if (sample_file(a, &p) || sample_offset(c, d, &qp) || sample_offset(c, -d, &qm))
        goto out;
    found = 0;
    const double size = ob_joint_size(c, d), near = OB_DIAG_FAR * size;
    const double xp = one_sided(&p, &qp), xm = one_sided(&p, &qm);
    if (xm <= near && xm < 0.1 * xp) {
        char ds[40];
        ob_fmt_double(ds, sizeof ds, -d);
        snprintf(buf, len, "%s: it is within %.3g of the offset at d = %s: wrong sign of --d?", name, xm, ds);
        found = 1;
        goto out;
    }
    const ob_frame flip = {{1, 0, 0, -1, 0, 0}};
    const double rf = residual(&p, &flip, &qp);
    ob_frame f;
    const double rs = rf <= near ? rf : best_similarity(&p, &qp, &f);
    if (rf <= near)
        f = flip;
    if (rs <= near && rs < 0.1 * fmax(xp, one_sided(&qp, &p))) {
        say_similarity(&f, given, rs, name, buf, len);
        found = 1;
    }
out:
    poly_free(&p);
    poly_free(&qp);
    poly_free(&qm);
    return found;
}
