/*
 * test_progress.c - the progress display tells the truth (progress.h): the
 * estimator, a pure function, on synthetic runs (no timed assertion: the
 * machines are shared): the work done and to come, the ETA from the cost
 * model calibrated by the groups finished, the tail (a big group running
 * alone), a resume (no job finished yet, the largest group first), a group
 * past its prediction; the line's text; and the driver's side: what every
 * engine tells the callback adds up to the work it measured.
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/random.h"
#include "host/run/progress.h"
#include "methods/driver/driver.h"
#include "tests/check.h"

/* The model's unit: 1 ms of predicted cost is 1e6 ns of thread time. */
enum { MS = 1000000 };

static ob_work_group done_g(double cost, double spent, double wall)
{
    return (ob_work_group){cost, spent, wall, OB_WORK_DONE, -1};
}

static ob_work_group running_g(double cost, double spent, double wall)
{
    return (ob_work_group){cost, spent, wall, OB_WORK_RUNNING, -1};
}

static ob_work_group pending_g(double cost) { return (ob_work_group){cost, 0.0, 0.0, OB_WORK_PENDING, -1}; }

static ob_progress_est estimate(const ob_work_group *g, size_t n, int threads, int whole, double elapsed)
{
    const ob_progress_in in = {g, n, threads, whole, elapsed, 0, 0, 0};
    ob_progress_est e;
    memset(&e, 0, sizeof e);
    CHECK(ob_progress_estimate(&in, &e) == 0, "estimate");
    return e;
}

/* Nothing measured yet: no rate, so no ETA; nothing done. */
static void test_nothing_yet(void)
{
    ob_work_group g[3] = {pending_g(5), pending_g(2), pending_g(1)};
    ob_progress_est e = estimate(g, 3, 2, 1, 3.0);
    CHECK(e.eta_s < 0, "no rate yet: ETA ? (got %g)", e.eta_s);
    CHECK(e.fraction == 0.0 && e.done_ns == 0.0, "nothing done: %g %g", e.fraction, e.done_ns);
    CHECK_NEAR(e.left_ns, 8.0 * MS, 1.0, "all the predicted work to come");
    e = estimate(NULL, 0, 2, 1, 0.0);
    CHECK(e.fraction == 0.0 && e.eta_s < 0, "no groups: %g %g", e.fraction, e.eta_s);
}

/* The bulk, the model exact: half the equal groups done on 2 threads. */
static void test_bulk(void)
{
    ob_work_group g[100];
    for (int i = 0; i < 100; i++)
        g[i] = i < 50 ? done_g(1, 1.0 * MS, 1.0 * MS) : pending_g(1);
    ob_progress_est e = estimate(g, 100, 2, 1, 0.025);
    CHECK_NEAR(e.fraction, 0.5, 1e-12, "half the work");
    CHECK_NEAR(e.done_ns, 50.0 * MS, 1e-3, "work done");
    CHECK_NEAR(e.left_ns, 50.0 * MS, 1e-3, "work to come");
    CHECK_NEAR(e.eta_s, 0.025, 1e-9, "the other half at the same speed on 2 threads");
}

/* The long tail: every small group done, the big one (scheduled
 * first) running alone on one of 8 threads, 65 % of it to go.  The share of
 * the cost done says the run is 80 % through and 0.35 s in: 0.09 s left;
 * the truth is 0.65 s, the big group's rest on its one thread. */
static void test_long_tail(void)
{
    enum { N = 4001 };
    ob_work_group *g = malloc(N * sizeof *g);
    g[0] = running_g(1000, 350.0 * MS, 350.0 * MS);
    for (int i = 1; i < N; i++)
        g[i] = done_g(1, 1.0 * MS, 1.0 * MS);
    ob_progress_est e = estimate(g, N, 8, 1, 0.35);
    CHECK_NEAR(e.eta_s, 0.65, 1e-9, "the big group's rest on one thread");
    CHECK_NEAR(e.fraction, 4350.0 / 5000.0, 1e-12, "the work done");
    /* the same with two threads and a few small groups still pending: they
     * run beside the big one and change nothing */
    g[N - 1] = g[N - 2] = pending_g(1);
    e = estimate(g, N, 2, 1, 0.35);
    CHECK_NEAR(e.eta_s, 0.65, 1e-9, "small groups beside the tail");
    free(g);
}

