/*
 * test_approx.c - the export writers and the approximation readers of
 * measure (host/io/export*.c, host/io/approx_read*.c) and the projection
 * match (host/measure/match.c):
 *   - pieces written as JSON and .curves read back bit for bit (homogeneous
 *     points, base links), as DXF to the rounding of x = w x / w;
 *   - a piece without a link on a straight base is matched to the range its
 *     ends lie over (known by construction), reversed when it runs backwards,
 *     and its error there is that of the exact offset line (0);
 *   - mutated files never crash a reader, and every error names the file;
 *   - the DXF reader's LINE, ARC, CIRCLE, ELLIPSE and LWPOLYLINE (exact
 *     pieces: every point on the circle or ellipse to round-off, joints bit
 *     for bit, the direction and the object coordinate system's mirror),
 *     the entities it skips named with their count and first line, and
 *     its errors (hand-written files).
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/io/approx_read.h"
#include "host/io/export.h"
#include "host/measure/measure.h"

typedef int (*wfn)(FILE *, const ob_job *, const ob_approx *);
static int w_json(FILE *f, const ob_job *j, const ob_approx *a) { return ob_export_write_json(f, j, 256, a); }

/* The text a writer makes of a. */
static char *write_mem(wfn w, const ob_job *j, const ob_approx *a, size_t *len)
{
    char *buf = NULL;
    FILE *f = open_memstream(&buf, len);
    w(f, j, a);
    fclose(f);
    return buf;
}

/* Two pieces: a cubic and a rational quadratic, linked to base segment 0. */
static void sample_approx(ob_approx *a)
{
    memset(a, 0, sizeof *a);
    ob_apiece *p = ob_approx_add(a);
    const double xy[4][2] = {{0.1, 0.2}, {0.30000000000000004, 1.0 / 3.0}, {0.7, -2e-7}, {1.0, 0.5}};
    ob_bez_from_points(&p->approx, 3, xy);
    p->has_base = 1, p->seg = 0, p->a = 0.0, p->b = 0.5, p->t0 = 0.0, p->t1 = 0.3141592653589793;
    p = ob_approx_add(a);
    p->approx.deg = 2;
    ob_bez_set(&p->approx, 0, 1.0, 0.5, 1.0);
    ob_bez_set(&p->approx, 1, 1.5, 0.7, 0.7071067811865476);
    ob_bez_set(&p->approx, 2, 2.0, 0.5, 1.0);
    p->has_base = 1, p->seg = 0, p->a = 0.0, p->b = 0.5, p->t0 = 0.3141592653589793, p->t1 = 1.0;
    a->same_param = 1;
}

static void test_round_trip(const ob_job *j)
{
    ob_approx a;
    sample_approx(&a);
    const struct { const char *name; wfn w; int exact; } fmts[] = {
        {"t.json", w_json, 1}, {"t.curves", ob_export_write_curves, 1}, {"t.dxf", ob_export_write_dxf, 0}};
    for (int f = 0; f < 3; f++) {
        size_t len;
        char *text = write_mem(fmts[f].w, j, &a, &len);
        ob_err err = {""};
        ob_approx b = {0};
        const ob_afmt fm = ob_approx_format(fmts[f].name, text, len);
        const int rc = fm == OB_AFMT_JSON ? ob_approx_read_json(text, len, fmts[f].name, &b, &err)
                       : fm == OB_AFMT_DXF ? ob_approx_read_dxf(text, len, fmts[f].name, &b, &err)
                                           : ob_approx_read_curves(text, len, fmts[f].name, &b, &err);
        CHECK(rc == 0 && b.n == 2 && b.same_param == 1, "%s: rc %d, %d pieces: %s", fmts[f].name, rc, b.n, err.msg);
        CHECK(b.have_job && strcmp(b.job_curve, j->curve->id) == 0 && b.job_d == j->d,
              "%s: the exporting job (have %d, curve '%s', d %.17g) did not come back", fmts[f].name, b.have_job,
              b.job_curve, b.job_d);
        for (int k = 0; k < b.n && k < 2; k++) {
            const ob_apiece *p = &a.v[k], *q = &b.v[k];
            CHECK(q->has_base && q->seg == p->seg && q->a == p->a && q->b == p->b && q->t0 == p->t0 && q->t1 == p->t1,
                  "%s piece %d: the link did not come back exactly", fmts[f].name, k);
            CHECK(q->approx.deg == p->approx.deg && q->approx.rational == p->approx.rational, "%s piece %d: degree",
                  fmts[f].name, k);
            double worst = 0.0;
            for (int i = 0; i <= p->approx.deg; i++)
                for (int c = 0; c < 3; c++)
                    worst = fmax(worst, fabs(q->approx.h[i][c] - p->approx.h[i][c]));
            CHECK(fmts[f].exact ? worst == 0.0 : worst <= 4e-16, "%s piece %d: points differ by %.3g", fmts[f].name,
                  k, worst);
        }
        ob_approx_free(&b);
        free(text);
    }
    ob_approx_free(&a);
}

