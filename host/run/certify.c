/*
 * certify.c - `run --certify` (see certify.h).
 */
#include "host/run/certify.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "host/diag.h"
#include "host/io/approx.h"
#include "host/run/clock.h"
#include "host/run/cert_progress.h"
#include "host/run/progress.h"
#include "host/run/signals.h"
#include "methods/metrics/cert_job.h"

int ob_certify_wants(const ob_job *j) { return j->status == OB_OK || j->status == OB_LIMIT; }

/* Job j's pieces, refitted from its span log, the base piece each
 * approximates, cut in floating point, and where that was cut from (the
 * certificate encloses the segment as stored: cert_curve.h) (malloc'd
 * arrays of a->n): 0, or -1 with the reason in why (*base, *src and *apx are
 * then freed, a is safe to free). */
static int job_pieces(const ob_job *j, const ob_span_log *log, ob_approx *a, ob_bez **base, ob_cert_src **src,
                      ob_bez **apx, double **hint, char *why, size_t len)
{
    ob_err err;
    *base = *apx = NULL;
    *src = NULL;
    if (ob_approx_from_job(j, log, a, &err) != 0) {
        snprintf(why, len, "%.180s", err.msg);
        return -1;
    }
    *base = malloc((size_t)(a->n + 1) * sizeof **base);
    *apx = malloc((size_t)(a->n + 1) * sizeof **apx);
    *src = malloc((size_t)(a->n + 1) * sizeof **src);
    *hint = malloc((size_t)(a->n + 1) * sizeof **hint);
    int rc = *base && *apx && *src && *hint ? 0 : -1;
    if (rc)
        snprintf(why, len, "out of memory");
    for (int k = 0, s = 0; k < a->n && rc == 0; k++) {
        const ob_apiece *p = &a->v[k];
        /* the pieces come in the log's order, each span's fit's pieces
         * together (host/io/approx.h): each has its span's error */
        while (s < log->n && !(log->v[s].seg == p->seg && log->v[s].a == p->a && log->v[s].b == p->b))
            s++;
        (*hint)[k] = s < log->n ? log->v[s].err : NAN;
        (*apx)[k] = p->approx;
        if (ob_apiece_base(j->curve, p, &(*base)[k]) == 0)
            (*src)[k] = (ob_cert_src){&j->curve->seg[p->seg], p->a, p->b, p->t0, p->t1};
        else {
            snprintf(why, len, "piece %d has no base piece", k + 1);
            rc = -1;
        }
    }
    if (rc) {
        free(*base), free(*apx), free(*src), free(*hint);
        *base = *apx = NULL;
        *src = NULL;
        *hint = NULL;
    }
    return rc;
}

int ob_certify_past_deadline(void *ctx) { return ob_thread_ns() > *(const double *)ctx; }

/* Job j's certificate (its cert_* fields) from its span log: 0, or -1 with
 * the reason in why.  timeout_ns > 0: one that runs past it in thread time
 * has no verdict (cert_done OB_CERT_TIMEOUT). */
static int certify_job(ob_job *j, const ob_span_log *log, int samples, int mode, double timeout_ns, char *why,
                       size_t len)
{
    ob_approx a = {0};
    ob_bez *base, *apx;
    ob_cert_src *src;
    double *hint;
    int rc = job_pieces(j, log, &a, &base, &src, &apx, &hint, why, len);
    if (rc == 0) {
        ob_cert_opts co;
        ob_cert_defaults(&co);
        co.decide = j->tol;  /* an enclosure that straddles tol is refined to a verdict where the budget allows */
        co.verdict = mode != OB_CERTIFY_TIGHT;  /* the verdict alone (cert_job.h), or tight to rtol */
        ob_cert_job cj;
        const double t0 = ob_thread_ns();
        double deadline = t0 + timeout_ns;  /* --job-timeout, in the certificate's own thread time */
        if (timeout_ns > 0)
            co.cancel = ob_certify_past_deadline, co.cancel_ctx = &deadline;
        /* the run's errors order a verdict's pieces (the largest first;
         * tight orders by its own sampling, as it always has) */
        const int crc = ob_certify_job_src(a.n, base, src, apx, j->d, samples, &co, co.verdict ? hint : NULL, &cj, NULL);
        j->cert_ns = ob_thread_ns() - t0;
        if (cj.cancelled) {  /* past --job-timeout: no verdict, never a wrong one */
            j->err_upper = j->err_lower = NAN;
            j->cert_done = OB_CERT_TIMEOUT;
        } else if (crc != 0 && cj.failed == 0) {  /* not an unbounded piece: no memory */
            snprintf(why, len, "out of memory");
            rc = -1;
        } else {
            j->err_upper = crc != 0 ? INFINITY : cj.upper;  /* a piece unbounded: the job is */
            j->err_lower = cj.lower;
            j->cert_done = OB_CERT_DONE;
        }
    }
    free(base);
    free(src);
    free(hint);
    free(apx);
    ob_approx_free(&a);
    return rc;
}