/* A group past its predicted cost still needs time: never "ETA 0 s" while
 * it runs, and the longer it runs the longer the ETA.  Just past its
 * prediction, a share of what it used again; far past, as much again. */
static void test_overrun(void)
{
    ob_work_group g[3] = {running_g(10, 12.0 * MS, 12.0 * MS), done_g(5, 5.0 * MS, 5.0 * MS),
                          done_g(5, 5.0 * MS, 5.0 * MS)};
    ob_progress_est e = estimate(g, 3, 2, 1, 0.022);
    CHECK(e.eta_s > 0, "running past its prediction: ETA > 0 (got %g)", e.eta_s);
    CHECK_NEAR(e.eta_s, OB_PROGRESS_OVERRUN * 1.2 * 0.012, 1e-9, "1.2 times over: a share of it again");
    CHECK(e.fraction < 1.0, "not done: %g", e.fraction);
    g[0].spent_ns = g[0].wall_ns = 40.0 * MS;
    const ob_progress_est e2 = estimate(g, 3, 2, 1, 0.05);
    CHECK(e2.eta_s > e.eta_s, "ETA grows as it overruns: %g > %g", e2.eta_s, e.eta_s);
    CHECK_NEAR(e2.eta_s, 0.04, 1e-9, "4 times over: as much again");
    g[0].spent_ns = g[0].wall_ns = 400.0 * MS;
    const ob_progress_est e3 = estimate(g, 3, 2, 1, 0.41);
    CHECK_NEAR(e3.eta_s, 0.4, 1e-9, "40 times over: as much again, not more");
}

/* A resume: the interrupted run's largest group (scheduled first) runs; no
 * job has finished, nothing is calibrated.  The old display said "0 %, ETA
 * ?" for as long as that group ran; the work done and an ETA are known
 * from the first measured chunk (the model's own unit, the speed measured:
 * 0.5 on a shared machine). */
static void test_resume(void)
{
    ob_work_group g[11];
    g[0] = running_g(300, 10.0 * MS, 20.0 * MS);
    for (int i = 1; i < 11; i++)
        g[i] = pending_g(1);
    ob_progress_est e = estimate(g, 11, 2, 1, 0.02);
    CHECK(e.eta_s >= 0, "an ETA while the first group runs (got %g)", e.eta_s);
    CHECK_NEAR(e.eta_s, 0.58, 1e-9, "the big group's rest at half speed");
    CHECK_NEAR(e.fraction, 10.0 / 310.0, 1e-12, "work done counted before any job finished");
}

/* The model's unit is calibrated by the groups finished: a machine 3 times
 * slower than the model's takes 3 times the predicted time. */
static void test_calibration(void)
{
    ob_work_group g[200];
    for (int i = 0; i < 200; i++)
        g[i] = i < 100 ? done_g(1, 3.0 * MS, 3.0 * MS) : pending_g(1);
    ob_progress_est e = estimate(g, 200, 1, 1, 0.3);
    /* the prior (1 ms = 1e6 ns) weighs OB_PROGRESS_PRIOR_SHARE of the run */
    const double c0 = OB_PROGRESS_PRIOR_SHARE * 200, k = (300.0 * MS + c0 * MS) / (100 + c0);
    CHECK_NEAR(e.left_ns, 100 * k, 1e-3, "work to come calibrated");
    CHECK_NEAR(e.eta_s, 100 * k * 1e-9, 1e-9, "ETA calibrated");
    CHECK(e.eta_s > 0.29 && e.eta_s < 0.3, "about 3x the model: %g", e.eta_s);
}