/* The job named in an export's text, read back from its stem: ids that
 * hold "__d", "__" and '/', a method name starting with d, none at all. */
static void test_parse_job(void)
{
    static const struct { const char *text, *curve; double d; } ok[] = {
        {"offbench export: a__d1__x__d-1e-05__tiller__tol0.001; piece 0 of 2", "a__d1__x", -1e-05},
        {"the approximation of job dir~c__d0.25__dummy__tol1e-3, max_err 1", "dir/c", 0.25},
        {"offbench export: c__d3__d__tol0.1", "c", 3},
    };
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        ob_approx a = {0};
        const int r = ob_approx_parse_job(ok[i].text, &a);
        CHECK(r == 1 && strcmp(a.job_curve, ok[i].curve) == 0 && a.job_d == ok[i].d,
              "'%s': %d, curve '%s', d %.17g", ok[i].text, r, a.job_curve, a.job_d);
    }
    static const char *const bad[] = {"offbench piece 0 base segment 1", "offbench export: c__tiller__tol0.1",
                                      "offbench export: c__dx__tiller__tol0.1", "of job c__d1__tiller"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ob_approx a = {0};
        CHECK(ob_approx_parse_job(bad[i], &a) == 0 && !a.have_job, "'%s' named a job", bad[i]);
    }
}

/* A straight base from (0,0) to (2,0), d = 0.5: the exact offset is the line
 * y = 0.5; a piece on it over x in [0.5, 1.5], given backwards. */
static void test_match(void)
{
    ob_bez seg;
    const double base[2][2] = {{0, 0}, {2, 0}};
    ob_bez_from_points(&seg, 1, base);
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "line");
    c.nseg = 1;
    c.seg = &seg;
    ob_approx a = {0};
    ob_apiece *p = ob_approx_add(&a);
    const double pts[3][2] = {{1.5, 0.5}, {1.0, 0.5}, {0.5, 0.5}};
    ob_bez_from_points(&p->approx, 2, pts);
    a.same_param = 1;
    ob_err err = {""};
    const int rc = ob_approx_match(&c, 0.5, &a, "m.curves", &err);
    CHECK(rc == 0 && p->has_base && p->seg == 0, "match: %s", err.msg);
    CHECK_NEAR(p->a, 0.25, 1e-12, "matched start");
    CHECK_NEAR(p->b, 0.75, 1e-12, "matched end");
    CHECK(p->t0 == 0.0 && p->t1 == 1.0 && a.same_param == 0, "matched fit range [0, 1], no shared parameter");
    double q[2];
    ob_bez_point(&p->approx, 0.0, q);
    CHECK(q[0] == 0.5 && q[1] == 0.5, "the piece was reversed to run with the base: starts at (%g, %g)", q[0], q[1]);
    ob_mres r;
    CHECK(ob_approx_measure(&c, 0.5, &a, OB_METRIC_HAUSDORFF, 256, "m.curves", &r, &err) == 0 && r.applies &&
              r.err <= 1e-15,
          "hausdorff error of the exact offset line: %.3g (%s)", r.err, err.msg);
    CHECK(ob_approx_measure(&c, 0.5, &a, OB_METRIC_RADIAL, 256, "m.curves", &r, &err) == 0 && !r.applies,
          "radial does not apply to a matched piece");
    /* both ends on one offset point */
    const double dot[2][2] = {{1.0, 0.5}, {1.0, 0.5}};
    p->has_base = 0;
    ob_bez_from_points(&p->approx, 1, dot);
    CHECK(ob_approx_match(&c, 0.5, &a, "m.curves", &err) != 0 && strstr(err.msg, "m.curves:0: piece 0"),
          "a point-like piece is refused: %s", err.msg);
    ob_approx_free(&a);
}

