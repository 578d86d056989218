/*
 * test_timing.c - what the timing columns measure (README "Output": fit_ns is the
 * thread CPU time of the job's fits; eval_ns is the job's own measuring cost,
 * its share of a batch by the work it used when one launch measures many
 * jobs).  No assertion here depends on how fast or loaded the machine is:
 * a sleeping fit uses no CPU time whatever the load, and shares of one
 * launch are in the ratio of the work counts exactly.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "methods/driver/driver.h"
#include "tests/check.h"
#include "tests/driver_fixture.h"


static void sleep_ms(int ms)
{
    struct timespec ts = {0, ms * 1000000L};
    while (nanosleep(&ts, &ts) != 0)
        ;
}

/* A fit that waits 30 ms (as if blocked on I/O) and returns the base. */
static ob_fit_status sleepy_fit(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *out, char *msg, size_t len)
{
    (void)a, (void)w, (void)msg, (void)len;
    sleep_ms(30);
    ob_fit_single(out, b);
    return OB_FIT_OK;
}
static int same_degree(int n, int r, const double *par) { (void)r, (void)par; return n; }

static void setup(ob_job *j, ob_curve *c, const ob_method *m, double tol)
{
    fixture_job(j, c, m, OB_METRIC_HAUSDORFF, OB_SPLIT_MID, tol);
}

static void test_fit_is_cpu_time(ob_curve *c)
{
    const ob_method sleepy = {.name = "sleepy", .citation = "test", .continuity = "G0",
                              .caps = OB_CAP_POLY_OUT | OB_CAP_SAME_PARAM, .out_degree = same_degree,
                              .fit = sleepy_fit};
    ob_job j;
    setup(&j, c, &sleepy, 1e3); /* passes at once: one fit */
    ob_driver_opts o;
    ob_driver_defaults(&o);
    o.samples = 16;
    CHECK(ob_driver_run(&j, 1, &o, NULL) == 0 && j.status == OB_OK, "sleepy job runs: %s", ob_status_name(j.status));
    CHECK(j.fit_ns < 10e6, "a fit that sleeps 30 ms used %.3g ms of thread CPU time (wall time counted?)",
          j.fit_ns * 1e-6);
}

/* A stand-in for the OpenCL backend: measures on the CPU, then waits, so the
 * launch's wall time is far above the work; launch_ns adds up that wall time. */
static double launch_ns;
static int slow_batch(void *ctx, const ob_measure_rec *recs, int n, int samples, ob_errval *out)
{
    (void)ctx;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int i = 0; i < n; i++)
        ob_measure(recs[i].metric, recs[i].base, recs[i].approx, recs[i].d, samples, &out[i]);
    sleep_ms(20);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    launch_ns += (t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec);
    return 0;
}

static void test_batch_shares_by_work(ob_curve *c)
{
    /* tiller (cubic) and ahn (degree 6) on the whole curve at a tolerance
     * both pass at once: one batch of two records of unequal work */
    ob_job j[2];
    setup(&j[0], c, ob_method_find("tiller"), 1e3);
    setup(&j[1], c, ob_method_find("ahn"), 1e3);
    ob_driver_opts o;
    ob_driver_defaults(&o);
    const ob_driver_hooks h = {.batch = slow_batch};
    launch_ns = 0.0;
    CHECK(ob_driver_run(j, 2, &o, &h) == 0 && j[0].status == OB_OK && j[1].status == OB_OK, "two jobs run");
    CHECK(j[0].segments == 1 && j[1].segments == 1, "one piece each (%d, %d)", j[0].segments, j[1].segments);
    /* the work each record took, as the kernel would report it */
    ob_errval e[2];
    for (int k = 0; k < 2; k++) {
        ob_fit fit;
        char work[1 << 16], msg[160];
        double par[OB_MAX_PARAMS];
        ob_param_defaults(j[k].method, par);
        const ob_fit_args a = {1.0, 1e3, par};
        j[k].method->fit(&c->seg[0], &a, j[k].method->work_size <= sizeof work ? work : NULL, &fit, msg,
                         sizeof msg);
        ob_measure(OB_METRIC_HAUSDORFF, &c->seg[0], &fit.seg[0], 1.0, o.samples, &e[k]);
    }
    CHECK(e[0].work > 0 && e[1].work > 0 && e[0].work != e[1].work, "work counts %g, %g", e[0].work, e[1].work);
    const double want = e[1].work / e[0].work, got = j[1].eval_ns / j[0].eval_ns;
    CHECK(fabs(got / want - 1.0) < 1e-9, "eval_ns in the ratio of the work: %.6g, work ratio %.6g", got, want);
    /* the driver times the call around the backend's own interval */
    CHECK(j[0].eval_ns + j[1].eval_ns >= launch_ns && launch_ns >= 20e6,
          "the shares add up to the launch's wall time (%.6g + %.6g vs %.6g ns)", j[0].eval_ns, j[1].eval_ns,
          launch_ns);
}

int main(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    test_fit_is_cpu_time(&c);
    test_batch_shares_by_work(&c);
    ob_curve_free(&c);
    return check_done();
}
