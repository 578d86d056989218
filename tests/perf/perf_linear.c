/*
 * perf_linear.c - every reader of user-given input costs linear time (or
 * n log n) in its input: meta.json and the JSON of `measure`, the .curves
 * reader (`list curves`, `run`, `measure`), the DXF reader, results.csv and
 * samples.csv, and compare's checks and join over them (issue 36, class 8).
 *
 * How, without a timed assertion: each reader runs on a generated input of
 * size n and of size 4n within this one process, and the test requires
 * t(4n) / t(n) < 8 (linear gives about 4, quadratic about 16).  That is a
 * ratio of two times measured back to back, not a time compared with a
 * fixed budget, so a slow or busy machine scales both alike.  To keep noise
 * out: n is doubled until one run takes at least 50 ms, and each time is the
 * best of 3 runs (the first run at a size also pays for the fresh memory it
 * touches; the best is a warm one at both sizes).  Linear readers measure 4
 * to 6 here (larger tables miss the caches more), quadratic ones 12 to 23.
 * OB_LINEAR_VERBOSE=1 prints the sizes and times.
 *
 * Not part of `make test` (`make perf` runs it): it still compares times,
 * and the test machines are shared; at about 20 s it is also too long for
 * the suite.  tests/unit/test_strmap.c checks the map the readers now use
 * without a clock.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tests/check.h"
#include "host/compare/compare.h"
#include "host/io/approx_read.h"
#include "host/io/curvefile.h"
#include "host/io/metajson.h"
#include "host/io/results_csv.h"

enum { RUNS = 3 };
#define MIN_RUN_S 0.05
#define MAX_RATIO 8.0

/* ---- a growable text ---- */

typedef struct {
    char *s;
    size_t n, cap;
} text;

static void put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(text *t, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        const int k = vsnprintf(t->s ? t->s + t->n : NULL, t->s ? t->cap - t->n : 0, fmt, ap);
        va_end(ap);
        if (k >= 0 && t->s && t->n + (size_t)k < t->cap) {
            t->n += (size_t)k;
            return;
        }
        t->cap = t->cap ? 2 * t->cap : 1 << 16;
        t->s = realloc(t->s, t->cap);
        if (!t->s) {
            fputs("out of memory\n", stderr);
            exit(2);
        }
    }
}

/* This thread's CPU time: the time it waited for a core shared with other
 * work does not count. */
static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the ratio ---- */

/* A reader under test: make builds the input of size n (untimed), read
 * parses it and frees what it read (timed; 0 when it read what it should). */
typedef struct {
    const char *name;
    int n0, nmax;
    void (*make)(text *t, int n);
    int (*read)(const text *t, int n);
} reader;

/* One timed read of t; -1 (said on stderr) when the reader failed. */
static double time_read(const reader *r, const text *t, int n)
{
    const double t0 = now_s();
    const int rc = r->read(t, n);
    const double dt = now_s() - t0;
    if (rc != 0)
        fprintf(stderr, "%s: the reader failed at size %d\n", r->name, n);
    return rc == 0 ? dt : -1;
}

/* The time of one read at size n (calibration). */
static double one_time(const reader *r, int n)
{
    text t = {0};
    r->make(&t, n);
    const double dt = time_read(r, &t, n);
    free(t.s);
    return dt;
}

/* The best of RUNS reads at n and at 4n, interleaved (n, 4n, n, 4n, ...)
 * so that a change in the machine's load falls on both sizes alike. */
static void best_times(const reader *r, int n, double *t1, double *t4)
{
    text a = {0}, b = {0};
    r->make(&a, n);
    r->make(&b, 4 * n);
    *t1 = *t4 = 1e300;
    for (int k = 0; k < RUNS; k++) {
        const double x = time_read(r, &a, n), y = time_read(r, &b, 4 * n);
        if (x < 0 || y < 0) {
            *t1 = *t4 = 1e300;
            break;
        }
        *t1 = x < *t1 ? x : *t1;
        *t4 = y < *t4 ? y : *t4;
    }
    free(a.s);
    free(b.s);
}

static void check_linear(const reader *r)
{
    int n = r->n0;
    double t1, t4;
    double t;
    while ((t = one_time(r, n)) >= 0 && t < MIN_RUN_S && 2 * n <= r->nmax)
        n *= 2;
    best_times(r, n, &t1, &t4);
    CHECK(t >= 0 && t1 < 1e300 && t4 < 1e300, "%s: the reader failed (at %d or %d)", r->name, n, 4 * n);
    if (getenv("OB_LINEAR_VERBOSE"))
        fprintf(stderr, "%-26s n %7d: %8.1f ms, 4n: %8.1f ms, ratio %.2f\n", r->name, n, 1e3 * t1, 1e3 * t4,
                t4 / t1);
    CHECK(t1 > 0 && t4 / t1 < MAX_RATIO, "%s: 4x the input took %.1fx the time (%.1f ms at %d, %.1f ms at %d): "
          "not linear", r->name, t4 / t1, 1e3 * t1, n, 1e3 * t4, 4 * n);
}

