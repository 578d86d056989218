/*
 * cmd_run.c - `./offbench run`: load curves, plan the jobs (curve x d x method
 * x tol, in that nesting), run the driver, write results.csv and meta.json.
 */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "host/io/columns.h"
#include "host/backend/clrt.h"
#include "host/cli/commands.h"
#include "host/io/curvefile.h"
#include "host/io/datadir.h"
#include "host/diag.h"
#include "host/run/journal.h"
#include "host/run/mpirun.h"
#include "methods/core/offdeg.h"
#include "host/run/shard.h"
#include "host/run/options.h"
#include "host/io/output.h"
#include "host/run/progress.h"
#include "host/io/random.h"

typedef struct {
    const ob_job *jobs;
    size_t njobs;
    const ob_run_opts *o;
    const char *data;
    double wall;
    const double *rep_fit, *rep_eval;  /* --reps: reps x njobs timings */
} run_out;

static int write_samples_cb(FILE *f, void *ctx)
{
    run_out *r = ctx;
    return ob_write_samples(f, r->jobs, r->njobs, r->o->reps, r->rep_fit, r->rep_eval);
}

static int write_results_cb(FILE *f, void *ctx)
{
    run_out *r = ctx;
    return ob_write_results(f, r->jobs, r->njobs);
}

static int write_meta_cb(FILE *f, void *ctx)
{
    run_out *r = ctx;
    return ob_write_meta(f, r->o, r->data, r->njobs, r->wall);
}

int ob_load_run_curves(const ob_run_opts *o, ob_curveset *set, char *where, size_t wlen)
{
    char err[1024];
    int rc = 0;
    where[0] = '\0';
    if (o->curves_file) {
        snprintf(where, wlen, "%s", o->curves_file);
        rc = ob_curves_load_file(o->curves_file, set, err, sizeof err);
    } else if (o->random_n == 0) {
        rc = ob_load_default_curves(set, where, wlen, err, sizeof err);
    }
    if (rc == 0 && o->random_n > 0) {
        size_t k = strlen(where);
        snprintf(where + k, wlen - k, "%srandom %ld:%" PRIu64, k ? " + " : "", o->random_n, o->random_seed);
        /* with --curve, only the selected random curves are generated */
        rc = ob_random_append(set, o->random_seed, o->random_n, o->curve_ids, o->ncurve_ids, err, sizeof err);
    }
    if (rc != 0) {
        ob_error("%s", err);
        return -1;
    }
    for (int i = 0; i < o->ncurve_ids; i++)
        if (ob_curveset_find(set, o->curve_ids[i]) < 0) {
            ob_error("--curve: no curve '%s' in %s (see './offbench list curves')", o->curve_ids[i], where);
            return -1;
        }
    return 0;
}

static int selected(const ob_run_opts *o, const char *id)
{
    if (!o->curve_ids)
        return 1;
    for (int i = 0; i < o->ncurve_ids; i++)
        if (strcmp(o->curve_ids[i], id) == 0)
            return 1;
    return 0;
}

