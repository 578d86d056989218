/*
 * test_engines.c - how the work is scheduled never changes an answer
 * (driver.h, ob_engine): every engine, at 1, 2 and 7 threads and at chunk
 * sizes from 1 to the default, gives every job the same outputs, bit for
 * bit (timings aside) and the same accepted pieces; the group engine tells
 * each job once, in the same order at any thread count; a stopped run keeps
 * what it finished; the schedule model (ob_trace_makespan) is a list
 * schedule.  The jobs: random curves of every family, every registered
 * method, every split rule, a sampled metric and the bound, tolerances
 * that share pieces.
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/random.h"
#include "methods/driver/driver.h"
#include "tests/check.h"

static const double tols[3] = {1e-1, 1e-2, 3e-3};

enum { NCURVES = 8 };

typedef struct {
    ob_job *jobs;
    size_t n;
    ob_curve *curves;   /* NCURVES, where the jobs point */
} jobset;

/* Every split rule over the jobs; optimal (about ten times greedy's fits)
 * only for methods whose fits are cheap, to keep the test short. */
static ob_split split_of(const ob_method *m, int mi, int c)
{
    static const char *const cheap[] = {"tiller", "cobb", "ahn", "interp", "elber"};
    for (size_t k = 0; k < sizeof cheap / sizeof *cheap; k++)
        if (strcmp(m->name, cheap[k]) == 0)
            return (ob_split)((mi + c) % OB_SPLIT_COUNT);
    return (ob_split)((mi + c) % OB_SPLIT_OPTIMAL);
}

/* The jobs: 8 random curves (one per family) x their offsets x every method
 * x one split rule (by method and curve, all four covered) x 3 tols, the
 * hausdorff metric; and tiller under the bound and mid. */
static jobset make_jobs(void)
{
    jobset s;
    memset(&s, 0, sizeof s);
    s.curves = calloc(NCURVES, sizeof *s.curves);
    size_t cap = 0;
    for (int c = 0; c < NCURVES; c++) {
        CHECK(ob_random_curve(5, c, &s.curves[c]) == 0, "random curve %d", c);
        for (int m = 0; ob_methods[m]; m++)
            cap += (size_t)s.curves[c].nd * 3 + 3;
    }
    s.jobs = calloc(cap + 64, sizeof *s.jobs);
    for (int c = 0; c < NCURVES; c++)
        for (int k = 0; k < s.curves[c].nd; k++)
            for (int m = 0; ob_methods[m]; m++)
                for (int t = 0; t < 3; t++) {
                    ob_job *j = &s.jobs[s.n++];
                    j->curve = &s.curves[c];
                    j->d = s.curves[c].d[k];
                    j->method = ob_methods[m];
                    j->metric = m == 0 && c % 2 ? OB_METRIC_BOUND : OB_METRIC_HAUSDORFF;
                    j->split = split_of(ob_methods[m], m, c);
                    j->tol = tols[t];
                }
    return s;
}

