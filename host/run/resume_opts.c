/*
 * resume_opts.c - `run --resume DIR` with no other option: the run's own
 * options, taken from the fingerprint it left in DIR (see resume_opts.h).
 *
 * Why from the fingerprint and not meta.json: an interrupted run has no
 * meta.json yet (it is written with results.csv), while its journal's first
 * line, and a finished run's results.fingerprint, hold every option that
 * decides the results.  What is taken is checked again like any resume: the
 * journal's own comparison of the whole fingerprint (data, kernel, build)
 * still decides.
 */
#include "host/run/resume_opts.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "host/run/journal.h"
#include "host/run/record.h"

/* A fingerprint key that is a run option (journal.c writes them). */
typedef struct {
    const char *key, *flag;
} key_flag;

static const key_flag KEYS[] = {
    {"samples", "samples"}, {"max_depth", "max-depth"}, {"max_segments", "max-segments"},
    {"inflections", "inflections"}, {"job_timeout", "job-timeout"}, {"curves", "curve"},
    {"methods", "methods"}, {"tols", "tols"}, {"metric", "metric"}, {"split", "split"},
    {"certify", "certify"}, {"shard", "shard"},
};
enum { NKEYS = sizeof KEYS / sizeof KEYS[0] };

/* The parts of a data source as plan.c records it ("data"): a curve file,
 * "random N:SEED", the two joined by " + ", or the default curves' source
 * ("embedded copy of datasets/", or $OFFBENCH_DATA: host/io/datadir.c).
 * *flen: the length of the file part (0: none); *rnd: "N:SEED" or NULL;
 * returns 1 when the file part is the default curves. */
static int split_where(const char *where, size_t *flen, const char **rnd)
{
    const char *plus = strstr(where, " + random ");
    *rnd = NULL;
    *flen = strlen(where);
    if (strncmp(where, "random ", 7) == 0) {
        *rnd = where + 7;
        *flen = 0;
    } else if (plus) {
        *rnd = plus + 10;
        *flen = (size_t)(plus - where);
    }
    const char *env = getenv("OFFBENCH_DATA");
    return !*rnd && (strcmp(where, "embedded copy of datasets/") == 0 || (env && *env && strcmp(where, env) == 0));
}

/* --curves and --random from the run's data source. */
static int take_data(ob_run_opts *o, const char *where)
{
    size_t flen;
    const char *rnd;
    if (split_where(where, &flen, &rnd))
        return 0;
    if (rnd && ob_run_opt_set(o, "random", rnd) != 0)
        return -1;
    if (flen == 0)
        return 0;
    char *file = strndup(where, flen);
    if (!file) {
        ob_error("out of memory");
        return -1;
    }
    free(o->curves_file_owned);
    o->curves_file = o->curves_file_owned = file;
    return 0;
}

/* One option from its fingerprint value v, as the run had it. */
static int take_one(ob_run_opts *o, const key_flag *k, const char *v)
{
    if (strcmp(k->key, "inflections") == 0)
        return ob_run_opt_set(o, k->flag, strcmp(v, "0") == 0 ? "no" : "yes");
    if (strcmp(k->key, "job_timeout") == 0) {
        o->driver.job_timeout_ns = strtod(v, NULL);  /* nanoseconds, as recorded: exactly the run's */
        return 0;
    }
    if (strcmp(k->key, "certify") == 0) {
        o->certify = strcmp(v, "tight") == 0 ? OB_CERTIFY_TIGHT : strcmp(v, "verdict") == 0 ? OB_CERTIFY_VERDICT : 0;
        return 0;
    }
    if ((strcmp(k->key, "curves") == 0 && strcmp(v, "all") == 0) || (strcmp(k->key, "shard") == 0 && strcmp(v, "none") == 0))
        return 0;
    return ob_run_opt_set(o, k->flag, v);
}

