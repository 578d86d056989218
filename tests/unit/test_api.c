/*
 * test_api.c - liboffbench's C API (include/offbench.h), linked against
 * build/liboffbench.so as a user would: every function, bad input (unknown
 * names, NaN d, a bad file named FILE:LINE), and a cross-check against
 * `offbench run`'s row for liu2002_ex1, tiller, d = 1, tol 1e-3 (the
 * program in $OFFBENCH, else ./offbench; run from the repository root).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "include/offbench.h"
#include "tests/check.h"

#define PUBLISHED "datasets/published.curves"

static void test_version(void)
{
    CHECK(strcmp(obx_version(), OBX_VERSION) == 0, "obx_version %s", obx_version());
    char want[32];
    snprintf(want, sizeof want, "%d.%d.%d", OBX_VERSION_MAJOR, OBX_VERSION_MINOR, OBX_VERSION_PATCH);
    CHECK(strcmp(want, OBX_VERSION) == 0, "OBX_VERSION %s vs its parts %s", OBX_VERSION, want);
}

/* A file whose third line is wrong: the message names PATH:3. */
static void test_bad_file(void)
{
    char path[] = "/tmp/obx_badXXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0, "mkstemp");
    if (fd < 0)
        return;
    const char text[] = "curve bad\n  bezier 3\n  point 0 zero\nend\n";
    CHECK(write(fd, text, sizeof text - 1) == (ssize_t)(sizeof text - 1), "write");
    close(fd);
    obx_curveset *s = NULL;
    obx_error e = {0, ""};
    CHECK(obx_curves_load_file(path, &s, &e) == -1 && !s, "bad file loaded");
    char where[64];
    snprintf(where, sizeof where, "%s:3:", path);
    CHECK(e.code == OBX_E_PARSE && strstr(e.message, where), "code %d message '%s'", e.code, e.message);
    unlink(path);
    e = (obx_error){0, ""};
    CHECK(obx_curves_load_file("/nonexistent/x.curves", &s, &e) == -1 && e.code == OBX_E_IO,
          "missing file: code %d '%s'", e.code, e.message);
    CHECK(obx_curves_load_file(NULL, &s, NULL) == -1, "NULL path, NULL err");
}

static void test_curves(const obx_curveset *s)
{
    CHECK(obx_curves_count(s) >= 5, "count %d", obx_curves_count(s));
    int i = obx_curves_find(s, "liu2002_ex1");
    CHECK(i >= 0 && strcmp(obx_curves_id(s, i), "liu2002_ex1") == 0, "find");
    const double *d = NULL;
    CHECK(obx_curves_offsets(s, i, &d) == 2 && d && d[0] == 1 && d[1] == -1, "offsets");
    CHECK(obx_curves_id(s, -1) == NULL && obx_curves_id(s, 1 << 20) == NULL, "id out of range");
    CHECK(obx_curves_find(s, "no_such") == -1 && obx_curves_count(NULL) == 0, "find none");
    obx_curveset *def = NULL;
    obx_error e = {0, ""};
    CHECK(obx_curves_load_default(&def, &e) == 0 && obx_curves_find(def, "liu2002_ex1") >= 0, "default: %s",
          e.message);
    obx_curves_free(def);
    obx_curves_free(NULL);
}

/* A curve's segments, as its file gives them (liu2002_ex1: one cubic), and
 * its family; out-of-range and small buffers refused. */
