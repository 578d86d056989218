/*
 * bench_protocol.c - `bench`'s figures of the external-method protocol
 * (bench_protocol.h, docs/external-methods.md): what a fit costs through a
 * worker against the same arithmetic in process, and how a Python method
 * scales over threads.  Ratios taken in this one run, on this machine.
 *
 * Per fit call: the built-in tiller in process, tiller served by this
 * program (`offbench worker tiller`: the same C arithmetic, so the
 * difference is the protocol's own cost: the request written and read,
 * the pipe both ways, the answer checked), and the Python port
 * examples/external/tiller.py.  Each variant's pass over the pieces is
 * repeated until one round lasts long enough for the clock (as Google
 * Benchmark sizes its iterations), the rounds of the three interleaved so
 * that a load that comes and goes falls on all of them, and each reported
 * as the median of its rounds with their interquartile range.
 *
 * Scaling: the Python method on --random 100:7 at five tolerances, with 1
 * thread and with every thread (one worker process per thread), wall time
 * and speed-up, and the built-in tiller on the same jobs beside it; the
 * rows of the two thread counts are checked to be the same.
 */
#include "host/cli/bench_protocol.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "host/diag.h"
#include "host/io/random.h"
#include "host/run/signals.h"
#include "methods/driver/driver.h"
#include "methods/external/ext.h"

static double wall_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmp_dbl(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The pieces every variant fits: the first segment of each curve, at its
 * first offset, tolerance 1e-3. */
typedef struct {
    const ob_bez *base[100];
    double d[100];
    int n;
} pieces;

/* One variant of the per-call figure: a method and its parameters. */
typedef struct {
    const char *label;       /* builtin, worker, python */
    const ob_method *m;
    double par[OB_MAX_PARAMS];
    long iters;              /* passes over the pieces a round */
    double round_s[15];      /* seconds per call, each round */
    int failed;              /* a fit did not return ok: the variant has no figure */
} variant;

/* One pass over the pieces, iters times; seconds per call. */
static double run_pass(variant *v, const pieces *p)
{
    static ob_fit out;       /* large: kept off the stack, bench runs this on one thread */
    char msg[256];
    void *work = v->m->work_size ? malloc(v->m->work_size) : NULL;
    const double t0 = wall_s();
    for (long it = 0; it < v->iters; it++)
        for (int i = 0; i < p->n; i++) {
            const ob_fit_args a = {p->d[i], 1e-3, v->par};
            if (v->m->fit(p->base[i], &a, work, &out, msg, sizeof msg) != OB_FIT_OK && !v->failed) {
                ob_warn("bench: %s fit of piece %d failed: %s", v->label, i, msg);
                v->failed = 1;
            }
        }
    const double dt = wall_s() - t0;
    free(work);
    return dt / ((double)v->iters * p->n);
}

/* Doubles v->iters until one round lasts min_s (the first pass is the
 * warm-up: it starts a worker). */
static void calibrate(variant *v, const pieces *p, double min_s)
{
    v->iters = 1;
    run_pass(v, p);
    while (run_pass(v, p) * (double)v->iters * p->n < min_s && v->iters < (1L << 20))
        v->iters *= 2;
}

/* Median and interquartile range of a variant's rounds, in µs. */
static void stats(const variant *v, int rounds, double *med, double *iqr)
{
    double s[15];
    memcpy(s, v->round_s, (size_t)rounds * sizeof *s);
    qsort(s, (size_t)rounds, sizeof *s, cmp_dbl);
    *med = 1e6 * s[rounds / 2];
    *iqr = 1e6 * (s[(3 * rounds) / 4] - s[rounds / 4]);
}

/* Registers NAME as an external method running command; the method, or
 * NULL with a warning. */
static const ob_method *register_worker(const char *name, const char *command)
{
    char msg[512];
    const ob_method *m = ob_method_find(name);
    if (m)
        return m;
    if (ob_ext_register(name, command, msg, sizeof msg) != 0) {
        ob_warn("bench: protocol: %s (%s) cannot start: %s", name, command, msg);
        return NULL;
    }
    return ob_method_find(name);
}

/* The command that runs this program's `worker tiller`, quoted for sh. */
static int self_worker(char *buf, size_t cap)
{
    char exe[PATH_MAX];
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0 || memchr(exe, '\'', (size_t)n))
        return -1;
    exe[n] = '\0';
    return snprintf(buf, cap, "'%s' worker tiller", exe) < (int)cap ? 0 : -1;
}