/* Each method parameter not given, as the run had it ("METHOD.NAME"). */
static void take_params(ob_run_opts *o, const char *fp)
{
    for (int m = 0; ob_methods[m]; m++)
        for (int k = 0; k < ob_methods[m]->nparams; k++) {
            char key[128];
            snprintf(key, sizeof key, "%s.%s", ob_methods[m]->name, ob_methods[m]->params[k].name);
            char *v = ob_run_param_typed(o, key) ? NULL : ob_fp_get(fp, key);
            if (v)
                o->params[m * OB_MAX_PARAMS + k] = strtod(v, NULL);
            free(v);
        }
}

/* Every option that decides the results and was not given, from fp. */
static int take_all(ob_run_opts *o, const char *fp)
{
    int rc = 0;
    for (int i = 0; i < NKEYS && rc == 0; i++) {
        char *v = ob_run_opt_typed(o, KEYS[i].flag) ? NULL : ob_fp_get(fp, KEYS[i].key);
        rc = v ? take_one(o, &KEYS[i], v) : 0;
        free(v);
    }
    if (rc == 0 && !ob_run_opt_typed(o, "curves") && !ob_run_opt_typed(o, "random")) {
        char *where = ob_fp_get(fp, "data");
        rc = where ? take_data(o, where) : 0;
        free(where);
    }
    if (rc == 0)
        take_params(o, fp);
    return rc;
}

/* How a recorded value reads as the option that gives it. */
static void run_value(const key_flag *k, const char *v, char *out, size_t len)
{
    if (strcmp(k->key, "inflections") == 0)
        snprintf(out, len, "--inflections %s", strcmp(v, "0") == 0 ? "no" : "yes");
    else if (strcmp(k->key, "job_timeout") == 0)
        snprintf(out, len, strtod(v, NULL) > 0 ? "--job-timeout %g" : "no --job-timeout", strtod(v, NULL) * 1e-9);
    else if (strcmp(k->key, "certify") == 0)
        snprintf(out, len, "%s", strcmp(v, "tight") == 0 ? "--certify=tight" : strcmp(v, "verdict") == 0 ? "--certify" : "no --certify");
    else if (strcmp(k->key, "curves") == 0 && strcmp(v, "all") == 0)
        snprintf(out, len, "every curve (no --curve)");
    else if (strcmp(k->key, "shard") == 0 && strcmp(v, "none") == 0)
        snprintf(out, len, "no --shard");
    else
        snprintf(out, len, "--%s %.200s", k->flag, v);
}

/* A data source as the options that give it. */
static void data_value(const char *where, char *out, size_t len)
{
    size_t flen;
    const char *rnd;
    if (split_where(where, &flen, &rnd))
        snprintf(out, len, "the curves under datasets/ (no --curves, no --random)");
    else
        snprintf(out, len, "%s%.*s%s%s%s", flen ? "--curves " : "", (int)(flen > 300 ? 300 : flen), where,
                 flen && rnd ? " " : "", rnd ? "--random " : "", rnd ? rnd : "");
}

/* The refusal of an option given that is not the run's own. */
static int refuse(const char *path, int journal, const char *dir, const char *given, const char *run)
{
    if (journal)
        ob_error("%s:1: the interrupted run had other options: %s (as given), the run's %s; leave the option out "
                 "to take the run's own (run --resume %s), or start afresh (another --out, or --force)",
                 path, given, run, dir);
    else
        ob_error("%s: the finished run had other options: %s (as given), the run's %s; leave the option out to "
                 "take the run's own (run --resume %s), or run afresh (another --out)", path, given, run, dir);
    return -1;
}

/* The data source given (--curves, --random), in plan.c's words, and as
 * typed; "" when neither was given. */