/* An error that is not finite is never ok (ob_err_can_pass): measure's
 * status of a piece the bound metric cannot bound (a weight < 0 or 0 of a
 * rational piece) is fail with a reason; positive weights stay ok. */
static void test_not_finite(void)
{
    CHECK(!ob_err_can_pass(INFINITY) && !ob_err_can_pass(-INFINITY) && !ob_err_can_pass(NAN), "inf, -inf, nan");
    CHECK(ob_err_can_pass(0.0) && ob_err_can_pass(1e-300) && ob_err_can_pass(1.7e308), "finite errors pass");
    const ob_mres na = {0, "why", NAN, -1, -1, NAN, 0, ""}, ok = {1, "", 0.1, 0, 0, 0.5, 1, ""},
                  bad = {1, "x", INFINITY, 0, 0, 0.5, 0, ""};
    CHECK(!strcmp(ob_mres_status(&na), "n/a") && !strcmp(ob_mres_status(&ok), "ok") &&
              !strcmp(ob_mres_status(&bad), "fail"),
          "statuses %s %s %s", ob_mres_status(&na), ob_mres_status(&ok), ob_mres_status(&bad));

    const double base_xy[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};
    ob_bez seg;
    ob_bez_from_points(&seg, 3, base_xy);
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "ex1");
    c.nseg = 1;
    c.seg = &seg;
    static const double weights[][4] = {{1, -1, 1, 1}, {1, 1, -0.5, 1}, {-1, 1, 1, 1}, {1, 1, 1, 1}, {1, 2, 0.5, 1}};
    for (size_t w = 0; w < sizeof weights / sizeof weights[0]; w++) {
        ob_approx a = {0};
        ob_apiece *p = ob_approx_add(&a);
        p->approx.deg = 3;
        for (int i = 0; i < 4; i++)  /* the base moved by about d = 1 along y */
            ob_bez_set(&p->approx, i, base_xy[i][0], base_xy[i][1] + 1.0, weights[w][i]);
        p->has_base = 1, p->seg = 0, p->a = 0.0, p->b = 1.0, p->t0 = 0.0, p->t1 = 1.0;
        a.same_param = 1;
        const int positive = weights[w][0] > 0 && weights[w][1] > 0 && weights[w][2] > 0 && weights[w][3] > 0;
        for (int m = 0; m < OB_METRIC_COUNT; m++) {
            ob_mres r;
            ob_err err = {""};
            if (ob_approx_measure(&c, 1.0, &a, (ob_metric)m, 64, "w.json", &r, &err) != 0)
                continue;  /* a metric that cannot measure it says so as an error */
            CHECK(r.ok == (r.applies && isfinite(r.err)), "weights %zu, %s: ok %d with err %g", w,
                  ob_metric_name((ob_metric)m), r.ok, r.err);
            CHECK(r.ok || !r.applies || (!strcmp(ob_mres_status(&r), "fail") && strstr(r.why, "not finite")),
                  "weights %zu, %s: status %s, why '%s'", w, ob_metric_name((ob_metric)m), ob_mres_status(&r),
                  r.why);
            if (m == OB_METRIC_BOUND && positive)
                CHECK(r.ok, "weights %zu: bound of positive weights is finite: %g", w, r.err);
            if (m == OB_METRIC_BOUND && w == 0)  /* the case of the issue: bound,ok,inf */
                CHECK(isinf(r.err) && !r.ok && !strcmp(ob_mres_status(&r), "fail"),
                      "weights %zu: bound gives %g, status %s", w, r.err, ob_mres_status(&r));
        }
        ob_approx_free(&a);
    }
}

static unsigned long long rng = 88172645463325252ull;
static unsigned next_rand(void)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (unsigned)(rng >> 16);
}