static void test_segments(const obx_curveset *s, int c)
{
    double xy[8], w[4];
    obx_error e = {0, ""};
    CHECK(obx_curves_segment_count(s, c) == 1, "segments %d", obx_curves_segment_count(s, c));
    CHECK(obx_curves_segment(s, c, 0, xy, w, 4, &e) == 3, "segment 0: %s", e.message);
    CHECK(xy[0] == -0.785938 && xy[1] == 0.891849 && xy[6] == 0.9 && xy[7] == -0.2 && w[0] == 1 && w[3] == 1,
          "points %g %g .. %g %g", xy[0], xy[1], xy[6], xy[7]);
    CHECK(obx_curves_segment(s, c, 0, NULL, NULL, 0, NULL) == 3, "degree only");
    CHECK(obx_curves_segment(s, c, 0, xy, w, 3, &e) == -1 && e.code == OBX_E_INVALID && strstr(e.message, "degree 3"),
          "small buffer: %s", e.message);
    CHECK(obx_curves_segment(s, c, 1, xy, w, 4, &e) == -1 && e.code == OBX_E_INVALID, "segment out of range");
    CHECK(obx_curves_segment(s, -1, 0, xy, w, 4, &e) == -1 && obx_curves_segment_count(s, -1) == 0 &&
              obx_curves_segment_count(NULL, 0) == 0, "curve out of range");
    CHECK(obx_curves_family(s, c) && strcmp(obx_curves_family(s, c), "published") == 0, "family %s",
          obx_curves_family(s, c) ? obx_curves_family(s, c) : "(null)");
    CHECK(obx_curves_family(s, -1) == NULL, "family out of range");
}

static void test_arrays(void)
{
    /* liu2002_ex1's cubic, and a rational quarter circle */
    const int deg[] = {3};
    const double xy[] = {-0.785938, 0.891849, -0.993306, -0.59695, 0.3, -2.5, 0.9, -0.2};
    obx_curveset *s = NULL;
    obx_error e = {0, ""};
    CHECK(obx_curves_from_arrays("ex1", 1, deg, xy, NULL, &s, &e) == 0, "arrays: %s", e.message);
    CHECK(obx_curves_count(s) == 1 && strcmp(obx_curves_id(s, 0), "ex1") == 0, "one curve");
    CHECK(obx_curves_offsets(s, 0, NULL) == 0, "no offsets of its own");
    CHECK(strcmp(obx_curves_family(s, 0), "user") == 0, "arrays' family: %s", obx_curves_family(s, 0));
    obx_result *r = NULL;
    CHECK(obx_fit(s, 0, "tiller", 1, 1e-3, NULL, NULL, NULL, &r, &e) == 0, "fit: %s", e.message);
    CHECK(r && strcmp(obx_result_status(r), "ok") == 0 && obx_result_max_err(r) <= 1e-3, "fit ok");
    obx_result_free(r);
    obx_curves_free(s);

    const int q[] = {2};
    const double qxy[] = {1, 0, 1, 1, 0, 1}, qw[] = {1, sqrt(0.5), 1};
    CHECK(obx_curves_from_arrays("arc", 1, q, qxy, qw, &s, &e) == 0, "rational: %s", e.message);
    double sxy[6], sw[3];
    CHECK(obx_curves_segment(s, 0, 0, sxy, sw, 3, &e) == 2 && sw[0] == 1 && fabs(sw[1] - sqrt(0.5)) < 1e-15 &&
              fabs(sxy[2] - 1) < 1e-15 && fabs(sxy[3] - 1) < 1e-15, "rational segment back: w %g, point %g %g",
          sw[1], sxy[2], sxy[3]);
    obx_curves_free(s);
    s = NULL;
    const double bad[] = {0, 0, NAN, 1};
    const int one[] = {1}, big[] = {99};
    e = (obx_error){0, ""};
    CHECK(obx_curves_from_arrays("x", 1, one, bad, NULL, &s, &e) == -1 && e.code == OBX_E_INVALID &&
              strstr(e.message, "point 1"), "NaN point: %s", e.message);
    CHECK(obx_curves_from_arrays("x", 1, big, qxy, NULL, &s, &e) == -1 && strstr(e.message, "degree 99"),
          "degree: %s", e.message);
    const double negw[] = {1, -1, 1};
    CHECK(obx_curves_from_arrays("x", 1, q, qxy, negw, &s, &e) == -1 && strstr(e.message, "weight 1"),
          "weight: %s", e.message);
    CHECK(obx_curves_from_arrays("bad id!", 1, q, qxy, NULL, &s, &e) == -1 && strstr(e.message, "id"), "id: %s",
          e.message);
    /* two segments of different degrees, joined: a line and a quadratic */
    const int two[] = {1, 2};
    const double txy[] = {0, 0, 1, 0, 1, 0, 2, 0, 2, 1};
    e = (obx_error){0, ""};
    CHECK(obx_curves_from_arrays("two", 2, two, txy, NULL, &s, &e) == 0 && obx_curves_segment_count(s, 0) == 2,
          "two segments: %s", e.message);
    CHECK(s && obx_curves_segment(s, 0, 0, NULL, NULL, 0, NULL) == 1 && obx_curves_segment(s, 0, 1, sxy, NULL, 3,
                                                                                           NULL) == 2 &&
              sxy[0] == 1 && sxy[4] == 2 && sxy[5] == 1, "segment 1 back");
    CHECK(obx_fit(s, 0, "tiller", 0.1, 1e-3, NULL, NULL, NULL, &r, &e) == 0 && strcmp(obx_result_status(r), "ok") == 0,
          "fit on two segments: %s", e.message);
    obx_result_free(r);
    obx_curves_free(s);
    s = NULL;
    const double tdot[] = {0, 0, 1, 0, 1, 1, 1, 1, 1, 1};
    CHECK(obx_curves_from_arrays("two", 2, two, tdot, NULL, &s, &e) == -1 && strstr(e.message, "segment 1"),
          "a point as segment 1: %s", e.message);
    const double dot[] = {1, 1, 1, 1};
    CHECK(obx_curves_from_arrays("x", 1, one, dot, NULL, &s, &e) == -1 && e.code == OBX_E_INVALID, "a point: %s",
          e.message);
    CHECK(!s, "nothing made");
}

