/*
 * test_perpiece.c - each piece's own error and worst point
 * (host/measure/perpiece.c, issue 50 item 3), on the quarter of the unit
 * circle whose d = -0.5 offset is the circle of radius 1.5 at the same
 * parameter (a rational quadratic scaled by 1.5: exact):
 *   - two exact pieces: errors at round-off, one row each;
 *   - one piece scaled by 1.001 about the centre: its row's error is
 *     1.5e-3, the other's at round-off; the largest row is the hausdorff
 *     metric's max_err bit for bit (ob_approx_measure); x, y lies on the
 *     scaled piece (radius 1.5015), x_off, y_off on the offset (radius 1.5),
 *     their distance the error;
 *   - two parts of one file piece (a cut at a base joint): one row, its
 *     error the larger part's, its range from the first part to the last;
 *   - the CSV names the entity, handle and id the pieces carry.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/testlib.h"
#include "host/measure/measure.h"
#include "host/measure/perpiece.h"

static const double W = 0.70710678118654757;

/* The quarter of the circle of radius r about the origin, from (r, 0). */
static ob_bez quarter(double r)
{
    ob_bez b;
    memset(&b, 0, sizeof b);
    b.deg = 2;
    b.rational = 1;
    ob_bez_set(&b, 0, r, 0, 1);
    ob_bez_set(&b, 1, r, r, W);
    ob_bez_set(&b, 2, 0, r, 1);
    return b;
}

/* Piece k of a: part [t0, t1] of the offset (radius 1.5 * s), linked to it. */
static void add_piece(ob_approx *a, double t0, double t1, double s, int part, const char *handle)
{
    ob_apiece *p = ob_approx_add(a);
    const ob_bez q = quarter(1.5 * s);
    ob_bez_subsegment(&q, t0, t1, &p->approx);
    p->has_base = 1;
    p->seg = 0;
    p->a = 0.0;
    p->b = 1.0;
    p->t0 = t0;
    p->t1 = t1;
    p->line = 10 * (a->n);
    p->part = part;
    snprintf(p->entity, sizeof p->entity, "SPLINE");
    snprintf(p->handle, sizeof p->handle, "%s", handle);
}

static ob_curve arc(ob_bez *seg)
{
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "arc");
    *seg = quarter(1.0);
    c.nseg = 1;
    c.seg = seg;
    return c;
}

static void test_rows(void)
{
    ob_bez seg;
    const ob_curve c = arc(&seg);
    ob_approx a = {0};
    add_piece(&a, 0.0, 0.5, 1.0, 0, "A1");
    add_piece(&a, 0.5, 1.0, 1.001, 0, "A2");
    a.same_param = 1;
    ob_perpiece pp;
    ob_err err = {""};
    CHECK(ob_approx_per_piece(&c, -0.5, &a, 256, "t", &pp, &err) == 0, "%s", err.msg);
    CHECK(pp.n == 2, "2 rows, got %d", pp.n);
    if (pp.n != 2)
        goto out;
    CHECK(pp.v[0].err < 1e-14, "the exact piece: %g", pp.v[0].err);
    CHECK_NEAR(pp.v[1].err, 1.5e-3, 1e-12, "the scaled piece's error");
    ob_mres r;
    CHECK(ob_approx_measure(&c, -0.5, &a, OB_METRIC_HAUSDORFF, 256, "t", &r, &err) == 0, "%s", err.msg);
    CHECK(fmax(pp.v[0].err, pp.v[1].err) == r.err, "the largest row %.17g is hausdorff's %.17g",
          fmax(pp.v[0].err, pp.v[1].err), r.err);
    CHECK(pp.v[1].seg == r.seg && pp.v[1].t == r.t, "where: seg %d t %.17g, hausdorff's %d %.17g", pp.v[1].seg,
          pp.v[1].t, r.seg, r.t);
    const ob_pp_row *w = &pp.v[1];
    CHECK_NEAR(hypot(w->x, w->y), 1.5015, 1e-12, "x, y on the scaled piece");
    CHECK_NEAR(hypot(w->xo, w->yo), 1.5, 1e-14, "x_off, y_off on the offset");
    CHECK_NEAR(hypot(w->x - w->xo, w->y - w->yo), w->err, 1e-12, "their distance is the error");
    CHECK(w->t >= 0.5 && w->t <= 1.0, "t %.17g in the piece's range", w->t);
    /* the CSV: entity, handle, the base range */
    FILE *f = tmpfile();
    const ob_pp_file pf = {"x.dxf", &a, &pp};
    CHECK(f && ob_perpiece_csv(f, &pf, 1) == 0, "the CSV is written");
    char buf[4096] = "";
    if (f) {
        rewind(f);
        const size_t n = fread(buf, 1, sizeof buf - 1, f);
        buf[n] = '\0';
        fclose(f);
    }
    CHECK(strncmp(buf, ob_perpiece_header, strlen(ob_perpiece_header)) == 0, "the header first");
    CHECK(strstr(buf, "\nx.dxf,1,SPLINE,A2,,20,2,0,0.5,0,1,") != NULL, "row 1 names its entity, handle, line, range: %s",
          buf);
out:
    ob_perpiece_free(&pp);
    ob_approx_free(&a);
}