/* Pending groups on the earliest free thread in schedule order: [10, 9, 8]
 * on 2 threads take 17, not 27 / 2. */
static void test_list_schedule(void)
{
    ob_work_group g[4] = {pending_g(10), pending_g(9), pending_g(8), done_g(1, 1.0 * MS, 1.0 * MS)};
    ob_progress_est e = estimate(g, 4, 2, 1, 0.0005);
    CHECK_NEAR(e.eta_s, 0.017, 1e-9, "list schedule");
    e = estimate(g, 4, 3, 1, 0.0005);
    CHECK_NEAR(e.eta_s, 0.010, 1e-9, "one thread each: the largest");
}

/* Groups that ended before any work (a method not applicable) say nothing
 * about the model's unit. */
static void test_skipped(void)
{
    ob_work_group g[3] = {done_g(50, 0, 0), done_g(1, 1.0 * MS, 1.0 * MS), pending_g(1)};
    ob_progress_est e = estimate(g, 3, 1, 1, 0.001);
    CHECK_NEAR(e.eta_s, 0.001, 1e-9, "skipped groups not calibrated on");
}

/* The work done moves with the measured work, not with the jobs told. */
static void test_steady(void)
{
    ob_work_group g[3] = {running_g(100, 0, 0), done_g(10, 10.0 * MS, 10.0 * MS), pending_g(10)};
    double last = -1.0;
    int up = 1;
    for (int s = 1; s <= 80; s++) {  /* within its prediction (past it, the work to come grows) */
        g[0].spent_ns = g[0].wall_ns = s * (double)MS;
        const ob_progress_est e = estimate(g, 3, 2, 1, 0.01 + s * 1e-3);
        up &= e.fraction > last;
        last = e.fraction;
    }
    CHECK(up, "the work done rises chunk by chunk");
}

/* The level and device engines: every thread works on every group, so the
 * work to come at the run's rate of work. */
static void test_level_engine(void)
{
    ob_work_group g[4] = {running_g(20, 10.0 * MS, 0), running_g(20, 10.0 * MS, 0), done_g(10, 10.0 * MS, 0),
                          done_g(10, 10.0 * MS, 0)};
    ob_progress_est e = estimate(g, 4, 4, 0, 0.01);
    /* 40 ms done in 10 ms of wall; 20 + 20 ms to come (k = 1 ms exactly) */
    CHECK_NEAR(e.left_ns, 20.0 * MS, 1e-3, "work to come");
    CHECK_NEAR(e.eta_s, 0.005, 1e-9, "at the run's rate");
}

/* Each method calibrated on its own groups: one right, one 4 times over
 * its prediction, the finished groups mostly the first's, the pending ones
 * mostly the second's.  The run's single ratio would say 63 ms to come;
 * the truth is 205 ms. */
