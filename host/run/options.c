/*
 * options.c - parsing of the `run` options.  Every error names the option.
 */
#include "host/run/options.h"
#include "host/run/shard.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/cli/cliopts.h"
#include "host/cli/suggest.h"
#include "host/diag.h"
#include "host/io/numfmt.h"
#include "host/io/random.h"
#include "host/run/fittime.h"

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
            char note[1024];
            ob_error("--methods: unknown method '%s' (see './offbench list methods')%s", names[i],
                     ob_suggest_method_note(names[i], note, sizeof note));
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
        char note[1024];
        ob_error("--param: unknown method '%.100s'%s", buf, ob_suggest_method_note(buf, note, sizeof note));
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

enum {
    RO_CURVES, RO_CURVE, RO_RANDOM, RO_METHODS, RO_TOLS, RO_METRIC, RO_SPLIT, RO_BACKEND, RO_DEVICE,
    RO_THREADS, RO_SAMPLES, RO_MAX_DEPTH, RO_MAX_SEGMENTS, RO_INFLECTIONS, RO_PARAM, RO_JOB_TIMEOUT,
    RO_REPS, RO_SHARD, RO_OUT, RO_RESUME, RO_FORCE, RO_EXPORT, RO_ENGINE, RO_CHUNK, RO_CERTIFY,
    RO_TIME_FITS, RO_FIT_REPS, RO_FIT_MIN_TIME, RO_TRIMMED, RO_COUNT
};
_Static_assert((int)RO_COUNT <= (int)OB_RUN_MAX_FLAGS, "ob_run_opts.typed holds every run option");

const ob_flag ob_run_flags[] = {
    {"curves", "FILE", "curve file (default: every file under datasets/)", RO_CURVES, OB_FLAG_ONCE},
    {"curve", "ID,...", "only these curves", RO_CURVE, OB_FLAG_LIST},
    {"random", "N[:SEED]", "N random test curves of the families (seed 1 by default)", RO_RANDOM, OB_FLAG_ONCE},
    {"methods", "LIST|all", "methods to run (default all; './offbench list methods')", RO_METHODS, OB_FLAG_LIST},
    {"tols", "T,...", "tolerances (default 1e-1,1e-2,1e-3,1e-4,1e-5)", RO_TOLS, OB_FLAG_LIST},
    {"metric", "M", "bound, radial, normal, hausdorff (default), param or certified", RO_METRIC, OB_FLAG_ONCE},
    {"split", "RULE", "mid (default), maxerr, greedy or optimal", RO_SPLIT, OB_FLAG_ONCE},
    {"backend", "B", "auto (default), opencl or cpu", RO_BACKEND, OB_FLAG_ONCE},
    {"device", "NAME", "the OpenCL device whose name contains NAME", RO_DEVICE, OB_FLAG_ONCE},
    {"threads", "N", "OpenMP threads (default: all cores)", RO_THREADS, OB_FLAG_ONCE},
    {"engine", "E", "how work is scheduled: auto (default), group, level or device; never changes a row", RO_ENGINE,
     OB_FLAG_ONCE},
    {"chunk", "N", "pieces per fit/measure batch (default 512, 8192 on a GPU); never changes a row", RO_CHUNK, OB_FLAG_ONCE},
    {"samples", "S", "samples per piece of the sampled metrics (default 256)", RO_SAMPLES, OB_FLAG_ONCE},
    {"max-depth", "N", "subdivision depth limit (default 40)", RO_MAX_DEPTH, OB_FLAG_ONCE},
    {"max-segments", "N", "pieces per job limit (default 20000)", RO_MAX_SEGMENTS, OB_FLAG_ONCE},
    {"inflections", "yes|no", "split every method's input at inflections (default yes)", RO_INFLECTIONS, OB_FLAG_ONCE},
    {"param", "METHOD.NAME=VALUE", "a method parameter ('./offbench list methods')", RO_PARAM, OB_FLAG_REPEAT},
    {"job-timeout", "S", "thread seconds per job before status timeout", RO_JOB_TIMEOUT, OB_FLAG_ONCE},
    {"reps", "N", "timed repetitions after a warm-up run (samples.csv)", RO_REPS, OB_FLAG_ONCE},
    {"shard", "K/N", "run shard K of N (merge the shards with 'merge')", RO_SHARD, OB_FLAG_ONCE},
    {"out", "DIR", "output directory (default out)", RO_OUT, OB_FLAG_ONCE},
    {"resume", "DIR", "finish the interrupted run in DIR with its own options (any given must be its own)", RO_RESUME,
     OB_FLAG_ONCE},
    {"force", NULL, "replace the finished run in --out, or start afresh over an interrupted one's journal (without it both are refused)", RO_FORCE, OB_FLAG_ONCE},
    {"export", "DIR", "each job's approximation as JSON, .curves, DXF and SVG", RO_EXPORT, OB_FLAG_ONCE},
    {"certify", "[=tight]", "certify each job's error: err_upper, err_lower, certified and cert_ns, refined until "
     "the verdict (within tol or not) is proven; =tight: to err_upper <= err_lower (1 + 1e-3) (docs/certified.md)",
     RO_CERTIFY, OB_FLAG_ONCE},
    {"time-fits", NULL, "time each method's fits as a microbenchmark: fit_calls, method_ns, method_iqr_ns and "
     "fits.csv (docs/output.md)", RO_TIME_FITS, OB_FLAG_ONCE},
    {"fit-reps", "N", "--time-fits: rounds of measurements per job (default 5)", RO_FIT_REPS, OB_FLAG_ONCE},
    {"fit-min-time", "MS", "--time-fits: each measurement's length in ms of thread CPU time (default 1)",
     RO_FIT_MIN_TIME, OB_FLAG_ONCE},
    {"trimmed", NULL, "measure each job's approximation, trimmed by its own crossings, against the trimmed offset: "
     "trimmed_err and trimmed_cut (docs/export-measure.md)", RO_TRIMMED, OB_FLAG_ONCE},
};
const int ob_run_nflags = (int)(sizeof ob_run_flags / sizeof ob_run_flags[0]);

