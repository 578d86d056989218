/*
 * test_joints.c - pieces that do not meet: the driver counts a joint whose
 * ends are apart as two control points, and measures the largest joint gap
 * and kink of every job.
 *
 * The reference here is independent of the driver's own joint code: each
 * accepted span (o.spans) is refitted with the job's method (fits are
 * deterministic) and the end points of consecutive pieces are compared
 * directly (homogeneous end control points divided by their weights).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "methods/driver/driver.h"
#include "tests/check.h"
#include "tests/driver_fixture.h"
#include "tests/testlib.h"

static const double ex1[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};

static ob_curve make_curve(const char *id, int nseg, const double (*xy)[2], double d)
{
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "%s", id);
    c.nseg = nseg;
    c.seg = calloc((size_t)nseg, sizeof *c.seg);
    for (int s = 0; s < nseg; s++)
        ob_bez_from_points(&c.seg[s], 3, xy + 3 * s);
    c.nd = 1;
    c.d = malloc(sizeof *c.d);
    c.d[0] = d;
    return c;
}

/* ex1 cut at t = 0.4 into two segments: the same curve, G1 (indeed smooth)
 * at the cut. */
static ob_curve make_ex1_cut(double d)
{
    ob_curve c = make_curve("ex1", 1, ex1, d);
    ob_bez l, r;
    ob_bez_split(&c.seg[0], 0.4, &l, &r);
    free(c.seg);
    c.nseg = 2;
    c.seg = calloc(2, sizeof *c.seg);
    c.seg[0] = l;
    c.seg[1] = r;
    return c;
}

/* The control-point bounding box of the base, grown by |d| on every side:
 * the size the gap threshold is relative to (see methods/driver/joints.h). */
static double ref_size(const ob_curve *c, double d)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int s = 0; s < c->nseg; s++)
        for (int i = 0; i <= c->seg[s].deg; i++)
            for (int k = 0; k < 2; k++) {
                const double v = c->seg[s].h[i][k] / c->seg[s].h[i][2];
                lo[k] = fmin(lo[k], v);
                hi[k] = fmax(hi[k], v);
            }
    return hypot(hi[0] - lo[0] + 2 * fabs(d), hi[1] - lo[1] + 2 * fabs(d));
}

static void end_point(const ob_bez *b, int at_end, double p[2])
{
    const int i = at_end ? b->deg : 0;
    p[0] = b->h[i][0] / b->h[i][2];
    p[1] = b->h[i][1] / b->h[i][2];
}

/* What the refit of a job's spans gives: its pieces' degrees, the open
 * joints (ends farther apart than rel * size) and the largest gap. */
typedef struct {
    long sumdeg;
    int pieces, open, joints;
    double max_gap;
    long bspline_ctrl;   /* sum over fits with their own count of (count - 1); -1: none */
} refit_t;

static refit_t refit(const ob_job *j, const ob_span_log *L, double rel)
{
    refit_t r = {0, 0, 0, 0, 0.0, -1};
    const double tol = rel * ref_size(j->curve, j->d);
    void *work = malloc(j->method->work_size ? j->method->work_size : 1);
    double par[OB_MAX_PARAMS];
    ob_param_defaults(j->method, par);
    double prev[2] = {0, 0};
    int have_prev = 0;
    for (int i = 0; i < L->n; i++) {
        ob_bez sub;
        ob_fit fit;
        char msg[160];
        ob_bez_subsegment(&j->curve->seg[L->v[i].seg], L->v[i].a, L->v[i].b, &sub);
        const ob_fit_args a = {j->d, j->tol, j->params ? j->params : par};
        if (j->method->fit(&sub, &a, work, &fit, msg, sizeof msg) != OB_FIT_OK) {
            r.pieces = -1;
            break;
        }
        if (fit.ctrl_points > 0)
            r.bspline_ctrl = (r.bspline_ctrl < 0 ? 0 : r.bspline_ctrl) + fit.ctrl_points - 1;
        for (int p = 0; p < fit.n; p++) {
            double s[2];
            end_point(&fit.seg[p], 0, s);
            if (have_prev) {
                const double g = hypot(s[0] - prev[0], s[1] - prev[1]);
                r.joints++;
                r.open += g > tol;
                if (g > r.max_gap)
                    r.max_gap = g;
            }
            end_point(&fit.seg[p], 1, prev);
            have_prev = 1;
            r.sumdeg += fit.seg[p].deg;
            r.pieces++;
        }
    }
    free(work);
    return r;
}

