/*
 * plan.c - what a run runs: its curves, its jobs, the hashes that identify
 * them, this process's shard (see plan.h).
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/cli/suggest.h"
#include "host/diag.h"
#include "host/io/datadir.h"
#include "host/io/random.h"
#include "host/run/plan.h"
#include "host/run/shard.h"
#include "methods/core/offdeg.h"

/* " (did you mean 'ID'?)" for an unknown curve id, over the ids of set,
 * into buf (or ""). */
static const char *curve_note(const ob_curveset *set, const char *id, char *buf, size_t len)
{
    const char **names = malloc((size_t)(set->n > 0 ? set->n : 1) * sizeof *names);
    buf[0] = '\0';
    if (names) {
        for (int i = 0; i < set->n; i++)
            names[i] = set->v[i].id;
        ob_suggest_note(id, names, set->n, buf, len);
    }
    free(names);
    return buf;
}

int ob_load_run_curves(const ob_run_opts *o, ob_curveset *set, char *where, size_t wlen)
{
    ob_err err;
    int rc = 0;
    where[0] = '\0';
    if (o->curves_file) {
        snprintf(where, wlen, "%s", o->curves_file);
        rc = ob_curves_load_file(o->curves_file, set, &err);
    } else if (o->random_n == 0) {
        rc = ob_load_default_curves(set, where, wlen, &err);
    }
    if (rc == 0 && o->random_n > 0) {
        size_t k = strlen(where);
        snprintf(where + k, wlen - k, "%srandom %ld:%" PRIu64, k ? " + " : "", o->random_n, o->random_seed);
        /* with --curve, only the selected random curves are generated */
        rc = ob_random_append(set, o->random_seed, o->random_n, o->curve_ids, o->ncurve_ids, &err);
    }
    if (rc != 0) {
        ob_error("%s", err.msg);
        return -1;
    }
    for (int i = 0; i < o->ncurve_ids; i++)
        if (ob_curveset_find(set, o->curve_ids[i]) < 0) {
            char note[160];
            ob_error("--curve: no curve '%s' in %s (see './offbench list curves')%s", o->curve_ids[i], where,
                     curve_note(set, o->curve_ids[i], note, sizeof note));
            return -1;
        }
    return 0;
}

int ob_run_selects(const ob_run_opts *o, const char *id)
{
    if (!o->curve_ids)
        return 1;
    for (int i = 0; i < o->ncurve_ids; i++)
        if (strcmp(o->curve_ids[i], id) == 0)
            return 1;
    return 0;
}

/* FNV-1a over the content of the curves the run uses (id, segments' degrees
 * and homogeneous control points, offsets). */
int ob_check_option_d(const char *cmd, const ob_curve *c, double d)
{
    char why[200];
    if (ob_offset_check(d, c->coord_max, why, sizeof why) == 0)
        return 0;
    if (c->file[0] && c->line > 0)
        ob_error("%s: --d: curve '%s' (%s:%d): %s; the curve file would refuse it too", cmd, c->id, c->file,
                 c->line, why);
    else
        ob_error("%s: --d: curve '%s': %s; a curve file would refuse it too", cmd, c->id, why);
    return -1;
}

uint64_t ob_curves_hash(const ob_run_opts *o, const ob_curveset *set)
{
    uint64_t h = OB_FNV_BASIS;
    for (int c = 0; c < set->n; c++) {
        const ob_curve *cv = &set->v[c];
        if (!ob_run_selects(o, cv->id))
            continue;
        h = ob_fnv1a(h, cv->id, strlen(cv->id) + 1);
        h = ob_fnv1a(h, &cv->nseg, sizeof cv->nseg);
        for (int s = 0; s < cv->nseg; s++) {
            h = ob_fnv1a(h, &cv->seg[s].deg, sizeof cv->seg[s].deg);
            h = ob_fnv1a(h, cv->seg[s].h, (size_t)(cv->seg[s].deg + 1) * sizeof cv->seg[s].h[0]);
        }
        h = ob_fnv1a(h, &cv->nd, sizeof cv->nd);
        h = ob_fnv1a(h, cv->d, (size_t)cv->nd * sizeof *cv->d);
    }
    return h;
}

void ob_offset_degrees(const ob_run_opts *o, ob_curveset *set)
{
#pragma omp parallel for schedule(dynamic, 1)
    for (int c = 0; c < set->n; c++) {
        ob_curve *cv = &set->v[c];
        char msg[160];
        if (ob_run_selects(o, cv->id) &&
            ob_curve_offset_degree(cv, &cv->offset_degree, &cv->offset_rational, msg, sizeof msg) == 0)
            cv->offset_known = 1;
    }
}

ob_job *ob_plan_jobs(const ob_run_opts *o, const ob_curveset *set, size_t *njobs)
{
    size_t n = 0;
    for (int c = 0; c < set->n; c++)
        if (ob_run_selects(o, set->v[c].id))
            n += (size_t)set->v[c].nd * (size_t)o->nmethods * (size_t)o->ntols;
    ob_job *jobs = calloc(n ? n : 1, sizeof *jobs);
    if (!jobs)
        return NULL;
    size_t k = 0;
    for (int c = 0; c < set->n; c++) {
        if (!ob_run_selects(o, set->v[c].id))
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

int ob_select_shard(int shard_k, int shard_n, ob_job **jobs, size_t *njobs, size_t **idx)
{
    int *of = malloc((*njobs ? *njobs : 1) * sizeof *of);
    *idx = malloc((*njobs ? *njobs : 1) * sizeof **idx);
    if (!of || !*idx || ob_shard_assign(*jobs, *njobs, shard_n, of) != 0) {
        free(of);
        ob_error("out of memory");
        return -1;
    }
    size_t n = 0;
    for (size_t i = 0; i < *njobs; i++)
        if (of[i] == shard_k) {
            (*jobs)[n] = (*jobs)[i];
            (*idx)[n++] = i;
        }
    free(of);
    *njobs = n;
    return 0;
}
