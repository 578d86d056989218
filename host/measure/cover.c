/*
 * cover.c - does an approximation cover the whole offset once?  (measure.h,
 * ob_approx_cover; README "measure".)
 *
 * Each piece's base range (segment, [u0, u1]) comes from its link; the
 * ranges are sorted by segment and start, and walked with a cursor: the
 * farthest base position covered so far.  A piece that starts after the
 * cursor leaves a gap; one that starts before it overlaps (or duplicates
 * the piece before it).  Joints between read links are compared bit for
 * bit; joints that involve a matched link are compared along the offset,
 * within the tolerance that measure.h describes.
 */
#include "host/measure/measure.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/driver/joints.h"

enum { ARC_CHORDS = 16 };

typedef struct {
    int seg, k;       /* base segment, piece (file index) */
    double u0, u1;    /* the base range */
    int exact;        /* 1: a read link (its joints compared bit for bit) */
    double len;       /* the length of its range's offset (where a link was matched) */
} range;

typedef struct {
    int seg;
    double u;
} pos;

typedef struct {
    const ob_curve *c;
    double d;
    double floor;     /* OB_COVER_REL times the curve's size */
    double tol;       /* where a matched link is involved: max(floor, 2 x the largest own error) */
    ob_cover *cv;
} walk;

/* The offset point of segment s at u. */
static void opoint(const walk *w, int s, double u, double o[2])
{
    ob_bez_offset_point(&w->c->seg[s], u, w->d, o);
}

/* The length of the offset of segment s over [u0, u1], as a polyline of
 * ARC_CHORDS chords (a chord alone would call a loop that returns near its
 * start short). */
static double arc_on(const walk *w, int s, double u0, double u1)
{
    double len = 0.0, p[2], q[2];
    opoint(w, s, u0, p);
    for (int i = 1; i <= ARC_CHORDS; i++) {
        opoint(w, s, i == ARC_CHORDS ? u1 : u0 + (u1 - u0) * i / ARC_CHORDS, q);
        len += hypot(q[0] - p[0], q[1] - p[1]);
        p[0] = q[0], p[1] = q[1];
    }
    return len;
}

static int cmp_pos(pos a, pos b)
{
    if (a.seg != b.seg)
        return a.seg < b.seg ? -1 : 1;
    return a.u < b.u ? -1 : a.u > b.u;
}

/* The length of the offset between a and b, across segments. */
static double offset_len(const walk *w, pos a, pos b)
{
    if (cmp_pos(a, b) > 0) {
        const pos x = a;
        a = b;
        b = x;
    }
    if (a.seg == b.seg)
        return arc_on(w, a.seg, a.u, b.u);
    double len = arc_on(w, a.seg, a.u, 1.0) + arc_on(w, b.seg, 0.0, b.u);
    for (int s = a.seg + 1; s < b.seg; s++)
        len += arc_on(w, s, 0.0, 1.0);
    return len;
}

/* (s, 1) is (s + 1, 0) where a next segment exists. */
static pos norm(const walk *w, int s, double u)
{
    return u >= 1.0 && s + 1 < w->c->nseg ? (pos){s + 1, 0.0} : (pos){s, u};
}

static int cmp_range(const void *x, const void *y)
{
    const range *p = x, *q = y;
    if (p->seg != q->seg)
        return p->seg < q->seg ? -1 : 1;
    if (p->u0 != q->u0)
        return p->u0 < q->u0 ? -1 : 1;
    if (p->u1 != q->u1)
        return p->u1 < q->u1 ? -1 : 1;
    return (p->k > q->k) - (p->k < q->k);
}

static int is_note(ob_cover_kind kind)
{
    return kind == OB_COVER_ORDER || kind == OB_COVER_NEAR_GAP || kind == OB_COVER_NEAR_OVERLAP;
}

/* Records one problem: counted, and kept among the first. */
static void add(walk *w, ob_cover_kind kind, int piece, int other, pos a, pos b)
{
    ob_cover *cv = w->cv;
    cv->count[kind]++;
    const ob_cover_issue is = {kind, piece, other, a.seg, b.seg, a.u, b.u};
    if (is_note(kind)) {
        if (cv->nnote < OB_COVER_KEEP)
            cv->note[cv->nnote++] = is;
    } else if (cv->nfail < OB_COVER_KEEP) {
        cv->fail[cv->nfail++] = is;
    }
}

/* The base range of piece k into *r; -1 with err for a link that is not a
 * piece of c. */
static int range_of(const walk *w, const ob_approx *a, int k, const char *name, range *r, ob_err *err)
{
    const ob_apiece *p = &a->v[k];
    ob_bez base;
    if (!p->has_base)
        return ob_fail(err, "%s:%d: piece %d has no base link (match it first)", name, p->line, k);
    if (ob_apiece_base(w->c, p, &base) != 0)
        return ob_fail(err, "%s:%d: piece %d: its base segment %d (span %.17g %.17g, fit %.17g %.17g) is not a "
                       "piece of curve '%s' (%d segments)", name, p->line, k, p->seg, p->a, p->b, p->t0, p->t1,
                       w->c->id, w->c->nseg);
    *r = (range){p->seg, k, ob_apiece_base_t(p, 0.0), ob_apiece_base_t(p, 1.0), !p->matched, 0.0};
    return 0;
}

