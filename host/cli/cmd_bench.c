/*
 * cmd_bench.c - `./offbench bench [--out DIR] [--quick] [--kernels] [--device NAME] [--protocol]`: the sampling engine
 * and whole runs, every figure measured in this one run and reported as
 * ratios (OpenCL vs CPU, 1 vs N threads), never compared with numbers from
 * elsewhere.  Writes DIR/bench.csv: what,backend,threads,items,seconds,rate,unit.
 *
 * Measurements:
 *   fma_peak         a dependency-free multiply-add loop: the machine's peak
 *                    double-precision rate, 1 thread and all threads
 *   fma_vector       the same with the widest vector FMA the CPU has (AVX-512
 *                    or AVX2): the machine's peak
 *   cl_build/<metric>/<layout>
 *                    the OpenCL program of each sampled metric in each layout
 *                    (one each, clrt.h): seconds to build it (or load it from
 *                    the binary cache) and launch it once; the backend column
 *                    says what the cache did: cache-hit, cache-miss, cache-off
 *   kernel_build     those summed
 *   cl_fma_peak      the OpenCL device's double-precision peak, by a kernel of
 *                    its own (independent mad chains on many work-items,
 *                    counted 2 flops each, its own time from its profiling
 *                    event, a warm-up launch untimed); the backend column is
 *                    the device's name
 *   samples/<metric> a fixed batch of records (random convex cubics and their
 *                    Cobb approximations at d = +-0.1), S samples each, measured
 *                    by the CPU path with 1 and N threads and by the OpenCL
 *                    kernel in both layouts, a work-group per record (rows
 *                    "opencl-groups") and a work-item per record
 *                    ("opencl-items"), and as "opencl" the layout runs use on
 *                    the device (after a warm-up launch, build time apart).
 *                    On a GPU or accelerator the batch is one launch of at
 *                    least 1e7 samples (OB_BENCH_GPU_SAMPLES); else 2,000
 *                    records (200 with --quick), and 1 thread measures at most
 *                    2,000 of them
 *   gflops/<metric>  the same as double-precision operations per second: the
 *                    work the metric core counts for itself (OBC_OPS_*: curve
 *                    evaluations weighted by degree, distances to samples,
 *                    chords and blocks; counted on the CPU pass, the kernel
 *                    runs the same code and counts the same).  A lower bound:
 *                    the rest of the metric's arithmetic is not counted.
 *   cl_peak_fraction/<metric>
 *                    those flops over the kernel's own time (profiling
 *                    events), as a fraction of cl_fma_peak (rate; unit
 *                    of_peak), per layout
 *   samples_per_record/<metric>, ops_per_sample/<metric>,
 *   bytes_per_record/<metric>, bytes_back_per_record/<metric>
 *                    the work counts (rate column): S; the counted flops per
 *                    sample (backend "any": the serial scan's; a layout's
 *                    own row where it does other work: hausdorff's groups,
 *                    kernels/README.md); the bytes a record moves to the device and back
 *                    (ob_cl_record_bytes: control points, degrees, offsets,
 *                    d, stop, metric; error, parameter, work)
 *   With --kernels, only the figures above: no whole runs.
 *   run              a whole run (published curves, tiller/cobb/ahn, hausdorff,
 *                    4 tolerances) with 1 and N threads: jobs per second
 *   random_run       all methods at 5 tolerances on a fixed random set (--random
 *                    24:1; 1000 curves would not fit the bench's time), CPU
 *                    and OpenCL: jobs per second
 *   fit_per_job/M,   per method of that run (CPU): the median over its jobs
 *   eval_per_job/M   of the fit time (its own thread CPU time) and of the
 *                    measuring time, seconds (rate: jobs/s of that work)
 *   greedy_run       the greedy rule on that set (all methods, 3 tolerances,
 *                    CPU): jobs per second with the probes that stop once they
 *                    fail (the default), and as greedy_run/full_probes with
 *                    every probe measured in full (the same results)
 *   own_split        cubic-opt alone on that set at 1e-2 ... 1e-5: the
 *                    driver's greedy rule (split = 0) against the fit's own
 *                    split, also under greedy (split = 1): jobs per second,
 *                    the median fit time per job of each (fit_per_job/
 *                    cubic-opt/greedy, .../own) and their control points
 *   engines_random100_7/ENGINE[/model16|/model64]
 *                    all methods at 5 tolerances on --random 100:7 (10 with
 *                    --quick) through each engine on all threads, the same
 *                    rows checked: rate is the efficiency, work / (threads x
 *                    wall), measured, and modelled at 16 and 64 threads
 *                    from the run's own trace (bench_engines.c); with OpenCL
 *                    each engine's wall and its records per launch (the device
 *                    engine: the device's busy time and the share of it hidden
 *                    behind fits)
 *   protocol/...     the external-method protocol (last: it registers
 *                    external methods; --protocol: this section alone):
 *                    per fit call of tiller in process, through `offbench
 *                    worker tiller` and through examples/external/tiller.py
 *                    (median of interleaved rounds, us; fit_call_iqr their
 *                    IQR; overhead the difference to the built-in), and
 *                    the Python method and the built-in on --random 100:7
 *                    with 1 and all threads (bench_protocol.c)
 */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "host/io/fsutil.h"
#include "host/io/outfile.h"
#include "kernels/metric_core.h"
#include "methods/driver/driver.h"
#include "host/backend/clrt.h"
#include "host/backend/select.h"
#include "host/cli/commands.h"
#include "host/io/curvefile.h"
#include "host/io/datadir.h"
#include "host/cli/bench_engines.h"
#include "host/cli/bench_protocol.h"
#include "host/cli/cliopts.h"
#include "host/diag.h"
#include "host/run/signals.h"
#include "host/io/random.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

typedef struct {
    FILE *csv;
} bench_out;

