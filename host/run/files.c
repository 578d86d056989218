/*
 * files.c - the files a run leaves in its directory (see files.h).
 */
#include <inttypes.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "host/io/columns.h"
#include "host/io/fsutil.h"
#include "host/io/output.h"
#include "host/run/files.h"
#include "host/run/journal.h"
#include "host/run/mpirun.h"
#include "host/run/shard.h"

static int write_samples_cb(FILE *f, void *ctx)
{
    const ob_run_files *r = ctx;
    return ob_write_samples(f, r->jobs, r->njobs, r->o->reps, r->rep_fit, r->rep_eval);
}

static int write_fits_cb(FILE *f, void *ctx)
{
    const ob_run_files *r = ctx;
    return ob_write_fits(f, r->jobs, r->njobs, r->o->fit_rounds, r->fit_round);
}

static int write_results_cb(FILE *f, void *ctx)
{
    const ob_run_files *r = ctx;
    return ob_write_results(f, r->jobs, r->njobs);
}

static int write_meta_cb(FILE *f, void *ctx)
{
    const ob_run_files *r = ctx;
    return ob_write_meta(f, r->o, r->rec, r->where, r->njobs, r->wall);
}

static int write_line_cb(FILE *f, void *ctx)
{
    fprintf(f, "%s\n", (const char *)ctx);
    return ferror(f) ? -1 : 0;
}

static int write_shard_cb(FILE *f, void *ctx)
{
    const ob_run_files *s = ctx;
    /* each job's index in the whole run and the hash of its key (shard.h),
     * for merge to check the rows of results.csv against the plan */
    fprintf(f, "job,key\n");
    for (size_t i = 0; i < s->njobs; i++)
        fprintf(f, "%zu,%016" PRIx64 "\n", s->shard_idx[i], ob_job_key_step(OB_FNV_BASIS, &s->jobs[i]));
    return ferror(f) ? -1 : 0;
}

typedef struct {
    const char *header, *body;
} text_out;

static int write_text_cb(FILE *f, void *ctx)
{
    const text_out *t = ctx;
    fprintf(f, "%s\n%s", t->header, t->body);
    return ferror(f) ? -1 : 0;
}

