/*
 * metric_sampled.c - the sampled metrics radial, normal, hausdorff and param on the
 * CPU.  The formulas live in kernels/metric_core.h, shared word for word with
 * the OpenCL kernel; see metric.h for the definitions.
 */
#include "methods/metrics/metric.h"

#include "kernels/metric_core.h"

#include <stdlib.h>

_Static_assert(OBC_RADIAL == OB_METRIC_RADIAL && OBC_NORMAL == OB_METRIC_NORMAL &&
                   OBC_HAUSDORFF == OB_METRIC_HAUSDORFF && OBC_PARAM == OB_METRIC_PARAM,
               "kernels/metric_core.h's metric codes are ob_metric's");

size_t ob_metric_scratch(int S) { return 2 * (size_t)OBC_TABLE_SIZE(ob_clamp_samples(S)); }

/* Hausdorff keeps sample tables of the offset and of the approximation: on
 * the stack up to the default S, on the heap past it (at most 0.5 MiB). */
enum { STACK_SAMPLES = 512 };

static int measure_core(int code, const ob_bez *base, const ob_bez *approx, double d, int S, double stop,
                        ob_errval *out)
{
    double local[2 * OBC_TABLE_SIZE(STACK_SAMPLES)];
    S = ob_clamp_samples(S);
    double *scratch = local;
    if (S > STACK_SAMPLES && !(scratch = malloc(ob_metric_scratch(S) * sizeof *scratch))) {
        out->err = (double)INFINITY;
        out->t = 0.0;
        return -1;
    }
    long ops = 0;
    obc_measure(code, &base->h[0][0], base->deg, &approx->h[0][0], approx->deg, d, S, stop, scratch, &out->err,
                &out->t, &ops);
    out->work = (double)ops;
    if (scratch != local)
        free(scratch);
    return 0;
}

int ob_metric_sampled(ob_metric m, const ob_bez *base, const ob_bez *approx, double d, int S, double stop,
                      ob_errval *out)
{
    return measure_core((int)m, base, approx, d, S, stop, out);
}

int ob_metric_radial(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_RADIAL, base, approx, d, S, 0.0, out);
}

int ob_metric_normal(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_NORMAL, base, approx, d, S, 0.0, out);
}

int ob_metric_hausdorff(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_HAUSDORFF, base, approx, d, S, 0.0, out);
}

int ob_metric_param(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_PARAM, base, approx, d, S, 0.0, out);
}
