/*
 * test_cert_progress.c - the certificate pass's progress (cert_progress.h):
 * its cost model (pieces x a per-status figure, calibrated per method and
 * status on the jobs certified so far), the ETA's arithmetic on synthetic
 * passes (no timed assertion: the machines are shared), and its line.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/run/cert_progress.h"
#include "host/run/progress.h"
#include "methods/driver/driver.h"
#include "tests/check.h"

static ob_job job(const char *method, ob_status st, int segments)
{
    ob_job j;
    memset(&j, 0, sizeof j);
    j.method = ob_method_find(method);
    j.status = st;
    j.segments = segments;
    return j;
}

/* The estimate of p at wall time `now` (s since the pass began). */
static ob_progress_est estimate(const ob_cert_progress *p, double now)
{
    ob_work_group *g = malloc((p->n ? p->n : 1) * sizeof *g);
    ob_cert_progress_groups(p, now, g);
    const ob_progress_in in = {g, p->n, p->threads, 1, now, 0, 0, 0};
    ob_progress_est e;
    memset(&e, 0, sizeof e);
    CHECK(ob_progress_estimate(&in, &e) == 0, "estimate");
    free(g);
    return e;
}

/* The model: pieces x ms per piece, limit jobs dearer; a kind per method
 * and status. */
static void test_cost(void)
{
    const ob_job a = job("tiller", OB_OK, 10), b = job("tiller", OB_LIMIT, 10), c = job("ahn", OB_OK, 10);
    CHECK_NEAR(ob_cert_cost(&a), 10 * OB_CERT_MS_PER_PIECE, 1e-12, "ok: pieces x ms per piece");
    CHECK_NEAR(ob_cert_cost(&b), 10 * OB_CERT_MS_PER_PIECE_LIMIT, 1e-12, "limit: pieces x its ms per piece");
    CHECK(ob_cert_cost(&b) > 3 * ob_cert_cost(&a), "a limit job costs much more than an ok one");
    const ob_job z = job("tiller", OB_OK, 0);
    CHECK(ob_cert_cost(&z) > 0, "a job without pieces still costs something: %g", ob_cert_cost(&z));
    CHECK(ob_cert_kind(&a) != ob_cert_kind(&b) && ob_cert_kind(&a) != ob_cert_kind(&c) &&
              ob_cert_kind(&b) != ob_cert_kind(&c),
          "a kind per method and status: %d %d %d", ob_cert_kind(&a), ob_cert_kind(&b), ob_cert_kind(&c));
    CHECK(ob_cert_kind(&a) >= 0 && ob_cert_kind(&b) < OB_PROGRESS_MAX_KINDS, "kinds the estimator calibrates");
}

/* Four equal jobs on 2 threads, two certified at twice the model's time:
 * the other two are predicted at twice theirs too, side by side. */
static void test_calibrated(void)
{
    ob_cert_progress p;
    CHECK(ob_cert_progress_init(&p, 4, 2) == 0, "init");
    const ob_job j = job("tiller", OB_OK, 10);  /* 40 ms predicted */
    for (size_t k = 0; k < 4; k++)
        ob_cert_progress_set(&p, k, &j);
    ob_cert_progress_start(&p, 0, 0.0);
    ob_cert_progress_start(&p, 1, 0.0);
    ob_cert_progress_done(&p, 0, 80e6, 0.08);
    ob_cert_progress_done(&p, 1, 80e6, 0.08);
    CHECK(p.done == 2, "2 done: %zu", p.done);
    const ob_progress_est e = estimate(&p, 0.08);
    /* per kind: (160e6 + k0 0.05 x 160) / (80 + 8), k0 the run's: (160e6 +
     * 1e6 x 0.01 x 160) / (80 + 1.6): 1.998e6 ns per ms; 2 x 40 ms left on 2
     * threads at thread time = wall time */
    const double k0 = (160e6 + 1e6 * 1.6) / 81.6, k = (160e6 + k0 * 8) / 88;
    CHECK_NEAR(e.left_ns, 80 * k, 1.0, "the work left, calibrated");
    CHECK_NEAR(e.eta_s, 40 * k * 1e-9, 1e-9, "the ETA: one job per thread");
    CHECK_NEAR(e.fraction, 160e6 / (160e6 + 80 * k), 1e-12, "the work done");
    /* on one thread, twice as long */
    ob_cert_progress one = p;
    one.threads = 1;
    CHECK_NEAR(estimate(&one, 0.08).eta_s, 80 * k * 1e-9, 1e-9, "one thread: the two one after the other");
    ob_cert_progress_end(&p);
}

/* ok and limit jobs are calibrated apart: the ok jobs at the model, the
 * limit ones at 3 x it; a pending limit job is predicted at 3 x. */
