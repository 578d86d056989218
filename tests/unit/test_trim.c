/*
 * test_trim.c - the trimmed offset (host/measure/trim.c, issue 50):
 *   - the parabola (t, t^2), t in [-2, 2], at d = 1 (its concave side, a
 *     swallowtail): the self-intersection at t = +-sqrt(4d^2 - 1)/2 on
 *     x = 0, y = t^2 + 1/2, the cusps where 1 - d kappa = 0, both to
 *     1e-13; the kept arcs exactly the outside parts; at d = -1 all kept;
 *   - a quarter circle (atlas_circle) offset inward by more than its
 *     radius: nothing kept; by less: all kept;
 *   - a whole circle of four rational quarters: the same, over its wrap;
 *   - an ellipse of four quarters offset inwards past its least radius of
 *     curvature: swallowtails at the major axis' ends, one over the wrap,
 *     their self-intersections on the axis;
 *   - liu2002_ex1 at d = 1: some of it removed (all but [0, 0.092]: its
 *     end circle cuts it); every kept arc's points at distance |d| from
 *     the curve, every removed one's nearer; at d = -1 all kept;
 *   - trimmed-hausdorff: the exact offset of a quarter circle as a
 *     rational quadratic measures at round-off; half of it missing: the
 *     missing end's distance.
 *   - corners (G0 joints): an L of two line segments, on its convex side
 *     the two sides and a quarter circle of radius |d| about the corner,
 *     on its concave side the sides cut where they cross (at d = -1e-7
 *     too: the crossing inside the chords next to the corner); a closed
 *     square, outside its 4 sides and 4 quarter circles (the wrap's
 *     included, length 4 + 2 pi |d|), inside 4 shorter sides and no arc;
 *     an M whose two peaks' arcs cut each other where the circles about
 *     the peaks cross; a reversal (out and back along a segment,
 *     closed): a stadium, half circles round both ends on either side;
 *     the square's exact outside offset (lines and rational quarter
 *     circles) measures at round-off.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "tests/testlib.h"
#include "host/io/curvefile.h"
#include "host/measure/trim.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The parabola (t, t^2) for t in [-a, a] as one quadratic: u = (t + a) / 2a. */
static void parabola(ob_bez *b, double a)
{
    const double p[3][2] = {{-a, a * a}, {0, -a * a}, {a, a * a}};
    ob_bez_from_points(b, 2, p);
}

static int count_kind(const ob_trim *tr, ob_split_kind k)
{
    int n = 0;
    for (int i = 0; i < tr->nsplit; i++)
        n += tr->split[i].kind == k;
    return n;
}

/* The split of kind k nearest u, or NAN. */
static double split_near(const ob_trim *tr, ob_split_kind k, double u)
{
    double best = NAN;
    for (int i = 0; i < tr->nsplit; i++)
        if (tr->split[i].kind == k && !(fabs(tr->split[i].t - u) >= fabs(best - u)))
            best = tr->split[i].t;
    return best;
}

static void test_parabola(void)
{
    const double a = 2.0, d = 1.0, ts = sqrt(4 * d * d - 1) / 2, tc = sqrt((pow(2 * d, 2.0 / 3) - 1) / 4);
    ob_bez b;
    parabola(&b, a);
    ob_curve c = curve_of(&b, 1, "parabola");
    ob_trim tr = {0};
    ob_err err = {""};
    CHECK(ob_trim_offset(&c, d, &tr, &err) == 0, "%s", err.msg);
    CHECK(count_kind(&tr, OB_SPLIT_CUSP) == 2, "2 cusps, %d", count_kind(&tr, OB_SPLIT_CUSP));
    CHECK(count_kind(&tr, OB_SPLIT_SELF) == 2, "2 self-intersection parameters, %d", count_kind(&tr, OB_SPLIT_SELF));
    for (int s = -1; s <= 1; s += 2) {
        const double us = (s * ts + a) / (2 * a), uc = (s * tc + a) / (2 * a);
        const double u = split_near(&tr, OB_SPLIT_SELF, us);
        CHECK_NEAR(u, us, 1e-13, "self-intersection parameter");
        double p[2];
        ob_bez_offset_point(&b, u, d, p);
        CHECK_NEAR(p[0], 0.0, 1e-13, "self-intersection x");
        CHECK_NEAR(p[1], ts * ts + 0.5, 1e-13, "self-intersection y");
        CHECK_NEAR(split_near(&tr, OB_SPLIT_CUSP, uc), uc, 1e-13, "cusp parameter");
    }
    CHECK(tr.n == 2, "2 kept arcs, %d", tr.n);
    if (tr.n == 2) {
        CHECK(tr.arc[0].seg == 0 && tr.arc[0].t0 == 0.0 && tr.arc[1].t1 == 1.0, "the outside parts to the ends");
        CHECK_NEAR(tr.arc[0].t1, (a - ts) / (2 * a), 1e-13, "first arc's end");
        CHECK_NEAR(tr.arc[1].t0, (a + ts) / (2 * a), 1e-13, "second arc's start");
    }
    ob_trim_free(&tr);
    CHECK(ob_trim_offset(&c, -d, &tr, &err) == 0 && tr.n == 1 && tr.arc[0].t0 == 0.0 && tr.arc[0].t1 == 1.0,
          "convex side: all kept (%d arcs, %d splits)", tr.n, tr.nsplit);
    ob_trim_free(&tr);
}

