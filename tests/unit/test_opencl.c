/*
 * test_opencl.c - the OpenCL kernel against the CPU reference.
 *
 * A few hundred random records of every kind (base degrees 2..7, polynomial
 * and rational, approximations from every registered method, both signs of d,
 * the four sampled metrics) are measured by the kernel in one batch and by the
 * CPU path one by one, under both layouts of the kernel (a work-group per
 * record, a work-item per record), at several sample counts and under
 * stops (ob_measure_until): error, parameter of the maximum and counted
 * work must agree bit for bit (the work of hausdorff's data-parallel group
 * kernel aside: it does more than the serial scan, see work_agrees).  Each metric and layout is its own program,
 * built when first used: the mixed batches build all eight, once each.
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
            recs[n] = (ob_measure_rec){&base[n], &approx[n], d, mets[n % 3], 0.0};
            n++;
        }
        free(work);
        free(fit);
    }
    return n;
}

/* Whether the kernel's counted work must be the CPU's: everywhere but
 * hausdorff in the group layout, which computes a side's samples all at
 * once (kernels/measure.cl) and so does more than the serial scan, whose
 * running maximum lets most samples stop early: its count is what it did,
 * positive. */
static int work_agrees(const char *layout, ob_metric m, double cpu, double gpu)
{
    if (m == OB_METRIC_HAUSDORFF && strcmp(layout, "groups") == 0)
        return gpu > 0.0 && isfinite(gpu);
    return cpu == gpu;
}

/* Records of which the kernel's error, parameter and work are the CPU's
 * bit for bit (work: work_agrees); prints the others. */
static int same_bits(const ob_measure_rec *r, const ob_errval *cpu, const ob_errval *gpu, int n, const char *what)
{
    int same = 0;
    for (int i = 0; i < n; i++) {
        const int eq = memcmp(&cpu[i].err, &gpu[i].err, sizeof(double)) == 0 &&
                       memcmp(&cpu[i].t, &gpu[i].t, sizeof(double)) == 0 &&
                       work_agrees(what, r[i].metric, cpu[i].work, gpu[i].work);
        same += eq;
        if (!eq)
            fprintf(stderr, "%s: record %d (%s, deg %d/%d): cpu %a at %a (work %.0f), kernel %a at %a (work %.0f)\n",
                    what, i, ob_metric_name(r[i].metric), r[i].base->deg, r[i].approx->deg, cpu[i].err, cpu[i].t,
                    cpu[i].work, gpu[i].err, gpu[i].t, gpu[i].work);
    }
    return same;
}

