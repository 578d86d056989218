/*
 * test_match.c - pieces that run over several base segments (measure's
 * projection match, host/measure/match.c, issue 39: a CAD system's offset
 * is cut where it likes, not where the base's segments join):
 *   - a line over a straight base of three segments is cut at the two
 *     joints, its parts linked to [0.5, 1], [0, 1], [0, 0.5], its error 0,
 *     and it stays one piece of the file (numbers, count);
 *   - an exact offset circle in three 120-degree arcs over a base circle in
 *     four quarter arcs (joints nowhere near each other, the last arc over
 *     the closed base's start point): every part on its segment, the error
 *     at round-off;
 *   - one cubic across a two-segment base measures as it does across the
 *     same curve in one segment (the joint's line is the offset's normal);
 *   - a piece that never crosses a joint's normal line is refused, named.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "tests/testlib.h"
#include "host/measure/measure.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double hausdorff(const ob_curve *c, double d, const ob_approx *a, ob_mres *r)
{
    ob_err err = {""};
    if (ob_approx_measure(c, d, a, OB_METRIC_HAUSDORFF, 256, "t", r, &err) != 0 || !r->applies)
        return NAN;
    return r->err;
}

static void test_straight(void)
{
    ob_bez seg[3];
    for (int s = 0; s < 3; s++) {
        const double p[2][2] = {{s, 0}, {s + 1, 0}};
        ob_bez_from_points(&seg[s], 1, p);
    }
    ob_curve c = curve_of(seg, 3, "line3");
    ob_approx a = {0};
    const double first[2][2] = {{-0.2, 0.5}, {-0.1, 0.5}}, line[2][2] = {{2.5, 0.5}, {0.5, 0.5}};
    ob_bez_from_points(&ob_approx_add(&a)->approx, 1, line);  /* backwards */
    ob_err err = {""};
    const int rc = ob_approx_match(&c, 0.5, &a, "s.dxf", &err);
    CHECK(rc == 0 && a.n == 3, "a line over three segments becomes 3 linked parts: rc %d, %d parts (%s)", rc, a.n,
          err.msg);
    if (rc != 0 || a.n != 3)
        goto out;
    const double want[3][2] = {{0.5, 1.0}, {0.0, 1.0}, {0.0, 0.5}};
    for (int k = 0; k < 3; k++) {
        CHECK(a.v[k].seg == k && a.v[k].part == k && a.v[k].matched, "part %d on segment %d (part %d)", k,
              a.v[k].seg, a.v[k].part);
        CHECK(fabs(a.v[k].a - want[k][0]) <= 1e-9 && fabs(a.v[k].b - want[k][1]) <= 1e-9,
              "part %d links [%.17g, %.17g]", k, a.v[k].a, a.v[k].b);
    }
    double e0[2], s1[2];
    ob_bez_point(&a.v[0].approx, 1.0, e0);
    ob_bez_point(&a.v[1].approx, 0.0, s1);
    CHECK(e0[0] == s1[0] && e0[1] == s1[1], "the parts meet bit for bit");
    CHECK(ob_approx_file_pieces(&a) == 1 && ob_approx_file_piece(&a, 2) == 0, "still one piece of the file");
    ob_mres r;
    CHECK(hausdorff(&c, 0.5, &a, &r) <= 1e-15, "hausdorff of the exact offset line: %.3g", r.err);
    /* a piece before it in the file keeps its number, the cut one is 1 */
    ob_approx_free(&a);
    ob_bez_from_points(&ob_approx_add(&a)->approx, 1, first);
    ob_bez_from_points(&ob_approx_add(&a)->approx, 1, line);
    a.v[0].has_base = 1;  /* as if read with a link */
    CHECK(ob_approx_match(&c, 0.5, &a, "s.dxf", &err) == 0 && a.n == 4 && ob_approx_file_piece(&a, 3) == 1 &&
              ob_approx_file_pieces(&a) == 2,
          "file numbers after a cut: %d parts, last is piece %d", a.n, a.n ? ob_approx_file_piece(&a, a.n - 1) : -1);
out:
    ob_approx_free(&a);
}

/* A rational quadratic arc of the circle (cx, cy, r) from angle t0 to t1
 * (|t1 - t0| < pi). */
static void arc(ob_bez *b, double r, double t0, double t1)
{
    const double h = 0.5 * (t1 - t0), m = 0.5 * (t0 + t1), w = cos(h);
    ob_bez_from_points(b, 2, (const double[3][2]){{0, 0}, {0, 0}, {0, 0}});
    ob_bez_set(b, 0, r * cos(t0), r * sin(t0), 1.0);
    ob_bez_set(b, 1, r * cos(m) / w, r * sin(m) / w, w);
    ob_bez_set(b, 2, r * cos(t1), r * sin(t1), 1.0);
}

