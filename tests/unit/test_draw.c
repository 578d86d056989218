/*
 * test_draw.c - the pieces behind `draw` and `trace`: SVG text escaping and
 * the document writer (host/view/svg.c), bounding boxes, and the job view
 * (host/view/jobview.c): the refitted pieces tile the curve and reproduce the run,
 * and the pointwise error of each metric agrees with an independent
 * computation (testlib's reference evaluation, dense polylines) and stays
 * below the run's max_err.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/diag.h"
#include "host/view/jobview.h"
#include "host/view/svg.h"
#include "tests/testlib.h"

/* ---- escaping -------------------------------------------------------------- */

static void test_escape(void)
{
    char buf[256];
    size_t n = ob_svg_escape(buf, sizeof buf, "a&b<c>\"d'e");
    CHECK(strcmp(buf, "a&amp;b&lt;c&gt;&quot;d&apos;e") == 0 && n == strlen(buf), "escaped: %s (%zu)", buf, n);
    n = ob_svg_escape(buf, sizeof buf, "x\001y\tz\n\x7f\xc3\xa9");
    CHECK(strcmp(buf, "x?y\tz\n\x7f\xc3\xa9") == 0, "control characters become '?', tab, newline and UTF-8 stay: %s", buf);
    n = ob_svg_escape(buf, sizeof buf, "");
    CHECK(n == 0 && buf[0] == '\0', "empty text");
    /* truncation keeps whole entities and reports the full length */
    n = ob_svg_escape(buf, 4, "&x");
    CHECK(n == 6 && strcmp(buf, "") == 0, "no room for '&amp;': '%s' (%zu)", buf, n);
    n = ob_svg_escape(buf, 6, "&x");
    CHECK(n == 6 && strcmp(buf, "&amp;") == 0, "room for the entity only: '%s'", buf);
    n = ob_svg_escape(buf, 7, "&x");
    CHECK(n == 6 && strcmp(buf, "&amp;x") == 0, "room for all: '%s'", buf);
    n = ob_svg_escape(buf, 3, "abcdef");
    CHECK(n == 6 && strcmp(buf, "ab") == 0, "plain text truncated: '%s'", buf);
    n = ob_svg_escape(buf, 4, "ab<c");
    CHECK(n == 7 && strcmp(buf, "ab") == 0, "nothing after a piece that did not fit: '%s'", buf);
}

/* ---- bounding boxes ----------------------------------------------------------- */

static void test_bbox(void)
{
    ob_bbox b;
    ob_bbox_init(&b);
    CHECK(b.empty && ob_bbox_size(&b) == 0.0, "a new box is empty");
    ob_bbox_add(&b, NAN, 1.0);
    ob_bbox_add(&b, 1.0, INFINITY);
    CHECK(b.empty, "non-finite points are ignored");
    ob_bbox_add(&b, 1.0, 2.0);
    ob_bbox_add(&b, -3.0, 5.0);
    ob_bbox_add(&b, 0.0, -1.0);
    CHECK(!b.empty && b.xmin == -3 && b.xmax == 1 && b.ymin == -1 && b.ymax == 5, "box [%g,%g]x[%g,%g]", b.xmin,
          b.xmax, b.ymin, b.ymax);
    CHECK(ob_bbox_size(&b) == 6.0, "size is the larger side");
    ob_bbox_grow(&b, 0.5);
    CHECK(b.xmin == -3.5 && b.xmax == 1.5 && b.ymin == -1.5 && b.ymax == 5.5, "grow");
    double p[2] = {100.0, -100.0}, q[2] = {NAN, 0.0}, r[2] = {0.25, 0.5};
    ob_bbox_clamp(&b, p);
    ob_bbox_clamp(&b, q);
    ob_bbox_clamp(&b, r);
    CHECK(p[0] == 1.5 && p[1] == -1.5 && q[0] == -3.5 && q[1] == 0.0 && r[0] == 0.25 && r[1] == 0.5,
          "clamp: (%g,%g) (%g,%g) (%g,%g)", p[0], p[1], q[0], q[1], r[0], r[1]);

    ob_bbox flat;
    ob_bbox_init(&flat);
    ob_bbox_add(&flat, 0.0, 1.0);
    ob_bbox_add(&flat, 10.0, 1.0);
    ob_bbox_aspect(&flat, 0.35, 0.8, 1.0);
    CHECK(fabs((flat.ymax - flat.ymin) - 3.5) < 1e-12 && fabs(0.5 * (flat.ymax + flat.ymin) - 1.0) < 1e-12 &&
              flat.xmin == 0.0 && flat.xmax == 10.0,
          "a flat box gets height 0.35 width about its centre: [%g,%g]", flat.ymin, flat.ymax);
    ob_bbox tall;
    ob_bbox_init(&tall);
    ob_bbox_add(&tall, 2.0, 0.0);
    ob_bbox_add(&tall, 2.0, 10.0);
    ob_bbox_aspect(&tall, 0.35, 0.8, 1.0);
    CHECK(fabs((tall.xmax - tall.xmin) - 8.0) < 1e-12 && fabs(0.5 * (tall.xmax + tall.xmin) - 2.0) < 1e-12,
          "a thin box gets width 0.8 height: [%g,%g]", tall.xmin, tall.xmax);
    ob_bbox pt;
    ob_bbox_init(&pt);
    ob_bbox_add(&pt, 3.0, 4.0);
    ob_bbox_aspect(&pt, 0.35, 0.8, 2.0);
    CHECK(pt.xmax - pt.xmin >= 2.0 && pt.ymax - pt.ymin >= 0.7 && pt.xmin < 3.0 && pt.xmax > 3.0,
          "a point gets a size");
}