static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; i++) {
        h ^= c[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* FNV-1a over the content of the curves the run uses (id, segments' degrees
 * and homogeneous control points, offsets): a resume of a run whose curve
 * file changed is refused (journal.h). */
static uint64_t curves_hash(const ob_run_opts *o, const ob_curveset *set)
{
    uint64_t h = 14695981039346656037ull;
    for (int c = 0; c < set->n; c++) {
        const ob_curve *cv = &set->v[c];
        if (!selected(o, cv->id))
            continue;
        h = fnv1a(h, cv->id, strlen(cv->id) + 1);
        h = fnv1a(h, &cv->nseg, sizeof cv->nseg);
        for (int s = 0; s < cv->nseg; s++) {
            h = fnv1a(h, &cv->seg[s].deg, sizeof cv->seg[s].deg);
            h = fnv1a(h, cv->seg[s].h, (size_t)(cv->seg[s].deg + 1) * sizeof cv->seg[s].h[0]);
        }
        h = fnv1a(h, &cv->nd, sizeof cv->nd);
        h = fnv1a(h, cv->d, (size_t)cv->nd * sizeof *cv->d);
    }
    return h;
}

static int write_line_cb(FILE *f, void *ctx)
{
    fprintf(f, "%s\n", (const char *)ctx);
    return ferror(f) ? -1 : 0;
}

/* A fresh run owns its directory: the files of an earlier run there go
 * (a journal only with --force: without it the run was refused before). */
static void remove_stale(const char *dir)
{
    static const char *const names[] = {"results.csv", "meta.json", "samples.csv", "shard.csv",
                                        "results.fingerprint", "results.journal.csv"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char p[4200];
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        remove(p);
    }
}

static ob_job *plan_jobs(const ob_run_opts *o, const ob_curveset *set, size_t *njobs)
{
    size_t n = 0;
    for (int c = 0; c < set->n; c++)
        if (selected(o, set->v[c].id))
            n += (size_t)set->v[c].nd * (size_t)o->nmethods * (size_t)o->ntols;
    ob_job *jobs = calloc(n ? n : 1, sizeof *jobs);
    if (!jobs)
        return NULL;
    size_t k = 0;
    for (int c = 0; c < set->n; c++) {
        if (!selected(o, set->v[c].id))
            continue;
        for (int di = 0; di < set->v[c].nd; di++)
            for (int m = 0; m < o->nmethods; m++)
                for (int t = 0; t < o->ntols; t++) {
                    ob_job *j = &jobs[k++];
                    j->curve = &set->v[c];
                    j->d = set->v[c].d[di];
                    j->method = o->methods[m];
                    j->params = o->params + ob_method_index(o->methods[m]) * OB_MAX_PARAMS;
                    j->metric = o->metric;
                    j->split = o->split;
                    j->tol = o->tols[t];
                }
    }
    *njobs = n;
    return jobs;
}

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

/* One driver run with its progress bar; returns the driver's status and the
 * wall time in *wall. */
static int run_once(ob_job *jobs, size_t njobs, ob_run_opts *o, const char *what, double *wall)
{
    ob_progress bar;
    ob_progress_init(&bar);
    if (what)
        ob_info("%s", what);
    o->driver.progress = ob_progress_cb;
    o->driver.progress_ctx = &bar;
    double t0 = now_s();
    int rc = ob_driver_run(jobs, njobs, &o->driver);
    *wall = now_s() - t0;
    ob_progress_end(&bar);
    o->driver.progress = NULL;
    o->driver.progress_ctx = NULL;
    return rc;
}

/* --reps N: the first run is the warm-up (its results are the run's); then N
 * timed runs, whose per-job timings go to fit/eval (N x njobs, rep-major) and
 * whose medians replace the jobs' timing columns.  A timed run whose results
 * differ from the warm-up's is nondeterminism: counted in o->rep_mismatches
 * and said on stderr; the warm-up's results are kept.  *wall becomes the
 * median wall time of the timed runs.  Returns 0, or -1 (out of memory). */
static int run_reps(ob_job *jobs, size_t njobs, ob_run_opts *o, double *fit, double *eval, double *wall)
{
    const int reps = o->reps;
    ob_job *ref = malloc(njobs * sizeof *ref);
    double *walls = malloc((size_t)reps * sizeof *walls), *tmp = malloc((size_t)reps * sizeof *tmp);
    int rc = 0;
    if (!ref || !walls || !tmp) {
        rc = -1;
        goto out;
    }
    memcpy(ref, jobs, njobs * sizeof *ref);
    for (int r = 0; r < reps && rc == 0; r++) {
        char what[64];
        snprintf(what, sizeof what, "timed repetition %d of %d", r + 1, reps);
        rc = run_once(jobs, njobs, o, what, &walls[r]);
        for (size_t i = 0; i < njobs; i++) {
            fit[(size_t)r * njobs + i] = jobs[i].fit_ns;
            eval[(size_t)r * njobs + i] = jobs[i].eval_ns;
            if (!same_result(&jobs[i], &ref[i])) {
                if (o->rep_mismatches++ < 5)
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
        }
        *wall = median_strided(walls, 1, reps, tmp);
    }
    if (o->rep_mismatches > 0)
        ob_warn("%ld job results differed between repetitions", o->rep_mismatches);
out:
    free(ref);
    free(walls);
    free(tmp);
    return rc;
}

/* --shard K/N: keep the jobs of shard K (in job order); *idx gets their
 * indices in the whole run's job list.  0, or -1 after ob_error(). */
static int select_shard(const ob_run_opts *o, ob_job **jobs, size_t *njobs, size_t **idx)
{
    int *of = malloc((*njobs ? *njobs : 1) * sizeof *of);
    *idx = malloc((*njobs ? *njobs : 1) * sizeof **idx);
    if (!of || !*idx || ob_shard_assign(*jobs, *njobs, o->shard_n, of) != 0) {
        free(of);
        ob_error("out of memory");
        return -1;
    }
    size_t n = 0;
    for (size_t i = 0; i < *njobs; i++)
        if (of[i] == o->shard_k) {
            (*jobs)[n] = (*jobs)[i];
            (*idx)[n++] = i;
        }
    free(of);
    *njobs = n;
    return 0;
}

typedef struct {
    const size_t *idx;
    size_t n;
    const ob_job *jobs;
} shard_out;

static int write_shard_cb(FILE *f, void *ctx)
{
    const shard_out *s = ctx;
    /* each job's index in the whole run and the hash of its key (shard.h),
     * for merge to check the rows of results.csv against the plan */
    fprintf(f, "job,key\n");
    for (size_t i = 0; i < s->n; i++)
        fprintf(f, "%zu,%016" PRIx64 "\n", s->idx[i], ob_job_key_step(OB_FNV_BASIS, &s->jobs[i]));
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

/* Under mpirun: every rank sends its rows to rank 0, which writes the files
 * of the whole run.  Returns the exit status (the same on every rank). */
static int mpi_write(const ob_job *jobs, size_t njobs, const size_t *idx, ob_run_opts *o, const char *where,
                     double wall, int drc, const double *rep_fit, const double *rep_eval)
{
    char **rows = calloc(njobs ? njobs : 1, sizeof *rows), **smp = calloc(njobs ? njobs : 1, sizeof *smp);
    int ok = rows && smp && drc == 0;
    for (size_t i = 0; ok && i < njobs; i++) {
        rows[i] = job_text(&jobs[i], 0, NULL, NULL, 0);
        smp[i] = o->reps > 0 ? job_text(&jobs[i], o->reps, rep_fit + i, rep_eval + i, njobs) : strdup("");
        ok = rows[i] && smp[i];
    }
    char *res = NULL, *sam = NULL;
    int status = 1;
    if (ob_mpi_max(!ok) > 0) {
        ob_error("rank %d: %s", ob_mpi_rank(), ok ? "another rank failed" : "out of memory");
    } else if (ob_mpi_gather(rows, smp, idx, njobs, o->jobs_total, &res, &sam) != 0) {
        ob_error("rank %d: gathering the rows at rank 0 failed", ob_mpi_rank());
    } else if (ob_mpi_rank() == 0) {
        run_out r = {NULL, o->jobs_total, o, where, wall, NULL, NULL};
        text_out rt = {ob_results_header(), res}, st = {OB_SAMPLES_HEADER, sam};
        ob_out_file set[3];
        size_t nset = 0;
        set[nset++] = (ob_out_file){"meta.json", write_meta_cb, &r};
        if (o->reps != 0)
            set[nset++] = (ob_out_file){"samples.csv", write_text_cb, &st};
        set[nset++] = (ob_out_file){"results.csv", write_text_cb, &rt};  /* last: see ob_write_set_atomically */
        const int written = ob_write_set_atomically(o->out_dir, set, nset) == 0;
        ob_info("%d ranks, %zu jobs in %.2f s: %s %s/results.csv", o->mpi_ranks, o->jobs_total,
                wall, written ? "wrote" : "could not write", o->out_dir);
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

/* SIGINT / SIGTERM: the driver stops at the next batch; a second signal
 * acts as usual (SA_RESETHAND). */
static volatile sig_atomic_t stop_signal = 0;

static void on_stop_signal(int sig)
{
    stop_signal = sig;
}

static void catch_stop_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sa.sa_flags = SA_RESETHAND | SA_RESTART;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

typedef struct {
    ob_journal *jr;
    const ob_job *jobs;
    int failed;
} journal_ctx;

static void journal_job_done(void *ctx, size_t i)
{
    journal_ctx *c = ctx;
    if (!c->failed && ob_journal_add(c->jr, &c->jobs[i]) != 0) {
        c->failed = 1;
        ob_error("%s: cannot write: rows are no longer saved as jobs finish", c->jr->path);
    }
}

/* The run without repetitions: rows saved to the journal as jobs finish;
 * with --resume, the jobs the journal (or a finished results.csv) already
 * has are restored instead of run.  Returns the driver's status (1: stopped
 * by a signal), or 2 when the journal cannot be used (said through
 * ob_error()).  *restored_n: how many jobs were restored. */
static int run_journaled(ob_job *jobs, size_t njobs, ob_run_opts *o, const char *where, ob_journal *jr,
                         double *wall, size_t *restored_n)
{
    char err[1024];
    ob_res_table prev;
    char *fp = ob_resume_fingerprint(o, where);
    size_t *idx = malloc((njobs ? njobs : 1) * sizeof *idx);
    ob_job *pend = malloc((njobs ? njobs : 1) * sizeof *pend);
    int rc = 2;
    *restored_n = 0;
    if (!fp || !idx || !pend) {
        ob_error("out of memory");
        memset(&prev, 0, sizeof prev);
        goto out;
    }
    if (ob_journal_open(jr, o->out_dir, fp, o->resume_dir != NULL, &prev, err, sizeof err) != 0) {
        ob_error("%s", err);
        goto out;
    }
    size_t np = 0;
    for (size_t i = 0; i < njobs; i++) {
        ob_job *j = &jobs[i];
        const ob_res_row key = {.curve = j->curve->id, .method = j->method->name,
                                .metric = ob_metric_name(j->metric), .split = ob_split_name(j->split), .d = j->d,
                                .tol = j->tol};
        const ob_res_row *row = prev.n ? ob_res_find(&prev, &key) : NULL;
        if (row && ob_job_from_row(j, row) == 0) {
            ++*restored_n;
            if (jr->from_results && ob_journal_add(jr, j) != 0) {
                ob_error("%s: cannot write", jr->path);
                goto out;
            }
        } else {
            idx[np] = i;
            pend[np++] = *j;
        }
    }
    if (*restored_n)
        ob_info("resuming %s: %zu of %zu jobs restored, %zu to run", o->out_dir, *restored_n,
                njobs, np);
    journal_ctx jc = {jr, pend, 0};
    o->driver.job_done = journal_job_done;
    o->driver.job_done_ctx = &jc;
    o->driver.stop = &stop_signal;
    rc = run_once(pend, np, o, NULL, wall);
    o->driver.job_done = NULL;
    o->driver.job_done_ctx = NULL;
    for (size_t k = 0; k < np; k++)
        jobs[idx[k]] = pend[k];
out:
    ob_res_free(&prev);
    free(fp);
    free(idx);
    free(pend);
    return rc;
}

/* --backend: opencl must work (exit 2 with the reason otherwise), auto uses it
 * when it works and says why not in meta.json, cpu never tries.  The kernel
 * is built here, once, before any timed work. */
int ob_open_backend(ob_run_opts *o, ob_cl **cl)
{
    ob_backend_info *b = &o->binfo;
    if (o->backend == OB_BACKEND_CPU) {
        snprintf(b->why_cpu, sizeof b->why_cpu, "--backend cpu");
        return 0;
    }
    char err[8192];
    if (ob_cl_open(o->device, cl, err, sizeof err) != 0) {
        if (o->backend == OB_BACKEND_OPENCL || o->device) {
            ob_error("--backend opencl: %s", err);
            return -1;
        }
        snprintf(b->why_cpu, sizeof b->why_cpu, "%.500s", err);
        return 0;
    }
    b->opencl = 1;
    snprintf(b->platform, sizeof b->platform, "%s", ob_cl_platform(*cl));
    snprintf(b->device, sizeof b->device, "%s", ob_cl_device(*cl));
    snprintf(b->driver, sizeof b->driver, "%s", ob_cl_driver(*cl));
    snprintf(b->kernels, sizeof b->kernels, "%s", ob_cl_source(*cl));
    b->build_seconds = ob_cl_build_seconds(*cl);
    o->driver.batch = ob_cl_measure_batch;
    o->driver.batch_ctx = *cl;
    o->driver.batch_fallbacks = &b->fallbacks;
    ob_info("OpenCL %s / %s, kernels from %s built in %.2f s", b->platform, b->device,
            b->kernels, b->build_seconds);
    return 0;
}

int ob_cmd_run(int argc, char **argv, int full_argc, char **full_argv)
{
    ob_run_opts o;
    ob_curveset set = {0};
    ob_job *jobs = NULL;
    ob_cl *cl = NULL;
    double *rep_fit = NULL, *rep_eval = NULL;
    size_t *shard_idx = NULL;
    ob_journal journal;
    memset(&journal, 0, sizeof journal);
    int lock_fd = -1;
    int status = 2;
    const int prc = ob_run_opts_parse(argc, argv, &o);
    if (prc != OB_CLI_OK) {
        status = prc == OB_CLI_HELP ? 0 : 2;
        goto done;
    }
    o.argc = full_argc;
    o.argv = full_argv;
    {
        const char *oom = getenv("OFFBENCH_TEST_OOM_AFTER");  /* test hook (driver.h) */
        if (oom && *oom)
            o.driver.test_oom_after = strtol(oom, NULL, 10);
    }
    const int ranks = ob_mpi_size();
    if (ranks > 1) {  /* every rank sees the same arguments: they all stop here alike */
        if (o.shard_n > 0 || o.resume_dir) {
            ob_error("under mpirun the ranks split the run: --shard and --resume do not apply");
            goto done;
        }
        o.shard_k = ob_mpi_rank();
        o.shard_n = ranks;
        o.mpi_ranks = ranks;
    }
    char where[4096];
    if (ob_load_run_curves(&o, &set, where, sizeof where) != 0)
        goto done;
    if (o.threads > 0)
        omp_set_num_threads(o.threads);
    /* the exact offset degree of every curve the run uses, once per curve */
#pragma omp parallel for schedule(dynamic, 1)
    for (int c = 0; c < set.n; c++) {
        ob_curve *cv = &set.v[c];
        char msg[160];
        if (selected(&o, cv->id) &&
            ob_curve_offset_degree(cv, &cv->offset_degree, &cv->offset_rational, msg, sizeof msg) == 0)
            cv->offset_known = 1;
    }
    size_t njobs = 0;
    jobs = plan_jobs(&o, &set, &njobs);
    if (!jobs) {
        ob_error("out of memory planning the jobs");
        status = 1;
        goto done;
    }
    if (njobs == 0) {
        ob_error("no jobs: the selected curves have no offsets");
        goto done;
    }
    {
        char *fp = ob_run_fingerprint(&o, where);
        if (!fp) {
            ob_error("out of memory");
            status = 1;
            goto done;
        }
        o.jobs_total = njobs;
        o.plan_hash = ob_plan_hash(jobs, njobs, fp);
        o.plan_seed = ob_plan_seed(fp);
        free(fp);
    }
    o.data_hash = curves_hash(&o, &set);
    if (ranks > 1 && !ob_mpi_all_equal(o.plan_hash)) {
        ob_error("rank %d: the ranks were started with other arguments or data (plan hash differs)", ob_mpi_rank());
        goto done;
    }
    if (o.shard_n > 0) {
        if (select_shard(&o, &jobs, &njobs, &shard_idx) != 0) {
            status = 1;
            goto done;
        }
        ob_info("%s %d/%d: %zu of %zu jobs", ranks > 1 ? "rank" : "shard", o.shard_k, o.shard_n,
                njobs, o.jobs_total);
    }
    if (ob_open_backend(&o, &cl) != 0)
        goto done;
    /* Only now, when the run can start, is the directory created and taken:
     * under MPI only rank 0 writes; the ranks learn together that it can. */
    {
        int dirfail = 0;
        if (ob_mpi_rank() == 0) {
            char err[8400];
            struct stat st;
            int lrc = 0;
            const char *const inputs[] = {o.curves_file};
            if (ob_check_out_not_input("run", o.out_dir, 1, inputs, 1) != 0) {
                dirfail = 2;  /* the curve file would sit among (or be) the run's outputs */
            } else if (o.resume_dir && stat(o.out_dir, &st) != 0) {
                ob_error("--resume: %s does not exist: nothing to resume", o.out_dir);
                dirfail = 2;
            } else if (!o.resume_dir && ob_mkdir_p(o.out_dir) != 0) {
                ob_error("--out: cannot create '%s': %s", o.out_dir, strerror(errno));
                dirfail = 1;
            } else if ((lrc = ob_lock_dir(o.out_dir, &lock_fd, err, sizeof err)) != 0) {
                ob_error("%s", err);
                dirfail = lrc == -2 ? 2 : 1;
            } else if (!o.resume_dir) {
                char jp[4200];
                snprintf(jp, sizeof jp, "%s/results.journal.csv", o.out_dir);
                if (!o.force && stat(jp, &st) == 0) {
                    ob_error("%s holds an interrupted run (%s): finish it with --resume %s, choose another --out, "
                             "or add --force to discard it and start afresh", o.out_dir, jp, o.out_dir);
                    dirfail = 2;
                } else {
                    remove_stale(o.out_dir);
                }
            }
        }
        const long worst = ob_mpi_max(dirfail);
        if (worst > 0) {
            status = worst == 2 ? 2 : 1;
            goto done;
        }
    }
    double wall = 0.0;
    size_t restored = 0;
    catch_stop_signals();
    o.driver.stop = &stop_signal;
    int drc = o.reps > 0 || ranks > 1 ? run_once(jobs, njobs, &o, o.reps > 0 ? "warm-up run" : NULL, &wall)
                                      : run_journaled(jobs, njobs, &o, where, &journal, &wall, &restored);
    if (ranks > 1 && ob_mpi_max(drc == 1) > 0 && drc != 1) {
        drc = 1;  /* another rank was stopped: none writes */
        stop_signal = stop_signal ? stop_signal : SIGTERM;
    }
    if (drc == 2)
        goto done;
    if (drc == 1) {
        ob_journal_close(&journal, 0);
        if (o.reps > 0)
            ob_error("interrupted by signal %d: nothing written (a run with --reps cannot be resumed)",
                     (int)stop_signal);
        else
            ob_error("interrupted by signal %d: the finished jobs' rows are in %s; run the same command with "
                     "--resume %s to finish", (int)stop_signal, journal.path, o.out_dir);
        status = 128 + (int)stop_signal;
        goto done;
    }
    if (drc == 0 && o.reps > 0) {
        rep_fit = malloc((size_t)o.reps * njobs * sizeof *rep_fit);
        rep_eval = malloc((size_t)o.reps * njobs * sizeof *rep_eval);
        drc = !rep_fit || !rep_eval ? -1 : run_reps(jobs, njobs, &o, rep_fit, rep_eval, &wall);
    }
    if (ranks > 1) {
        ob_info("rank %d: %zu jobs in %.2f s", ob_mpi_rank(), njobs, wall);
        status = mpi_write(jobs, njobs, shard_idx, &o, where, ob_mpi_max(wall), drc, rep_fit, rep_eval);
        goto done;
    }
    if (drc != 0) {
        /* jobs that never ran are no results: nothing is written, the
         * journal (if any) keeps the finished jobs' rows */
        ob_journal_close(&journal, 0);
        if (o.reps > 0)
            ob_error("ran out of memory: nothing written");
        else
            ob_error("ran out of memory before every job had run: nothing written; the finished jobs' rows are in "
                     "%s; --resume %s runs the others", journal.path, o.out_dir);
        status = 1;
        goto done;
    }
    char *rfp = ob_resume_fingerprint(&o, where);
    if (!rfp) {
        ob_error("out of memory");
        status = 1;
        goto done;
    }
    run_out r = {jobs, njobs, &o, where, wall, rep_fit, rep_eval};
    /* All or none: every file is written to a temporary first and renamed
     * only when all are complete, results.csv last, so a results.csv is
     * never there beside another run's fingerprint, meta.json, samples.csv
     * or shard.csv (ob_write_set_atomically; README "Output"). */
    shard_out so = {shard_idx, njobs, jobs};
    ob_out_file outs[5];
    size_t nset = 0;
    outs[nset++] = (ob_out_file){"results.fingerprint", write_line_cb, rfp};
    if (o.reps != 0 && drc == 0)
        outs[nset++] = (ob_out_file){"samples.csv", write_samples_cb, &r};
    if (o.shard_n != 0)
        outs[nset++] = (ob_out_file){"shard.csv", write_shard_cb, &so};
    outs[nset++] = (ob_out_file){"meta.json", write_meta_cb, &r};
    outs[nset++] = (ob_out_file){"results.csv", write_results_cb, &r};
    const int written = ob_write_set_atomically(o.out_dir, outs, nset) == 0;
    free(rfp);
    status = written ? 0 : 1;
    ob_journal_close(&journal, written);  /* results.csv has every row now */
    size_t cnt[OB_TIMEOUT + 1] = {0};
    for (size_t i = 0; i < njobs; i++)
        if (jobs[i].status <= OB_TIMEOUT)
            cnt[jobs[i].status]++;
    char timeouts[48] = "";
    if (cnt[OB_TIMEOUT])
        snprintf(timeouts, sizeof timeouts, ", timeout %zu", cnt[OB_TIMEOUT]);
    ob_info("%zu jobs in %.2f s (%d threads%s): ok %zu, limit %zu, fail %zu, skip %zu%s; %s %s/results.csv",
            njobs, wall, omp_get_max_threads(), o.reps > 0 ? ", median of the timed repetitions" : "", cnt[OB_OK],
            cnt[OB_LIMIT], cnt[OB_FAIL], cnt[OB_SKIP], timeouts, written ? "wrote" : "could not write", o.out_dir);
done:
    ob_journal_close(&journal, 0);
    if (lock_fd >= 0)
        close(lock_fd);  /* the lock goes with it */
    ob_cl_close(cl);
    free(rep_fit);
    free(rep_eval);
    free(shard_idx);
    free(jobs);
    ob_curveset_free(&set);
    ob_run_opts_free(&o);
    return status;
}