static void test_methods(void)
{
    int n = obx_method_count(), found = 0, params = 0;
    CHECK(n > 10, "methods %d", n);
    for (int i = 0; i < n; i++) {
        found += strcmp(obx_method_name(i), "tiller") == 0;
        CHECK(obx_method_citation(i) != NULL, "citation %d", i);
        for (int k = 0; k < obx_method_param_count(i); k++, params++) {
            obx_param_info p;
            CHECK(obx_method_param(i, k, &p, NULL) == 0 && p.name && p.min <= p.def && p.def <= p.max,
                  "param %d.%d", i, k);
        }
    }
    CHECK(found == 1 && params > 0, "tiller listed, %d parameters", params);
    obx_param_info p;
    obx_error e = {0, ""};
    CHECK(obx_method_name(n) == NULL && obx_method_param_count(-1) == 0, "out of range");
    CHECK(obx_method_param(0, 99, &p, &e) == -1 && e.code == OBX_E_INVALID, "bad param index");
}

/* Bad arguments of obx_fit: each fails with OBX_E_INVALID and a message. */
static void test_fit_errors(const obx_curveset *s, int c)
{
    obx_result *r = NULL;
    obx_error e = {0, ""};
    CHECK(obx_fit(s, c, "nosuch", 1, 1e-3, NULL, NULL, NULL, &r, &e) == -1 && e.code == OBX_E_INVALID &&
              strstr(e.message, "nosuch") && strstr(e.message, "tiller"), "unknown method: %s", e.message);
    CHECK(obx_fit(s, c, "tiller", NAN, 1e-3, NULL, NULL, NULL, &r, &e) == -1 && strstr(e.message, "finite"),
          "NaN d: %s", e.message);
    CHECK(obx_fit(s, c, "tiller", 1, 0, NULL, NULL, NULL, &r, &e) == -1 && strstr(e.message, "tolerance"),
          "tol 0: %s", e.message);
    CHECK(obx_fit(s, c, "tiller", 1, 1e-3, "nosuch", NULL, NULL, &r, &e) == -1 && strstr(e.message, "metric"),
          "metric: %s", e.message);
    CHECK(obx_fit(s, c, "tiller", 1, 1e-3, NULL, "half", NULL, &r, &e) == -1 && strstr(e.message, "split"),
          "split: %s", e.message);
    CHECK(obx_fit(s, -1, "tiller", 1, 1e-3, NULL, NULL, NULL, &r, &e) == -1, "curve index");
    CHECK(obx_fit(s, c, "zhao", 1, 1e-3, NULL, NULL, "nope=1", &r, &e) == -1 && strstr(e.message, "nope"),
          "param name: %s", e.message);
    CHECK(obx_fit(s, c, "tiller", 1, 1e-3, NULL, NULL, NULL, &r, NULL) == 0, "NULL err on success");
    obx_result_free(r);
    CHECK(!isnan(0.0) && obx_fit(NULL, 0, "tiller", 1, 1e-3, NULL, NULL, NULL, &r, NULL) == -1, "NULL set");
}

