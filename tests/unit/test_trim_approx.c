/*
 * test_trim_approx.c - an approximation trimmed by its own crossings
 * (host/measure/trim_approx.c, `run --trimmed`, issue 50):
 *   - cubic Hermite pieces of the parabola's untrimmed offset at d = 1
 *     (through its swallowtail): one region cut; what is kept lies within
 *     twice the pieces' error of the exact trimmed offset, while the
 *     untrimmed pieces are far from it (the loop); the kept parts end at
 *     the pieces' own crossing, near the offset's (0, 5/4);
 *   - at d = -1 (no loop) nothing is cut and every piece is kept bit for
 *     bit;
 *   - the S cubic at d = 0.4, whose offset crosses the opposite offset
 *     (not itself): trimming needs those crossings to come within the
 *     pieces' error of the trimmed offset;
 *   - a closed circle whose "offset" inward by 2 is the antipodal circle,
 *     on the curve: all of it removed, one region across the wrap;
 *   - a piece with a NaN point: an error, no crash.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "tests/testlib.h"
#include "host/measure/trim.h"
#include "host/measure/trim_approx.h"
#include "methods/metrics/metric.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* n cubic Hermite pieces of the untrimmed d-offset of segment b, over n
 * equal parameter ranges; *herr: their largest hausdorff error. */
static void hermite(const ob_bez *b, double d, int n, ob_approx *a, double *herr)
{
    memset(a, 0, sizeof *a);
    *herr = 0.0;
    for (int k = 0; k < n; k++) {
        const double u0 = (double)k / n, u1 = (double)(k + 1) / n, h = (u1 - u0) / 3.0;
        double p[4][2], d0[2], d1[2];
        ob_bez_offset_point_d(b, u0, d, p[0], d0);
        ob_bez_offset_point_d(b, u1, d, p[3], d1);
        p[1][0] = p[0][0] + h * d0[0], p[1][1] = p[0][1] + h * d0[1];
        p[2][0] = p[3][0] - h * d1[0], p[2][1] = p[3][1] - h * d1[1];
        ob_apiece *q = ob_approx_add(a);
        ob_bez_from_points(&q->approx, 3, p);
        ob_bez base;
        ob_bez_subsegment(b, u0, u1, &base);
        ob_errval e;
        ob_measure(OB_METRIC_HAUSDORFF, &base, &q->approx, d, 256, &e);
        *herr = fmax(*herr, e.err);
    }
}

/* The trimmed-hausdorff distance of pieces a from the exact trimmed offset. */
static double set_dist(const ob_curve *c, double d, const ob_approx *a)
{
    ob_trim tr = {0};
    ob_err err = {""};
    ob_mres r;
    char msg[200];
    double e = NAN;
    if (ob_trim_offset(c, d, &tr, &err) == 0 && ob_trimmed_hausdorff(c, d, &tr, a, 256, &r, msg, sizeof msg, &err) == 0)
        e = r.err;
    ob_trim_free(&tr);
    return e;
}

static void test_parabola(void)
{
    const double pts[3][2] = {{-2, 4}, {0, -4}, {2, 4}}; /* (t, t^2), t in [-2, 2] */
    ob_bez b;
    ob_bez_from_points(&b, 2, pts);
    ob_curve c = curve_of(&b, 1, "parabola");
    ob_approx a, kept;
    ob_err err = {""};
    double herr;
    hermite(&b, 1.0, 200, &a, &herr);
    int cut = -1;
    CHECK(ob_trim_approx(&c, 1.0, &a, 2 * herr, &kept, &cut, &err) == 0, "%s", err.msg);
    CHECK(cut == 1, "d = 1: one region cut, %d", cut);
    const double whole = set_dist(&c, 1.0, &a), trimmed = set_dist(&c, 1.0, &kept);
    CHECK(whole > 0.1, "the untrimmed pieces are far from the trimmed offset: %g", whole);
    CHECK(trimmed <= 2 * herr, "the kept parts within 2 x the pieces' error %g: %g", herr, trimmed);
    CHECK(herr > 0 && herr < 1e-3, "the pieces' error %g", herr);
    /* the kept parts end at the pieces' crossing, near the offset's, on
     * x = 0, y = 5/4 (t = +-sqrt(3)/2): one piece ends there, the next
     * starts there */
    const double X[2] = {0.0, 1.25};
    int at = 0;
    for (int k = 0; k + 1 < kept.n; k++) {
        double p[2], q[2];
        ob_bez_point(&kept.v[k].approx, 1.0, p);
        ob_bez_point(&kept.v[k + 1].approx, 0.0, q);
        at += dist2d(p, X) < 10 * herr && dist2d(q, X) < 10 * herr;
    }
    CHECK(at == 1, "the cut at the crossing: %d joints there", at);
    ob_approx_free(&kept);
    ob_approx_free(&a);

    hermite(&b, -1.0, 50, &a, &herr);
    CHECK(ob_trim_approx(&c, -1.0, &a, 2 * herr, &kept, &cut, &err) == 0 && cut == 0 && kept.n == a.n,
          "d = -1: nothing cut, %d regions, %d of %d pieces", cut, kept.n, a.n);
    int same = kept.n == a.n;
    for (int k = 0; same && k < a.n; k++)
        same = memcmp(&kept.v[k].approx, &a.v[k].approx, sizeof a.v[k].approx) == 0;
    CHECK(same, "d = -1: every piece kept bit for bit");
    ob_approx_free(&kept);
    ob_approx_free(&a);
}