static int parse_curve_ids(const char *v, ob_run_opts *o)
{
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
    return 0;
}

static int parse_dir(const char *opt, const char *v, const char **out)
{
    if (!*v) {
        ob_error("%s: empty directory name", opt);
        return -1;
    }
    *out = v;
    return 0;
}

/* The selections: which curves, methods, tolerances, metric and split. */
static int apply_selection(ob_run_opts *o, int id, const char *opt, const char *v)
{
    switch (id) {
    case RO_CURVES: o->curves_file = v; return 0;
    case RO_CURVE: return parse_curve_ids(v, o);
    case RO_RANDOM: return ob_random_parse(opt, v, &o->random_n, &o->random_seed);
    case RO_METHODS: return parse_methods(v, o);
    case RO_TOLS: return parse_tols(v, o);
    case RO_METRIC:
        if (ob_metric_parse(v, &o->metric)) {
            ob_error("--metric: unknown metric '%s' (bound, radial, normal, hausdorff, param, certified)", v);
            return -1;
        }
        return 0;
    case RO_SPLIT:
        if (ob_split_parse(v, &o->split)) {
            ob_error("--split: unknown split rule '%s' (mid, maxerr, greedy, optimal)", v);
            return -1;
        }
        return 0;
    }
    return 1; /* not a selection */
}

/* How the run goes: backend, limits, outputs. */
static int apply_execution(ob_run_opts *o, int id, const char *opt, const char *v)
{
    double s;
    switch (id) {
    case RO_BACKEND:
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
        return 0;
    case RO_DEVICE: o->device = v; return 0;
    case RO_THREADS: return parse_int(opt, v, 1, 1024, &o->threads);
    case RO_ENGINE:
        if (ob_engine_parse(v, &o->driver.engine)) {
            ob_error("--engine: unknown engine '%s' (auto, group, level, device)", v);
            return -1;
        }
        return 0;
    case RO_CHUNK: return parse_int(opt, v, 1, 1 << 20, &o->driver.chunk);
    case RO_SAMPLES: return parse_int(opt, v, OB_MIN_SAMPLES, OB_MAX_SAMPLES, &o->driver.samples);
    case RO_MAX_DEPTH: return parse_int(opt, v, 1, 60, &o->driver.max_depth);
    case RO_MAX_SEGMENTS: return parse_int(opt, v, 1, 10000000, &o->driver.max_segments);
    case RO_INFLECTIONS:
        if (strcmp(v, "yes") != 0 && strcmp(v, "no") != 0) {
            ob_error("--inflections: expected yes or no, got '%s'", v);
            return -1;
        }
        o->driver.inflections = strcmp(v, "yes") == 0;
        return 0;
    case RO_JOB_TIMEOUT:
        if (ob_parse_double(v, &s) || !(s > 0) || s > 1e6) {
            ob_error("--job-timeout: expected seconds > 0 (at most 1e6), got '%s'", v);
            return -1;
        }
        o->driver.job_timeout_ns = s * 1e9;
        return 0;
    case RO_REPS: return parse_int(opt, v, 1, 1000, &o->reps);
    case RO_SHARD: return ob_shard_parse(opt, v, &o->shard_k, &o->shard_n);
    case RO_OUT: o->out_given = 1; return parse_dir(opt, v, &o->out_dir);
    case RO_RESUME: return parse_dir(opt, v, &o->resume_dir);
    case RO_FORCE: o->force = 1; return 0;
    case RO_EXPORT: return parse_dir(opt, v, &o->export_dir);
    case RO_CERTIFY:
        if (v && strcmp(v, "tight") != 0 && strcmp(v, "verdict") != 0) {
            ob_error("--certify: unknown mode '%s' (--certify alone: the verdict; --certify=tight)", v);
            return -1;
        }
        o->certify = v && strcmp(v, "tight") == 0 ? OB_CERTIFY_TIGHT : OB_CERTIFY_VERDICT;
        return 0;
    case RO_TIME_FITS: o->time_fits = 1; return 0;
    case RO_TRIMMED: o->trimmed = 1; return 0;
    case RO_FIT_REPS: o->fit_opts_given = 1; return parse_int(opt, v, 1, 1000, &o->fit_rounds);
    case RO_FIT_MIN_TIME:
        o->fit_opts_given = 1;
        if (ob_parse_double(v, &s) || !(s > 0) || s > 1e4) {
            ob_error("--fit-min-time: expected milliseconds > 0 (at most 1e4), got '%s'", v);
            return -1;
        }
        o->fit_min_ns = s * 1e6;
        return 0;
    }
    return 1;
}

