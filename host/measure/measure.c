/*
 * measure.c - an approximation's error with the run's engine (measure.h).
 */
#include "host/measure/measure.h"
#include "host/run/signals.h"

#include <math.h>
#include <stdio.h>

int ob_approx_measure(const ob_curve *c, double d, const ob_approx *a, ob_metric m, int samples, const char *name,
                      ob_mres *r, ob_err *err)
{
    *r = (ob_mres){1, "", 0.0, -1, -1, NAN, 0, ""};
    if (ob_metric_same_param(m) && !a->same_param) {
        r->applies = 0;
        r->why = "needs an approximation in the base's parameter (a file from --export of a method that keeps it)";
        return 0;
    }
    for (int k = 0; k < a->n && ob_metric_reads_param(m); k++)
        if (a->v[k].matched) {
            r->applies = 0;
            r->why = "reads each piece at the base parameter its link maps it to: the file carries no link (a "
                     "file from --export does), and a match by projection gives none";
            return 0;
        }
    for (int k = 0; k < a->n; k++) {
        if (ob_stop_signal()) /* a long loop polls the stop (signals.h) */
            return ob_fail(err, "%s: stopped by signal %d after %d of %d pieces", name, ob_stop_signal(), k, a->n);
        const ob_apiece *p = &a->v[k];
        ob_bez base;
        if (ob_apiece_base(c, p, &base) != 0) {
            ob_fail(err, "%s:%d: piece %d: its base segment %d (span %.17g %.17g, fit %.17g %.17g) is not a "
                    "piece of curve '%s' (%d segments)", name, p->line, k, p->seg, p->a, p->b, p->t0, p->t1, c->id,
                    c->nseg);
            return -1;
        }
        ob_errval e;
        /* the certified metric encloses the segment as stored, over the exact span (cert_curve.h) */
        const ob_cert_src src = {&c->seg[p->seg], p->a, p->b, p->t0, p->t1};
        if (ob_measure_src(m, &base, &src, &p->approx, d, samples, 0.0, &e) != 0 || isnan(e.err)) {
            ob_fail(err, "%s:%d: piece %d: metric %s cannot measure it (degree %d)", name, p->line, k,
                    ob_metric_name(m), p->approx.deg);
            return -1;
        }
        if (!(e.err <= r->err) || r->piece < 0) {  /* as the driver keeps a job's max_err */
            r->err = e.err;
            r->piece = ob_approx_file_piece(a, k);  /* the file's number, not the part's */
            r->seg = p->seg;
            r->t = p->a + (p->b - p->a) * (p->t0 + (p->t1 - p->t0) * e.t);
        }
    }
    r->ok = ob_err_can_pass(r->err);
    if (!r->ok)
        r->why = "the error is not finite: the metric cannot bound a piece (a pole or a weight <= 0 of a "
                 "rational piece?)";
    return 0;
}

const char *ob_mres_status(const ob_mres *r)
{
    return !r->applies ? "n/a" : r->ok ? "ok" : "fail";
}