static void test_quarter(const ob_curveset *set)
{
    const int i = ob_curveset_find(set, "atlas_circle");
    CHECK(i >= 0, "atlas_circle");
    if (i < 0)
        return;
    ob_trim tr = {0};
    ob_err err = {""};
    CHECK(ob_trim_offset(&set->v[i], 1.5, &tr, &err) == 0 && tr.n == 0, "inward past the center: %d arcs", tr.n);
    ob_trim_free(&tr);
    CHECK(ob_trim_offset(&set->v[i], 0.5, &tr, &err) == 0 && tr.n == 1 && tr.arc[0].t0 == 0.0 && tr.arc[0].t1 == 1.0,
          "inward by less than the radius: all kept (%d arcs)", tr.n);
    ob_trim_free(&tr);
}

/* A unit circle of four rational quadratic quarters, counter-clockwise. */
static void circle4(ob_bez *q)
{
    const double w = sqrt(0.5);
    for (int k = 0; k < 4; k++) {
        const double c0 = cos(k * M_PI / 2), s0 = sin(k * M_PI / 2), c1 = cos((k + 1) * M_PI / 2),
                     s1 = sin((k + 1) * M_PI / 2);
        memset(&q[k], 0, sizeof q[k]);
        q[k].deg = 2;
        ob_bez_set(&q[k], 0, c0, s0, 1.0);
        ob_bez_set(&q[k], 1, c0 + c1, s0 + s1, w);
        ob_bez_set(&q[k], 2, c1, s1, 1.0);
    }
    ob_bez_set(&q[3], 2, 1.0, 0.0, 1.0); /* closed bit for bit */
}

static void test_circle(void)
{
    ob_bez q[4];
    circle4(q);
    ob_curve c = curve_of(q, 4, "circle4");
    ob_trim tr = {0};
    ob_err err = {""};
    CHECK(ob_trim_offset(&c, 1.5, &tr, &err) == 0 && tr.n == 0, "closed circle inward past the center: %d arcs", tr.n);
    ob_trim_free(&tr);
    CHECK(ob_trim_offset(&c, -0.5, &tr, &err) == 0 && tr.n == 4, "outward: 4 whole arcs, %d", tr.n);
    for (int k = 0; k < tr.n; k++)
        CHECK(tr.arc[k].seg == k && tr.arc[k].t0 == 0.0 && tr.arc[k].t1 == 1.0, "arc %d whole", k);
    ob_trim_free(&tr);
}

/* The ellipse x^2/4 + y^2 = 1 (the circle's quarters, x doubled) offset
 * inwards by 0.8 > its least radius of curvature 1/2: a swallowtail about
 * each end of the major axis, the one at x = 2 across the closed curve's
 * wrap (segment 3 to segment 0).  By symmetry each self-intersection lies
 * on the x axis; the kept arcs' points are 0.8 from the ellipse, the
 * removed parts' nearer. */
