/*
 * test_random.c - the random test families of `--random N[:SEED]`
 * (host/io/random.c).
 *
 * Determinism (a curve is a function of (seed, index) alone: not of N, the
 * threads, or the other curves generated), the id and source format, the
 * spread over families, and each family's defining property, checked on 800
 * curves of two seeds with computations independent of the generator
 * (curvature and derivatives from testlib.h's ref_eval, control polygons read
 * back from the homogeneous points).  Also the spec parser, id selection and
 * id clashes with loaded curve files.
 */
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/testlib.h"
#include "host/io/curvefile.h"
#include "host/diag.h"
#include "host/io/random.h"

static char last_error[512];
static void capture(const char *m) { snprintf(last_error, sizeof last_error, "%s", m); }

static int same_curve(const ob_curve *a, const ob_curve *b)
{
    if (strcmp(a->id, b->id) || strcmp(a->family, b->family) || strcmp(a->source, b->source) ||
        a->nseg != b->nseg || a->nd != b->nd)
        return 0;
    for (int s = 0; s < a->nseg; s++)
        if (a->seg[s].deg != b->seg[s].deg || a->seg[s].rational != b->seg[s].rational ||
            memcmp(a->seg[s].h, b->seg[s].h, (size_t)(a->seg[s].deg + 1) * sizeof a->seg[s].h[0]))
            return 0;
    return memcmp(a->d, b->d, (size_t)a->nd * sizeof *a->d) == 0;
}

/* Euclidean control points and weights read back from the homogeneous form. */
static void polygon(const ob_bez *b, double (*p)[2], double *w)
{
    for (int k = 0; k <= b->deg; k++) {
        w[k] = b->h[k][2];
        p[k][0] = b->h[k][0] / w[k];
        p[k][1] = b->h[k][1] / w[k];
    }
}

static double legk(const double (*p)[2], int k) { return hypot(p[k + 1][0] - p[k][0], p[k + 1][1] - p[k][1]); }

/* Distance of point q from the line through a and b. */
static double line_dist(const double a[2], const double b[2], const double q[2])
{
    double ux = b[0] - a[0], uy = b[1] - a[1];
    return fabs(ux * (q[1] - a[1]) - uy * (q[0] - a[0])) / hypot(ux, uy);
}

static double ref_kappa(const ob_bez *b, double t)
{
    double o[3][2];
    ref_eval(b, t, 2, o);
    double s = hypot(o[1][0], o[1][1]);
    return (o[1][0] * o[2][1] - o[1][1] * o[2][0]) / (s * s * s);
}

/* max |kappa| by a 4096-point scan and golden-section refinement of every
 * scan maximum within 10 % of the largest; *sign: the sign of kappa there. */
static double ref_max_kappa(const ob_bez *b, int *sign)
{
    enum { S = 4096 };
    static double k[S + 1];
    double best = 0;
    for (int i = 0; i <= S; i++) {
        k[i] = ref_kappa(b, (double)i / S);
        best = fmax(best, fabs(k[i]));
    }
    double top = 0;
    *sign = 0;
    for (int i = 0; i <= S; i++) {
        double ai = fabs(k[i]);
        if (ai < 0.9 * best || (i > 0 && fabs(k[i - 1]) > ai) || (i < S && fabs(k[i + 1]) > ai))
            continue;
        double s = k[i] < 0 ? -1 : 1, a = (i > 0 ? i - 1.0 : 0.0) / S, c = (i < S ? i + 1.0 : S) / S;
        for (int it = 0; it < 60; it++) {
            double m1 = a + (c - a) / 3, m2 = c - (c - a) / 3;
            if (s * ref_kappa(b, m1) > s * ref_kappa(b, m2))
                c = m2;
            else
                a = m1;
        }
        double f = fmax(ai, s * ref_kappa(b, 0.5 * (a + c)));
        if (f > top) {
            top = f;
            *sign = (int)s;
        }
    }
    return top;
}

