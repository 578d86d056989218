/*
 * test_frame.c - measure's drawing frames (host/measure/frame.h, issue 50
 * item 2):
 *   - --transform's list parsing: exactly n finite numbers, words, NaN,
 *     infinities, a wrong count refused;
 *   - a singular or non-finite matrix refused, a reflection accepted;
 *   - composing (a after b) and mapping a point;
 *   - applying a map to a rational piece maps its curve point for point
 *     and keeps its weights;
 *   - the Procrustes fit recovers a known similarity, with and without a
 *     reflection, from exact pairs, and its text reads back.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "host/measure/frame.h"
#include "methods/core/curve.h"

static void test_parse(void)
{
    double v[6];
    CHECK(ob_frame_parse_list("1,2,3,4,5,6", v, 6) == 0 && v[0] == 1 && v[5] == 6, "six numbers");
    CHECK(ob_frame_parse_list("25.4,-1e-3", v, 2) == 0 && v[0] == 25.4 && v[1] == -1e-3, "two numbers");
    CHECK(ob_frame_parse_list("1,2,3,4,5", v, 6) != 0, "five of six");
    CHECK(ob_frame_parse_list("1,2,3,4,5,6,7", v, 6) != 0, "seven of six");
    CHECK(ob_frame_parse_list("1,2,x,4,5,6", v, 6) != 0, "a word");
    CHECK(ob_frame_parse_list("1,nan,3,4,5,6", v, 6) != 0, "NaN");
    CHECK(ob_frame_parse_list("inf,2", v, 2) != 0, "inf");
    CHECK(ob_frame_parse_list("1,,2", v, 3) != 0, "an empty item");
    CHECK(ob_frame_parse_list("", v, 1) != 0, "nothing");
}

static void test_refuse(void)
{
    CHECK(ob_frame_refuse(&OB_FRAME_IDENTITY) == NULL, "identity");
    const ob_frame flip = {{1, 0, 0, -1, 0, 0}};
    CHECK(ob_frame_refuse(&flip) == NULL && ob_frame_det(&flip) < 0, "a reflection is usable");
    const ob_frame sing = {{1, 2, 2, 4, 0, 0}}, zero = {{0, 0, 0, 0, 1, 1}};
    CHECK(ob_frame_refuse(&sing) != NULL && ob_frame_refuse(&zero) != NULL, "singular");
    const ob_frame nanm = {{1, 0, 0, 1, NAN, 0}}, infm = {{INFINITY, 0, 0, 1, 0, 0}};
    CHECK(ob_frame_refuse(&nanm) != NULL && ob_frame_refuse(&infm) != NULL, "not finite");
    const ob_frame tiny = {{1e-9, 0, 0, 1e-9, 0, 0}};
    CHECK(ob_frame_refuse(&tiny) == NULL, "a small uniform scale is not singular");
}

static void test_mul_point(void)
{
    const ob_frame s = {{2, 0, 0, 3, 0, 0}}, t = {{1, 0, 0, 1, 5, -1}};
    const ob_frame ts = ob_frame_mul(&t, &s); /* scale, then translate */
    double p[2] = {1, 1}, q[2];
    ob_frame_point(&ts, p, q);
    CHECK(q[0] == 7 && q[1] == 2, "translate after scale: (%g, %g)", q[0], q[1]);
    const ob_frame st = ob_frame_mul(&s, &t);
    ob_frame_point(&st, p, q);
    CHECK(q[0] == 12 && q[1] == 0, "scale after translate: (%g, %g)", q[0], q[1]);
}

static void test_apply(void)
{
    ob_approx a = {0};
    ob_apiece *p = ob_approx_add(&a);
    ob_bez *b = &p->approx;
    b->deg = 2;
    ob_bez_set(b, 0, 1, 0, 1);
    ob_bez_set(b, 1, 1, 1, sqrt(0.5));
    ob_bez_set(b, 2, 0, 1, 1);
    const ob_bez before = *b;
    const ob_frame f = {{0, 25.4, -25.4, 0, 3, 4}}; /* rotate by 90 degrees, scale, translate */
    ob_frame_apply(&f, &a);
    double worst = 0.0;
    for (int i = 0; i <= 10; i++) {
        double u[2], v[2], w[2];
        ob_bez_point(&before, i / 10.0, u);
        ob_frame_point(&f, u, w);
        ob_bez_point(b, i / 10.0, v);
        worst = fmax(worst, hypot(v[0] - w[0], v[1] - w[1]));
    }
    CHECK(worst < 1e-12, "the mapped piece is the map of the piece (%g)", worst);
    CHECK(ob_bez_weight(b, 1) == ob_bez_weight(&before, 1) && b->rational, "weights kept");
    ob_approx_free(&a);
}

static void test_fit(int reflect)
{
    const double th = 0.7, s = 3.5;
    const double sy = reflect ? -1.0 : 1.0;
    const ob_frame g = {{s * cos(th), s * sin(th), -s * sin(th) * sy, s * cos(th) * sy, -2.0, 10.0}};
    double p[7][2], q[7][2];
    for (int i = 0; i < 7; i++) {
        p[i][0] = cos(i * 0.9) + 0.1 * i;
        p[i][1] = sin(i * 1.3) * 0.5;
        ob_frame_point(&g, p[i], q[i]);
    }
    ob_frame f;
    CHECK(ob_similarity_fit((const double (*)[2])p, (const double (*)[2])q, 7, reflect, &f) == 0, "fit");
    double e = 0.0;
    for (int k = 0; k < 6; k++)
        e = fmax(e, fabs(f.m[k] - g.m[k]));
    CHECK(e < 1e-12, "reflect %d: the fit is the similarity (%g)", reflect, e);
    char txt[200];
    ob_frame_text(&f, txt, sizeof txt);
    ob_frame back;
    CHECK(ob_frame_parse_list(txt, back.m, 6) == 0 && fabs(back.m[0] - f.m[0]) < 1e-8, "text reads back: %s", txt);
    /* the wrong handedness fits worse */
    ob_frame h;
    ob_similarity_fit((const double (*)[2])p, (const double (*)[2])q, 7, !reflect, &h);
    double r = 0.0;
    for (int i = 0; i < 7; i++) {
        double m[2];
        ob_frame_point(&h, p[i], m);
        r = fmax(r, hypot(m[0] - q[i][0], m[1] - q[i][1]));
    }
    CHECK(r > 0.1, "reflect %d: the other handedness leaves a residual (%g)", reflect, r);
    const double same[3][2] = {{1, 1}, {1, 1}, {1, 1}};
    CHECK(ob_similarity_fit(same, (const double (*)[2])q, 3, reflect, &f) != 0, "coincident points refused");
}

int main(void)
{
    test_parse();
    test_refuse();
    test_mul_point();
    test_apply();
    test_fit(0);
    test_fit(1);
    return check_done();
}
