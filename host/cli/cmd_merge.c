/*
 * cmd_merge.c - ./offbench merge DIR... --out DIR: the shards of one run
 * (`run --shard K/N`, each in its own directory) into exactly the results.csv
 * the unsharded run writes, with its meta.json and, when every shard has one,
 * samples.csv.
 *
 * Refused (exit 2, the reason naming the directory): a directory without a
 * finished shard (results.csv, shard.csv, meta.json); shards of another run
 * (plan_hash: the job list and the options that decide results; shard
 * count; job total); another build or method versions (git_commit, compiler,
 * cflags, method_versions.*); the same shard twice; a shard missing; a job
 * index out of range or in two shards; a shard.csv whose indices do not match
 * its results.csv rows one for one; a results.csv with another header; a
 * directory with a journal (results.journal.csv: an unfinished shard); a row
 * whose key (curve, d, method, metric, split, tol) is not that of the job
 * shard.csv gives it (shard.csv holds each job's index and key hash: the
 * reason names results.csv and the line); rows whose keys, in job order, do
 * not hash to the run's plan_hash (from meta.json's plan_seed); a shard of
 * run --certify with an uncertified one, or another --certify mode (the
 * reason names --certify, meta.json's certify.mode); a shard of run
 * --certify with a job with an approximation (ok, limit) but no
 * certificate (naming results.csv and the line).  Rows
 * are copied as text, so the merged file is byte for byte what the shards
 * wrote, in job order.  Like run, merge takes --out's lock (DIR/.lock,
 * ob_take_run_dir): exit 2 while another process holds it.  Exit 1: the
 * output cannot be written.
 *
 * meta.json: the meta.json of shard 0 with "shard" set to null,
 * "merged_shards" and "shards" (each shard's backend, threads, host, ...)
 * added, "jobs" the whole run's, "wall_seconds" the longest shard's, and
 * "mixed" for a value the shards do not share (merge_meta.c, merge.h).
 *
 * --export: shards that exported into one directory each wrote
 * index.shardK-of-N.csv there; merge checks them against the shards' rows
 * and writes that directory's index.csv, in job order (merge_export.c).
 */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "host/io/fsutil.h"
#include "host/io/columns.h"
#include "host/cli/commands.h"
#include "host/cli/merge.h"
#include "host/cli/cliopts.h"
#include "host/diag.h"
#include "host/io/metajson.h"
#include "host/io/output.h"
#include "host/io/results_csv.h"
#include "host/run/shard.h"
#include "host/run/signals.h"
#include "host/io/slurp.h"

typedef ob_shard_in shard_in;


static void shard_free(shard_in *s)
{
    ob_json_free(&s->meta);
    free(s->meta_text);
    free(s->res_text);
    free(s->idx_text);
    free(s->smp_text);
    free(s->lines);
    free(s->slines);
    free(s->idx);
    free(s->key);
}

/* The key of a results.csv row (curve, d, method, metric, split, tol) as
 * written, unquoted into buf; 0, or -1 when the line has no six fields. */
static int row_key(const char *line, char *buf, size_t cap, const char *key[6])
{
    size_t n = 0;
    const char *p = line;
    for (int k = 0; k < 6; k++) {
        key[k] = buf + n;
        if (*p == '"') {
            for (p++;; p++) {
                if (!*p)
                    return -1;
                if (*p == '"') {
                    if (p[1] != '"')
                        break;
                    p++;
                }
                if (n + 1 >= cap)
                    return -1;
                buf[n++] = *p;
            }
            p++;
        } else {
            for (; *p && *p != ','; p++) {
                if (n + 1 >= cap)
                    return -1;
                buf[n++] = *p;
            }
        }
        if (n + 1 >= cap || (*p != ',' && k < 5) || (k == 5 && *p != ',' && *p))
            return -1;
        buf[n++] = '\0';
        if (*p)
            p++;
    }
    return 0;
}

int ob_merge_split_lines(char *text, size_t len, char **hdr, char ***v, size_t *n)
{
    size_t cap = 64;
    *v = malloc(cap * sizeof **v);
    *n = 0;
    *hdr = NULL;
    if (!*v)
        return -1;
    char *p = text, *end = text + len;
    while (p < end) {
        char *nl = memchr(p, '\n', (size_t)(end - p));
        char *e = nl ? nl : end;
        if (e > p && e[-1] == '\r')
            e[-1] = '\0';
        *e = '\0';
        if (!*hdr) {
            *hdr = p;
        } else if (*p) {
            if (*n == cap) {
                char **nv = realloc(*v, (cap *= 2) * sizeof **v);
                if (!nv)
                    return -1;
                *v = nv;
            }
            (*v)[(*n)++] = p;
        }
        p = nl ? nl + 1 : end;
    }
    return 0;
}

