/*
 * metric_certified.c - the certified two-sided Hausdorff enclosure: the
 * search (feet, branch and bound) around the enclosures of cert_bounds.c.
 * Method and contract in metric_certified.h.
 */
#include "methods/metrics/metric_certified.h"

#include <stdlib.h>

#include "methods/metrics/cert_bounds.h"
#include "methods/metrics/cert_feet.h"
#include "methods/metrics/cert_heap.h"
#include "methods/metrics/cert_job.h"
#include "methods/metrics/metric.h"

enum { LOWER_ROOTS = 16, PROBE_EVERY = 16 };
enum { LOWER_BUDGET = 4000 };  /* interval bounds per certified point */
enum { CANCEL_EVERY = 64 };    /* search steps between two calls of the cancel hook */
#define MIN_WIDTH 1e-13  /* intervals narrower than this are not split */
#define THIRD_FLOORS 1e4  /* the third-order form below this many round-off floors (leaf_bound) */

/* One one-sided distance: points of P, their distance to Q. */
typedef struct {
    ob_cv P, Q;
    int S;
    double (*tab)[2];              /* Q at the S sample parameters */
    double *foot, *dist, *slope;   /* the feet of P's samples on Q (cert_feet.h) */
    ob_cert_heap heap;             /* intervals of P's parameter, largest bound first */
} side_t;

/* The whole certificate's state. */
typedef struct {
    side_t side[2];
    ob_cert_opts o;
    double floor;
    double stop;      /* a bound already certified elsewhere (cert_job.h): no need to refine below it */
    long upper_work;  /* upper enclosures so far: what the budget limits */
    long cancel_tick;
    ob_certified *out;
} cert_t;

/* verdict mode (ob_cert_opts.verdict): only whether H <= decide is asked */
static int verdict(const cert_t *c) { return c->o.verdict && c->o.decide > 0; }

/* The sample index that ends interval g of the G intervals of the grid. */
static int grid_end(int S, int G, int g) { return (int)((long)g * (S - 1) / G); }

/* The number of intervals the search starts from on S samples (opts.grid). */
static int grid_count(const cert_t *c, int S)
{
    const int G = c->o.grid > 0 ? c->o.grid : c->o.verdict && c->o.decide > 0 ? OB_CERT_VERDICT_GRID : 0;
    return G > 0 && G < S - 1 ? G : S - 1;
}

static double met_target(const cert_t *c)
{
    return fmax(fmax(c->out->lower * (1.0 + c->o.rtol), c->floor), c->stop);
}

/* What the search refines to: met_target, or below it to o.decide while the
 * enclosure straddles it (lower <= decide < upper: no verdict yet).  In
 * verdict mode: decide until lower > decide, then nothing (decided: over). */
static double target(const cert_t *c)
{
    if (verdict(c))
        return c->out->lower > c->o.decide ? INFINITY : fmax(fmax(c->o.decide, c->floor), c->stop);
    const double t = met_target(c);
    return c->o.decide > 0 && c->out->lower <= c->o.decide && t > c->o.decide ? c->o.decide : t;
}

/* Whether the caller's cancel hook stops the search (asked every
 * CANCEL_EVERY calls; once it has, always). */
static int cancelled(cert_t *c)
{
    if (c->out->cancelled)
        return 1;
    if (!c->o.cancel || ++c->cancel_tick % CANCEL_EVERY)
        return 0;
    c->out->cancelled = c->o.cancel(c->o.cancel_ctx) != 0;
    return c->out->cancelled;
}

/* The least bound over an interval's lines (metric_certified.h): the
 * interpolation of its ends' feet, the line that bounded its parent
 * (where a foot jumped off it), and each end's foot continued at its
 * speed; the later ones only while the least is above `want`.  The parent's line is why a
 * half is never much worse than its parent where a new foot lands on
 * another branch of a self-intersecting offset.  Sets it->lt, it->lk to
 * the line that gave the bound. */