static void test_ellipse_wrap(void)
{
    ob_bez q[4];
    circle4(q);
    for (int k = 0; k < 4; k++)
        for (int i = 0; i <= 2; i++)
            q[k].h[i][0] *= 2.0;
    ob_curve c = curve_of(q, 4, "ellipse4");
    ob_trim tr = {0};
    ob_err err = {""};
    const double d = 0.8;
    CHECK(ob_trim_offset(&c, d, &tr, &err) == 0, "%s", err.msg);
    CHECK(count_kind(&tr, OB_SPLIT_SELF) == 4 && count_kind(&tr, OB_SPLIT_CUSP) == 4,
          "4 self-intersection parameters and 4 cusps, %d and %d", count_kind(&tr, OB_SPLIT_SELF),
          count_kind(&tr, OB_SPLIT_CUSP));
    int wrap = 0;
    for (int i = 0; i < tr.nsplit; i++)
        if (tr.split[i].kind == OB_SPLIT_SELF) {
            double p[2];
            ob_bez_offset_point(&q[tr.split[i].seg], tr.split[i].t, d, p);
            CHECK_NEAR(p[1], 0.0, 1e-13, "self-intersection on the x axis");
            wrap += p[0] > 0.0 && (tr.split[i].seg == 0 || tr.split[i].seg == 3);
        }
    CHECK(wrap == 2, "the swallowtail at x = 2 across the wrap: %d of its splits on segments 3 and 0", wrap);
    int far = 0, near = 0;
    for (int k = 0; k < tr.n; k++)
        for (int j = 0; j <= 8; j++) {
            double p[2];
            ob_bez_offset_point(&q[tr.arc[k].seg], tr.arc[k].t0 + (tr.arc[k].t1 - tr.arc[k].t0) * j / 8.0, d, p);
            far += ob_trim_base_dist(&c, p) < d - 1e-9;
        }
    double p[2];
    ob_bez_offset_point(&q[0], 0.0, d, p); /* the tip of the swallowtail at x = 2: removed */
    near += ob_trim_base_dist(&c, p) < d - 1e-6;
    CHECK(far == 0 && near == 1 && tr.n == 4, "%d arcs, %d kept points nearer than d, tip removed %d", tr.n, far, near);
    ob_trim_free(&tr);
}

static void test_liu(const ob_curveset *set)
{
    const int i = ob_curveset_find(set, "liu2002_ex1");
    CHECK(i >= 0, "liu2002_ex1");
    if (i < 0)
        return;
    const ob_curve *c = &set->v[i];
    ob_trim tr = {0};
    ob_err err = {""};
    CHECK(ob_trim_offset(c, 1.0, &tr, &err) == 0 && tr.n >= 1, "liu2002_ex1 at d = 1: %d arcs", tr.n);
    double kept = 0.0;
    int far = 0, near = 0;
    for (int k = 0; k <= tr.n; k++) {
        const double g0 = k ? tr.arc[k - 1].t1 : 0.0, g1 = k < tr.n ? tr.arc[k].t0 : 1.0; /* the part removed before */
        double p[2];
        if (g1 > g0) {
            ob_bez_offset_point(&c->seg[0], 0.5 * (g0 + g1), 1.0, p);
            near += ob_trim_base_dist(c, p) < 1.0 - 1e-6;
        }
        if (k == tr.n)
            break;
        kept += tr.arc[k].t1 - tr.arc[k].t0;
        for (int j = 0; j <= 16; j++) {
            ob_bez_offset_point(&c->seg[0], tr.arc[k].t0 + (tr.arc[k].t1 - tr.arc[k].t0) * j / 16.0, 1.0, p);
            far += ob_trim_base_dist(c, p) < 1.0 - 1e-9;
        }
    }
    CHECK(kept < 0.95, "some of it removed: %g of [0, 1] kept", kept);
    CHECK(far == 0, "%d kept points nearer than |d|", far);
    CHECK(near >= 1, "the removed parts nearer than |d| (%d)", near);
    ob_trim_free(&tr);
    CHECK(ob_trim_offset(c, -1.0, &tr, &err) == 0 && tr.n == 1 && tr.arc[0].t1 - tr.arc[0].t0 == 1.0,
          "d = -1: all kept (%d arcs)", tr.n);
    ob_trim_free(&tr);
}

