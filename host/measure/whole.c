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
 * tables of every piece and of every tile of the offset (kept in a bounded
 * cache), and for a query point the nearest foot on one target by
 * obc_side_dist.  Here a query asks its own target first (the piece's own
 * tile, or the tile's own piece), then every other target whose bounding
 * circle comes nearer than the best so far, nearest circles first (a grid
 * of the circles lists those that can).  Each piece (tile) is scanned at its S
 * samples, every 8th first, each sample asked only for distances above the
 * running maximum (the cut: a target that settles under it ends the query),
 * and its largest sample refined by golden section, as the metric does.
 */
#include "host/measure/measure.h"
#include "host/run/signals.h"

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

/* The targets' circles in a uniform grid (CSR: cell i holds
 * items[start[i] .. start[i + 1])); each circle in every cell its box
 * meets; circles of no finite size, or over many cells, in `always`. */
typedef struct {
    double x0, y0, h;
    int nx, ny;
    int *start, *items, *always, nalways;
} grid;

enum { SIDE_A = 0, SIDE_O = 1 }; /* queries on the approximation / on the offset */

/* Bytes of sample tables kept per side (64 MiB: 3,900 pieces at the
 * default 256 samples); past it the tables are recomputed as needed. */
#define CACHE_BYTES ((size_t)64 << 20)

typedef struct {
    const ob_approx *a;
    int n, S;
    double d;
    ob_bez *tile;        /* the offset's base pieces, one per piece */
    double *tab[2];      /* table caches: [SIDE_A] of the pieces, [SIDE_O] of the offset's tiles */
    int *held[2];        /* per slot of a cache: the piece (tile) whose table it holds, or -1 */
    int slots;           /* tables per cache */
    circle *circ[2];     /* their bounding circles */
    grid grid[2];        /* of circ[0] and circ[1] */
    cand *cands;         /* the other targets of the current query piece, nearest circle first */
    int ncand;
    int *stamp;          /* per target: the last candidates() call that listed it */
    int gen;             /* candidates() calls so far */
} whole;

/* The sample table of piece (side SIDE_A) or tile (SIDE_O) k into T. */
static void fill(const whole *w, int side, int k, double *T)
{
    long ops = 0;
    const ob_bez *b = side == SIDE_A ? &w->a->v[k].approx : &w->tile[k];
    obc_fill_table(&b->h[0][0], b->deg, side == SIDE_A ? 0.0 : w->d, w->S, T, &ops);
}

/* The table of piece (tile) k: from its side's cache, a direct-mapped one
 * (slot k mod slots), filled when the slot holds another.  A query uses
 * one table of each side at a time, and the pieces it asks lie near it. */
static const double *table(const whole *w, int side, int k)
{
    const int slot = k % w->slots;
    double *T = w->tab[side] + (size_t)slot * OBC_TABLE_SIZE(w->S);
    if (w->held[side][slot] != k) {
        fill(w, side, k, T);
        w->held[side][slot] = k;
    }
    return T;
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

static int cmp_double(const void *x, const void *y)
{
    const double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* The cells [*a, *b] that the interval [lo, hi] meets along one axis. */
static void cell_range(double lo, double hi, double x0, double h, int n, int *a, int *b)
{
    const double fa = floor((lo - x0) / h), fb = floor((hi - x0) / h);
    *a = fa < 0 ? 0 : fa > n - 1 ? n - 1 : (int)fa;
    *b = fb < 0 ? 0 : fb > n - 1 ? n - 1 : (int)fb;
}

/* The cells that circle c's box meets: [*ia, *ib] x [*ja, *jb]; how many. */
static long grid_box(const grid *g, const circle *c, int *ia, int *ib, int *ja, int *jb)
{
    cell_range(c->x - c->r, c->x + c->r, g->x0, g->h, g->nx, ia, ib);
    cell_range(c->y - c->r, c->y + c->r, g->y0, g->h, g->ny, ja, jb);
    return (long)(*ib - *ia + 1) * (*jb - *ja + 1);
}

/* Files circle j in the cells its box meets (fill 1), or counts them. */
static void grid_visit(grid *g, const circle *c, int j, int fill)
{
    int ia, ib, ja, jb;
    grid_box(g, c, &ia, &ib, &ja, &jb);
    for (int y = ja; y <= jb; y++)
        for (int x = ia; x <= ib; x++) {
            const int cell = y * g->nx + x;
            if (fill)
                g->items[g->start[cell]++] = j;
            else
                g->start[cell + 1]++;
        }
}

/* 1 when circle c goes in the cells: of finite size, and over at most
 * GRID_SPREAD of them (a larger one is listed for every query instead, so
 * that the grid holds at most GRID_SPREAD n entries). */
enum { GRID_SPREAD = 64 };
static int in_cells(const grid *g, const circle *c)
{
    int ia, ib, ja, jb;
    return isfinite(c->r) && grid_box(g, c, &ia, &ib, &ja, &jb) <= GRID_SPREAD;
}

/* The grid of n circles: cells about the size of a circle (twice the
 * median radius), at most 4 n + 16 of them.  0, or -1 out of memory. */
static int grid_build(grid *g, const circle *c, int n)
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    double *r = malloc((size_t)(n > 0 ? n : 1) * sizeof *r);
    int nr = 0;
    g->always = malloc((size_t)(n > 0 ? n : 1) * sizeof *g->always);
    if (!r || !g->always) {
        free(r);
        return -1;
    }
    for (int j = 0; j < n; j++)
        if (isfinite(c[j].r)) {
            x0 = fmin(x0, c[j].x), x1 = fmax(x1, c[j].x), y0 = fmin(y0, c[j].y), y1 = fmax(y1, c[j].y);
            r[nr++] = c[j].r;
        }
    qsort(r, (size_t)nr, sizeof *r, cmp_double);
    double h = nr ? 2.0 * r[nr / 2] : 0.0; /* twice the median radius */
    free(r);
    const double w = nr ? fmax(x1 - x0, y1 - y0) : 0.0;
    h = fmax(h, fmax(w / 4096.0, 1e-300)); /* at most 4097 cells a side */
    g->x0 = nr ? x0 : 0.0, g->y0 = nr ? y0 : 0.0;
    for (;; h *= 2.0) { /* at most 4 n + 16 cells */
        g->nx = nr ? (int)((x1 - x0) / h) + 1 : 1;
        g->ny = nr ? (int)((y1 - y0) / h) + 1 : 1;
        if ((double)g->nx * g->ny <= 4.0 * n + 16.0)
            break;
    }
    g->h = h;
    const int cells = g->nx * g->ny;
    if (!(g->start = calloc((size_t)cells + 1, sizeof *g->start)))
        return -1;
    for (int j = 0; j < n; j++) {
        if (in_cells(g, &c[j]))
            grid_visit(g, &c[j], j, 0);
        else
            g->always[g->nalways++] = j;
    }
    for (int i = 0; i < cells; i++)
        g->start[i + 1] += g->start[i];
    if (!(g->items = malloc((size_t)(g->start[cells] > 0 ? g->start[cells] : 1) * sizeof *g->items)))
        return -1;
    for (int j = 0; j < n; j++)
        if (in_cells(g, &c[j]))
            grid_visit(g, &c[j], j, 1);
    for (int i = cells; i > 0; i--) /* filing moved each start to the next cell's */
        g->start[i] = g->start[i - 1];
    g->start[0] = 0;
    return 0;
}

static void grid_free(grid *g)
{
    free(g->start);
    free(g->items);
    free(g->always);
}

/* Target j as a candidate of query circle q, if it can be nearer than ub. */
static void consider(whole *w, int s, int k, int j, const circle *q, double ub)
{
    if (j == k || w->stamp[j] == w->gen)
        return;
    w->stamp[j] = w->gen;
    const circle *t = &w->circ[!s][j];
    const double lb = hypot(q->x - t->x, q->y - t->y) - q->r - t->r;
    if (!(lb >= ub))
        w->cands[w->ncand++] = (cand){j, lb};
}

/* The other targets of query piece k (side s) whose circles can come
 * nearer to its circle than its own target's farthest reach, nearest
 * first. */
static void candidates(whole *w, int s, int k)
{
    const circle *q = &w->circ[s][k], *o = &w->circ[!s][k];
    const grid *g = &w->grid[!s];
    const double ub = hypot(q->x - o->x, q->y - o->y) + q->r + o->r, reach = ub + q->r;
    w->ncand = 0;
    w->gen++;
    for (int i = 0; i < g->nalways; i++)
        consider(w, s, k, g->always[i], q, ub);
    if (isfinite(reach)) {
        int ia, ib, ja, jb;
        cell_range(q->x - reach, q->x + reach, g->x0, g->h, g->nx, &ia, &ib);
        cell_range(q->y - reach, q->y + reach, g->y0, g->h, g->ny, &ja, &jb);
        for (int y = ja; y <= jb; y++)
            for (int x = ia; x <= ib; x++)
                for (int i = g->start[y * g->nx + x]; i < g->start[y * g->nx + x + 1]; i++)
                    consider(w, s, k, g->items[i], q, ub);
    } else {
        for (int j = 0; j < w->n; j++)
            consider(w, s, k, j, q, ub);
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
 * the circles of every table. */
static void prepare(whole *w, const ob_curve *c, const ob_cover *cv)
{
    for (int k = 0; k < w->n; k++) {
        const ob_apiece *p = &w->a->v[k];
        if (p->matched || cv->lo[k] != ob_apiece_base_t(p, 0.0) || cv->hi[k] != ob_apiece_base_t(p, 1.0) ||
            ob_apiece_base(c, p, &w->tile[k]) != 0)
            ob_bez_subsegment(&c->seg[p->seg], cv->lo[k], cv->hi[k], &w->tile[k]);
        for (int s = 0; s < 2; s++)
            w->circ[s][k] = circle_of(table(w, s, k), w->S);
    }
}

static void whole_free(whole *w)
{
    free(w->tile);
    for (int s = 0; s < 2; s++) {
        free(w->tab[s]);
        free(w->held[s]);
    }
    free(w->circ[0]);
    free(w->circ[1]);
    grid_free(&w->grid[0]);
    grid_free(&w->grid[1]);
    free(w->cands);
    free(w->stamp);
}

int ob_approx_hausdorff_whole(const ob_curve *c, double d, const ob_approx *a, const ob_cover *cv, int samples,
                              ob_mres *r, ob_err *err)
{
    *r = (ob_mres){1, "", 0.0, -1, -1, NAN, 0, ""};
    const size_t n = a->n > 0 ? (size_t)a->n : 1, S = (size_t)ob_clamp_samples(samples);
    whole w;
    memset(&w, 0, sizeof w);
    w.a = a, w.n = a->n, w.S = (int)S, w.d = d;
    w.tile = malloc(n * sizeof *w.tile);
    w.cands = malloc(n * sizeof *w.cands);
    w.stamp = calloc(n, sizeof *w.stamp);
    /* tables kept per side: all of them up to CACHE_BYTES */
    const size_t fit = CACHE_BYTES / (OBC_TABLE_SIZE(S) * sizeof(double));
    w.slots = (int)(n < fit ? n : fit > 8 ? fit : 8);
    for (int s = 0; s < 2; s++) {
        w.tab[s] = malloc((size_t)w.slots * OBC_TABLE_SIZE(S) * sizeof *w.tab[s]);
        w.held[s] = malloc((size_t)w.slots * sizeof *w.held[s]);
        for (int i = 0; w.held[s] && i < w.slots; i++)
            w.held[s][i] = -1;
        w.circ[s] = malloc(n * sizeof *w.circ[s]);
    }
    if (!w.tile || !w.cands || !w.stamp || !w.tab[0] || !w.tab[1] || !w.held[0] || !w.held[1] || !w.circ[0] ||
        !w.circ[1]) {
        whole_free(&w);
        return ob_fail(err, "hausdorff-whole: out of memory (%d pieces, %d samples)", a->n, (int)S);
    }
    prepare(&w, c, cv);
    if (grid_build(&w.grid[0], w.circ[0], w.n) != 0 || grid_build(&w.grid[1], w.circ[1], w.n) != 0) {
        whole_free(&w);
        return ob_fail(err, "hausdorff-whole: out of memory (%d pieces)", a->n);
    }
    double best = -1.0, ubest = 0.0;
    int sbest = SIDE_A, kbest = 0;
    for (int s = 0; s < 2; s++)
        for (int k = 0; k < w.n; k++) {
            if (ob_stop_signal()) { /* a long loop polls the stop (signals.h) */
                whole_free(&w);
                return ob_fail(err, "hausdorff-whole: stopped by signal %d", ob_stop_signal());
            }
            double u;
            const double e = piece_max(&w, s, k, &u);
            if (!(e <= best))
                best = e, ubest = u, sbest = s, kbest = k;
        }
    r->err = best;
    r->piece = ob_approx_file_piece(a, kbest);  /* the file's number of the piece */
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
    r->ok = ob_err_can_pass(r->err);  /* a distance that is not finite is never ok */
    if (!r->ok)
        r->why = "the distance is not finite: a piece the metric cannot bound (a pole or a weight <= 0 of a "
                 "rational piece?)";
    whole_free(&w);
    return 0;
}
