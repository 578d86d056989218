/*
 * trimmed.c - `run --trimmed` (see trimmed.h).
 */
#include "host/run/trimmed.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "host/io/approx.h"
#include "host/measure/trim.h"
#include "host/measure/trim_approx.h"
#include "host/run/clock.h"
#include "host/run/signals.h"

int ob_trimmed_wants(const ob_job *j) { return j->status == OB_OK || j->status == OB_LIMIT; }

/* One (curve, d) of the run and its exact trimmed offset. */
typedef struct {
    const ob_curve *c;
    double d;
    ob_trim tr;
    int ok;          /* 1: tr was computed */
    char why[200];   /* else: why not */
} offset_key;

typedef struct {
    offset_key *key;
    int nkey;
    int *of_job;     /* [njobs]: the job's key, -1: not measured */
} offsets;

/* The distinct (curve, d) of the jobs measured, each job's among them. */
static int collect(const ob_job *jobs, size_t njobs, offsets *o)
{
    o->key = malloc((njobs ? njobs : 1) * sizeof *o->key);
    o->of_job = malloc((njobs ? njobs : 1) * sizeof *o->of_job);
    if (!o->key || !o->of_job)
        return -1;
    for (size_t i = 0; i < njobs; i++) {
        o->of_job[i] = -1;
        if (!ob_trimmed_wants(&jobs[i]))
            continue;
        int k = o->nkey - 1; /* jobs of one (curve, d) mostly come together */
        while (k >= 0 && !(o->key[k].c == jobs[i].curve && o->key[k].d == jobs[i].d))
            k--;
        if (k < 0) {
            k = o->nkey++;
            o->key[k] = (offset_key){.c = jobs[i].curve, .d = jobs[i].d};
        }
        o->of_job[i] = k;
    }
    return 0;
}

static void offsets_free(offsets *o)
{
    for (int k = 0; k < o->nkey; k++)
        ob_trim_free(&o->key[k].tr);
    free(o->key);
    free(o->of_job);
}

static double base_start(const ob_apiece *p) { return p->seg + ob_apiece_base_t(p, 0.0); }

static int cmp_piece(const void *x, const void *y)
{
    const double a = base_start(x), b = base_start(y);
    return (a > b) - (a < b);
}

double ob_trimmed_margin(const ob_job *j)
{
    const double e = isfinite(j->max_err) ? j->max_err : j->tol;
    return 2.0 * e + OB_TRIM_REL * ob_trim_curve_size(j->curve, j->d);
}

/* The two-sided distance between the trimmed sets, with the empty cases. */
static int distance(const ob_job *j, const ob_trim *tr, const ob_approx *kept, int samples, double *e, ob_err *err)
{
    if (tr->n == 0 || kept->n == 0) {
        *e = tr->n == 0 && kept->n == 0 ? 0.0 : INFINITY;
        return 0;
    }
    ob_mres r;
    char msg[200];
    if (ob_trimmed_hausdorff(j->curve, j->d, tr, kept, samples, &r, msg, sizeof msg, err) != 0)
        return -1;
    *e = r.err;
    return 0;
}

/* Job j measured against its trimmed offset tr: 0, or -1 with err. */
static int measure_job(ob_job *j, const ob_span_log *log, const ob_trim *tr, int samples, ob_err *err)
{
    ob_approx a = {0}, kept = {0};
    int rc = ob_approx_from_job(j, log, &a, err);
    if (rc == 0) {
        qsort(a.v, (size_t)a.n, sizeof *a.v, cmp_piece); /* the curve's order (the log has the driver's) */
        int cut = 0;
        double te = NAN;
        rc = ob_trim_approx(j->curve, j->d, &a, ob_trimmed_margin(j), &kept, &cut, err);
        if (rc == 0)
            rc = distance(j, tr, &kept, samples, &te, err);
        if (rc == 0)
            j->trimmed_done = 1, j->trimmed_err = te, j->trimmed_cut = cut;
    }
    ob_approx_free(&a);
    ob_approx_free(&kept);
    return rc;
}

/* The exact trimmed offsets, then the jobs, each a unit of work. */
static void run_all(offsets *o, ob_job *jobs, size_t njobs, const ob_span_log *spans, int samples, long *nbad,
                    int *stopped)
{
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < o->nkey; k++) {
        ob_err err;
        offset_key *key = &o->key[k];
        if (!ob_stop_signal() && ob_trim_offset(key->c, key->d, &key->tr, &err) == 0)
            key->ok = 1;
        else
            snprintf(key->why, sizeof key->why, "%.199s", ob_stop_signal() ? "stopped" : err.msg);
    }
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : nbad[0])
    for (long i = 0; i < (long)njobs; i++) {
        const int k = o->of_job[i];
        if (k < 0 || ob_stop_signal())
            continue;
        ob_err err;
        ob_job *j = &jobs[i];
        if (!o->key[k].ok)
            snprintf(err.msg, sizeof err.msg, "%.199s", o->key[k].why);
        if (!o->key[k].ok || measure_job(j, &spans[i], &o->key[k].tr, samples, &err) != 0) {
            nbad[0]++;
            ob_warn("--trimmed: job %s d=%g %s tol=%g not measured: %s", j->curve->id, j->d, j->method->name, j->tol,
                    err.msg);
        }
    }
    *stopped = ob_stop_signal() != 0;
}

int ob_trimmed_run(int samples, ob_job *jobs, size_t njobs, const ob_span_log *spans, double *seconds)
{
    const double start = ob_mono_s();
    offsets o = {0};
    long nbad = 0;
    int stopped = 0;
    if (collect(jobs, njobs, &o) != 0) {
        offsets_free(&o);
        ob_error("--trimmed: out of memory");
        return -1;
    }
    size_t n = 0;
    for (size_t i = 0; i < njobs; i++)
        n += o.of_job[i] >= 0;
    if (n)
        ob_info("measuring %zu jobs against the trimmed offsets of %d (curve, d)", n, o.nkey);
    run_all(&o, jobs, njobs, spans, samples, &nbad, &stopped);
    offsets_free(&o);
    *seconds = ob_mono_s() - start;
    if (stopped)
        for (size_t i = 0; i < njobs; i++)
            jobs[i].trimmed_done = 0;
    if (nbad)
        ob_warn("--trimmed: %ld jobs left without trimmed_err", nbad);
    return stopped ? 1 : 0;
}