/* A row whose rate is given (not items / seconds): a count or a fraction. */
static void row_rate(bench_out *b, const char *what, const char *backend, int threads, double items, double seconds,
                     double rate, const char *unit)
{
    fprintf(b->csv, "%s,%s,%d,%.0f,%.6f,%.6g,%s\n", what, backend, threads, items, seconds, rate, unit);
}

static void row(bench_out *b, const char *what, const char *backend, int threads, double items, double seconds,
                const char *unit)
{
    row_rate(b, what, backend, threads, items, seconds, seconds > 0 ? items / seconds : 0.0, unit);
}

/* Samples per launch of the kernel benchmark on a GPU or an accelerator:
 * enough to fill it (issue 40). */
#define OB_BENCH_GPU_SAMPLES 1e7

/* ---- FMA peak ---------------------------------------------------------- */

/* 8 independent chains of a*x + y per lane so the loop is bound by the
 * multiply-add units, not by latency. */
static double fma_loop(long iters)
{
    double x[8] = {1, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7}, a = 0.999999, c = 1e-7;
    for (long i = 0; i < iters; i++)
        for (int k = 0; k < 8; k++)
            x[k] = a * x[k] + c;
    return x[0] + x[1] + x[2] + x[3] + x[4] + x[5] + x[6] + x[7];
}

/* The same with 8 independent vector accumulators of the widest FMA unit. */
typedef double v8d __attribute__((vector_size(64)));
typedef double v4d __attribute__((vector_size(32)));

/* fp-contract=fast: -std=c11 turns contraction off, and this loop must be FMAs
 * (gcc's attribute; clang, used by `make fuzz`, contracts within statements
 * by default) */
#if defined(__clang__)
#define OB_CONTRACT
#else
#define OB_CONTRACT optimize("fp-contract=fast"),
#endif
__attribute__((OB_CONTRACT target("avx512f,fma"))) static double fma_avx512(long iters)
{
    v8d x[8], a = {0}, c = {0};
    for (int k = 0; k < 8; k++)
        for (int l = 0; l < 8; l++) {
            x[k][l] = 1.0 + 0.01 * (8 * k + l);
            a[l] = 0.999999;
            c[l] = 1e-7;
        }
    for (long i = 0; i < iters; i++)
        for (int k = 0; k < 8; k++)
            x[k] = a * x[k] + c;
    double s = 0;
    for (int k = 0; k < 8; k++)
        for (int l = 0; l < 8; l++)
            s += x[k][l];
    return s;
}

__attribute__((OB_CONTRACT target("avx2,fma"))) static double fma_avx2(long iters)
{
    v4d x[10], a = {0.999999, 0.999999, 0.999999, 0.999999}, c = {1e-7, 1e-7, 1e-7, 1e-7};
    for (int k = 0; k < 10; k++)
        for (int l = 0; l < 4; l++)
            x[k][l] = 1.0 + 0.01 * (4 * k + l);
    for (long i = 0; i < iters; i++)
        for (int k = 0; k < 10; k++)
            x[k] = a * x[k] + c;
    double s = 0;
    for (int k = 0; k < 10; k++)
        for (int l = 0; l < 4; l++)
            s += x[k][l];
    return s;
}

/* Peak of the widest vector FMA: flops, or 0 if the CPU has none. */
static double fma_vector_peak(int threads, double *seconds, const char **isa)
{
    const long iters = 20000000;
    double per = 0.0, sink = 0.0;
    *isa = "none";
    __builtin_cpu_init();
    int w = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("fma") ? 512
            : __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? 256 : 0;
    if (!w)
        return 0.0;
    *isa = w == 512 ? "avx512" : "avx2";
    per = w == 512 ? 2.0 * 64 * iters : 2.0 * 40 * iters;
    double t0 = now_s();
#pragma omp parallel num_threads(threads) reduction(+ : sink)
    sink += w == 512 ? fma_avx512(iters) : fma_avx2(iters);
    *seconds = now_s() - t0;
    if (sink == 42.0)
        fputs("", stderr);
    return per * threads;
}

static double fma_peak(int threads, double *seconds)
{
    const long iters = 40000000;
    double sink = 0.0, t0 = now_s();
#pragma omp parallel num_threads(threads) reduction(+ : sink)
    sink += fma_loop(iters);
    *seconds = now_s() - t0;
    if (sink == 42.0)  /* keep the loop */
        fputs("", stderr);
    return 2.0 * 8 * iters * threads;  /* flops */
}

/* ---- the record batch --------------------------------------------------- */

static unsigned long long rng_next(unsigned long long *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

static double urand(unsigned long long *s) { return (rng_next(s) >> 11) * (1.0 / 9007199254740992.0); }

/* Random convex cubics (control polygon turning left by less than pi). */
static void make_batch(int n, ob_bez *base, ob_bez *approx, ob_measure_rec *recs, ob_metric metric)
{
    unsigned long long s = 0x9E3779B97F4A7C15ULL;
    const ob_method *cobb = ob_method_find("cobb");
    double par[OB_MAX_PARAMS];
    ob_param_defaults(cobb, par);
    for (int i = 0; i < n; i++) {
        double ang = 2 * OB_PI * urand(&s), turn = 0.3 + 1.2 * urand(&s), xy[4][2];
        double p[2] = {0, 0};
        for (int k = 0; k < 4; k++) {
            xy[k][0] = p[0];
            xy[k][1] = p[1];
            double a = ang + turn * k / 3.0, len = 0.5 + urand(&s);
            p[0] += len * cos(a);
            p[1] += len * sin(a);
        }
        ob_bez_from_points(&base[i], 3, (const double (*)[2])xy);
        const ob_fit_args args = {i % 2 ? 0.1 : -0.1, 1e-3, par};
        ob_fit fit;
        char msg[64];
        cobb->fit(&base[i], &args, NULL, &fit, msg, sizeof msg);
        approx[i] = fit.seg[0];
        recs[i] = (ob_measure_rec){&base[i], &approx[i], args.d, metric, 0.0, {NULL, 0, 0, 0, 0}};
    }
}

static void cpu_batch(const ob_measure_rec *recs, int n, int S, ob_errval *out, int threads)
{
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4)
    for (int i = 0; i < n; i++)
        ob_measure(recs[i].metric, recs[i].base, recs[i].approx, recs[i].d, S, &out[i]);
}