static const char *meta_str(const shard_in *s, const char *key)
{
    const ob_json_entry *e = ob_json_get(&s->meta, key);
    return e ? e->value : "(absent)";
}

/* Reads one shard directory; 0, or -1 after ob_error(). */
/* A finished shard's meta.json (no journal beside it): its K/N and reps. */
static int shard_meta(shard_in *s, const char *dir)
{
    char path[4200];
    ob_err err;
    snprintf(path, sizeof path, "%s/results.journal.csv", dir);
    FILE *jf = fopen(path, "r");
    if (jf || errno != ENOENT) {
        if (jf)
            fclose(jf);
        ob_error("merge: %s: an unfinished shard (%s is there: finish it with run ... --resume %s)", dir, path, dir);
        return -1;
    }
    snprintf(path, sizeof path, "%s/meta.json", dir);
    if (ob_json_load(path, &s->meta, &err) != 0 ||
        ob_slurp(path, &s->meta_text, &s->meta_len, &err) != 0) {
        ob_error("merge: %s (not a finished shard?)", err.msg);
        return -1;
    }
    const ob_json_entry *sh = ob_json_get(&s->meta, "shard");
    if (!sh || sh->type != OB_JSON_STRING || sscanf(sh->value, "%d/%d", &s->k, &s->n) != 2 || s->k < 0 ||
        s->k >= s->n) {
        ob_error("merge: %s: \"shard\" is %s: not a run with --shard K/N", path, sh ? sh->value : "absent");
        return -1;
    }
    const ob_json_entry *reps = ob_json_get(&s->meta, "reps");
    s->reps = reps ? atoi(reps->value) : 1;
    return 0;
}

/* Its results.csv, whole lines as run writes them. */
static int shard_results(shard_in *s, const char *dir)
{
    char path[4200], *hdr;
    ob_err err;
    snprintf(path, sizeof path, "%s/results.csv", dir);
    ob_res_table t;
    if (ob_res_load(path, &t, &err) != 0) {
        ob_error("merge: %s", err.msg);
        return -1;
    }
    const int nrows = t.n;
    /* a shard of run --certify: every job with an approximation has its
     * certificate (or cert_ns alone: stopped by --job-timeout) */
    const ob_json_entry *cm = ob_json_get(&s->meta, "certify.mode");
    for (int i = 0; cm && i < t.n; i++) {
        const ob_res_row *r = &t.v[i];
        if ((strcmp(r->status, "ok") == 0 || strcmp(r->status, "limit") == 0) && !r->cert_done) {
            ob_error("merge: %s:%d: status %s with no certificate (err_upper, err_lower, certified and cert_ns "
                     "empty) in a shard of run --certify (meta.json certify.mode %s)", path, r->line, r->status,
                     cm->value);
            ob_res_free(&t);
            return -1;
        }
    }
    ob_res_free(&t);
    if (ob_slurp(path, &s->res_text, &s->res_len, &err) != 0) {
        ob_error("merge: %s", err.msg);
        return -1;
    }
    if (ob_merge_split_lines(s->res_text, s->res_len, &hdr, &s->lines, &s->nlines) != 0) {
        ob_error("merge: out of memory");
        return -1;
    }
    if (!hdr || strcmp(hdr, ob_results_header()) != 0 || s->nlines != (size_t)nrows) {
        ob_error("merge: %s: not results.csv as run writes it (header, or a row over several lines)", path);
        return -1;
    }
    return 0;
}

/* Its shard.csv: each row's index in the run and key hash, checked against
 * the row. */