/* Text of one job's row (and samples) for the gather. */
static char *job_text(const ob_job *j, int reps, const double *fit, const double *eval, size_t stride)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return NULL;
    int rc = reps > 0 ? ob_write_job_samples(f, j, reps, fit, eval, stride) : ob_write_result_row(f, j);
    if (fclose(f) != 0 || rc != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

int ob_mpi_write_run_files(const ob_run_files *w, int drc)
{
    const ob_run_opts *o = w->o;
    const ob_job *jobs = w->jobs;
    const size_t njobs = w->njobs;
    char **rows = calloc(njobs ? njobs : 1, sizeof *rows), **smp = calloc(njobs ? njobs : 1, sizeof *smp);
    int ok = rows && smp && drc == 0;
    for (size_t i = 0; ok && i < njobs; i++) {
        rows[i] = job_text(&jobs[i], 0, NULL, NULL, 0);
        smp[i] = o->reps > 0 ? job_text(&jobs[i], o->reps, w->rep_fit + i, w->rep_eval + i, njobs) : strdup("");
        ok = rows[i] && smp[i];
    }
    char *res = NULL, *sam = NULL;
    int status = 1;
    if (ob_mpi_max(!ok) > 0) {
        ob_error("rank %d: %s", ob_mpi_rank(), ok ? "another rank failed" : "out of memory");
    } else if (ob_mpi_gather(rows, smp, w->shard_idx, njobs, w->rec->jobs_total, &res, &sam) != 0) {
        ob_error("rank %d: gathering the rows at rank 0 failed", ob_mpi_rank());
    } else if (ob_mpi_rank() == 0) {
        ob_run_files r = *w;
        r.jobs = NULL;
        r.njobs = w->rec->jobs_total;
        text_out rt = {ob_results_header(), res}, st = {OB_SAMPLES_HEADER, sam};
        ob_out_file set[3];
        size_t nset = 0;
        set[nset++] = (ob_out_file){"meta.json", write_meta_cb, &r};
        if (o->reps != 0)
            set[nset++] = (ob_out_file){"samples.csv", write_text_cb, &st};
        set[nset++] = (ob_out_file){"results.csv", write_text_cb, &rt};  /* last: see ob_write_set_atomically */
        const int written = ob_write_set_atomically(o->out_dir, set, nset) == 0;
        ob_info("%d ranks, %zu jobs in %.2f s: %s %s/results.csv", w->rec->mpi_ranks, w->rec->jobs_total,
                w->wall, written ? "wrote" : "could not write", o->out_dir);
        status = written ? 0 : 1;
    } else {
        status = 0;
    }
    status = (int)ob_mpi_max(status);
    for (size_t i = 0; i < njobs; i++) {
        if (rows)
            free(rows[i]);
        if (smp)
            free(smp[i]);
    }
    free(rows);
    free(smp);
    free(res);
    free(sam);
    return status;
}

int ob_write_run_files(const ob_run_files *r)
{
    const ob_run_opts *o = r->o;
    char *rfp = ob_resume_fingerprint(o, r->rec, r->where);
    if (!rfp) {
        ob_error("out of memory");
        return -1;
    }
    /* All or none: every file is written to a temporary first and renamed
     * only when all are complete, results.csv last, so a results.csv is
     * never there beside another run's fingerprint, meta.json, samples.csv
     * or shard.csv (ob_write_set_atomically; README "Output"). */
    ob_out_file outs[6];
    size_t nset = 0;
    outs[nset++] = (ob_out_file){"results.fingerprint", write_line_cb, rfp};
    if (o->reps != 0)
        outs[nset++] = (ob_out_file){"samples.csv", write_samples_cb, (void *)r};
    if (o->time_fits)
        outs[nset++] = (ob_out_file){"fits.csv", write_fits_cb, (void *)r};
    if (o->shard_n != 0)
        outs[nset++] = (ob_out_file){"shard.csv", write_shard_cb, (void *)r};
    outs[nset++] = (ob_out_file){"meta.json", write_meta_cb, (void *)r};
    outs[nset++] = (ob_out_file){"results.csv", write_results_cb, (void *)r};
    const int rc = ob_write_set_atomically(o->out_dir, outs, nset);
    free(rfp);
    return rc;
}

void ob_run_summary(const ob_run_files *r, int written)
{
    size_t cnt[OB_TIMEOUT + 1] = {0};
    for (size_t i = 0; i < r->njobs; i++)
        if (r->jobs[i].status <= OB_TIMEOUT)
            cnt[r->jobs[i].status]++;
    char timeouts[48] = "";
    if (cnt[OB_TIMEOUT])
        snprintf(timeouts, sizeof timeouts, ", timeout %zu", cnt[OB_TIMEOUT]);
    char cert[160] = "";
    if (r->o->certify) {  /* --certify: how many the certificate holds within tol */
        size_t yes = 0, done = 0, late = 0;
        for (size_t i = 0; i < r->njobs; i++)
            if (r->jobs[i].cert_done) {
                done++;
                yes += ob_job_certified(&r->jobs[i]);
                late += r->jobs[i].cert_done == OB_CERT_TIMEOUT;
            }
        char timed_out[48] = "";  /* past --job-timeout: no verdict */
        if (late)
            snprintf(timed_out, sizeof timed_out, "%zu timed out, ", late);
        snprintf(cert, sizeof cert, "; certified within tol %zu of %zu (%s%.2f s)", yes, done, timed_out,
                 r->rec->cert_seconds);
    }
    if (r->o->trimmed) {  /* --trimmed: how many jobs were measured against the trimmed offset */
        size_t done = 0, cut = 0;
        for (size_t i = 0; i < r->njobs; i++)
            done += r->jobs[i].trimmed_done != 0, cut += r->jobs[i].trimmed_done && r->jobs[i].trimmed_cut > 0;
        const size_t len = strlen(cert);
        snprintf(cert + len, sizeof cert - len, "; trimmed %zu, %zu with arcs cut (%.2f s)", done, cut,
                 r->rec->trim_seconds);
    }
    if (r->o->time_fits) {  /* --time-fits: how many jobs' fits were timed */
        size_t timed = 0;
        for (size_t i = 0; i < r->njobs; i++)
            timed += r->jobs[i].fit_calls > 0;
        const size_t len = strlen(cert);
        snprintf(cert + len, sizeof cert - len, "; fits timed %zu (%.2f s)", timed, r->rec->fit_seconds);
    }
    ob_info("%zu jobs in %.2f s (%d threads%s): ok %zu, limit %zu, fail %zu, skip %zu%s%s; %s %s/results.csv",
            r->njobs, r->wall, omp_get_max_threads(), r->o->reps > 0 ? ", median of the timed repetitions" : "",
            cnt[OB_OK], cnt[OB_LIMIT], cnt[OB_FAIL], cnt[OB_SKIP], timeouts, cert, written ? "wrote" : "could not write",
            r->o->out_dir);
}