static void test_kinds(void)
{
    ob_work_group g[155];
    size_t n = 0;
    for (int i = 0; i < 95; i++)
        g[n++] = done_g(1, 1.0 * MS, 1.0 * MS);
    for (int i = 0; i < 5; i++)
        g[n++] = pending_g(1);
    for (int i = 0; i < 5; i++)
        g[n++] = done_g(1, 4.0 * MS, 4.0 * MS);
    for (int i = 0; i < 50; i++)
        g[n++] = pending_g(1);
    const ob_progress_est one = estimate(g, n, 1, 1, 0.115);
    for (size_t i = 0; i < n; i++)
        g[i].kind = i < 100 ? 0 : 1;
    const ob_progress_est e = estimate(g, n, 1, 1, 0.115);
    const double c0 = OB_PROGRESS_PRIOR_SHARE * 155, k = (115.0 * MS + c0 * MS) / (100 + c0);
    const double k0 = (95.0 * MS + OB_PROGRESS_KIND_PRIOR * 100 * k) / (95 + OB_PROGRESS_KIND_PRIOR * 100);
    const double k1 = (20.0 * MS + OB_PROGRESS_KIND_PRIOR * 55 * k) / (5 + OB_PROGRESS_KIND_PRIOR * 55);
    CHECK_NEAR(one.left_ns, 55 * k, 1e-3, "one ratio for the run");
    CHECK_NEAR(e.left_ns, 5 * k0 + 50 * k1, 1e-3, "a ratio per method");
    CHECK(e.left_ns > 2 * one.left_ns, "per method: %g ms to come (truth 205)", e.left_ns / MS);
    /* a kind that is not a method index: the run's ratio */
    for (size_t i = 0; i < n; i++)
        g[i].kind = OB_PROGRESS_MAX_KINDS + 7;
    const ob_progress_est big = estimate(g, n, 1, 1, 0.115);
    CHECK_NEAR(big.left_ns, one.left_ns, 1e-3, "an out-of-range kind");
}

/* The speed now, not the run's average: the machine got twice as slow in
 * the latest window, so the rest takes twice as long. */
static void test_window(void)
{
    ob_work_group g[100];
    for (int i = 0; i < 100; i++)
        g[i] = i < 50 ? done_g(1, 1.0 * MS, 1.0 * MS) : pending_g(1);
    ob_progress_in in = {g, 100, 1, 1, 0.05, 0, 0, 0};
    ob_progress_est e;
    CHECK(ob_progress_estimate(&in, &e) == 0, "estimate");
    CHECK_NEAR(e.eta_s, 0.05, 1e-9, "the run's speed");
    in.win_work_ns = 10.0 * MS;
    in.win_wall_ns = 20.0 * MS;
    in.win_s = 0.02;
    CHECK(ob_progress_estimate(&in, &e) == 0, "estimate");
    CHECK_NEAR(e.eta_s, 0.1, 1e-9, "the window's speed (groups)");
    in.whole_groups = 0;
    CHECK(ob_progress_estimate(&in, &e) == 0, "estimate");
    CHECK_NEAR(e.eta_s, 0.1, 1e-9, "the window's rate (level engine)");
    /* a window without work (one long fit) says nothing: the run's speed,
     * not "ETA ?" */
    in.win_work_ns = 0;
    for (int whole = 0; whole <= 1; whole++) {
        in.whole_groups = whole;
        CHECK(ob_progress_estimate(&in, &e) == 0, "estimate");
        CHECK_NEAR(e.eta_s, 0.05, 1e-9, "an empty window");
    }
}

static void test_format(void)
{
    char buf[128];
    ob_progress_est e = {40.0, 60.0, 0.4, 65.2};
    ob_progress_format(buf, sizeof buf, 12, 100, &e, 30.4, 0);
    CHECK(strcmp(buf, "12/100 jobs (12 %), work 40 %, 30 s elapsed, ETA 65 s") == 0, "log line: %s", buf);
    ob_progress_format(buf, sizeof buf, 12, 100, &e, 30.4, 1);
    CHECK(strcmp(buf, "12/100 jobs, work 40 %, 30 s, ETA 65 s") == 0, "bar: %s", buf);
    e.eta_s = -1.0;
    ob_progress_format(buf, sizeof buf, 0, 100, &e, 2.0, 0);
    CHECK(strstr(buf, "ETA ?") != NULL, "unknown: %s", buf);
    e.eta_s = 0.2;
    ob_progress_format(buf, sizeof buf, 0, 100, &e, 2.0, 1);
    CHECK(strstr(buf, "ETA 0 s") != NULL, "under a second: %s", buf);
    ob_progress_format(buf, 8, 12, 100, &e, 30.4, 0);
    CHECK(strlen(buf) == 7, "cut to the buffer: %s", buf);
}

/* --- the driver's side --- */