static double leaf_bound(cert_t *c, const side_t *s, ob_cert_item *it, double want)
{
    const double m = 0.5 * (it->a + it->b), w = it->b - it->a, k0 = (it->tb - it->ta) / w;
    /* the quadratic through both ends' feet whose slope changes from ka to
     * kb (a Hermite fit; t' = k0 + 2 q h): its slip is O(w^3) */
    const double q = (it->kb - it->ka) / (2.0 * w), r = 0.5 * w;
    const double line[5][3] = {{it->ta + k0 * (m - it->a), k0, 0.0},
                               {0.5 * (it->ta + it->tb) - q * r * r, k0, q},
                               {it->lt + it->lk * (m - it->a), it->lk, 0.0},
                               {it->ta + it->ka * (m - it->a), it->ka, 0.0},
                               {it->tb + it->kb * (m - it->b), it->kb, 0.0}};
    double U = INFINITY;
    int best = -1;
    ob_cert_pside ps;
    /* the third-order form near round-off (THIRD_FLOORS floors): there the
     * second order's remainder |e''| h^2 / 2 is what stops the bound; above,
     * for a tight enclosure it is rarely the difference and costs ~40 % per
     * leaf.  A verdict starts from wide intervals (OB_CERT_VERDICT_GRID),
     * where the h^3 remainder is the difference: on the default job it
     * halves the leaves (1.27 to 0.71 million) and saves 19 % of the time */
    ob_cert_upper_prep(&s->P, it->a, it->b, verdict(c) || want < THIRD_FLOORS * c->floor, &ps);
    /* the parent's line only where a foot left it by more than the
     * interval's own extent along it (a jump between branches); elsewhere
     * the interpolation is as good, and an extra line costs budget */
    const double jump = fabs(it->ta - it->lt) + fabs(it->tb - (it->lt + it->lk * (it->b - it->a)));
    const int parent = it->lk == it->lk && jump > fabs(it->lk) * (it->b - it->a);
    for (int i = 0; i < 5 && (best < 0 || U > want); i++) {  /* one line at least: want may be +inf */
        if ((i == 2 && !parent) || (i == 1 && !(q == q && q != 0.0)))
            continue;
        const double Ui = ob_cert_upper_quad(&ps, &s->Q, line[i][0], line[i][1], line[i][2]);
        c->out->leaves++, c->upper_work++;
        if (Ui < U || best < 0)
            U = fmin(U, Ui), best = i;
    }
    /* the halves inherit a line: the quadratic's tangent at m where it won */
    it->lt = line[best][0] - line[best][1] * (m - it->a), it->lk = line[best][1];
    return U;
}

static void push_leaf(cert_t *c, side_t *s, ob_cert_item it)
{
    it.key = leaf_bound(c, s, &it, target(c));
    ob_cert_heap_push(&s->heap, it);
}

/* A certified lower bound of the distance from the box a to curve Q, refined
 * towards goal (branch and bound over Q's parameter, least bound first). */
static double point_lower(cert_t *c, const ob_cv *Q, const ob_iv a[2], double goal)
{
    ob_cert_heap h = {malloc((LOWER_ROOTS + 2 * (size_t)LOWER_BUDGET + 2) * sizeof(ob_cert_item)), 0,
                      LOWER_ROOTS + 2 * (size_t)LOWER_BUDGET + 2};
    if (!h.v)
        return 0.0;
    for (int i = 0; i < LOWER_ROOTS; i++) {
        const double t0 = (double)i / LOWER_ROOTS, t1 = (double)(i + 1) / LOWER_ROOTS;
        ob_cert_heap_push(&h, (ob_cert_item){-ob_cert_lower(Q, a, t0, t1), t0, t1, 0, 0, 0, 0, 0, 0});
    }
    double L = 0.0;
    for (long n = 0;; n++) {
        const ob_cert_item it = ob_cert_heap_pop(&h);
        L = -it.key;
        if (L >= goal || n >= LOWER_BUDGET || it.b - it.a < MIN_WIDTH || cancelled(c))
            break;
        const double m = 0.5 * (it.a + it.b);
        ob_cert_heap_push(&h, (ob_cert_item){-ob_cert_lower(Q, a, it.a, m), it.a, m, 0, 0, 0, 0, 0, 0});
        ob_cert_heap_push(&h, (ob_cert_item){-ob_cert_lower(Q, a, m, it.b), m, it.b, 0, 0, 0, 0, 0, 0});
        c->out->leaves += 2;
    }
    free(h.v);
    return L;
}

/* Certify the distance of P(u) to Q when its estimate could raise the lower
 * bound (in verdict mode, when it could decide: above decide, unless the
 * first bound of a piece that seeks one, `first`). */
static void probe(cert_t *c, int k, double u, int first)
{
    const side_t *s = &c->side[k];
    double p[2], d1[2], t;
    ob_iv a[2], a1[2];
    ob_cert_eval(&s->P, u, p, d1);
    const double est = ob_cert_nearest(&s->Q, p, (const double (*)[2])s->tab, s->S, &t);
    double useful = fmax(fmax(c->out->lower * (1.0 + 0.1 * c->o.rtol), c->floor), c->stop / (1.0 + c->o.rtol));
    if (verdict(c) && (!first || c->o.no_lower))
        useful = fmax(useful, c->o.decide);
    if (!(est > useful) || ob_cv_point(&s->P, u, a, a1))
        return;
    const double L = point_lower(c, &s->Q, a, est * (1.0 - 1e-5));
    if (L > c->out->lower)
        c->out->lower = L, c->out->lower_side = k, c->out->lower_param = u;
}