/* ---- the document writer ------------------------------------------------------ */

static char *slurp(FILE *f)
{
    long n = ftell(f);
    char *s = malloc((size_t)n + 1);
    rewind(f);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n)
        n = 0;
    if (s)
        s[n] = '\0';
    return s;
}

static void test_document(void)
{
    FILE *f = tmpfile();
    if (!f) {
        SKIP("no temporary file");
        return;
    }
    const double pts[3][2] = {{0, 0}, {1.5, -2}, {1e-7, 123456789}};
    ob_svg_begin(f, -1, -2, 10, 5, 800, "a <b> & \"c\"", ".x{fill:none}\n");
    ob_svg_comment(f, "x -- y -");
    ob_svg_clip_rect(f, "plot", 0, 0, 1, 1);
    ob_svg_group(f, "figure", "plot");
    ob_svg_polyline(f, "base", pts, 3);
    ob_svg_polyline(f, "none", pts, 1);
    ob_svg_circle(f, "joint", 1, 2, 0.5);
    ob_svg_rect(f, "ctrlpt", 0, 0, 1, 1);
    ob_svg_line(f, "offset", 0, 0, 1, 1);
    ob_svg_group_end(f);
    ob_svg_text(f, "title", 0, 0, 12, "start", "tol < 1e-3 & d > 0");
    ob_svg_end(f);
    char *s = slurp(f);
    fclose(f);
    if (!s) {
        SKIP("no memory");
        return;
    }
    CHECK(strncmp(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg ", 44) == 0, "XML declaration, then svg");
    CHECK(strstr(s, "viewBox=\"-1 -2 10 5\" width=\"800\" height=\"400\"") != NULL, "viewBox and size in proportion");
    CHECK(strstr(s, "<title>a &lt;b&gt; &amp; &quot;c&quot;</title>") != NULL, "title escaped");
    CHECK(strstr(s, "<style>\n.x{fill:none}\n</style>") != NULL, "style block");
    CHECK(strstr(s, "<!-- x - - y -  -->") != NULL, "no '--' inside a comment, nor '-' before its end");
    CHECK(strstr(s, "points=\"0,0 1.5,-2 1e-07,1.23457e+08\"") != NULL, "polyline numbers with %%.6g");
    CHECK(strstr(s, "class=\"none\"") == NULL, "a polyline of one point is not written");
    CHECK(strstr(s, "<circle class=\"joint\" cx=\"1\" cy=\"2\" r=\"0.5\"/>") != NULL, "circle");
    CHECK(strstr(s, "<g class=\"figure\" clip-path=\"url(#plot)\">") != NULL, "clipped group");
    CHECK(strstr(s, ">tol &lt; 1e-3 &amp; d &gt; 0</text>") != NULL, "text escaped");
    const char *end = s + strlen(s) - strlen("</svg>\n");
    CHECK(strcmp(end, "</svg>\n") == 0, "ends with </svg>");
    free(s);
}

/* ---- the job view ---------------------------------------------------------------- */

static char last_error[1024];
static void capture(const char *m) { snprintf(last_error, sizeof last_error, "%s", m); }

/* Opens and runs a job from run options; returns open's or run's status. */
static int job(ob_jobview *v, const char *const *args, int have_d, double d)
{
    char *argv[32];
    int argc = 0;
    argv[argc++] = (char *)"test";
    for (int i = 0; args[i]; i++)
        argv[argc++] = (char *)args[i];
    argv[argc] = NULL;
    memset(v, 0, sizeof *v);
    int rc = ob_run_opts_parse(argc, argv, &v->o) ? 2 : ob_jobview_open(v, "test", have_d, d);
    return rc ? rc : ob_jobview_run(v);
}

static double seg_dist(const double p[2], const double a[2], const double b[2])
{
    const double vx = b[0] - a[0], vy = b[1] - a[1];
    const double L = vx * vx + vy * vy;
    double s = L > 0 ? ((p[0] - a[0]) * vx + (p[1] - a[1]) * vy) / L : 0.0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    return hypot(p[0] - a[0] - s * vx, p[1] - a[1] - s * vy);
}

enum { DENSE = 4000 };

static void test_pieces(void)
{
    /* a multi-segment curve under greedy: pieces tile every segment, in order */
    static const char *const a1[] = {"--curve", "liu2002_ex2", "--methods", "cobb", "--tols", "1e-2", "--split",
                                     "greedy", "--backend", "cpu", NULL};
    ob_jobview v;
    int rc = job(&v, a1, 0, 0.0);
    CHECK(rc == 0 && v.job.status == OB_OK && ob_jobview_has_approx(&v), "liu2002_ex2 cobb runs (%d)", rc);
    CHECK(v.job.d == 0.5, "the curve's first offset by default");
    CHECK(v.npieces == v.job.segments && v.npieces > 4, "%d pieces for %d segments", v.npieces, v.job.segments);
    int tiled = v.npieces > 0 && v.pieces[0].seg == 0 && v.pieces[0].ta == 0.0 &&
                v.pieces[v.npieces - 1].seg == v.curve->nseg - 1 && v.pieces[v.npieces - 1].tb == 1.0;
    for (int i = 1; i < v.npieces && tiled; i++) {
        const ob_jv_piece *p = &v.pieces[i - 1], *q = &v.pieces[i];
        tiled = p->ta < p->tb && (q->seg == p->seg ? q->ta == p->tb : q->seg == p->seg + 1 && p->tb == 1.0 && q->ta == 0.0);
    }
    CHECK(tiled, "the pieces tile [0, 1] of every segment in curve order");
    ob_jobview_close(&v);
    ob_jobview_close(&v); /* twice is safe */
}

static void test_radial(void)
{
    static const char *const a[] = {"--curve", "liu2002_ex1", "--methods", "tiller", "--tols", "1e-2", "--metric",
                                    "radial", "--backend", "cpu", NULL};
    ob_jobview v;
    int rc = job(&v, a, 0, 0.0);
    CHECK(rc == 0 && v.job.status == OB_OK && v.npieces == v.job.segments, "tiller radial runs (%d)", rc);
    char s[512];
    ob_jobview_describe(&v, s, sizeof s);
    CHECK(strcmp(s, "liu2002_ex1: tiller, d = 1, tol = 0.01, metric radial, split mid") == 0, "describe: %s", s);
    ob_jobview_summary(&v, s, sizeof s);
    CHECK(strncmp(s, "status ok, ctrl_points = ", 25) == 0 && strstr(s, ", max_err = 0.00"), "summary: %s", s);
    CHECK(ob_jobview_point_is_approx(&v), "radial reports the approximation point");
    double *sc = malloc(ob_jobview_scratch(&v) * sizeof *sc);
    double worst = 0.0, dev = 0.0, dxy = 0.0;
    for (int k = 0; k < v.npieces && sc; k++) {
        const ob_jv_piece *p = &v.pieces[k];
        ob_jobview_prepare(&v, p, sc);
        for (int i = 0; i <= 400; i++) {
            const double u = i / 400.0, t = p->ta + (p->tb - p->ta) * u;
            double xy[2], A[2], C[2];
            const double e = ob_jobview_err_at(&v, p, sc, u, xy);
            ref_point(&p->approx, u, A);
            ref_point(&v.curve->seg[p->seg], t, C);
            dev = fmax(dev, fabs(e - fabs(dist2d(A, C) - 1.0)));
            dxy = fmax(dxy, dist2d(xy, A));
            worst = fmax(worst, e);
        }
    }
    CHECK(dev < 1e-12, "radial error = | |A(t) - C(t)| - |d| | by reference evaluation (off by %g)", dev);
    CHECK(dxy < 1e-13, "the point is A(t) (off by %g)", dxy);
    CHECK(worst <= v.job.max_err * (1 + 1e-9) && worst >= 0.95 * v.job.max_err,
          "dense maximum %.17g vs the run's max_err %.17g", worst, v.job.max_err);
    free(sc);
    ob_jobview_close(&v);

    /* bound has no pointwise form: the radial error stands in */
    static const char *const b[] = {"--curve", "liu2002_ex1", "--methods", "tiller", "--tols", "1e-2", "--metric",
                                    "bound", "--backend", "cpu", NULL};
    rc = job(&v, b, 0, 0.0);
    CHECK(rc == 0 && v.job.status == OB_OK && ob_jobview_point_is_approx(&v), "tiller bound runs");
    if (rc == 0 && v.npieces > 0) {
        double xy[2], A[2], C[2];
        const ob_jv_piece *p = &v.pieces[0];
        const double e = ob_jobview_err_at(&v, p, NULL, 0.3, xy);
        ref_point(&p->approx, 0.3, A);
        ref_point(&v.curve->seg[p->seg], p->ta + (p->tb - p->ta) * 0.3, C);
        CHECK(fabs(e - fabs(dist2d(A, C) - 1.0)) < 1e-12, "bound: the radial error at t");
    }
    ob_jobview_close(&v);
}

/* hausdorff and normal on the regular side (d = -1: no cusps on the offset),
 * against dense polylines of the approximation */
static void test_offset_side(void)
{
    double(*poly)[2] = malloc((DENSE + 1) * sizeof *poly);
    for (int which = 0; which < 2 && poly; which++) {
        const char *metric = which ? "normal" : "hausdorff";
        const char *const a[] = {"--curve", "liu2002_ex1", "--methods", which ? "zhao" : "tiller", "--tols", "1e-2",
                                 "--metric", metric, "--backend", "cpu", NULL};
        ob_jobview v;
        int rc = job(&v, a, 1, -1.0);
        CHECK(rc == 0 && v.job.status == OB_OK && v.job.d == -1.0 && !ob_jobview_point_is_approx(&v),
              "%s job with --d -1 runs (%d)", metric, rc);
        double *sc = malloc(ob_jobview_scratch(&v) * sizeof *sc);
        double dev = 0.0, dxy = 0.0, worst = 0.0;
        for (int k = 0; k < v.npieces && sc; k++) {
            const ob_jv_piece *p = &v.pieces[k];
            ob_jobview_prepare(&v, p, sc);
            /* normal: the line may meet A's extension past the piece's ends
             * (the metric looks on [-0.5, 1.5]) where A does not interpolate them */
            const double lo = which ? -0.25 : 0.0, hi = which ? 1.25 : 1.0;
            for (int i = 0; i <= DENSE; i++)
                ref_point(&p->approx, lo + (hi - lo) * i / DENSE, poly[i]);
            for (int i = 0; i <= 50; i++) {
                const double u = i / 50.0, t = p->ta + (p->tb - p->ta) * u;
                double xy[2], O[2];
                const double e = ob_jobview_err_at(&v, p, sc, u, xy);
                ref_offset(&v.curve->seg[p->seg], t, -1.0, O);
                dxy = fmax(dxy, dist2d(xy, O));
                worst = fmax(worst, e);
                double ref = INFINITY;
                if (which == 0) { /* distance from O(t) to the approximation */
                    for (int j = 0; j < DENSE; j++)
                        ref = fmin(ref, seg_dist(O, poly[j], poly[j + 1]));
                } else { /* along the normal line C + s N: the crossing nearest s = d */
                    double C[2];
                    ref_point(&v.curve->seg[p->seg], t, C);
                    const double N[2] = {-(O[0] - C[0]), -(O[1] - C[1])}; /* O = C - N for d = -1 */
                    for (int j = 0; j < DENSE; j++) {
                        const double g0 = (poly[j][0] - C[0]) * N[1] - (poly[j][1] - C[1]) * N[0];
                        const double g1 = (poly[j + 1][0] - C[0]) * N[1] - (poly[j + 1][1] - C[1]) * N[0];
                        if ((g0 <= 0) == (g1 <= 0))
                            continue;
                        const double w = g0 / (g0 - g1);
                        const double X[2] = {poly[j][0] + w * (poly[j + 1][0] - poly[j][0]),
                                             poly[j][1] + w * (poly[j + 1][1] - poly[j][1])};
                        const double sd = (X[0] - C[0]) * N[0] + (X[1] - C[1]) * N[1];
                        if (fabs(sd + 1.0) < ref)
                            ref = fabs(sd + 1.0);
                    }
                }
                dev = fmax(dev, fabs(e - ref));
            }
        }
        CHECK(dxy < 1e-12, "%s: the point is O(t) (off by %g)", metric, dxy);
        CHECK(dev < 1e-7, "%s: the pointwise error matches a dense polyline (off by %g)", metric, dev);
        CHECK(worst <= v.job.max_err * (1 + 1e-9) && worst >= 0.5 * v.job.max_err,
              "%s: sampled maximum %.17g vs the run's max_err %.17g", metric, worst, v.job.max_err);
        free(sc);
        ob_jobview_close(&v);
    }
    free(poly);
}

static void test_skip_and_errors(void)
{
    static const char *const a[] = {"--curve", "liu2002_ex1", "--methods", "hoschek", "--tols", "1e-2", "--metric",
                                    "bound", "--backend", "cpu", NULL};
    ob_jobview v;
    int rc = job(&v, a, 0, 0.0);
    char s[512];
    ob_jobview_summary(&v, s, sizeof s);
    CHECK(rc == 0 && v.job.status == OB_SKIP && !ob_jobview_has_approx(&v) && v.npieces == 0,
          "hoschek under bound is skipped, nothing to show (%d, %s)", rc, s);
    CHECK(strcmp(s, "status skip, ctrl_points = 0, segments = 0, max_err = -, max_gap = -, continuity = -") == 0,
          "skip summary: %s", s);
    CHECK(strstr(v.job.message, "bound") != NULL, "with the reason: %s", v.job.message);
    ob_jobview_close(&v);

    ob_error_handler old = ob_set_error_handler(capture);
    static const char *const two[] = {"--curve", "liu2002_ex1,liu2002_ex2", "--methods", "tiller", "--tols", "1e-2",
                                      NULL};
    last_error[0] = '\0';
    rc = job(&v, two, 0, 0.0);
    CHECK(rc == 2 && strstr(last_error, "--curve"), "two curves: %d, '%s'", rc, last_error);
    ob_jobview_close(&v);
    static const char *const none[] = {"--methods", "tiller", "--tols", "1e-2", NULL};
    last_error[0] = '\0';
    rc = job(&v, none, 0, 0.0);
    CHECK(rc == 2 && strstr(last_error, "--curve"), "no curve: %d, '%s'", rc, last_error);
    ob_jobview_close(&v);
    static const char *const unknown[] = {"--curve", "nosuch", "--methods", "tiller", "--tols", "1e-2", NULL};
    last_error[0] = '\0';
    rc = job(&v, unknown, 0, 0.0);
    CHECK(rc == 2 && strstr(last_error, "nosuch"), "unknown curve: %d, '%s'", rc, last_error);
    ob_jobview_close(&v);
    ob_set_error_handler(old);
}

int main(void)
{
    test_escape();
    test_bbox();
    test_document();
    test_pieces();
    test_radial();
    test_offset_side();
    test_skip_and_errors();
    return check_done();
}