/* The row of `offbench run` for (liu2002_ex1, 1, tiller, hausdorff, mid,
 * 0.001) into row; 0 or -1. */
static int run_row(char *row, size_t len)
{
    const char *prog = getenv("OFFBENCH") ? getenv("OFFBENCH") : "./offbench";
    char dir[] = "/tmp/obx_runXXXXXX", cmd[1024], path[256];
    if (!mkdtemp(dir))
        return -1;
    snprintf(cmd, sizeof cmd, "'%s' run --curves " PUBLISHED " --methods tiller --tols 1e-3 --out %s --force "
             ">/dev/null 2>&1", prog, dir);
    int rc = system(cmd) == 0 ? -1 : -2;
    snprintf(path, sizeof path, "%s/results.csv", dir);
    FILE *f = rc == -1 ? fopen(path, "r") : NULL;
    while (f && fgets(row, (int)len, f))
        if (strncmp(row, "liu2002_ex1,1,tiller,hausdorff,mid,0.001,", 41) == 0) {
            row[strcspn(row, "\n")] = '\0';
            rc = 0;
            break;
        }
    if (f)
        fclose(f);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        rc = -1;
    return rc;
}

/* The row without the timing columns fit_ns, eval_ns (12th, 13th). */
static void drop_timings(const char *row, char *out, size_t len)
{
    size_t k = 0;
    int field = 0;
    for (const char *p = row; *p && k + 1 < len; p++) {
        if (field != 11 && field != 12)
            out[k++] = *p;
        if (*p == ',')
            field++;
    }
    out[k] = '\0';
}

