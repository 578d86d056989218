/*
 * options.c - parsing of the `run` options.  Every error names the option.
 */
#include "options.h"
#include "shard.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "numfmt.h"
#include "random.h"

static int parse_int(const char *opt, const char *s, long lo, long hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (!*s || *end || errno || v < lo || v > hi) {
        ob_error("%s: expected a whole number from %ld to %ld, got '%s'", opt, lo, hi, s);
        return -1;
    }
    *out = (int)v;
    return 0;
}

/* Splits a comma list into a NULL-terminated strdup'd array. */
static char **split_list(const char *s, int *n)
{
    int cap = 1;
    for (const char *p = s; *p; p++)
        cap += *p == ',';
    char **v = calloc((size_t)cap + 1, sizeof *v);
    if (!v)
        return NULL;
    *n = 0;
    const char *p = s;
    for (;;) {
        const char *q = strchr(p, ',');
        size_t len = q ? (size_t)(q - p) : strlen(p);
        v[*n] = malloc(len + 1);
        if (!v[*n])
            break;
        memcpy(v[*n], p, len);
        v[*n][len] = '\0';
        (*n)++;
        if (!q)
            break;
        p = q + 1;
    }
    return v;
}

static void free_list(char **v, int n)
{
    if (!v)
        return;
    for (int i = 0; i < n; i++)
        free(v[i]);
    free(v);
}

static int parse_methods(const char *s, ob_run_opts *o)
{
    free(o->methods);
    o->methods = NULL;
    o->nmethods = 0;
    int total = ob_method_count();
    if (strcmp(s, "all") == 0) {
        o->methods = malloc((size_t)total * sizeof *o->methods);
        if (!o->methods)
            return -1;
        for (int i = 0; i < total; i++)
            o->methods[o->nmethods++] = ob_methods[i];
        return 0;
    }
    int n = 0;
    char **names = split_list(s, &n);
    if (!names)
        return -1;
    o->methods = malloc((size_t)(n > 0 ? n : 1) * sizeof *o->methods);
    int rc = o->methods ? 0 : -1;
    for (int i = 0; i < n && rc == 0; i++) {
        const ob_method *m = ob_method_find(names[i]);
        if (!m) {
            ob_error("--methods: unknown method '%s' (see './offbench list methods')", names[i]);
            rc = -1;
            break;
        }
        for (int k = 0; k < o->nmethods; k++)
            if (o->methods[k] == m) {
                ob_error("--methods: '%s' is listed twice", names[i]);
                rc = -1;
            }
        if (rc == 0)
            o->methods[o->nmethods++] = m;
    }
    if (rc == 0 && o->nmethods == 0) {
        ob_error("--methods: empty list");
        rc = -1;
    }
    free_list(names, n);
    return rc;
}

static int parse_tols(const char *s, ob_run_opts *o)
{
    int n = 0;
    char **v = split_list(s, &n);
    if (!v)
        return -1;
    int rc = 0;
    if (n > OB_MAX_TOLS) {
        ob_error("--tols: at most %d tolerances", OB_MAX_TOLS);
        rc = -1;
    }
    o->ntols = 0;
    for (int i = 0; i < n && rc == 0; i++) {
        double t;
        if (ob_parse_double(v[i], &t) || !(t > 0) || t > 1e6) {
            ob_error("--tols: '%s' is not a tolerance (a number > 0 and <= 1e6)", v[i]);
            rc = -1;
            break;
        }
        /* compared as numbers: 1e-2 and 0.01 are one job key */
        for (int k = 0; k < o->ntols && rc == 0; k++)
            if (o->tols[k] == t) {
                ob_error("--tols: '%s' is listed twice (the same tolerance as '%s')", v[i], v[k]);
                rc = -1;
            }
        if (rc)
            break;
        o->tols[o->ntols++] = t;
    }
    free_list(v, n);
    return rc;
}

/* --param METHOD.NAME=VALUE: the value read whole (no length limit) and
 * refused unless inside the parameter's range (method.h), so that no job
 * runs with a value its fit() would reject or silently replace. */
