/*
 * whole.c - the two-sided Hausdorff distance between a whole approximation
 * and the whole exact offset (measure.h, ob_approx_hausdorff_whole).
 *
 * Why not the hausdorff metric's maximum over the pieces: that measures
 * each piece against its own base piece only, so it is blind to what the
 * pieces leave out or cover twice (the coverage check is, see cover.c), and
 * it counts a point of a piece that lies nearer to a neighbour's part of
 * the offset at its distance from its own part: the per-piece maximum is an
 * upper bound of the whole's distance, not the distance.
 *
 * The engine is the hausdorff metric's (kernels/metric_core.h): sample
 * tables of every piece and of every tile of the offset, and for a query
 * point the nearest foot on one target by obc_side_dist.  Here a query asks
 * its own target first (the piece's own tile, or the tile's own piece), then
 * every other target whose bounding circle comes nearer than the best so
 * far, nearest circles first.  Each piece (tile) is scanned at its S
 * samples, every 8th first, each sample asked only for distances above the
 * running maximum (the cut: a target that settles under it ends the query),
 * and its largest sample refined by golden section, as the metric does.
 */
#include "host/measure/measure.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernels/metric_core.h"

typedef struct {
    double x, y, r;
} circle;

typedef struct {
    int j;
    double lb;
} cand;

enum { SIDE_A = 0, SIDE_O = 1 }; /* queries on the approximation / on the offset */

typedef struct {
    const ob_approx *a;
    int n, S;
    double d;
    ob_bez *tile;        /* the offset's base pieces, one per piece */
    double *tab[2];      /* tables: [SIDE_A] of the pieces, [SIDE_O] of the offset's tiles */
    circle *circ[2];     /* their bounding circles */
    cand *cands;         /* the other targets of the current query piece, nearest circle first */
    int ncand;
} whole;

static double *table(const whole *w, int side, int k)
{
    return w->tab[side] + (size_t)k * OBC_TABLE_SIZE(w->S);
}

/* The circle that holds every block circle of table T. */
static circle circle_of(const double *T, int S)
{
    const double *c = T + OBC_REC * S;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int b = 0; b < OBC_NBLK(S); b++) {
        x0 = fmin(x0, c[4 * b] - c[4 * b + 2]), x1 = fmax(x1, c[4 * b] + c[4 * b + 2]);
        y0 = fmin(y0, c[4 * b + 1] - c[4 * b + 2]), y1 = fmax(y1, c[4 * b + 1] + c[4 * b + 2]);
    }
    circle o = {0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0};
    for (int b = 0; b < OBC_NBLK(S); b++)
        o.r = fmax(o.r, hypot(c[4 * b] - o.x, c[4 * b + 1] - o.y) + c[4 * b + 2]);
    if (!isfinite(o.r))
        o = (circle){0.0, 0.0, INFINITY};
    return o;
}

/* Distance from the point of query piece k (side s) at u (sample i when
 * i >= 0) to target j of the other side; a value <= cut when it is <= cut
 * (obc_side_dist). */
static double side_dist(const whole *w, int s, int k, int j, double u, int i, double cut, int *hint, double *tf)
{
    long ops = 0;
    const int q = s == SIDE_A ? k : j, o = s == SIDE_A ? j : k; /* the piece and the tile */
    const ob_bez *A = &w->a->v[q].approx, *B = &w->tile[o];
    return obc_side_dist(s == SIDE_A ? OBC_K_H_APPROX : OBC_K_H_OFFSET, &B->h[0][0], B->deg, &A->h[0][0], A->deg,
                         w->d, w->S, table(w, !s, j), table(w, s, k), &ops, u, i, cut, hint, tf);
}

/* The query point of piece k (side s) at u (sample i when i >= 0). */
static void query_point(const whole *w, int s, int k, double u, int i, double Q[2])
{
    if (i >= 0) {
        const double *r = table(w, s, k) + OBC_REC * i;
        Q[0] = r[0], Q[1] = r[1];
        return;
    }
    double dQ[2], K[2];
    long ops = 0;
    const ob_bez *b = s == SIDE_A ? &w->a->v[k].approx : &w->tile[k];
    obc_pc_eval(&b->h[0][0], b->deg, s == SIDE_A ? 0.0 : w->d, u, Q, dQ, K, &ops);
}