/* The exact 0.5-offset of the quarter circle (radius 0.5) as one piece. */
static void test_measure(const ob_curveset *set)
{
    const int i = ob_curveset_find(set, "atlas_circle");
    if (i < 0)
        return;
    const ob_curve *c = &set->v[i];
    ob_trim tr = {0};
    ob_err err = {""};
    ob_approx a = {0};
    ob_apiece *p = ob_approx_add(&a);
    const double w = sqrt(0.5);
    p->approx.deg = 2;
    ob_bez_set(&p->approx, 0, 0.5, 0.0, 1.0);
    ob_bez_set(&p->approx, 1, 0.5, 0.5, w);
    ob_bez_set(&p->approx, 2, 0.0, 0.5, 1.0);
    ob_mres r;
    char msg[200];
    CHECK(ob_trim_offset(c, 0.5, &tr, &err) == 0 && ob_trimmed_hausdorff(c, 0.5, &tr, &a, 256, &r, msg, sizeof msg, &err) == 0,
          "%s", err.msg);
    CHECK(r.ok && r.err < 1e-14, "exact arc: %g (%s)", r.err, msg);
    const ob_bez whole = p->approx;
    ob_bez_subsegment(&whole, 0.0, 0.5, &p->approx); /* half of it, to 45 degrees */
    CHECK(ob_trimmed_hausdorff(c, 0.5, &tr, &a, 256, &r, msg, sizeof msg, &err) == 0, "%s", err.msg);
    CHECK_NEAR(r.err, 2 * 0.5 * sin(M_PI / 8), 1e-12, "half missing: the chord to 90 degrees");
    CHECK(strstr(msg, "trimmed offset") != NULL, "says the side: %s", msg);
    ob_trim_free(&tr);
    CHECK(ob_trim_offset(c, 1.5, &tr, &err) == 0 && ob_trimmed_hausdorff(c, 1.5, &tr, &a, 256, &r, msg, sizeof msg, &err) != 0 &&
              strstr(err.msg, "empty") != NULL,
          "nothing kept: an error (%s)", err.msg);
    ob_trim_free(&tr);
    ob_approx_free(&a);
}

/* A polyline of n - 1 line segments through p (n points) into seg. */
static void polyline(ob_bez *seg, const double (*p)[2], int n)
{
    for (int k = 0; k + 1 < n; k++) {
        memset(&seg[k], 0, sizeof seg[k]);
        ob_bez_from_points(&seg[k], 1, p + k);
    }
}

/* The length of a kept arc: a corner's r |t1 - t0|, a piece of O by 256
 * chords (the pieces here are offsets of lines: exact). */
static double arc_length(const ob_curve *c, double d, const ob_trim_arc *ar)
{
    if (ar->corner)
        return ar->r * fabs(ar->t1 - ar->t0);
    double L = 0.0, p[2], q[2];
    ob_trim_arc_point(c, d, ar, 0.0, p);
    for (int i = 1; i <= 256; i++) {
        ob_trim_arc_point(c, d, ar, i / 256.0, q);
        L += hypot(q[0] - p[0], q[1] - p[1]);
        p[0] = q[0], p[1] = q[1];
    }
    return L;
}

static double trim_length(const ob_curve *c, double d, const ob_trim *tr, int *corners)
{
    double L = 0.0;
    *corners = 0;
    for (int k = 0; k < tr->n; k++)
        L += arc_length(c, d, &tr->arc[k]), *corners += tr->arc[k].corner;
    return L;
}

/* Checks that arc k of tr runs from (x0, y0) to (x1, y1) to 1e-12. */
static void check_ends(const ob_curve *c, double d, const ob_trim *tr, int k, double x0, double y0, double x1,
                       double y1, const char *what)
{
    double p[2], q[2];
    if (k >= tr->n) {
        CHECK(0, "%s: no arc %d (%d arcs)", what, k, tr->n);
        return;
    }
    ob_trim_arc_point(c, d, &tr->arc[k], 0.0, p);
    ob_trim_arc_point(c, d, &tr->arc[k], 1.0, q);
    CHECK(hypot(p[0] - x0, p[1] - y0) <= 1e-12 && hypot(q[0] - x1, q[1] - y1) <= 1e-12,
          "%s: arc %d from (%.17g, %.17g) to (%.17g, %.17g), expected (%g, %g) to (%g, %g)", what, k, p[0], p[1], q[0],
          q[1], x0, y0, x1, y1);
}

/* An L: (-1, 0) to (0, 0) to (0, -1), a right turn.  Its left (d > 0) is
 * the convex side: both sides whole and the quarter circle about (0, 0)
 * from (0, d) to (d, 0), clockwise, between them.  Its right (d < 0) is
 * concave: the sides cross at (d, d) and end there, no arc; also at
 * d = -1e-7, where the crossing lies inside the two chords next to the
 * corner (OB_TRIM_POLY chords a segment). */
