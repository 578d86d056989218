/*
 * metric.c - metric names and dispatch.
 */
#include "methods/metrics/metric.h"

#include <math.h>
#include <string.h>

static const char *const names[OB_METRIC_COUNT] = {"bound", "radial", "normal", "hausdorff", "param", "certified"};

/* One line per metric, for meta.json (the definitions are metric.h's). */
static const char *const docs[OB_METRIC_COUNT] = {
    "symbolic Bernstein bound of | |A(t) - C(t)| - |d| | (Elber, Lee & Kim 1997), no sampling",
    "max | |A(t) - C(t)| - |d| |, same parameter, sampled",
    "max |s - d| where the normal line C(t) + s N(t) meets A (Zhao & Zhou 2017), sampled",
    "two-sided Hausdorff distance between A and the exact offset, sampled",
    "max |(A(t) - C(t) - d N(t)) . N(t)|, the error at the given parameter (Zhao & Zhou 2017, section 3), "
    "sampled; defined for every method, but for one whose output is not in the base's parameter it is the "
    "normal component at the same t, not the geometric distance",
    "certified upper bound of the two-sided Hausdorff distance between A and the exact offset (interval "
    "enclosures, outward rounding; never below the true distance)",
};

const char *ob_metric_doc(ob_metric m)
{
    return (m >= 0 && m < OB_METRIC_COUNT) ? docs[m] : "?";
}

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

int ob_metric_batched(ob_metric m)
{
    return m == OB_METRIC_RADIAL || m == OB_METRIC_NORMAL || m == OB_METRIC_HAUSDORFF || m == OB_METRIC_PARAM;
}

int ob_metric_reads_param(ob_metric m)
{
    return ob_metric_same_param(m) || m == OB_METRIC_PARAM;
}

int ob_clamp_samples(int samples)
{
    return samples < OB_MIN_SAMPLES ? OB_MIN_SAMPLES : samples > OB_MAX_SAMPLES ? OB_MAX_SAMPLES : samples;
}

/* The one dispatcher: ob_measure_until is this without a source, ob_measure
 * without a stop either. */
int ob_measure_src(ob_metric m, const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d,
                   int samples, double stop, ob_errval *out)
{
    out->work = 0.0;
    switch (m) {
    case OB_METRIC_BOUND: return ob_metric_bound(base, approx, d, out);
    case OB_METRIC_RADIAL:
    case OB_METRIC_NORMAL:
    case OB_METRIC_HAUSDORFF:
    case OB_METRIC_PARAM: return ob_metric_sampled(m, base, approx, d, samples, stop, out);
    case OB_METRIC_CERTIFIED: return ob_metric_certified_src(base, src, approx, d, samples, out);
    default: break;
    }
    out->err = INFINITY;
    out->t = 0.0;
    return -1;
}

int ob_measure_until(ob_metric m, const ob_bez *base, const ob_bez *approx, double d,
                     int samples, double stop, ob_errval *out)
{
    return ob_measure_src(m, base, NULL, approx, d, samples, stop, out);
}

int ob_err_can_pass(double err)
{
    return isfinite(err);
}

int ob_measure(ob_metric m, const ob_bez *base, const ob_bez *approx, double d,
               int samples, ob_errval *out)
{
    return ob_measure_until(m, base, approx, d, samples, 0.0, out);
}
