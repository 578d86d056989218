/*
 * export.c - the files of `--export DIR` (export.h): per job, and for a run.
 */
#include "host/io/export.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
    const char *const inputs[] = {o->curves_file};
    if (ob_check_out_not_input("run --export", o->export_dir, 1, inputs, 1) != 0)
        return 2;
    /* one log more than jobs, its cap -1: the end mark, so that
     * ob_export_finish and ob_export_free need no count */
    *spans = calloc(njobs + 1, sizeof **spans);
    if (!*spans) {
        ob_error("--export: out of memory");
        return 1;
    }
    (*spans)[njobs].cap = -1;
    return 0;
}

/* DIR/index.csv: one row per job. */
static int write_index(const char *dir, const ob_job *jobs, size_t njobs)
{
    char path[4200], stem[400], num[40];
    snprintf(path, sizeof path, "%s/index.csv", dir);
    ob_outfile o;
    ob_err err;
    if (ob_outfile_open(&o, path, 0, &err) != 0) {
        ob_error("--export: %s", err.msg);
        return -1;
    }
    FILE *f = o.f;
    fputs("curve,d,method,tol,status,max_err,segments,stem\n", f);
    for (size_t i = 0; i < njobs; i++) {
        const ob_job *j = &jobs[i];
        const int has = j->status == OB_OK || j->status == OB_LIMIT;
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

int ob_export_single(const char *dir, const ob_job *j, int samples, const ob_span_log *log)
{
    if (ob_mkdir_p(dir) != 0) {
        ob_error("--export: cannot create '%s': %s", dir, strerror(errno));
        return 1;
    }
    if ((j->status == OB_OK || j->status == OB_LIMIT) && ob_export_job(dir, j, samples, log) != 0)
        return 1;
    return write_index(dir, j, 1) != 0 ? 1 : 0;
}

int ob_export_finish(const ob_run_opts *o, const ob_span_log *logs, const ob_job *jobs, int status)
{
    if (!o->export_dir || !logs || status != 0 || !jobs)
        return status;
    size_t njobs = 0;
    while (logs[njobs].cap != -1)
        njobs++;
    if (ob_mkdir_p(o->export_dir) != 0) {
        ob_error("--export: cannot create '%s': %s", o->export_dir, strerror(errno));
        return 1;
    }
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
        if (stop || ob_stop_signal() || (jobs[i].status != OB_OK && jobs[i].status != OB_LIMIT))
            continue;
        if (ob_export_job(o->export_dir, &jobs[i], samples, &logs[i]) != 0) {
#pragma omp atomic write
            failed = 1;
        }
        done++;
    }
    if (ob_stop_signal() && !failed)
        return ob_stop_exit("--export interrupted after %ld of %zu jobs: %s holds those jobs' files and no "
                            "index.csv (results.csv is complete); run the command again to export them all",
                            done, njobs, o->export_dir);
    if (failed || write_index(o->export_dir, jobs, njobs) != 0)
        return 1;
    ob_info("exported %ld approximations of %zu jobs to %s", done, njobs, o->export_dir);
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