static void run_job(ob_job *j, const ob_curve *c, const ob_method *m, ob_metric metric, ob_split split, double tol,
                    ob_span_log *L)
{
    ob_driver_opts o;
    ob_driver_defaults(&o);
    fixture_job(j, c, m, metric, split, tol);
    memset(L, 0, sizeof *L);
    ob_driver_hooks h = {.spans = L};
    ob_driver_run(j, 1, &o, &h);
}

/* ---- a test-only method whose pieces do not meet ------------------------------
 * Cobb's shift (P_j += d N(j/n)), cut in two pieces at 1/2; the second
 * piece's start and the fit's start are pulled 1e-6 of their leg along it,
 * so no joint closes, inside a fit or between fits.  `gappy-bs` reports the
 * two pieces as one representation of 4 control points (fit->ctrl_points,
 * like a B-spline output) and leaves its inside closed. */

static ob_fit_status gappy_any(const ob_bez *base, const ob_fit_args *a, ob_fit *out, int bs)
{
    ob_bez s = *base;
    const int n = base->deg;
    for (int j = 0; j <= n; j++) {
        double nn[2];
        if (ob_bez_normal(base, (double)j / n, nn) != 0)
            return OB_FIT_FAIL;
        s.h[j][0] += s.h[j][2] * a->d * nn[0];
        s.h[j][1] += s.h[j][2] * a->d * nn[1];
    }
    out->n = 2;
    out->ctrl_points = bs ? n + 1 : 0;
    out->t[0] = 0.0, out->t[1] = 0.5, out->t[2] = 1.0;
    ob_bez_split(&s, 0.5, &out->seg[0], &out->seg[1]);
    for (int p = bs ? 0 : 1; p >= 0; p--)
        for (int k = 0; k < 2; k++)
            out->seg[p].h[0][k] += 1e-6 * (out->seg[p].h[1][k] - out->seg[p].h[0][k]);
    return OB_FIT_OK;
}

static ob_fit_status gappy_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out, char *msg,
                               size_t msglen)
{
    (void)work, (void)msg, (void)msglen;
    return gappy_any(base, a, out, 0);
}

static ob_fit_status gappy_bs_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out, char *msg,
                                  size_t msglen)
{
    (void)work, (void)msg, (void)msglen;
    return gappy_any(base, a, out, 1);
}

static const ob_method gappy = {
    .name = "gappy", .version = 1, .citation = "test only", .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = ob_degree_same, .work_size = 1, .fit = gappy_fit,
};
static const ob_method gappy_bs = {
    .name = "gappy-bs", .version = 1, .citation = "test only", .continuity = "G0",
    .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = ob_degree_same, .work_size = 1, .fit = gappy_bs_fit,
};

/* The threshold of an open joint, relative to the curve's size. */
static const double GAP_REL = 1e-12;

/* ctrl_points = 1 + sum of degrees + open joints, checked against the refit. */
static void check_count(const ob_job *j, const ob_span_log *L, const char *what)
{
    const refit_t r = refit(j, L, GAP_REL);
    CHECK(r.pieces == j->segments, "%s: refit %d pieces, the run %d", what, r.pieces, j->segments);
    if (r.bspline_ctrl < 0)
        CHECK(j->ctrl_points == 1 + r.sumdeg + r.open, "%s: ctrl_points %ld, expected 1 + %ld + %d open joints",
              what, j->ctrl_points, r.sumdeg, r.open);
}

