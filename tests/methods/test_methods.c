/*
 * test_methods.c - the offset approximation methods, reached via the registry.
 *
 * Two kinds of checks:
 *  1. Contract checks run over EVERY registered method, so a new method is
 *     covered as soon as it is added to registry.c: status and message, piece
 *     structure, declared output degree, polynomial output when promised,
 *     finite control points, end-point interpolation (for the methods that are
 *     documented to interpolate), error decreasing under halving, determinism,
 *     no writes outside the caller's storage (guard bytes), and the symmetry
 *     "offset of the reversed curve by -d is the same point set".
 *  2. Properties the papers claim for tiller (exact on straight segments,
 *     translated legs), cobb (P_j + d N(j/n), weights kept) and ahn (Ahn 2023
 *     Prop. 3.3 and section 3.2: degree n+3, C1 and G2 Hermite interpolation
 *     of the offset, a normal field approximant with (N^a)' parallel to C').
 * Test curves: the cubic of liu2002_ex1, a convex quintic, deterministic
 * pseudo-random convex cubics (scaled so that |d| <= 1 stays below the
 * smallest radius of curvature) and, for rational-capable methods, a
 * rational quadratic quarter circle; offsets d = +-0.3, +-1.
 * Convention (curve.h): left normal N = (-y', x')/|C'|, d > 0 to the left.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "methods/core/curve.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"
#include "tests/testlib.h"

static const double DS[] = {0.3, -0.3, 1.0, -1.0};
enum { ND = sizeof DS / sizeof DS[0], MAXC = 8, MSGLEN = 128, GUARD = 64 };

static ob_bez curves[MAXC];
static char cname[MAXC][32];
static int ncurves;

/* ---- small helpers ---------------------------------------------------- */

static uint64_t lcg_state = 0x2545F4914F6CDD1DULL;
static double lcg(void)  /* uniform in [0,1) */
{
    lcg_state = lcg_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(lcg_state >> 11) * 0x1p-53;
}

static double cross(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }

static double max_abs_curvature(const ob_bez *b)
{
    double k = 0.0;
    for (int i = 0; i <= 200; i++)
        k = fmax(k, fabs(ob_bez_curvature(b, i / 200.0)));
    return k;
}

static int is_convex(const ob_bez *b)
{
    double ts[OB_MAX_DEG * 3];
    return ob_bez_inflections(b, ts, OB_MAX_DEG * 3) == 0 && ob_bez_turn(b, 256) < OB_PI;
}

/* Fit with guard bytes around the output, after the scratch space and after
 * the message; checks the guards and that the base is left untouched. */
typedef struct {
    unsigned char pre[GUARD];
    ob_fit fit;
    unsigned char post[GUARD];
} guarded_fit;

static int guard_ok(const unsigned char *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (p[i] != 0xA5)
            return 0;
    return 1;
}

static ob_fit_status run_fit_tol(const ob_method *m, const ob_bez *base, double d, double tol, ob_fit *out,
                                 char msg[MSGLEN])
{
    guarded_fit *g = malloc(sizeof *g);
    unsigned char *work = malloc(m->work_size + GUARD);
    char mbuf[MSGLEN + GUARD];
    if (!g || !work) {
        CHECK(0, "out of memory");
        exit(2);
    }
    memset(g, 0xA5, sizeof *g);
    memset(work, 0xA5, m->work_size + GUARD);
    memset(mbuf, 0xA5, sizeof mbuf);
    mbuf[0] = '\0';
    ob_bez copy = *base;
    double par[OB_MAX_PARAMS];
    ob_param_defaults(m, par);
    const ob_fit_args args = {d, tol, par};
    ob_fit_status st = m->fit(base, &args, work, &g->fit, mbuf, MSGLEN);
    CHECK(guard_ok(g->pre, GUARD) && guard_ok(g->post, GUARD), "%s: wrote outside ob_fit", m->name);
    CHECK(guard_ok(work + m->work_size, GUARD), "%s: wrote past work_size %zu", m->name, m->work_size);
    CHECK(guard_ok((unsigned char *)mbuf + MSGLEN, GUARD) && memchr(mbuf, 0, MSGLEN),
          "%s: message not terminated within msglen", m->name);
    CHECK(memcmp(&copy, base, sizeof copy) == 0, "%s: modified its input", m->name);
    *out = g->fit;
    memcpy(msg, mbuf, MSGLEN);
    msg[MSGLEN - 1] = '\0';
    free(g);
    free(work);
    return st;
}