/* Mutated copies of every format: 0 or an error naming the file, no crash. */
static void test_hostile(const ob_job *j)
{
    ob_approx a;
    sample_approx(&a);
    const wfn ws[3] = {w_json, ob_export_write_curves, ob_export_write_dxf};
    const char *names[3] = {"h.json", "h.curves", "h.dxf"};
    int bad_msgs = 0, runs = 0;
    static const char alphabet[] = "{}[],:\"0123456789.-e \n\r\tabcnulltruefalse";
    for (int f = 0; f < 3; f++) {
        size_t len;
        char *text = write_mem(ws[f], j, &a, &len);
        for (int it = 0; it < 1500; it++) {
            char *m = malloc(len + 1);
            memcpy(m, text, len + 1);
            const int edits = 1 + (int)(next_rand() % 4);
            for (int e = 0; e < edits; e++)
                m[next_rand() % len] = alphabet[next_rand() % (sizeof alphabet - 1)];
            const size_t cut = next_rand() % 8 == 0 ? next_rand() % len : len;
            ob_approx b = {0};
            ob_err err = {""};
            const int rc = f == 0 ? ob_approx_read_json(m, cut, names[f], &b, &err)
                           : f == 1 ? ob_approx_read_curves(m, cut, names[f], &b, &err)
                                    : ob_approx_read_dxf(m, cut, names[f], &b, &err);
            bad_msgs += rc != 0 && strncmp(err.msg, names[f], strlen(names[f])) != 0;
            bad_msgs += rc == 0 && b.n > 0 && b.v[0].approx.deg < 1;
            runs++;
            ob_approx_free(&b);
            free(m);
        }
        free(text);
    }
    CHECK(bad_msgs == 0, "%d of %d mutated files gave an error not naming the file", bad_msgs, runs);
    ob_approx_free(&a);
}

/* Numbers out of every range where a count or degree is expected. */
static void test_huge_numbers(void)
{
    const char *json = "{\"pieces\": [{\"degree\": 1e300, \"points\": [[0, 0], [1, 1]]}]}";
    const char *json2 = "{\"pieces\": [{\"degree\": 1, \"points\": [[0, 0], [1, 1]], \"seg\": 1e300, "
                        "\"span\": [0, 1], \"t\": [0, 1]}]}";
    const char *dxf = "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\n1e300\n0\nENDSEC\n0\nEOF\n";
    ob_err err = {""};
    ob_approx b = {0};
    CHECK(ob_approx_read_json(json, strlen(json), "h.json", &b, &err) != 0 && strstr(err.msg, "h.json:1:"),
          "degree 1e300: %s", err.msg);
    ob_approx_free(&b);
    CHECK(ob_approx_read_json(json2, strlen(json2), "h.json", &b, &err) != 0 && strstr(err.msg, "base link"),
          "seg 1e300: %s", err.msg);
    ob_approx_free(&b);
    CHECK(ob_approx_read_dxf(dxf, strlen(dxf), "h.dxf", &b, &err) != 0 && strstr(err.msg, "h.dxf:8: group 71"),
          "DXF degree 1e300: %s", err.msg);
    ob_approx_free(&b);
}

/* ---- DXF entities besides SPLINE ------------------------------------------------ */

/* Reads DXF text (lines joined by '\n') into a; the reader's status. */
static int dxf(const char *text, ob_approx *a, ob_err *err)
{
    memset(a, 0, sizeof *a);
    return ob_approx_read_dxf(text, strlen(text), "h.dxf", a, err);
}

/* The largest |distance from c - r| over 65 points of every piece. */
static double off_circle(const ob_approx *a, double cx, double cy, double r)
{
    double worst = 0.0;
    for (int k = 0; k < a->n; k++)
        for (int i = 0; i <= 64; i++) {
            double p[2];
            ob_bez_point(&a->v[k].approx, i / 64.0, p);
            worst = fmax(worst, fabs(hypot(p[0] - cx, p[1] - cy) - r));
        }
    return worst;
}

/* 1 when every piece starts where the one before ends, bit for bit (and
 * the last ends where the first starts, when closed). */
static int joined(const ob_approx *a, int closed)
{
    int ok = 1;
    for (int k = 1; k <= a->n - !closed; k++) {
        const ob_bez *p = &a->v[k - 1].approx, *q = &a->v[k % a->n].approx;
        ok &= p->h[p->deg][0] / p->h[p->deg][2] == q->h[0][0] / q->h[0][2] &&
              p->h[p->deg][1] / p->h[p->deg][2] == q->h[0][1] / q->h[0][2];
    }
    return ok;
}

