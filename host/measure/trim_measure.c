/*
 * trim_measure.c - trimmed-hausdorff (trim.h, ob_trimmed_hausdorff): the
 * two-sided Hausdorff distance between a file's pieces and the trimmed
 * offset, both taken as point sets: no parameter match, no cover check (a
 * missing part shows as a large distance from the trimmed offset).
 */
#include "host/measure/trim.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "host/run/signals.h"

enum { SIDE_FILE = 0, SIDE_TRIM = 1, ARC_SAMPLES_MIN = 1024, BLK = 32 };

/* One side: the file's pieces or the trimmed offset's arcs, each sampled
 * at T parameters u_i = i / (T - 1). */
typedef struct {
    int side, n, T;
    const ob_approx *a;
    const ob_trim *tr;
    const ob_curve *c;
    double d;
    double *pts;   /* [n][T][2] */
    double *circ;  /* [n][4]: a circle holding the curve (x, y, r), the longest chord between samples */
    double *f2;    /* [T]: scratch, squared distances to the samples of one curve */
    int nb;        /* blocks of BLK samples a curve (the last shares its first sample with the one before) */
    double *blk;   /* [n][nb][3]: a circle holding each block's samples (x, y, r) */
    char *seen;    /* [nb]: scratch, the blocks of one curve scanned */
    double *bd;    /* [nb]: scratch, the distances to their centres */
} cset;

#define NBLK(T) (((T) - 1 + BLK - 1) / BLK)

static void cs_point(const cset *s, int k, double u, double p[2])
{
    if (s->side == SIDE_FILE) {
        ob_bez_point(&s->a->v[k].approx, u, p);
        return;
    }
    ob_trim_arc_point(s->c, s->d, &s->tr->arc[k], u, p);
}

/* The point of curve k at u and its derivative in u. */
static void cs_point_d(const cset *s, int k, double u, double p[2], double dp[2])
{
    double e[3][2];
    if (s->side == SIDE_FILE) {
        ob_bez_eval(&s->a->v[k].approx, u, 1, e);
        p[0] = e[0][0], p[1] = e[0][1], dp[0] = e[1][0], dp[1] = e[1][1];
        return;
    }
    const ob_trim_arc *ar = &s->tr->arc[k];
    if (ar->corner) { /* ctr + r (cos a, sin a), a = t0 + (t1 - t0) u */
        const double a = ar->t0 + (ar->t1 - ar->t0) * u, w = ar->r * (ar->t1 - ar->t0);
        p[0] = ar->ctr[0] + ar->r * cos(a), p[1] = ar->ctr[1] + ar->r * sin(a);
        dp[0] = -w * sin(a), dp[1] = w * cos(a);
        return;
    }
    const ob_bez *b = &s->c->seg[ar->seg];
    const double t = ar->t0 + (ar->t1 - ar->t0) * u;
    ob_bez_eval(b, t, 2, e);
    const double L = hypot(e[1][0], e[1][1]);
    ob_bez_offset_point(b, t, s->d, p);
    const double f = L > 0.0 ? (1.0 - s->d * (e[1][0] * e[2][1] - e[1][1] * e[2][0]) / (L * L * L)) * (ar->t1 - ar->t0)
                             : 0.0;
    dp[0] = e[1][0] * f, dp[1] = e[1][1] * f;
}

static double sample_u(const cset *s, int i)
{
    return i == s->T - 1 ? 1.0 : (double)i / (s->T - 1);
}

/* Samples and the bounding circle of curve k. */
static void cs_fill(cset *s, int k)
{
    double *P = s->pts + 2 * (size_t)k * s->T, *o = s->circ + 4 * (size_t)k;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, h = 0.0, r = 0.0;
    for (int i = 0; i < s->T; i++) {
        cs_point(s, k, sample_u(s, i), P + 2 * i);
        x0 = fmin(x0, P[2 * i]), x1 = fmax(x1, P[2 * i]), y0 = fmin(y0, P[2 * i + 1]), y1 = fmax(y1, P[2 * i + 1]);
        if (i > 0)
            h = fmax(h, hypot(P[2 * i] - P[2 * i - 2], P[2 * i + 1] - P[2 * i - 1]));
    }
    o[0] = 0.5 * (x0 + x1), o[1] = 0.5 * (y0 + y1);
    for (int i = 0; i < s->T; i++)
        r = fmax(r, hypot(P[2 * i] - o[0], P[2 * i + 1] - o[1]));
    o[2] = isfinite(r + h) ? r + h : INFINITY, o[3] = h;
    for (int b = 0; b < s->nb; b++) { /* samples b BLK ... (b + 1) BLK */
        const int i0 = b * BLK, i1 = (b + 1) * BLK < s->T - 1 ? (b + 1) * BLK : s->T - 1;
        double *c = s->blk + 3 * ((size_t)k * s->nb + b), bx0 = INFINITY, by0 = INFINITY, bx1 = -INFINITY, by1 = -INFINITY;
        for (int i = i0; i <= i1; i++)
            bx0 = fmin(bx0, P[2 * i]), bx1 = fmax(bx1, P[2 * i]), by0 = fmin(by0, P[2 * i + 1]), by1 = fmax(by1, P[2 * i + 1]);
        c[0] = 0.5 * (bx0 + bx1), c[1] = 0.5 * (by0 + by1), c[2] = 0.0;
        for (int i = i0; i <= i1; i++)
            c[2] = fmax(c[2], hypot(P[2 * i] - c[0], P[2 * i + 1] - c[1]));
        if (!isfinite(c[2]))
            c[2] = INFINITY;
    }
}

