/*
 * bench_engines.c - `bench`'s engine figures (README "Engines"): the same
 * jobs through the level engine and the group engine on all threads here,
 * measured in one run, each with its efficiency (work / (threads x wall)),
 * where the rest of the threads' time went, and the efficiency its own
 * trace models at 16 and 64 threads (ob_trace_makespan); then the OpenCL
 * backend through each engine, with the batch size the device got.  Every
 * run's rows are checked equal to the first's (timings aside).
 */
#include "host/cli/bench_engines.h"
#include "host/run/signals.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static size_t rows_differing(const ob_job *a, const ob_job *b, size_t n)
{
    size_t bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += !(a[i].status == b[i].status && a[i].ctrl_points == b[i].ctrl_points &&
                 a[i].segments == b[i].segments && same_bits(a[i].max_err, b[i].max_err) &&
                 same_bits(a[i].max_gap, b[i].max_gap) && strcmp(a[i].message, b[i].message) == 0);
    return bad;
}

/* One engine's run of the jobs (copied from tmpl): its figures and trace. */
typedef struct {
    ob_engine_stats st;
    ob_trace tr;
    ob_job *jobs;
} engine_run;

static int run_engine(const ob_job *tmpl, size_t n, ob_engine e, const ob_driver_hooks *backend, engine_run *r)
{
    memset(r, 0, sizeof *r);
    r->jobs = malloc((n ? n : 1) * sizeof *r->jobs);
    if (!r->jobs)
        return -1;
    memcpy(r->jobs, tmpl, n * sizeof *r->jobs);
    ob_driver_opts o;
    ob_driver_defaults(&o);
    o.engine = e;
    ob_driver_hooks h;
    memset(&h, 0, sizeof h);
    if (backend) {
        h.batch = backend->batch;
        h.batch_ctx = backend->batch_ctx;
        h.batch_chunk = backend->batch_chunk;
        h.batch_submit = backend->batch_submit;
        h.batch_wait = backend->batch_wait;
        h.batch_overlap = backend->batch_overlap;
    }
    h.stats = &r->st;
    h.trace = &r->tr;
    h.stop = ob_stop_flag();  /* bench discards its figures when stopped */
    return ob_driver_run(r->jobs, n, &o, &h) == 0 ? 0 : -1;
}

/* Efficiency the trace models at P threads: work / (P x makespan). */
static double modelled(const engine_run *r, int P)
{
    const double span = ob_trace_makespan(&r->tr, P);
    return span > 0 ? r->tr.work_ns / (P * span) : 0.0;
}

/* The threads' time, threads x wall, split into the work (fits and
 * measurements), the decisions and sorting (the level engine's on one
 * thread while the others wait at its barrier: counted for all threads;
 * the group engine's in its groups' own threads), and the rest: waiting
 * (barriers, the tail) and what the trace does not see (joints, making
 * the records, taking tasks, the lock that tells jobs finished). */
static void where_it_went(const engine_run *r, double *work, double *decide, double *rest)
{
    double ser = 0.0;
    for (size_t p = 0; p < r->tr.nphase; p++)
        ser += r->tr.phase[p].serial_ns * (r->tr.phase[p].group >= 0 ? 1 : r->st.threads);
    const double all = r->st.threads * r->st.wall_ns;
    *work = r->st.work_ns / all;
    *decide = ser / all;
    *rest = 1.0 - *work - *decide;
}

