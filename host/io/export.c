/*
 * export.c - the files of `--export DIR` (export.h): per job, and for a run.
 */
#include "host/io/export.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "host/io/export_dir.h"
#include "host/io/fsutil.h"
#include "host/diag.h"
#include "host/io/numfmt.h"
#include "host/io/outfile.h"
#include "host/run/signals.h"

void ob_export_stem(char *buf, size_t len, const ob_job *j)
{
    char id[sizeof j->curve->id], d[40], tol[40];
    snprintf(id, sizeof id, "%s", j->curve->id);
    for (char *p = id; *p; p++)
        if (*p == '/')
            *p = '~';
    ob_fmt_double(d, sizeof d, j->d);
    ob_fmt_double(tol, sizeof tol, j->tol);
    snprintf(buf, len, "%s__d%s__%s__tol%s", id, d, j->method->name, tol);
}

void ob_export_num(FILE *f, double x, int json)
{
    char b[40];
    if (json && !isfinite(x)) {
        fputs("null", f);
        return;
    }
    ob_fmt_double(b, sizeof b, x);
    fputs(b, f);
}

void ob_export_span(FILE *f, const ob_apiece *p)
{
    fputs("span ", f);
    ob_export_num(f, p->a, 0);
    fputc(' ', f);
    ob_export_num(f, p->b, 0);
    fputs(" fit ", f);
    ob_export_num(f, p->t0, 0);
    fputc(' ', f);
    ob_export_num(f, p->t1, 0);
}

typedef int (*writer_fn)(FILE *f, const ob_job *j, int samples, const ob_approx *a);

static int w_json(FILE *f, const ob_job *j, int s, const ob_approx *a) { return ob_export_write_json(f, j, s, a); }
static int w_curves(FILE *f, const ob_job *j, int s, const ob_approx *a) { (void)s; return ob_export_write_curves(f, j, a); }
static int w_dxf(FILE *f, const ob_job *j, int s, const ob_approx *a) { (void)s; return ob_export_write_dxf(f, j, a); }
static int w_svg(FILE *f, const ob_job *j, int s, const ob_approx *a) { (void)s; return ob_export_write_svg(f, j, a); }

/* DIR/STEM.EXT through the writer; 0 or -1 after ob_error(). */
static int write_one(const char *dir, const char *stem, const char *ext, writer_fn w, const ob_job *j, int samples,
                     const ob_approx *a)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s.%s", dir, stem, ext);
    ob_outfile o;
    ob_err err;
    if (ob_outfile_open(&o, path, 0, &err) != 0) {
        ob_error("--export: %s", err.msg);
        return -1;
    }
    if (w(o.f, j, samples, a) != 0) {
        ob_error("--export: writing '%s' failed", path);
        ob_outfile_discard(&o);
        return -1;
    }
    if (ob_outfile_commit(&o, 0, &err) != 0) {
        ob_error("--export: %s", err.msg);
        return -1;
    }
    return 0;
}

int ob_export_job(const char *dir, const ob_job *j, int samples, const ob_span_log *log)
{
    ob_approx a = {0};
    char stem[400];
    ob_err err;
    ob_export_stem(stem, sizeof stem, j);
    if (ob_approx_from_job(j, log, &a, &err) != 0) {
        ob_error("--export: job %s: %s", stem, err.msg);
        ob_approx_free(&a);
        return -1;
    }
    static const char *const ext[] = {"json", "curves", "dxf", "svg"};
    const writer_fn w[] = {w_json, w_curves, w_dxf, w_svg};
    int rc = 0;
    for (int k = 0; k < 4 && rc == 0; k++)
        rc = write_one(dir, stem, ext[k], w[k], j, samples, &a);
    ob_approx_free(&a);
    return rc;
}

int ob_export_prepare(const ob_run_opts *o, int mpi_ranks, size_t njobs, ob_span_log **spans)
{
    *spans = NULL;
    if (!o->export_dir)
        return 0;
    const char *why = o->resume_dir ? "--resume (the restored jobs did not run here)"
                      : o->reps > 0 ? "--reps (the repetitions time whole runs; export from a plain run)"
                      : mpi_ranks > 1 ? "MPI ranks (each rank runs a part of the jobs)" : NULL;
    if (why) {
        ob_error("--export: not with %s", why);
        return 2;
    }
    if (ob_export_check_dir("run", o->export_dir, o->curves_file) != 0)
        return 2;
    if (!(*spans = ob_span_logs_new(njobs))) {
        ob_error("--export: out of memory");
        return 1;
    }
    return 0;
}

ob_span_log *ob_span_logs_new(size_t njobs)
{
    /* one log more than jobs, its cap -1: the end mark, so that
     * ob_export_finish and ob_export_free need no count */
    ob_span_log *s = calloc(njobs + 1, sizeof *s);
    if (s)
        s[njobs].cap = -1;
    return s;
}

/* Whether job j has an approximation to export (ok or limit). */
static int has_approx(const ob_job *j) { return j->status == OB_OK || j->status == OB_LIMIT; }