/* ---- meta.json: many keys, each looked up once (as compare does) ---- */

static void make_meta(text *t, int n)
{
    put(t, "{\"argv\": [\"run\", \"--reps\", \"3\"],\n \"method_params\": {");
    for (int i = 0; i < n; i++)
        put(t, "%s\n  \"m%d.p\": %d", i ? "," : "", i, i);
    put(t, "},\n \"s\": \"a string\"}\n");
}

static int read_meta(const text *t, int n)
{
    ob_json_flat f;
    ob_err err;
    if (ob_json_flatten(t->s, t->n, "meta.json", &f, &err) != 0)
        return -1;
    char key[64];
    int found = 0;
    for (int i = 0; i < n; i++) {
        snprintf(key, sizeof key, "method_params.m%d.p", i);
        found += ob_json_get(&f, key) != NULL;
    }
    const int ok = f.n == n + 2 && found == n;
    ob_json_free(&f);
    return ok ? 0 : -1;
}

/* ---- measure's JSON: many pieces and many other keys ---- */

static void make_approx_json(text *t, int n)
{
    put(t, "{\"format\": \"offbench-approximation\",\n");
    for (int i = 0; i < n; i++)
        put(t, "\"note%d\": \"x\",\n", i);
    put(t, "\"pieces\": [");
    for (int i = 0; i < n / 4; i++)
        put(t, "%s\n {\"degree\": 1, \"points\": [[%d, 0], [%d, 1]]}", i ? "," : "", i, i + 1);
    put(t, "]}\n");
}

static int read_approx_json(const text *t, int n)
{
    ob_approx a = {0};
    ob_err err;
    const int rc = ob_approx_read_json(t->s, t->n, "a.json", &a, &err);
    const int ok = rc == 0 && a.n == n / 4;
    ob_approx_free(&a);
    return ok ? 0 : -1;
}

/* ---- .curves: many curves (list curves, run, measure) ---- */

static void make_curves(text *t, int n)
{
    for (int i = 0; i < n; i++)
        put(t, "curve c%d\n  bezier 1\n  point 0 0\n  point %d 1\n  offset 0.5\nend\n", i, i + 1);
}

static int read_curves(const text *t, int n)
{
    ob_curveset set = {0};
    ob_err err;
    const int rc = ob_curves_parse(t->s, t->n, "big.curves", &set, &err);
    const int ok = rc == 0 && set.n == n && ob_curveset_find(&set, "c0") == 0;
    ob_curveset_free(&set);
    return ok ? 0 : -1;
}

/* ---- DXF: many SPLINE entities ---- */

static void make_dxf(text *t, int n)
{
    put(t, "0\nSECTION\n2\nENTITIES\n");
    for (int i = 0; i < n; i++)
        put(t, "0\nSPLINE\n71\n1\n72\n4\n40\n0\n40\n0\n40\n1\n40\n1\n73\n2\n10\n%d\n20\n0\n10\n%d\n20\n1\n", i,
            i + 1);
    put(t, "0\nENDSEC\n0\nEOF\n");
}

static int read_dxf(const text *t, int n)
{
    ob_approx a = {0};
    ob_err err;
    const int rc = ob_approx_read_dxf(t->s, t->n, "a.dxf", &a, &err);
    const int ok = rc == 0 && a.n == n;
    ob_approx_free(&a);
    return ok ? 0 : -1;
}

/* ---- results.csv and samples.csv ---- */

static const char HDR[] =
    "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message,family\n";

/* n rows of n methods (method "m" when one_method), metric metric. */
static void put_rows(text *t, int n, const char *metric, int one_method)
{
    put(t, "%s", HDR);
    for (int i = 0; i < n; i++)
        put(t, "c%d,1,m%d,%s,mid,0.1,4,1,3,1e-3,ok,2000000,0,,user\n", i % 97, one_method ? 0 : i, metric);
}

static void make_results(text *t, int n)
{
    put_rows(t, n, "hausdorff", 0);
    put(t, "@");  /* samples.csv follows the '@' */
    put(t, "curve,d,method,metric,split,tol,rep,fit_ns,eval_ns\n");
    for (int i = 0; i < n; i++)
        for (int rep = 1; rep <= 2; rep++)
            put(t, "c%d,1,m%d,hausdorff,mid,0.1,%d,2000000,0\n", i % 97, i, rep);
}