/* The issue: zhao-rational on liu2002_ex1 leaves joints open by about tol. */
static void test_zhao_rational_gaps(void)
{
    ob_curve c = make_curve("liu2002_ex1", 1, ex1, 1.0);
    const double tols[2] = {1e-3, 1e-5};
    for (int i = 0; i < 2; i++) {
        ob_job j;
        ob_span_log L;
        run_job(&j, &c, ob_method_find("zhao-rational"), OB_METRIC_HAUSDORFF, OB_SPLIT_MID, tols[i], &L);
        const refit_t r = refit(&j, &L, GAP_REL);
        char what[64];
        snprintf(what, sizeof what, "zhao-rational tol %g", tols[i]);
        CHECK(j.status == OB_OK && r.open > 0, "%s: %s, %d open joints", what, ob_status_name(j.status), r.open);
        CHECK(r.max_gap > 0.1 * tols[i], "%s: max gap %g", what, r.max_gap);
        check_count(&j, &L, what);
        const double gtol = ob_joint_gap_tol(&c, j.d);
        CHECK(j.max_gap > gtol && j.max_gap == r.max_gap, "%s: max_gap %.17g, the refit's %.17g (threshold %g)", what,
              j.max_gap, r.max_gap, gtol);
        CHECK(j.continuity == OB_CONT_OPEN && j.open_joints == r.open && j.joints == r.joints,
              "%s: continuity '%s', %d of %d joints open (refit %d of %d)", what, ob_cont_name(j.continuity),
              j.open_joints, j.joints, r.open, r.joints);
        CHECK(j.max_kink >= 0 && j.max_kink <= OB_PI, "%s: max_kink %g", what, j.max_kink);
        free(L.v);
    }
    ob_curve_free(&c);
}

/* Pieces that meet (ahn, a Hermite interpolant) keep 1 + sum of degrees. */
static void test_closed_methods_count(void)
{
    ob_curve c = make_curve("liu2002_ex1", 1, ex1, 1.0);
    const char *const names[] = {"ahn", "cobb", "tiller", NULL};
    for (int m = 0; names[m]; m++) {
        ob_job j;
        ob_span_log L;
        run_job(&j, &c, ob_method_find(names[m]), OB_METRIC_HAUSDORFF, OB_SPLIT_MID, 1e-4, &L);
        const refit_t r = refit(&j, &L, GAP_REL);
        CHECK(j.status == OB_OK && r.open == 0, "%s: %d open joints, max gap %g", names[m], r.open, r.max_gap);
        check_count(&j, &L, names[m]);
        const double gtol = ob_joint_gap_tol(&c, j.d);
        CHECK(j.max_gap <= gtol && j.max_gap == r.max_gap && j.open_joints == 0 && j.joints == j.segments - 1,
              "%s: max_gap %g (threshold %g), %d open of %d joints, %d segments", names[m], j.max_gap, gtol,
              j.open_joints, j.joints, j.segments);
        if (m == 0)  /* ahn: G2/C1 Hermite, its kinks are round-off */
            CHECK(j.continuity == OB_CONT_G1 && j.max_kink < 1e-11, "ahn: continuity '%s', max_kink %g",
                  ob_cont_name(j.continuity), j.max_kink);
        if (m == 1)  /* cobb: the end tangents are not the offset's */
            CHECK(j.continuity == OB_CONT_G0 && j.max_kink > 1e-4, "cobb: continuity '%s', max_kink %g",
                  ob_cont_name(j.continuity), j.max_kink);
        if (m == 2)
            CHECK(j.continuity == OB_CONT_G1 || j.continuity == OB_CONT_G0, "tiller: closed, '%s'",
                  ob_cont_name(j.continuity));
        free(L.v);
    }
    ob_curve_free(&c);
}

/* The test-only gappy methods: every joint open, inside fits and between
 * them, also across a G1 joint of two base segments. */
