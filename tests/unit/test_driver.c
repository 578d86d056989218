/*
 * test_driver.c - the adaptive subdivision driver: counting, split rules,
 * limits, statuses, pre-splitting, and independence from the thread count and
 * the batch size.  Includes the published protocol checks that the driver is
 * responsible for (Liu-Wang Table 1 Til/Cob, Ahn Table 1).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "methods/driver/driver.h"
#include "tests/check.h"
#include "tests/driver_fixture.h"


/* These tests are about the driver, not the methods (each method's behaviour
 * is tested in its own program): a fixed set of fast methods of both kinds,
 * same-degree control-point shifting and degree-raising Hermite, keeps the
 * run time independent of how many methods are registered. */
static const char *const driver_methods[] = {"tiller", "cobb", "ahn", NULL};

/* The driver's logic does not depend on how densely a metric samples: the
 * tests below use 64 samples (the published protocols keep the default). */
static ob_driver_opts fast_opts(void)
{
    ob_driver_opts o;
    ob_driver_defaults(&o);
    o.samples = 64;
    return o;
}

static void run_one(ob_job *j, const ob_curve *c, const char *method, ob_metric metric, ob_split split,
                    double tol, const ob_driver_opts *o)
{
    const ob_driver_opts fast = fast_opts();
    if (!o)
        o = &fast;
    memset(j, 0, sizeof *j);
    j->curve = c;
    j->d = c->d[0];
    j->method = ob_method_find(method);
    j->metric = metric;
    j->split = split;
    j->tol = tol;
    ob_driver_run(j, 1, o, NULL);
}

/* Liu-Wang Table 1 (Til, Cob) and Ahn Table 1: the protocols under which they
 * reproduce exactly (README "Published figures this version reproduces exactly"). */
static void test_published_protocols(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    const double tols[5] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5};
    const long til[5] = {10, 31, 97, 322, 886}, cob[5] = {10, 31, 94, 316, 865}, ahn[5] = {13, 19, 31, 43, 61};
    for (int sign = -1; sign <= 1; sign += 2) {
        c.d[0] = sign;
        for (int i = 0; i < 5; i++) {
            ob_job j;
            ob_driver_opts paper;
            ob_driver_defaults(&paper);
            run_one(&j, &c, "tiller", OB_METRIC_BOUND, OB_SPLIT_MID, tols[i], &paper);
            CHECK(j.ctrl_points == til[i] && j.status == OB_OK, "tiller d=%d tol=%g: %ld", sign, tols[i], j.ctrl_points);
            run_one(&j, &c, "cobb", OB_METRIC_BOUND, OB_SPLIT_MID, tols[i], &paper);
            CHECK(j.ctrl_points == cob[i] && j.status == OB_OK, "cobb d=%d tol=%g: %ld", sign, tols[i], j.ctrl_points);
            run_one(&j, &c, "ahn", OB_METRIC_RADIAL, OB_SPLIT_MID, tols[i], &paper);
            CHECK(j.ctrl_points == ahn[i] && j.status == OB_OK, "ahn d=%d tol=%g: %ld", sign, tols[i], j.ctrl_points);
        }
    }
    ob_curve_free(&c);
}

/* Every ok job meets its tolerance; counting is 1 + sum of degrees. */
static void test_counting_and_tolerance(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    for (int mi = 0; driver_methods[mi]; mi++)
        for (int metric = 0; metric < OB_METRIC_COUNT; metric++)
            for (int split = 0; split < OB_SPLIT_COUNT; split++) {
                const ob_method *m = ob_method_find(driver_methods[mi]);
                ob_job j;
                run_one(&j, &c, driver_methods[mi], (ob_metric)metric, (ob_split)split, 1e-3, NULL);
                if (j.status == OB_SKIP)
                    continue;
                CHECK(j.status == OB_OK, "%s/%s/%s: status %s (%s)", m->name,
                      ob_metric_name(metric), ob_split_name(split), ob_status_name(j.status), j.message);
                CHECK(j.max_err <= 1e-3, "%s/%s/%s: max_err %g", m->name,
                      ob_metric_name(metric), ob_split_name(split), j.max_err);
                int deg = ob_method_out_degree(m, 3, 0, NULL);
                CHECK(j.out_degree == deg, "%s out_degree %d", m->name, j.out_degree);
                CHECK(j.ctrl_points == 1 + (long)j.segments * deg, "%s: %ld ctrl for %d segments",
                      m->name, j.ctrl_points, j.segments);
            }
    ob_curve_free(&c);
}

