/*
 * fit_error.h - the largest error of a method's fit under a metric, each
 * piece measured against its own sub-segment of the base as the driver
 * measures it (the tests that call a method's fit() directly).
 */
#ifndef OB_TEST_FIT_ERROR_H
#define OB_TEST_FIT_ERROR_H

#include <math.h>

#include "methods/core/curve.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"

/* Largest error over the pieces of f (fit of base C at offset d) under mt,
 * S samples per piece. */
static inline double fit_max_err(ob_metric mt, const ob_bez *C, const ob_fit *f, double d, int S)
{
    double worst = 0.0;
    for (int i = 0; i < f->n; i++) {
        ob_bez sub;
        ob_bez_subsegment(C, f->t[i], f->t[i + 1], &sub);
        ob_errval e;
        ob_measure(mt, &sub, &f->seg[i], d, S, &e);
        worst = fmax(worst, e.err);
    }
    return worst;
}

#endif