/* The estimated distance from P(u) to Q. */
static double estimate(const side_t *s, double u)
{
    double x[2], d1[2], t;
    ob_cert_eval(&s->P, u, x, d1);
    return ob_cert_nearest(&s->Q, x, (const double (*)[2])s->tab, s->S, &t);
}

/* The sampled maximum of side k, refined by golden section, then probed. */
static void first_lower(cert_t *c, int k)
{
    const side_t *s = &c->side[k];
    int j = 0;
    for (int i = 1; i < s->S; i++)
        if (s->dist[i] > s->dist[j])
            j = i;
    double a = (double)(j > 0 ? j - 1 : 0) / (s->S - 1), b = (double)(j < s->S - 1 ? j + 1 : j) / (s->S - 1);
    /* golden section for the largest estimate: one foot per step */
    const double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = estimate(s, x1), f2 = estimate(s, x2);
    for (int it = 0; it < 36; it++) {
        if (f1 >= f2) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - g * (b - a), f1 = estimate(s, x1);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + g * (b - a), f2 = estimate(s, x2);
        }
    }
    probe(c, k, (double)j / (s->S - 1), 1);
    probe(c, k, 0.5 * (a + b), 1);
}

/* Branch and bound on side k until its largest bound meets the target: the
 * sample intervals first, then the worst interval halved, its middle given
 * its own foot (so a foot map that bends or jumps inside is followed). */
static void refine(cert_t *c, int k)
{
    side_t *s = &c->side[k];
    const double h = 1.0 / (s->S - 1);
    const int G = grid_count(c, s->S);
    for (int g = 0, j0 = 0; g < G; g++) {
        const int j1 = grid_end(s->S, G, g + 1);
        push_leaf(c, s, (ob_cert_item){0, j0 * h, j1 * h, s->foot[j0], s->foot[j1], s->slope[j0], s->slope[j1], 0.0, NAN});
        j0 = j1;
    }
    for (long n = 1; c->upper_work < c->o.budget * (k + 1); n++) {
        if (n % PROBE_EVERY == 0)
            probe(c, k, 0.5 * (s->heap.v[0].a + s->heap.v[0].b), 0);
        const ob_cert_item it = s->heap.v[0];
        if (!(it.key > target(c)) || it.b - it.a < MIN_WIDTH || (isinf(it.key) && it.b - it.a < 1e-9) ||
            cancelled(c))
            break;
        ob_cert_heap_pop(&s->heap);
        const double m = 0.5 * (it.a + it.b), hint = it.lt + it.lk * (m - it.a);  /* the parent's line at m */
        double tm, km;
        ob_cert_foot_hint(&s->P, &s->Q, m, (const double (*)[2])s->tab, s->S, hint, &tm, &km);
        push_leaf(c, s, (ob_cert_item){0, it.a, m, it.ta, tm, it.ka, km, it.lt, it.lk});
        push_leaf(c, s, (ob_cert_item){0, m, it.b, tm, it.tb, km, it.kb, hint, it.lk});
    }
}

static double curve_size(const ob_bez *b)
{
    double m = 0.0, p[2];
    for (int i = 0; i <= b->deg; i++) {
        ob_bez_ctrl(b, i, p);
        m = fmax(m, fmax(fabs(p[0]), fabs(p[1])));
    }
    return m;
}

/* The feet of the samples of side s not found yet (side_alloc found the
 * grid's alone): what the sampled maximum (first_lower) reads. */
static void side_all_feet(side_t *s)
{
    for (int j = 0; j < s->S; j++)
        if (!(s->dist[j] >= 0))
            s->dist[j] = ob_cert_foot(&s->P, &s->Q, (double)j / (s->S - 1), (const double (*)[2])s->tab, s->S,
                                      &s->foot[j], &s->slope[j]);
}

/* The largest distance found at a foot of side s (the grid's, or all). */
static double side_max(const side_t *s)
{
    double m = 0.0;
    for (int j = 0; j < s->S; j++)
        if (s->dist[j] > m)
            m = s->dist[j];
    return m;
}

