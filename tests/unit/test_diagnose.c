/*
 * test_diagnose.c - what measure says of a file far from the offset
 * (host/measure/diagnose.h, issue 50 item 2), on liu2002_ex1's cubic with
 * its exact d-offset as 200 line pieces:
 *   - the pieces at -d measured at d: the wrong sign, and X small;
 *   - the pieces drawn in a CAD frame (x 25.4, y flipped, moved): a
 *     similarity, its --transform the inverse map (snapped: exact to
 *     round-off), and composed after a frame given;
 *   - the pieces rotated by 30 degrees and scaled by 3: found without a
 *     reflection, within the polyline's own error;
 *   - a line nowhere near: nothing found, nothing said;
 *   - the far rule: 1e-2 of the size.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "host/measure/diagnose.h"
#include "methods/driver/joints.h"

static ob_bez base;

static ob_curve curve(void)
{
    static const double xy[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};
    ob_bez_from_points(&base, 3, xy);
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "liu2002_ex1");
    c.nseg = 1;
    c.seg = &base;
    return c;
}

/* The exact d-offset of c as n line pieces, each mapped by f. */
static void offset_lines(const ob_curve *c, double d, int n, const ob_frame *f, ob_approx *a)
{
    for (int i = 0; i < n; i++) {
        double p[2][2], q[2][2];
        ob_bez_offset_point(&c->seg[0], (double)i / n, d, p[0]);
        ob_bez_offset_point(&c->seg[0], (double)(i + 1) / n, d, p[1]);
        ob_frame_point(f, p[0], q[0]);
        ob_frame_point(f, p[1], q[1]);
        ob_bez_from_points(&ob_approx_add(a)->approx, 1, (const double (*)[2])q);
    }
}

/* The six numbers after "--transform " in s into m; 0 or -1. */
static int suggested(const char *s, ob_frame *m)
{
    const char *t = strstr(s, "--transform ");
    return t ? ob_frame_parse_list(t + strlen("--transform "), m->m, 6) : -1;
}

static void test_sign(const ob_curve *c)
{
    ob_approx a = {0};
    char buf[1024];
    offset_lines(c, -1.0, 200, &OB_FRAME_IDENTITY, &a);
    CHECK(ob_diagnose(c, 1.0, &a, &OB_FRAME_IDENTITY, "f", buf, sizeof buf) == 1, "found");
    CHECK(strstr(buf, "of the offset at d = -1: wrong sign of --d?") != NULL, "%s", buf);
    double x = 1.0;
    CHECK(sscanf(buf, "f: it is within %lf", &x) == 1 && x < 1e-3, "within %g", x);
    ob_approx_free(&a);
}

static void test_cad_frame(const ob_curve *c)
{
    const ob_frame g = {{25.4, 0, 0, -25.4, 100, 50}}; /* base -> file */
    const ob_frame inv = {{1 / 25.4, 0, 0, -1 / 25.4, -100 / 25.4, 50 / 25.4}};
    ob_approx a = {0};
    char buf[1024];
    offset_lines(c, 1.0, 200, &g, &a);
    CHECK(ob_diagnose(c, 1.0, &a, &OB_FRAME_IDENTITY, "f", buf, sizeof buf) == 1, "found: %s", buf);
    ob_frame m;
    double e = 1.0;
    if (suggested(buf, &m) == 0) {
        e = 0.0;
        for (int k = 0; k < 6; k++)
            e = fmax(e, fabs(m.m[k] - inv.m[k]));
    }
    CHECK(e < 1e-8, "the inverse map (%g): %s", e, buf);
    /* a frame given (a scale by 2 the file was read through) is composed in */
    const ob_frame two = {{2, 0, 0, 2, 0, 0}}, half = {{0.5, 0, 0, 0.5, 0, 0}};
    ob_frame_apply(&two, &a);
    CHECK(ob_diagnose(c, 1.0, &a, &two, "f", buf, sizeof buf) == 1, "found after a frame");
    const ob_frame want = ob_frame_mul(&inv, &half);
    const ob_frame total = ob_frame_mul(&want, &two); /* the map found after the one given */
    e = 1.0;
    if (suggested(buf, &m) == 0) {
        e = 0.0;
        for (int k = 0; k < 6; k++)
            e = fmax(e, fabs(m.m[k] - total.m[k]));
    }
    /* 1/50.8 is no unit's factor: not snapped, the fit's own (to the residual) */
    CHECK(e < 1e-3, "composed after the frame given (%g): %s", e, buf);
    ob_approx_free(&a);
}

static void test_rotation(const ob_curve *c)
{
    const double th = OB_PI / 6, s = 3.0;
    const ob_frame g = {{s * cos(th), s * sin(th), -s * sin(th), s * cos(th), -4, 9}};
    ob_approx a = {0};
    char buf[1024];
    offset_lines(c, 1.0, 200, &g, &a);
    CHECK(ob_diagnose(c, 1.0, &a, &OB_FRAME_IDENTITY, "f", buf, sizeof buf) == 1, "found: %s", buf);
    ob_frame m;
    double e = 1.0;
    if (suggested(buf, &m) == 0) { /* m after g is the identity, to the polyline's error */
        const ob_frame id = ob_frame_mul(&m, &g);
        e = 0.0;
        for (int k = 0; k < 6; k++)
            e = fmax(e, fabs(id.m[k] - OB_FRAME_IDENTITY.m[k]));
    }
    CHECK(e < 1e-3, "the inverse rotation (%g): %s", e, buf);
    CHECK(strstr(buf, "then y = -y") == NULL, "no reflection: %s", buf);
    ob_approx_free(&a);
}

static void test_nothing(const ob_curve *c)
{
    ob_approx a = {0};
    char buf[1024];
    const double xy[2][2] = {{40, 40}, {41, 40.5}};
    ob_bez_from_points(&ob_approx_add(&a)->approx, 1, xy);
    /* one line is a similarity of any stretch of the offset: the two-sided residual refuses it */
    CHECK(ob_diagnose(c, 1.0, &a, &OB_FRAME_IDENTITY, "f", buf, sizeof buf) == 0 && buf[0] == '\0', "%s", buf);
    ob_approx_free(&a);
}

int main(void)
{
    const ob_curve c = curve();
    const double size = ob_joint_size(&c, 1.0);
    CHECK(!ob_diag_far(&c, 1.0, 0.0099 * size) && ob_diag_far(&c, 1.0, 0.0101 * size) && ob_diag_far(&c, 1.0, NAN),
          "far: over 1e-2 of the size, or not a number");
    test_sign(&c);
    test_cad_frame(&c);
    test_rotation(&c);
    test_nothing(&c);
    return check_done();
}