/* The greedy split reaches no more segments than the midpoint split. */
/* The smaller of a and b (b when a is not a number). */
static double tol_or(double a, double b) { return a <= b ? a : b; }

static void test_greedy_not_worse(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    const double tols[3] = {1e-2, 1e-3, 1e-4};
    for (int m = 0; driver_methods[m]; m++)
        for (int i = 0; i < 3; i++) {
            ob_job a, b;
            run_one(&a, &c, driver_methods[m], OB_METRIC_HAUSDORFF, OB_SPLIT_MID, tols[i], NULL);
            run_one(&b, &c, driver_methods[m], OB_METRIC_HAUSDORFF, OB_SPLIT_GREEDY, tols[i], NULL);
            CHECK(b.status == OB_OK && b.segments <= a.segments, "%s tol %g: greedy %d vs mid %d",
                  driver_methods[m], tols[i], b.segments, a.segments);
        }
    ob_curve_free(&c);
}

/* The optimal rule: no more pieces than greedy (fewer where greedy's error
 * does not grow with the prefix: tiller next to the cusps at d = 1), every
 * error within tol, the largest no more than greedy's, and lower on most
 * jobs with several pieces (not where the largest error is that of a
 * stretch of one piece between forced breaks, which no level changes). */
static void test_optimal(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    const double tols[3] = {1e-2, 1e-3, 1e-4};
    int lower = 0, multi = 0;
    for (int sign = -1; sign <= 1; sign += 2) {
        c.d[0] = sign;
        for (int m = 0; driver_methods[m]; m++)
            for (int i = 0; i < 3; i++) {
                ob_job g, o;
                run_one(&g, &c, driver_methods[m], OB_METRIC_HAUSDORFF, OB_SPLIT_GREEDY, tols[i], NULL);
                run_one(&o, &c, driver_methods[m], OB_METRIC_HAUSDORFF, OB_SPLIT_OPTIMAL, tols[i], NULL);
                CHECK(o.status == OB_OK && o.ctrl_points <= g.ctrl_points && o.segments <= g.segments &&
                      o.max_err <= tol_or(g.max_err, tols[i]),
                      "%s d %d tol %g: optimal %s %ld points, max_err %g; greedy %ld, %g", driver_methods[m], sign,
                      tols[i], ob_status_name(o.status), o.ctrl_points, o.max_err, g.ctrl_points, g.max_err);
                multi += g.segments > 1;
                lower += g.segments > 1 && o.max_err < g.max_err;
            }
    }
    CHECK(multi > 0 && 4 * lower >= 3 * multi, "optimal: max_err lower than greedy's on %d of %d jobs with several pieces",
          lower, multi);
    ob_curve_free(&c);
}

/* Depth and segment limits end a job with status limit, a message, and a
 * complete (if too coarse) approximation. */
static void test_limits(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    ob_driver_opts o = fast_opts();
    o.max_segments = 5;
    for (int split = 0; split < OB_SPLIT_COUNT; split++) {
        ob_job j;
        run_one(&j, &c, "tiller", OB_METRIC_RADIAL, (ob_split)split, 1e-7, &o);
        CHECK(j.status == OB_LIMIT, "%s: status %s", ob_split_name(split), ob_status_name(j.status));
        CHECK(strstr(j.message, "limit") != NULL, "%s: message '%s'", ob_split_name(split), j.message);
        CHECK(j.segments >= 1 && j.segments <= o.max_segments + 1, "%s: %d segments", ob_split_name(split), j.segments);
        CHECK(j.max_err > 1e-7 && isfinite(j.max_err), "%s: max_err %g", ob_split_name(split), j.max_err);
    }
    o = fast_opts();
    o.max_depth = 2;
    ob_job j;
    run_one(&j, &c, "cobb", OB_METRIC_BOUND, OB_SPLIT_MID, 1e-6, &o);
    CHECK(j.status == OB_LIMIT && j.segments == 4, "depth 2: %s, %d segments", ob_status_name(j.status), j.segments);
    CHECK(strstr(j.message, "depth limit") != NULL, "message '%s'", j.message);
    ob_curve_free(&c);
}

