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

int ob_shard_assign(const ob_job *jobs, size_t njobs, int n, int *shard_of)
{
    double *cost = calloc(njobs ? njobs : 1, sizeof *cost);
    size_t *order = malloc((njobs ? njobs : 1) * sizeof *order);
    double *load = calloc((size_t)(n > 0 ? n : 1), sizeof *load);
    int rc = -1;
    if (!cost || !order || !load)
        goto out;
    for (size_t i = 0; i < njobs; i++)
        cost[i] = ob_job_cost(&jobs[i]);
    if (ob_cost_order(cost, njobs, order))
        goto out;
    for (size_t k = 0; k < njobs; k++) {
        int best = 0;
        for (int s = 1; s < n; s++)
            if (load[s] < load[best])
                best = s;
        shard_of[order[k]] = best;
        load[best] += cost[order[k]];
    }
    rc = 0;
out:
    free(cost);
    free(order);
    free(load);
    return rc;
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
