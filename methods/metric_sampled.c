/*
 * metric_sampled.c - the sampled metrics radial, normal and hausdorff on the
 * CPU.  The formulas live in kernels/metric_core.h, shared word for word with
 * the OpenCL kernel; see metric.h for the definitions.
 */
#include "metric.h"

#include "../kernels/metric_core.h"

_Thread_local long obc_eval_count;

/* Hausdorff keeps S samples of the offset and of the approximation. */
static int measure_core(int code, const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    double scratch[4 * OB_MAX_SAMPLES];
    obc_measure(code, &base->h[0][0], base->deg, &approx->h[0][0], approx->deg, d, ob_clamp_samples(S),
                scratch, &out->err, &out->t);
    return 0;
}

int ob_metric_radial(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_RADIAL, base, approx, d, S, out);
}

int ob_metric_normal(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_NORMAL, base, approx, d, S, out);
}

int ob_metric_hausdorff(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_HAUSDORFF, base, approx, d, S, out);
}