static void free_jobs(jobset *s)
{
    free(s->jobs);
    for (int c = 0; c < NCURVES; c++)
        ob_curve_free(&s->curves[c]);
    free(s->curves);
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Every output but the timings, bit for bit. */
static int same_job(const ob_job *a, const ob_job *b)
{
    return a->status == b->status && a->ctrl_points == b->ctrl_points && a->segments == b->segments &&
           a->out_degree == b->out_degree && same_bits(a->max_err, b->max_err) &&
           strcmp(a->message, b->message) == 0 && same_bits(a->max_gap, b->max_gap) &&
           same_bits(a->max_kink, b->max_kink) && a->continuity == b->continuity && a->joints == b->joints &&
           a->open_joints == b->open_joints;
}

static int same_spans(const ob_span_log *a, const ob_span_log *b)
{
    if (a->n != b->n || a->oom || b->oom)
        return 0;
    for (int k = 0; k < a->n; k++)
        if (a->v[k].seg != b->v[k].seg || !same_bits(a->v[k].a, b->v[k].a) || !same_bits(a->v[k].b, b->v[k].b))
            return 0;
    return 1;
}

/* The order in which jobs were told finished. */
typedef struct {
    size_t *order;
    size_t n;
    int *told;
    int twice;
} tellings;

static void on_done(void *ctx, size_t i)
{
    tellings *t = ctx;
    if (t->told[i]++)
        t->twice++;
    t->order[t->n++] = i;
}

typedef struct {
    ob_job *jobs;
    ob_span_log *spans;
    tellings told;
    ob_engine_stats st;
    int rc;
} outcome;

/* A batch backend that measures on the CPU, synchronous or asynchronous
 * (two slots; every `fail_every`-th submission or wait fails, and the driver
 * must then measure on the CPU itself). */
enum { BK_NONE = 0, BK_SYNC, BK_ASYNC, BK_ASYNC_FAILING };
typedef struct {
    ob_measure_rec *recs[2];
    int n[2], samples[2];
    long calls;
    int fail_every;
} fake_backend;

static int fake_batch(void *ctx, const ob_measure_rec *recs, int n, int samples, ob_errval *out)
{
    (void)ctx;
    for (int i = 0; i < n; i++)
        if (ob_measure_until(recs[i].metric, recs[i].base, recs[i].approx, recs[i].d, samples, recs[i].stop,
                             &out[i]))
            out[i].err = NAN;
    return 0;
}

static int fake_submit(void *ctx, int slot, const ob_measure_rec *recs, int n, int samples)
{
    fake_backend *f = ctx;
    if (f->fail_every && ++f->calls % f->fail_every == 0)
        return -1;
    free(f->recs[slot]);
    f->recs[slot] = malloc((size_t)n * sizeof *recs);
    memcpy(f->recs[slot], recs, (size_t)n * sizeof *recs);
    f->n[slot] = n;
    f->samples[slot] = samples;
    return 0;
}

static int fake_wait(void *ctx, int slot, ob_errval *out, double *device_ns)
{
    fake_backend *f = ctx;
    *device_ns = 1e3 * f->n[slot];
    if (f->fail_every && ++f->calls % f->fail_every == 0)
        return -1;
    return fake_batch(ctx, f->recs[slot], f->n[slot], f->samples[slot], out);
}

static outcome run_with(const jobset *s, ob_engine e, int threads, int chunk, int backend)
{
    outcome r;
    memset(&r, 0, sizeof r);
    r.jobs = malloc(s->n * sizeof *r.jobs);
    memcpy(r.jobs, s->jobs, s->n * sizeof *r.jobs);
    r.spans = calloc(s->n, sizeof *r.spans);
    r.told.order = malloc(s->n * sizeof *r.told.order);
    r.told.told = calloc(s->n, sizeof *r.told.told);
    ob_driver_opts o;
    ob_driver_defaults(&o);
    o.samples = 32;
    o.engine = e;
    o.chunk = chunk;
    ob_driver_hooks h;
    memset(&h, 0, sizeof h);
    h.spans = r.spans;
    h.job_done = on_done;
    h.job_done_ctx = &r.told;
    h.stats = &r.st;
    fake_backend fb = {{NULL, NULL}, {0, 0}, {0, 0}, 0, backend == BK_ASYNC_FAILING ? 3 : 0};
    if (backend != BK_NONE) {
        h.batch = fake_batch;
        h.batch_ctx = &fb;
    }
    if (backend == BK_ASYNC || backend == BK_ASYNC_FAILING) {
        h.batch_submit = fake_submit;
        h.batch_wait = fake_wait;
    }
    omp_set_num_threads(threads);
    r.rc = ob_driver_run(r.jobs, s->n, &o, &h);
    free(fb.recs[0]);
    free(fb.recs[1]);
    return r;
}

static outcome run(const jobset *s, ob_engine e, int threads, int chunk) { return run_with(s, e, threads, chunk, BK_NONE); }

static void outcome_free(outcome *r, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(r->spans[i].v);
    free(r->spans);
    free(r->jobs);
    free(r->told.order);
    free(r->told.told);
}

static void check_same(const jobset *s, const outcome *ref, const outcome *got, const char *what)
{
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < s->n; i++)
        if (!same_job(&ref->jobs[i], &got->jobs[i]) || !same_spans(&ref->spans[i], &got->spans[i]))
            if (bad++ == 0)
                first = i;
    CHECK(got->rc == 0 && bad == 0, "%s: %zu of %zu jobs differ from the level engine at 1 thread (first: "
          "%s d=%g %s %s tol %g: %s %ld %.17g vs %s %ld %.17g)", what, bad, s->n, s->jobs[first].curve->id,
          s->jobs[first].d, s->jobs[first].method->name, ob_split_name(s->jobs[first].split),
          s->jobs[first].tol, ob_status_name(ref->jobs[first].status), ref->jobs[first].ctrl_points,
          ref->jobs[first].max_err, ob_status_name(got->jobs[first].status), got->jobs[first].ctrl_points,
          got->jobs[first].max_err);
    CHECK(got->told.n == s->n && got->told.twice == 0, "%s: %zu of %zu jobs told, %d twice", what, got->told.n,
          s->n, got->told.twice);
}

