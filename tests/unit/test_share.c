/*
 * test_share.c - jobs that differ only in their tolerance share the fits and
 * measurements of their common pieces (driver.c, "shared pieces"): every
 * job's results are exactly those it gets alone, and the shared run fits
 * fewer pieces than the jobs alone do.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/driver/driver.h"
#include "tests/check.h"
#include "tests/driver_fixture.h"

static const double tols[5] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5};

/* tiller's fit, counting its calls (a test method may keep state) */
static long fit_calls;
static ob_fit_status counting_fit(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *out, char *msg, size_t len)
{
#pragma omp atomic
    fit_calls++;
    return ob_method_find("tiller")->fit(b, a, w, out, msg, len);
}

static void setup(ob_job *j, const ob_curve *c, const ob_method *m, ob_split sp, double tol)
{
    fixture_job(j, c, m, OB_METRIC_HAUSDORFF, sp, tol);
}

static int same_result(const ob_job *a, const ob_job *b)
{
    return a->status == b->status && a->ctrl_points == b->ctrl_points && a->segments == b->segments &&
           a->out_degree == b->out_degree && memcmp(&a->max_err, &b->max_err, sizeof a->max_err) == 0 &&
           strcmp(a->message, b->message) == 0 && a->open_joints == b->open_joints;
}

static void check_split(const ob_curve *c, const ob_method *m, ob_split sp, int expect_sharing)
{
    ob_driver_opts o;
    ob_driver_defaults(&o);
    o.samples = 64;
    ob_job together[5], alone[5];
    fit_calls = 0;
    for (int k = 0; k < 5; k++)
        setup(&together[k], c, m, sp, tols[k]);
    CHECK(ob_driver_run(together, 5, &o, NULL) == 0, "shared run");
    const long shared_calls = fit_calls;
    fit_calls = 0;
    for (int k = 0; k < 5; k++) {
        setup(&alone[k], c, m, sp, tols[k]);
        CHECK(ob_driver_run(&alone[k], 1, &o, NULL) == 0, "job alone");
    }
    const long alone_calls = fit_calls;
    for (int k = 0; k < 5; k++)
        CHECK(same_result(&together[k], &alone[k]), "%s %s tol %g: shared %s/%ld/%.17g vs alone %s/%ld/%.17g",
              m->name, ob_split_name(sp), tols[k], ob_status_name(together[k].status), together[k].ctrl_points,
              together[k].max_err, ob_status_name(alone[k].status), alone[k].ctrl_points, alone[k].max_err);
    if (expect_sharing)
        CHECK(shared_calls < alone_calls, "%s %s: %ld fits shared, %ld alone", m->name, ob_split_name(sp),
              shared_calls, alone_calls);
    else
        CHECK(shared_calls == alone_calls, "%s %s: a fit that reads tol is never shared (%ld vs %ld)", m->name,
              ob_split_name(sp), shared_calls, alone_calls);
}

static int uses_tol(const double *par) { (void)par; return 1; }

int main(void)
{
    ob_curve c = fixture_curve("ex1", 3, fixture_liu_ex1, 1.0);
    ob_method counting = *ob_method_find("tiller");
    counting.name = "counting-tiller";
    counting.fit = counting_fit;
    ob_method reads_tol = counting;
    reads_tol.fit_uses_tol = uses_tol;
    for (int sp = 0; sp < OB_SPLIT_COUNT; sp++) {
        check_split(&c, &counting, (ob_split)sp, 1);
        check_split(&c, &reads_tol, (ob_split)sp, 0);
    }
    /* every registered method that shares, mid split: the same results
     * shared or alone (one that reads tol is never shared: the counting
     * method above checks that path; skipping them keeps SISL's server
     * processes out of this program) */
    for (int i = 0; ob_methods[i]; i++) {
        if (ob_method_fit_uses_tol(ob_methods[i], NULL))
            continue;
        ob_driver_opts o;
        ob_driver_defaults(&o);
        o.samples = 32;
        o.max_segments = 400;
        ob_job together[3], alone[3];
        for (int k = 0; k < 3; k++) {
            setup(&together[k], &c, ob_methods[i], OB_SPLIT_MID, tols[k]);
            setup(&alone[k], &c, ob_methods[i], OB_SPLIT_MID, tols[k]);
        }
        ob_driver_run(together, 3, &o, NULL);
        for (int k = 0; k < 3; k++) {
            ob_driver_run(&alone[k], 1, &o, NULL);
            CHECK(same_result(&together[k], &alone[k]), "%s tol %g: shared and alone differ", ob_methods[i]->name,
                  tols[k]);
        }
    }
    ob_curve_free(&c);
    return check_done();
}