/* A job to certify and its sort key. */
typedef struct {
    size_t i;
    int segments;
} todo;

/* The most pieces first, then job order (a total order: qsort is stable here). */
static int todo_cmp(const void *a, const void *b)
{
    const todo *x = a, *y = b;
    if (x->segments != y->segments)
        return x->segments > y->segments ? -1 : 1;
    return (x->i > y->i) - (x->i < y->i);
}

/* The jobs to certify, the most pieces first (the longest certificates
 * start first, so that no thread is left alone with one at the end). */
static todo *certify_order(const ob_job *jobs, size_t njobs, size_t *n)
{
    todo *t = malloc((njobs ? njobs : 1) * sizeof *t);
    *n = 0;
    if (!t)
        return NULL;
    for (size_t i = 0; i < njobs; i++)
        if (ob_certify_wants(&jobs[i]) && !jobs[i].cert_done)
            t[(*n)++] = (todo){i, jobs[i].segments};
    qsort(t, *n, sizeof *t, todo_cmp);
    return t;
}

/* The pass's progress (cert_progress.h) over the jobs in idx's order: 0,
 * or -1 without memory. */
static int progress_init(ob_cert_progress *cp, const ob_job *jobs, const todo *idx, size_t n)
{
    if (ob_cert_progress_init(cp, n, omp_get_max_threads()) != 0)
        return -1;
    for (size_t k = 0; k < n; k++)
        ob_cert_progress_set(cp, k, &jobs[idx[k].i]);
    return 0;
}

int ob_certify_run(int samples, int mode, double timeout_ns, ob_job *jobs, size_t njobs, const ob_span_log *spans,
                   ob_journal *jr, double *seconds)
{
    const double start = ob_mono_s();
    *seconds = 0.0;
    size_t n;
    todo *idx = certify_order(jobs, njobs, &n);
    ob_cert_progress cp;
    if (!idx || progress_init(&cp, jobs, idx, n) != 0) {
        free(idx);
        ob_error("--certify: out of memory");
        return -1;
    }
    if (n)
        ob_info("certifying %zu jobs", n);
    samples = ob_clamp_samples(samples);
    int failed = 0, stopped = 0;
#pragma omp parallel for schedule(dynamic, 1)
    for (long k = 0; k < (long)n; k++) {
        int quit;
#pragma omp atomic read
        quit = stopped;
        if (quit || ob_stop_signal()) {
#pragma omp atomic write
            stopped = 1;
            continue;
        }
        ob_job *j = &jobs[idx[k].i];
        char why[200];
#pragma omp critical(ob_certify_report)
        ob_cert_progress_start(&cp, (size_t)k, ob_cert_progress_now(&cp));
        if (certify_job(j, &spans[idx[k].i], samples, mode, timeout_ns, why, sizeof why) != 0) {
#pragma omp critical(ob_certify_report)
            {
                ob_cert_progress_clear(&cp);
                ob_error("--certify: %s d=%g %s tol=%g: %s", j->curve->id, j->d, j->method->name, j->tol, why);
                failed = 1;
                ob_cert_progress_done(&cp, (size_t)k, j->cert_ns, ob_cert_progress_now(&cp));
            }
            continue;
        }
#pragma omp critical(ob_certify_report)
        {
            if (j->cert_done == OB_CERT_TIMEOUT) {
                ob_cert_progress_clear(&cp);
                ob_warn("--certify: %s d=%g %s tol=%g: the certificate passed --job-timeout (%g s of thread time): "
                        "no verdict (err_upper, err_lower and certified empty)",
                        j->curve->id, j->d, j->method->name, j->tol, 1e-9 * timeout_ns);
            }
            if (jr && !failed && ob_journal_add(jr, j) != 0) {
                ob_error("%s: cannot write: rows are no longer saved as jobs are certified", jr->path);
                failed = 1;
            }
            /* a long pass is not silent: "certified N/M jobs, X s elapsed, ETA Y s" */
            ob_cert_progress_done(&cp, (size_t)k, j->cert_ns, ob_cert_progress_now(&cp));
            ob_cert_progress_show(&cp);
        }
    }
    ob_cert_progress_end(&cp);
    free(idx);
    *seconds = ob_mono_s() - start;
    return failed ? -1 : stopped ? 1 : 0;
}