static void test_circle(void)
{
    ob_bez seg[4];
    for (int s = 0; s < 4; s++)
        arc(&seg[s], 1.0, s * M_PI / 2, (s + 1) * M_PI / 2);
    ob_curve c = curve_of(seg, 4, "circle");
    /* counter-clockwise: the left normal points inwards; d = 0.25 is the
     * circle of radius 0.75.  Its arcs from 45 degrees, 120 each: the
     * last runs over the closed base's start point (its seam). */
    const double d = 0.25, rr = 0.75, deg = M_PI / 180;
    ob_approx a = {0};
    arc(&ob_approx_add(&a)->approx, rr, 45 * deg, 165 * deg);
    arc(&ob_approx_add(&a)->approx, rr, 285 * deg, 165 * deg);  /* backwards */
    arc(&ob_approx_add(&a)->approx, rr, 285 * deg, 405 * deg);
    ob_err err = {""};
    const int rc = ob_approx_match(&c, d, &a, "c.dxf", &err);
    CHECK(rc == 0 && a.n == 7 && ob_approx_file_pieces(&a) == 3, "three arcs over four quarters: %d parts (%s)", a.n,
          err.msg);
    if (rc == 0 && a.n == 7) {
        const int segs[7] = {0, 1, 1, 2, 3, 3, 0};
        for (int k = 0; k < 7; k++)
            CHECK(a.v[k].seg == segs[k], "part %d on segment %d (want %d)", k, a.v[k].seg, segs[k]);
        CHECK(fabs(a.v[0].a - 0.5) <= 1e-6 && fabs(a.v[6].b - 0.5) <= 1e-6,
              "the first starts, the last ends half-way along the first quarter: %.17g %.17g", a.v[0].a, a.v[6].b);
        ob_mres r;
        CHECK(hausdorff(&c, d, &a, &r) <= 1e-12, "exact arcs: hausdorff %.3g", r.err);
        CHECK(r.piece >= 0 && r.piece <= 2, "the worst part names a piece of the file: %d", r.piece);
    }
    ob_approx_free(&a);
}

/* One cubic through four points of the offset of a cubic base, measured
 * over the base as one segment and as the same curve cut at t = 0.4. */
static void test_cut_base(void)
{
    const double P[4][2] = {{0, 0}, {1, 2}, {3, 2}, {4, 0}};
    ob_bez whole, cut[2];
    ob_bez_from_points(&whole, 3, P);
    ob_bez_split(&whole, 0.4, &cut[0], &cut[1]);
    const double d = -0.3;
    double Q[4][2];
    for (int i = 0; i < 4; i++)
        ob_bez_offset_point(&whole, i / 3.0, d, Q[i]);
    ob_approx a1 = {0}, a2 = {0};
    ob_bez_from_points(&ob_approx_add(&a1)->approx, 3, Q);  /* control points at offset points: not exact */
    ob_bez_from_points(&ob_approx_add(&a2)->approx, 3, Q);
    ob_curve c1 = curve_of(&whole, 1, "one"), c2 = curve_of(cut, 2, "two");
    ob_err err = {""};
    CHECK(ob_approx_match(&c1, d, &a1, "a", &err) == 0 && ob_approx_match(&c2, d, &a2, "b", &err) == 0 && a2.n == 2,
          "matched over one and two segments (%s)", err.msg);
    ob_mres r1, r2;
    const double e1 = hausdorff(&c1, d, &a1, &r1), e2 = hausdorff(&c2, d, &a2, &r2);
    CHECK(e1 > 1e-3 && fabs(e2 - e1) <= 1e-6 * e1, "one cubic, its error over one segment %.9g and over two %.9g",
          e1, e2);
    ob_approx_free(&a1);
    ob_approx_free(&a2);
}

/* Base: two segments meeting at (1, 0) at a right angle, (0,0)-(1,0)-(1,1);
 * d = 0.25 (left: above the first, left of the second).  A piece from
 * above the first segment to left of the second that bows away below the
 * base never crosses the joint's line on the offset's side. */
static void test_refused(void)
{
    ob_bez seg[2];
    ob_bez_from_points(&seg[0], 1, (const double[2][2]){{0, 0}, {1, 0}});
    ob_bez_from_points(&seg[1], 1, (const double[2][2]){{1, 0}, {1, 1}});
    ob_curve c = curve_of(seg, 2, "corner");
    ob_approx a = {0};
    ob_bez_from_points(&ob_approx_add(&a)->approx, 2, (const double[3][2]){{0.5, 0.25}, {3, -3}, {0.75, 0.5}});
    ob_apiece *p = ob_approx_add(&a);
    ob_bez_from_points(&p->approx, 1, (const double[2][2]){{0.75, 0.6}, {0.75, 0.9}});
    p->line = 7;
    ob_err err = {""};
    CHECK(ob_approx_match(&c, 0.25, &a, "r.dxf", &err) != 0 && strstr(err.msg, "r.dxf:0: piece 0") &&
              strstr(err.msg, "segments 0 and 1 join"),
          "a piece that never crosses the joint's line is refused: %s", err.msg);
    ob_approx_free(&a);
}

int main(void)
{
    test_straight();
    test_circle();
    test_cut_base();
    test_refused();
    return check_done();
}
