/*
 * metric.c - metric names and dispatch.
 */
#include "methods/metrics/metric.h"

#include <math.h>
#include <string.h>

static const char *const names[OB_METRIC_COUNT] = {"bound", "radial", "normal", "hausdorff"};

const char *ob_metric_name(ob_metric m)
{
    return (m >= 0 && m < OB_METRIC_COUNT) ? names[m] : "?";
}

int ob_metric_parse(const char *name, ob_metric *m)
{
    for (int i = 0; i < OB_METRIC_COUNT; i++)
        if (strcmp(name, names[i]) == 0) {
            *m = (ob_metric)i;
            return 0;
        }
    return -1;
}

int ob_metric_same_param(ob_metric m)
{
    return m == OB_METRIC_BOUND || m == OB_METRIC_RADIAL;
}

int ob_clamp_samples(int samples)
{
    return samples < OB_MIN_SAMPLES ? OB_MIN_SAMPLES : samples > OB_MAX_SAMPLES ? OB_MAX_SAMPLES : samples;
}

int ob_measure(ob_metric m, const ob_bez *base, const ob_bez *approx, double d,
               int samples, ob_errval *out)
{
    out->work = 0.0;
    switch (m) {
    case OB_METRIC_BOUND: return ob_metric_bound(base, approx, d, out);
    case OB_METRIC_RADIAL: return ob_metric_radial(base, approx, d, samples, out);
    case OB_METRIC_NORMAL: return ob_metric_normal(base, approx, d, samples, out);
    case OB_METRIC_HAUSDORFF: return ob_metric_hausdorff(base, approx, d, samples, out);
    default: break;
    }
    out->err = INFINITY;
    out->t = 0.0;
    return -1;
}