/* Pieces are cut at inflections, and for ahn where the tangent turns by pi. */
static void test_presplit(void)
{
    const double s_curve[4][2] = {{0, 0}, {1, 1}, {2, -1}, {3, 0}};
    ob_curve c = fixture_curve("s", 3, s_curve, 0.1);
    ob_job j;
    run_one(&j, &c, "cobb", OB_METRIC_RADIAL, OB_SPLIT_MID, 1e3, NULL);
    CHECK(j.segments == 2, "S curve, huge tol: %d segments (inflection split)", j.segments);
    ob_driver_opts o = fast_opts();
    o.inflections = 0;
    run_one(&j, &c, "cobb", OB_METRIC_RADIAL, OB_SPLIT_MID, 1e3, &o);
    CHECK(j.segments == 1, "S curve, no inflection split: %d segments", j.segments);
    run_one(&j, &c, "ahn", OB_METRIC_RADIAL, OB_SPLIT_MID, 1e3, &o);
    CHECK(j.segments == 2, "ahn needs convex pieces whatever the option: %d segments", j.segments);
    ob_curve_free(&c);

    /* a convex cubic whose tangent turns by more than pi */
    const double wide[4][2] = {{0, 0}, {4, 3}, {-4, 3}, {0, 0.5}};
    ob_curve w = fixture_curve("wide", 3, wide, 0.05);
    CHECK(ob_bez_inflections(&w.seg[0], (double[8]){0}, 8) == 0, "test curve is convex");
    CHECK(ob_bez_turn(&w.seg[0], 512) > OB_PI, "test curve turns by %g > pi", ob_bez_turn(&w.seg[0], 512));
    run_one(&j, &w, "ahn", OB_METRIC_RADIAL, OB_SPLIT_MID, 1e3, NULL);
    CHECK(j.status == OB_OK && j.segments == 2, "ahn on a curve turning > pi: %s, %d segments",
          ob_status_name(j.status), j.segments);
    run_one(&j, &w, "cobb", OB_METRIC_RADIAL, OB_SPLIT_MID, 1e3, NULL);
    CHECK(j.segments == 1, "cobb has no turning limit: %d segments", j.segments);
    ob_curve_free(&w);
}

/* Methods that fail, produce garbage, or cannot take the input. */
static ob_fit_status fail_fit(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *out, char *msg, size_t len)
{
    (void)b, (void)a, (void)w, (void)out;
    snprintf(msg, len, "singular test system");
    return OB_FIT_FAIL;
}
static ob_fit_status nan_fit(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *out, char *msg, size_t len)
{
    (void)a, (void)w, (void)msg, (void)len;
    ob_fit_single(out, b);
    out->seg[0].h[1][0] = NAN;
    return OB_FIT_OK;
}
static int same_degree(int n, int r, const double *par)
{
    (void)r;
    (void)par;
    return n;
}

static void test_failures_are_contained(void)
{
    const ob_method failing = {.name = "failing", .citation = "test", .continuity = "G0",
                               .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = same_degree, .fit = fail_fit};
    const ob_method garbage = {.name = "garbage", .citation = "test", .continuity = "G0",
                               .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = same_degree, .fit = nan_fit};
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    ob_job jobs[3];
    memset(jobs, 0, sizeof jobs);
    const ob_method *ms[3] = {&failing, &garbage, ob_method_find("tiller")};
    for (int i = 0; i < 3; i++) {
        jobs[i].curve = &c;
        jobs[i].d = 1.0;
        jobs[i].method = ms[i];
        jobs[i].metric = OB_METRIC_HAUSDORFF;
        jobs[i].split = OB_SPLIT_MID;
        jobs[i].tol = 1e-3;
    }
    ob_driver_opts o = fast_opts();
    o.max_segments = 64;
    CHECK(ob_driver_run(jobs, 3, &o, NULL) == 0, "run completes");
    CHECK(jobs[0].status == OB_FAIL && strstr(jobs[0].message, "singular test system"), "fail: %s '%s'",
          ob_status_name(jobs[0].status), jobs[0].message);
    CHECK(jobs[0].ctrl_points == 0 && isnan(jobs[0].max_err), "fail row has no counts");
    CHECK(jobs[1].status == OB_LIMIT && jobs[1].segments <= o.max_segments + 1, "NaN output: %s, %d segments",
          ob_status_name(jobs[1].status), jobs[1].segments);
    CHECK(isinf(jobs[1].max_err), "NaN output measures as +inf, got %g", jobs[1].max_err);
    CHECK(jobs[2].status == OB_OK && jobs[2].max_err <= 1e-3, "a good job beside them is unaffected");

    /* rational input to a polynomial-only method: skip with a reason */
    ob_curve r = fixture_curve("arc", 2, (const double[3][2]){{1, 0}, {1, 1}, {0, 1}}, 0.5);
    ob_bez_set(&r.seg[0], 1, 1, 1, sqrt(0.5));
    ob_job j;
    run_one(&j, &r, "ahn", OB_METRIC_HAUSDORFF, OB_SPLIT_MID, 1e-3, NULL);
    CHECK(j.status == OB_SKIP && strstr(j.message, "rational"), "ahn on rational: %s '%s'",
          ob_status_name(j.status), j.message);
    run_one(&j, &r, "tiller", OB_METRIC_HAUSDORFF, OB_SPLIT_MID, 1e-3, NULL);
    CHECK(j.status == OB_OK, "tiller takes rational input: %s '%s'", ob_status_name(j.status), j.message);
    ob_curve_free(&r);
    ob_curve_free(&c);
}