/* The largest error of the pieces (hausdorff, each against its base piece,
 * S samples): the accuracy that matched links meet within. */
static double own_error(const walk *w, const ob_approx *a, int S)
{
    double e = 0.0;
    for (int k = 0; k < a->n; k++) {
        ob_bez base;
        ob_errval v;
        if (ob_apiece_base(w->c, &a->v[k], &base) == 0 &&
            ob_measure(OB_METRIC_HAUSDORFF, &base, &a->v[k].approx, w->d, S, &v) == 0 && v.err > e)
            e = v.err;
    }
    return e;
}

/* How far apart a and b are: 0 the same position (or within the floor),
 * 1 within the tolerance, 2 beyond it (exact: any difference is beyond).
 * piece: the length of the shorter piece beside the stretch; a stretch
 * fails only when it is longer than a quarter of that too. */
static int apart(const walk *w, pos a, pos b, int exact, double piece)
{
    if (cmp_pos(a, b) == 0)
        return 0;
    if (exact)
        return 2;
    const double len = offset_len(w, a, b);
    return len <= w->floor ? 0 : len <= w->tol || len <= 0.25 * piece ? 1 : 2;
}

/* A stretch from a to b after piece p and before piece q (NULL: the
 * curve's start or end): nothing (the same place), a note (within the
 * tolerance) or a failure of kind `kind`, seen at q (at p after the last). */
static void stretch(walk *w, ob_cover_kind kind, const range *p, const range *q, pos a, pos b, int exact)
{
    const double beside = fmin(p ? p->len : INFINITY, q ? q->len : INFINITY);
    const int how = apart(w, a, b, exact, beside);
    if (how)
        add(w, how == 2 ? kind : kind == OB_COVER_GAP ? OB_COVER_NEAR_GAP : OB_COVER_NEAR_OVERLAP, q ? q->k : p->k,
            p ? p->k : -1, a, b);
}

/* 1 when p and q cover one range (within the tolerance where a match is
 * involved). */
static int same_range(const walk *w, const range *p, const range *q)
{
    const int ex = p->exact && q->exact;
    const double l = fmin(p->len, q->len);
    return p->seg == q->seg && apart(w, (pos){p->seg, p->u0}, (pos){q->seg, q->u0}, ex, l) < 2 &&
           apart(w, (pos){p->seg, p->u1}, (pos){q->seg, q->u1}, ex, l) < 2;
}

/* The walk over the ranges in base order (s[0..n)). */
static void check_order(walk *w, const range *s, int n)
{
    pos cur = {0, 0.0};      /* the farthest position covered */
    const range *cr = NULL;  /* the piece that reached it */
    for (int i = 0; i < n; i++) {
        const range *r = &s[i];
        const pos start = norm(w, r->seg, r->u0), end = norm(w, r->seg, r->u1);
        const int exact = (!cr || cr->exact) && r->exact, c = cmp_pos(start, cur);
        if (c > 0)
            stretch(w, OB_COVER_GAP, cr, r, cur, start, exact);
        else if (c < 0 && same_range(w, &s[i - 1], r))
            add(w, OB_COVER_DUPLICATE, r->k, s[i - 1].k, (pos){r->seg, r->u0}, (pos){r->seg, r->u1});
        else if (c < 0)
            stretch(w, OB_COVER_OVERLAP, cr, r, (pos){r->seg, r->u0},
                    cmp_pos(end, cur) < 0 ? (pos){r->seg, r->u1} : cur, exact);
        if (cmp_pos(end, cur) > 0) {
            cur = end;
            cr = r;
        }
    }
    const pos last = {w->c->nseg - 1, 1.0};
    if (cr && cmp_pos(cur, last) < 0)
        stretch(w, OB_COVER_GAP, cr, NULL, cur, last, cr->exact);
}

/* Each tile from the middle of the joint before the piece to the middle of
 * the joint after it (exact joints: the joint itself), 0 and 1 at a
 * segment's first and last piece. */
static void tiles(ob_cover *cv, const range *s, int n)
{
    for (int i = 0; i < n; i++) {
        const range *r = &s[i];
        const int first = i == 0 || s[i - 1].seg != r->seg, last = i == n - 1 || s[i + 1].seg != r->seg;
        cv->lo[r->k] = first ? 0.0 : 0.5 * (s[i - 1].u1 + r->u0);
        cv->hi[r->k] = last ? 1.0 : 0.5 * (r->u1 + s[i + 1].u0);
    }
}