static void test_equivalence(const jobset *s)
{
    outcome ref = run(s, OB_ENGINE_LEVEL, 1, 512);
    CHECK(ref.st.engine == OB_ENGINE_LEVEL && ref.st.groups > 0 && ref.st.work_ns > 0,
          "the level engine says what it did (%ld groups, %.3g s of work)", ref.st.groups, ref.st.work_ns * 1e-9);
    outcome group1 = run(s, OB_ENGINE_GROUP, 1, 512);
    check_same(s, &ref, &group1, "engine group, 1 thread, chunk 512");
    const struct {
        ob_engine e;
        int threads, chunk, backend;
        ob_engine ran;
    } cfg[] = {{OB_ENGINE_LEVEL, 2, 512, BK_NONE, OB_ENGINE_LEVEL},
               {OB_ENGINE_LEVEL, 7, 512, BK_NONE, OB_ENGINE_LEVEL},
               {OB_ENGINE_LEVEL, 2, 3, BK_NONE, OB_ENGINE_LEVEL},
               {OB_ENGINE_GROUP, 2, 512, BK_NONE, OB_ENGINE_GROUP},
               {OB_ENGINE_GROUP, 7, 512, BK_NONE, OB_ENGINE_GROUP},
               {OB_ENGINE_GROUP, 2, 1, BK_NONE, OB_ENGINE_GROUP},
               {OB_ENGINE_GROUP, 7, 5, BK_NONE, OB_ENGINE_GROUP},
               {OB_ENGINE_AUTO, 2, 512, BK_NONE, OB_ENGINE_GROUP},
               {OB_ENGINE_AUTO, 2, 512, BK_SYNC, OB_ENGINE_LEVEL},
               {OB_ENGINE_GROUP, 2, 512, BK_SYNC, OB_ENGINE_GROUP},
               {OB_ENGINE_DEVICE, 2, 512, BK_SYNC, OB_ENGINE_LEVEL},
               {OB_ENGINE_DEVICE, 2, 512, BK_ASYNC, OB_ENGINE_DEVICE},
               {OB_ENGINE_DEVICE, 7, 5, BK_ASYNC, OB_ENGINE_DEVICE},
               {OB_ENGINE_DEVICE, 1, 64, BK_ASYNC_FAILING, OB_ENGINE_DEVICE}};
    for (size_t k = 0; k < sizeof cfg / sizeof cfg[0]; k++) {
        char what[128];
        static const char *const bk[] = {"none", "sync", "async", "async, failing"};
        snprintf(what, sizeof what, "engine %s, %d threads, chunk %d, backend %s", ob_engine_name(cfg[k].e),
                 cfg[k].threads, cfg[k].chunk, bk[cfg[k].backend]);
        outcome got = run_with(s, cfg[k].e, cfg[k].threads, cfg[k].chunk, cfg[k].backend);
        check_same(s, &ref, &got, what);
        const ob_engine ran = cfg[k].ran;
        if (cfg[k].backend != BK_NONE)
            CHECK(got.st.launches > 0 && got.st.records > 0, "%s: %ld launches, %ld records", what,
                  got.st.launches, got.st.records);
        CHECK(got.st.engine == ran && got.st.threads == cfg[k].threads, "%s: ran %s on %d threads", what,
              ob_engine_name(got.st.engine), got.st.threads);
        if (ran == OB_ENGINE_GROUP)
            CHECK(got.told.n == group1.told.n &&
                      memcmp(got.told.order, group1.told.order, got.told.n * sizeof *got.told.order) == 0,
                  "%s: jobs told in the same order as at 1 thread", what);
        outcome_free(&got, s->n);
    }
    /* the group engine tells a group's jobs together, groups by predicted
     * cost: not the level engine's order, but every job once */
    CHECK(group1.told.n == s->n, "group engine: every job told (%zu of %zu)", group1.told.n, s->n);
    outcome_free(&group1, s->n);
    outcome_free(&ref, s->n);
}

