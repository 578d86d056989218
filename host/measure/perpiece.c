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

/* The tangent component of A(s) - q along the unit tangent T. */
static double along(const ob_bez *A, double s, const double q[2], const double T[2])
{
    double p[2];
    ob_bez_point(A, s, p);
    return (p[0] - q[0]) * T[0] + (p[1] - q[1]) * T[1];
}

/* The distance from p to the d-offset of base (OFF_SAMPLES samples, the
 * nearest refined by golden section between its neighbours). */
enum { OFF_SAMPLES = 512 };
static double off_dist(const ob_bez *base, double d, const double p[2])
{
    int kb = 0;
    double best = INFINITY, o[2];
    for (int k = 0; k <= OFF_SAMPLES; k++) {
        ob_bez_offset_point(base, (double)k / OFF_SAMPLES, d, o);
        const double e = hypot(p[0] - o[0], p[1] - o[1]);
        if (e < best)
            best = e, kb = k;
    }
    const double g = 0.6180339887498949;
    double lo = (double)(kb > 0 ? kb - 1 : 0) / OFF_SAMPLES, hi = (double)(kb < OFF_SAMPLES ? kb + 1 : kb) / OFF_SAMPLES;
    for (int it = 0; it < 80 && hi - lo > 1e-15; it++) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        double o1[2], o2[2];
        ob_bez_offset_point(base, x1, d, o1);
        ob_bez_offset_point(base, x2, d, o2);
        if (hypot(p[0] - o1[0], p[1] - o1[1]) < hypot(p[0] - o2[0], p[1] - o2[1]))
            hi = x2;
        else
            lo = x1;
    }
    ob_bez_offset_point(base, 0.5 * (lo + hi), d, o);
    return fmin(best, hypot(p[0] - o[0], p[1] - o[1]));
}

/* The tangent component of A(s) - q along T, bisected to its root between
 * lo and hi (it changes sign there). */
static double bisect_along(const ob_bez *A, double lo, double hi, const double q[2], const double T[2])
{
    const int neg = along(A, lo, q, T) < 0.0;
    for (int it = 0; it < 60; it++) {
        const double m = 0.5 * (lo + hi);
        if (m <= lo || m >= hi)
            break;
        *((along(A, m, q, T) < 0.0) == neg ? &lo : &hi) = m;
    }
    return 0.5 * (lo + hi);
}

/* ||A(s) - q| - e|. */
static double off_e(const ob_bez *A, double s, const double q[2], double e)
{
    return fabs(sqrt(dist2_at(A, s, q)) - e);
}

/* Golden-section minimum of off_e over [lo, hi]. */
static double golden_e(const ob_bez *A, double lo, double hi, const double q[2], double e)
{
    const double g = 0.6180339887498949;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = off_e(A, x1, q, e), f2 = off_e(A, x2, q, e);
    for (int it = 0; it < 80 && hi - lo > 1e-15; it++) {
        if (f1 < f2)
            hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = off_e(A, x1, q, e);
        else
            lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = off_e(A, x2, q, e);
    }
    return f1 < f2 ? x1 : x2;
}

enum { E_CANDIDATES = 16 };

/* The parameter of A's point at the worst error e, q = O(t) its offset
 * point: where the worst is on the offset's side, A's point nearest to q
 * (it is e from q); where it is on A's side (a bump of A), the point of A
 * e from q whose own distance to the offset is e (q its foot: on the
 * normal line through q, or q a clamped end of the base range).
 * Candidates: the nearest point, then the crossings of the normal line
 * (T: the offset's unit tangent at q; sign changes over NEAR_SAMPLES
 * chords, bisected) and the local minima of ||A - q| - e| (the
 * E_CANDIDATES smallest, golden section), scored by how far each is from e
 * to q and from e to the offset; the best. */
static double worst_s(const ob_bez *A, const ob_bez *base, double d, const double q[2], const double T[2], double e)
{
    const double s0 = nearest_s(A, q), h = 1.0 / NEAR_SAMPLES;
    if (off_e(A, s0, q, e) <= 1e-9 * e)
        return s0;
    double cross[E_CANDIDATES], seed[E_CANDIDATES], fseed[E_CANDIDATES];
    int nx = 0, ns = 0;
    double g0 = along(A, 0.0, q, T), f0 = INFINITY, f1 = off_e(A, 0.0, q, e);
    for (int k = 0; k <= NEAR_SAMPLES; k++) {
        const double s = k * h, f2 = k < NEAR_SAMPLES ? off_e(A, s + h, q, e) : INFINITY;
        if (k > 0) {
            const double g1 = along(A, s, q, T);
            if ((g0 < 0.0) != (g1 < 0.0) && nx < E_CANDIDATES)
                cross[nx++] = bisect_along(A, s - h, s, q, T);
            g0 = g1;
        }
        if (f1 <= f0 && f1 <= f2) { /* a local minimum: keep the E_CANDIDATES smallest */
            int at = 0, room = ns < E_CANDIDATES;
            if (room)
                at = ns++;
            else /* full: the largest kept is replaced when larger */
                for (int i = 1; i < E_CANDIDATES; i++)
                    at = fseed[i] > fseed[at] ? i : at;
            if (room || fseed[at] > f1)
                seed[at] = s, fseed[at] = f1;
        }
        f0 = f1, f1 = f2;
    }
    double best = s0, gap = INFINITY;
    for (int i = 0; i < nx + ns; i++) {
        const double c = i < nx ? cross[i] : golden_e(A, fmax(seed[i - nx] - h, 0.0), fmin(seed[i - nx] + h, 1.0), q, e);
        double p[2];
        ob_bez_point(A, c, p);
        const double g = off_e(A, c, q, e) + fabs(off_dist(base, d, p) - e);
        if (g < gap)
            best = c, gap = g;
    }
    return best;
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
    double q[2], xy[2], D[2][2], T[2] = {0.0, 0.0};
    ob_bez_offset_point(base, e->t, d, q);
    ob_bez_eval(base, e->t, 1, D);
    const double L = hypot(D[1][0], D[1][1]);
    if (L > 0.0)
        T[0] = D[1][0] / L, T[1] = D[1][1] / L;
    ob_bez_point(&p->approx, L > 0.0 ? worst_s(&p->approx, base, d, q, T, e->err) : nearest_s(&p->approx, q), xy);
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