static void given_data(const ob_run_opts *o, char *where, size_t wlen, char *typed, size_t tlen)
{
    const char *f = ob_run_opt_typed(o, "curves"), *r = ob_run_opt_typed(o, "random");
    where[0] = typed[0] = '\0';
    if (!f && !r)
        return;
    snprintf(where, wlen, "%s%s", f ? f : "", f && r ? " + " : "");
    if (r)
        snprintf(where + strlen(where), wlen - strlen(where), "random %ld:%" PRIu64, o->random_n, o->random_seed);
    snprintf(typed, tlen, "%s%s%s%s%s", f ? "--curves " : "", f ? f : "", f && r ? " " : "", r ? "--random " : "",
             r ? r : "");
}

/* Each option given that the run recorded otherwise is refused. */
static int check_given(const ob_run_opts *o, const char *fp, const char *path, int journal)
{
    char where[4200], typed[4300], given[4400], run[600];
    given_data(o, where, sizeof where, typed, sizeof typed);
    const ob_run_record rec = {0};
    char *now = ob_resume_fingerprint(o, &rec, where), *was = ob_fp_get(fp, "data");
    int rc = now ? 0 : -1;
    if (!now)
        ob_error("out of memory");
    if (rc == 0 && typed[0] && was && strcmp(was, where) != 0) {
        data_value(was, run, sizeof run);
        rc = refuse(path, journal, o->resume_dir, typed, run);
    }
    for (int i = 0; i < NKEYS && rc == 0; i++) {
        const char *t = ob_run_opt_typed(o, KEYS[i].flag);
        char *w = t ? ob_fp_get(fp, KEYS[i].key) : NULL, *n = w ? ob_fp_get(now, KEYS[i].key) : NULL;
        if (w && n && strcmp(w, n) != 0) {
            snprintf(given, sizeof given, "--%s%s%.300s", KEYS[i].flag, t[0] ? " " : "", t);
            run_value(&KEYS[i], w, run, sizeof run);
            rc = refuse(path, journal, o->resume_dir, given, run);
        }
        free(w);
        free(n);
    }
    for (int k = 0; k < o->nparam_seen && rc == 0; k++) {
        const char *eq = strchr(o->param_seen[k], '=');
        char key[160];
        snprintf(key, sizeof key, "%.*s", eq ? (int)(eq - o->param_seen[k]) : 0, o->param_seen[k]);
        char *w = ob_fp_get(fp, key), *n = w ? ob_fp_get(now, key) : NULL;
        if (w && n && strcmp(w, n) != 0) {
            snprintf(given, sizeof given, "--param %.300s", o->param_seen[k]);
            snprintf(run, sizeof run, "--param %s=%.100s", key, w);
            rc = refuse(path, journal, o->resume_dir, given, run);
        }
        free(w);
        free(n);
    }
    free(was);
    free(now);
    return rc;
}

/* Whether any option that decides the results was given. */
static int any_given(const ob_run_opts *o)
{
    for (int i = 0; i < NKEYS; i++)
        if (ob_run_opt_typed(o, KEYS[i].flag))
            return 1;
    return o->nparam_seen > 0 || ob_run_opt_typed(o, "curves") || ob_run_opt_typed(o, "random");
}

int ob_resume_take_options(ob_run_opts *o)
{
    char path[4200];
    int journal = 0;
    char *fp = ob_stored_fingerprint(o->resume_dir, path, sizeof path, &journal);
    if (!fp) {
        if (journal && !any_given(o)) {
            ob_error("%s:1: no options of a run to take (the journal is not whole, or not offbench's): give the "
                     "run's own options with --resume %s, or start afresh (another --out, or --force)", path,
                     o->resume_dir);
            return -1;
        }
        return 0;  /* nothing there: the resume itself says so */
    }
    const char *typed[OB_RUN_MAX_FLAGS];
    memcpy(typed, o->typed, sizeof typed);  /* what was given, not what is taken */
    int rc = take_all(o, fp);
    memcpy(o->typed, typed, sizeof typed);
    if (rc == 0)
        rc = check_given(o, fp, path, journal);
    free(fp);
    return rc;
}