static void test_status_apart(void)
{
    ob_cert_progress p;
    CHECK(ob_cert_progress_init(&p, 5, 1) == 0, "init");
    const ob_job ok = job("tiller", OB_OK, 10), lim = job("tiller", OB_LIMIT, 10);
    const double cok = ob_cert_cost(&ok), clim = ob_cert_cost(&lim);
    ob_cert_progress_set(&p, 0, &lim);
    ob_cert_progress_set(&p, 1, &lim);
    ob_cert_progress_set(&p, 2, &ok);
    ob_cert_progress_set(&p, 3, &ok);
    ob_cert_progress_set(&p, 4, &lim);
    double t = 0.0;
    const double ns[4] = {3e6 * clim, 3e6 * clim, 1e6 * cok, 1e6 * cok};
    for (size_t k = 0; k < 4; k++) {
        ob_cert_progress_start(&p, k, t);
        t += 1e-9 * ns[k];
        ob_cert_progress_done(&p, k, ns[k], t);
    }
    const ob_progress_est e = estimate(&p, t);
    /* the limit kind's ratio, shrunk a little toward the run's */
    const double cost = 3 * clim + 2 * cok, done_ns = 6e6 * clim + 2e6 * cok, done_c = 2 * clim + 2 * cok;
    const double k0 = (done_ns + 1e6 * 0.01 * cost) / (done_c + 0.01 * cost);
    const double c0 = 0.05 * 3 * clim, kl = (6e6 * clim + k0 * c0) / (2 * clim + c0);
    CHECK_NEAR(e.left_ns, kl * clim, 1.0, "the pending limit job at its kind's ratio");
    CHECK(e.left_ns > 2.8e6 * clim && e.left_ns < 3.0e6 * clim, "about 3 x the model: %g", e.left_ns / (1e6 * clim));
    CHECK_NEAR(e.eta_s, 1e-9 * kl * clim, 1e-9, "ETA: that job on the one thread");
    ob_cert_progress_end(&p);
}

/* A running job counts what it has run (its wall time at the speed of the
 * jobs done): the ETA is what is left of it, then the pending ones. */
static void test_running(void)
{
    ob_cert_progress p;
    CHECK(ob_cert_progress_init(&p, 3, 1) == 0, "init");
    const ob_job j = job("tiller", OB_OK, 25);  /* 100 ms predicted */
    for (size_t k = 0; k < 3; k++)
        ob_cert_progress_set(&p, k, &j);
    /* the first at half speed (a shared machine): 100 ms of thread time in 0.2 s */
    ob_cert_progress_start(&p, 0, 0.0);
    ob_cert_progress_done(&p, 0, 100e6, 0.2);
    ob_cert_progress_start(&p, 1, 0.2);
    ob_work_group g[3];
    ob_cert_progress_groups(&p, 0.3, g);
    CHECK(g[0].state == OB_WORK_DONE && g[1].state == OB_WORK_RUNNING && g[2].state == OB_WORK_PENDING, "states");
    CHECK_NEAR(g[1].wall_ns, 0.1e9, 1e-3, "the running job's wall time");
    CHECK_NEAR(g[1].spent_ns, 0.05e9, 1e-3, "its thread time: at the speed of the jobs done");
    CHECK_NEAR(g[0].spent_ns, 100e6, 1e-9, "a job done: its cert_ns");
    const ob_progress_est e = estimate(&p, 0.3);
    /* at the model (1e6 ns per ms): 50 ms left of the running one, 100 of
     * the pending one, at half speed: 0.3 s */
    CHECK_NEAR(e.left_ns, 150e6, 1.0, "left: the running job's rest and the pending one");
    CHECK_NEAR(e.eta_s, 0.3, 1e-9, "the ETA at the measured speed");
    ob_cert_progress_end(&p);
}

/* Nothing certified yet: no ETA. */
static void test_nothing_yet(void)
{
    ob_cert_progress p;
    CHECK(ob_cert_progress_init(&p, 2, 2) == 0, "init");
    const ob_job j = job("tiller", OB_OK, 3);
    ob_cert_progress_set(&p, 0, &j);
    ob_cert_progress_set(&p, 1, &j);
    CHECK(estimate(&p, 1.0).eta_s < 0, "no rate yet");
    ob_cert_progress_end(&p);
    CHECK(ob_cert_progress_init(&p, 0, 2) == 0, "init with no job");
    CHECK(estimate(&p, 1.0).eta_s < 0, "no jobs");
    ob_cert_progress_end(&p);
}

static void test_format(void)
{
    char buf[160];
    ob_progress_est e = {0, 0, 0.3, 30.4};
    ob_progress_format_pass(buf, sizeof buf, "certified", 199, 5584, &e, 871.2, 0);
    CHECK(strcmp(buf, "certified 199/5584 jobs, 871 s elapsed, ETA 30 s") == 0, "the log line: %s", buf);
    ob_progress_format_pass(buf, sizeof buf, "certified", 199, 5584, &e, 871.2, 1);
    CHECK(strcmp(buf, "certified 199/5584 jobs, 871 s, ETA 30 s") == 0, "the bar's: %s", buf);
    e.eta_s = -1;
    ob_progress_format_pass(buf, sizeof buf, "certified", 0, 3, &e, 2, 0);
    CHECK(strcmp(buf, "certified 0/3 jobs, 2 s elapsed, ETA ?") == 0, "no ETA yet: %s", buf);
}

int main(void)
{
    test_cost();
    test_calibrated();
    test_status_apart();
    test_running();
    test_nothing_yet();
    test_format();
    return check_done();
}
