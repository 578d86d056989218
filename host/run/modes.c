/*
 * modes.c - the ways a run runs its jobs: once, journaled (resumable), with
 * timed repetitions (see modes.h).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "host/diag.h"
#include "host/run/certify.h"
#include "host/run/modes.h"
#include "host/run/progress.h"
#include "host/run/shard.h"
#include "host/run/spread.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Median of v[0], v[stride], ... (n values); sorts a copy in tmp. */
static double median_strided(const double *v, size_t stride, int n, double *tmp)
{
    for (int r = 0; r < n; r++)
        tmp[r] = v[(size_t)r * stride];
    qsort(tmp, (size_t)n, sizeof *tmp, cmp_double);
    return n % 2 ? tmp[n / 2] : 0.5 * (tmp[n / 2 - 1] + tmp[n / 2]);
}

static int same_result(const ob_job *a, const ob_job *b)
{
    return a->status == b->status && a->ctrl_points == b->ctrl_points && a->segments == b->segments &&
           a->out_degree == b->out_degree &&
           (a->max_err == b->max_err || (isnan(a->max_err) && isnan(b->max_err))) &&
           (a->max_gap == b->max_gap || (isnan(a->max_gap) && isnan(b->max_gap))) &&
           a->continuity == b->continuity;
}

int ob_run_plain(const ob_run_ctx *c, ob_job *jobs, size_t njobs, const char *what, double *wall)
{
    ob_driver_hooks h = c->hooks;
    if (what)
        ob_info("%s", what);
    ob_progress bar;
    ob_progress_init(&bar);
    h.progress = ob_progress_cb;
    h.progress_ctx = &bar;
    h.stats = &c->rec->engine;
    double t0 = now_s();
    int rc = ob_driver_run(jobs, njobs, &c->o->driver, &h);
    *wall = now_s() - t0;
    ob_progress_end(&bar);
    return rc;
}

int ob_run_reps(const ob_run_ctx *c, ob_job *jobs, size_t njobs, double *fit, double *eval, double *wall)
{
    const int reps = c->o->reps;
    ob_job *ref = malloc(njobs * sizeof *ref);
    double *walls = malloc((size_t)reps * sizeof *walls), *tmp = malloc((size_t)reps * sizeof *tmp);
    double *tot = malloc((size_t)reps * sizeof *tot);
    int rc = 0;
    if (!ref || !walls || !tmp || !tot) {
        rc = -1;
        goto out;
    }
    memcpy(ref, jobs, njobs * sizeof *ref);
    for (int r = 0; r < reps && rc == 0; r++) {
        char what[64];
        snprintf(what, sizeof what, "timed repetition %d of %d", r + 1, reps);
        rc = ob_run_plain(c, jobs, njobs, what, &walls[r]);
        ob_loadavg_sample(&c->rec->load);
        for (size_t i = 0; i < njobs; i++) {
            fit[(size_t)r * njobs + i] = jobs[i].fit_ns;
            eval[(size_t)r * njobs + i] = jobs[i].eval_ns;
            if (!same_result(&jobs[i], &ref[i])) {
                if (c->rec->rep_mismatches++ < 5)
                    ob_warn("repetition %d of %s d=%g %s tol=%g differs from the "
                            "warm-up (%s, %ld points vs %s, %ld): nondeterministic", r + 1, jobs[i].curve->id,
                            jobs[i].d, jobs[i].method->name, jobs[i].tol, ob_status_name(jobs[i].status),
                            jobs[i].ctrl_points, ob_status_name(ref[i].status), ref[i].ctrl_points);
            }
        }
    }
    memcpy(jobs, ref, njobs * sizeof *ref);
    if (rc == 0) {
        for (size_t i = 0; i < njobs; i++) {
            jobs[i].fit_ns = median_strided(fit + i, njobs, reps, tmp);
            jobs[i].eval_ns = median_strided(eval + i, njobs, reps, tmp);
            for (int r = 0; r < reps; r++)
                tot[r] = fit[(size_t)r * njobs + i] + eval[(size_t)r * njobs + i];
            jobs[i].time_reps = reps;
            ob_spread(tot, reps, 1, tmp, &jobs[i].time_iqr_ns, &jobs[i].time_cv);
        }
        *wall = median_strided(walls, 1, reps, tmp);
    }
    if (c->rec->rep_mismatches > 0)
        ob_warn("%ld job results differed between repetitions", c->rec->rep_mismatches);
out:
    free(ref);
    free(walls);
    free(tmp);
    free(tot);
    return rc;
}