static void point_at(const ob_approx *a, int k, double t, double p[2]) { ob_bez_point(&a->v[k].approx, t, p); }

static void test_dxf_line_arc(void)
{
    ob_approx a;
    ob_err err = {""};
    int rc = dxf("0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n0.5\n20\n-1\n30\n0\n11\n2\n21\n3\n31\n0\n"
                 "0\nENDSEC\n0\nEOF\n", &a, &err);
    CHECK(rc == 0 && a.n == 1 && a.v[0].approx.deg == 1 && !a.v[0].approx.rational && a.v[0].line == 6 &&
              a.v[0].approx.h[0][0] == 0.5 && a.v[0].approx.h[0][1] == -1 && a.v[0].approx.h[1][0] == 2 &&
              a.v[0].approx.h[1][1] == 3 && !a.v[0].has_base && !a.same_param,
          "LINE: one piece of degree 1 from (0.5, -1) to (2, 3), at its line (%s)", err.msg);
    ob_approx_free(&a);
    /* 270 degrees counterclockwise from 30: three pieces of 90 */
    rc = dxf("0\nARC\n10\n1\n20\n2\n40\n3\n50\n30\n51\n300\n", &a, &err);
    double p[2];
    CHECK(rc == 0 && a.n == 3 && joined(&a, 0), "ARC 30..300: 3 joined pieces (%d: %s)", a.n, err.msg);
    CHECK(rc == 0 && off_circle(&a, 1, 2, 3) <= 1e-14, "ARC: on the circle to %.2g", off_circle(&a, 1, 2, 3));
    for (int k = 0; k < a.n && rc == 0; k++)
        CHECK(a.v[k].approx.deg == 2 && a.v[k].approx.rational && fabs(a.v[k].approx.h[1][2] - sqrt(0.5)) < 1e-15,
              "ARC piece %d: rational quadratic, middle weight cos 45", k);
    if (rc == 0 && a.n == 3) {
        point_at(&a, 0, 0.0, p);
        CHECK(fabs(p[0] - (1 + 3 * cos(OB_PI / 6))) < 1e-15 && fabs(p[1] - (2 + 3 * sin(OB_PI / 6))) < 1e-15,
              "ARC starts at 30 degrees (%g, %g)", p[0], p[1]);
        point_at(&a, 2, 1.0, p);
        CHECK(fabs(p[0] - (1 + 3 * cos(OB_PI * 300 / 180))) < 1e-14 &&
                  fabs(p[1] - (2 + 3 * sin(OB_PI * 300 / 180))) < 1e-14,
              "ARC ends at 300 degrees (%g, %g)", p[0], p[1]);
        point_at(&a, 1, 0.5, p);
        CHECK(fabs(atan2(p[1] - 2, p[0] - 1) - OB_PI * 165 / 180) < 1e-14, "ARC runs counterclockwise: 165 degrees "
              "in the middle");
    }
    ob_approx_free(&a);
    /* across 0: 350 to 10 is 20 degrees, one piece through (1 + 3, 2) */
    rc = dxf("0\nARC\n10\n1\n20\n2\n40\n3\n50\n350\n51\n10\n", &a, &err);
    if (rc == 0 && a.n == 1)
        point_at(&a, 0, 0.5, p);
    CHECK(rc == 0 && a.n == 1 && fabs(p[0] - 4) < 1e-15 && fabs(p[1] - 2) < 1e-15,
          "ARC 350..10: one piece through angle 0 (%d: %s)", a.n, err.msg);
    ob_approx_free(&a);
    /* a whole circle: four quarters, closed bit for bit */
    rc = dxf("0\nCIRCLE\n10\n-1\n20\n0.25\n40\n0.75\n", &a, &err);
    CHECK(rc == 0 && a.n == 4 && joined(&a, 1) && off_circle(&a, -1, 0.25, 0.75) <= 1e-15,
          "CIRCLE: 4 pieces, closed, on the circle (%d: %s)", a.n, err.msg);
    ob_approx_free(&a);
    /* extrusion -z: the object coordinate system's x is -x */
    rc = dxf("0\nARC\n10\n1\n20\n0\n40\n1\n50\n0\n51\n90\n210\n0\n220\n0\n230\n-1\n", &a, &err);
    double q[2];
    if (rc == 0 && a.n == 1)
        point_at(&a, 0, 0.0, p), point_at(&a, 0, 1.0, q);
    CHECK(rc == 0 && a.n == 1 && fabs(p[0] + 2) < 1e-15 && fabs(p[1]) < 1e-15 && fabs(q[0] + 1) < 1e-15 &&
              fabs(q[1] - 1) < 1e-15 && off_circle(&a, -1, 0, 1) < 1e-15,
          "ARC under extrusion -z: mirrored, from (-2, 0) to (-1, 1) (%s)", err.msg);
    ob_approx_free(&a);
}