static int cs_init(cset *s, int side, int n, int T)
{
    s->side = side, s->n = n, s->T = T, s->nb = NBLK(T);
    s->blk = malloc(3 * (size_t)n * (size_t)s->nb * sizeof *s->blk);
    s->seen = malloc((size_t)s->nb);
    s->bd = malloc((size_t)s->nb * sizeof *s->bd);
    s->pts = malloc(2 * (size_t)n * (size_t)T * sizeof *s->pts);
    s->circ = malloc(4 * (size_t)n * sizeof *s->circ);
    s->f2 = malloc((size_t)T * sizeof *s->f2);
    if (!s->pts || !s->circ || !s->f2 || !s->blk || !s->seen || !s->bd)
        return -1;
    for (int k = 0; k < n; k++)
        cs_fill(s, k);
    return 0;
}

static double dist_at(const cset *s, int k, double u, const double q[2])
{
    double p[2];
    cs_point(s, k, u, p);
    return hypot(q[0] - p[0], q[1] - p[1]);
}

/* Golden-section minimum of |q - curve k (u)| over [lo, hi]; *ub where. */
static double golden_min(const cset *s, int k, const double q[2], double lo, double hi, double *ub)
{
    const double g = 0.6180339887498949;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = dist_at(s, k, x1, q), f2 = dist_at(s, k, x2, q);
    for (int it = 0; it < 80 && hi - lo > 1e-15; it++) {
        if (f1 < f2)
            hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = dist_at(s, k, x1, q);
        else
            lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = dist_at(s, k, x2, q);
    }
    *ub = f1 < f2 ? x1 : x2;
    return fmin(f1, f2);
}

/* The foot of q on curve k from u by Gauss-Newton steps
 * u -= (P - q).P' / |P'|^2 inside [lo, hi]; 1 with *ub and the distance
 * when the step fell below 1e-15, 0 when it did not within 12 steps. */
static int gauss_newton(const cset *s, int k, const double q[2], double u, double lo, double hi, double *ub, double *e)
{
    for (int it = 0; it < 12; it++) {
        double p[2], dp[2];
        cs_point_d(s, k, u, p, dp);
        const double n2 = dp[0] * dp[0] + dp[1] * dp[1];
        if (!(n2 > 0.0))
            return 0;
        const double step = ((p[0] - q[0]) * dp[0] + (p[1] - q[1]) * dp[1]) / n2, v = fmin(fmax(u - step, lo), hi);
        /* settled: a step below 1e-15, or below what the points' round-off
         * moves u by (a short curve's small |P'| magnifies it: its steps
         * would wander there and golden section take over) */
        const double noise = 8.0 * DBL_EPSILON * (fabs(p[0]) + fabs(p[1]) + fabs(q[0]) + fabs(q[1])) / sqrt(n2);
        if (fabs(v - u) <= fmax(1e-15, noise) || (v == u)) {
            *ub = v, *e = dist_at(s, k, v, q);
            return 1;
        }
        u = v;
    }
    return 0;
}

/* The squared distances from q to the samples of the blocks of curve k
 * that can hold a sample within h of the nearest (into s->f2, the blocks
 * marked in s->seen); the nearest sample's index and squared distance. */
static int scan_blocks(const cset *s, int k, const double q[2], double h, double *m2)
{
    const double *P = s->pts + 2 * (size_t)k * s->T, *B = s->blk + 3 * (size_t)k * s->nb;
    double U = INFINITY;
    int i0 = 0;
    *m2 = INFINITY;
    for (int b = 0; b < s->nb; b++) { /* the nearest sample is at most U away */
        const double dx = q[0] - B[3 * b], dy = q[1] - B[3 * b + 1];
        s->bd[b] = sqrt(dx * dx + dy * dy); /* no hypot: a hot loop, coordinates far from overflow */
        U = fmin(U, s->bd[b] + B[3 * b + 2]);
    }
    for (int b = 0; b < s->nb; b++) {
        s->seen[b] = s->bd[b] - B[3 * b + 2] <= U + h;
        if (!s->seen[b])
            continue;
        const int i1 = (b + 1) * BLK < s->T - 1 ? (b + 1) * BLK : s->T - 1;
        for (int i = b * BLK; i <= i1; i++) {
            const double dx = q[0] - P[2 * i], dy = q[1] - P[2 * i + 1];
            s->f2[i] = dx * dx + dy * dy;
            if (s->f2[i] < *m2)
                *m2 = s->f2[i], i0 = i;
        }
    }
    return i0;
}