static ob_fit_status run_fit(const ob_method *m, const ob_bez *base, double d, ob_fit *out, char msg[MSGLEN])
{
    return run_fit_tol(m, base, d, 1e-3, out, msg);
}

/* Bitwise equality of the meaningful part of two fits. */
static int same_fit(const ob_fit *a, const ob_fit *b)
{
    if (a->n != b->n || a->n < 1 || a->n > OB_MAX_PIECES)
        return 0;
    if (memcmp(a->t, b->t, (size_t)(a->n + 1) * sizeof a->t[0]))
        return 0;
    for (int i = 0; i < a->n; i++) {
        const ob_bez *p = &a->seg[i], *q = &b->seg[i];
        if (p->deg != q->deg || p->rational != q->rational || p->deg < 0 || p->deg > OB_MAX_DEG ||
            memcmp(p->h, q->h, (size_t)(p->deg + 1) * sizeof p->h[0]))
            return 0;
    }
    return 1;
}

/* Largest error over the pieces of a fit, each against its part of the base. */
static double fit_error(ob_metric metric, const ob_bez *base, const ob_fit *f, double d)
{
    double worst = 0.0;
    for (int i = 0; i < f->n; i++) {
        ob_bez sub;
        ob_bez_subsegment(base, f->t[i], f->t[i + 1], &sub);
        ob_errval e;
        ob_measure(metric, &sub, &f->seg[i], d, OB_DEFAULT_SAMPLES, &e);
        worst = fmax(worst, e.err);
    }
    return worst;
}

/* Methods whose construction interpolates the offset's end points (README
 * "Methods"). */
static int interpolates_ends(const ob_method *m)
{
    static const char *const names[] = {"tiller", "cobb", "ahn", "kim2018", "liu", "interp", "cubic-opt", NULL};
    for (int i = 0; names[i]; i++)
        if (strcmp(names[i], m->name) == 0)
            return 1;
    return 0;
}

/* ---- test curves -------------------------------------------------------- */

static void add_curve(const char *name, const ob_bez *b)
{
    curves[ncurves] = *b;
    snprintf(cname[ncurves], sizeof cname[ncurves], "%s", name);
    ncurves++;
}