/* min |C'| / max |C'| over 65 parameters. */
static double speed_ratio(const ob_bez *b)
{
    double lo = INFINITY, hi = 0;
    for (int i = 0; i <= 64; i++) {
        double o[2][2];
        ref_eval(b, i / 64.0, 1, o);
        double s = hypot(o[1][0], o[1][1]);
        lo = fmin(lo, s);
        hi = fmax(hi, s);
    }
    return lo / hi;
}

/* A sign change of x'y'' - y'x'' inside [0.04, 0.96] on a fine grid. */
static int grid_inflection(const ob_bez *b)
{
    double prev = 0;
    for (int i = 0; i <= 4000; i++) {
        double o[3][2];
        ref_eval(b, 0.04 + 0.92 * i / 4000.0, 2, o);
        double c = o[1][0] * o[2][1] - o[1][1] * o[2][0];
        if (i && c * prev < 0)
            return 1;
        if (c != 0)
            prev = c;
    }
    return 0;
}

/* Well-conditioned polygon: legs >= 0.05, width >= 0.1, no stall. */
static int generic_ok(const ob_bez *b, const double (*p)[2])
{
    int n = b->deg;
    double w = 0;
    for (int k = 0; k < n; k++)
        if (legk(p, k) < 0.05)
            return 0;
    int closed = hypot(p[n][0] - p[0][0], p[n][1] - p[0][1]) < 0.05;
    for (int k = 1; k < n; k++)
        w = fmax(w, closed ? hypot(p[k][0] - p[0][0], p[k][1] - p[0][1]) : line_dist(p[0], p[n], p[k]));
    return w >= 0.1 && speed_ratio(b) >= 0.05 * (1 - 1e-12);
}

static void test_ids_and_parse(void)
{
    char id[64];
    ob_random_id(7, 42, id, sizeof id);
    CHECK(strcmp(id, "rnd7_000042") == 0, "id %s", id);
    ob_random_id(18446744073709551615ULL, 9999999, id, sizeof id);
    CHECK(strcmp(id, "rnd18446744073709551615_9999999") == 0, "id %s", id);

    long n = -1;
    uint64_t seed = 99;
    CHECK(ob_random_parse("--random", "500", &n, &seed) == 0 && n == 500 && seed == 1, "500 -> %ld:%llu", n,
          (unsigned long long)seed);
    CHECK(ob_random_parse("--random", "24:3", &n, &seed) == 0 && n == 24 && seed == 3, "24:3");
    CHECK(ob_random_parse("--random", "10000000:0", &n, &seed) == 0 && n == 10000000 && seed == 0, "max N, seed 0");
    CHECK(ob_random_parse("--random", "1:18446744073709551615", &n, &seed) == 0 && seed == UINT64_MAX, "max seed");
    ob_error_handler old = ob_set_error_handler(capture);
    const char *bad[] = {"0", "abc", "5:", "5:x", "", ":3", "-5", "+5", " 5", "5 ", "10000001", "1e3",
                         "5:-1", "5:3:4", "5:18446744073709551616", "99999999999999999999999", "5:0x10"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        last_error[0] = '\0';
        int rc = ob_random_parse("--random", bad[i], &n, &seed);
        CHECK(rc == -1 && strstr(last_error, "--random"), "'%s' must be refused naming the option: rc %d, '%s'",
              bad[i], rc, last_error);
    }
    ob_set_error_handler(old);
}

