/*
 * cert_job.h - the certified Hausdorff enclosure (metric_certified.h) of a
 * whole job: the pieces of one approximation against their base pieces, and
 * a job's err_lower <= max over pieces of H(A_i, O_i) <= err_upper.
 *
 * Why a job-level entry: a job's error is the largest of its pieces', so a
 * piece whose distance is far below another piece's certified lower bound
 * need not be enclosed to rtol of its own (tiny) distance, only shown below
 * that bound.  Enclosing every piece to rtol of its own distance costs
 * seconds on a piece 1e-8 from the offset (every interval must be resolved
 * to a relative 1e-3 of 1e-8, beyond any budget); shown below the job's
 * bound it takes milliseconds.  Nothing is weakened: every piece's upper is
 * still a certified upper bound, and the job's lower a distance attained.
 */
#ifndef OB_CERT_JOB_H
#define OB_CERT_JOB_H

#include "methods/metrics/cert_curve.h"
#include "methods/metrics/metric_certified.h"

/* Purpose: ob_certify_hausdorff_opts, refining no further than `stop`: the
 *          search ends when upper <= max(lower (1 + rtol), floor, stop), and
 *          the lower bound is only sought above stop / (1 + rtol).
 * Inputs:  stop >= 0 and finite (anything else counts as 0: exactly
 *          ob_certify_hausdorff_opts).
 * Outputs: *out as ob_certify_hausdorff_opts; lower <= H <= upper holds
 *          whatever stop is; met = 1 when upper <= max(lower (1 + rtol),
 *          floor, stop); lower may then be well below H (it was not sought).
 * Returns: as ob_certify_hausdorff_opts. */
int ob_certify_hausdorff_until(const ob_bez *base, const ob_bez *approx, double d, int samples,
                               const ob_cert_opts *opts, double stop, ob_certified *out);

/* Purpose: ob_certify_hausdorff_until with the base piece enclosed from the
 *          segment it was cut from (src, cert_curve.h): the offset of the
 *          curve as stored over the exact range, not of the rounded cut
 *          `base` (which only guides the search).  src NULL: `base` is the
 *          curve as stored.
 * Returns: as ob_certify_hausdorff_opts; -1 also for a src whose ranges are
 *          not inside [0, 1] (upper +inf). */
int ob_certify_piece(const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d, int samples,
                     const ob_cert_opts *opts, double stop, ob_certified *out);

typedef struct {
    double lower, upper;  /* max over pieces of lower, of upper: lower <= the job's H <= upper */
    int met;              /* 1: upper <= max(lower (1 + rtol), the largest floor) */
    int failed;           /* pieces whose ob_certify returned -1 (upper then +inf) */
    int upper_piece;      /* the piece whose upper is the job's */
    long leaves;          /* sum over pieces */
    int cancelled;        /* opts->cancel stopped it: pieces left unenclosed
                             (upper +inf), the verdict unknown */
    int unsought;         /* verdict mode: pieces not enclosed once the job was
                             shown over tol (upper then +inf: not sought) */
} ob_cert_job;

/* Purpose: the certified enclosure of a job of n pieces: piece i is approx[i]
 *          against the exact d-offset of base[i].
 * Inputs:  hint: an estimate of each piece's distance (the run's sampled
 *          errors), or NULL (then the sampled `hausdorff` metric at `samples`
 *          is measured here); it only orders the work.
 * Method:  the pieces in decreasing hint, each by ob_certify_hausdorff_until
 *          with stop = (the job's lower bound so far) (1 + rtol).
 * Outputs: *out; per-piece results into piece[i] when piece is not NULL.
 * Returns: 0; -1 when a piece could not be bounded (out->upper = +inf; lower
 *          still valid) or no memory. */
int ob_certify_job(int n, const ob_bez *base, const ob_bez *approx, double d, int samples, const ob_cert_opts *opts,
                   const double *hint, ob_cert_job *out, ob_certified *piece);

/* Purpose: ob_certify_job with each base piece enclosed from where it was
 *          cut (src[i], ob_certify_piece; src NULL: as ob_certify_job).
 * Method:  with opts->verdict (decide = the job's tol), the question is
 *          only "is the job within tol?": each piece is refined until its
 *          upper <= tol, or until a distance attained above tol is found;
 *          once one is (the job is over tol), the other pieces are not
 *          enclosed (out->unsought) and upper is +inf: the verdict needs
 *          none, and a job over tol (a `limit` job) has the most pieces.
 *          Only the first piece (the largest hint) seeks a lower bound
 *          where it cannot decide.  met: the verdict is reached (upper <=
 *          tol or lower > tol). */
int ob_certify_job_src(int n, const ob_bez *base, const ob_cert_src *src, const ob_bez *approx, double d, int samples,
                       const ob_cert_opts *opts, const double *hint, ob_cert_job *out, ob_certified *piece);

#endif
