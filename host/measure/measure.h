/*
 * measure.h - the error of an approximation read from a file (`measure`),
 * with the run's engine: each piece against its base piece by ob_measure
 * (methods/metrics/metric.h), the largest over the pieces, as the driver
 * computes a job's max_err (methods/driver/driver.c, measure_chunk).
 *
 * Pieces that carry their base link (files offbench exported: approx.h) are
 * measured against exactly the base piece the run measured, so the result
 * is the run's max_err (the CPU backend's; tests/e2e/e2e_export.sh).  Pieces
 * without one are matched first (ob_approx_match).
 */
#ifndef OB_MEASURE_H
#define OB_MEASURE_H

#include <stddef.h>

#include "host/io/approx.h"
#include "methods/core/err.h"

/* Purpose: give every piece without a base link one, by projection: each
 *          end point goes to the base parameter whose exact offset point
 *          C(t) + d N(t) is nearest (a scan of 512 parameters per base
 *          segment, then golden-section refinement), both ends on one base
 *          segment; the piece is then linked to span [ta, tb] of that
 *          segment (fit [0, 1]), reversed first (its control points in the
 *          other order, an exact reparameterization) when it runs against
 *          the base.
 * Errors:  returns 0; -1 with "NAME:LINE: piece K: reason" in err->msg when both
 *          ends fall on one point, or on two base segments that do not meet
 *          there (the piece must then be cut where the base's segments join).
 * Note:    on an offset with loops (cusps) the nearest point can lie on the
 *          wrong branch; such files should carry the link. */
int ob_approx_match(const ob_curve *c, double d, ob_approx *a, const char *name, ob_err *err);

/* One metric's result. */
typedef struct {
    int applies;        /* 0: why says why not */
    const char *why;
    double err;         /* the largest error over the pieces */
    int piece;          /* where: the piece, its base segment and base parameter */
    int seg;
    double t;
    int ok;             /* applies and err is finite (ob_err_can_pass); else why says why not */
} ob_mres;

/* The status `measure` writes for r: "ok", "n/a" (the metric does not
 * apply) or "fail" (an error that is not finite is never ok). */
const char *ob_mres_status(const ob_mres *r);

/* Purpose: the error of every piece of a (all pieces linked) against the
 *          d-offset of curve c under metric m, S samples, the largest kept.
 *          bound and radial apply only when a->same_param (the pieces share
 *          the base's parameter).
 *          r->ok 0 with r->why when the largest error is not finite (a
 *          piece the metric cannot bound: a pole of a rational piece).
 * Returns: 0; -1 with "NAME:LINE: piece K: reason" in err->msg when a piece
 *          cannot be measured (a link to a segment c does not have; bound
 *          past its degree). */
int ob_approx_measure(const ob_curve *c, double d, const ob_approx *a, ob_metric m, int samples, const char *name,
                      ob_mres *r, ob_err *err);

#endif