/* The squared distance of sample i as scanned, or infinity. */
static double f2_at(const cset *s, int i)
{
    if (i < 0 || i >= s->T)
        return INFINITY;
    const int b = i / BLK, b1 = i == 0 ? 0 : (i - 1) / BLK; /* a block's last sample is the next one's first */
    return s->seen[b < s->nb ? b : s->nb - 1] || s->seen[b1] ? s->f2[i] : INFINITY;
}

/* The distance from q to curve k: its nearest sample, and every local
 * minimum of the samples within a chord of it, refined; a value > cut
 * when it is (then not refined). */
static double curve_dist(const cset *s, int k, const double q[2], double cut, double *uf)
{
    const double h = s->circ[4 * (size_t)k + 3];
    double m2;
    const int i0 = scan_blocks(s, k, q, h, &m2);
    double best = sqrt(m2);
    *uf = sample_u(s, i0);
    if (best - h > cut)
        return best;
    const double lim = (fmin(best, cut) + h) * (fmin(best, cut) + h);
    for (int b = 0; b < s->nb; b++) {
        if (!s->seen[b])
            continue;
        const int i1 = (b + 1) * BLK < s->T - 1 ? (b + 1) * BLK : s->T - 1;
        for (int i = b * BLK; i <= i1; i++) {
            const double f = s->f2[i];
            if (!(f <= lim && f <= f2_at(s, i - 1) && f <= f2_at(s, i + 1)))
                continue;
            double u, e;
            const double lo = sample_u(s, i > 0 ? i - 1 : 0), hi = sample_u(s, i < s->T - 1 ? i + 1 : i);
            if (!gauss_newton(s, k, q, sample_u(s, i), lo, hi, &u, &e))
                e = golden_min(s, k, q, lo, hi, &u);
            if (e < best)
                best = e, *uf = u;
        }
    }
    return best;
}

/* The distance from q to the whole set s: curves whose circles can hold
 * a nearer point, the one of *kf (the last query's) first. */
static double set_dist(const cset *s, const double q[2], int *kf, double *uf)
{
    double u, best = curve_dist(s, *kf, q, INFINITY, uf);
    const int k0 = *kf;
    for (int k = 0; k < s->n; k++) {
        const double *o = s->circ + 4 * (size_t)k;
        const double dx = q[0] - o[0], dy = q[1] - o[1];
        if (k == k0 || !(sqrt(dx * dx + dy * dy) - o[2] < best))
            continue;
        const double e = curve_dist(s, k, q, best, &u);
        if (e < best)
            best = e, *kf = k, *uf = u;
    }
    return best;
}

/* The distance from curve k of side Q at u to side G. */
static double query_dist(const cset *Q, const cset *G, int k, double u, int *kf, double *uf)
{
    double p[2];
    cs_point(Q, k, u, p);
    return set_dist(G, p, kf, uf);
}

/* Golden-section maximum of query_dist over [lo, hi]; *ub where. */
static double golden_max(const cset *Q, const cset *G, int k, double lo, double hi, int *kf, double *ub)
{
    const double g = 0.6180339887498949;
    double uf, x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = query_dist(Q, G, k, x1, kf, &uf), f2 = query_dist(Q, G, k, x2, kf, &uf);
    for (int it = 0; it < 60 && hi - lo > 1e-10; it++) { /* at a maximum: the distance to 1e-20 relative */
        if (f1 > f2)
            hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = query_dist(Q, G, k, x1, kf, &uf);
        else
            lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = query_dist(Q, G, k, x2, kf, &uf);
    }
    *ub = f1 > f2 ? x1 : x2;
    return fmax(f1, f2);
}

/* The largest distance from side Q to side G: every sample, the largest
 * of each curve refined; *kq, *uq where. */
static double side_max(const cset *Q, const cset *G, int *kq, double *uq)
{
    double best = -1.0, uf;
    int kf = 0;
    for (int k = 0; k < Q->n; k++) {
        const double *P = Q->pts + 2 * (size_t)k * Q->T;
        double ek = -1.0;
        int ik = 0;
        for (int i = 0; i < Q->T; i++) {
            const double e = set_dist(G, P + 2 * i, &kf, &uf);
            if (!(e <= ek))
                ek = e, ik = i;
        }
        double u = sample_u(Q, ik);
        const double er = golden_max(Q, G, k, sample_u(Q, ik > 0 ? ik - 1 : 0),
                                     sample_u(Q, ik < Q->T - 1 ? ik + 1 : ik), &kf, &uf);
        if (er > ek)
            ek = er, u = uf;
        if (!(ek <= best))
            best = ek, *kq = k, *uq = u;
    }
    return best;
}