static void test_scurve(void)
{
    const double pts[4][2] = {{0, 0}, {4, 3}, {-3, 3}, {1, 0}};
    ob_bez b;
    ob_bez_from_points(&b, 3, pts);
    ob_curve c = curve_of(&b, 1, "scurve");
    ob_approx a, kept;
    ob_err err = {""};
    double herr;
    int cut = -1;
    hermite(&b, 0.4, 400, &a, &herr);
    CHECK(ob_trim_approx(&c, 0.4, &a, 2 * herr, &kept, &cut, &err) == 0 && cut >= 1, "S at 0.4: %d cut", cut);
    const double whole = set_dist(&c, 0.4, &a), trimmed = set_dist(&c, 0.4, &kept);
    CHECK(whole > 0.05, "the untrimmed pieces are far from the trimmed offset: %g", whole);
    CHECK(trimmed <= 2 * herr, "the kept parts within 2 x the pieces' error %g: %g", herr, trimmed);
    ob_approx_free(&kept);
    ob_approx_free(&a);
}

static void test_circle(void)
{
    const double w = sqrt(0.5);
    ob_bez q[4];
    ob_approx a = {0}, kept;
    for (int k = 0; k < 4; k++) {
        const double c0 = cos(k * M_PI / 2), s0 = sin(k * M_PI / 2), c1 = cos((k + 1) * M_PI / 2),
                     s1 = sin((k + 1) * M_PI / 2);
        memset(&q[k], 0, sizeof q[k]);
        q[k].deg = 2;
        ob_bez_set(&q[k], 0, c0, s0, 1.0);
        ob_bez_set(&q[k], 1, c0 + c1, s0 + s1, w);
        ob_bez_set(&q[k], 2, c1, s1, 1.0);
    }
    ob_bez_set(&q[3], 2, 1.0, 0.0, 1.0);
    for (int k = 0; k < 4; k++) { /* C + 2 N = -C: the antipodal quarter */
        ob_apiece *p = ob_approx_add(&a);
        p->approx = q[k];
        for (int i = 0; i <= 2; i++)
            ob_bez_set(&p->approx, i, -(i == 1 ? q[k].h[i][0] / w : q[k].h[i][0]),
                       -(i == 1 ? q[k].h[i][1] / w : q[k].h[i][1]), i == 1 ? w : 1.0);
    }
    ob_curve c = curve_of(q, 4, "circle4");
    ob_err err = {""};
    int cut = -1;
    CHECK(ob_trim_approx(&c, 2.0, &a, 1e-9, &kept, &cut, &err) == 0 && kept.n == 0 && cut == 1,
          "the antipodal circle: all removed, one region over the wrap: %d kept, %d cut", kept.n, cut);
    ob_approx_free(&kept);
    ob_bez_set(&a.v[2].approx, 1, NAN, 0.0, w);
    CHECK(ob_trim_approx(&c, 2.0, &a, 1e-9, &kept, &cut, &err) == -1 && strstr(err.msg, "not finite"),
          "a NaN piece: an error: %s", err.msg);
    ob_approx_free(&kept);
    ob_approx_free(&a);
}

/* An L, (0, 1) -> (0, 0) -> (1, 0), two lines with a corner (a left
 * turn), and its offset's two lines as the approximation (exact): at
 * d = -0.25 (the right, convex side) a CAD kernel fills their gap with the
 * quarter circle about the corner, and so must the trimming, to measure at
 * round-off; at d = 0.25 (concave) the lines overlap and are cut where
 * they cross, (0.25, 0.25), also at round-off. */
static void test_corner(void)
{
    const double l0[2][2] = {{0, 1}, {0, 0}}, l1[2][2] = {{0, 0}, {1, 0}};
    ob_bez seg[2];
    ob_bez_from_points(&seg[0], 1, l0);
    ob_bez_from_points(&seg[1], 1, l1);
    ob_curve c = curve_of(seg, 2, "L");
    for (int s = -1; s <= 1; s += 2) {
        const double d = 0.25 * s;
        ob_approx a = {0}, kept;
        for (int k = 0; k < 2; k++) {
            double p[2][2];
            ob_bez_offset_point(&seg[k], 0.0, d, p[0]);
            ob_bez_offset_point(&seg[k], 1.0, d, p[1]);
            ob_apiece *q = ob_approx_add(&a);
            ob_bez_from_points(&q->approx, 1, p);
            q->has_base = 1, q->seg = k, q->a = 0.0, q->b = 1.0, q->t0 = 0.0, q->t1 = 1.0;
        }
        ob_err err = {""};
        int cut = -1;
        CHECK(ob_trim_approx(&c, d, &a, 1e-9, &kept, &cut, &err) == 0, "%s", err.msg);
        const double e = set_dist(&c, d, &kept), raw = set_dist(&c, d, &a);
        CHECK(e < 1e-12, "the L at d = %g: the offset's lines trimmed (and the corner filled) measure %g", d, e);
        CHECK(raw > 0.05, "the L at d = %g: the lines as they are measure %g", d, raw);
        ob_approx_free(&kept);
        ob_approx_free(&a);
    }
}

int main(void)
{
    test_corner();
    test_parabola();
    test_scurve();
    test_circle();
    return check_done();
}
