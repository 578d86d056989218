/*
 * metric.h - how far an approximation is from the exact offset.
 *
 * All metrics compare one approximating segment A with the exact offset
 * O(t) = C(t) + d N(t) of one base segment C over t in [0,1]:
 *   bound      Elber-Lee-Kim's symbolic measure: the Bernstein coefficients of
 *              D(t) = ||A(t) - C(t)||^2 (rational: of its numerator over its
 *              denominator) bound D; error = max(|sqrt(max(Dmin,0)) - |d||,
 *              |sqrt(Dmax) - |d||).  No sampling.  Assumes A shares C's parameter.
 *   radial     max_t | ||A(t) - C(t)|| - |d| |, sampled (same parameter).
 *   normal     Zhao-Zhou: along the normal line C(t) + s N(t), the signed
 *              distance s to its intersection with A near t; error |s - d|.
 *              Independent of A's parameterization.
 *   hausdorff  two-sided Hausdorff distance between A and the untrimmed offset
 *              O over [0,1]; nearest points by a global coarse scan of the
 *              samples, local descent and Gauss-Newton projection.
 *   param      Zhao-Zhou's error at the given parameter (Zhao & Zhou 2017,
 *              section 3): max_t |(A(t) - O(t)) . N(t)|, sampled.  It reads A
 *              at the base's parameter like radial, but the driver does not
 *              refuse other methods: for them it is the normal component of
 *              A(t) - O(t), blind to a drift of A along the offset to first
 *              order, neither the geometric distance nor a bound of it.
 *   certified  the upper end of a certified enclosure of the two-sided
 *              Hausdorff distance (metric_certified.h: interval arithmetic
 *              with outward rounding, lower <= true <= upper by
 *              construction): never below the true distance, within a
 *              relative 1e-3 of it where the search meets its target.  Its t
 *              is the sampled hausdorff's.  On the CPU only, like bound.
 * Sampled metrics use S parameters t_k = k/(S-1) and refine the largest sample
 * by golden-section search between its neighbours.
 *
 * This file is the CPU reference; the OpenCL kernels implement the same
 * formulas and are checked against it.
 */
#ifndef OB_METRIC_H
#define OB_METRIC_H

#include "methods/core/curve.h"
#include "methods/metrics/cert_curve.h"

/* The sampled metrics' codes are shared with kernels/metric_core.h. */
typedef enum {
    OB_METRIC_BOUND = 0,
    OB_METRIC_RADIAL,
    OB_METRIC_NORMAL,
    OB_METRIC_HAUSDORFF,
    OB_METRIC_PARAM,
    OB_METRIC_CERTIFIED,
    OB_METRIC_COUNT
} ob_metric;

const char *ob_metric_name(ob_metric m);
/* One-line definition of metric m (for meta.json); "?" if unknown. */
const char *ob_metric_doc(ob_metric m);
/* Returns 0 and sets *m, or -1 for an unknown name. */
int ob_metric_parse(const char *name, ob_metric *m);
/* 1 if the metric is only run on methods whose output is parameterized like
 * the base (bound, radial: the driver skips the others).  param reads A at the
 * base's parameter too but is defined for any A (see above): 0. */
int ob_metric_same_param(ob_metric m);
/* 1 if a batch backend (the OpenCL kernel) measures metric m: the sampled
 * ones (radial, normal, hausdorff, param); bound and certified are measured
 * on the CPU. */
int ob_metric_batched(ob_metric m);
/* 1 if the metric reads A at the base's parameter t, so that it changes when
 * A is reparameterized (bound, radial, param); 0 for the geometric ones
 * (normal, hausdorff). */
int ob_metric_reads_param(ob_metric m);

enum { OB_DEFAULT_SAMPLES = 256, OB_MIN_SAMPLES = 8, OB_MAX_SAMPLES = 4096 };

typedef struct {
    double err;  /* the error, >= 0 (+inf when it cannot be measured) */
    double t;    /* base parameter in [0,1] where it is largest */
    double work; /* floating-point operations the measurement took, as
                    kernels/metric_core.h counts them (OBC_OPS_*); 0 for bound */
} ob_errval;

/* Purpose: error of `approx` against the exact d-offset of `base`.
 * Inputs:  samples S (ignored by bound), clamped to [OB_MIN_SAMPLES, OB_MAX_SAMPLES].
 * Returns: 0; -1 if the metric cannot be applied (bound with a degree past
 *          OB_BERN_MAX; no memory for the sample tables past S = 512), with
 *          out->err = +inf. */
int ob_measure(ob_metric m, const ob_bez *base, const ob_bez *approx, double d,
               int samples, ob_errval *out);

/* Purpose: ob_measure for a caller that only needs to know whether the
 *          error exceeds stop where it does (a piece failing its level in a
 *          greedy search).
 * Inputs:  stop > 0 (else, and under bound, this is ob_measure).
 * Outputs: where the full error is <= stop, exactly ob_measure's result, bit
 *          for bit; where it is above, possibly the error of the first sample
 *          (in scan order) that exceeds stop, and its parameter: a value
 *          above stop and at most the full error.  out->work: what was done.
 * Returns: as ob_measure. */
int ob_measure_until(ob_metric m, const ob_bez *base, const ob_bez *approx, double d,
                     int samples, double stop, ob_errval *out);

/* Purpose: ob_measure_until of a base piece cut out of a stored segment
 *          (src, cert_curve.h; NULL: base is the curve as stored): the
 *          certified metric encloses the stored segment over the exact range
 *          (the cut only guides it); the others measure the cut `base`.
 * Returns: as ob_measure_until. */
int ob_measure_src(ob_metric m, const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d,
                   int samples, double stop, ob_errval *out);

/* Purpose: whether a measured error may stand in an `ok` result: a finite
 *          number.  +inf (a piece the metric cannot bound, a pole) and NaN
 *          are never ok: the driver splits such a piece like any failing one
 *          and never ends a job ok with it, `measure` reports it `fail`, and
 *          the readers of results.csv (compare, merge, --resume) refuse an
 *          ok row with it.
 * Returns: 1 or 0. */
int ob_err_can_pass(double err);

/* The sample count actually used: S clamped to [OB_MIN_SAMPLES, OB_MAX_SAMPLES]. */
int ob_clamp_samples(int samples);

/* Doubles of working space one sampled measurement needs at S samples (the
 * OpenCL host sizes its scratch buffer with it). */
size_t ob_metric_scratch(int samples);

/* The individual metrics (same contract, S clamped likewise). */
int ob_metric_bound(const ob_bez *base, const ob_bez *approx, double d, ob_errval *out);
int ob_metric_radial(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out);
int ob_metric_normal(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out);
int ob_metric_hausdorff(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out);
int ob_metric_param(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out);
/* certified: err = the enclosure's upper end (+inf where none exists: a cusp
 * of the base), t and work the sampled hausdorff's at S samples. */
int ob_metric_certified(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out);
/* certified, with the base piece's source (ob_measure_src) */
int ob_metric_certified_src(const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d, int S,
                            ob_errval *out);
/* A sampled metric m (radial, normal, hausdorff, param) under a stop, as
 * ob_measure_until. */
int ob_metric_sampled(ob_metric m, const ob_bez *base, const ob_bez *approx, double d, int S, double stop,
                      ob_errval *out);

#endif
