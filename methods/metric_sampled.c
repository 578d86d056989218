/*
 * metric_sampled.c - the sampled metrics radial, normal and hausdorff on the
 * CPU.  The formulas live in kernels/metric_core.h, shared word for word with
 * the OpenCL kernel; see metric.h for the definitions.
 */
#include "metric.h"

#include "../kernels/metric_core.h"

#include <pthread.h>
#include <stdlib.h>

size_t ob_metric_scratch(int S) { return 2 * (size_t)OBC_TABLE_SIZE(ob_clamp_samples(S)); }

/* The basis tables (metric_core.h, obc_basis_build) of the sample counts in
 * use: built once each, kept for the life of the program (a run uses one
 * S; tests a few). */
enum { BASIS_CACHE = 16 };
static struct {
    int S;
    double *B;
} basis_cache[BASIS_CACHE];
static pthread_mutex_t basis_lock = PTHREAD_MUTEX_INITIALIZER;

const double *ob_metric_basis(int S)
{
    S = ob_clamp_samples(S);
    const double *got = NULL;
    pthread_mutex_lock(&basis_lock);
    int k = 0;
    while (k < BASIS_CACHE && basis_cache[k].B && basis_cache[k].S != S)
        k++;
    if (k < BASIS_CACHE && !basis_cache[k].B) {
        double *B = malloc((size_t)OBC_BASIS_SIZE(S) * sizeof *B);
        if (B) {
            obc_basis_build(S, B);
            basis_cache[k].S = S;
            basis_cache[k].B = B;
        }
    }
    if (k < BASIS_CACHE)
        got = basis_cache[k].B;
    pthread_mutex_unlock(&basis_lock);
    return got;
}

/* Hausdorff keeps sample tables of the offset and of the approximation: on
 * the stack up to the default S, on the heap past it (at most 0.5 MiB). */
enum { STACK_SAMPLES = 512 };

static int measure_core(int code, const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    double local[2 * OBC_TABLE_SIZE(STACK_SAMPLES)];
    S = ob_clamp_samples(S);
    double *scratch = local;
    if (S > STACK_SAMPLES && !(scratch = malloc(ob_metric_scratch(S) * sizeof *scratch))) {
        out->err = (double)INFINITY;
        out->t = 0.0;
        return -1;
    }
    const double *basis = code == OBC_HAUSDORFF ? ob_metric_basis(S) : NULL;
    if (code == OBC_HAUSDORFF && !basis) {
        if (scratch != local)
            free(scratch);
        out->err = (double)INFINITY;
        out->t = 0.0;
        return -1;
    }
    long ops = 0;
    obc_measure(code, &base->h[0][0], base->deg, &approx->h[0][0], approx->deg, d, S, basis, scratch, &out->err,
                &out->t, &ops);
    out->work = (double)ops;
    if (scratch != local)
        free(scratch);
    return 0;
}

int ob_metric_radial(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_RADIAL, base, approx, d, S, out);
}

int ob_metric_normal(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_NORMAL, base, approx, d, S, out);
}

int ob_metric_hausdorff(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    return measure_core(OBC_HAUSDORFF, base, approx, d, S, out);
}