/* An error that is not finite is never ok (ob_err_can_pass): a method whose
 * pieces measure +inf (a NaN control point) ends limit or fail under every
 * split rule and metric, even at the loosest tolerance, with no ok row; a
 * good job of the same batch stays ok with a finite error. */
static void test_infinite_error_never_ok(void)
{
    const ob_method garbage = {.name = "garbage", .citation = "test", .continuity = "G0",
                               .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = same_degree, .fit = nan_fit};
    static const ob_split splits[] = {OB_SPLIT_MID, OB_SPLIT_MAXERR, OB_SPLIT_GREEDY, OB_SPLIT_OPTIMAL};
    static const ob_metric metrics[] = {OB_METRIC_BOUND, OB_METRIC_RADIAL, OB_METRIC_NORMAL, OB_METRIC_HAUSDORFF};
    static const double tols[] = {1e-3, 1e6};
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    ob_driver_opts o = fast_opts();
    o.max_segments = 16;
    o.max_depth = 6;
    for (size_t s = 0; s < sizeof splits / sizeof splits[0]; s++)
        for (size_t m = 0; m < sizeof metrics / sizeof metrics[0]; m++)
            for (size_t t = 0; t < sizeof tols / sizeof tols[0]; t++) {
                ob_job jobs[2];
                fixture_job(&jobs[0], &c, &garbage, metrics[m], splits[s], tols[t]);
                fixture_job(&jobs[1], &c, ob_method_find("tiller"), metrics[m], splits[s], 1e6);
                CHECK(ob_driver_run(jobs, 2, &o, NULL) == 0, "run completes");
                CHECK(jobs[0].status != OB_OK && (jobs[0].status != OB_LIMIT || isinf(jobs[0].max_err)),
                      "%s, %s, tol %g: status %s, max_err %g", ob_split_name(splits[s]),
                      ob_metric_name(metrics[m]), tols[t], ob_status_name(jobs[0].status), jobs[0].max_err);
                CHECK(jobs[1].status == OB_OK && isfinite(jobs[1].max_err), "tiller beside it: %s %g",
                      ob_status_name(jobs[1].status), jobs[1].max_err);
            }
    ob_curve_free(&c);
}

/* A method that asks for smaller pieces (its output would not fit) gets them;
 * one whose representation has its own control-point count is counted so. */
static ob_fit_status picky_fit(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *out, char *msg, size_t len)
{
    (void)w;
    double p0[2], p1[2];
    ob_bez_ctrl(b, 0, p0);
    ob_bez_ctrl(b, b->deg, p1);
    if (hypot(p1[0] - p0[0], p1[1] - p0[1]) > 1.0) {
        snprintf(msg, len, "chord longer than 1");
        return OB_FIT_RETRY_SMALLER;
    }
    ob_bez t = *b;
    for (int i = 0; i <= t.deg; i++) {  /* Cobb's displacement, to have a real approximation */
        double P[2], N[2];
        ob_bez_ctrl(b, i, P);
        ob_bez_normal(b, (double)i / t.deg, N);
        ob_bez_set(&t, i, P[0] + a->d * N[0], P[1] + a->d * N[1], 1.0);
    }
    ob_fit_single(out, &t);
    out->ctrl_points = (long)a->par[0];
    return OB_FIT_OK;
}

