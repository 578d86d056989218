/*
 * perpiece.c - each piece's own error and worst point (perpiece.h).
 */
#include "host/measure/perpiece.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/run/signals.h"
#include "methods/metrics/metric.h"

void ob_perpiece_free(ob_perpiece *pp)
{
    free(pp->v);
    memset(pp, 0, sizeof *pp);
}

/* The squared distance from part A's point at s to q. */
static double dist2_at(const ob_bez *A, double s, const double q[2])
{
    double p[2];
    ob_bez_point(A, s, p);
    return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]);
}

enum { NEAR_SAMPLES = 1024 };

/* The parameter of A's point nearest to q: the nearest of NEAR_SAMPLES + 1
 * samples, refined by golden section between its neighbours. */
static double nearest_s(const ob_bez *A, const double q[2])
{
    int kb = 0;
    double best = INFINITY;
    for (int k = 0; k <= NEAR_SAMPLES; k++) {
        const double e = dist2_at(A, (double)k / NEAR_SAMPLES, q);
        if (e < best)
            best = e, kb = k;
    }
    const double g = 0.6180339887498949;
    double lo = (double)(kb > 0 ? kb - 1 : 0) / NEAR_SAMPLES, hi = (double)(kb < NEAR_SAMPLES ? kb + 1 : kb) / NEAR_SAMPLES;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = dist2_at(A, x1, q), f2 = dist2_at(A, x2, q);
    for (int it = 0; it < 80 && hi - lo > 1e-15; it++) {
        if (f1 < f2)
            hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = dist2_at(A, x1, q);
        else
            lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = dist2_at(A, x2, q);
    }
    const double s = f1 < f2 ? x1 : x2;
    return fmin(f1, f2) <= best ? s : (double)kb / NEAR_SAMPLES;
}

/* Part k of a measured as ob_approx_measure measures it under hausdorff:
 * its error e and the parameter of O on its base piece (*base). */
static int measure_part(const ob_curve *c, double d, const ob_approx *a, int k, int samples, const char *name,
                        ob_bez *base, ob_errval *e, ob_err *err)
{
    const ob_apiece *p = &a->v[k];
    if (ob_apiece_base(c, p, base) != 0)
        return ob_fail(err, "%s:%d: piece %d: its base segment %d is not a piece of curve '%s'", name, p->line,
                       ob_approx_file_piece(a, k), p->seg, c->id);
    const ob_cert_src src = {&c->seg[p->seg], p->a, p->b, p->t0, p->t1};
    if (ob_measure_src(OB_METRIC_HAUSDORFF, base, &src, &p->approx, d, samples, 0.0, e) != 0 || isnan(e->err))
        return ob_fail(err, "%s:%d: piece %d: metric hausdorff cannot measure it (degree %d)", name, p->line,
                       ob_approx_file_piece(a, k), p->approx.deg);
    return 0;
}

/* Takes part k's error into row r (the first of equal maxima kept, as
 * ob_approx_measure keeps them), with its worst point. */
static void take_part(const ob_approx *a, int k, const ob_bez *base, const ob_errval *e, double d, ob_pp_row *r)
{
    if (e->err <= r->err && r->worst >= 0)
        return;
    const ob_apiece *p = &a->v[k];
    r->err = e->err;
    r->worst = k;
    r->seg = p->seg;
    r->t = p->a + (p->b - p->a) * (p->t0 + (p->t1 - p->t0) * e->t);
    r->x = r->y = r->xo = r->yo = NAN;
    if (!isfinite(e->err))
        return;
    double q[2], xy[2];
    ob_bez_offset_point(base, e->t, d, q);
    ob_bez_point(&p->approx, nearest_s(&p->approx, q), xy);
    r->xo = q[0], r->yo = q[1], r->x = xy[0], r->y = xy[1];
}

int ob_approx_per_piece(const ob_curve *c, double d, const ob_approx *a, int samples, const char *name,
                        ob_perpiece *pp, ob_err *err)
{
    memset(pp, 0, sizeof *pp);
    const int n = ob_approx_file_pieces(a);
    if (n > 0 && !(pp->v = calloc((size_t)n, sizeof *pp->v)))
        return ob_fail(err, "%s: out of memory", name);
    for (int k = 0; k < a->n; k++) {
        if (ob_stop_signal()) { /* a long loop polls the stop (signals.h) */
            ob_perpiece_free(pp);
            return ob_fail(err, "%s: stopped by signal %d after %d of %d pieces", name, ob_stop_signal(), k, a->n);
        }
        const int fp = ob_approx_file_piece(a, k);
        ob_pp_row *r = &pp->v[fp];
        if (k == 0 || fp != ob_approx_file_piece(a, k - 1))
            *r = (ob_pp_row){fp, k, k, 0.0, -1, 0, 0.0, NAN, NAN, NAN, NAN};
        r->last = k;
        ob_bez base;
        ob_errval e;
        if (measure_part(c, d, a, k, samples, name, &base, &e, err) != 0) {
            ob_perpiece_free(pp);
            return -1;
        }
        take_part(a, k, &base, &e, d, r);
    }
    pp->n = n;
    return 0;
}
