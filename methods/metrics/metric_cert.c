/*
 * metric_cert.c - the `certified` metric: ob_certify_hausdorff's upper end
 * as a measurement (metric.h).
 */
#include "methods/metrics/metric.h"

#include <math.h>

#include "methods/metrics/cert_job.h"
#include "methods/metrics/metric_certified.h"

/* Purpose: the certified metric of approx against the exact d-offset of base.
 * Outputs: out->err the enclosure's upper end (never below the true
 *          two-sided Hausdorff distance; +inf where no bound exists, e.g. a
 *          cusp of the base, which the driver splits like any failing
 *          piece); out->t the sampled hausdorff's parameter (where the split
 *          rules and draw look), out->work the sampled measurement's.
 * Method:  the sampled hausdorff at S samples, then the enclosure from the
 *          same grid (metric_certified.h).
 * Returns: 0; -1 where the sampled measurement cannot be made (no memory
 *          for its tables), with err = +inf. */
int ob_metric_certified_src(const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d, int S,
                            ob_errval *out)
{
    if (ob_metric_hausdorff(base, approx, d, S, out) != 0)
        return -1;
    ob_certified c;
    if (ob_certify_piece(base, src, approx, d, S, NULL, 0.0, &c) != 0 || !(c.upper >= 0.0)) {
        out->err = INFINITY;
        return 0;
    }
    out->err = c.upper;
    return 0;
}

int ob_metric_certified(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return ob_metric_certified_src(base, NULL, approx, d, S, out);
}