static int parse_param(const char *s, ob_run_opts *o)
{
    char *buf = strdup(s);
    if (!buf)
        return -1;
    int rc = -1;
    char *dot = strchr(buf, '.'), *eq = strchr(buf, '=');
    if (!dot || !eq || eq < dot) {
        ob_error("--param: expected METHOD.NAME=VALUE, got '%.300s'", s);
        goto out;
    }
    *dot = *eq = '\0';
    const ob_method *m = ob_method_find(buf);
    if (!m) {
        ob_error("--param: unknown method '%.100s'", buf);
        goto out;
    }
    int k = ob_param_find(m, dot + 1);
    if (k < 0) {
        ob_error("--param: method '%s' has no parameter '%.100s' (see './offbench list methods')", buf, dot + 1);
        goto out;
    }
    const ob_param *p = &m->params[k];
    double v;
    char msg[256];
    if (ob_parse_double(eq + 1, &v)) {
        ob_error("--param %s.%s: '%.100s' is not a number (range %.17g to %.17g%s)", m->name, p->name, eq + 1,
                 p->min, p->max, p->integer ? ", whole numbers" : "");
        goto out;
    }
    if (ob_param_check(m, p, v, msg, sizeof msg)) {
        ob_error("--param %s", msg);
        goto out;
    }
    o->params[ob_method_index(m) * OB_MAX_PARAMS + k] = v;
    rc = 0;
out:
    free(buf);
    return rc;
}

/* 1 when --param values a and b set the same METHOD.NAME. */
static int same_param(const char *a, const char *b)
{
    const char *ea = strchr(a, '='), *eb = strchr(b, '=');
    return ea && eb && ea - a == eb - b && strncmp(a, b, (size_t)(ea - a)) == 0;
}