int main(void)
{
    testlib_seed(0x5DEECE66DULL);
    ob_cl *cl = NULL;
    ob_err err = {""};
    if (ob_cl_open(NULL, 0, &cl, &err) != 0) {
        fprintf(stderr, "no OpenCL: %s\n", err.msg);
        /* no loader, platform or fp64 device: skipped; a device that does
         * not build the kernel (or a failing call) is a failure */
        const int absent = strstr(err.msg, "no OpenCL") != NULL;
        if (absent)
            SKIP("kernel vs CPU: no OpenCL platform");
        else
            CHECK(0, "kernel vs CPU: the backend does not open: %s", err.msg);
        return check_done();
    }
    int n = build_records();
    CHECK(n >= NREC / 2, "built %d records", n);
    static ob_errval gpu[NREC], cpu[NREC];
    const int S = 128;
    int cmp_n = 0;
    double worst = 0.0;
    for (int lay = 0; lay < 2; lay++) {
        ob_cl_set_layout(cl, lay ? OB_CL_ITEMS : OB_CL_GROUPS);
        const char *ln = ob_cl_layout_name(ob_cl_get_layout(cl));
        CHECK(ob_cl_get_layout(cl) == (lay ? OB_CL_ITEMS : OB_CL_GROUPS), "layout %s set", ln);
        /* the mixed batch (radial, normal, hausdorff in turn) at several S,
         * S = 8 and 11 below and beside the lane and block widths, 513 past
         * the stack tables */
        const int Ss[] = {S, 8, 11, 513};
        for (int si = 0; si < 4; si++) {
            CHECK(ob_cl_measure_batch(cl, recs, n, Ss[si], gpu) == 0, "%s: kernel launch at S = %d", ln, Ss[si]);
            cmp_n = 0;
            for (int i = 0; i < n; i++) {
                ob_measure(recs[i].metric, recs[i].base, recs[i].approx, recs[i].d, Ss[si], &cpu[i]);
                cmp_n += isfinite(cpu[i].err);
                if (isfinite(cpu[i].err) && isfinite(gpu[i].err))
                    worst = fmax(worst, fabs(cpu[i].err - gpu[i].err) / fmax(fabs(cpu[i].err), 1e-300));
            }
            CHECK(same_bits(recs, cpu, gpu, n, ln) == n, "%s, S = %d: every record bit for bit", ln, Ss[si]);
        }
        CHECK(cmp_n > n / 2, "%s: %d finite errors", ln, cmp_n);

        /* param (Zhao-Zhou's error at the given parameter): the same records
         * under it */
        static ob_measure_rec prec[NREC];
        for (int i = 0; i < n; i++) {
            prec[i] = recs[i];
            prec[i].metric = OB_METRIC_PARAM;
        }
        CHECK(ob_cl_measure_batch(cl, prec, n, S, gpu) == 0, "%s: param launch", ln);
        int finite = 0;
        for (int i = 0; i < n; i++) {
            ob_measure(OB_METRIC_PARAM, prec[i].base, prec[i].approx, prec[i].d, S, &cpu[i]);
            finite += isfinite(cpu[i].err) && cpu[i].err > 0.0;
        }
        CHECK(same_bits(prec, cpu, gpu, n, ln) == n, "%s: param bit for bit", ln);
        CHECK(finite > n / 2, "param: %d positive finite errors", finite);

        /* under stops (from a third of each record's error to twice it,
         * and none), every metric: ob_measure_until's bits, work included,
         * with some records ending early */
        static ob_measure_rec srec[NREC];
        const double frac[5] = {0.0, 0.3, 0.999, 1.0, 2.0};
        const ob_metric four[4] = {OB_METRIC_RADIAL, OB_METRIC_NORMAL, OB_METRIC_HAUSDORFF, OB_METRIC_PARAM};
        int early = 0;
        for (int i = 0; i < n; i++) {
            ob_errval full;
            srec[i] = recs[i];
            srec[i].metric = four[i % 4];
            ob_measure(srec[i].metric, srec[i].base, srec[i].approx, srec[i].d, S, &full);
            srec[i].stop = frac[(i / 4) % 5] * full.err;
            ob_measure_until(srec[i].metric, srec[i].base, srec[i].approx, srec[i].d, S, srec[i].stop, &cpu[i]);
            early += cpu[i].work < full.work;
        }
        CHECK(ob_cl_measure_batch(cl, srec, n, S, gpu) == 0, "%s: launch with stops", ln);
        CHECK(same_bits(srec, cpu, gpu, n, ln) == n, "%s: stops: every record bit for bit", ln);
        CHECK(early > n / 10, "%s: stops: %d records end early", ln, early);

        /* a NaN control point measures as +inf on both, under every metric,
         * with the same parameter and the same work (the scan stops at the
         * first bad sample) */
        ob_bez bad[4];
        ob_measure_rec r[4];
        const ob_metric all[4] = {OB_METRIC_RADIAL, OB_METRIC_NORMAL, OB_METRIC_HAUSDORFF, OB_METRIC_PARAM};
        for (int k = 0; k < 4; k++) {
            bad[k] = approx[2 + k];
            bad[k].h[1][0] = NAN;
            r[k] = (ob_measure_rec){recs[2 + k].base, &bad[k], recs[2 + k].d, all[k], 0.0};
        }
        ob_errval e1[4], e2[4];
        CHECK(ob_cl_measure_batch(cl, r, 4, S, e1) == 0, "%s: NaN records launch", ln);
        int inf = 0;
        for (int k = 0; k < 4; k++) {
            ob_measure(r[k].metric, r[k].base, r[k].approx, r[k].d, S, &e2[k]);
            inf += isinf(e1[k].err) && isinf(e2[k].err);
        }
        CHECK(inf == 4, "%s: NaN: %d of 4 metrics +inf on both", ln, inf);
        CHECK(same_bits(r, e2, e1, 4, ln) == 4, "%s: NaN records bit for bit", ln);
    }
    fprintf(stderr, "largest relative difference of errors: %.3g\n", worst);
    /* one program per metric and layout, each built once, when first used */
    ob_cl_build rep[16];
    const int nb = ob_cl_builds(cl, rep, 16);
    int each = nb == 8;
    for (int i = 0; i < nb && each; i++)
        for (int j = 0; j < i; j++)
            each &= rep[i].metric != rep[j].metric || rep[i].layout != rep[j].layout;
    CHECK(each, "8 programs built (4 metrics, 2 layouts), each once: %d", nb);
    ob_cl_close(cl);
    return check_done();
}