static void test_gappy_counts(void)
{
    for (int cut = 0; cut < 2; cut++) {
        ob_curve c = cut ? make_ex1_cut(1.0) : make_curve("ex1", 1, ex1, 1.0);
        for (int split = 0; split < OB_SPLIT_COUNT; split++) {
            ob_job j;
            ob_span_log L;
            char what[64];
            snprintf(what, sizeof what, "gappy %s%s", ob_split_name((ob_split)split), cut ? " (2 segments)" : "");
            run_job(&j, &c, &gappy, OB_METRIC_HAUSDORFF, (ob_split)split, 1e-3, &L);
            CHECK(j.status == OB_OK, "%s: %s %s", what, ob_status_name(j.status), j.message);
            CHECK(j.ctrl_points == 4L * j.segments, "%s: %ld ctrl_points for %d pieces (each piece 3 + its own start)",
                  what, j.ctrl_points, j.segments);
            check_count(&j, &L, what);
            const refit_t r = refit(&j, &L, GAP_REL);
            CHECK(j.continuity == OB_CONT_OPEN && j.open_joints == j.segments - 1 && j.joints == j.segments - 1 &&
                      j.max_gap == r.max_gap,
                  "%s: '%s', %d open of %d joints, max_gap %.17g (refit %.17g)", what, ob_cont_name(j.continuity),
                  j.open_joints, j.joints, j.max_gap, r.max_gap);
            free(L.v);
            /* a representation of its own (B-spline-like): its count, plus
             * one per open joint between fits */
            snprintf(what, sizeof what, "gappy-bs %s%s", ob_split_name((ob_split)split), cut ? " (2 segments)" : "");
            run_job(&j, &c, &gappy_bs, OB_METRIC_HAUSDORFF, (ob_split)split, 1e-3, &L);
            CHECK(j.status == OB_OK && L.n > 1, "%s: %s, %d spans", what, ob_status_name(j.status), L.n);
            CHECK(j.ctrl_points == 1 + 3L * L.n + (L.n - 1), "%s: %ld ctrl_points for %d fits", what, j.ctrl_points,
                  L.n);
            CHECK(j.open_joints == L.n - 1 && j.joints == j.segments - 1 && j.continuity == OB_CONT_OPEN,
                  "%s: %d open joints of %d, '%s'", what, j.open_joints, j.joints, ob_cont_name(j.continuity));
            free(L.v);
        }
        ob_curve_free(&c);
    }
}

/* End points and one-sided end tangents, against the curve itself: the
 * direction of C(h) - C(0) (and C(1) - C(1 - h)) for a small h. */
static void check_end(const ob_bez *b, const char *what)
{
    for (int e = 0; e < 2; e++) {
        ob_end end;
        ob_bez_end(b, e, &end);
        double p[2], q[2];
        ref_point(b, e ? 1.0 : 0.0, p);
        ref_point(b, e ? 1.0 - 1e-6 : 1e-6, q);
        double v[2] = {e ? p[0] - q[0] : q[0] - p[0], e ? p[1] - q[1] : q[1] - p[1]};
        const double len = hypot(v[0], v[1]);
        CHECK(dist2d(end.p, p) <= 1e-15 * (1 + hypot(p[0], p[1])), "%s end %d: point (%g, %g) vs (%g, %g)", what, e,
              end.p[0], end.p[1], p[0], p[1]);
        CHECK(fabs(end.t[0] - v[0] / len) < 1e-4 && fabs(end.t[1] - v[1] / len) < 1e-4 &&
                  fabs(hypot(end.t[0], end.t[1]) - 1) < 1e-14,
              "%s end %d: tangent (%g, %g), the curve leaves along (%g, %g)", what, e, end.t[0], end.t[1],
              v[0] / len, v[1] / len);
    }
}