static void test_corner_l(void)
{
    const double p[3][2] = {{-1, 0}, {0, 0}, {0, -1}}, d = 0.25;
    ob_bez s[2];
    polyline(s, p, 3);
    ob_curve c = curve_of(s, 2, "L");
    ob_trim tr = {0};
    ob_err err = {""};
    int nc;
    CHECK(ob_trim_offset(&c, d, &tr, &err) == 0, "%s", err.msg);
    CHECK(tr.n == 3 && tr.arc[0].corner == 0 && tr.arc[1].corner == 1 && tr.arc[2].corner == 0,
          "L convex side: side, corner, side: %d arcs", tr.n);
    if (tr.n == 3) {
        CHECK(tr.arc[1].seg == 1 && tr.arc[1].r == d && tr.arc[1].ctr[0] == 0.0 && tr.arc[1].ctr[1] == 0.0 &&
                  tr.arc[1].t1 < tr.arc[1].t0,
              "the corner arc: about the joint at segment 1's start, radius d, clockwise (seg %d, r %g, %g to %g)",
              tr.arc[1].seg, tr.arc[1].r, tr.arc[1].t0, tr.arc[1].t1);
        check_ends(&c, d, &tr, 0, -1, d, 0, d, "L convex");
        check_ends(&c, d, &tr, 1, 0, d, d, 0, "L convex");
        check_ends(&c, d, &tr, 2, d, 0, d, -1, "L convex");
    }
    CHECK_NEAR(trim_length(&c, d, &tr, &nc), 2 + M_PI / 2 * d, 1e-12, "L convex: length 2 + pi d / 2");
    ob_trim_free(&tr);
    const double dc[2] = {-0.25, -1e-7};
    for (int i = 0; i < 2; i++) {
        CHECK(ob_trim_offset(&c, dc[i], &tr, &err) == 0, "%s", err.msg);
        CHECK(tr.n == 2 && tr.arc[0].corner == 0 && tr.arc[1].corner == 0, "L concave d = %g: 2 sides, %d arcs",
              dc[i], tr.n);
        check_ends(&c, dc[i], &tr, 0, -1, dc[i], dc[i], dc[i], "L concave");
        check_ends(&c, dc[i], &tr, 1, dc[i], dc[i], dc[i], -1, "L concave");
        CHECK_NEAR(trim_length(&c, dc[i], &tr, &nc), 2 * (1 + dc[i]), 1e-12, "L concave: 2 (1 - |d|)");
        CHECK(nc == 0, "L concave: no corner arc, %d", nc);
        ob_trim_free(&tr);
    }
}

/* The unit square, counter-clockwise, closed: its left is inside.  Outside
 * (d = -0.25) the 4 sides and 4 quarter circles, the one about (0, 0) (the
 * wrap's joint) last; inside (d = 0.25) 4 sides of 0.5, no arc. */