typedef struct {
    ob_journal *jr;
    const ob_job *jobs;
    int failed;
    int certify;  /* --certify: a job with an approximation is journaled once certified (certify.h) */
    ob_run_record *rec;  /* its backend noted with the first row (backends.h) */
    const char *dir;
    int noted;
} journal_ctx;

static void journal_job_done(void *ctx, size_t i)
{
    journal_ctx *c = ctx;
    char why[4400];
    if (c->certify && ob_certify_wants(&c->jobs[i]))
        return;
    if (!c->noted && (c->noted = 1) && ob_backends_note(c->dir, &c->rec->binfo, &c->rec->backends, why, sizeof why))
        ob_warn("%s: meta.json's \"backends\" may miss this run's backend", why);
    if (!c->failed && ob_journal_add(c->jr, &c->jobs[i]) != 0) {
        c->failed = 1;
        ob_error("%s: cannot write: rows are no longer saved as jobs finish", c->jr->path);
    }
}

int ob_run_journaled(const ob_run_ctx *c, ob_job *jobs, size_t njobs, const char *where, ob_journal *jr, double *wall,
                     size_t *restored_n)
{
    const ob_run_opts *o = c->o;
    ob_driver_hooks h = c->hooks;
    ob_err err;
    ob_res_table prev;
    char *fp = ob_resume_fingerprint(o, c->rec, where);
    size_t *idx = malloc((njobs ? njobs : 1) * sizeof *idx);
    ob_job *pend = malloc((njobs ? njobs : 1) * sizeof *pend);
    int rc = 2;
    *restored_n = 0;
    if (!fp || !idx || !pend) {
        ob_error("out of memory");
        memset(&prev, 0, sizeof prev);
        goto out;
    }
    if (ob_journal_open(jr, o->out_dir, fp, o->resume_dir != NULL, &prev, &err) != 0) {
        ob_error("%s", err.msg);
        goto out;
    }
    if (ob_backends_load(o->out_dir, o->resume_dir != NULL, &c->rec->backends, err.msg, sizeof err.msg) != 0)
        ob_warn("%s: meta.json's \"backends\" lists only this run's", err.msg);
    size_t np = 0;
    for (size_t i = 0; i < njobs; i++) {
        ob_job *j = &jobs[i];
        const ob_res_row key = {.curve = j->curve->id, .method = j->method->name,
                                .metric = ob_metric_name(j->metric), .split = ob_split_name(j->split), .d = j->d,
                                .tol = j->tol};
        const ob_res_row *row = prev.n ? ob_res_find(&prev, &key) : NULL;
        /* with --certify a row is restored only with its certificate (a
         * run stopped before it was certified reruns the job) */
        if (row && ob_job_from_row(j, row) == 0 && !(o->certify && ob_certify_wants(j) && !j->cert_done)) {
            ++*restored_n;
            if (jr->from_results && ob_journal_add(jr, j) != 0) {
                ob_error("%s: cannot write", jr->path);
                goto out;
            }
        } else {
            *j = (ob_job){.curve = j->curve, .d = j->d, .method = j->method, .params = j->params,
                          .test_fit_repeat = j->test_fit_repeat, .metric = j->metric, .split = j->split,
                          .tol = j->tol};  /* the inputs only: a row read back but not restored leaves nothing */
            idx[np] = i;
            pend[np++] = *j;
        }
    }
    if (*restored_n)
        ob_info("resuming %s: %zu of %zu jobs restored, %zu to run", o->out_dir, *restored_n,
                njobs, np);
    journal_ctx jc = {jr, pend, 0, o->certify, c->rec, o->out_dir, 0};
    h.job_done = journal_job_done;
    h.job_done_ctx = &jc;
    /* the driver runs pend: its span logs are pend's, put back at the jobs' places after */
    ob_span_log *logs = h.spans && np ? calloc(np, sizeof *logs) : NULL;
    if (h.spans && np && !logs) {
        rc = -1;  /* the caller says: out of memory */
        goto out;
    }
    h.spans = logs;
    ob_run_ctx cj = *c;
    cj.hooks = h;
    rc = ob_run_plain(&cj, pend, np, NULL, wall);
    for (size_t k = 0; k < np; k++) {
        jobs[idx[k]] = pend[k];
        if (logs) {
            free(c->hooks.spans[idx[k]].v);
            c->hooks.spans[idx[k]] = logs[k];
        }
    }
    free(logs);
out:
    ob_res_free(&prev);
    free(fp);
    free(idx);
    free(pend);
    return rc;
}