static void test_end_tangents(void)
{
    const double S2 = sqrt(0.5);
    ob_end pe;
    ob_bez pt = {0};
    pt.h[0][2] = 1.0;
    ob_bez_end(&pt, 0, &pe);
    CHECK(pe.t[0] == 0 && pe.t[1] == 0, "a point has no tangent");
    ob_bez c = make(3, ex1, NULL);
    check_end(&c, "ex1");
    /* collapsed end legs: the next control point's direction */
    const double col[4][2] = {{0, 0}, {0, 0}, {1, 1}, {1, 1}};
    ob_bez b = make(3, col, NULL);
    check_end(&b, "collapsed legs");
    ob_end e0;
    ob_bez_end(&b, 0, &e0);
    CHECK(fabs(e0.t[0] - S2) < 1e-15 && fabs(e0.t[1] - S2) < 1e-15, "collapsed first leg: (%g, %g)",
          e0.t[0], e0.t[1]);
    /* rational: a quarter circle, and with a negative middle weight the
     * other three quarters, which leave the ends the other way */
    ob_bez q = quarter_circle(2.0, 0);
    check_end(&q, "quarter circle");
    const double qxy[3][2] = {{2, 0}, {2, 2}, {0, 2}}, wneg[3] = {1, -S2, 1};
    ob_bez qn = make(2, qxy, wneg);
    check_end(&qn, "three quarters (negative weight)");
    ob_end a, z;
    ob_bez_end(&q, 0, &a);
    ob_bez_end(&qn, 0, &z);
    CHECK(a.t[1] > 0.99 && z.t[1] < -0.99, "quarter leaves upwards (%g), three quarters downwards (%g)", a.t[1],
          z.t[1]);
    /* the quarter, then the three quarters backwards: the circle goes on
     * (closed, no kink); the quarter, then itself backwards: a cusp */
    ob_joint_stats st;
    memset(&st, 0, sizeof st);
    ob_end qend, rs, back;
    ob_bez_end(&q, 1, &qend);
    ob_bez r = reversed(&qn), qr = reversed(&q);
    ob_bez_end(&r, 0, &rs);
    CHECK(ob_joint_measure(&st, &qend, &rs, 1e-12) == 0 && st.max_kink < 1e-15 && ob_joint_continuity(&st) == OB_CONT_G1,
          "quarter then the reversed three quarters: gap %g, kink %g", st.max_gap, st.max_kink);
    ob_bez_end(&qr, 0, &back);
    CHECK(ob_joint_measure(&st, &qend, &back, 1e-12) == 0 && fabs(st.max_kink - OB_PI) < 1e-15 && st.kinked == 1 &&
              ob_joint_continuity(&st) == OB_CONT_G0 && st.joints == 2,
          "quarter then itself backwards: kink %g", st.max_kink);
    ob_cont k;
    CHECK(ob_cont_parse("G1", &k) == 0 && k == OB_CONT_G1 && ob_cont_parse("", &k) == 0 && k == OB_CONT_NONE &&
              ob_cont_parse("C2", &k) != 0 && strcmp(ob_cont_name(OB_CONT_OPEN), "open") == 0,
          "continuity names");
}

/* Base curves with a corner or a gap between segments: that joint is not
 * measured (the exact offset jumps there), but its two ends are two points. */
static void test_base_corner(void)
{
    const double two[7][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2},
                              {1.5, -1.0}, {2.0, -1.0}, {2.5, -0.5}};
    for (int kind = 0; kind < 3; kind++) {
        ob_curve c = kind == 0 ? make_ex1_cut(-1.0) : make_curve("corner", 2, two, -1.0);
        if (kind == 2)  /* a gap: the second segment moved off the first's end */
            for (int i = 0; i <= 3; i++)
                ob_bez_set(&c.seg[1], i, c.seg[1].h[i][0] + 0.05, c.seg[1].h[i][1], 1.0);
        const double gtol = ob_joint_gap_tol(&c, -1.0);
        CHECK(ob_base_joint_smooth(&c, 0, gtol) == (kind == 0), "kind %d: base G1 at the joint: %d", kind,
              ob_base_joint_smooth(&c, 0, gtol));
        ob_job j;
        ob_span_log L;
        run_job(&j, &c, ob_method_find("ahn"), OB_METRIC_HAUSDORFF, OB_SPLIT_MID, 1e-3, &L);
        long sumdeg = 6L * j.segments;
        CHECK(j.status == OB_OK && j.continuity == OB_CONT_G1 && j.max_gap <= gtol, "kind %d: ahn %s, '%s', max_gap %g",
              kind, ob_status_name(j.status), ob_cont_name(j.continuity), j.max_gap);
        CHECK(j.joints == j.segments - 1 - (kind > 0) && j.open_joints == (kind > 0) &&
                  j.ctrl_points == 1 + sumdeg + (kind > 0),
              "kind %d: %d joints measured of %d, %d counted twice, ctrl_points %ld", kind, j.joints, j.segments - 1,
              j.open_joints, j.ctrl_points);
        free(L.v);
        run_job(&j, &c, &gappy, OB_METRIC_HAUSDORFF, OB_SPLIT_MID, 1e-3, &L);
        CHECK(j.open_joints == j.segments - 1 && j.joints == j.segments - 1 - (kind > 0) && j.ctrl_points == 4L * j.segments,
              "kind %d: gappy: %d open, %d measured of %d, ctrl %ld", kind, j.open_joints, j.joints, j.segments - 1,
              j.ctrl_points);
        free(L.v);
        ob_curve_free(&c);
    }
}