static void test_determinism(void)
{
    /* the same (seed, index) in separate calls */
    int same = 1;
    for (long i = 0; i < 64; i++) {
        ob_curve a, b;
        ob_random_curve(7, i, &a);
        ob_curve c;
        ob_random_curve(7, i + 1000, &c); /* something in between */
        ob_random_curve(7, i, &b);
        same &= same_curve(&a, &b);
        ob_curve_free(&a);
        ob_curve_free(&b);
        ob_curve_free(&c);
    }
    CHECK(same, "a curve is a function of (seed, index)");

    /* regardless of N and of the thread count */
    ob_curveset s100 = {0}, s1000 = {0}, s1 = {0};
    ob_err err = {""};
    omp_set_num_threads(2);
    CHECK(ob_random_append(&s100, 7, 100, NULL, 0, &err) == 0 && s100.n == 100, "append 100");
    CHECK(ob_random_append(&s1000, 7, 1000, NULL, 0, &err) == 0 && s1000.n == 1000, "append 1000");
    omp_set_num_threads(1);
    CHECK(ob_random_append(&s1, 7, 1000, NULL, 0, &err) == 0 && s1.n == 1000, "append 1000, 1 thread");
    omp_set_num_threads(2);
    int agree = s100.n == 100 && s1000.n == 1000 && s1.n == 1000;
    for (int i = 0; agree && i < 100; i++)
        agree &= same_curve(&s100.v[i], &s1000.v[i]);
    CHECK(agree, "curve i of --random 100:7 is curve i of --random 1000:7");
    agree = s1000.n == 1000 && s1.n == 1000;
    for (int i = 0; agree && i < 1000; i++)
        agree &= same_curve(&s1.v[i], &s1000.v[i]);
    CHECK(agree, "1 and 2 threads generate the same curves");
    int direct = 1;
    for (int i = 0; i < s1000.n; i += 37) {
        ob_curve c;
        ob_random_curve(7, i, &c);
        direct &= same_curve(&c, &s1000.v[i]);
        ob_curve_free(&c);
    }
    CHECK(direct, "the set holds exactly ob_random_curve(seed, i)");

    /* different seeds differ: every curve, in its control points */
    int differ = 0;
    for (long i = 0; i < 200; i++) {
        ob_curve a, b;
        ob_random_curve(7, i, &a);
        ob_random_curve(8, i, &b);
        differ += a.seg[0].deg != b.seg[0].deg ||
                  memcmp(a.seg[0].h, b.seg[0].h, (size_t)(a.seg[0].deg + 1) * sizeof a.seg[0].h[0]) != 0;
        ob_curve_free(&a);
        ob_curve_free(&b);
    }
    CHECK(differ == 200, "seeds 7 and 8 differ on %d of 200 curves", differ);
    /* and no two curves of one seed share a control point */
    double *x0 = malloc((size_t)s1000.n * sizeof *x0);
    int ndup = 0;
    if (x0) {
        for (int i = 0; i < s1000.n; i++)
            x0[i] = s1000.v[i].seg[0].h[1][0] / s1000.v[i].seg[0].h[1][2];
        for (int i = 0; i < s1000.n; i++)
            for (int j = i + 1; j < s1000.n; j++)
                ndup += x0[i] == x0[j];
        free(x0);
    }
    CHECK(x0 && ndup == 0, "the 1000 curves of seed 7 are distinct: %d pairs share P_1.x", ndup);

    /* --curve selection: only the listed random ids, in index order */
    char *ids[] = {"rnd7_000005", "rnd7_5", "rnd8_000001", "liu2002_ex1", "rnd7_000003",
                   "rnd7_000005", "rnd7_000100", "rnd7_", "rnd7_00000x", "rnd7_0000003"};
    ob_curveset sel = {0};
    int rc = ob_random_append(&sel, 7, 100, ids, (int)(sizeof ids / sizeof *ids), &err);
    CHECK(rc == 0 && sel.n == 2, "selection: rc %d, %d curves", rc, sel.n);
    if (sel.n == 2) {
        CHECK(same_curve(&sel.v[0], &s1000.v[3]) && same_curve(&sel.v[1], &s1000.v[5]),
              "selected curves are curves 3 and 5: %s %s", sel.v[0].id, sel.v[1].id);
    }
    ob_curveset_free(&sel);
    ob_curveset_free(&s100);
    ob_curveset_free(&s1000);
    ob_curveset_free(&s1);
}