static void test_retry_and_counts(void)
{
    static const ob_param pp[1] = {{"count", 0.0, "control points claimed per fit (0: from the degrees)", 0.0, 1e6, 1}};
    const ob_method picky = {.name = "picky", .citation = "test", .continuity = "G0",
                             .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = ob_degree_same,
                             .fit = picky_fit, .params = pp, .nparams = 1};
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    double par[OB_MAX_PARAMS] = {0};
    ob_job j;
    memset(&j, 0, sizeof j);
    j.curve = &c;
    j.d = 1.0;
    j.method = &picky;
    j.params = par;
    j.metric = OB_METRIC_RADIAL;
    j.split = OB_SPLIT_MID;
    j.tol = 1e3;
    const ob_driver_opts fo = fast_opts();
    ob_driver_run(&j, 1, &fo, NULL);
    CHECK(j.status == OB_OK && j.segments >= 4, "pieces with chords over 1 are split: %s, %d segments",
          ob_status_name(j.status), j.segments);
    CHECK(j.ctrl_points == 1 + 3L * j.segments, "counted from degrees: %ld", j.ctrl_points);
    par[0] = 7;
    int k = j.segments;
    ob_driver_run(&j, 1, NULL, NULL);
    CHECK(j.ctrl_points == 1 + 6L * k, "own representation of 7 points per fit: %ld for %d fits", j.ctrl_points, k);
    ob_driver_opts o = fast_opts();
    o.max_depth = 1;
    ob_driver_run(&j, 1, &o, NULL);
    CHECK(j.status == OB_FAIL && strstr(j.message, "chord longer than 1"), "retry past the depth limit fails: %s '%s'",
          ob_status_name(j.status), j.message);
    j.split = OB_SPLIT_GREEDY;
    ob_driver_run(&j, 1, NULL, NULL);
    CHECK(j.status == OB_OK && j.segments >= 4, "greedy with retries: %s, %d", ob_status_name(j.status), j.segments);
    ob_curve_free(&c);
}

/* The optimal rule fits a stretch that one piece covers at tol once: its
 * final pass would fit and measure that same piece again.  tiller is exact
 * on a line (its offset is the control polygon's), so every job here is one
 * piece; a stretch of several pieces still gets its passes. */
static long counted_calls;
static ob_fit_status counted_fit(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *out, char *msg, size_t len)
{
    __atomic_add_fetch(&counted_calls, 1, __ATOMIC_RELAXED);
    return ob_method_find("tiller")->fit(b, a, w, out, msg, len);
}

static void test_optimal_one_piece(void)
{
    const ob_method *til = ob_method_find("tiller");
    const ob_method counted = {.name = "counted", .citation = "test", .continuity = til->continuity,
                               .caps = til->caps, .out_degree = til->out_degree, .work_size = til->work_size,
                               .fit = counted_fit};
    const double line[4][2] = {{0, 0}, {1.0 / 3, 0.1}, {2.0 / 3, 0.2}, {1, 0.3}};
    ob_curve c = fixture_curve("line", 3, line, 0.1);
    ob_job j;
    fixture_job(&j, &c, &counted, OB_METRIC_HAUSDORFF, OB_SPLIT_OPTIMAL, 1e-6);
    counted_calls = 0;
    const ob_driver_opts o = fast_opts();
    ob_driver_run(&j, 1, &o, NULL);
    CHECK(j.status == OB_OK && j.segments == 1 && j.ctrl_points == 4 && counted_calls == 1,
          "optimal, a line: %s, %d segments, %ld points, %ld fits (one piece: one fit)", ob_status_name(j.status),
          j.segments, j.ctrl_points, counted_calls);
    ob_curve_free(&c);
    c = fixture_curve("ex1", 3, fixture_liu_ex1, -1.0);
    ob_job g;
    fixture_job(&g, &c, &counted, OB_METRIC_HAUSDORFF, OB_SPLIT_GREEDY, 1e-3);
    fixture_job(&j, &c, &counted, OB_METRIC_HAUSDORFF, OB_SPLIT_OPTIMAL, 1e-3);
    ob_driver_run(&g, 1, &o, NULL);
    counted_calls = 0;
    ob_driver_run(&j, 1, &o, NULL);
    CHECK(g.segments > 1 && j.status == OB_OK && j.segments <= g.segments && j.max_err <= 1e-3 &&
              counted_calls > 2 * j.segments,
          "optimal, ex1 d = -1 at 1e-3: %d segments (greedy %d), max_err %g (greedy %g), %ld fits", j.segments,
          g.segments, j.max_err, g.max_err, counted_calls);
    ob_curve_free(&c);
}

/* A method that asks for a smaller piece wherever the piece covers a point
 * of its "pole" set, whatever its size: the failure at the retry limit is
 * found without fitting the whole binary tree of halvings below (the base
 * is the segment x = t, so a piece's x range is its parameter range). */