static void make_curves(void)
{
    static const double liu[4][2] = {
        {-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};
    ob_bez b;
    ob_bez_from_points(&b, 3, liu);
    CHECK(is_convex(&b), "liu2002_ex1 is convex with turn < pi");
    add_curve("liu2002_ex1", &b);

    /* convex quintic: points on a widening spiral, 0.45 rad per leg */
    double q[6][2];
    for (int i = 0; i <= 5; i++) {
        double r = 2.5 + 0.25 * i, th = 0.45 * i;
        q[i][0] = r * cos(th);
        q[i][1] = r * sin(th);
    }
    ob_bez_from_points(&b, 5, q);
    CHECK(is_convex(&b), "quintic is convex with turn < pi");
    CHECK(max_abs_curvature(&b) < 1.0 / 1.2, "quintic: radius of curvature > 1.2");
    add_curve("quintic", &b);

    /* pseudo-random convex cubics: legs turning the same way by 0.2..1.1 rad */
    for (int c = 0; c < 4; c++) {
        for (int tries = 0; tries < 100; tries++) {
            double p[4][2] = {{4 * lcg() - 2, 4 * lcg() - 2}};
            double th = 2 * OB_PI * lcg(), sg = lcg() < 0.5 ? -1.0 : 1.0;
            for (int i = 1; i <= 3; i++) {
                double len = 0.5 + lcg();
                p[i][0] = p[i - 1][0] + len * cos(th);
                p[i][1] = p[i - 1][1] + len * sin(th);
                th += sg * (0.2 + 0.9 * lcg());
            }
            /* scale so that the radius of curvature is >= 1.5 > max |d| */
            ob_bez_from_points(&b, 3, p);
            double s = fmax(1.0, 1.5 * max_abs_curvature(&b));
            for (int i = 0; i <= 3; i++)
                p[i][0] *= s, p[i][1] *= s;
            ob_bez_from_points(&b, 3, p);
            if (is_convex(&b))
                break;
        }
        CHECK(is_convex(&b), "random cubic %d is convex with turn < pi", c);
        char name[32];
        snprintf(name, sizeof name, "random%d", c);
        add_curve(name, &b);
    }
}

/* ---- 1 + 5: contract checks for every method ----------------------------- */

static void check_structure(const ob_method *m, const char *cn, const ob_bez *C, double d,
                            const ob_fit *f)
{
    CHECK(f->n >= 1 && f->n <= OB_MAX_PIECES, "%s/%s/%g: %d pieces", m->name, cn, d, f->n);
    if (f->n < 1 || f->n > OB_MAX_PIECES)
        return;
    int incr = f->t[0] == 0.0 && f->t[f->n] == 1.0;
    for (int i = 0; i < f->n; i++)
        incr &= f->t[i] < f->t[i + 1];
    CHECK(incr, "%s/%s/%g: t[0]=0 < ... < t[n]=1", m->name, cn, d);
    int want = ob_method_out_degree(m, C->deg, C->rational, NULL);
    for (int i = 0; i < f->n; i++) {
        const ob_bez *s = &f->seg[i];
        CHECK(s->deg == want, "%s/%s/%g: piece %d degree %d, out_degree says %d", m->name, cn, d,
              i, s->deg, want);
        if (s->deg < 0 || s->deg > OB_MAX_DEG)
            continue;
        int finite = 1, poly = 1;
        for (int k = 0; k <= s->deg; k++) {
            finite &= isfinite(s->h[k][0]) && isfinite(s->h[k][1]) && isfinite(s->h[k][2]);
            poly &= s->h[k][2] == 1.0;
        }
        CHECK(finite, "%s/%s/%g: piece %d has non-finite control points", m->name, cn, d, i);
        if ((m->caps & OB_CAP_POLY_OUT) && !C->rational)
            CHECK(poly, "%s/%s/%g: piece %d: weights not all 1 (OB_CAP_POLY_OUT)", m->name, cn, d, i);
    }
    if (interpolates_ends(m)) {
        double o[2], a[2];
        ob_bez_offset_point(C, 0.0, d, o);
        ob_bez_point(&f->seg[0], 0.0, a);
        CHECK(dist2d(o, a) < 1e-12, "%s/%s/%g: start %.17g,%.17g vs offset %.17g,%.17g", m->name,
              cn, d, a[0], a[1], o[0], o[1]);
        ob_bez_offset_point(C, 1.0, d, o);
        ob_bez_point(&f->seg[f->n - 1], 1.0, a);
        CHECK(dist2d(o, a) < 1e-12, "%s/%s/%g: end %.17g,%.17g vs offset %.17g,%.17g", m->name, cn,
              d, a[0], a[1], o[0], o[1]);
    }
}

static void test_generic(const ob_method *m, const char *cn, const ob_bez *C, double d)
{
    static ob_fit f, f2, h0, h1;
    char msg[MSGLEN];
    ob_fit_status st = run_fit(m, C, d, &f, msg);
    CHECK(st == OB_FIT_OK || ((st == OB_FIT_SKIP || st == OB_FIT_RETRY_SMALLER) && msg[0]), "%s/%s/%g: status %s (%s)",
          m->name, cn, d, ob_fit_status_name(st), msg);
    if (st != OB_FIT_OK)
        return;
    check_structure(m, cn, C, d, &f);
    if (f.n < 1 || f.n > OB_MAX_PIECES)
        return;

    /* determinism */
    ob_fit_status st2 = run_fit(m, C, d, &f2, msg);
    CHECK(st2 == OB_FIT_OK && same_fit(&f, &f2), "%s/%s/%g: two fits differ", m->name, cn, d);

    /* a fit that claims to ignore the tolerance gives the same bits at any
     * (the driver then shares it among the jobs that differ in tol only) */
    if (!ob_method_fit_uses_tol(m, NULL)) {
        const double tols[2] = {1e-1, 1e-6};
        for (int k = 0; k < 2; k++) {
            ob_fit_status st3 = run_fit_tol(m, C, d, tols[k], &f2, msg);
            CHECK(st3 == OB_FIT_OK && same_fit(&f, &f2), "%s/%s/%g: the fit at tol %g differs from the fit at 1e-3 "
                  "(the method does not declare fit_uses_tol)", m->name, cn, d, tols[k]);
        }
    }

    /* halving reduces the Hausdorff error (unless the method's accuracy is set
     * by the tolerance, not by the piece) */
    double whole = fit_error(OB_METRIC_HAUSDORFF, C, &f, d);
    CHECK(isfinite(whole), "%s/%s/%g: error %g", m->name, cn, d, whole);
    if (whole > 1e-6 && (m->caps & OB_CAP_TOL_DRIVEN))
        SKIP("halving: the method declares OB_CAP_TOL_DRIVEN");
    else if (whole > 1e-6) {
        ob_bez L, R;
        ob_bez_subsegment(C, 0.0, 0.5, &L);
        ob_bez_subsegment(C, 0.5, 1.0, &R);
        ob_fit_status s0 = run_fit(m, &L, d, &h0, msg), s1 = run_fit(m, &R, d, &h1, msg);
        CHECK((s0 == OB_FIT_OK || s0 == OB_FIT_RETRY_SMALLER) && (s1 == OB_FIT_OK || s1 == OB_FIT_RETRY_SMALLER),
              "%s/%s/%g: halves: %s %s", m->name, cn, d, ob_fit_status_name(s0), ob_fit_status_name(s1));
        if (s0 == OB_FIT_OK && s1 == OB_FIT_OK) {
            double e0 = fit_error(OB_METRIC_HAUSDORFF, &L, &h0, d);
            double e1 = fit_error(OB_METRIC_HAUSDORFF, &R, &h1, d);
            /* a fit of several pieces (split at offset cusps, say) may keep
             * its worst piece whole in one half: then no larger */
            const double allow = f.n > 1 ? whole * (1 + 1e-6) : whole;
            CHECK(fmax(e0, e1) < whole || (f.n > 1 && fmax(e0, e1) <= allow), "%s/%s/%g: halves %.3g %.3g, "
                  "whole %.3g (%d pieces)", m->name, cn, d, e0, e1, whole, f.n);
        }
    }

    /* symmetry: the reversed curve offset by -d is the same point set */
    ob_bez Cr = reversed(C);
    ob_fit_status sr = run_fit(m, &Cr, -d, &f2, msg);
    CHECK(sr == OB_FIT_OK || sr == OB_FIT_RETRY_SMALLER, "%s/%s/%g: reversed: %s (%s)", m->name, cn, d,
          ob_fit_status_name(sr), msg);
    if (m->caps & OB_CAP_ORIENTED)
        SKIP("reversal symmetry: the method declares OB_CAP_ORIENTED");
    else if (sr == OB_FIT_OK && f2.n >= 1 && f2.n <= OB_MAX_PIECES) {
        double er = fit_error(OB_METRIC_HAUSDORFF, &Cr, &f2, -d);
        CHECK_NEAR(er, whole, 1e-9, "reversed curve, -d: hausdorff error");
    }
}

/* ---- 2: tiller ------------------------------------------------------------ */

static void test_tiller(void)
{
    const ob_method *m = ob_method_find("tiller");
    CHECK(m != NULL, "tiller registered");
    if (!m)
        return;
    static ob_fit f;
    char msg[MSGLEN];
    /* collinear control polygons, in order, non-uniform spacing */
    const double P0[2] = {0.1, -0.2}, dir[2] = {3.0, 2.0};
    const double len = hypot(dir[0], dir[1]), nrm[2] = {-dir[1] / len, dir[0] / len};
    static const double s3[] = {0, 0.07, 0.6, 1}, s5[] = {0, 0.1, 0.15, 0.5, 0.8, 1};
    for (int which = 0; which < 2; which++) {
        int n = which ? 5 : 3;
        const double *s = which ? s5 : s3;
        double p[6][2];
        for (int i = 0; i <= n; i++)
            p[i][0] = P0[0] + s[i] * dir[0], p[i][1] = P0[1] + s[i] * dir[1];
        ob_bez C;
        ob_bez_from_points(&C, n, p);
        for (int k = 0; k < 2; k++) {
            double d = DS[k];
            ob_fit_status st = run_fit(m, &C, d, &f, msg);
            CHECK(st == OB_FIT_OK && f.n == 1, "tiller line deg %d d %g: %s", n, d, msg);
            if (st != OB_FIT_OK)
                continue;
            for (ob_metric mt = 0; mt < OB_METRIC_COUNT; mt++) {
                ob_errval e;
                ob_measure(mt, &C, &f.seg[0], d, OB_DEFAULT_SAMPLES, &e);
                CHECK(e.err < 1e-12, "tiller line deg %d d %g: %s error %g", n, d,
                      ob_metric_name(mt), e.err);
            }
            for (int i = 0; i <= n; i++) {
                double q[2];
                ob_bez_ctrl(&f.seg[0], i, q);
                CHECK_NEAR(q[0], p[i][0] + d * nrm[0], 1e-14, "tiller line: x moved by d n");
                CHECK_NEAR(q[1], p[i][1] + d * nrm[1], 1e-14, "tiller line: y moved by d n");
            }
        }
    }
    /* general polygons: Q_j at signed distance d from both adjacent legs' lines */
    for (int c = 0; c < ncurves; c++) {
        const ob_bez *C = &curves[c];
        for (int k = 0; k < ND; k++) {
            double d = DS[k];
            if (run_fit(m, C, d, &f, msg) != OB_FIT_OK)
                continue;
            int n = C->deg;
            for (int j = 0; j <= n; j++) {
                double q[2], a[2], b[2];
                ob_bez_ctrl(&f.seg[0], j, q);
                for (int leg = j - 1; leg <= j; leg++) {
                    if (leg < 0 || leg >= n)
                        continue;
                    ob_bez_ctrl(C, leg, a);
                    ob_bez_ctrl(C, leg + 1, b);
                    double u[2] = {b[0] - a[0], b[1] - a[1]}, v[2] = {q[0] - a[0], q[1] - a[1]};
                    CHECK_NEAR(cross(u, v) / hypot(u[0], u[1]), d, 1e-12,
                               "tiller: signed distance of Q_j to an adjacent leg");
                }
            }
        }
    }
}

/* ---- 3: cobb -------------------------------------------------------------- */

static void check_cobb_points(const ob_method *m, const char *cn, const ob_bez *C, double d)
{
    static ob_fit f;
    char msg[MSGLEN];
    ob_fit_status st = run_fit(m, C, d, &f, msg);
    CHECK(st == OB_FIT_OK && f.n == 1 && f.seg[0].deg == C->deg, "cobb %s %g: %s", cn, d, msg);
    if (st != OB_FIT_OK || f.n != 1 || f.seg[0].deg != C->deg)
        return;
    for (int j = 0; j <= C->deg; j++) {
        double P[2], N[2], q[2];
        ob_bez_ctrl(C, j, P);
        ob_bez_normal(C, (double)j / C->deg, N);
        ob_bez_ctrl(&f.seg[0], j, q);
        CHECK(dist2d(q, (double[2]){P[0] + d * N[0], P[1] + d * N[1]}) <= 1e-14,
              "cobb %s %g: P_%d not moved by d N(j/n)", cn, d, j);
        CHECK(ob_bez_weight(&f.seg[0], j) == ob_bez_weight(C, j), "cobb %s %g: weight %d changed",
              cn, d, j);
    }
}

static void test_cobb(void)
{
    const ob_method *m = ob_method_find("cobb");
    CHECK(m != NULL, "cobb registered");
    if (!m)
        return;
    for (int c = 0; c < ncurves; c++)
        for (int k = 0; k < ND; k++)
            check_cobb_points(m, cname[c], &curves[c], DS[k]);
    ob_bez qc = quarter_circle(1.0, 0);
    CHECK(qc.rational, "quarter circle is rational");
    for (int k = 0; k < 2; k++)
        check_cobb_points(m, "quarter circle", &qc, DS[k]);
}

/* ---- 4: ahn ----------------------------------------------------------------- */

static void check_ahn_hermite(const ob_method *m, const char *cn, const ob_bez *C, double d0)
{
    static ob_fit f;
    char msg[MSGLEN];
    const int n = C->deg;
    /* keep 1 - d kappa >= 0.5 at the ends, so the offset is regular there */
    double k0 = ob_bez_curvature(C, 0.0), k1 = ob_bez_curvature(C, 1.0);
    double d = d0 * fmin(1.0, 0.5 / fmax(fabs(k0), fabs(k1)));
    ob_fit_status st = run_fit(m, C, d, &f, msg);
    CHECK(st == OB_FIT_OK && f.n == 1, "ahn %s %g: %s (%s)", cn, d, ob_fit_status_name(st), msg);
    if (st != OB_FIT_OK || f.n != 1)
        return;
    const ob_bez *A = &f.seg[0];
    CHECK(A->deg == n + 3 && !A->rational, "ahn %s %g: degree %d, rational %d", cn, d, A->deg,
          A->rational);
    if (A->deg != n + 3)
        return;
    for (int i = 0; i <= 1; i++) {
        double t = i, a[3][2], c[3][2], o[2];
        ob_bez_eval(A, t, 2, a);
        ob_bez_eval(C, t, 2, c);
        ob_bez_offset_point(C, t, d, o);
        double kap = ob_bez_curvature(C, t), g = 1.0 - d * kap;
        CHECK(dist2d(a[0], o) < 1e-12, "ahn %s %g: A(%d) vs C + d N: %g", cn, d, i, dist2d(a[0], o));
        double dO[2] = {c[1][0] * g, c[1][1] * g};
        CHECK(dist2d(a[1], dO) <= 1e-9 * hypot(dO[0], dO[1]), "ahn %s %g: A'(%d) %.17g,%.17g vs "
              "O' %.17g,%.17g", cn, d, i, a[1][0], a[1][1], dO[0], dO[1]);
        double ka = ob_bez_curvature(A, t), ko = kap / g;
        CHECK(fabs(ka - ko) <= 1e-8 * fabs(ko), "ahn %s %g: curvature at %d: %.17g vs offset "
              "%.17g", cn, d, i, ka, ko);
    }
    /* the normal field approximant N^a = (A - C)/d */
    ob_bez Ce, Na;
    CHECK(ob_bez_elevate(C, n + 3, &Ce) == 0, "elevate");
    double na[OB_MAX_DEG + 1][2];
    for (int k = 0; k <= n + 3; k++) {
        na[k][0] = (A->h[k][0] - Ce.h[k][0]) / d;
        na[k][1] = (A->h[k][1] - Ce.h[k][1]) / d;
    }
    ob_bez_from_points(&Na, n + 3, (const double(*)[2])na);
    for (int i = 0; i <= 1; i++) {
        double N[2], v[2];
        ob_bez_normal(C, i, N);
        ob_bez_point(&Na, i, v);
        CHECK(dist2d(v, N) < 1e-12, "ahn %s %g: N^a(%d) = %.17g,%.17g vs N %.17g,%.17g", cn, d, i,
              v[0], v[1], N[0], N[1]);
    }
    int parallel = 1;
    double worst = 0.0;
    for (int k = 0; k <= 40; k++) {
        double t = k / 40.0, a[2][2], c[2][2];
        ob_bez_eval(&Na, t, 1, a);
        ob_bez_eval(C, t, 1, c);
        double ca = hypot(c[1][0], c[1][1]), na1 = hypot(a[1][0], a[1][1]);
        double r = fabs(cross(a[1], c[1])) / (ca * (na1 + ca));
        worst = fmax(worst, r);
        parallel &= r < 1e-10;
    }
    CHECK(parallel, "ahn %s %g: (N^a)' not parallel to C' (relative cross %g)", cn, d, worst);
}

/* Segments that the `mid` split rule needs for radial error <= tol. */
static int count_mid_split(const ob_method *m, const ob_bez *C, double d, double tol, int depth)
{
    static ob_fit f;
    char msg[MSGLEN];
    if (run_fit(m, C, d, &f, msg) != OB_FIT_OK)
        return 1000;
    if (fit_error(OB_METRIC_RADIAL, C, &f, d) <= tol || depth >= 12)
        return 1;
    ob_bez L, R;
    ob_bez_split(C, 0.5, &L, &R);
    return count_mid_split(m, &L, d, tol, depth + 1) + count_mid_split(m, &R, d, tol, depth + 1);
}

static void test_ahn(void)
{
    const ob_method *m = ob_method_find("ahn");
    CHECK(m != NULL, "ahn registered");
    if (!m)
        return;
    CHECK(ob_method_out_degree(m, 3, 0, NULL) == 6 && ob_method_out_degree(m, 5, 0, NULL) == 8, "ahn: out_degree n+3");
    for (int c = 0; c < ncurves; c++)
        for (int k = 0; k < ND; k++)
            check_ahn_hermite(m, cname[c], &curves[c], DS[k]);

    static ob_fit f;
    char msg[MSGLEN];
    ob_bez qc = quarter_circle(1.0, 0);
    ob_fit_status st = run_fit(m, &qc, 0.3, &f, msg);
    CHECK(st == OB_FIT_SKIP && msg[0], "ahn: rational input gives %s (%s)", ob_fit_status_name(st), msg);

    /* a straight segment: kappa = 0, N^a = N, the offset is exact */
    static const double line[4][2] = {{0.1, -0.2}, {0.31, -0.06}, {1.9, 1.0}, {3.1, 1.8}};
    ob_bez L;
    ob_bez_from_points(&L, 3, line);
    for (int k = 0; k < 2; k++) {
        st = run_fit(m, &L, DS[k], &f, msg);
        CHECK(st == OB_FIT_OK, "ahn: straight cubic, d %g: %s (%s)", DS[k], ob_fit_status_name(st), msg);
        if (st == OB_FIT_OK)
            CHECK(fit_error(OB_METRIC_HAUSDORFF, &L, &f, DS[k]) < 1e-12, "ahn: straight cubic, d "
                  "%g: error %g", DS[k], fit_error(OB_METRIC_HAUSDORFF, &L, &f, DS[k]));
    }

    /* Ahn Table 1, liu2002_ex1, radial metric, mid split: 13, 19, 31, 43, 61
     * control points (6k + 1) at tol 1e-1 .. 1e-5.  The radial error does not
     * depend on the sign of d (A - C = d N^a), so both signs give the column.
     * The whole curve (turn 3.02 rad, close to pi) has radial error 0.276:
     * more than 0.1, as the 2 segments at tol 0.1 require. */
    static const int published[5] = {13, 19, 31, 43, 61};
    for (int k = 2; k < ND; k++) {
        double tol = 0.1;
        for (int i = 0; i < 5; i++, tol /= 10) {
            int segs = count_mid_split(m, &curves[0], DS[k], tol, 0);
            CHECK(6 * segs + 1 == published[i], "ahn liu2002_ex1 d %g tol %g: %d control points, "
                  "Ahn Table 1 has %d", DS[k], tol, 6 * segs + 1, published[i]);
        }
    }
    const ob_bez *C = &curves[0];
    for (int h = 0; h < 2; h++) {
        ob_bez H;
        ob_bez_subsegment(C, 0.5 * h, 0.5 * h + 0.5, &H);
        st = run_fit(m, &H, 1.0, &f, msg);
        CHECK(st == OB_FIT_OK, "ahn liu2002_ex1 half %d: %s", h, msg);
        if (st == OB_FIT_OK) {
            double e = fit_error(OB_METRIC_RADIAL, &H, &f, 1.0);
            CHECK(e < 0.1, "ahn liu2002_ex1 d=1: radial error %g (half %d)", e, h);
        }
    }
}

/* Every parameter of every registered method has a documented range
 * (method.h) that holds its default, and ob_param_check (what --param
 * applies) accepts exactly that range; fit() does not reject a value at
 * either end of it. */
static void test_param_ranges(const ob_method *m)
{
    char msg[256];
    CHECK(m->nparams >= 0 && m->nparams <= OB_MAX_PARAMS && (m->nparams == 0 || m->params),
          "%s: %d parameters", m->name, m->nparams);
    for (int k = 0; k < m->nparams; k++) {
        const ob_param *p = &m->params[k];
        CHECK(p->name && p->name[0] && p->doc && p->doc[0], "%s: parameter %d has a name and a doc", m->name, k);
        CHECK(isfinite(p->min) && isfinite(p->max) && p->min < p->max, "%s.%s: range %g..%g", m->name, p->name,
              p->min, p->max);
        CHECK(p->def >= p->min && p->def <= p->max, "%s.%s: default %g inside %g..%g", m->name, p->name, p->def,
              p->min, p->max);
        if (p->integer)
            CHECK(p->min == floor(p->min) && p->max == floor(p->max) && p->def == floor(p->def),
                  "%s.%s: whole-number range and default", m->name, p->name);
        CHECK(ob_param_check(m, p, p->def, msg, sizeof msg) == 0, "%s.%s: default accepted", m->name, p->name);
        CHECK(ob_param_check(m, p, p->min, msg, sizeof msg) == 0, "%s.%s: min accepted", m->name, p->name);
        CHECK(ob_param_check(m, p, p->max, msg, sizeof msg) == 0, "%s.%s: max accepted", m->name, p->name);
        const double below = p->integer ? p->min - 1 : nextafter(p->min, -INFINITY);
        const double above = p->integer ? p->max + 1 : nextafter(p->max, INFINITY);
        CHECK(ob_param_check(m, p, below, msg, sizeof msg) != 0 && strstr(msg, p->name) && strstr(msg, "range"),
              "%s.%s: %g refused with a message naming it: %s", m->name, p->name, below, msg);
        CHECK(ob_param_check(m, p, above, msg, sizeof msg) != 0, "%s.%s: %g refused", m->name, p->name, above);
        CHECK(ob_param_check(m, p, NAN, msg, sizeof msg) != 0, "%s.%s: nan refused", m->name, p->name);
        if (p->integer)
            CHECK(ob_param_check(m, p, p->min + 0.5, msg, sizeof msg) != 0, "%s.%s: %g refused (not whole)",
                  m->name, p->name, p->min + 0.5);
        /* fit() itself takes both ends (on liu2002_ex1: any status, but not
         * a complaint about the parameter) */
        static const double ends_skip_slow = 1000; /* a timeout or pass count above this is not run */
        for (int e = 0; e < 2; e++) {
            double par[OB_MAX_PARAMS];
            ob_param_defaults(m, par);
            par[k] = e ? p->max : p->min;
            if (par[k] > ends_skip_slow && p->integer)
                continue;
            if (strcmp(m->name, "sisl") == 0 && strcmp(p->name, "timeout") == 0)
                continue;
            void *work = m->work_size ? malloc(m->work_size) : NULL;
            ob_fit f;
            msg[0] = '\0';
            const ob_fit_args a = {0.5, 1e-2, par};
            ob_fit_status st = m->fit(&curves[0], &a, work, &f, msg, sizeof msg);
            free(work);
            CHECK(st == OB_FIT_OK || st == OB_FIT_RETRY_SMALLER || !(strstr(msg, "range") || strstr(msg, "must be")),
                  "%s.%s = %g: fit refuses a value inside the range: %s", m->name, p->name, par[k], msg);
            /* the degree the method declares for these values is every piece's */
            const int want = ob_method_out_degree(m, curves[0].deg, curves[0].rational, par);
            for (int i = 0; st == OB_FIT_OK && i < f.n; i++)
                CHECK(f.seg[i].deg == want, "%s.%s = %g: piece %d has degree %d, out_degree says %d", m->name,
                      p->name, par[k], i, f.seg[i].deg, want);
        }
    }
}

int main(void)
{
    make_curves();
    CHECK(ob_methods[0] != NULL, "at least one method registered");
    ob_bez qc = quarter_circle(2.5, 0);
    for (int i = 0; ob_methods[i]; i++) {
        const ob_method *m = ob_methods[i];
        CHECK(m->name && m->name[0] && m->fit && m->out_degree, "method %d incomplete", i);
        CHECK(m->version >= 1, "%s: has a version (meta.json method_versions), got %d", m->name, m->version);
        CHECK(ob_method_find(m->name) == m, "%s: found by name", m->name);
        CHECK(m->cost_ms > 0 && m->cost_ms < 1e4, "%s: a cost for --shard's model (cost_ms, method.h), got %g",
              m->name, m->cost_ms);
        test_param_ranges(m);
        for (int c = 0; c < ncurves; c++)
            for (int k = 0; k < ND; k++)
                test_generic(m, cname[c], &curves[c], DS[k]);
        if (m->caps & OB_CAP_RATIONAL_IN)
            for (int k = 0; k < ND; k++)
                test_generic(m, "quarter circle r 2.5", &qc, DS[k]);
    }
    test_tiller();
    test_cobb();
    test_ahn();
    return check_done();
}
