/*
 * shard.c - cost-balanced partition of a run's jobs (see shard.h).
 */
#include "host/run/shard.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "host/io/numfmt.h"

typedef struct {
    double cost;
    size_t i;
} costed;

static int by_cost_desc(const void *a, const void *b)
{
    const costed *x = a, *y = b;
    if (x->cost != y->cost)
        return x->cost > y->cost ? -1 : 1;
    return (x->i > y->i) - (x->i < y->i);
}

int ob_shard_assign(const ob_job *jobs, size_t njobs, int n, int *shard_of)
{
    costed *c = malloc((njobs ? njobs : 1) * sizeof *c);
    double *load = calloc((size_t)(n > 0 ? n : 1), sizeof *load);
    if (!c || !load) {
        free(c);
        free(load);
        return -1;
    }
    for (size_t i = 0; i < njobs; i++)
        c[i] = (costed){ob_job_cost(&jobs[i]), i};
    qsort(c, njobs, sizeof *c, by_cost_desc);
    for (size_t k = 0; k < njobs; k++) {
        int best = 0;
        for (int s = 1; s < n; s++)
            if (load[s] < load[best])
                best = s;
        shard_of[c[k].i] = best;
        load[best] += c[k].cost;
    }
    free(c);
    free(load);
    return 0;
}

int ob_shard_parse(const char *opt, const char *spec, int *k, int *n)
{
    char *e;
    errno = 0;
    long kk = strtol(spec, &e, 10);
    if (e == spec || *e != '/' || errno) {
        ob_error("%s: expected K/N (shard K of N, 0 <= K < N), got '%s'", opt, spec);
        return -1;
    }
    const char *s2 = e + 1;
    long nn = strtol(s2, &e, 10);
    if (e == s2 || *e || errno || nn < 1 || nn > 100000 || kk < 0 || kk >= nn) {
        ob_error("%s: expected K/N with 0 <= K < N <= 100000, got '%s'", opt, spec);
        return -1;
    }
    *k = (int)kk;
    *n = (int)nn;
    return 0;
}

uint64_t ob_fnv1a(uint64_t h, const void *p, size_t len)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < len; i++) {
        h ^= b[i];
        h *= 1099511628211ULL;
    }
    return h;
}

static uint64_t fnv_str(uint64_t h, const char *s)
{
    return ob_fnv1a(h, s, strlen(s) + 1);  /* with the NUL: "ab","c" != "a","bc" */
}

uint64_t ob_plan_seed(const char *fp)
{
    return fnv_str(OB_FNV_BASIS, fp);
}

uint64_t ob_key_step(uint64_t h, const char *const key[6])
{
    for (int k = 0; k < 6; k++)
        h = fnv_str(h, key[k]);
    return h;
}

uint64_t ob_job_key_step(uint64_t h, const ob_job *j)
{
    char d[40], tol[40];
    ob_fmt_double(d, sizeof d, j->d);
    ob_fmt_double(tol, sizeof tol, j->tol);
    const char *const key[6] = {j->curve->id, d, j->method->name, ob_metric_name(j->metric),
                                ob_split_name(j->split), tol};
    return ob_key_step(h, key);
}

uint64_t ob_plan_hash(const ob_job *jobs, size_t njobs, const char *fp)
{
    uint64_t h = ob_plan_seed(fp);
    for (size_t i = 0; i < njobs; i++)
        h = ob_job_key_step(h, &jobs[i]);
    return h;
}