static void test_fit_cross(const obx_curveset *s, int c)
{
    obx_result *r = NULL;
    obx_error e = {0, ""};
    CHECK(obx_fit(s, c, "tiller", 1, 1e-3, "hausdorff", "mid", NULL, &r, &e) == 0, "fit: %s", e.message);
    if (!r)
        return;
    char row[2048], a[2048], b[2048];
    int rc = run_row(row, sizeof row);
    CHECK(rc == 0, "offbench run: %d", rc);
    drop_timings(row, a, sizeof a);
    drop_timings(obx_result_row(r), b, sizeof b);
    CHECK(rc != 0 || strcmp(a, b) == 0, "rows differ:\n  run %s\n  api %s", a, b);
    long cp = -1;
    int segs = -1;
    double err = NAN;
    CHECK(rc == 0 && sscanf(row + 41, "%ld,%d,%*d,%lf,ok,", &cp, &segs, &err) == 3, "run row %s", row);
    CHECK(cp == obx_result_ctrl_points(r) && segs == obx_result_segments(r) && err == obx_result_max_err(r),
          "run %ld %d %.17g, api %ld %d %.17g", cp, segs, err, obx_result_ctrl_points(r), obx_result_segments(r),
          obx_result_max_err(r));
    CHECK(strncmp(obx_results_header(), "curve,d,method,", 15) == 0, "header");
    CHECK(strcmp(obx_result_message(r), "") == 0, "message");
    /* the pieces: as many as segments, cubic, and measured again under
     * normal they stay within the tolerance's neighbourhood */
    int n = obx_result_piece_count(r);
    CHECK(n == obx_result_segments(r) && n > 1, "pieces %d", n);
    int *deg = malloc((size_t)n * sizeof *deg);
    double *xy = malloc((size_t)n * 8 * sizeof *xy);
    double w[4];
    for (int k = 0; k < n && deg && xy; k++) {
        deg[k] = obx_result_piece(r, k, xy + 8 * k, w, 4, &e);
        CHECK(deg[k] == 3 && w[0] == 1 && w[3] == 1, "piece %d degree %d", k, deg[k]);
    }
    CHECK(obx_result_piece(r, 0, xy, w, 2, &e) == -1 && strstr(e.message, "degree 3"), "small buffer");
    CHECK(obx_result_piece(r, n, NULL, NULL, 0, &e) == -1, "piece out of range");
    CHECK(obx_result_piece(r, 0, NULL, NULL, 0, NULL) == 3, "degree only");
    obx_measurement m;
    CHECK(obx_measure(s, c, 1, n, deg, xy, NULL, "hausdorff", &m, &e) == 0, "measure: %s", e.message);
    CHECK(strcmp(m.status, "ok") == 0 && m.max_err <= 1e-3 && m.max_err > 0.5 * obx_result_max_err(r),
          "measured %g (%s), the fit %g", m.max_err, m.status, obx_result_max_err(r));
    /* hausdorff-whole: no match needed; at most the per-piece value */
    const double per_piece = m.max_err;
    CHECK(obx_measure(s, c, 1, n, deg, xy, NULL, "hausdorff-whole", &m, &e) == 0 && strcmp(m.status, "ok") == 0 &&
              m.max_err <= per_piece * (1 + 1e-12) && m.max_err > 0.5 * obx_result_max_err(r),
          "hausdorff-whole %g (%s: %s), per piece %g", m.max_err, m.status, e.message, per_piece);
    CHECK(obx_measure(s, c, 1, n - 1, deg + 1, xy + 8, NULL, "hausdorff-whole", &m, &e) == -1 &&
              e.code == OBX_E_MEASURE && strstr(e.message, "does not cover the d = 1 offset of curve liu2002_ex1 once (1 gaps"),
          "hausdorff-whole of pieces with a gap: %s", e.message);
    CHECK(obx_measure(s, c, 1, n, deg, xy, NULL, "bound", &m, &e) == 0 && strcmp(m.status, "n/a") == 0,
          "bound without links: %s", m.status);
    CHECK(obx_measure(s, c, 1, n, deg, xy, NULL, "worst", &m, &e) == -1 && strstr(e.message, "metric"), "metric");
    CHECK(obx_measure(s, c, NAN, n, deg, xy, NULL, NULL, &m, &e) == -1 && e.code == OBX_E_INVALID, "NaN d");
    CHECK(obx_measure(s, c, 1, 0, deg, xy, NULL, NULL, &m, &e) == -1, "no pieces");
    free(deg);
    free(xy);
    obx_result_free(r);
}

/* sisl: its fits run in build/offbench-sisl-server beside the library. */
static void test_sisl(const obx_curveset *s, int c)
{
    obx_result *r = NULL;
    obx_error e = {0, ""};
    CHECK(obx_fit(s, c, "sisl", 1, 1e-3, NULL, NULL, NULL, &r, &e) == 0, "sisl: %s", e.message);
    CHECK(r && strcmp(obx_result_status(r), "ok") == 0 && obx_result_piece_count(r) > 0, "sisl ok: %s %s",
          r ? obx_result_status(r) : "-", r ? obx_result_message(r) : "-");
    obx_result_free(r);
}