static long pole_calls;
static ob_fit_status pole_fit(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *out, char *msg, size_t len)
{
    (void)a, (void)w;
    __atomic_add_fetch(&pole_calls, 1, __ATOMIC_RELAXED);
    double p0[2], p1[2];
    ob_bez_ctrl(b, 0, p0);
    ob_bez_ctrl(b, b->deg, p1);
    /* always: everywhere; else the point 0.26 and all of (0.5, 1] */
    const int always = a->par[0] != 0.0;
    if (always || (p0[0] <= 0.26 && p1[0] >= 0.26) || p1[0] > 0.5) {
        snprintf(msg, len, "pole");
        return OB_FIT_RETRY_SMALLER;
    }
    ob_fit_single(out, b);
    return OB_FIT_OK;
}

static void test_retry_chains(void)
{
    static const ob_param pp[1] = {{"always", 0.0, "1: every piece asks for a smaller one", 0.0, 1.0, 1}};
    const ob_method pole = {.name = "pole", .citation = "test", .continuity = "G0",
                            .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = ob_degree_same,
                            .fit = pole_fit, .params = pp, .nparams = 1};
    const double line[4][2] = {{0, 0}, {1.0 / 3, 0}, {2.0 / 3, 0}, {1, 0}};
    ob_curve c = fixture_curve("line", 3, line, 0.1);
    double par[OB_MAX_PARAMS] = {1};
    const ob_split splits[2] = {OB_SPLIT_MID, OB_SPLIT_MAXERR};
    for (int k = 0; k < 2; k++) {
        ob_job j;
        fixture_job(&j, &c, &pole, OB_METRIC_RADIAL, splits[k], 1e-3);
        j.params = par;
        par[0] = 1;
        pole_calls = 0;
        const ob_driver_opts o = fast_opts();
        ob_driver_run(&j, 1, &o, NULL);
        CHECK(j.status == OB_FAIL && strstr(j.message, "pole, still after 12 halvings, at t in [0, 0.000244141]"),
              "%s: everywhere: %s '%s'", ob_split_name(splits[k]), ob_status_name(j.status), j.message);
        CHECK(pole_calls <= 2 * 13, "%s: everywhere: %ld fits for a failure at 12 halvings (breadth first: 4607)",
              ob_split_name(splits[k]), pole_calls);
        /* the chain down (0.5, 1] fails no sooner than the piece on 0.26, to
         * its left at the same level, as the breadth-first order has it */
        par[0] = 0;
        pole_calls = 0;
        ob_driver_run(&j, 1, &o, NULL);
        CHECK(j.status == OB_FAIL && strstr(j.message, "pole, still after 12 halvings, at t in [0.259766, 0.26001]"),
              "%s: the leftmost failure at the limit: %s '%s'", ob_split_name(splits[k]), ob_status_name(j.status),
              j.message);
        CHECK(pole_calls < 200, "%s: %ld fits (breadth first: 2633)", ob_split_name(splits[k]), pole_calls);
    }
    ob_curve_free(&c);
}

/* Same results for any thread count and batch size (timings aside). */
static void test_determinism(void)
{
    const double q5[6][2] = {{3, -1}, {4, 2}, {4.5, 2}, {5.5, 1.5}, {6.5, 0}, {7, -1}};
    ob_curve c[2] = {fixture_curve("ex1", 3, fixture_liu_ex1, 1.0), fixture_curve("q5", 5, q5, 0.5)};
    enum { NJ = 2 * 3 * OB_SPLIT_COUNT * 2 };  /* curves x methods x split rules x tols */
    ob_job ref[NJ], got[NJ];
    int n = 0;
    for (int ci = 0; ci < 2; ci++)
        for (int m = 0; driver_methods[m]; m++)
            for (int split = 0; split < OB_SPLIT_COUNT; split++)
                for (int t = 0; t < 2; t++) {
                    memset(&ref[n], 0, sizeof ref[n]);
                    ref[n].curve = &c[ci];
                    ref[n].d = c[ci].d[0];
                    ref[n].method = ob_method_find(driver_methods[m]);
                    ref[n].metric = OB_METRIC_HAUSDORFF;
                    ref[n].split = (ob_split)split;
                    ref[n].tol = t ? 1e-3 : 1e-2;
                    n++;
                }
    memcpy(got, ref, sizeof ref);
    ob_driver_opts o = fast_opts();
    omp_set_num_threads(1);
    ob_driver_run(ref, (size_t)n, &o, NULL);
    omp_set_num_threads(2);
    o.chunk = 7;
    ob_driver_run(got, (size_t)n, &o, NULL);
    int same = 1;
    for (int i = 0; i < n; i++)
        same &= ref[i].ctrl_points == got[i].ctrl_points && ref[i].segments == got[i].segments &&
                memcmp(&ref[i].max_err, &got[i].max_err, sizeof(double)) == 0 && ref[i].status == got[i].status;
    CHECK(same, "1 thread / batch 2048 vs 2 threads / batch 7 give identical results");
    ob_curve_free(&c[0]);
    ob_curve_free(&c[1]);
}