static void test_clash(void)
{
    const char *text = "curve rnd7_000002\n source x\n bezier 1\n point 0 0\n point 1 0\n offset 1\nend\n"
                       "curve mine\n source x\n bezier 1\n point 0 0\n point 1 0\n offset 1\nend\n";
    ob_curveset set = {0};
    ob_err err = {""};
    CHECK(ob_curves_parse(text, strlen(text), "x.curves", &set, &err) == 0 && set.n == 2, "parse: %s",
          err.msg);
    int rc = ob_random_append(&set, 7, 10, NULL, 0, &err);
    CHECK(rc == -1 && set.n == 2 && strstr(err.msg, "rnd7_000002") && strstr(err.msg, "x.curves:1"),
          "a random id that clashes with a file's is an error naming both: rc %d, n %d, '%s'", rc, set.n, err.msg);
    rc = ob_random_append(&set, 7, 2, NULL, 0, &err);
    CHECK(rc == 0 && set.n == 4 && strcmp(set.v[2].id, "rnd7_000000") == 0, "no clash below index 2: rc %d n %d",
          rc, set.n);
    rc = ob_random_append(&set, 8, 10, NULL, 0, &err);
    CHECK(rc == 0 && set.n == 14, "another seed does not clash: rc %d n %d", rc, set.n);
    ob_curveset_free(&set);
}

/* Every property of curve i of seed; counts failures per property in bad[]. */
enum { P_FORMAT, P_BOX, P_DEGREE, P_WEIGHTS, P_GENERIC, P_OFFSETS, P_INFLECTION, P_TIGHT, P_LOOP,
       P_DEGEN, P_COUNT };
static const char *const pname[P_COUNT] = {"id/family/source", "control points finite and in the box",
                                           "degree and rational flag", "weights in [0.5,2]",
                                           "well-conditioned polygon", "offsets", "inflection",
                                           "tight: |d| 0.9..0.99 rmin, concave side",
                                           "loop: |d| 1.1..2 rmin, concave side", "degenerate kind"};

/* Every control point finite and inside the unit box. */
static int in_box(const double (*p)[2], int n)
{
    int inbox = 1;
    for (int k = 0; k <= n; k++)
        inbox &= isfinite(p[k][0]) && isfinite(p[k][1]) && p[k][0] >= 0 && p[k][0] <= 1 && p[k][1] >= 0 &&
                 p[k][1] <= 1;
    return inbox;
}

/* The degree and kind (rational or not) the family promises. */
static int degree_ok(int fam, const ob_bez *b)
{
    const int n = b->deg;
    int deg_ok;
    switch (fam) {
    case 0: deg_ok = n == 3; break;
    case 1: deg_ok = n == 5; break;
    case 2: deg_ok = n == 7; break;
    case 3: deg_ok = n == 2 || n == 3; break;
    case 5: case 6: deg_ok = n == 3; break;
    default: deg_ok = n == 3 || n == 5; break;
    }
    deg_ok &= b->rational == (fam == 3);
    return deg_ok;
}

/* Weights in [0.5, 2] and not all alike for the rational family, all 1 otherwise. */
static int weights_ok(int fam, const double *w, int n)
{
    double wlo = INFINITY, whi = 0;
    for (int k = 0; k <= n; k++) {
        wlo = fmin(wlo, w[k]);
        whi = fmax(whi, w[k]);
    }
    if (fam == 3)
        return wlo >= 0.5 && whi <= 2 && whi >= 1.2 * wlo;
    return wlo == 1 && whi == 1;
}

/* One or two finite non-zero offsets; outside families 5 and 6 in
 * 0.02..0.25 and, when two, of opposite signs. */
static int offsets_ok(int fam, const ob_curve *c)
{
    int offs = (c->nd == 1 || c->nd == 2);
    for (int k = 0; k < c->nd; k++)
        offs &= isfinite(c->d[k]) && c->d[k] != 0;
    if (fam != 5 && fam != 6) {
        for (int k = 0; k < c->nd; k++)
            offs &= fabs(c->d[k]) >= 0.02 && fabs(c->d[k]) <= 0.25;
        if (c->nd == 2)
            offs &= c->d[0] * c->d[1] < 0;
    }
    return offs;
}