static void test_corner_square(void)
{
    const double p[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
    ob_bez s[4];
    polyline(s, p, 5);
    ob_curve c = curve_of(s, 4, "square");
    ob_trim tr = {0};
    ob_err err = {""};
    int nc;
    const double d = -0.25, r = 0.25;
    CHECK(ob_trim_offset(&c, d, &tr, &err) == 0, "%s", err.msg);
    CHECK(tr.n == 8, "square outside: 8 arcs, %d", tr.n);
    for (int k = 0; k < tr.n && tr.n == 8; k++)
        CHECK(tr.arc[k].corner == (k % 2) && tr.arc[k].seg == (k % 2 ? (k / 2 + 1) % 4 : k / 2),
              "arc %d: corner %d seg %d", k, tr.arc[k].corner, tr.arc[k].seg);
    if (tr.n == 8) {
        check_ends(&c, d, &tr, 0, 0, -r, 1, -r, "square outside");
        check_ends(&c, d, &tr, 1, 1, -r, 1 + r, 0, "square outside");
        check_ends(&c, d, &tr, 5, 0, 1 + r, -r, 1, "square outside");
        check_ends(&c, d, &tr, 7, -r, 0, 0, -r, "square outside: the wrap's corner");
    }
    CHECK_NEAR(trim_length(&c, d, &tr, &nc), 4 + 2 * M_PI * r, 1e-12, "square outside: 4 + 2 pi |d|");
    CHECK(nc == 4, "square outside: 4 corner arcs, %d", nc);
    ob_trim_free(&tr);
    CHECK(ob_trim_offset(&c, -d, &tr, &err) == 0, "%s", err.msg);
    CHECK_NEAR(trim_length(&c, -d, &tr, &nc), 4 * (1 - 2 * r), 1e-12, "square inside: 4 (1 - 2 d)");
    CHECK(tr.n == 4 && nc == 0, "square inside: 4 sides, no arc: %d arcs, %d corners", tr.n, nc);
    check_ends(&c, -d, &tr, 0, r, r, 1 - r, r, "square inside");
    check_ends(&c, -d, &tr, 3, r, 1 - r, r, r, "square inside");
    ob_trim_free(&tr);
}

/* An M, (0, 0) (0.5, 1) (1, 0.2) (1.5, 1) (2, 0), offset up by 0.7: the
 * arcs about the peaks P1 = (0.5, 1) and P2 = (1.5, 1) (1 apart) cut each
 * other where their circles cross, at X = (1, 1 + sqrt(0.24)); the
 * valley's sides come nearer than 0.7 to the peaks: removed.  Kept: the
 * first side, P1's arc from its normal to X, P2's from X to its normal,
 * the last side. */
static void test_corner_cut(void)
{
    const double p[5][2] = {{0, 0}, {0.5, 1}, {1, 0.2}, {1.5, 1}, {2, 0}}, d = 0.7, h = sqrt(0.24);
    ob_bez s[4];
    polyline(s, p, 5);
    ob_curve c = curve_of(s, 4, "M");
    ob_trim tr = {0};
    ob_err err = {""};
    int nc;
    CHECK(ob_trim_offset(&c, d, &tr, &err) == 0, "%s", err.msg);
    CHECK(tr.n == 4 && tr.arc[1].corner && tr.arc[2].corner && tr.arc[1].seg == 1 && tr.arc[2].seg == 3,
          "M: side, P1's arc, P2's arc, side: %d arcs", tr.n);
    const double n0 = 1 / sqrt(1.25), a0 = atan2(0.5, -1), ax = atan2(h, 0.5);
    check_ends(&c, d, &tr, 0, -d * n0, 0.5 * d * n0, 0.5 - d * n0, 1 + 0.5 * d * n0, "M");
    check_ends(&c, d, &tr, 1, 0.5 - d * n0, 1 + 0.5 * d * n0, 1, 1 + h, "M: P1's arc to X");
    check_ends(&c, d, &tr, 2, 1, 1 + h, 1.5 + d * n0, 1 + 0.5 * d * n0, "M: P2's arc from X");
    CHECK_NEAR(trim_length(&c, d, &tr, &nc), 2 * sqrt(1.25) + 2 * d * (a0 - ax), 1e-12, "M: length");
    CHECK(nc == 2, "M: 2 corner arcs, %d", nc);
    for (int k = 0; k < tr.n; k++)
        for (int j = 0; j <= 16; j++) {
            double q[2];
            ob_trim_arc_point(&c, d, &tr.arc[k], j / 16.0, q);
            CHECK(fabs(ob_trim_base_dist(&c, q) - d) <= 1e-12, "M: arc %d at %d/16: %.17g from the curve", k, j,
                  ob_trim_base_dist(&c, q));
        }
    ob_trim_free(&tr);
}

/* Out along (0, 0) to (1, 0) and back, a closed curve: its tangent turns
 * by pi at both joints.  On either side the offset is the two sides and
 * the half circles about (1, 0) and (0, 0) round the ends (a stadium,
 * 2 + 2 pi |d|). */
static void test_corner_reversal(void)
{
    const double p[3][2] = {{0, 0}, {1, 0}, {0, 0}};
    ob_bez s[2];
    polyline(s, p, 3);
    ob_curve c = curve_of(s, 2, "hairpin");
    for (int sd = -1; sd <= 1; sd += 2) {
        const double d = 0.2 * sd;
        ob_trim tr = {0};
        ob_err err = {""};
        int nc;
        CHECK(ob_trim_offset(&c, d, &tr, &err) == 0, "%s", err.msg);
        CHECK(tr.n == 4 && tr.arc[1].corner && tr.arc[3].corner, "reversal d = %g: side, half circle, side, half "
              "circle: %d arcs", d, tr.n);
        check_ends(&c, d, &tr, 1, 1, d, 1, -d, "reversal: round (1, 0)");
        check_ends(&c, d, &tr, 3, 0, -d, 0, d, "reversal: round (0, 0), the wrap");
        CHECK_NEAR(trim_length(&c, d, &tr, &nc), 2 + 2 * M_PI * fabs(d), 1e-12, "reversal: a stadium, 2 + 2 pi |d|");
        ob_trim_free(&tr);
    }
}

/* The square's exact outside offset at radius r: for each side k (from
 * corner V_k to V_k+1, outward normal at angle (k - 1) pi / 2) a line,
 * then the rational quarter circle about V_k+1; the one about V_skip + 1
 * left out (skip < 0: none). */
static void square_offset(ob_approx *a, double r, int skip)
{
    const double vx[4] = {0, 1, 1, 0}, vy[4] = {0, 0, 1, 1}, w = sqrt(0.5);
    for (int k = 0; k < 4; k++) {
        const double c0 = cos((k - 1) * M_PI / 2), s0 = sin((k - 1) * M_PI / 2), c1 = cos(k * M_PI / 2),
                     s1 = sin(k * M_PI / 2), cx = vx[(k + 1) % 4], cy = vy[(k + 1) % 4];
        const double e[2][2] = {{vx[k] + r * c0, vy[k] + r * s0}, {cx + r * c0, cy + r * s0}};
        ob_bez_from_points(&ob_approx_add(a)->approx, 1, e);
        if (k == skip)
            continue;
        ob_bez *q = &ob_approx_add(a)->approx;
        q->deg = 2;
        ob_bez_set(q, 0, cx + r * c0, cy + r * s0, 1.0);
        ob_bez_set(q, 1, cx + r * (c0 + c1), cy + r * (s0 + s1), w);
        ob_bez_set(q, 2, cx + r * c1, cy + r * s1, 1.0);
    }
}

/* trimmed-hausdorff samples and projects onto corner arcs: the square's
 * exact outside offset at d = -0.25 measures at round-off; without the
 * quarter circle about (1, 1), that arc's midpoint is 2 |d| sin(pi / 8)
 * from the nearest file point (the two lines' ends). */
static void test_corner_measure(void)
{
    const double p[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}, d = -0.25;
    ob_bez s[4];
    polyline(s, p, 5);
    ob_curve c = curve_of(s, 4, "square");
    ob_trim tr = {0};
    ob_err err = {""};
    ob_mres r;
    char msg[200];
    CHECK(ob_trim_offset(&c, d, &tr, &err) == 0, "%s", err.msg);
    ob_approx a = {0}, b = {0};
    square_offset(&a, -d, -1);
    square_offset(&b, -d, 1);
    CHECK(ob_trimmed_hausdorff(&c, d, &tr, &a, 256, &r, msg, sizeof msg, &err) == 0, "%s", err.msg);
    CHECK(r.ok && r.err < 1e-14, "square's exact outside offset: %g (%s)", r.err, msg);
    CHECK(ob_trimmed_hausdorff(&c, d, &tr, &b, 256, &r, msg, sizeof msg, &err) == 0, "%s", err.msg);
    /* a kink (the nearest file point switches between the lines' ends):
     * golden section's 1e-10 in u gives the distance to some 1e-11 */
    CHECK_NEAR(r.err, -2 * d * sin(M_PI / 8), 1e-10, "the arc about (1, 1) missing: 2 |d| sin(pi / 8)");
    CHECK(strstr(msg, "trimmed offset") != NULL && r.seg == 2 && r.t == 0.0,
          "says the side and the corner (segment 2 at t = 0): seg %d t %g, %s", r.seg, r.t, msg);
    ob_trim_free(&tr);
    ob_approx_free(&a);
    ob_approx_free(&b);
}

int main(void)
{
    ob_curveset atlas = {0}, pub = {0};
    ob_err err = {""};
    CHECK(ob_curves_load_file("datasets/atlas.curves", &atlas, &err) == 0, "atlas.curves: %s", err.msg);
    CHECK(ob_curves_load_file("datasets/published.curves", &pub, &err) == 0, "published.curves: %s", err.msg);
    test_parabola();
    test_quarter(&atlas);
    test_circle();
    test_ellipse_wrap();
    test_liu(&pub);
    test_measure(&atlas);
    test_corner_l();
    test_corner_square();
    test_corner_cut();
    test_corner_reversal();
    test_corner_measure();
    ob_curveset_free(&atlas);
    ob_curveset_free(&pub);
    return check_done();
}