/* --param: each METHOD.NAME at most once (the flag itself repeats). */
static int apply_param(ob_run_opts *o, const char *v)
{
    for (int k = 0; k < o->nparam_seen; k++)
        if (same_param(o->param_seen[k], v)) {
            ob_error("--param %.*s: given twice", (int)(strchr(v, '=') - v), v);
            return -1;
        }
    if (parse_param(v, o))
        return -1;
    if (o->nparam_seen < OB_MAX_PARAM_ARGS)
        o->param_seen[o->nparam_seen++] = v;
    return 0;
}

int ob_run_flag_apply(void *ctx, int id, const char *opt, const char *value)
{
    ob_run_opts *o = ctx;
    if (id >= 0 && id < RO_COUNT)  /* as given, for the messages of --resume (resume_opts.h) */
        o->typed[id] = value ? value : "";
    if (id == RO_PARAM)
        return apply_param(o, value);
    int rc = apply_selection(o, id, opt, value);
    if (rc <= 0)
        return rc;
    rc = apply_execution(o, id, opt, value);
    if (rc > 0) {
        ob_error("%s: not an option of run", opt);
        return -1;
    }
    return rc;
}

int ob_run_opt_set(ob_run_opts *o, const char *name, const char *value)
{
    char opt[64];
    snprintf(opt, sizeof opt, "--%s", name);
    for (int i = 0; i < ob_run_nflags; i++)
        if (strcmp(ob_run_flags[i].name, name) == 0)
            return ob_run_flag_apply(o, ob_run_flags[i].id, opt, value);
    ob_error("%s: not an option of run", opt);
    return -1;
}

const char *ob_run_opt_typed(const ob_run_opts *o, const char *name)
{
    for (int i = 0; i < ob_run_nflags; i++)
        if (strcmp(ob_run_flags[i].name, name) == 0)
            return o->typed[ob_run_flags[i].id];
    return NULL;
}

const char *ob_run_param_typed(const ob_run_opts *o, const char *key)
{
    const size_t n = strlen(key);
    for (int k = 0; k < o->nparam_seen; k++)
        if (strncmp(o->param_seen[k], key, n) == 0 && o->param_seen[k][n] == '=')
            return o->param_seen[k] + n + 1;
    return NULL;
}

int ob_run_opts_init(ob_run_opts *o, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    o->metric = OB_METRIC_HAUSDORFF;
    o->split = OB_SPLIT_MID;
    o->backend = OB_BACKEND_AUTO;
    o->out_dir = "out";
    o->argc = argc;
    o->argv = argv;
    ob_driver_defaults(&o->driver);
    o->fit_rounds = OB_FITTIME_ROUNDS;
    o->fit_min_ns = OB_FITTIME_MIN_NS;
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
    return 0;
}

int ob_run_opts_finish(ob_run_opts *o)
{
    if (o->fit_opts_given && !o->time_fits) {
        ob_error("--fit-reps and --fit-min-time set how --time-fits measures: add --time-fits");
        return -1;
    }
    if (!o->resume_dir)
        return 0;
    if (o->trimmed) {
        ob_error("--resume: not with --trimmed (a run with it keeps no journal: its pass measures the whole run)");
        return -1;
    }
    if (o->time_fits) {
        ob_error("--resume: not with --time-fits (the fits are timed in one pass over the whole run)");
        return -1;
    }
    if (o->out_given && strcmp(o->out_dir, o->resume_dir) != 0) {
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
    return 0;
}

int ob_run_opts_parse(int argc, char **argv, ob_run_opts *o)
{
    if (ob_run_opts_init(o, argc, argv))
        return OB_CLI_ERROR;
    const ob_flagset set = {ob_run_flags, ob_run_nflags, NULL, NULL, "run options", ob_run_flag_apply, o};
    const int rc = ob_cli_parse(OB_RUN_SYNOPSIS, &set, 1, argc, argv, 0, NULL, NULL);
    if (rc != OB_CLI_OK)
        return rc;
    return ob_run_opts_finish(o) ? OB_CLI_ERROR : OB_CLI_OK;
}

void ob_run_opts_free(ob_run_opts *o)
{
    if (!o)
        return;
    free_list(o->curve_ids, o->ncurve_ids);
    free(o->methods);
    free(o->params);
    free(o->curves_file_owned);
    o->curves_file_owned = NULL;
    o->curve_ids = NULL;
    o->methods = NULL;
    o->params = NULL;
}