/* The joint columns do not depend on the thread count or the batch size. */
static void test_joints_deterministic(void)
{
    ob_curve c = make_ex1_cut(1.0);
    const ob_method *ms[4] = {ob_method_find("zhao-rational"), ob_method_find("ahn"), &gappy, &gappy_bs};
    enum { NJ = 4 * OB_SPLIT_COUNT };
    ob_job ref[NJ], got[NJ];
    int n = 0;
    for (int m = 0; m < 4; m++)
        for (int split = 0; split < OB_SPLIT_COUNT; split++) {
            memset(&ref[n], 0, sizeof ref[n]);
            ref[n].curve = &c;
            ref[n].d = 1.0;
            ref[n].method = ms[m];
            ref[n].metric = OB_METRIC_HAUSDORFF;
            ref[n].split = (ob_split)split;
            ref[n].tol = 1e-3;
            n++;
        }
    memcpy(got, ref, sizeof ref);
    ob_driver_opts o;
    ob_driver_defaults(&o);
    o.samples = 64;
    const int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    ob_driver_run(ref, (size_t)n, &o, NULL);
    omp_set_num_threads(2);
    o.chunk = 5;
    ob_driver_run(got, (size_t)n, &o, NULL);
    omp_set_num_threads(nt);
    int same = 1;
    for (int i = 0; i < n; i++)
        same &= ref[i].ctrl_points == got[i].ctrl_points && memcmp(&ref[i].max_gap, &got[i].max_gap, sizeof(double)) == 0 &&
                memcmp(&ref[i].max_kink, &got[i].max_kink, sizeof(double)) == 0 &&
                ref[i].continuity == got[i].continuity && ref[i].open_joints == got[i].open_joints;
    CHECK(same, "joints: 1 thread / batch 512 vs 2 threads / batch 5 give identical results");
    ob_curve_free(&c);
}

/* Jobs without an approximation or without joints have none measured. */
static void test_no_joints(void)
{
    ob_curve c = make_curve("ex1", 1, ex1, 1.0);
    ob_job j;
    ob_span_log L;
    run_job(&j, &c, ob_method_find("cobb"), OB_METRIC_HAUSDORFF, OB_SPLIT_MID, 10.0, &L);
    CHECK(j.status == OB_OK && j.segments == 1 && isnan(j.max_gap) && isnan(j.max_kink) &&
              j.continuity == OB_CONT_NONE && j.ctrl_points == 4,
          "one piece: %d segments, max_gap %g, '%s'", j.segments, j.max_gap, ob_cont_name(j.continuity));
    free(L.v);
    ob_bez_set(&c.seg[0], 1, 1.0, 1.0, 2.0);  /* rational input: tiller takes it, ahn skips */
    run_job(&j, &c, ob_method_find("ahn"), OB_METRIC_HAUSDORFF, OB_SPLIT_MID, 1e-3, &L);
    CHECK(j.status == OB_SKIP && isnan(j.max_gap) && j.continuity == OB_CONT_NONE, "skip: %s, max_gap %g, '%s'",
          ob_status_name(j.status), j.max_gap, ob_cont_name(j.continuity));
    free(L.v);
    ob_curve_free(&c);
}

int main(void)
{
    test_end_tangents();
    test_zhao_rational_gaps();
    test_closed_methods_count();
    test_gappy_counts();
    test_base_corner();
    test_joints_deterministic();
    test_no_joints();
    return check_done();
}
