/*
 * certify.h - `run --certify`: each job's error certified, not only sampled
 * (issue 41, docs/certified.md).
 *
 * Once the driver has run, every job with an approximation (status ok or
 * limit) has its pieces refitted from its span log (fits are deterministic:
 * host/io/approx.h, as --export does) and enclosed by ob_certify_job
 * (methods/metrics/cert_job.h):
 *     err_lower <= H(A, O) <= err_upper,
 * H the two-sided Hausdorff distance of the approximation to the untrimmed
 * exact offset, whatever the run's --metric.  The rows gain err_upper,
 * err_lower, certified (yes: err_upper <= tol) and cert_ns; the other
 * columns are the same as without --certify, bit for bit.
 *
 * Why after the driver and not inside it: the driver's decisions are taken
 * on one thread (the level engine) or under its lock (job_done); the
 * certificate costs tens of times the sampled measurement, so it runs as its
 * own parallel pass, every thread taking whole jobs, largest first.
 */
#ifndef OB_CERTIFY_H
#define OB_CERTIFY_H

#include <stddef.h>

#include "host/run/journal.h"

/* Whether job j is one --certify certifies: it has an approximation. */
int ob_certify_wants(const ob_job *j);

/* Purpose: certify every job of jobs that has an approximation and no
 *          certificate yet (a job restored by --resume brings its own).
 * Inputs:  mode: OB_CERTIFY_VERDICT (refined until the job is shown within
 *          its tol or over it: cert_job.h) or OB_CERTIFY_TIGHT (to rtol, 1e-3);
 *          samples: the run's samples per piece (--samples: the feet the
 *          certificate starts from); timeout_ns: --job-timeout (0:
 *          none): a certificate past it in thread time is stopped and has
 *          no verdict (cert_done OB_CERT_TIMEOUT, a warning naming the
 *          job; its row's err_upper, err_lower and certified empty, cert_ns
 *          the time it ran); spans: the jobs' span logs (the driver's hooks.spans), one per
 *          job; jr: the journal, or NULL: each certified job's row is added
 *          to it as it is done (rows of jobs with an approximation are held
 *          back from the journal until then: journal.h).
 * Outputs: each such job's cert_done, err_upper, err_lower, cert_ns;
 *          *seconds: the pass's wall time.
 * Returns: 0; 1 when a stop signal came (the jobs not yet certified keep
 *          cert_done 0); -1 after ob_error() when a job could not be
 *          certified (a refit that does not repeat the run, no memory, a
 *          journal that cannot be written): the others still are. */
int ob_certify_run(int samples, int mode, double timeout_ns, ob_job *jobs, size_t njobs, const ob_span_log *spans,
                   ob_journal *jr, double *seconds);

/* Purpose: ob_cert_opts.cancel for --job-timeout: nonzero once the calling
 *          thread's time (ob_thread_ns) is past ctx's deadline (ctx points
 *          to a double, the deadline in ns). */
int ob_certify_past_deadline(void *ctx);

#endif