static int shard_index(shard_in *s, const char *dir)
{
    char path[4200];
    ob_err err;
    snprintf(path, sizeof path, "%s/shard.csv", dir);
    char *hdr, **il;
    size_t ni;
    if (ob_slurp(path, &s->idx_text, &s->idx_len, &err) != 0) {
        ob_error("merge: %s", err.msg);
        return -1;
    }
    if (ob_merge_split_lines(s->idx_text, s->idx_len, &hdr, &il, &ni) != 0 || !hdr || strcmp(hdr, "job,key") != 0 ||
        ni != s->nlines) {
        free(il);
        ob_error("merge: %s: expected the header 'job,key' and one index per row of results.csv (%zu)", path,
                 s->nlines);
        return -1;
    }
    s->idx = malloc((ni ? ni : 1) * sizeof *s->idx);
    s->key = malloc((ni ? ni : 1) * sizeof *s->key);
    for (size_t i = 0; s->idx && s->key && i < ni; i++) {
        char *e, *e2;
        errno = 0;
        unsigned long long v = strtoull(il[i], &e, 10);
        const int bad = *il[i] == '-' || e == il[i] || *e != ',' || errno;
        unsigned long long h = bad ? 0 : strtoull(e + 1, &e2, 16);
        if (bad || e2 != e + 17 || *e2 || errno) {
            ob_error("merge: %s:%zu: '%s' is not a job index and key hash", path, i + 2, il[i]);
            free(il);
            return -1;
        }
        s->idx[i] = (size_t)v;
        s->key[i] = (uint64_t)h;
    }
    free(il);
    if (!s->idx || !s->key) {
        ob_error("out of memory");
        return -1;
    }
    /* every row must be the job shard.csv says it is */
    for (size_t i = 0; i < ni; i++) {
        char buf[4096];
        const char *key[6];
        if (row_key(s->lines[i], buf, sizeof buf, key) != 0 || ob_key_step(OB_FNV_BASIS, key) != s->key[i]) {
            ob_error("merge: %s/results.csv:%zu: the row is not job %zu of the run (%s/shard.csv:%zu): rows "
                     "edited, reordered or from another run",
                     dir, i + 2, s->idx[i], dir, i + 2);
            return -1;
        }
    }
    return 0;
}

/* Its samples.csv, when there is one (--reps). */
static int shard_samples(shard_in *s, const char *dir)
{
    char path[4200];
    ob_err err;
    char *hdr;
    snprintf(path, sizeof path, "%s/samples.csv", dir);
    FILE *probe = fopen(path, "r");
    if (probe) {
        fclose(probe);
        if (ob_slurp(path, &s->smp_text, &s->smp_len, &err) != 0 ||
            ob_merge_split_lines(s->smp_text, s->smp_len, &hdr, &s->slines, &s->nslines) != 0 || !hdr ||
            strcmp(hdr, OB_SAMPLES_HEADER) != 0 || s->nslines != s->nlines * (size_t)s->reps) {
            ob_error("merge: %s: expected %d rows per job of results.csv", path, s->reps);
            return -1;
        }
    }
    return 0;
}

static int load_shard(shard_in *s, const char *dir)
{
    memset(s, 0, sizeof *s);
    s->dir = dir;
    return shard_meta(s, dir) || shard_results(s, dir) || shard_index(s, dir) || shard_samples(s, dir) ? -1 : 0;
}

/* What every shard of one run has in common. */
static int check_same(const shard_in *a, const shard_in *b)
{
    static const char *const keys[] = {"data_hash", "kernel_fnv1a", "plan_hash", "plan_seed", "jobs_total", "git_commit", "compiler", "cflags", "reps"};
    /* --certify is part of the plan (plan_hash): say so rather than only that the hashes differ */
    const ob_json_entry *ca = ob_json_get(&a->meta, "certify.mode"), *cb = ob_json_get(&b->meta, "certify.mode");
    if (!ob_json_same(ca, cb)) {
        if (ca && cb)
            ob_error("merge: %s and %s are not shards of one run: %s ran with --certify=%s, %s with --certify=%s "
                     "(meta.json certify.mode)", a->dir, b->dir, a->dir, ca->value, b->dir, cb->value);
        else
            ob_error("merge: %s and %s are not shards of one run: %s ran with --certify (mode %s), %s without it "
                     "(meta.json certify.mode)", a->dir, b->dir, ca ? a->dir : b->dir, (ca ? ca : cb)->value,
                     ca ? b->dir : a->dir);
        return -1;
    }
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        if (!ob_json_same(ob_json_get(&a->meta, keys[k]), ob_json_get(&b->meta, keys[k]))) {
            ob_error("merge: %s and %s are not shards of one run: %s %s vs %s", a->dir, b->dir, keys[k],
                     meta_str(a, keys[k]), meta_str(b, keys[k]));
            return -1;
        }
    for (int i = 0; i < a->meta.n; i++) {
        const ob_json_entry *e = &a->meta.v[i];
        if (strncmp(e->path, "method_versions.", 16) == 0 && !ob_json_same(e, ob_json_get(&b->meta, e->path))) {
            ob_error("merge: %s and %s: %s %s vs %s", a->dir, b->dir, e->path, e->value, meta_str(b, e->path));
            return -1;
        }
    }
    if (a->n != b->n) {
        ob_error("merge: %s is shard %d/%d, %s is %d/%d: another shard count", a->dir, a->k, a->n, b->dir, b->k,
                 b->n);
        return -1;
    }
    if ((a->smp_text != NULL) != (b->smp_text != NULL)) {
        ob_error("merge: %s has samples.csv and %s has not", a->smp_text ? a->dir : b->dir,
                 a->smp_text ? b->dir : a->dir);
        return -1;
    }
    return 0;
}