int ob_approx_cover(const ob_curve *c, double d, const ob_approx *a, int samples, const char *name, ob_cover *cv,
                    ob_err *err)
{
    memset(cv, 0, sizeof *cv);
    const size_t n = a->n > 0 ? (size_t)a->n : 1;
    range *s = malloc(n * sizeof *s);
    int *rank = malloc(n * sizeof *rank);
    cv->order = malloc(n * sizeof *cv->order);
    cv->lo = malloc(n * sizeof *cv->lo);
    cv->hi = malloc(n * sizeof *cv->hi);
    cv->n = a->n;
    int rc = s && rank && cv->order && cv->lo && cv->hi ? 0 : ob_fail(err, "%s: out of memory", name);
    walk w = {c, d, OB_COVER_REL * ob_joint_size(c, d), 0.0, cv};
    int matched = 0;
    for (int k = 0; k < a->n && rc == 0; k++) {
        rc = range_of(&w, a, k, name, &s[k], err);
        matched |= a->v[k].matched;
    }
    if (rc == 0 && matched) { /* what matched links meet within */
        w.tol = fmax(w.floor, 2.0 * own_error(&w, a, ob_clamp_samples(samples)));
        for (int k = 0; k < a->n; k++)
            s[k].len = arc_on(&w, s[k].seg, s[k].u0, s[k].u1);
    }
    if (rc == 0 && a->n > 0) {
        qsort(s, (size_t)a->n, sizeof *s, cmp_range);
        for (int i = 0; i < a->n; i++) {
            cv->order[i] = s[i].k;
            rank[s[i].k] = i;
        }
        for (int k = 1; k < a->n; k++)
            if (rank[k] < rank[k - 1]) {
                const ob_apiece *p = &a->v[k];
                add(&w, OB_COVER_ORDER, k, k - 1, (pos){p->seg, ob_apiece_base_t(p, 0.0)},
                    (pos){p->seg, ob_apiece_base_t(p, 1.0)});
            }
        check_order(&w, s, a->n);
        if (ob_cover_fails(cv) == 0)
            tiles(cv, s, a->n);
    }
    free(s);
    free(rank);
    return rc;
}

int ob_cover_fails(const ob_cover *cv)
{
    return cv->count[OB_COVER_GAP] + cv->count[OB_COVER_OVERLAP] + cv->count[OB_COVER_DUPLICATE];
}

/* "segment S from t = X to t = Y" or "segment S t = X to segment S2 t = Y". */
static void range_text(const ob_cover_issue *is, char *buf, size_t len)
{
    if (is->seg0 == is->seg1)
        snprintf(buf, len, "segment %d from t = %.17g to t = %.17g", is->seg0, is->t0, is->t1);
    else
        snprintf(buf, len, "segment %d t = %.17g to segment %d t = %.17g", is->seg0, is->t0, is->seg1, is->t1);
}

/* Where a gap lies: after `other`, or at the curve's start or end. */
static void gap_where(const ob_cover_issue *is, const ob_approx *a, char *buf, size_t len)
{
    if (is->other < 0)
        snprintf(buf, len, "before this piece, the first on the base");
    else if (is->other == is->piece)
        snprintf(buf, len, "after this piece, the last on the base");
    else
        snprintf(buf, len, "after piece %d, line %d", ob_approx_file_piece(a, is->other), a->v[is->other].line);
}

void ob_cover_text(const ob_cover_issue *is, const ob_approx *a, const char *name, char *buf, size_t len)
{
    static const char near[] = ", within the tolerance of pieces matched by projection: hausdorff-whole measures it";
    char rg[160], oth[64] = "", where[80];
    range_text(is, rg, sizeof rg);
    gap_where(is, a, where, sizeof where);
    const int in = is->piece >= 0 && is->piece < a->n, line = in ? a->v[is->piece].line : 0;
    const int piece = in ? ob_approx_file_piece(a, is->piece) : is->piece;  /* the file's number */
    if (is->other >= 0 && is->other < a->n)
        snprintf(oth, sizeof oth, "piece %d (line %d)", ob_approx_file_piece(a, is->other), a->v[is->other].line);
    switch (is->kind) {
    case OB_COVER_GAP:
    case OB_COVER_NEAR_GAP:
        snprintf(buf, len, "%s:%d: piece %d: %sgap: nothing covers base %s (%s)%s", name, line, piece,
                 is->kind == OB_COVER_GAP ? "" : "small ", rg, where, is->kind == OB_COVER_GAP ? "" : near);
        break;
    case OB_COVER_OVERLAP:
    case OB_COVER_NEAR_OVERLAP:
        snprintf(buf, len, "%s:%d: piece %d: %soverlap: base %s is covered by %s too%s", name, line, piece,
                 is->kind == OB_COVER_OVERLAP ? "" : "small ", rg, oth, is->kind == OB_COVER_OVERLAP ? "" : near);
        break;
    case OB_COVER_DUPLICATE:
        snprintf(buf, len, "%s:%d: piece %d: duplicate of %s: base %s", name, line, piece, oth, rg);
        break;
    default:
        snprintf(buf, len, "%s:%d: piece %d: out of order: it lies before %s on the base (%s)", name, line,
                 piece, oth, rg);
        break;
    }
}

void ob_cover_free(ob_cover *cv)
{
    if (!cv)
        return;
    free(cv->order);
    free(cv->lo);
    free(cv->hi);
    memset(cv, 0, sizeof *cv);
}
