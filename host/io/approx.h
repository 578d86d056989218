/*
 * approx.h - one job's approximation as a list of pieces, for `run --export`
 * (host/io/export*.c) and `measure` (host/cli/cmd_measure.c).
 *
 * A piece is a Bézier segment (homogeneous, over [0, 1]) in the base curve's
 * coordinates.  When it comes from a run (or from a file offbench exported)
 * it also knows the base piece it approximates, exactly as the driver cut it:
 * base segment `seg`, the accepted span [a, b] of that segment, and the part
 * [t0, t1] of the span's fit that the piece covers (ob_fit.t).  The base
 * piece is then subsegment(subsegment(seg, a, b), t0, t1), bit for bit what
 * the driver measured (methods/driver/driver.c, measure_chunk), so measuring
 * it again gives the run's numbers.  A piece from elsewhere (a CAD system's
 * offset) has no such link (has_base 0): measure finds its base range by
 * projecting its end points onto the exact offset (approx_match.c).
 */
#ifndef OB_APPROX_H
#define OB_APPROX_H

#include <stddef.h>

#include "methods/driver/driver.h"
#include "methods/core/err.h"

typedef struct {
    int has_base;       /* 1: seg, a, b, t0, t1 are known */
    int seg;            /* base segment index */
    double a, b;        /* the accepted span of segment seg */
    double t0, t1;      /* the piece's part of the span's fit */
    int fit_first;      /* 1: the first piece of its fit */
    int line;           /* where it was read (0: not read from a file) */
    ob_bez approx;      /* the approximating piece over [0, 1] */
} ob_apiece;

typedef struct {
    ob_apiece *v;
    int n, cap;
    int same_param;     /* 1: the pieces share the base's parameter (the
                           method has OB_CAP_SAME_PARAM; bound and radial
                           apply); 0 unknown or not */
    int have_job;       /* 1: the file names the job that exported it */
    char job_curve[64]; /* that job's curve id and offset distance d */
    double job_d;
} ob_approx;

/* Always safe to call (also on a zeroed approximation). */
void ob_approx_free(ob_approx *a);

/* Appends a zeroed piece and returns it, or NULL when out of memory. */
ob_apiece *ob_approx_add(ob_approx *a);

/* Purpose: the base piece that piece p approximates (p->has_base set):
 *          segment p->seg of curve c cut to [a, b], then to [t0, t1], as the
 *          driver cuts it.  Returns 0, or -1 when p->seg is not a segment of c
 *          or the ranges are not inside [0, 1] with a < b, t0 < t1. */
int ob_apiece_base(const ob_curve *c, const ob_apiece *p, ob_bez *base);

/* Purpose: the pieces of a finished job: every accepted span of its log
 *          refitted with the job's method (fits are deterministic; this is
 *          how draw gets them too, host/view/jobview.c), in curve order.
 * Inputs:  j: a job that ended ok or limit; log: its span log.
 * Outputs: *out (appended to; same_param from the method's capabilities).
 * Errors:  returns 0; -1 with a reason in err->msg (a refit that fails or does not
 *          give the run's segment count; out of memory). */
int ob_approx_from_job(const ob_job *j, const ob_span_log *log, ob_approx *out, ob_err *err);

#endif