typedef struct {
    const shard_in *sh;
    int nsh;
    size_t total;
    const int *who;        /* shard of each job */
    const size_t *row;     /* its row in that shard */
    double wall;
} merged;

static int write_results_cb(FILE *f, void *ctx)
{
    const merged *m = ctx;
    fprintf(f, "%s\n", ob_results_header());
    for (size_t j = 0; j < m->total; j++)
        fprintf(f, "%s\n", m->sh[m->who[j]].lines[m->row[j]]);
    return ferror(f) ? -1 : 0;
}

static int write_samples_cb(FILE *f, void *ctx)
{
    const merged *m = ctx;
    fprintf(f, "%s\n", OB_SAMPLES_HEADER);
    for (size_t j = 0; j < m->total; j++) {
        const shard_in *s = &m->sh[m->who[j]];
        for (int r = 0; r < s->reps; r++)
            fprintf(f, "%s\n", s->slines[m->row[j] * (size_t)s->reps + (size_t)r]);
    }
    return ferror(f) ? -1 : 0;
}

static int write_meta_cb(FILE *f, void *ctx)
{
    const merged *m = ctx;
    return ob_merge_write_meta(f, m->sh, m->nsh, m->total, m->wall);
}

static const ob_flag merge_flags[] = {
    {"out", "DIR", "the merged run's directory", 0, OB_FLAG_ONCE},
};

static int apply_merge_flag(void *ctx, int id, const char *opt, const char *v)
{
    (void)id;
    if (!*v) {
        ob_error("merge: %s needs a directory", opt);
        return -1;
    }
    *(const char **)ctx = v;
    return 0;
}

/* Every shard K of N given exactly once. */
static int check_complete_set(const shard_in *sh, int nin, const char *const *in)
{
    const int n = sh[0].n;
    int *have = calloc((size_t)n, sizeof *have);
    if (!have)
        return -1;
    for (int i = 0; i < nin; i++) {
        if (have[sh[i].k]) {
            ob_error("merge: shard %d/%d given twice (%s and %s)", sh[i].k, n, in[have[sh[i].k] - 1], in[i]);
            free(have);
            return -1;
        }
        have[sh[i].k] = i + 1;
    }
    for (int k = 0; k < n; k++)
        if (!have[k]) {
            ob_error("merge: shard %d/%d is missing: an incomplete set", k, n);
            free(have);
            return -1;
        }
    free(have);
    return 0;
}

/* Where each of the run's total jobs is: shard who[j], line row[j]; every
 * job in exactly one shard.  *wall: the slowest shard's wall time. */
static int map_rows(const shard_in *sh, int nin, const char *const *in, size_t total, int *who, size_t *row,
                    double *wall)
{
    *wall = 0.0;
    for (int i = 0; i < nin; i++) {
        const ob_json_entry *w = ob_json_get(&sh[i].meta, "wall_seconds");
        if (w && atof(w->value) > *wall)
            *wall = atof(w->value);
        for (size_t r = 0; r < sh[i].nlines; r++) {
            const size_t j = sh[i].idx[r];
            if (j >= total) {
                ob_error("merge: %s/shard.csv:%zu: job %zu, but the run has %zu jobs", in[i], r + 2, j, total);
                return -1;
            }
            if (who[j] >= 0) {
                ob_error("merge: job %zu is in %s and in %s: overlapping shards", j, in[who[j]], in[i]);
                return -1;
            }
            who[j] = i;
            row[j] = r;
        }
    }
    for (size_t j = 0; j < total; j++)
        if (who[j] < 0) {
            ob_error("merge: job %zu is in no shard: a gap (of %zu jobs)", j, total);
            return -1;
        }
    return 0;
}

/* The rows' keys in job order must give the plan's hash: each row is the
 * job its shard.csv names (checked above), and these are the run's jobs
 * at those indices */