/* Family 4: an inflection well inside (0,1), also seen on a grid. */
static int inflection_ok(const ob_bez *b)
{
    double ts[64];
    int m = ob_bez_inflections(b, ts, 64), inside = 0;
    for (int k = 0; k < m; k++)
        inside |= ts[k] >= 0.05 && ts[k] <= 0.95;
    return inside && grid_inflection(b);
}

/* Families 5 (tight) and 6 (loop): |d| against the smallest radius of
 * curvature, on the curving side, and 1 - d kappa keeps (5) or changes (6)
 * sign; the ratios seen are widened into ratio_lo/hi. */
static int tight_loop_ok(int fam, const ob_curve *c, double *ratio_lo, double *ratio_hi)
{
    const ob_bez *b = &c->seg[0];
    int s;
    double kmax = ref_max_kappa(b, &s), rmin = 1 / kmax;
    double lo = fam == 5 ? 0.9 : 1.1, hi = fam == 5 ? 0.99 : 2.0;
    int ok = rmin >= 0.03 * (1 - 1e-9) && rmin <= 0.5 * (1 + 1e-9);
    for (int k = 0; k < c->nd; k++) {
        double r = fabs(c->d[k]) / rmin;
        ok &= (c->d[k] > 0) == (s > 0) && r >= lo * (1 - 1e-7) && r <= hi * (1 + 1e-7);
        ratio_lo[fam - 5] = fmin(ratio_lo[fam - 5], r);
        ratio_hi[fam - 5] = fmax(ratio_hi[fam - 5], r);
        /* the meaning: 1 - d kappa(t) > 0 everywhere (tight), or it
         * changes sign (loop: the offset's speed vanishes) */
        double minf = INFINITY;
        for (int q = 0; q <= 4096; q++)
            minf = fmin(minf, 1 - c->d[k] * ref_kappa(b, q / 4096.0));
        ok &= fam == 5 ? minf > 0 : minf < 0;
    }
    return ok;
}

/* Family 7: the degenerate kind of index i, and the polygon it promises
 * (nearly straight, or exactly one tiny leg). */
static int degenerate_ok(long i, const double (*p)[2], int n)
{
    int kind = ob_random_degenerate_kind(i), ok = kind == (int)((i / 8) % 3);
    if (kind == OB_RND_DEGEN_STRAIGHT) {
        double dev = 0;
        for (int k = 1; k < n; k++)
            dev = fmax(dev, line_dist(p[0], p[n], p[k]));
        ok &= dev <= 1e-6 * (1 + 1e-6) && dev >= 1e-9 * (1 - 1e-3);
        for (int k = 0; k < n; k++)
            ok &= legk(p, k) >= 0.0249;
    } else {
        double lo = kind == OB_RND_DEGEN_COINCIDENT ? 1e-8 : 1e-5, hi = lo * 100;
        int tiny = 0;
        for (int k = 0; k < n; k++) {
            double L = legk(p, k);
            if (L >= lo * (1 - 1e-6) && L <= hi * (1 + 1e-6))
                tiny++;
            else
                ok &= L >= 0.05;
        }
        ok &= tiny == 1;
    }
    return ok;
}

/* Curve i of seed: its name, then each property its family promises,
 * counted into bad[] by property. */