/* 1 when two runs of the same job gave the same outputs, bit for bit (all
 * but the times). */
static int same_outputs(const ob_job *a, const ob_job *b)
{
    return a->status == b->status && a->ctrl_points == b->ctrl_points && a->segments == b->segments &&
           a->out_degree == b->out_degree && memcmp(&a->max_err, &b->max_err, sizeof a->max_err) == 0 &&
           strcmp(a->message, b->message) == 0 && memcmp(&a->max_gap, &b->max_gap, sizeof a->max_gap) == 0 &&
           memcmp(&a->max_kink, &b->max_kink, sizeof a->max_kink) == 0 && a->continuity == b->continuity &&
           a->open_joints == b->open_joints;
}

/* Greedy and optimal probes measured only until they are known to fail
 * (the default) give the results of probes measured in full
 * (full_probes), for every registered method under greedy, for ahn and
 * cubic-opt under optimal (ten times greedy's fits), under hausdorff and normal,
 * with two tolerances per job group (their pieces are shared; the job at
 * the smaller one measures them, and must stop at the larger level), on
 * both sides of ex1 (d = 1 has offset cusps). */
static void test_probe_stops(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    enum { NJ = 2 * 2 * 2 * 64 };
    static ob_job ref[NJ], got[NJ];
    int n = 0;
    for (int sign = -1; sign <= 1; sign += 2)
        for (int split = OB_SPLIT_GREEDY; split <= OB_SPLIT_OPTIMAL; split++)
            for (int mi = 0; mi < ob_method_count(); mi++) {
                const ob_method *m = ob_methods[mi];
                const int in = split == OB_SPLIT_GREEDY || strcmp(m->name, "cubic-opt") == 0 ||
                               strcmp(m->name, "ahn") == 0;
                for (int metric = 0; in && metric < 2 && n + 2 <= NJ; metric++)
                    for (int t = 0; t < 2; t++) {
                        ob_job *j = &ref[n++];
                        memset(j, 0, sizeof *j);
                        j->curve = &c;
                        j->d = sign;
                        j->method = m;
                        j->metric = metric ? OB_METRIC_NORMAL : OB_METRIC_HAUSDORFF;
                        j->split = (ob_split)split;
                        j->tol = t ? 1e-2 : 1e-3; /* the smaller first: it measures the shared pieces */
                    }
            }
    memcpy(got, ref, sizeof ref);
    ob_driver_opts o = fast_opts();
    o.full_probes = 1;
    ob_driver_run(ref, (size_t)n, &o, NULL);
    o.full_probes = 0;
    ob_driver_run(got, (size_t)n, &o, NULL);
    int same = 0;
    double full_ns = 0.0, stop_ns = 0.0;
    for (int i = 0; i < n; i++) {
        const int eq = same_outputs(&ref[i], &got[i]);
        same += eq;
        full_ns += ref[i].eval_ns;
        stop_ns += got[i].eval_ns;
        if (!eq)
            fprintf(stderr, "%s %s %s d %g tol %g: full %s %ld %a \"%s\", stopped %s %ld %a \"%s\"\n",
                    ref[i].method->name, ob_split_name(ref[i].split), ob_metric_name(ref[i].metric), ref[i].d,
                    ref[i].tol, ob_status_name(ref[i].status), ref[i].ctrl_points, ref[i].max_err, ref[i].message,
                    ob_status_name(got[i].status), got[i].ctrl_points, got[i].max_err, got[i].message);
    }
    CHECK(n > 2 * ob_method_count() && same == n, "probe stops: %d of %d jobs as with probes in full", same, n);
    fprintf(stderr, "probe stops: measuring %.3g s in full, %.3g s with stops\n", full_ns * 1e-9, stop_ns * 1e-9);
    ob_curve_free(&c);
}

/* The span log: the accepted pieces tile [0, 1] of the base, and refitting
 * them with the method reproduces the job's segment and control-point counts
 * (what draw and trace rely on). */