static int read_results(const text *t, int n)
{
    ob_res_table r;
    ob_err err;
    const char *at = strchr(t->s, '@');
    if (ob_res_parse(t->s, (size_t)(at - t->s), "results.csv", &r, &err) != 0)
        return -1;
    const int rc = ob_res_attach_samples(&r, at + 1, t->n - (size_t)(at + 1 - t->s), "samples.csv", &err);
    const int ok = rc == 0 && r.n == n && r.maxrep == 2;
    ob_res_free(&r);
    return ok ? 0 : -1;
}

/* ---- compare: the context checks and the join ---- */

/* base | new, each "results.csv@meta.json"; the new side's metric and
 * method_params differ (the context checks reach every key and row). */
static void make_compare(text *t, int n)
{
    for (int side = 0; side < 2; side++) {
        put_rows(t, n, side ? "bound" : "hausdorff", 0);
        put(t, "@{\"method_params\": {");
        for (int i = 0; i < n; i++)
            put(t, "%s\"m%d.p\": %d", i ? ", " : "", i, side);
        put(t, "}}%s", side ? "" : "|");
    }
}

/* One side from "results.csv@meta.json" at s (ending at end). */
static int load_side(const char *s, const char *end, ob_cmp_side *sd, const char *label)
{
    ob_err err;
    const char *at = memchr(s, '@', (size_t)(end - s));
    memset(sd, 0, sizeof *sd);
    sd->label = label;
    if (!at || ob_res_parse(s, (size_t)(at - s), label, &sd->res, &err) != 0)
        return -1;
    sd->has_meta = ob_json_flatten(at + 1, (size_t)(end - at - 1), label, &sd->meta, &err) == 0;
    return sd->has_meta ? 0 : -1;
}

static int read_compare(const text *t, int n)
{
    ob_cmp_side b, nw;
    ob_cmp_result r;
    ob_err err;
    const ob_cmp_opts o = ob_cmp_defaults();
    const char *bar = strchr(t->s, '|');
    memset(&r, 0, sizeof r);
    int rc = load_side(t->s, bar, &b, "BASE") || load_side(bar + 1, t->s + t->n, &nw, "NEW") ? -1 : 0;
    if (rc == 0)
        rc = ob_cmp_context(&b, &nw, &o, &r, &err);
    /* every method_params key differs for a method both ran, and the metric */
    const int ok = rc == 0 && r.incomparable.n == n + 1;
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&b);
    ob_cmp_side_free(&nw);
    return ok ? 0 : -1;
}

/* The join of n rows of n methods, with 2 repetitions a side. */
static void make_join(text *t, int n)
{
    for (int side = 0; side < 2; side++) {
        put_rows(t, n, "hausdorff", 0);
        put(t, "@{\"reps\": 2}%s", side ? "" : "|");
    }
}

static int read_join(const text *t, int n)
{
    ob_cmp_side b, nw;
    ob_cmp_result r;
    ob_err err;
    const ob_cmp_opts o = ob_cmp_defaults();
    const char *bar = strchr(t->s, '|');
    memset(&r, 0, sizeof r);
    int rc = load_side(t->s, bar, &b, "BASE") || load_side(bar + 1, t->s + t->n, &nw, "NEW") ? -1 : 0;
    if (rc == 0)
        rc = ob_cmp_context(&b, &nw, &o, &r, &err) || ob_cmp_rows(&b, &nw, &o, &r, &err);
    const int ok = rc == 0 && r.joined == n && r.nms == n && ob_cmp_status(&r) == 0;
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&b);
    ob_cmp_side_free(&nw);
    return ok ? 0 : -1;
}

int main(void)
{
    static const reader readers[] = {
        {"meta.json keys", 1000, 1 << 20, make_meta, read_meta},
        {"measure JSON", 1000, 1 << 20, make_approx_json, read_approx_json},
        {".curves curves", 1000, 1 << 18, make_curves, read_curves},
        {"DXF splines", 1000, 1 << 18, make_dxf, read_dxf},
        {"results+samples rows", 1000, 1 << 18, make_results, read_results},
        {"compare context", 500, 1 << 17, make_compare, read_compare},
        {"compare join", 500, 1 << 17, make_join, read_join},
    };
    for (size_t i = 0; i < sizeof readers / sizeof readers[0]; i++)
        check_linear(&readers[i]);
    return check_done();
}