static void test_parts(void)
{
    ob_bez seg;
    const ob_curve c = arc(&seg);
    ob_approx a = {0};
    add_piece(&a, 0.0, 0.3, 1.0, 0, "B1");
    add_piece(&a, 0.3, 0.6, 1.0, 0, "B2");
    add_piece(&a, 0.6, 1.0, 1.002, 1, "B2"); /* the second part of piece 1 */
    ob_perpiece pp;
    ob_err err = {""};
    CHECK(ob_approx_per_piece(&c, -0.5, &a, 256, "t", &pp, &err) == 0, "%s", err.msg);
    CHECK(pp.n == 2 && ob_approx_file_pieces(&a) == 2, "2 rows for 2 file pieces, got %d", pp.n);
    if (pp.n == 2) {
        CHECK(pp.v[1].piece == 1 && pp.v[1].first == 1 && pp.v[1].last == 2, "piece 1: parts 1 to 2, got %d..%d",
              pp.v[1].first, pp.v[1].last);
        CHECK_NEAR(pp.v[1].err, 3e-3, 1e-12, "its error is the larger part's");
        CHECK(pp.v[1].worst == 2, "the worst part: 2, got %d", pp.v[1].worst);
    }
    ob_perpiece_free(&pp);
    ob_approx_free(&a);
}

/* A wide bump over a straight base: y = 0, x in [0, 1], d = 1, its offset
 * y = 1; the piece rises to y = 1.6 at x = 0.5 (a cubic through (0, 1) and
 * (1, 1)).  The error, 0.6, is the bump's top's distance from O(0.5) =
 * (0.5, 1); the piece's nearest point to O(0.5) is elsewhere (its ends are
 * 0.5 away): x, y must be the top, at 0.6. */
static void test_wide_bump(void)
{
    const double line[2][2] = {{0, 0}, {1, 0}}, bump[4][2] = {{0, 1}, {0, 1.8}, {1, 1.8}, {1, 1}};
    ob_bez seg;
    ob_bez_from_points(&seg, 1, line);
    const ob_curve c = curve_of(&seg, 1, "line");
    ob_approx a = {0};
    ob_apiece *p = ob_approx_add(&a);
    ob_bez_from_points(&p->approx, 3, bump);
    p->has_base = 1, p->seg = 0, p->a = 0.0, p->b = 1.0, p->t0 = 0.0, p->t1 = 1.0;
    ob_perpiece pp;
    ob_err err = {""};
    CHECK(ob_approx_per_piece(&c, 1.0, &a, 256, "bump", &pp, &err) == 0 && pp.n == 1, "%s", err.msg);
    if (pp.n == 1) {
        const ob_pp_row *r = &pp.v[0];
        CHECK_NEAR(r->err, 0.6, 1e-9, "the bump's error");
        CHECK_NEAR(r->x, 0.5, 1e-6, "x, y is the bump's top: x");
        CHECK_NEAR(r->y, 1.6, 1e-9, "x, y is the bump's top: y");
        CHECK_NEAR(hypot(r->x - r->xo, r->y - r->yo), r->err, 1e-9 * r->err, "x, y is max_err from x_off, y_off");
    }
    ob_perpiece_free(&pp);
    ob_approx_free(&a);
}

int main(void)
{
    test_rows();
    test_wide_bump();
    test_parts();
    return check_done();
}