static void test_span_log(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    const ob_driver_opts fast = fast_opts();
    for (int m = 0; driver_methods[m]; m++)
        for (int sp = 0; sp < OB_SPLIT_COUNT; sp++) {
            ob_job j;
            memset(&j, 0, sizeof j);
            j.curve = &c;
            j.d = 1.0;
            j.method = ob_method_find(driver_methods[m]);
            j.metric = OB_METRIC_HAUSDORFF;
            j.split = (ob_split)sp;
            j.tol = 1e-3;
            ob_span_log log = {0};
            ob_driver_opts o = fast;
            ob_driver_hooks h = {.spans = &log};
            ob_driver_run(&j, 1, &o, &h);
            const char *name = driver_methods[m], *spn = ob_split_name((ob_split)sp);
            CHECK(j.status == OB_OK && log.n > 0 && !log.oom, "%s/%s: spans logged (%d)", name, spn, log.n);
            int tiled = log.n > 0 && log.v[0].a == 0.0 && log.v[log.n - 1].b == 1.0;
            for (int i = 1; i < log.n; i++)
                tiled = tiled && log.v[i].a == log.v[i - 1].b && log.v[i].seg == 0;
            CHECK(tiled, "%s/%s: spans tile [0, 1] in order", name, spn);
            long ctrl = 1;
            int pieces = 0;
            double par[OB_MAX_PARAMS];
            ob_param_defaults(j.method, par);
            void *work = malloc(j.method->work_size ? j.method->work_size : 1);
            for (int i = 0; i < log.n; i++) {
                ob_bez sub;
                ob_fit fit;
                char msg[160];
                ob_bez_subsegment(&c.seg[0], log.v[i].a, log.v[i].b, &sub);
                const ob_fit_args args = {j.d, j.tol, par};
                if (j.method->fit(&sub, &args, work, &fit, msg, sizeof msg) != OB_FIT_OK)
                    break;
                pieces += fit.n;
                if (fit.ctrl_points > 0)
                    ctrl += fit.ctrl_points - 1;
                else
                    for (int p = 0; p < fit.n; p++)
                        ctrl += fit.seg[p].deg;
            }
            free(work);
            CHECK(pieces == j.segments && ctrl == j.ctrl_points, "%s/%s: refit gives %d pieces, %ld points (job %d, %ld)",
                  name, spn, pieces, ctrl, j.segments, j.ctrl_points);
            free(log.v);
        }
    ob_curve_free(&c);
}

/* --job-timeout: a job past its thread-time budget ends with status timeout
 * (no approximation: ctrl_points 0, max_err NaN, a message); a job that
 * finishes within its first level is not cut; the other jobs of the run go
 * on. */
static void test_job_timeout(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    ob_driver_opts o = fast_opts();
    o.job_timeout_ns = 1.0;  /* 1 ns: any job needing a second level */
    ob_job j[2];
    memset(j, 0, sizeof j);
    for (int k = 0; k < 2; k++) {
        j[k].curve = &c;
        j[k].d = 1.0;
        j[k].method = ob_method_find("tiller");
        j[k].metric = OB_METRIC_HAUSDORFF;
        j[k].split = OB_SPLIT_MID;
    }
    j[0].tol = 1e-5;  /* hundreds of segments */
    j[1].tol = 1e3;   /* passes at once */
    CHECK(ob_driver_run(j, 2, &o, NULL) == 0, "driver run");
    CHECK(j[0].status == OB_TIMEOUT && j[0].ctrl_points == 0 && isnan(j[0].max_err) &&
              strstr(j[0].message, "job timeout"),
          "tiller 1e-5 with a 1 ns budget: %s, %ld points, '%s'", ob_status_name(j[0].status), j[0].ctrl_points,
          j[0].message);
    CHECK(j[1].status == OB_OK && j[1].ctrl_points > 0, "a job done in its first level is not cut: %s",
          ob_status_name(j[1].status));
    CHECK(strcmp(ob_status_name(OB_TIMEOUT), "timeout") == 0, "status name");
    ob_curve_free(&c);
}

int main(void)
{
    test_job_timeout();
    test_span_log();
    test_published_protocols();
    test_counting_and_tolerance();
    test_greedy_not_worse();
    test_optimal();
    test_optimal_one_piece();
    test_limits();
    test_presplit();
    test_failures_are_contained();
    test_infinite_error_never_ok();
    test_retry_and_counts();
    test_retry_chains();
    test_determinism();
    test_probe_stops();
    return check_done();
}