/* DIR/NAME (index.csv, or a shard's index): one row per job. */
static int write_index(const char *dir, const char *name, const ob_job *jobs, size_t njobs)
{
    char path[4200], stem[400], num[40];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    ob_outfile o;
    ob_err err;
    if (ob_outfile_open(&o, path, 0, &err) != 0) {
        ob_error("--export: %s", err.msg);
        return -1;
    }
    FILE *f = o.f;
    fprintf(f, "%s\n", OB_EXPORT_INDEX_HEADER);
    for (size_t i = 0; i < njobs; i++) {
        const ob_job *j = &jobs[i];
        const int has = has_approx(j);
        fprintf(f, "%s,", j->curve->id);
        ob_export_num(f, j->d, 0);
        fprintf(f, ",%s,", j->method->name);
        ob_export_num(f, j->tol, 0);
        fprintf(f, ",%s,", ob_status_name(j->status));
        if (has) {
            ob_fmt_double(num, sizeof num, j->max_err);
            fputs(num, f);
        }
        ob_export_stem(stem, sizeof stem, j);
        fprintf(f, ",%d,%s\n", has ? j->segments : 0, has ? stem : "");
    }
    if (ob_outfile_commit(&o, 0, &err) != 0) {
        ob_error("--export: %s", err.msg);
        return -1;
    }
    return 0;
}

/* The stems of jobs[0..n) into m: those with an approximation (approx 1),
 * or all.  0, or -1 out of memory. */
static int stem_set(const ob_job *jobs, size_t n, int approx, ob_strmap *m)
{
    char stem[400];
    for (size_t i = 0; i < n; i++) {
        if (approx && !has_approx(&jobs[i]))
            continue;
        ob_export_stem(stem, sizeof stem, &jobs[i]);
        if (ob_strmap_put(m, stem, 0) == -2)
            return -1;
    }
    return 0;
}

/* Before the export writes: create dir, remove its index (index.csv; a
 * shard's own index too: a reader never takes an earlier one for this
 * run's), and the names the export owns that this one will not write
 * (export_dir.h): for a plain export every other stem and shard index, for
 * a shard only its own jobs' stems without an approximation.  0, or 1
 * after ob_error(). */
static int begin_dir(const char *dir, const ob_job *jobs, size_t njobs, int shard_k, int shard_n)
{
    if (ob_mkdir_p(dir) != 0) {
        ob_error("--export: cannot create '%s': %s", dir, strerror(errno));
        return 1;
    }
    ob_strmap keep = {0}, scope = {0};
    ob_err err;
    int rc = stem_set(jobs, njobs, 1, &keep) || (shard_n > 0 && stem_set(jobs, njobs, 0, &scope)) ? -1 : 0;
    if (rc != 0)
        ob_error("--export: out of memory");
    char own[64];
    ob_export_index_name(own, sizeof own, shard_k, shard_n);
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, own);
    if (rc == 0 && unlink(path) != 0 && errno != ENOENT) {
        ob_error("--export: %s: cannot remove the earlier index: %s", path, strerror(errno));
        rc = -1;
    }
    const ob_prune_rule rule = {&keep, shard_n > 0 ? &scope : NULL, shard_n > 0 ? -1 : 0, 1};
    long removed = 0;
    if (rc == 0 && (rc = ob_export_prune(dir, &rule, &removed, &err)) != 0)
        ob_error("--export: %s", err.msg);
    if (rc == 0 && removed > 0)
        ob_info("--export: removed %ld files of %s that are not this %s's", removed, dir,
                shard_n > 0 ? "shard" : "export");
    ob_strmap_free(&keep);
    ob_strmap_free(&scope);
    return rc == 0 ? 0 : 1;
}

int ob_export_single(const char *dir, const ob_job *j, int samples, const ob_span_log *log)
{
    if (begin_dir(dir, j, 1, 0, 0) != 0)
        return 1;
    if (has_approx(j) && ob_export_job(dir, j, samples, log) != 0)
        return 1;
    return write_index(dir, "index.csv", j, 1) != 0 ? 1 : 0;
}

int ob_export_finish(const ob_run_opts *o, const ob_span_log *logs, const ob_job *jobs, int status)
{
    if (!o->export_dir || !logs || status != 0 || !jobs)
        return status;
    size_t njobs = 0;
    while (logs[njobs].cap != -1)
        njobs++;
    if (begin_dir(o->export_dir, jobs, njobs, o->shard_k, o->shard_n) != 0)
        return 1;
    /* jobs in parallel (each writes its own files; methods keep no state,
     * as in the driver); the first failure, or a signal, stops the rest: a
     * job started finishes its files (each is renamed into place whole) */
    long done = 0;
    int failed = 0;
    const int samples = ob_clamp_samples(o->driver.samples);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : done)
    for (long i = 0; i < (long)njobs; i++) {
        int stop;
#pragma omp atomic read
        stop = failed;
        if (stop || ob_stop_signal() || !has_approx(&jobs[i]))
            continue;
        if (ob_export_job(o->export_dir, &jobs[i], samples, &logs[i]) != 0) {
#pragma omp atomic write
            failed = 1;
        }
        done++;
    }
    char index[64];
    ob_export_index_name(index, sizeof index, o->shard_k, o->shard_n);
    if (ob_stop_signal() && !failed)
        return ob_stop_exit("--export interrupted after %ld of %zu jobs: %s holds those jobs' files and no "
                            "%s (results.csv is complete); run the command again to export them all",
                            done, njobs, o->export_dir, index);
    if (failed || write_index(o->export_dir, index, jobs, njobs) != 0)
        return 1;
    ob_info("exported %ld approximations of %zu jobs to %s (%s%s)", done, njobs, o->export_dir, index,
            o->shard_n > 0 ? "; merge combines the shards' indexes into index.csv" : "");
    return 0;
}

void ob_export_free(ob_span_log *logs)
{
    if (!logs)
        return;
    for (size_t i = 0; logs[i].cap != -1; i++)
        free(logs[i].v);
    free(logs);
}