static int check_plan_hash(const shard_in *sh, const char *const *in, size_t total, const int *who, const size_t *row)
{
    const ob_json_entry *ps = ob_json_get(&sh[0].meta, "plan_seed"), *ph = ob_json_get(&sh[0].meta, "plan_hash");
    if (!ps || !ph || ps->type != OB_JSON_STRING || ph->type != OB_JSON_STRING) {
        ob_error("merge: %s/meta.json: no plan_seed or plan_hash (written by an older offbench?)", in[0]);
        return -1;
    }
    uint64_t h = (uint64_t)strtoull(ps->value, NULL, 16);
    for (size_t j = 0; j < total; j++) {
        char buf[4096];
        const char *key[6];
        row_key(sh[who[j]].lines[row[j]], buf, sizeof buf, key);  /* parsed in load_shard */
        h = ob_key_step(h, key);
    }
    char hex[20];
    snprintf(hex, sizeof hex, "%016" PRIx64, h);
    if (strcmp(hex, ph->value) != 0) {
        ob_error("merge: the rows in job order are not the run's jobs (their keys hash to %s, plan_hash is %s): "
                 "job indices in shard.csv edited?",
                 hex, ph->value);
        return -1;
    }
    return 0;
}

int ob_cmd_merge(int argc, char **argv)
{
    const char *out = NULL;
    int nin = 0, status = 2;
    const char **in = calloc((size_t)(argc > 1 ? argc : 1), sizeof *in);
    shard_in *sh = NULL;
    int *who = NULL;
    size_t *row = NULL;
    int lock_fd = -1;
    ob_merge_export xp = {0};
    if (!in)
        return 1;
    const ob_flagset flags = {merge_flags, 1, NULL, NULL, "options", apply_merge_flag, &out};
    const int prc = ob_cli_parse("DIR... --out DIR   (the shards of one run into its results.csv)", &flags, 1, argc,
                                 argv, argc, (char **)in, &nin);
    if (prc != OB_CLI_OK) {
        status = prc == OB_CLI_HELP ? 0 : 2;
        goto done;
    }
    if (!out || nin == 0) {
        ob_error("merge: usage: ./offbench merge DIR... --out DIR (the directories of run --shard K/N)");
        goto done;
    }
    /* the shards themselves are the inputs: --out must not be, or hold, one */
    if (ob_check_out_not_input("merge", out, 1, in, (size_t)nin) != 0)
        goto done;  /* status 2 */
    sh = calloc((size_t)nin, sizeof *sh);
    if (!sh)
        goto done;
    for (int i = 0; i < nin; i++)
        if (ob_stop_signal() || load_shard(&sh[i], in[i]) != 0)
            goto done;
    for (int i = 1; i < nin; i++)
        if (check_same(&sh[0], &sh[i]) != 0)
            goto done;
    if (check_complete_set(sh, nin, in) != 0)
        goto done;
    const ob_json_entry *te = ob_json_get(&sh[0].meta, "jobs_total");
    const size_t total = te ? (size_t)strtoull(te->value, NULL, 10) : 0;
    who = malloc((total ? total : 1) * sizeof *who);
    row = malloc((total ? total : 1) * sizeof *row);
    if (!who || !row)
        goto done;
    for (size_t j = 0; j < total; j++)
        who[j] = -1;
    double wall;
    if (map_rows(sh, nin, in, total, who, row, &wall) != 0 || check_plan_hash(sh, in, total, who, row) != 0 ||
        ob_merge_export_load(sh, nin, who, row, total, &xp) != 0)
        goto done;
    /* the run directory's lock, as run takes it: no run (and no other
     * merge) writes there while the merged files are written */
    if ((status = ob_take_run_dir("merge", out, 1, &lock_fd)) != 0)
        goto done;
    merged m = {sh, nin, total, who, row, wall};
    ob_out_file set[3];  /* all or none, results.csv renamed last */
    size_t nset = 0;
    set[nset++] = (ob_out_file){"meta.json", write_meta_cb, &m};
    if (sh[0].smp_text)
        set[nset++] = (ob_out_file){"samples.csv", write_samples_cb, &m};
    set[nset++] = (ob_out_file){"results.csv", write_results_cb, &m};
    status = ob_stop_signal() || ob_write_set_atomically(out, set, nset) != 0 ? 1 : 0;
    if (status == 0)
        ob_info("merged %d shards, %zu jobs, into %s/results.csv", nin, total, out);
    if (status == 0 && ob_merge_export_write(&xp) != 0)
        status = 1;  /* --export: the shards' indexes into index.csv (merge.h) */
done:
    if (ob_stop_signal() && status != 0)  /* the set is written whole or not at all */
        status = ob_stop_exit("merge: nothing written to %s; run the command again", out);
    if (lock_fd >= 0)
        close(lock_fd);  /* the lock goes with it */
    ob_merge_export_free(&xp);
    for (int i = 0; sh && i < nin; i++)
        shard_free(&sh[i]);
    free(sh);
    free(who);
    free(row);
    free(in);
    return status;
}