static void test_dxf_ellipse(void)
{
    ob_approx a;
    ob_err err = {""};
    /* major axis 2 along x, minor 0.5 of it: x^2 / 4 + y^2 = 1 */
    int rc = dxf("0\nELLIPSE\n10\n0\n20\n0\n11\n2\n21\n0\n40\n0.5\n41\n0\n42\n6.283185307179586\n", &a, &err);
    double worst = 0.0, p[2];
    for (int k = 0; k < a.n; k++)
        for (int i = 0; i <= 64; i++) {
            point_at(&a, k, i / 64.0, p);
            worst = fmax(worst, fabs(p[0] * p[0] / 4 + p[1] * p[1] - 1));
        }
    CHECK(rc == 0 && a.n == 4 && joined(&a, 1) && worst < 1e-14, "ELLIPSE: 4 pieces, closed, on it to %.2g (%s)",
          worst, err.msg);
    if (rc == 0 && a.n == 4)
        point_at(&a, 0, 1.0, p);
    CHECK(rc == 0 && a.n == 4 && fabs(p[0]) < 1e-15 && fabs(p[1] - 1) < 1e-15,
          "ELLIPSE: the minor axis (0.5 of 2) on the major's left: (0, 1) at pi/2 (%g, %g)", p[0], p[1]);
    ob_approx_free(&a);
    rc = dxf("0\nELLIPSE\n10\n0\n20\n0\n11\n2\n21\n0\n40\n0.5\n41\n0\n42\n3.141592653589793\n"
             "210\n0\n220\n0\n230\n-1\n", &a, &err);
    if (rc == 0 && a.n == 2)
        point_at(&a, 0, 1.0, p);
    CHECK(rc == 0 && a.n == 2 && fabs(p[0]) < 1e-15 && fabs(p[1] + 1) < 1e-15,
          "half an ELLIPSE under extrusion -z: 2 pieces, the minor axis on the right (%d: %g, %g)", a.n, p[0], p[1]);
    ob_approx_free(&a);
}

static void test_dxf_polyline(void)
{
    ob_approx a;
    ob_err err = {""};
    /* a closed outline: a line, a semicircle (bulge 1) through (2, 1), a
     * line, and the closing line */
    int rc = dxf("0\nLWPOLYLINE\n90\n4\n70\n1\n10\n0\n20\n0\n10\n1\n20\n0\n42\n1\n10\n1\n20\n2\n10\n0\n20\n2\n",
                 &a, &err);
    double p[2];
    CHECK(rc == 0 && a.n == 5 && joined(&a, 1), "LWPOLYLINE: 5 pieces, closed bit for bit (%d: %s)", a.n, err.msg);
    if (rc == 0 && a.n == 5) {
        CHECK(a.v[0].approx.deg == 1 && a.v[1].approx.deg == 2 && a.v[2].approx.deg == 2 && a.v[3].approx.deg == 1 &&
                  a.v[4].approx.deg == 1,
              "LWPOLYLINE: line, two arcs, line, closing line");
        point_at(&a, 1, 1.0, p);
        CHECK(fabs(p[0] - 2) < 1e-15 && fabs(p[1] - 1) < 1e-15, "bulge 1 runs counterclockwise through (2, 1): (%g, %g)",
              p[0], p[1]);
        ob_approx b = {0};
        for (int k = 1; k <= 2; k++)
            ob_approx_add(&b)->approx = a.v[k].approx;
        CHECK(off_circle(&b, 1, 1, 1) < 1e-15, "the semicircle's pieces are on the circle");
        ob_approx_free(&b);
        CHECK(a.v[0].line == 8 && a.v[1].line == 12 && a.v[3].line == 18,
              "each segment at its first vertex's line (%d, %d, %d)", a.v[0].line, a.v[1].line, a.v[3].line);
    }
    ob_approx_free(&a);
    /* bulge -1: clockwise, through (0, 1); bulge 0.5 on a mirrored polyline */
    rc = dxf("0\nLWPOLYLINE\n10\n1\n20\n0\n42\n-1\n10\n1\n20\n2\n", &a, &err);
    if (rc == 0 && a.n == 2)
        point_at(&a, 0, 1.0, p);
    CHECK(rc == 0 && a.n == 2 && fabs(p[0]) < 1e-15 && fabs(p[1] - 1) < 1e-15, "bulge -1: through (0, 1) (%s)", err.msg);
    ob_approx_free(&a);
    rc = dxf("0\nLWPOLYLINE\n210\n0\n220\n0\n230\n-1\n10\n0\n20\n0\n42\n0.41421356237309503\n10\n2\n20\n0\n",
             &a, &err);
    double q[2];
    if (rc == 0 && a.n == 1)
        point_at(&a, 0, 0.0, p), point_at(&a, 0, 1.0, q);
    CHECK(rc == 0 && a.n == 1 && p[0] == 0 && q[0] == -2 && off_circle(&a, -1, 1, sqrt(2.0)) < 1e-15,
          "a quarter circle (bulge tan 22.5) under extrusion -z: from (0, 0) to (-2, 0) about (-1, 1) (%s)", err.msg);
    ob_approx_free(&a);
}