static void cs_free(cset *s)
{
    free(s->pts);
    free(s->circ);
    free(s->f2);
    free(s->blk);
    free(s->seen);
    free(s->bd);
}

/* Fills r and msg for the worst place: curve k of side Q at u. */
static void locate(const cset *Q, const cset *G, int k, double u, double e, ob_mres *r, char *msg, size_t len)
{
    double p[2], uf;
    int kf = 0;
    cs_point(Q, k, u, p);
    set_dist(G, p, &kf, &uf);
    const cset *arcs = Q->side == SIDE_TRIM ? Q : G;
    const int ka = Q->side == SIDE_TRIM ? k : kf;
    const double ua = Q->side == SIDE_TRIM ? u : uf;
    const ob_trim_arc *ar = &arcs->tr->arc[ka];
    r->err = e;
    r->piece = ob_approx_file_piece(Q->a ? Q->a : G->a, Q->side == SIDE_FILE ? k : kf);
    r->seg = ar->seg;
    r->t = ar->corner ? 0.0 : ar->t0 + (ar->t1 - ar->t0) * ua; /* a corner arc's points are the corner's */
    snprintf(msg, len, Q->side == SIDE_FILE ? "the farthest point of the approximation from the trimmed offset, at "
                                              "(%.9g, %.9g)"
                                            : "the farthest point of the trimmed offset from the approximation, at "
                                              "(%.9g, %.9g)",
             p[0], p[1]);
    r->note = msg;
}

int ob_trimmed_hausdorff(const ob_curve *c, double d, const ob_trim *tr, const ob_approx *a, int samples,
                         ob_mres *r, char *msg, size_t len, ob_err *err)
{
    *r = (ob_mres){1, "", 0.0, -1, -1, NAN, 0, ""};
    msg[0] = '\0';
    if (tr->n == 0)
        return ob_fail(err, "trimmed-hausdorff: the trimmed offset is empty: every point of C + dN comes nearer "
                       "than |d| to curve %s", c->id);
    if (a->n == 0)
        return ob_fail(err, "trimmed-hausdorff: no pieces");
    const int S = ob_clamp_samples(samples);
    cset F = {0}, A = {0};
    F.a = a, A.tr = tr, A.c = c, A.d = d;
    if (cs_init(&F, SIDE_FILE, a->n, S) || cs_init(&A, SIDE_TRIM, tr->n, S > ARC_SAMPLES_MIN ? S : ARC_SAMPLES_MIN)) {
        cs_free(&F), cs_free(&A);
        return ob_fail(err, "trimmed-hausdorff: out of memory (%d pieces, %d samples)", a->n, S);
    }
    int kf = 0, ka = 0;
    double uf = 0.0, ua = 0.0;
    const double ef = side_max(&F, &A, &kf, &uf);
    const double et = ob_stop_signal() ? NAN : side_max(&A, &F, &ka, &ua);
    if (ob_stop_signal()) {
        cs_free(&F), cs_free(&A);
        return ob_fail(err, "trimmed-hausdorff: stopped by signal %d", ob_stop_signal());
    }
    if (ef >= et)
        locate(&F, &A, kf, uf, ef, r, msg, len);
    else
        locate(&A, &F, ka, ua, et, r, msg, len);
    r->ok = ob_err_can_pass(r->err);
    if (!r->ok)
        r->why = "the distance is not finite: a piece that cannot be evaluated (a pole or a weight <= 0 of a rational "
                 "piece?)";
    cs_free(&F), cs_free(&A);
    return 0;
}

int ob_measure_trimmed(const ob_curve *c, double d, const ob_approx *a, int samples, const char *dump, ob_mres *r,
                       char *msg, size_t len, ob_err *err)
{
    ob_trim tr;
    if (ob_trim_offset(c, d, &tr, err) != 0) {
        ob_trim_free(&tr);
        return -1;
    }
    if (dump) {
        FILE *f = fopen(dump, "w");
        const int bad = !f || ob_trim_dump(f, c, d, &tr) != 0;
        if ((f && fclose(f) != 0) || bad) {
            ob_trim_free(&tr);
            return ob_fail(err, "--trim-dump: cannot write %s", dump);
        }
    }
    const int rc = ob_trimmed_hausdorff(c, d, &tr, a, samples, r, msg, len, err);
    ob_trim_free(&tr);
    return rc;
}