/* A stop after a few jobs: the run returns 1, the jobs it told are final
 * and equal to the full run's, the others are "interrupted". */
static const volatile sig_atomic_t *stop_flag;
static volatile sig_atomic_t stop_now;
static size_t stop_after, stop_seen;

static void stop_on_done(void *ctx, size_t i)
{
    on_done(ctx, i);
    if (++stop_seen >= stop_after)
        stop_now = 1;
}

static void test_stop(const jobset *s, ob_engine e)
{
    outcome ref = run(s, OB_ENGINE_LEVEL, 2, 512);
    outcome r;
    memset(&r, 0, sizeof r);
    r.jobs = malloc(s->n * sizeof *r.jobs);
    memcpy(r.jobs, s->jobs, s->n * sizeof *r.jobs);
    r.told.order = malloc(s->n * sizeof *r.told.order);
    r.told.told = calloc(s->n, sizeof *r.told.told);
    r.spans = calloc(s->n, sizeof *r.spans);
    ob_driver_opts o;
    ob_driver_defaults(&o);
    o.samples = 32;
    o.engine = e;
    ob_driver_hooks h;
    memset(&h, 0, sizeof h);
    stop_now = 0;
    stop_seen = 0;
    stop_after = s->n / 4;
    stop_flag = &stop_now;
    h.stop = stop_flag;
    h.job_done = stop_on_done;
    h.job_done_ctx = &r.told;
    omp_set_num_threads(2);
    const int rc = ob_driver_run(r.jobs, s->n, &o, &h);
    size_t bad = 0, interrupted = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (r.told.told[i])
            bad += !same_job(&r.jobs[i], &ref.jobs[i]);
        else
            interrupted += r.jobs[i].status == OB_FAIL && strcmp(r.jobs[i].message, "interrupted") == 0;
    }
    CHECK(rc == 1 && r.told.n >= stop_after && r.told.n < s->n,
          "engine %s stopped after %zu jobs: rc %d, %zu told of %zu", ob_engine_name(e), stop_after, rc, r.told.n,
          s->n);
    CHECK(bad == 0 && interrupted == s->n - r.told.n,
          "engine %s stopped: %zu told jobs differ from the full run, %zu of %zu others interrupted",
          ob_engine_name(e), bad, interrupted, s->n - r.told.n);
    outcome_free(&r, s->n);
    outcome_free(&ref, s->n);
}

/* The model: a list schedule, grain tasks at a time to the earliest free
 * thread, phases one after the other with their serial time. */