/* An old-style POLYLINE reads as the LWPOLYLINE of its VERTEX entities:
 * the header's point is no vertex; the pieces at their VERTEX's line. */
static void test_dxf_old_polyline(void)
{
    ob_approx a;
    ob_err err = {""};
    const char *t = "0\nPOLYLINE\n10\n7\n20\n7\n70\n1\n0\nVERTEX\n10\n1\n20\n0\n42\n-1\n"
                    "0\nVERTEX\n10\n1\n20\n2\n0\nSEQEND\n";
    int rc = dxf(t, &a, &err);
    double p[2] = {0, 0};
    if (rc == 0 && a.n >= 2)
        point_at(&a, 0, 1.0, p);
    CHECK(rc == 0 && a.n == 3 && fabs(p[0]) < 1e-15 && fabs(p[1] - 1) < 1e-15 && a.v[0].line == 10 &&
              a.v[1].line == 10 && a.v[2].line == 18 && a.v[2].approx.deg == 1,
          "closed POLYLINE of bulge -1: 2 arc pieces through (0, 1), the closing line (n %d, %s)", a.n, err.msg);
    ob_approx_free(&a);
    rc = dxf("0\nPOLYLINE\n0\nVERTEX\n10\n1\n20\n0\n0\nSEQEND\n", &a, &err);
    CHECK(rc == -1 && strstr(err.msg, ":2: POLYLINE with 1 VERTEX entities"), "one VERTEX: refused (%s)", err.msg);
    ob_approx_free(&a);
}

/* The line (from 1) of the first line of text that starts with at. */
static int line_of(const char *text, const char *at)
{
    int line = 1;
    for (const char *p = text; *p; p++) {
        if ((p == text || p[-1] == '\n') && strncmp(p, at, strlen(at)) == 0)
            return line;
        line += *p == '\n';
    }
    return -1;
}

/* Entities that are no pieces are named with their count and first line;
 * a POLYLINE's VERTEX and SEQEND belong to it (a 3D one is skipped); block definitions are not
 * the drawing's. */
