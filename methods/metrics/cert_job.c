/*
 * cert_job.c - a job's certified Hausdorff enclosure (see cert_job.h).
 */
#include "methods/metrics/cert_job.h"

#include <math.h>
#include <stdlib.h>

#include "methods/metrics/metric.h"

enum { HINT_SAMPLES = 32 };  /* the coarse sampling that orders a verdict's pieces */

typedef struct {
    double key;
    int i;
} order_t;

static int by_key_desc(const void *a, const void *b)
{
    const order_t *x = a, *y = b;
    if (x->key != y->key)
        return x->key > y->key ? -1 : 1;
    return x->i - y->i;  /* deterministic */
}

/* Piece k's options and stop (in decreasing hint) given the job so far: to
 * rtol of the job's lower bound; in verdict mode to the tol, with a lower
 * bound sought first on the first piece only. */
static double piece_opts(const ob_cert_opts *o, int k, const ob_cert_job *job, ob_cert_opts *po)
{
    *po = *o;
    if (!(o->verdict && o->decide > 0))
        return job->lower * (1.0 + o->rtol);
    po->no_lower = k > 0;
    return 0.0;
}

int ob_certify_job(int n, const ob_bez *base, const ob_bez *approx, double d, int samples, const ob_cert_opts *opts,
                   const double *hint, ob_cert_job *out, ob_certified *piece)
{
    return ob_certify_job_src(n, base, NULL, approx, d, samples, opts, hint, out, piece);
}

int ob_certify_job_src(int n, const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d, int samples,
                       const ob_cert_opts *opts, const double *hint, ob_cert_job *out, ob_certified *piece)
{
    ob_cert_opts o;
    if (opts)
        o = *opts;
    else
        ob_cert_defaults(&o);
    *out = (ob_cert_job){0.0, 0.0, 1, 0, -1, 0, 0, 0};
    order_t *ord = malloc((size_t)(n > 0 ? n : 1) * sizeof *ord);
    if (!ord) {
        out->upper = INFINITY, out->met = 0;
        return -1;
    }
    for (int i = 0; i < n; i++) {
        double h = hint ? hint[i] : NAN;
        if (!hint) {
            /* verdict mode orders by a coarse sampling: the order only
             * decides which piece seeks the lower bound first, and the
             * full sampling costs as much as the verdict itself */
            ob_errval e;
            ob_metric_hausdorff(&base[i], &approx[i], d, o.verdict && o.decide > 0 ? HINT_SAMPLES : samples, &e);
            h = e.err;
        }
        ord[i] = (order_t){h == h ? h : INFINITY, i};  /* unknown first: it may be the largest */
    }
    qsort(ord, (size_t)n, sizeof *ord, by_key_desc);
    const int verdict = o.verdict && o.decide > 0;
    for (int k = 0; k < n && !out->cancelled; k++) {
        const int i = ord[k].i;
        if (verdict && out->lower > o.decide) {  /* decided: over tol; the rest is not sought */
            out->unsought = n - k;
            out->upper = INFINITY;
            if (piece)
                for (int r = k; r < n; r++)
                    piece[ord[r].i] = (ob_certified){.upper = INFINITY};
            break;
        }
        ob_certified r;
        ob_cert_opts po;
        const double stop = piece_opts(&o, k, out, &po);
        const int rc = ob_certify_piece(&base[i], src ? &src[i] : NULL, &approx[i], d, samples, &po, stop, &r);
        if (piece)
            piece[i] = r;
        out->cancelled = r.cancelled;
        out->failed += rc != 0;
        out->met &= r.met;
        out->leaves += r.leaves;
        out->lower = fmax(out->lower, r.lower);
        if (!(r.upper <= out->upper) || out->upper_piece < 0)
            out->upper = fmax(out->upper, r.upper), out->upper_piece = i;
    }
    free(ord);
    if (verdict)
        out->met = out->upper <= o.decide || out->lower > o.decide;
    if (out->cancelled)
        out->met = 0;
    if (out->failed || out->cancelled) {
        out->upper = INFINITY, out->met = 0;
        return -1;
    }
    return 0;
}