/* ---- whole runs --------------------------------------------------------- */

static const double five_tols[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5};

/* The jobs of every curve of set and offset, method (only, with parameter
 * values par; NULL: every method at its defaults) and tolerance of tols,
 * hausdorff, split rule split, into jobs (NULL: only counted).  Returns
 * their number. */
static size_t fill_jobs(ob_job *jobs, const ob_curveset *set, const ob_method *only, const double *par,
                        ob_split split, const double *tols, int ntol)
{
    const int nm = only ? 1 : ob_method_count();
    size_t k = 0;
    for (int c = 0; c < set->n; c++)
        for (int di = 0; di < set->v[c].nd; di++)
            for (int m = 0; m < nm; m++)
                for (int t = 0; t < ntol; t++, k++) {
                    if (!jobs)
                        continue;
                    ob_job *j = &jobs[k];
                    j->curve = &set->v[c];
                    j->d = set->v[c].d[di];
                    j->method = only ? only : ob_methods[m];
                    j->params = par;
                    j->metric = OB_METRIC_HAUSDORFF;
                    j->split = split;
                    j->tol = tols[t];
                }
    return k;
}

/* Every driver run of bench: the hooks given (or none) and the stop flag,
 * so that SIGINT/SIGTERM end a long run at its next chunk (its figures are
 * then not written: ob_cmd_bench discards the file). */
static void bench_driver_run(ob_job *jobs, size_t n, const ob_driver_opts *o, const ob_driver_hooks *h)
{
    ob_driver_hooks hh;
    if (h)
        hh = *h;
    else
        memset(&hh, 0, sizeof hh);
    hh.stop = ob_stop_flag();
    ob_driver_run(jobs, n, o, &hh);
}

/* Every method at the ntol tolerances tols on the curves of set, hausdorff,
 * the split rule split.  keep: NULL, or where the jobs go (with their
 * timings; the caller frees).  Returns the wall time, seconds. */
static double random_run(const ob_curveset *set, ob_split split, const double *tols, int ntol,
                         const ob_driver_opts *o, const ob_driver_hooks *h, size_t *njobs, ob_job **keep)
{
    const size_t n = fill_jobs(NULL, set, NULL, NULL, split, tols, ntol);
    ob_job *jobs = calloc(n ? n : 1, sizeof *jobs);
    if (!jobs)
        return -1.0;
    fill_jobs(jobs, set, NULL, NULL, split, tols, ntol);
    double t0 = now_s();
    bench_driver_run(jobs, n, o, h);
    double dt = now_s() - t0;
    if (keep)
        *keep = jobs;
    else
        free(jobs);
    *njobs = n;
    return dt;
}