static void per_call(FILE *csv, const pieces *p, int quick)
{
    char self[PATH_MAX + 32];
    variant v[3] = {{"builtin", ob_method_find("tiller"), {0}, 0, {0}, 0}};
    int nv = 1;
    if (self_worker(self, sizeof self) == 0 && (v[nv].m = register_worker("tiller_w", self)))
        v[nv++].label = "worker";
    if (access("examples/external/tiller.py", R_OK) == 0 &&
        (v[nv].m = register_worker("tiller_py", "python3 examples/external/tiller.py")))
        v[nv++].label = "python";
    else
        printf("protocol: no Python figure (python3 and examples/external/tiller.py, run from the source tree)\n");
    const int rounds = quick ? 5 : 11;
    for (int k = 0; k < nv; k++) {
        ob_param_defaults(v[k].m, v[k].par);
        calibrate(&v[k], p, quick ? 0.005 : 0.05);
    }
    for (int r = 0; r < rounds && !ob_stop_signal(); r++)
        for (int k = 0; k < nv; k++)
            v[k].round_s[r] = run_pass(&v[k], p);
    if (ob_stop_signal())
        return;
    double base = 0;
    printf("protocol: per fit call (tiller, %d pieces, %d rounds, median / IQR):", p->n, rounds);
    for (int k = 0; k < nv; k++) {
        double med, iqr;
        char what[64];
        stats(&v[k], rounds, &med, &iqr);
        if (v[k].failed)
            continue;
        if (k == 0)
            base = med;
        snprintf(what, sizeof what, "protocol/fit_call/tiller/%s", v[k].label);
        fprintf(csv, "%s,%s,1,%ld,%.9f,%.6g,us\n", what, v[k].label, v[k].iters * p->n, med * 1e-6, med);
        snprintf(what, sizeof what, "protocol/fit_call_iqr/tiller/%s", v[k].label);
        fprintf(csv, "%s,%s,1,%d,%.9f,%.6g,us\n", what, v[k].label, rounds, iqr * 1e-6, iqr);
        printf(" %s %.3g / %.2g us", v[k].label, med, iqr);
        if (k > 0) {
            snprintf(what, sizeof what, "protocol/overhead/tiller/%s", v[k].label);
            fprintf(csv, "%s,%s,1,%d,%.9f,%.6g,us\n", what, v[k].label, p->n, (med - base) * 1e-6, med - base);
            printf(" (+%.3g us, x%.0f)", med - base, base > 0 ? med / base : 0.0);
        }
    }
    printf("\n");
}

/* The jobs of m on every curve of set and offset at five tolerances. */
static ob_job *tiller_jobs(const ob_curveset *set, const ob_method *m, size_t *n)
{
    static const double tols[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5};
    size_t k = 0;
    for (int c = 0; c < set->n; c++)
        k += (size_t)set->v[c].nd * 5;
    ob_job *jobs = calloc(k ? k : 1, sizeof *jobs);
    *n = k;
    k = 0;
    for (int c = 0; jobs && c < set->n; c++)
        for (int di = 0; di < set->v[c].nd; di++)
            for (int t = 0; t < 5; t++, k++) {
                jobs[k].curve = &set->v[c];
                jobs[k].d = set->v[c].d[di];
                jobs[k].method = m;
                jobs[k].metric = OB_METRIC_HAUSDORFF;
                jobs[k].split = OB_SPLIT_MID;
                jobs[k].tol = tols[t];
            }
    return jobs;
}

/* Wall seconds of m's jobs on threads threads; the jobs into *keep. */
static double scaling_run(const ob_curveset *set, const ob_method *m, int threads, ob_job **keep, size_t *n)
{
    ob_driver_opts o;
    ob_driver_hooks h;
    ob_driver_defaults(&o);
    memset(&h, 0, sizeof h);
    h.stop = ob_stop_flag();
    *keep = tiller_jobs(set, m, n);
    if (!*keep)
        return -1;
    omp_set_num_threads(threads);
    const double t0 = wall_s();
    ob_driver_run(*keep, *n, &o, &h);
    return wall_s() - t0;
}

/* 1 when two runs of the same jobs gave the same rows (timings aside). */
static int same_rows(const ob_job *a, const ob_job *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (a[i].status != b[i].status || a[i].ctrl_points != b[i].ctrl_points || a[i].segments != b[i].segments ||
            memcmp(&a[i].max_err, &b[i].max_err, sizeof a[i].max_err) != 0)
            return 0;
    return 1;
}

static void scaling(FILE *csv, int N, int quick)
{
    ob_err err;
    ob_curveset set = {0};
    const int ncurves = quick ? 10 : 100;
    const ob_method *py = ob_method_find("tiller_py"), *c = ob_method_find("tiller");
    if (!py || ob_random_append(&set, 7, ncurves, NULL, 0, &err) != 0) {
        ob_curveset_free(&set);
        return;
    }
    const ob_method *ms[2] = {py, c};
    for (int k = 0; k < 2 && !ob_stop_signal(); k++) {
        ob_job *j1 = NULL, *jN = NULL;
        size_t n = 0;
        const double t1 = scaling_run(&set, ms[k], 1, &j1, &n), tN = scaling_run(&set, ms[k], N, &jN, &n);
        if (t1 > 0 && tN > 0 && !ob_stop_signal()) {
            char what[96];
            const int same = same_rows(j1, jN, n);
            snprintf(what, sizeof what, "protocol/random%d_7/%s", ncurves, ms[k]->name);
            fprintf(csv, "%s,cpu,1,%zu,%.6f,%.6g,jobs/s\n", what, n, t1, n / t1);
            fprintf(csv, "%s,cpu,%d,%zu,%.6f,%.6g,jobs/s\n", what, N, n, tN, n / tN);
            printf("protocol: %s on --random %d:7 (%zu jobs): %.2f s on 1 thread, %.2f s on %d (x%.2f)%s\n",
                   ms[k]->name, ncurves, n, t1, tN, N, t1 / tN, same ? ", the same rows" : "");
            if (!same)
                ob_warn("bench: %s gave other rows on %d threads than on 1", ms[k]->name, N);
        }
        free(j1);
        free(jN);
    }
    ob_curveset_free(&set);
}

int ob_bench_protocol(FILE *csv, int N, int quick)
{
    ob_err err;
    ob_curveset set = {0};
    pieces p = {{0}, {0}, 0};
    if (ob_random_append(&set, 7, 100, NULL, 0, &err) != 0)
        return -1;
    for (int c = 0; c < set.n && p.n < 100; c++)
        if (set.v[c].nseg > 0 && set.v[c].nd > 0) {
            p.base[p.n] = &set.v[c].seg[0];
            p.d[p.n++] = set.v[c].d[0];
        }
    per_call(csv, &p, quick);
    if (!ob_stop_signal())
        scaling(csv, N, quick);
    ob_curveset_free(&set);
    return 0;
}