typedef struct {
    size_t calls, last_done, total;
    int rising;
} progress_seen;

static void on_progress(void *ctx, size_t done, size_t total)
{
    progress_seen *p = ctx;
    p->rising &= done >= p->last_done && done <= total;
    p->calls++;
    p->last_done = done;
    p->total = total;
}

/* A batch's results are obx_fit's, timings aside; progress rises to the end. */
static void test_batch(const obx_curveset *s, int c)
{
    enum { N = 6 };
    const char *methods[N] = {"tiller", "tiller", "tiller", "cobb", "lee", "sisl"};
    const double tols[N] = {1e-2, 1e-3, 1e-4, 1e-3, 1e-3, 1e-2};
    obx_job_spec jobs[N];
    for (int i = 0; i < N; i++)
        jobs[i] = (obx_job_spec){c, methods[i], i % 2 ? 1.0 : -1.0, tols[i], NULL, i == 2 ? "greedy" : NULL, NULL};
    obx_result *out[N];
    obx_error e = {0, ""};
    progress_seen p = {0, 0, 0, 1};
    CHECK(obx_run_batch(s, jobs, N, on_progress, &p, out, &e) == 0, "batch: %s", e.message);
    CHECK(p.calls > 0 && p.rising && p.last_done == N && p.total == N, "progress: %zu calls, last %zu of %zu",
          p.calls, p.last_done, p.total);
    for (int i = 0; i < N; i++) {
        obx_result *r = NULL;
        CHECK(obx_fit(s, c, methods[i], jobs[i].d, tols[i], NULL, jobs[i].split, NULL, &r, &e) == 0, "fit");
        char a[2048], b[2048];
        drop_timings(obx_result_row(out[i]), a, sizeof a);
        drop_timings(r ? obx_result_row(r) : "", b, sizeof b);
        CHECK(strcmp(a, b) == 0 && obx_result_piece_count(out[i]) == obx_result_piece_count(r),
              "job %d: batch %s, fit %s", i, a, b);
        obx_result_free(r);
        obx_result_free(out[i]);
    }
    jobs[3].method = "nosuch";
    CHECK(obx_run_batch(s, jobs, N, NULL, NULL, out, &e) == -1 && strncmp(e.message, "job 3: ", 7) == 0 &&
              out[0] == NULL, "bad spec: %s", e.message);
    CHECK(obx_run_batch(s, jobs, 0, NULL, NULL, out, NULL) == -1, "no jobs");
}

/* obx_result_certify (0.4): the enclosure, the row's four columns; a second
 * call the same; NULL refused. */
static void test_certify(const obx_curveset *s, int c)
{
    obx_result *r = NULL;
    obx_error e = {0, ""};
    CHECK(obx_fit(s, c, "tiller", 1.0, 1e-3, NULL, NULL, NULL, &r, &e) == 0, "fit: %s", e.message);
    if (!r)
        return;
    CHECK(strstr(obx_result_row(r), ",,,,") != NULL, "before: the certificate's columns empty");
    double up = 0, lo = 0;
    CHECK(obx_result_certify(r, NULL, &up, &lo, &e) == 0, "certify: %s", e.message);
    CHECK(0 <= lo && lo <= up && up <= 1e-3, "the verdict: within tol [%g, %g]", lo, up);
    CHECK(strstr(obx_result_row(r), ",yes,") != NULL, "the row says certified yes: %s", obx_result_row(r));
    double up2 = 0, lo2 = 0;
    CHECK(obx_result_certify(r, "verdict", &up2, &lo2, &e) == 0 && up2 == up && lo2 == lo, "twice: the same");
    CHECK(obx_result_certify(r, "tight", &up2, &lo2, &e) == 0 && lo2 <= up2 && up2 <= lo2 * (1 + 1e-3) && lo2 > 0 &&
              up2 <= 1e-3,
          "tight: within rtol [%g, %g]", lo2, up2);
    CHECK(obx_result_certify(r, "loose", &up2, &lo2, &e) == -1 && e.code == OBX_E_INVALID &&
              strstr(e.message, "unknown certificate mode 'loose' (verdict, tight)") && isnan(up2),
          "an unknown mode: %s", e.message);
    obx_result_free(r);
    /* a job without an approximation: python/tests/test_fit.py (a built-in curve's) */
    CHECK(obx_result_certify(NULL, NULL, &up, NULL, &e) == -1 && e.code == OBX_E_INVALID && isnan(up), "NULL: %s",
          e.message);
}