/* A CPU run: its efficiency, where the rest went, its model at 16 and 64. */
static void report_cpu(FILE *csv, const char *what, const engine_run *r)
{
    double w, s, rest;
    where_it_went(r, &w, &s, &rest);
    const char *e = ob_engine_name(r->st.engine);
    printf("  %-6s cpu     %2d threads: %6.2f s wall, efficiency %5.1f %% (decisions %4.1f %%, waiting and "
           "untraced %4.1f %%); modelled %5.1f %% at %d, %5.1f %% at 16, %5.1f %% at 64\n",
           e, r->st.threads, r->st.wall_ns * 1e-9, 100 * w, 100 * s, 100 * rest,
           100 * modelled(r, r->st.threads), r->st.threads, 100 * modelled(r, 16), 100 * modelled(r, 64));
    fprintf(csv, "%s/%s,cpu,%d,%ld,%.6f,%.6g,efficiency\n", what, e, r->st.threads, r->st.groups,
            r->st.wall_ns * 1e-9, w);
    const int P[2] = {16, 64};
    for (int k = 0; k < 2; k++)
        fprintf(csv, "%s/%s/model%d,cpu,%d,%ld,%.6f,%.6g,efficiency\n", what, e, P[k], P[k], r->st.groups,
                ob_trace_makespan(&r->tr, P[k]) * 1e-9, modelled(r, P[k]));
}

/* A run with the batch backend: its wall against the CPU's, the batches.
 * (Its thread-time efficiency means little: a launch's wall time is shared
 * among its records, and the device's own threads are not counted.) */
static void report_backend(FILE *csv, const char *what, const engine_run *r, double cpu_wall_ns)
{
    const double per = r->st.launches > 0 ? (double)r->st.records / r->st.launches : 0.0;
    printf("  %-6s opencl  %2d threads: %6.2f s wall (x%.2f the level engine on the CPU); %ld launches, %.0f "
           "records each", ob_engine_name(r->st.engine), r->st.threads, r->st.wall_ns * 1e-9,
           cpu_wall_ns / r->st.wall_ns, r->st.launches, per);
    if (r->st.device_ns > 0)
        printf("; device busy %.2f s, %.0f %% of it hidden behind fits", r->st.device_ns * 1e-9,
               100 * (1.0 - r->st.blocked_ns / r->st.device_ns));
    printf("\n");
    fprintf(csv, "%s/%s,opencl,%d,%ld,%.6f,%.6g,records/launch\n", what, ob_engine_name(r->st.engine),
            r->st.threads, r->st.records, r->st.wall_ns * 1e-9, per);
}

static void engine_run_free(engine_run *r)
{
    ob_trace_free(&r->tr);
    free(r->jobs);
}

int ob_bench_engines(FILE *csv, const ob_job *jobs, size_t n, const char *what, const ob_driver_hooks *cl)
{
    printf("engines (%s: %zu jobs; efficiency = fit and measure thread time / (threads x wall)):\n", what, n);
    engine_run ref;
    if (run_engine(jobs, n, OB_ENGINE_LEVEL, NULL, &ref) != 0) {
        engine_run_free(&ref);
        return -1;
    }
    report_cpu(csv, what, &ref);
    const struct {
        ob_engine e;
        const ob_driver_hooks *h;
        const char *backend;
    } runs[] = {{OB_ENGINE_GROUP, NULL, "cpu"},
                {OB_ENGINE_LEVEL, cl, "opencl"},
                {OB_ENGINE_GROUP, cl, "opencl"},
                {OB_ENGINE_DEVICE, cl, "opencl"}};
    size_t bad = 0;
    double wall_group_cpu = 0.0;
    for (size_t k = 0; k < sizeof runs / sizeof runs[0] && !ob_stop_signal(); k++) {
        if (runs[k].h == NULL && strcmp(runs[k].backend, "opencl") == 0)
            continue;
        engine_run r;
        if (run_engine(jobs, n, runs[k].e, runs[k].h, &r) == 0) {
            if (runs[k].h)
                report_backend(csv, what, &r, ref.st.wall_ns);
            else
                report_cpu(csv, what, &r);
            bad += rows_differing(ref.jobs, r.jobs, n);
            if (k == 0)
                wall_group_cpu = r.st.wall_ns;
        }
        engine_run_free(&r);
    }
    printf("  group vs level on the CPU: x%.2f; rows differing from the level engine's: %zu\n",
           wall_group_cpu > 0 ? ref.st.wall_ns / wall_group_cpu : 0.0, bad);
    engine_run_free(&ref);
    return bad ? -1 : 0;
}