int ob_run_opts_parse(int argc, char **argv, ob_run_opts *o)
{
    memset(o, 0, sizeof *o);
    o->metric = OB_METRIC_HAUSDORFF;
    o->split = OB_SPLIT_MID;
    o->backend = OB_BACKEND_AUTO;
    o->out_dir = "out";
    o->argc = argc;
    o->argv = argv;
    ob_driver_defaults(&o->driver);
    static const double default_tols[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5};
    for (int i = 0; i < 5; i++)
        o->tols[i] = default_tols[i];
    o->ntols = 5;
    if (parse_methods("all", o))
        return -1;
    const int nm = ob_method_count();
    o->params = malloc((size_t)nm * OB_MAX_PARAMS * sizeof *o->params);
    if (!o->params)
        return -1;
    for (int i = 0; i < nm; i++)
        ob_param_defaults(ob_methods[i], o->params + i * OB_MAX_PARAMS);

    int out_given = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            ob_error("run: see README.md or './offbench help' for the options");
            return -1;
        }
        if (strcmp(a, "--force") == 0) {  /* the one option without a value */
            o->force = 1;
            continue;
        }
        if (!v) {
            ob_error("%s: missing value", a);
            return -1;
        }
        /* One rule for every option but --param (one per METHOD.NAME, checked
         * in parse_param): given twice is an error, not "the last one wins",
         * so that a command line means what it says (a list option takes
         * all its values in one comma list). */
        if (strcmp(a, "--param") != 0)
            for (int k = 1; k < i; k += 2)
                if (strcmp(argv[k], a) == 0) {
                    ob_error("%s: given twice (give each option once%s)", a,
                             strcmp(a, "--curve") == 0 || strcmp(a, "--tols") == 0 || strcmp(a, "--methods") == 0
                                 ? "; list all values in one comma list"
                                 : "");
                    return -1;
                }
        if (strcmp(a, "--curves") == 0) {
            o->curves_file = v;
        } else if (strcmp(a, "--curve") == 0) {
            free_list(o->curve_ids, o->ncurve_ids);
            o->curve_ids = split_list(v, &o->ncurve_ids);
            if (!o->curve_ids)
                return -1;
            for (int k = 0; k < o->ncurve_ids; k++)
                for (int l = 0; l < k; l++)
                    if (strcmp(o->curve_ids[k], o->curve_ids[l]) == 0) {
                        ob_error("--curve: '%s' is listed twice", o->curve_ids[k]);
                        return -1;
                    }
        } else if (strcmp(a, "--random") == 0) {
            if (ob_random_parse(a, v, &o->random_n, &o->random_seed))
                return -1;
        } else if (strcmp(a, "--methods") == 0) {
            if (parse_methods(v, o))
                return -1;
        } else if (strcmp(a, "--param") == 0) {
            for (int k = 1; k < i; k += 2)
                if (strcmp(argv[k], "--param") == 0 && same_param(argv[k + 1], v)) {
                    ob_error("--param %.*s: given twice", (int)(strchr(v, '=') - v), v);
                    return -1;
                }
            if (parse_param(v, o))
                return -1;
        } else if (strcmp(a, "--tols") == 0) {
            if (parse_tols(v, o))
                return -1;
        } else if (strcmp(a, "--metric") == 0) {
            if (ob_metric_parse(v, &o->metric)) {
                ob_error("--metric: unknown metric '%s' (bound, radial, normal, hausdorff)", v);
                return -1;
            }
        } else if (strcmp(a, "--split") == 0) {
            if (ob_split_parse(v, &o->split)) {
                ob_error("--split: unknown split rule '%s' (mid, maxerr, greedy, optimal)", v);
                return -1;
            }
        } else if (strcmp(a, "--backend") == 0) {
            if (strcmp(v, "auto") == 0)
                o->backend = OB_BACKEND_AUTO;
            else if (strcmp(v, "cpu") == 0)
                o->backend = OB_BACKEND_CPU;
            else if (strcmp(v, "opencl") == 0)
                o->backend = OB_BACKEND_OPENCL;
            else {
                ob_error("--backend: unknown backend '%s' (auto, opencl, cpu)", v);
                return -1;
            }
        } else if (strcmp(a, "--device") == 0) {
            o->device = v;
        } else if (strcmp(a, "--threads") == 0) {
            if (parse_int(a, v, 1, 1024, &o->threads))
                return -1;
        } else if (strcmp(a, "--job-timeout") == 0) {
            double s;
            if (ob_parse_double(v, &s) || !(s > 0) || s > 1e6) {
                ob_error("--job-timeout: expected seconds > 0 (at most 1e6), got '%s'", v);
                return -1;
            }
            o->driver.job_timeout_ns = s * 1e9;
        } else if (strcmp(a, "--reps") == 0) {
            if (parse_int(a, v, 1, 1000, &o->reps))
                return -1;
        } else if (strcmp(a, "--out") == 0) {
            if (!*v) {
                ob_error("--out: empty directory name");
                return -1;
            }
            o->out_dir = v;
            out_given = 1;
        } else if (strcmp(a, "--samples") == 0) {
            if (parse_int(a, v, OB_MIN_SAMPLES, OB_MAX_SAMPLES, &o->driver.samples))
                return -1;
        } else if (strcmp(a, "--max-depth") == 0) {
            if (parse_int(a, v, 1, 60, &o->driver.max_depth))
                return -1;
        } else if (strcmp(a, "--max-segments") == 0) {
            if (parse_int(a, v, 1, 10000000, &o->driver.max_segments))
                return -1;
        } else if (strcmp(a, "--inflections") == 0) {
            if (strcmp(v, "yes") == 0)
                o->driver.inflections = 1;
            else if (strcmp(v, "no") == 0)
                o->driver.inflections = 0;
            else {
                ob_error("--inflections: expected yes or no, got '%s'", v);
                return -1;
            }
        } else if (strcmp(a, "--shard") == 0) {
            if (ob_shard_parse(a, v, &o->shard_k, &o->shard_n))
                return -1;
        } else if (strcmp(a, "--resume") == 0) {
            if (!*v) {
                ob_error("--resume: empty directory name");
                return -1;
            }
            o->resume_dir = v;
        } else {
            ob_error("run: unknown option '%s'", a);
            return -1;
        }
        i += takes;
    }
    if (o->resume_dir) {
        if (out_given && strcmp(o->out_dir, o->resume_dir) != 0) {
            ob_error("--resume %s: the results go back into that directory; --out %s names another", o->resume_dir,
                     o->out_dir);
            return -1;
        }
        if (o->reps > 0) {
            ob_error("--resume: not with --reps (repetitions time whole runs)");
            return -1;
        }
        if (o->force) {
            ob_error("--resume: not with --force (--force starts the run afresh)");
            return -1;
        }
        o->out_dir = o->resume_dir;
    }
    return 0;
}

void ob_run_opts_free(ob_run_opts *o)
{
    if (!o)
        return;
    free_list(o->curve_ids, o->ncurve_ids);
    free(o->methods);
    free(o->params);
    o->curve_ids = NULL;
    o->methods = NULL;
    o->params = NULL;
}