typedef struct {
    int calls;
    size_t ngroups;
    int sorted;         /* schedule order: cost never rises */
    int counts_ok;      /* done <= total, a group DONE has spent >= 0 */
    double last_spent;  /* the groups' spent summed, at the last call */
    int last_all_done;
    size_t last_done, last_total;
} seen;

static void record(void *ctx, const ob_progress_info *pi)
{
    seen *s = ctx;
    ob_work_group *g = malloc((pi->ngroups ? pi->ngroups : 1) * sizeof *g);
    pi->groups(pi, g);
    s->calls++;
    s->ngroups = pi->ngroups;
    s->counts_ok &= pi->done <= pi->total && pi->threads >= 1;
    double spent = 0.0;
    int all = 1;
    for (size_t k = 0; k < pi->ngroups; k++) {
        spent += g[k].spent_ns;
        all &= g[k].state == OB_WORK_DONE;
        s->counts_ok &= g[k].spent_ns >= 0 && g[k].cost > 0;
        if (k > 0)
            s->sorted &= g[k].cost <= g[k - 1].cost;
    }
    s->last_spent = spent;
    s->last_all_done = all;
    s->last_done = pi->done;
    s->last_total = pi->total;
    free(g);
}

/* Every engine tells the callback groups in schedule order whose spent time
 * adds up to the work it measured, all done at the end. */
static void test_driver_feed(void)
{
    ob_curve c[3];
    ob_job jobs[3 * 3 * 3];
    const char *names[3] = {"tiller", "cobb", "hoschek"};
    const double tols[3] = {1e-2, 1e-3, 1e-4};
    size_t n = 0;
    for (int k = 0; k < 3; k++) {
        CHECK(ob_random_curve(3, k, &c[k]) == 0, "curve");
        for (int m = 0; m < 3; m++)
            for (int t = 0; t < 3; t++) {
                ob_job *j = &jobs[n++];
                memset(j, 0, sizeof *j);
                j->curve = &c[k];
                j->d = c[k].d[0];
                j->method = ob_method_find(names[m]);
                j->metric = OB_METRIC_HAUSDORFF;
                j->split = OB_SPLIT_MID;
                j->tol = tols[t];
            }
    }
    const ob_engine engines[2] = {OB_ENGINE_GROUP, OB_ENGINE_LEVEL};
    for (int e = 0; e < 2; e++) {
        ob_driver_opts o;
        ob_driver_defaults(&o);
        o.engine = engines[e];
        o.chunk = 4;
        seen s = {0, 0, 1, 1, 0.0, 0, 0, 0};
        ob_engine_stats st;
        ob_driver_hooks h;
        memset(&h, 0, sizeof h);
        h.progress = record;
        h.progress_ctx = &s;
        h.stats = &st;
        omp_set_num_threads(2);
        CHECK(ob_driver_run(jobs, n, &o, &h) == 0, "run");
        CHECK(s.calls > 0 && s.ngroups > 0 && s.ngroups <= n, "%s: told (%d calls, %zu groups)",
              ob_engine_name(engines[e]), s.calls, s.ngroups);
        CHECK(s.sorted && s.counts_ok, "%s: schedule order, counts", ob_engine_name(engines[e]));
        CHECK(s.last_all_done && s.last_done == n && s.last_total == n, "%s: all done at the end",
              ob_engine_name(engines[e]));
        CHECK_NEAR(s.last_spent, st.work_ns, 1e-9 * st.work_ns, "the groups' time is the engine's work");
    }
    for (int k = 0; k < 3; k++)
        ob_curve_free(&c[k]);
}

int main(void)
{
    test_nothing_yet();
    test_bulk();
    test_long_tail();
    test_overrun();
    test_resume();
    test_calibration();
    test_list_schedule();
    test_skipped();
    test_steady();
    test_level_engine();
    test_kinds();
    test_window();
    test_format();
    test_driver_feed();
    return check_done();
}