/* obx_external_register: an external method in the library's registry, as
 * --external registers it; the same name and command again is fine (Python
 * registers its function on every run), a clash is an error naming it. */
static void test_external(void)
{
    const char *port = "python3 examples/external/tiller.py";
    obx_error e = {0, ""};
    const int before = obx_method_count();
    CHECK(obx_external_register("tiller_api", port, &e) == 0, "register: %s", e.message);
    CHECK(obx_method_count() == before + 1 && strcmp(obx_method_name(before), "tiller_api") == 0,
          "the method is listed last");
    CHECK(obx_external_register("tiller_api", port, &e) == 0 && obx_method_count() == before + 1,
          "the same again: ok, not listed twice: %s", e.message);
    CHECK(obx_external_register("tiller_api", "python3 tests/e2e/external_bad.py error", &e) == -1 &&
              e.code == OBX_E_INVALID && strstr(e.message, "tiller_api") && strstr(e.message, "another command"),
          "the name with another command: %s", e.message);
    CHECK(obx_external_register("tiller", port, &e) == -1 && e.code == OBX_E_INVALID &&
              strstr(e.message, "'tiller'") && strstr(e.message, "built-in"),
          "a built-in's name: %s", e.message);
    CHECK(obx_external_register("nohello", "true", &e) == -1 && e.code == OBX_E_INVALID &&
              strstr(e.message, "nohello") && strstr(e.message, "no hello line"),
          "a command that says nothing: %s", e.message);
    CHECK(obx_external_register(NULL, port, &e) == -1 && e.code == OBX_E_INVALID, "NULL name");
    obx_curveset *s = NULL;
    obx_result *a = NULL, *b = NULL;
    if (obx_curves_load_file(PUBLISHED, &s, &e) != 0)
        return;
    const int c = obx_curves_find(s, "liu2002_ex1");
    CHECK(obx_fit(s, c, "tiller", 1.0, 1e-3, NULL, NULL, NULL, &a, &e) == 0 &&
              obx_fit(s, c, "tiller_api", 1.0, 1e-3, NULL, NULL, NULL, &b, &e) == 0,
          "fit: %s", e.message);
    if (a && b)
        CHECK(obx_result_max_err(a) == obx_result_max_err(b) && obx_result_ctrl_points(a) == obx_result_ctrl_points(b) &&
                  strcmp(obx_result_status(a), obx_result_status(b)) == 0,
              "the port's job is the built-in's: %s vs %s", obx_result_row(a), obx_result_row(b));
    obx_result_free(a);
    obx_result_free(b);
    obx_curves_free(s);
}

int main(void)
{
    test_version();
    test_bad_file();
    obx_curveset *s = NULL;
    obx_error e = {0, ""};
    CHECK(obx_curves_load_file(PUBLISHED, &s, &e) == 0, "load: %s", e.message);
    if (s) {
        int c = obx_curves_find(s, "liu2002_ex1");
        test_curves(s);
        test_segments(s, c);
        test_fit_errors(s, c);
        test_fit_cross(s, c);
        test_sisl(s, c);
        test_batch(s, c);
        test_certify(s, c);
    }
    obx_curves_free(s);
    test_arrays();
    test_methods();
    test_external();
    return check_done();
}