static int cmp_dbl(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Per method, the median over its jobs of the fit time (fit_ns: the
 * method's own thread CPU time) and of the measuring time (eval_ns), as
 * bench.csv rows fit_per_job/NAME and eval_per_job/NAME (items 1: rate is
 * jobs per second of that work) and one printed line. */
static void per_method_times(bench_out *b, const ob_job *jobs, size_t n, int threads)
{
    double *v = malloc((n ? n : 1) * sizeof *v), *w = malloc((n ? n : 1) * sizeof *w);
    if (!v || !w) {
        free(v);
        free(w);
        return;
    }
    printf("median per job, fit / measure (ms):");
    for (int m = 0; ob_methods[m]; m++) {
        size_t k = 0;
        for (size_t i = 0; i < n; i++)
            if (jobs[i].method == ob_methods[m]) {
                v[k] = jobs[i].fit_ns * 1e-9;
                w[k++] = jobs[i].eval_ns * 1e-9;
            }
        if (k == 0)
            continue;
        qsort(v, k, sizeof *v, cmp_dbl);
        qsort(w, k, sizeof *w, cmp_dbl);
        char what[96];
        snprintf(what, sizeof what, "fit_per_job/%s", ob_methods[m]->name);
        row(b, what, "cpu", threads, 1.0, v[k / 2], "jobs/s");
        snprintf(what, sizeof what, "eval_per_job/%s", ob_methods[m]->name);
        row(b, what, "cpu", threads, 1.0, w[k / 2], "jobs/s");
        printf(" %s %.3g / %.3g", ob_methods[m]->name, v[k / 2] * 1e3, w[k / 2] * 1e3);
    }
    printf("\n");
    free(v);
    free(w);
}

static double whole_run(int threads, const ob_curveset *set, const ob_driver_opts *o, const ob_driver_hooks *h,
                        size_t *njobs)
{
    static const char *methods[] = {"tiller", "cobb", "ahn"};
    static const double tols[] = {1e-1, 1e-2, 1e-3, 1e-4};
    size_t n = 0;
    for (int c = 0; c < set->n; c++)
        n += (size_t)set->v[c].nd * 3 * 4;
    ob_job *jobs = calloc(n, sizeof *jobs);
    if (!jobs)
        return -1.0;
    size_t k = 0;
    for (int c = 0; c < set->n; c++)
        for (int di = 0; di < set->v[c].nd; di++)
            for (int m = 0; m < 3; m++)
                for (int t = 0; t < 4; t++) {
                    ob_job *j = &jobs[k++];
                    j->curve = &set->v[c];
                    j->d = set->v[c].d[di];
                    j->method = ob_method_find(methods[m]);
                    j->metric = OB_METRIC_HAUSDORFF;
                    j->split = OB_SPLIT_MID;
                    j->tol = tols[t];
                }
    omp_set_num_threads(threads);
    double t0 = now_s();
    bench_driver_run(jobs, n, o, h);
    double dt = now_s() - t0;
    free(jobs);
    *njobs = n;
    return dt;
}

typedef struct {
    const char *out, *device;
    int quick, kernels, protocol;
} bench_args;

static const ob_flag bench_flags[] = {
    {"out", "DIR", "output directory (default out/bench)", 0, OB_FLAG_ONCE},
    {"quick", NULL, "a tenth of the records (a smoke test of the figures)", 1, OB_FLAG_ONCE},
    {"kernels", NULL, "only the peaks, the OpenCL builds and each metric's samples (no whole runs)", 2,
     OB_FLAG_ONCE},
    {"device", "NAME", "the OpenCL device whose name contains NAME (default: the first with fp64)", 3,
     OB_FLAG_ONCE},
    {"protocol", NULL, "only the external-method protocol's figures (per fit call, and a Python method's "
     "scaling)", 4, OB_FLAG_ONCE},
};

static int apply_bench_flag(void *ctx, int id, const char *opt, const char *v)
{
    bench_args *a = ctx;
    if (id == 1 || id == 2) {
        *(id == 1 ? &a->quick : &a->kernels) = 1;
        return 0;
    }
    if (id == 3) {
        a->device = v;
        return 0;
    }
    if (id == 4) {
        a->protocol = 1;
        return 0;
    }
    return ob_cli_apply_dir(&a->out, id, opt, v);
}

/* The machine's FMA peaks: scalar on 1 and N threads (peak[0], peak[1]) and
 * vector on N (*vpeak, 0 when unknown), in flop/s. */
static void bench_peaks(bench_out *b, int N, double peak[2], double *vpeak)
{
    /* FMA peak */
    double secs;
    for (int k = 0; k < 2; k++) {
        int th = k ? N : 1;
        double fl = fma_peak(th, &secs);
        peak[k] = fl / secs;
        row(b, "fma_peak", "cpu", th, fl, secs, "flop/s");
    }
    printf("FMA peak, scalar code as the CPU path is built: %.2f GFLOP/s on 1 thread, %.2f on %d (x%.2f)\n",
           peak[0] / 1e9, peak[1] / 1e9, N, peak[1] / peak[0]);
    const char *isa;
    double vfl = fma_vector_peak(N, &secs, &isa);
    *vpeak = vfl > 0 ? vfl / secs : 0.0;
    if (vfl > 0) {
        row(b, "fma_vector", isa, N, vfl, secs, "flop/s");
        printf("FMA peak, %s vector: %.2f GFLOP/s on %d threads: the machine's peak\n", isa, *vpeak / 1e9, N);
    }

}

/* The sampled metrics the bench measures. */
static const ob_metric bench_mets[4] = {OB_METRIC_RADIAL, OB_METRIC_NORMAL, OB_METRIC_HAUSDORFF, OB_METRIC_PARAM};

/* The OpenCL backend with every metric's program built in both layouts
 * (cl_build rows), or NULL (said on stdout). */
static ob_cl *bench_open_cl(bench_out *b, const char *device)
{
    ob_cl *cl = NULL;
    ob_err err;
    if (ob_cl_open(device, 0, &cl, &err) != 0) {
        printf("OpenCL: not available (%s); its rows are missing\n", err.msg);
        return NULL;
    }
    for (int lay = 0; lay < 2 && !ob_stop_signal(); lay++)
        for (int mi = 0; mi < 4 && !ob_stop_signal(); mi++)
            if (ob_cl_prepare(cl, bench_mets[mi], lay ? OB_CL_ITEMS : OB_CL_GROUPS, &err) != 0) {
                printf("OpenCL: %s; its rows are missing\n", err.msg);
                ob_cl_close(cl);
                return NULL;
            }
    ob_cl_build rep[16];
    const int n = ob_cl_builds(cl, rep, 16);
    printf("OpenCL: %s / %s: %d programs (a metric in a layout each) built in %.2f s (not in any timing below):\n",
           ob_cl_platform(cl), ob_cl_device(cl), n, ob_cl_build_seconds(cl));
    for (int i = 0; i < n && i < 16; i++) {
        char what[64];
        snprintf(what, sizeof what, "cl_build/%s/%s", ob_metric_name(rep[i].metric), ob_cl_layout_name(rep[i].layout));
        const char *how = strncmp(rep[i].cache, "hit", 3) == 0 ? "cache-hit"
                          : strncmp(rep[i].cache, "off", 3) == 0 ? "cache-off" : "cache-miss";
        row(b, what, how, 0, 1, rep[i].seconds, "builds/s");
        printf("  %-28s %7.2f s  %s\n", what, rep[i].seconds, rep[i].cache);
    }
    row(b, "kernel_build", "opencl", 0, n, ob_cl_build_seconds(cl), "builds/s");
    return cl;
}

/* The OpenCL device's double-precision peak (cl_fma_peak, the device by
 * name), flop/s; 0 when it could not be measured (said on stdout). */
static double bench_cl_peak(bench_out *b, ob_cl *cl, int quick)
{
    double fl = 0.0, secs = 0.0;
    ob_err err;
    if (ob_cl_fma_peak(cl, quick ? 0.1 : 0.5, &fl, &secs, &err) != 0 || secs <= 0.0) {
        printf("OpenCL fp64 peak: not measured (%s)\n", err.msg);
        return 0.0;
    }
    char dev[256];  /* a CSV field: no commas */
    snprintf(dev, sizeof dev, "%s", ob_cl_device(cl));
    for (char *p = dev; *p; p++)
        if (*p == ',' || *p == '\n' || *p == '"')
            *p = ' ';
    row(b, "cl_fma_peak", dev, 0, fl, secs, "flop/s");
    printf("OpenCL fp64 peak (mad chains, counted 2 flops each), %s: %.2f GFLOP/s\n", ob_cl_device(cl),
           fl / secs / 1e9);
    return fl / secs;
}

/* One OpenCL batch of the records in layout l: host wall seconds (*wall)
 * and the kernels' own time (*kern, profiling events; the wall when the
 * driver gives none).  0, or -1 when the batch failed. */
static int cl_timed(ob_cl *cl, const ob_measure_rec *recs, int R, int S, ob_errval *out, double *wall, double *kern)
{
    double dev_ns = 0.0;
    ob_cl_measure_batch(cl, recs, 8 < R ? 8 : R, S, out);  /* warm-up: buffers, first launch */
    const double t0 = now_s();
    if (ob_cl_submit(cl, 0, recs, R, S) != 0 || ob_cl_wait(cl, 0, out, &dev_ns) != 0)
        return -1;
    *wall = now_s() - t0;
    *kern = dev_ns > 0 ? 1e-9 * dev_ns : *wall;
    return 0;
}

/* One metric's batch in bench_metrics and what its CPU pass measured: the
 * OpenCL layouts and the summary lines read them. */
typedef struct {
    const ob_measure_rec *recs;
    int R, R1, S, N;
    ob_errval *o1, *o2;        /* the CPU's errors, an OpenCL layout's */
    const char *mn;            /* the metric's name */
    char what[64], gw[64];     /* the rows "samples/<metric>", "gflops/<metric>" */
    double cN, flops;          /* N threads' seconds, the work counted */
    size_t to, back;           /* bytes to the device and back, all records */
} metric_bench;

/* The CPU figures of one metric's batch: 1 thread on the first R1 records,
 * N threads on all; the work counts into mb. */
static void bench_metric_cpu(bench_out *b, metric_bench *mb)
{
    const int R = mb->R, R1 = mb->R1, S = mb->S, N = mb->N;
    cpu_batch(mb->recs, 8, S, mb->o1, 1);  /* warm-up */
    double t0 = now_s();
    cpu_batch(mb->recs, R1, S, mb->o1, 1);
    const double c1 = now_s() - t0;
    t0 = now_s();
    cpu_batch(mb->recs, R, S, mb->o1, N);
    const double cN = now_s() - t0;
    double flops = 0.0;  /* as the metric core counts them */
    size_t to = 0, back = 0;
    for (int i = 0; i < R; i++) {
        flops += mb->o1[i].work;
        size_t t, bk;
        ob_cl_record_bytes(mb->recs[i].base->deg, mb->recs[i].approx->deg, &t, &bk);
        to += t;
        back += bk;
    }
    row(b, mb->what, "cpu", 1, (double)R1 * S, c1, "samples/s");
    row(b, mb->what, "cpu", N, (double)R * S, cN, "samples/s");
    printf("%-18s CPU: %9.0f samples/s on 1 thread, %9.0f on %d (x%.2f)", mb->what, R1 * S / c1, R * S / cN, N,
           (R1 * S / c1) > 0 ? (R * S / cN) / (R1 * S / c1) : 0.0);
    snprintf(mb->gw, sizeof mb->gw, "gflops/%s", mb->mn);
    row(b, mb->gw, "cpu", N, flops, cN, "flop/s");
    mb->cN = cN;
    mb->flops = flops;
    mb->to = to;
    mb->back = back;
}

/* One OpenCL layout l of one metric's batch (rows "opencl-groups",
 * "opencl-items", and as "opencl" the layout runs use); its share of the
 * device's peak into share.  Returns its wall seconds, -1 when the batch
 * failed. */
static double bench_metric_cl(bench_out *b, ob_cl *cl, const metric_bench *mb, ob_cl_layout l,
                              ob_cl_layout runs_use, double clpeak, char *share, size_t slen)
{
    const int R = mb->R, S = mb->S;
    const double flops = mb->flops;
    char bk[32], wk[64];
    snprintf(bk, sizeof bk, "opencl-%s", ob_cl_layout_name(l));
    ob_cl_set_layout(cl, l);
    double g, kern;
    if (cl_timed(cl, mb->recs, R, S, mb->o2, &g, &kern) != 0)
        return -1.0;
    snprintf(wk, sizeof wk, "cl_peak_fraction/%s", mb->mn);
    for (int as_run = 0; as_run < (l == runs_use ? 2 : 1); as_run++) {
        row(b, mb->what, as_run ? "opencl" : bk, 0, (double)R * S, g, "samples/s");
        row(b, mb->gw, as_run ? "opencl" : bk, 0, flops, g, "flop/s");
        if (clpeak > 0)
            row_rate(b, wk, as_run ? "opencl" : bk, 0, flops, kern, flops / kern / clpeak, "of_peak");
    }
    int same = 0;
    double lw = 0.0; /* the work this layout did (hausdorff's groups do more) */
    for (int i = 0; i < R; i++) {
        same += memcmp(&mb->o1[i].err, &mb->o2[i].err, sizeof(double)) == 0;
        lw += mb->o2[i].work;
    }
    printf("; OpenCL %s%s %9.0f (x%.2f vs CPU on %d threads; %d of %d errors bit for bit", ob_cl_layout_name(l),
           l == runs_use ? " (runs)" : "", R * S / g, mb->cN / g, mb->N, same, R);
    if (lw != flops) {
        snprintf(wk, sizeof wk, "ops_per_sample/%s", mb->mn);
        row_rate(b, wk, bk, 0, (double)R * S, 0.0, lw / ((double)R * S), "flop/sample");
        printf("; its own work %.0f flops a sample, x%.2f the serial scan's", lw / ((double)R * S), lw / flops);
    }
    printf(")");
    if (clpeak > 0)
        snprintf(share, slen, "%s %.3g GFLOP/s in the kernel's own time, %.2f%%", ob_cl_layout_name(l),
                 flops / kern / 1e9, 100.0 * flops / kern / clpeak);
    return g;
}

/* The closing lines of one metric: the best rate against the CPU's peaks
 * and the device's, and the work counts. */
static void bench_metric_summary(bench_out *b, const metric_bench *mb, double gbest, const double peak[2],
                                 double vpeak, char share[2][96])
{
    const int R = mb->R, S = mb->S;
    const double flops = mb->flops;
    char wk[64];
    printf("\n%-18s >= %.2f GFLOP/s at best (as the metric core counts them), %.1f%% of the scalar peak%s", "",
           gbest / 1e9, 100.0 * gbest / peak[1], vpeak > 0 ? "" : "\n");
    if (vpeak > 0)
        printf(", %.1f%% of the vector peak\n", 100.0 * gbest / vpeak);
    if (share[0][0] || share[1][0])
        printf("%-18s of the device's fp64 peak: %s%s%s\n", "", share[0], share[0][0] && share[1][0] ? "; " : "",
               share[1]);
    snprintf(wk, sizeof wk, "samples_per_record/%s", mb->mn);
    row_rate(b, wk, "any", 0, R, 0.0, S, "samples/record");
    snprintf(wk, sizeof wk, "ops_per_sample/%s", mb->mn);
    row_rate(b, wk, "any", 0, (double)R * S, 0.0, flops / ((double)R * S), "flop/sample");
    snprintf(wk, sizeof wk, "bytes_per_record/%s", mb->mn);
    row_rate(b, wk, "opencl", 0, R, 0.0, (double)mb->to / R, "bytes/record");
    snprintf(wk, sizeof wk, "bytes_back_per_record/%s", mb->mn);
    row_rate(b, wk, "opencl", 0, R, 0.0, (double)mb->back / R, "bytes/record");
    printf("%-18s work: %d samples a record, %.0f flops a sample (counted), %.0f bytes a record to the device, "
           "%.0f back\n", "", S, flops / ((double)R * S), (double)mb->to / R, (double)mb->back / R);
}

/* The sampling engine, per metric: R records of S samples on the CPU (1
 * thread on the first R1 of them, N threads on all) and with OpenCL (cl, or
 * NULL; clpeak its fp64 peak, 0 unknown), and the work counts; 0, or -1
 * after ob_error(). */
static int bench_metrics(bench_out *b, ob_cl *cl, int R, int R1, int S, int N, const double peak[2], double vpeak,
                         double clpeak)
{
    ob_bez *base = malloc((size_t)R * sizeof *base), *approx = malloc((size_t)R * sizeof *approx);
    ob_measure_rec *recs = malloc((size_t)R * sizeof *recs);
    ob_errval *o1 = malloc((size_t)R * sizeof *o1), *o2 = malloc((size_t)R * sizeof *o2);
    int rc = 0;
    if (!base || !approx || !recs || !o1 || !o2) {
        ob_error("bench: out of memory");
        rc = -1;
        goto out;
    }
    if (cl)
        printf("OpenCL batches: %d records of %d samples, %.3g samples a launch%s\n", R, S, (double)R * S,
               ob_cl_is_gpu(cl) ? " (a GPU: at least 1e7)" : "");
    for (int mi = 0; mi < 4 && !ob_stop_signal(); mi++) {
        metric_bench mb = {.recs = recs, .R = R, .R1 = R1, .S = S, .N = N, .o1 = o1, .o2 = o2};
        mb.mn = ob_metric_name(bench_mets[mi]);
        snprintf(mb.what, sizeof mb.what, "samples/%s", mb.mn);
        make_batch(R, base, approx, recs, bench_mets[mi]);
        bench_metric_cpu(b, &mb);
        double gbest = mb.flops / mb.cN;
        const ob_cl_layout runs_use = ob_cl_get_layout(cl);
        char share[2][96] = {"", ""};
        for (int lay = 0; cl && lay < 2 && !ob_stop_signal(); lay++) {
            const double g = bench_metric_cl(b, cl, &mb, lay ? OB_CL_ITEMS : OB_CL_GROUPS, runs_use, clpeak,
                                             share[lay], sizeof share[lay]);
            if (g >= 0)
                gbest = fmax(gbest, mb.flops / g);
        }
        ob_cl_set_layout(cl, runs_use);
        bench_metric_summary(b, &mb, gbest, peak, vpeak, share);
    }

out:
    free(base);
    free(approx);
    free(recs);
    free(o1);
    free(o2);
    return rc;
}

/* Whole runs of the default job, 1 vs N threads on the CPU path, and with
 * OpenCL (cl, or NULL). */
static void bench_whole_runs(bench_out *b, ob_cl *cl, int N)
{
    ob_curveset set = {0};
    char where[4096];
    ob_err cerr;
    if (ob_load_default_curves(&set, where, sizeof where, &cerr) == 0) {
        ob_driver_opts o;
        ob_driver_defaults(&o);
        size_t nj = 0;
        const double r1 = whole_run(1, &set, &o, NULL, &nj);
        const double rN = ob_stop_signal() ? 0.0 : whole_run(N, &set, &o, NULL, &nj);
        row(b, "run", "cpu", 1, (double)nj, r1, "jobs/s");
        row(b, "run", "cpu", N, (double)nj, rN, "jobs/s");
        printf("whole run (%zu jobs, hausdorff): %.2f s on 1 thread, %.2f s on %d: speedup x%.2f\n", nj, r1, rN, N,
               r1 / rN);
        if (cl && !ob_stop_signal()) {
            const ob_driver_hooks clh = {.batch = ob_cl_measure_batch, .batch_ctx = cl,
                                         .batch_chunk = ob_cl_is_gpu(cl) ? OB_GPU_CHUNK : 0};
            double g = whole_run(N, &set, &o, &clh, &nj);
            row(b, "run", "opencl", N, (double)nj, g, "jobs/s");
            printf("whole run with the OpenCL backend: %.2f s (x%.2f vs CPU on %d threads)\n", g, rN / g, N);
        }
    }
    ob_curveset_free(&set);

}

/* The greedy rule on the random set (all methods, 1e-2 ... 1e-4, CPU) with
 * every probe measured in full and with probes that stop once they fail
 * (the default; the same results): jobs per second of each. */
static void bench_probe_stops(bench_out *b, const ob_curveset *set, int N)
{
    static const double tols[] = {1e-2, 1e-3, 1e-4};
    ob_driver_opts o;
    ob_driver_defaults(&o);
    size_t nj = 0;
    o.full_probes = 1;
    const double full = random_run(set, OB_SPLIT_GREEDY, tols, 3, &o, NULL, &nj, NULL);
    row(b, "greedy_run/full_probes", "cpu", N, (double)nj, full, "jobs/s");
    o.full_probes = 0;
    const double stop = random_run(set, OB_SPLIT_GREEDY, tols, 3, &o, NULL, &nj, NULL);
    row(b, "greedy_run", "cpu", N, (double)nj, stop, "jobs/s");
    printf("greedy run (all methods, 3 tolerances: %zu jobs): %.0f jobs/s with every probe measured in full, %.0f "
           "with probes that stop once they fail (x%.2f)\n", nj, nj / full, nj / stop, full / stop);
}

/* The median of the fit times of n jobs, seconds (v: n doubles of scratch). */
static double median_fit(const ob_job *jobs, size_t n, double *v)
{
    for (size_t i = 0; i < n; i++)
        v[i] = jobs[i].fit_ns * 1e-9;
    qsort(v, n, sizeof *v, cmp_dbl);
    return n ? v[n / 2] : 0.0;
}

/* cubic-opt on the random set, 1e-2 ... 1e-5, greedy: the driver's search
 * (every probe measured) against the fit's own split (split = 1): the
 * same jobs, timed in this one run, and their control points compared. */
static void bench_own_split(bench_out *b, const ob_curveset *set, int N)
{
    static const double tols[] = {1e-2, 1e-3, 1e-4, 1e-5};
    const ob_method *m = ob_method_find("cubic-opt");
    const int ks = m ? ob_param_find(m, "split") : -1;
    const size_t n = fill_jobs(NULL, set, m, NULL, OB_SPLIT_GREEDY, tols, 4);
    ob_job *jobs = calloc(2 * (n ? n : 1), sizeof *jobs);
    double *v = malloc((n ? n : 1) * sizeof *v), par[2][OB_MAX_PARAMS];
    if (ks < 0 || !jobs || !v) {
        free(jobs);
        free(v);
        return;
    }
    for (int r = 0; r < 2; r++) {
        ob_param_defaults(m, par[r]);
        par[r][ks] = r;
    }
    for (int r = 0; r < 2; r++)
        fill_jobs(jobs + r * n, set, m, par[r], OB_SPLIT_GREEDY, tols, 4);
    ob_driver_opts o;
    ob_driver_defaults(&o);
    double dt[2];
    for (int r = 0; r < 2; r++) {
        const double t0 = now_s();
        bench_driver_run(jobs + r * n, n, &o, NULL);
        dt[r] = now_s() - t0;
    }
    long cp[2] = {0, 0}, fewer = 0, more = 0, both = 0;
    for (size_t i = 0; i < n; i++) {
        if (jobs[i].status != OB_OK || jobs[n + i].status != OB_OK)
            continue;  /* a failed job's count is 0 */
        both++;
        cp[0] += jobs[i].ctrl_points;
        cp[1] += jobs[n + i].ctrl_points;
        fewer += jobs[n + i].ctrl_points < jobs[i].ctrl_points;
        more += jobs[n + i].ctrl_points > jobs[i].ctrl_points;
    }
    const double fg = median_fit(jobs, n, v), fo = median_fit(jobs + n, n, v);
    row(b, "own_split/greedy", "cpu", N, (double)n, dt[0], "jobs/s");
    row(b, "own_split/own", "cpu", N, (double)n, dt[1], "jobs/s");
    row(b, "fit_per_job/cubic-opt/greedy", "cpu", N, 1.0, fg, "jobs/s");
    row(b, "fit_per_job/cubic-opt/own", "cpu", N, 1.0, fo, "jobs/s");
    printf("cubic-opt's own split (%zu jobs, 1e-2 ... 1e-5): %.0f jobs/s against greedy's %.0f (x%.2f); median "
           "fit per job %.3g ms against %.3g; on the %ld jobs ok in both, control points %ld against %ld (x%.3f; "
           "%ld jobs fewer, %ld more)\n", n, n / dt[1], n / dt[0], dt[0] / dt[1], fo * 1e3, fg * 1e3, both, cp[1],
           cp[0], cp[0] ? (double)cp[1] / cp[0] : 0.0, fewer, more);
    free(jobs);
    free(v);
}

/* The engines on a random set large enough to model 16 and 64 threads from
 * (bench_engines.c): all methods at 5 tolerances, mid, hausdorff. */
static void bench_engines(bench_out *b, ob_cl *cl, int N, int quick)
{
    ob_err cerr;
    ob_curveset set = {0};
    char what[64];
    const long ncurves = quick ? 10 : 100;
    snprintf(what, sizeof what, "engines_random%ld_7", ncurves);
    if (ob_random_append(&set, 7, ncurves, NULL, 0, &cerr) == 0) {
        const size_t n = fill_jobs(NULL, &set, NULL, NULL, OB_SPLIT_MID, five_tols, 5);
        ob_job *jobs = calloc(n ? n : 1, sizeof *jobs);
        if (jobs) {
            fill_jobs(jobs, &set, NULL, NULL, OB_SPLIT_MID, five_tols, 5);
            omp_set_num_threads(N);
            const ob_driver_hooks clh = {.batch = ob_cl_measure_batch, .batch_ctx = cl,
                                         .batch_submit = ob_cl_batch_submit, .batch_wait = ob_cl_batch_wait,
                                         .batch_overlap = ob_cl_is_gpu(cl),
                                         .batch_chunk = ob_cl_is_gpu(cl) ? OB_GPU_CHUNK : 0};
            if (ob_bench_engines(b->csv, jobs, n, what, cl ? &clh : NULL) != 0)
                ob_error("bench: the engines' rows differ (or memory ran out): see above");
        }
        free(jobs);
    }
    ob_curveset_free(&set);
}

/* All methods at 5 tolerances on a fixed random set, on the CPU and with
 * OpenCL (cl, or NULL); then each method's median times per job; then the
 * greedy rule with and without probe stops; then cubic-opt's own split. */
static void bench_random(bench_out *b, ob_cl *cl, int N, int quick)
{
    ob_err cerr;
    ob_curveset rset = {0};
    if (ob_random_append(&rset, 1, quick ? 8 : 24, NULL, 0, &cerr) == 0) {
        ob_driver_opts o;
        ob_driver_defaults(&o);
        omp_set_num_threads(N);
        size_t nj = 0;
        ob_job *kept = NULL;
        double c = random_run(&rset, OB_SPLIT_MID, five_tols, 5, &o, NULL, &nj, &kept);
        row(b, "random_run", "cpu", N, (double)nj, c, "jobs/s");
        printf("random run (%d curves, all %d methods, 5 tolerances: %zu jobs): %.0f jobs/s on the CPU",
               rset.n, ob_method_count(), nj, nj / c);
        if (cl && !ob_stop_signal()) {
            const ob_driver_hooks clh = {.batch = ob_cl_measure_batch, .batch_ctx = cl,
                                         .batch_chunk = ob_cl_is_gpu(cl) ? OB_GPU_CHUNK : 0};
            double g = random_run(&rset, OB_SPLIT_MID, five_tols, 5, &o, &clh, &nj, NULL);
            row(b, "random_run", "opencl", N, (double)nj, g, "jobs/s");
            printf(", %.0f with OpenCL (x%.2f)", nj / g, c / g);
        }
        printf("\n");
        if (kept)
            per_method_times(b, kept, nj, N);
        free(kept);
        if (!ob_stop_signal())
            bench_probe_stops(b, &rset, N);
        if (!ob_stop_signal())
            bench_own_split(b, &rset, N);
    }
    ob_curveset_free(&rset);
    if (!ob_stop_signal())
        bench_engines(b, cl, N, quick);
}

/* bench --protocol: that section alone, its file committed as a whole
 * bench's is; the exit status. */
static int bench_protocol_only(bench_out *b, ob_outfile *of, const char *out, const char *path, int N, int quick)
{
    ob_err err;
    ob_bench_protocol(b->csv, N, quick);
    if (ob_stop_signal()) {
        ob_outfile_discard(of);
        return ob_stop_exit("bench: nothing written to %s (a bench.csv there is an earlier run's); run it again", out);
    }
    if (ob_outfile_commit(of, 0, &err) != 0) {
        ob_error("%s", err.msg);
        return 1;
    }
    printf("wrote %s\n", path);
    return 0;
}

int ob_cmd_bench(int argc, char **argv)
{
    bench_args a = {"out/bench", NULL, 0, 0, 0};
    const ob_flagset flags = {bench_flags, 5, NULL, NULL, "options", apply_bench_flag, &a};
    const int prc = ob_cli_parse("[--out DIR] [--quick] [--kernels] [--device NAME] [--protocol]", &flags, 1, argc,
                                 argv, 0, NULL, NULL);
    if (prc != OB_CLI_OK)
        return prc == OB_CLI_HELP ? 0 : 2;
    if (a.protocol && a.kernels) {
        ob_error("bench: --protocol and --kernels each ask for one section only: give one");
        return 2;
    }
    if (ob_mkdir_p(a.out) != 0) {
        ob_error("--out: cannot create '%s': %s", a.out, strerror(errno));
        return 1;
    }
    char path[4200];
    snprintf(path, sizeof path, "%s/bench.csv", a.out);
    ob_outfile of;  /* written afresh, never through a link (outfile.h) */
    ob_err err;
    if (ob_outfile_open(&of, path, 0, &err) != 0) {
        ob_error("%s", err.msg);
        return 1;
    }
    bench_out b = {of.f};
    fprintf(b.csv, "what,backend,threads,items,seconds,rate,unit\n");
    const int N = omp_get_num_procs();
    if (a.protocol)
        return bench_protocol_only(&b, &of, a.out, path, N, a.quick);
    double peak[2], vpeak;
    bench_peaks(&b, N, peak, &vpeak);
    ob_cl *cl = ob_stop_signal() ? NULL : bench_open_cl(&b, a.device);
    if (a.device && !cl && !ob_stop_signal()) {  /* asked for by name, as run --device is */
        ob_outfile_discard(&of);
        ob_error("bench --device %s: that OpenCL device cannot measure (see above); nothing written", a.device);
        return 2;
    }
    const double clpeak = cl && !ob_stop_signal() ? bench_cl_peak(&b, cl, a.quick) : 0.0;
    /* records: on a GPU at least 1e7 samples a launch; on the CPU (and a CPU
     * device) few enough for a 2-core machine */
    const int S = OB_DEFAULT_SAMPLES, small = a.quick ? 200 : 2000;
    const int R = cl && ob_cl_is_gpu(cl) ? (int)ceil(OB_BENCH_GPU_SAMPLES / S) : small;
    int rc = ob_stop_signal() ? 0 : bench_metrics(&b, cl, R, R < small ? R : small, S, N, peak, vpeak, clpeak);
    if (rc == 0 && !a.kernels && !ob_stop_signal())
        bench_whole_runs(&b, cl, N);
    if (rc == 0 && !a.kernels && !ob_stop_signal())
        bench_random(&b, cl, N, a.quick);
    if (rc == 0 && !a.kernels && !ob_stop_signal()) /* last: it registers external methods */
        ob_bench_protocol(b.csv, N, a.quick);
    ob_cl_close(cl);
    if (ob_stop_signal()) {  /* a section cut short has no figures: none are written */
        ob_outfile_discard(&of);
        return ob_stop_exit("bench: nothing written to %s (a bench.csv there is an earlier run's); run it again",
                            a.out);
    }
    if (ob_outfile_commit(&of, 0, &err) != 0) {  /* the rows so far, as before, also when rc != 0 */
        ob_error("%s", err.msg);
        return 1;
    }
    if (rc != 0)
        return 1;
    printf("wrote %s\n", path);
    return 0;
}