static void check_curve(uint64_t seed, long i, int *bad, int *famcount, double *ratio_lo, double *ratio_hi)
{
    ob_curve c;
    if (ob_random_curve(seed, i, &c) != 0) {
        bad[P_FORMAT]++;
        return;
    }
    const int fam = (int)(i % 8);
    famcount[fam]++;
    char id[64], src[160];
    snprintf(id, sizeof id, "rnd%llu_%06ld", (unsigned long long)seed, i);
    snprintf(src, sizeof src, "random family %s, seed %llu, index %ld", ob_random_family_names[fam],
             (unsigned long long)seed, i);
    if (strcmp(c.id, id) || strcmp(c.family, ob_random_family_names[fam]) || strcmp(c.source, src) ||
        c.nseg != 1 || ob_random_family(i) != fam)
        bad[P_FORMAT]++;
    const ob_bez *b = &c.seg[0];
    const int n = b->deg;
    double p[OB_MAX_DEG + 1][2], w[OB_MAX_DEG + 1];
    polygon(b, p, w);

    bad[P_BOX] += !in_box((const double (*)[2])p, n);
    bad[P_DEGREE] += !degree_ok(fam, b);
    bad[P_WEIGHTS] += !weights_ok(fam, w, n);
    if (fam <= 6)
        bad[P_GENERIC] += !generic_ok(b, (const double (*)[2])p);
    bad[P_OFFSETS] += !offsets_ok(fam, &c);
    if (fam == 4)
        bad[P_INFLECTION] += !inflection_ok(b);
    if (fam == 5 || fam == 6)
        bad[fam == 5 ? P_TIGHT : P_LOOP] += !tight_loop_ok(fam, &c, ratio_lo, ratio_hi);
    if (fam == 7)
        bad[P_DEGEN] += !degenerate_ok(i, (const double (*)[2])p, n);
    ob_curve_free(&c);
}

static void test_families(uint64_t seed, long count)
{
    int bad[P_COUNT] = {0}, famcount[8] = {0};
    double rlo[2] = {INFINITY, INFINITY}, rhi[2] = {0, 0};
    for (long i = 0; i < count; i++)
        check_curve(seed, i, bad, famcount, rlo, rhi);
    for (int k = 0; k < P_COUNT; k++)
        CHECK(bad[k] == 0, "seed %llu: %s fails on %d of %ld curves", (unsigned long long)seed, pname[k], bad[k], count);
    int spread = 1;
    for (int f = 0; f < 8; f++)
        spread &= famcount[f] == count / 8;
    CHECK(spread, "seed %llu: each family has %ld curves", (unsigned long long)seed, count / 8);
    /* the draws cover their ranges */
    CHECK(rlo[0] < 0.91 && rhi[0] > 0.98, "tight ratios span %g..%g", rlo[0], rhi[0]);
    CHECK(rlo[1] < 1.2 && rhi[1] > 1.9, "loop ratios span %g..%g", rlo[1], rhi[1]);
}

/* The degenerate kinds and the other families are not all alike: degrees and
 * offset counts vary. */
static void test_variety(void)
{
    int deg5 = 0, deg3 = 0, rat2 = 0, rat3 = 0, nd1 = 0, nd2 = 0;
    for (long i = 0; i < 800; i++) {
        ob_curve c;
        ob_random_curve(1, i, &c);
        int f = (int)(i % 8);
        if (f == 4 || f == 7) {
            deg3 += c.seg[0].deg == 3;
            deg5 += c.seg[0].deg == 5;
        }
        if (f == 3) {
            rat2 += c.seg[0].deg == 2;
            rat3 += c.seg[0].deg == 3;
        }
        nd1 += c.nd == 1;
        nd2 += c.nd == 2;
        ob_curve_free(&c);
    }
    CHECK(deg3 > 60 && deg5 > 30, "inflection/degenerate degrees: %d cubics, %d quintics", deg3, deg5);
    CHECK(rat2 > 25 && rat3 > 25, "rational: %d quadratics, %d cubics", rat2, rat3);
    CHECK(nd1 > 300 && nd2 > 300, "offset counts: %d with one, %d with two", nd1, nd2);
}

int main(void)
{
    testlib_seed(0x51ed);
    test_ids_and_parse();
    test_determinism();
    test_clash();
    test_families(1, 800);
    test_families(7, 800);
    test_variety();
    return check_done();
}