static void test_dxf_skipped(void)
{
    ob_approx a;
    ob_err err = {""};
    const char *t = "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n0\nLINE\n10\n0\n20\n0\n11\n1\n21\n1\n0\nENDBLK\n0\nENDSEC\n"
                    "0\nSECTION\n2\nENTITIES\n0\nTEXT\n1\nhi\n0\nLINE\n10\n0\n20\n0\n11\n1\n21\n0\n0\nTEXT\n1\nho\n"
                    "0\nPOLYLINE\n70\n8\n0\nVERTEX\n0\nVERTEX\n0\nSEQEND\n0\nHATCH\n"
                    "0\nARC\n10\n0\n20\n0\n40\n1\n50\n0\n51\n90\n210\n1\n220\n0\n230\n0\n"
                    "0\nLINE\n10\n5\n20\n5\n11\n5\n21\n5\n0\nENDSEC\n0\nEOF\n";
    const int rc = dxf(t, &a, &err);
    CHECK(rc == 0 && a.n == 1 && a.nskipped == 6 && a.nskipped_types == 5, "%d pieces, %d skipped of %d types (%s)",
          a.n, a.nskipped, a.nskipped_types, err.msg);
    static const struct { const char *type, *at; int count; } want[] = {
        {"TEXT", "TEXT\n1\nhi", 2}, {"POLYLINE 3D or mesh", "POLYLINE", 1}, {"HATCH", "HATCH", 1},
        {"ARC off the XY plane", "ARC", 1}, {"LINE of length 0", "LINE\n10\n5", 1}};
    for (int i = 0; i < 5 && rc == 0 && i < a.nskipped_types; i++)
        CHECK(strcmp(a.skipped[i].type, want[i].type) == 0 && a.skipped[i].count == want[i].count &&
                  a.skipped[i].line == line_of(t, want[i].at),
              "skipped %d: %s x %d at line %d (want %s x %d at %d)", i, a.skipped[i].type, a.skipped[i].count,
              a.skipped[i].line, want[i].type, want[i].count, line_of(t, want[i].at));
    ob_approx_free(&a);
    /* more types than the table holds: counted in nskipped */
    ob_approx b = {0};
    char name[16];
    for (int i = 0; i < OB_APPROX_SKIP_TYPES + 3; i++) {
        snprintf(name, sizeof name, "T%d", i);
        ob_approx_note_skip(&b, name, i + 1);
    }
    CHECK(b.nskipped == OB_APPROX_SKIP_TYPES + 3 && b.nskipped_types == OB_APPROX_SKIP_TYPES,
          "%d skipped, %d types kept", b.nskipped, b.nskipped_types);
}

/* Malformed entities: exit with FILE:LINE. */
static void test_dxf_errors(void)
{
    static const struct { const char *text, *want; } bad[] = {
        {"0\nARC\n10\n0\n20\n0\n50\n0\n51\n90\n", "h.dxf:2: ARC without group 40"},
        {"0\nCIRCLE\n10\n0\n20\n0\n40\n-1\n", "h.dxf:2: CIRCLE of radius -1"},
        {"0\nLINE\n10\n0\n20\n0\n11\n1\n", "h.dxf:2: LINE without group 21"},
        {"0\nLINE\n10\n0\n20\nx\n", "h.dxf:6: group 20: 'x' is not a number"},
        {"0\nELLIPSE\n10\n0\n20\n0\n11\n1\n21\n0\n40\n0\n", "h.dxf:2: ELLIPSE with axis ratio 0"},
        {"0\nLWPOLYLINE\n90\n3\n10\n0\n20\n0\n10\n1\n20\n0\n", "h.dxf:2: LWPOLYLINE with 2 vertices (group 90 announces 3"},
        {"0\nLWPOLYLINE\n10\n0\n20\n0\n", "h.dxf:2: LWPOLYLINE with 1 vertices"},
        {"0\nLWPOLYLINE\n42\n1\n10\n0\n20\n0\n", "h.dxf:4: LWPOLYLINE: group 42 before the first vertex"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        ob_approx a;
        ob_err err = {""};
        CHECK(dxf(bad[i].text, &a, &err) != 0 && strstr(err.msg, bad[i].want), "bad DXF %zu: '%s' (want '%s')", i,
              err.msg, bad[i].want);
        ob_approx_free(&a);
    }
}

int main(void)
{
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "a/b");
    ob_job j;
    memset(&j, 0, sizeof j);
    j.curve = &c;
    j.d = 0.25;
    j.tol = 1e-3;
    j.method = ob_method_find("tiller");
    j.max_err = 0.000123;
    char stem[400];
    ob_export_stem(stem, sizeof stem, &j);
    CHECK(strcmp(stem, "a~b__d0.25__tiller__tol0.001") == 0, "stem %s", stem);
    test_round_trip(&j);
    test_parse_job();
    test_match();
    test_not_finite();
    test_hostile(&j);
    test_huge_numbers();
    test_dxf_line_arc();
    test_dxf_ellipse();
    test_dxf_polyline();
    test_dxf_old_polyline();
    test_dxf_skipped();
    test_dxf_errors();
    return check_done();
}