static void test_model(void)
{
    double task[] = {3, 3, 2, 2, 2, 5, 1, 1};
    ob_trace_phase ph[2] = {{0, 5, 1, 1.0, -1}, {5, 3, 2, 0.5, -1}};
    ob_trace t = {task, 8, 8, ph, 2, 2, 0, 0};
    /* phase 1 on 2 threads: 3 | 3, then 2 -> 5, 2 -> 5, 2 -> 7: 7, +1 serial;
     * phase 2, grain 2: {5, 1} = 6 | {1} = 1: 6, +0.5 serial */
    CHECK(ob_trace_makespan(&t, 2) == 14.5, "2 threads: %g (14.5 wanted)", ob_trace_makespan(&t, 2));
    CHECK(ob_trace_makespan(&t, 1) == 20.5, "1 thread: the sum, %g (20.5 wanted)", ob_trace_makespan(&t, 1));
    /* phase 1 on 64: the longest task, 3; phase 2: 6 */
    CHECK(ob_trace_makespan(&t, 64) == 10.5, "64 threads: %g (10.5 wanted)", ob_trace_makespan(&t, 64));
    /* the group engine: group 0 one chunk of four tasks of 4, group 1 one
     * task of 1; on 2 threads the second thread finishes group 1 at 1 and
     * helps with group 0: 17 of work end at 9 (16 without the help) */
    double gtask[] = {4, 4, 4, 4, 1};
    ob_trace_phase gph[3] = {{0, 0, 1, 0.0, -1}, {0, 4, 1, 0.0, 0}, {4, 1, 1, 0.0, 1}};
    ob_trace g = {gtask, 5, 5, gph, 3, 3, 0, 0};
    CHECK(ob_trace_makespan(&g, 2) == 9.0, "group engine, 2 threads: %g (9 wanted)", ob_trace_makespan(&g, 2));
    CHECK(ob_trace_makespan(&g, 1) == 17.0, "group engine, 1 thread: %g (17 wanted)", ob_trace_makespan(&g, 1));
    CHECK(ob_trace_makespan(&g, 8) == 4.0, "group engine, 8 threads: %g (4 wanted)", ob_trace_makespan(&g, 8));
    /* a group's next chunk waits for its previous one: chunks of 3 and 3
     * on 4 threads take 6, whatever the helpers */
    double ctask[] = {3, 3};
    ob_trace_phase cph[2] = {{0, 1, 1, 0.0, 0}, {1, 1, 1, 0.0, 0}};
    ob_trace c2 = {ctask, 2, 2, cph, 2, 2, 0, 0};
    CHECK(ob_trace_makespan(&c2, 4) == 6.0, "chained chunks: %g (6 wanted)", ob_trace_makespan(&c2, 4));
}

/* The traces of a real run: each engine's model at its own thread count is
 * at most the work it traced and at least the work over the threads. */
static void test_traces(const jobset *s)
{
    for (int e = OB_ENGINE_LEVEL; e <= OB_ENGINE_GROUP; e++) {
        ob_job *jobs = malloc(s->n * sizeof *jobs);
        memcpy(jobs, s->jobs, s->n * sizeof *jobs);
        ob_driver_opts o;
        ob_driver_defaults(&o);
        o.samples = 32;
        o.engine = (ob_engine)e;
        ob_trace tr;
        memset(&tr, 0, sizeof tr);
        ob_driver_hooks h;
        memset(&h, 0, sizeof h);
        h.trace = &tr;
        omp_set_num_threads(2);
        ob_driver_run(jobs, s->n, &o, &h);
        double sum = 0.0;
        for (size_t k = 0; k < tr.ntask; k++)
            sum += tr.task[k];
        const double m1 = ob_trace_makespan(&tr, 1), m16 = ob_trace_makespan(&tr, 16);
        CHECK(!tr.oom && tr.nphase >= 2 && sum >= 0.9 * tr.work_ns && m1 >= sum && m16 <= m1 && m16 >= sum / 16,
              "engine %s: trace of %zu tasks in %zu phases, %.3g s of tasks for %.3g s of work, model 1 thread "
              "%.3g s, 16 threads %.3g s", ob_engine_name((ob_engine)e), tr.ntask, tr.nphase, sum * 1e-9,
              tr.work_ns * 1e-9, m1 * 1e-9, m16 * 1e-9);
        ob_trace_free(&tr);
        free(jobs);
    }
}

int main(void)
{
    test_model();
    jobset s = make_jobs();
    CHECK(s.n > 300, "%zu jobs", s.n);
    test_equivalence(&s);
    test_stop(&s, OB_ENGINE_LEVEL);
    test_stop(&s, OB_ENGINE_GROUP);
    test_traces(&s);
    free_jobs(&s);
    return check_done();
}
