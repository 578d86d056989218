/*
 * test_opencl.c - the OpenCL kernel against the CPU reference.
 *
 * A few hundred random records of every kind (base degrees 2..7, polynomial
 * and rational, approximations from every registered method, both signs of d,
 * the three sampled metrics) are measured by the kernel in one batch and by the
 * CPU path one by one: errors must agree to a relative 1e-9 (or 1e-15
 * absolute), and so must the parameters of the maxima where the errors do.
 * The same records under param must agree bit for bit.
 * Without an OpenCL platform every check here is skipped (and counted so).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/backend/clrt.h"
#include "methods/driver/driver.h"
#include "tests/check.h"
#include "tests/testlib.h"

enum { NREC = 600 };

static ob_bez base[NREC], approx[NREC];
static ob_measure_rec recs[NREC];

/* A random base segment: a control polygon turning gently (no wild loops),
 * rational with weights in [0.5, 2] for every third record. */
static void random_base(ob_bez *b, int deg, int rational)
{
    double p[2] = {urange(-1, 1), urange(-1, 1)}, ang = urange(0, 2 * OB_PI), turn = urange(-1.5, 1.5);
    memset(b, 0, sizeof *b);
    b->deg = deg;
    for (int k = 0; k <= deg; k++) {
        ob_bez_set(b, k, p[0], p[1], rational && k > 0 && k < deg ? urange(0.5, 2.0) : 1.0);
        double a = ang + turn * k / deg, len = urange(0.3, 1.0);
        p[0] += len * cos(a);
        p[1] += len * sin(a);
    }
}

static int build_records(void)
{
    int n = 0, guard = 0;
    const ob_metric mets[3] = {OB_METRIC_RADIAL, OB_METRIC_NORMAL, OB_METRIC_HAUSDORFF};
    while (n < NREC && guard++ < 20 * NREC) {
        /* choices from the attempt count, so a combination a method skips
         * (rational input to a polynomial method) is not drawn again forever */
        const ob_method *m = ob_methods[guard % ob_method_count()];
        int deg = 2 + (guard / 3) % 6, rational = (guard % 3) == 0;
        random_base(&base[n], deg, rational);
        double d = (n % 2 ? 1 : -1) * urange(0.02, 0.3);
        double par[OB_MAX_PARAMS];
        ob_param_defaults(m, par);
        const ob_fit_args a = {d, 1e-3, par};
        size_t ws = m->work_size ? m->work_size : 1;
        void *work = malloc(ws);
        ob_fit *fit = malloc(sizeof *fit);
        char msg[160];
        ob_fit_status st = work && fit ? m->fit(&base[n], &a, work, fit, msg, sizeof msg) : OB_FIT_FAIL;
        if (st == OB_FIT_OK && fit->n >= 1) {
            /* the first piece against its part of the base */
            ob_bez_subsegment(&base[n], fit->t[0], fit->t[1], &base[n]);
            approx[n] = fit->seg[0];
            recs[n] = (ob_measure_rec){&base[n], &approx[n], d, mets[n % 3]};
            n++;
        }
        free(work);
        free(fit);
    }
    return n;
}

int main(void)
{
    testlib_seed(0x5DEECE66DULL);
    ob_cl *cl = NULL;
    ob_err err = {""};
    if (ob_cl_open(NULL, &cl, &err) != 0) {
        fprintf(stderr, "no OpenCL: %s\n", err.msg);
        SKIP("kernel vs CPU: no OpenCL platform");
        return check_done();
    }
    int n = build_records();
    CHECK(n >= NREC / 2, "built %d records", n);
    static ob_errval gpu[NREC], cpu[NREC];
    const int S = 128;
    CHECK(ob_cl_measure_batch(cl, recs, n, S, gpu) == 0, "kernel launch");
    int agree = 0, tagree = 0, compared = 0;
    double worst = 0.0;
    for (int i = 0; i < n; i++) {
        ob_measure(recs[i].metric, recs[i].base, recs[i].approx, recs[i].d, S, &cpu[i]);
        if (isinf(cpu[i].err) && isinf(gpu[i].err)) {
            agree++;
            tagree++;
            continue;
        }
        compared++;
        double diff = fabs(cpu[i].err - gpu[i].err), rel = diff / fmax(fabs(cpu[i].err), 1e-300);
        int ok = rel <= 1e-9 || diff <= 1e-15;
        agree += ok;
        if (ok)
            tagree += fabs(cpu[i].t - gpu[i].t) <= 1e-6;
        worst = fmax(worst, rel);
        if (!ok)
            fprintf(stderr, "record %d (%s, deg %d/%d): cpu %.17g gpu %.17g\n", i,
                    ob_metric_name(recs[i].metric), recs[i].base->deg, recs[i].approx->deg, cpu[i].err, gpu[i].err);
    }
    CHECK(agree == n, "%d of %d records agree (worst relative difference %.3g)", agree, n, worst);
    CHECK(tagree == n, "%d of %d maxima at the same parameter", tagree, n);
    CHECK(compared > n / 2, "%d finite comparisons", compared);

    /* param (Zhao-Zhou's error at the given parameter): the same records
     * under it, bit for bit the CPU's error and parameter */
    static ob_measure_rec prec[NREC];
    for (int i = 0; i < n; i++) {
        prec[i] = recs[i];
        prec[i].metric = OB_METRIC_PARAM;
    }
    CHECK(ob_cl_measure_batch(cl, prec, n, S, gpu) == 0, "param launch");
    int same = 0, finite = 0;
    for (int i = 0; i < n; i++) {
        ob_measure(OB_METRIC_PARAM, prec[i].base, prec[i].approx, prec[i].d, S, &cpu[i]);
        const int eq = memcmp(&cpu[i].err, &gpu[i].err, sizeof(double)) == 0 &&
                       memcmp(&cpu[i].t, &gpu[i].t, sizeof(double)) == 0 && cpu[i].work == gpu[i].work;
        same += eq;
        finite += isfinite(cpu[i].err) && cpu[i].err > 0.0;
        if (!eq)
            fprintf(stderr, "param record %d (deg %d/%d): cpu %a at %a, gpu %a at %a\n", i, prec[i].base->deg,
                    prec[i].approx->deg, cpu[i].err, cpu[i].t, gpu[i].err, gpu[i].t);
    }
    CHECK(same == n, "param: %d of %d records bit for bit (error, parameter, work)", same, n);
    CHECK(finite > n / 2, "param: %d positive finite errors", finite);

    /* the batch buffers are reused and grown: a second, larger S and batch */
    CHECK(ob_cl_measure_batch(cl, recs, n, 300, gpu) == 0, "second launch with more samples");
    ob_measure(recs[n - 1].metric, recs[n - 1].base, recs[n - 1].approx, recs[n - 1].d, 300, &cpu[0]);
    CHECK_NEAR(gpu[n - 1].err, cpu[0].err, 1e-9 * fmax(1.0, fabs(cpu[0].err)), "last record at S = 300");

    /* a NaN control point measures as +inf on both */
    ob_bez bad = approx[2];
    bad.h[1][0] = NAN;
    ob_measure_rec r = {recs[2].base, &bad, recs[2].d, OB_METRIC_HAUSDORFF};
    ob_errval e1, e2;
    CHECK(ob_cl_measure_batch(cl, &r, 1, S, &e1) == 0, "NaN record launch");
    ob_measure(r.metric, r.base, r.approx, r.d, S, &e2);
    CHECK(isinf(e1.err) && isinf(e2.err), "NaN: kernel %g, cpu %g", e1.err, e2.err);
    ob_cl_close(cl);
    return check_done();
}