static int side_alloc(side_t *s, int S, long budget, int G)
{
    s->S = S;
    s->tab = malloc((size_t)S * sizeof *s->tab);
    s->foot = malloc(3 * (size_t)S * sizeof *s->foot);
    s->heap.cap = (size_t)S + 2 * (size_t)budget + 8;
    s->heap.v = malloc(s->heap.cap * sizeof *s->heap.v);
    s->heap.n = 0;
    if (!s->tab || !s->foot || !s->heap.v)
        return -1;
    s->dist = s->foot + S, s->slope = s->foot + 2 * S;
    ob_cert_table(&s->Q, S, s->tab);
    if (G >= S - 1) {
        ob_cert_feet(&s->P, &s->Q, S, (const double (*)[2])s->tab, s->foot, s->dist, s->slope);
        return 0;
    }
    for (int j = 0; j < S; j++)  /* the grid's feet alone; the others when asked (side_all_feet) */
        s->dist[j] = -1.0;
    for (int g = 0; g <= G; g++) {
        const int j = grid_end(S, G, g);
        s->dist[j] = ob_cert_foot(&s->P, &s->Q, (double)j / (S - 1), (const double (*)[2])s->tab, S, &s->foot[j],
                                  &s->slope[j]);
    }
    return 0;
}

static void side_free(side_t *s)
{
    free(s->tab);
    free(s->foot);
    free(s->heap.v);
}

void ob_cert_defaults(ob_cert_opts *o)
{
    o->rtol = 1e-3;
    o->floor_rel = 1e-13;
    o->budget = 20000;
    o->decide = 0.0;
    o->verdict = 0;
    o->no_lower = 0;
    o->grid = 0;
    o->cancel = NULL;
    o->cancel_ctx = NULL;
}

int ob_certify_piece(const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d, int samples,
                     const ob_cert_opts *opts, double stop, ob_certified *out)
{
    cert_t c = {.out = out, .stop = stop > 0 && stop < INFINITY ? stop : 0.0};
    if (opts)
        c.o = *opts;
    else
        ob_cert_defaults(&c.o);
    *out = (ob_certified){0};
    out->upper = INFINITY;
    ob_cv A, O;
    ob_cv_from_src(&A, approx, NULL, 0.0, 0);
    if (ob_cv_from_src(&O, base, src, d, 1) != 0)
        return -1;
    ob_cv_hodo *hd = malloc(2 * sizeof *hd);  /* ~8 KB each: not on the stack */
    if (!hd)
        return -1;
    ob_cv_hodo_attach(&A, &hd[0]);
    ob_cv_hodo_attach(&O, &hd[1]);
    c.side[0].P = A, c.side[0].Q = O, c.side[1].P = O, c.side[1].Q = A;
    c.floor = c.o.floor_rel * (fmax(curve_size(base), curve_size(approx)) + fabs(d));
    const int S = ob_clamp_samples(samples);
    int rc = -1;
    const int G = grid_count(&c, S);
    if (side_alloc(&c.side[0], S, c.o.budget, G) == 0 && side_alloc(&c.side[1], S, c.o.budget, G) == 0) {
        /* the sampled maximum's distance certified: always, but in verdict
         * mode on a piece that seeks no lower bound only where the grid
         * already says it may be over decide */
        for (int k = 0; k < 2; k++)
            if (!verdict(&c) || !c.o.no_lower || side_max(&c.side[k]) > c.o.decide) {
                side_all_feet(&c.side[k]);
                first_lower(&c, k);
            }
        refine(&c, 0);
        refine(&c, 1);
        out->upper_ao = c.side[0].heap.n ? c.side[0].heap.v[0].key : 0.0;
        out->upper_oa = c.side[1].heap.n ? c.side[1].heap.v[0].key : 0.0;
        out->upper = fmax(out->upper_ao, out->upper_oa);
        out->met = verdict(&c) ? out->upper <= c.o.decide || out->lower > c.o.decide : out->upper <= met_target(&c);
        rc = isinf(out->upper) || out->upper != out->upper ? -1 : 0;
        if (rc)
            out->upper = INFINITY;
    }
    side_free(&c.side[0]);
    side_free(&c.side[1]);
    free(hd);
    return rc;
}

int ob_certify_hausdorff_until(const ob_bez *base, const ob_bez *approx, double d, int samples,
                               const ob_cert_opts *opts, double stop, ob_certified *out)
{
    return ob_certify_piece(base, NULL, approx, d, samples, opts, stop, out);
}

int ob_certify_hausdorff_opts(const ob_bez *base, const ob_bez *approx, double d, int samples,
                              const ob_cert_opts *opts, ob_certified *out)
{
    return ob_certify_hausdorff_until(base, approx, d, samples, opts, 0.0, out);
}

int ob_certify_hausdorff(const ob_bez *base, const ob_bez *approx, double d, int samples, ob_certified *out)
{
    return ob_certify_hausdorff_opts(base, approx, d, samples, NULL, out);
}