/* Distance from the point of query piece k (side s) at u to the whole
 * other side, or a value <= cut when it is <= cut; *jf, *tf: the target
 * and parameter of the foot (when above the cut). */
static double whole_dist(const whole *w, int s, int k, double u, int i, double cut, int *hint, int *jf, double *tf)
{
    double t, best = side_dist(w, s, k, k, u, i, cut, hint, &t), Q[2];
    *jf = k, *tf = t;
    if (best <= cut || w->ncand == 0)
        return best;
    query_point(w, s, k, u, i, Q);
    for (int c = 0; c < w->ncand && w->cands[c].lb < best; c++) {
        const int j = w->cands[c].j;
        const circle *cj = &w->circ[!s][j];
        if (!(hypot(Q[0] - cj->x, Q[1] - cj->y) - cj->r < best))
            continue;
        int h = OBC_NO_HINT;
        const double e = side_dist(w, s, k, j, u, i, cut, &h, &t);
        if (e < best)
            best = e, *jf = j, *tf = t;
        if (best <= cut)
            break;
    }
    return best;
}

static int cmp_cand(const void *x, const void *y)
{
    const cand *p = x, *q = y;
    return p->lb < q->lb ? -1 : p->lb > q->lb ? 1 : (p->j > q->j) - (p->j < q->j);
}

/* The other targets of query piece k (side s), by how near their circles
 * can come to its circle. */
static void candidates(whole *w, int s, int k)
{
    const circle *q = &w->circ[s][k];
    w->ncand = 0;
    for (int j = 0; j < w->n; j++)
        if (j != k) {
            const circle *t = &w->circ[!s][j];
            w->cands[w->ncand++] = (cand){j, hypot(q->x - t->x, q->y - t->y) - q->r - t->r};
        }
    qsort(w->cands, (size_t)w->ncand, sizeof *w->cands, cmp_cand);
}

/* Golden-section maximum of the distance on [lo, hi] of query piece k (as
 * obc_golden_max: a point that loses is asked only above the kept value). */
static double golden_max(const whole *w, int s, int k, double lo, double hi, int *hint, double *targ)
{
    const double g = 0.6180339887498949;
    int jf;
    double tf, x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = whole_dist(w, s, k, x1, -1, -1.0, hint, &jf, &tf), f2 = whole_dist(w, s, k, x2, -1, -1.0, hint, &jf, &tf);
    for (int it = 0; it < 40 && hi - lo > 1e-13; it++) {
        if (f1 > f2) {
            hi = x2, x2 = x1, f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = whole_dist(w, s, k, x1, -1, f2, hint, &jf, &tf);
        } else {
            lo = x1, x1 = x2, f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = whole_dist(w, s, k, x2, -1, f1 - fabs(f1) * 0x1p-51, hint, &jf, &tf);
        }
    }
    *targ = f1 > f2 ? x1 : x2;
    return f1 > f2 ? f1 : f2;
}

/* The largest distance from query piece k (side s) to the other whole, and
 * the piece's parameter where it is. */
static double piece_max(whole *w, int s, int k, double *umax)
{
    candidates(w, s, k);
    const int S = w->S, step = 8;
    double best = -1.0, tf;
    int kb = 0, hint = OBC_NO_HINT, jf;
    for (int pass = 0; pass < 2; pass++)
        for (int i = pass ? 1 : 0; i < S; i += pass ? 1 : step) {
            if (pass && i % step == 0)
                continue;
            const double e = whole_dist(w, s, k, obc_sample_t(i, S), i, best, &hint, &jf, &tf);
            if (!(e <= best))
                best = e, kb = i;
            if (isnan(e) || isinf(e)) {
                *umax = obc_sample_t(kb, S);
                return INFINITY;
            }
        }
    double ur;
    const double er = golden_max(w, s, k, obc_sample_t(kb > 0 ? kb - 1 : 0, S),
                                 obc_sample_t(kb < S - 1 ? kb + 1 : S - 1, S), &hint, &ur);
    *umax = er > best ? ur : obc_sample_t(kb, S);
    return er > best ? er : best;
}

/* The base parameter of tile k at its parameter t. */
static double tile_t(const whole *w, const ob_cover *cv, int k, double t)
{
    const ob_apiece *p = &w->a->v[k];
    if (!p->matched && cv->lo[k] == ob_apiece_base_t(p, 0.0) && cv->hi[k] == ob_apiece_base_t(p, 1.0))
        return p->a + (p->b - p->a) * (p->t0 + (p->t1 - p->t0) * t);
    return cv->lo[k] + (cv->hi[k] - cv->lo[k]) * t;
}

/* The tiles (a read link's own base piece where its tile is its range) and
 * every table and circle. */
static void prepare(whole *w, const ob_curve *c, const ob_cover *cv)
{
    long ops = 0;
    for (int k = 0; k < w->n; k++) {
        const ob_apiece *p = &w->a->v[k];
        if (p->matched || cv->lo[k] != ob_apiece_base_t(p, 0.0) || cv->hi[k] != ob_apiece_base_t(p, 1.0) ||
            ob_apiece_base(c, p, &w->tile[k]) != 0)
            ob_bez_subsegment(&c->seg[p->seg], cv->lo[k], cv->hi[k], &w->tile[k]);
        obc_fill_table(&p->approx.h[0][0], p->approx.deg, 0.0, w->S, table(w, SIDE_A, k), &ops);
        obc_fill_table(&w->tile[k].h[0][0], w->tile[k].deg, w->d, w->S, table(w, SIDE_O, k), &ops);
        w->circ[SIDE_A][k] = circle_of(table(w, SIDE_A, k), w->S);
        w->circ[SIDE_O][k] = circle_of(table(w, SIDE_O, k), w->S);
    }
}

static void whole_free(whole *w)
{
    free(w->tile);
    free(w->tab[0]);
    free(w->tab[1]);
    free(w->circ[0]);
    free(w->circ[1]);
    free(w->cands);
}

int ob_approx_hausdorff_whole(const ob_curve *c, double d, const ob_approx *a, const ob_cover *cv, int samples,
                              ob_mres *r, ob_err *err)
{
    *r = (ob_mres){1, "", 0.0, -1, -1, NAN, ""};
    const size_t n = a->n > 0 ? (size_t)a->n : 1, S = (size_t)ob_clamp_samples(samples);
    whole w = {a, a->n, (int)S, d, NULL, {NULL, NULL}, {NULL, NULL}, NULL, 0};
    w.tile = malloc(n * sizeof *w.tile);
    w.cands = malloc(n * sizeof *w.cands);
    for (int s = 0; s < 2; s++) {
        w.tab[s] = malloc(n * OBC_TABLE_SIZE(S) * sizeof *w.tab[s]);
        w.circ[s] = malloc(n * sizeof *w.circ[s]);
    }
    if (!w.tile || !w.cands || !w.tab[0] || !w.tab[1] || !w.circ[0] || !w.circ[1]) {
        whole_free(&w);
        return ob_fail(err, "hausdorff-whole: out of memory (%d pieces, %d samples)", a->n, (int)S);
    }
    prepare(&w, c, cv);
    double best = -1.0, ubest = 0.0;
    int sbest = SIDE_A, kbest = 0;
    for (int s = 0; s < 2; s++)
        for (int k = 0; k < w.n; k++) {
            double u;
            const double e = piece_max(&w, s, k, &u);
            if (!(e <= best))
                best = e, ubest = u, sbest = s, kbest = k;
        }
    r->err = best;
    r->piece = kbest;
    if (sbest == SIDE_A) { /* where: the nearest offset point to the farthest point of the pieces */
        int hint = OBC_NO_HINT, jf;
        double tf;
        candidates(&w, SIDE_A, kbest);
        whole_dist(&w, SIDE_A, kbest, ubest, -1, -1.0, &hint, &jf, &tf);
        r->seg = a->v[jf].seg;
        r->t = tile_t(&w, cv, jf, tf);
        r->note = "the farthest point of the approximation from the offset";
    } else {
        r->seg = a->v[kbest].seg;
        r->t = tile_t(&w, cv, kbest, ubest);
        r->note = "the farthest point of the offset from the approximation";
    }
    whole_free(&w);
    return 0;
}
