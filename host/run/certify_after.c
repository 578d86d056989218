/*
 * certify_after.c - `offbench certify RUN_DIR`: a finished run certified
 * after the fact (see certify_after.h).
 */
#include "host/run/certify_after.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/diag.h"
#include "host/io/columns.h"
#include "host/io/export.h"
#include "host/io/fsutil.h"
#include "host/io/metajson.h"
#include "host/io/output.h"
#include "host/io/results_csv.h"
#include "host/io/slurp.h"
#include "host/run/certify.h"
#include "host/run/journal.h"
#include "host/run/plan.h"
#include "host/run/resume_opts.h"
#include "host/run/shard.h"
#include "host/run/signals.h"

static const char MAGIC[] = "#offbench-certify-journal 1 ";
enum { PATH_LEN = 4200 };

/* One pass: the run as this binary plans it, its files, and what is done. */
typedef struct {
    ob_run_opts *o;
    const ob_cert_select *sel;
    const char *dir;
    ob_run_record rec;
    ob_curveset set;
    char where[4096];
    ob_job *jobs;                /* this run's (shard's) jobs, in job order */
    size_t njobs;
    size_t *shard_idx;
    uint64_t plan_hash_cert, plan_seed_cert; /* the plan of the run with --certify */
    ob_cl *cl;
    int lock_fd;
    char *fp_now;                /* the run's fingerprint as this binary computes it */
    char *fp_jr;                 /* the same without --certify: the journal's first line (a
                                    pass killed after its files were written, before its
                                    journal went, left it under the uncertified fingerprint) */
    char res_path[PATH_LEN], meta_path[PATH_LEN], fp_path[PATH_LEN], jr_path[PATH_LEN];
    char *text;                  /* results.csv as it is */
    size_t len;
    ob_res_table tab;
    int *line_of;                /* job i's row: its first line in results.csv */
    char *fresh;                 /* job i certified by this pass (or taken from the journal) */
    size_t nfresh;
    double prev_wall;            /* meta.json's certify.wall_seconds, 0 without */
    ob_journal jr;
} pass;

/* ---- is it a run, and this binary's ------------------------------------ */

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* 0, or the exit status after ob_error(). */
static int check_dir(pass *p)
{
    struct stat st;
    char jp[PATH_LEN];
    if (stat(p->dir, &st) != 0) {
        ob_error("certify: %s: %s (give the directory of a finished run)", p->dir, strerror(errno));
        return 2;
    }
    if (!S_ISDIR(st.st_mode)) {
        ob_error("certify: %s is not a directory (give the directory of a finished run)", p->dir);
        return 2;
    }
    snprintf(jp, sizeof jp, "%s/results.journal.csv", p->dir);
    if (exists(jp)) {
        ob_error("certify: %s holds an interrupted run (%s): finish it first with run --resume %s", p->dir, jp,
                 p->dir);
        return 2;
    }
    snprintf(p->res_path, sizeof p->res_path, "%s/results.csv", p->dir);
    snprintf(p->meta_path, sizeof p->meta_path, "%s/meta.json", p->dir);
    snprintf(p->fp_path, sizeof p->fp_path, "%s/results.fingerprint", p->dir);
    snprintf(p->jr_path, sizeof p->jr_path, "%s/certify.journal.csv", p->dir);
    if (!exists(p->res_path) || !exists(p->meta_path)) {
        ob_error("certify: %s is not a run directory: it has no %s (the directory `run --out DIR` wrote)", p->dir,
                 exists(p->res_path) ? "meta.json" : "results.csv");
        return 2;
    }
    if (!exists(p->fp_path)) {
        ob_error("certify: %s has no results.fingerprint (the options, data and build of its run; a merged or "
                 "MPI run, or one of an older build, has none): its jobs cannot be run again to refit their "
                 "pieces; certify the shards before merging, or run it again with --certify", p->dir);
        return 2;
    }
    ob_err err;
    const int lrc = ob_lock_dir(p->dir, &p->lock_fd, &err);
    if (lrc != 0) {
        ob_error("certify: %s", err.msg);
        return lrc == -2 ? 2 : 1;
    }
    return 0;
}

/* The run's options (its fingerprint), curves, jobs and hashes. */
static int plan(pass *p)
{
    ob_run_opts *o = p->o;
    o->out_dir = o->resume_dir = p->dir;
    if (ob_resume_take_options(o) != 0)
        return 2;
    if (o->threads > 0)
        omp_set_num_threads(o->threads);
    if (ob_load_run_curves(o, &p->set, p->where, sizeof p->where) != 0)
        return 2;
    p->rec.curves = &p->set;
    ob_offset_degrees(o, &p->set);
    p->jobs = ob_plan_jobs(o, &p->set, &p->njobs);
    if (!p->jobs) {
        ob_error("out of memory planning the jobs");
        return 1;
    }
    p->rec.data_hash = ob_curves_hash(o, &p->set);
    p->rec.jobs_total = p->njobs;
    for (int cert = 0; cert < 2; cert++) {  /* the plan as the run had it, and with --certify */
        ob_run_opts oc = *o;
        oc.certify = cert ? p->sel->mode : o->certify;
        char *fp = ob_run_fingerprint(&oc, p->where, p->rec.data_hash);
        if (!fp) {
            ob_error("out of memory");
            return 1;
        }
        const uint64_t h = ob_plan_hash(p->jobs, p->njobs, fp), s = ob_plan_seed(fp);
        free(fp);
        if (cert) {
            p->plan_hash_cert = h;
            p->plan_seed_cert = s;
        } else {
            p->rec.plan_hash = h;
            p->rec.plan_seed = s;
        }
    }
    p->rec.shard_k = o->shard_k;
    p->rec.shard_n = o->shard_n;
    if (o->shard_n > 0 && ob_select_shard(o->shard_k, o->shard_n, &p->jobs, &p->njobs, &p->shard_idx) != 0)
        return 1;
    const int brc = ob_open_backend(o->backend, o->device, 1u << o->metric, &p->rec.binfo, &p->cl);
    return brc ? ob_backend_exit(brc) : 0;
}

/* The run's fingerprint and plan hash against this binary's: 0, or 2 after
 * ob_error() naming the first difference. */
static int check_identity(pass *p)
{
    ob_err err;
    char *was = NULL, diff[512];
    size_t wlen = 0;
    if (ob_slurp(p->fp_path, &was, &wlen, &err) != 0) {
        ob_error("certify: %s", err.msg);
        return 2;
    }
    while (wlen > 0 && (was[wlen - 1] == '\n' || was[wlen - 1] == '\r'))
        was[--wlen] = '\0';
    ob_run_opts oc = *p->o;
    oc.certify = 0;
    p->fp_now = ob_resume_fingerprint(p->o, &p->rec, p->where);
    p->fp_jr = ob_resume_fingerprint(&oc, &p->rec, p->where);
    if (!p->fp_now || !p->fp_jr) {
        free(was);
        ob_error("out of memory");
        return 1;
    }
    const int d = ob_fingerprint_diff(was, p->fp_now, diff, sizeof diff);
    free(was);
    if (d) {
        ob_error("certify: %s: the run had other data or another build than this offbench: %s; its pieces cannot "
                 "be refitted here: certify it with the build and the data that ran it, or run it afresh with "
                 "--certify", p->fp_path, diff);
        return 2;
    }
    ob_json_flat meta;
    if (ob_json_load(p->meta_path, &meta, &err) != 0) {
        ob_error("certify: %s", err.msg);
        return 2;
    }
    const ob_json_entry *ph = ob_json_get(&meta, "plan_hash"), *cw = ob_json_get(&meta, "certify.wall_seconds");
    char want[32];
    snprintf(want, sizeof want, "%016" PRIx64, p->rec.plan_hash);
    int rc = 0;
    if (!ph || ph->type != OB_JSON_STRING || strcmp(ph->value, want) != 0) {
        ob_error("certify: %s:%d: plan_hash %s, this offbench plans %s for the run's options: not this run's jobs",
                 p->meta_path, ph ? ph->line : 1, ph ? ph->value : "missing", want);
        rc = 2;
    }
    p->prev_wall = cw && cw->type == OB_JSON_NUMBER ? strtod(cw->value, NULL) : 0.0;
    /* certificates of one mode only: a run certified (wholly or in part) in
     * the other mode is not mixed with this one */
    const ob_json_entry *cm = ob_json_get(&meta, "certify.mode");
    const char *mode = p->sel->mode == OB_CERTIFY_TIGHT ? "tight" : "verdict";
    if (rc == 0 && cm && cm->type == OB_JSON_STRING && strcmp(cm->value, mode) != 0) {
        ob_error("certify: %s:%d: the run is certified in mode %s; certify it %s", p->meta_path, cm->line, cm->value,
                 strcmp(cm->value, "tight") == 0 ? "with --tight" : "without --tight");
        rc = 2;
    }
    ob_json_free(&meta);
    return rc;
}

/* ---- the rows ------------------------------------------------------------ */

/* results.csv read; each job given its row (status, counts, certificate). */
static int load_rows(pass *p)
{
    ob_err err;
    if (ob_slurp(p->res_path, &p->text, &p->len, &err) != 0) {
        ob_error("certify: %s", err.msg);
        return 2;
    }
    const char *hdr = ob_results_header();
    const size_t hl = strlen(hdr);
    if (!(p->len > hl && memcmp(p->text, hdr, hl) == 0 &&
          (p->text[hl] == '\n' || (p->text[hl] == '\r' && p->len > hl + 1 && p->text[hl + 1] == '\n')))) {
        ob_error("certify: %s:1: not the columns of this offbench's results.csv (written by another version, or "
                 "edited)", p->res_path);
        return 2;
    }
    if (ob_res_parse(p->text, p->len, p->res_path, &p->tab, &err) != 0) {
        ob_error("certify: %s", err.msg);
        return 2;
    }
    if ((size_t)p->tab.n != p->njobs) {
        ob_error("certify: %s has %d rows, the run's options give %zu jobs: not this run's results", p->res_path,
                 p->tab.n, p->njobs);
        return 2;
    }
    p->line_of = malloc((p->njobs ? p->njobs : 1) * sizeof *p->line_of);
    p->fresh = calloc(p->njobs ? p->njobs : 1, 1);
    if (!p->line_of || !p->fresh) {
        ob_error("out of memory");
        return 1;
    }
    for (size_t i = 0; i < p->njobs; i++) {
        ob_job *j = &p->jobs[i];
        const ob_res_row key = {.curve = j->curve->id, .method = j->method->name, .metric = ob_metric_name(j->metric),
                                .split = ob_split_name(j->split), .d = j->d, .tol = j->tol};
        const ob_res_row *row = ob_res_find(&p->tab, &key);
        if (!row || ob_job_from_row(j, row) != 0) {
            ob_error("certify: %s has no row for %s d=%g %s tol=%g: not this run's results", p->res_path,
                     j->curve->id, j->d, j->method->name, j->tol);
            return 2;
        }
        p->line_of[i] = row->line;
    }
    return 0;
}

/* ---- the selection --------------------------------------------------------- */

static int in_names(char **v, int n, const char *s)
{
    for (int i = 0; i < n; i++)
        if (strcmp(v[i], s) == 0)
            return 1;
    return 0;
}

static int in_tols(const double *v, int n, double t)
{
    for (int i = 0; i < n; i++)
        if (v[i] == t)
            return 1;
    return 0;
}

static int selected(const ob_cert_select *s, const ob_job *j)
{
    return (!s->nmethods || in_names(s->methods, s->nmethods, j->method->name)) &&
           (!s->ntols || in_tols(s->tols, s->ntols, j->tol)) &&
           (!s->ncurves || in_names(s->curves, s->ncurves, j->curve->id));
}

/* Every name of the selection is a cell of the run: 0, or 2 after ob_error(). */
static int check_select(const pass *p)
{
    const ob_cert_select *s = p->sel;
    const ob_run_opts *o = p->o;
    for (int k = 0; k < s->nmethods; k++) {
        int found = 0;
        for (int m = 0; m < o->nmethods; m++)
            found |= strcmp(o->methods[m]->name, s->methods[k]) == 0;
        if (!found) {
            ob_error("certify: --methods: %s is not a method of the run in %s (see its meta.json or results.csv)",
                     s->methods[k], p->dir);
            return 2;
        }
    }
    for (int k = 0; k < s->ntols; k++)
        if (!in_tols(o->tols, o->ntols, s->tols[k])) {
            ob_error("certify: --tols: %g is not a tolerance of the run in %s", s->tols[k], p->dir);
            return 2;
        }
    for (int k = 0; k < s->ncurves; k++) {
        int found = 0;
        for (size_t i = 0; i < p->njobs && !found; i++)
            found = strcmp(p->jobs[i].curve->id, s->curves[k]) == 0;
        if (!found) {
            ob_error("certify: --curves: %s is not a curve of the run in %s", s->curves[k], p->dir);
            return 2;
        }
    }
    return 0;
}

/* ---- the journal ------------------------------------------------------------- */

/* The certificates of a pass that was killed, taken from its journal (the
 * jobs not yet certified in results.csv): 0, or the exit status. */
static int take_journal(pass *p)
{
    if (!exists(p->jr_path))
        return 0;
    ob_err err;
    char *t = NULL;
    size_t len = 0;
    if (ob_slurp(p->jr_path, &t, &len, &err) != 0) {
        ob_error("certify: %s", err.msg);
        return 2;
    }
    const char *nl = memchr(t, '\n', len);
    const size_t ml = sizeof MAGIC - 1;
    if (!nl) {  /* killed while its first line was written: nothing in it */
        free(t);
        return 0;
    }
    const size_t first = (size_t)(nl - t);
    if (first < ml || memcmp(t, MAGIC, ml) != 0 || first - ml != strlen(p->fp_jr) ||
        memcmp(t + ml, p->fp_jr, first - ml) != 0) {
        free(t);
        ob_error("certify: %s:1: not a journal of this run's certificates (another run or build): remove it",
                 p->jr_path);
        return 2;
    }
    size_t keep = len;  /* a partial last line is cut off */
    while (keep > first + 1 && t[keep - 1] != '\n')
        keep--;
    ob_res_table jt;
    int rc = 0;
    if (keep > first + 1 && ob_res_parse_at(t + first + 1, keep - first - 1, p->jr_path, 2, &jt, &err) != 0) {
        ob_error("certify: %s", err.msg);
        rc = 2;
    } else if (keep > first + 1) {
        size_t n = 0;
        for (size_t i = 0; i < p->njobs; i++) {
            ob_job *j = &p->jobs[i];
            const ob_res_row key = {.curve = j->curve->id, .method = j->method->name,
                                    .metric = ob_metric_name(j->metric), .split = ob_split_name(j->split), .d = j->d,
                                    .tol = j->tol};
            const ob_res_row *row = jt.n ? ob_res_find(&jt, &key) : NULL;
            if (row && row->cert_done && ob_certify_wants(j) && !j->cert_done) {
                j->cert_done = row->cert_done;  /* done, or timed out (no verdict) */
                j->err_upper = row->err_upper;
                j->err_lower = row->err_lower;
                j->cert_ns = row->cert_ns;
                p->fresh[i] = 1;
                n++;
            }
        }
        p->nfresh += n;
        if (n)
            ob_info("certify %s: %zu certificates taken from %s (a pass that was killed)", p->dir, n, p->jr_path);
        ob_res_free(&jt);
    }
    free(t);
    return rc;
}

/* A fresh journal holding the certificates taken so far; then appended to. */
static int start_journal(pass *p)
{
    char tmp[PATH_LEN + 8];
    snprintf(tmp, sizeof tmp, "%s.tmp", p->jr_path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        ob_error("certify: %s: cannot write: %s", tmp, strerror(errno));
        return 1;
    }
    fprintf(f, "%s%s\n%s\n", MAGIC, p->fp_jr, ob_results_header());
    for (size_t i = 0; i < p->njobs; i++)
        if (p->fresh[i])
            ob_write_result_row(f, &p->jobs[i]);
    const int bad = fflush(f) != 0 || ferror(f) || fsync(fileno(f)) != 0;
    if (fclose(f) != 0 || bad || rename(tmp, p->jr_path) != 0) {
        ob_error("certify: %s: cannot write: %s", p->jr_path, strerror(errno));
        remove(tmp);
        return 1;
    }
    memset(&p->jr, 0, sizeof p->jr);
    snprintf(p->jr.path, sizeof p->jr.path, "%s", p->jr_path);
    if (!(p->jr.f = fopen(p->jr_path, "a"))) {
        ob_error("certify: %s: cannot append: %s", p->jr_path, strerror(errno));
        return 1;
    }
    return 0;
}

/* ---- the files written ------------------------------------------------------- */

/* Whether every job with an approximation is certified (the whole run, not
 * only the selection). */
static int all_certified(const pass *p)
{
    for (size_t i = 0; i < p->njobs; i++)
        if (ob_certify_wants(&p->jobs[i]) && !p->jobs[i].cert_done)
            return 0;
    return 1;
}

/* One record of results.csv from text[at]: its end (past its line end) and
 * the offsets of field k's start and of field k2's end (k <= k2), fields
 * split at commas outside quotes. */
static size_t record(const char *t, size_t len, size_t at, int k, int k2, size_t *fs, size_t *fe, int *lines)
{
    int field = 0, q = 0;
    *fs = *fe = (size_t)-1;
    if (k == 0)
        *fs = at;
    size_t i = at;
    for (; i < len; i++) {
        const char c = t[i];
        if (c == '"')
            q = !q;
        if (c == '\n')
            ++*lines;
        if (q)
            continue;
        if (c == ',' || c == '\n' || c == '\r') {
            if (field == k2 && *fe == (size_t)-1)
                *fe = i;
            if (c == ',' && ++field == k)
                *fs = i + 1;
        }
        if (c == '\n')
            return i + 1;
    }
    if (field == k2 && *fe == (size_t)-1)
        *fe = i;
    return i;
}

static int write_results_cb(FILE *f, void *ctx)
{
    const pass *p = ctx;
    /* the line each job's row starts on, for the rows certified */
    int maxline = 1;
    for (size_t i = 0; i < p->njobs; i++)
        maxline = p->line_of[i] > maxline ? p->line_of[i] : maxline;
    int *job_at = malloc((size_t)(maxline + 1) * sizeof *job_at);
    if (!job_at)
        return -1;
    for (int l = 0; l <= maxline; l++)
        job_at[l] = -1;
    for (size_t i = 0; i < p->njobs; i++)
        if (p->fresh[i])
            job_at[p->line_of[i]] = (int)i;
    int line = 1;
    for (size_t at = 0; at < p->len;) {
        size_t fs, fe;
        const int here = line;
        const size_t end = record(p->text, p->len, at, OB_COL_ERR_UPPER, OB_COL_CERT_NS, &fs, &fe, &line);
        const int i = here <= maxline ? job_at[here] : -1;
        if (i < 0 || fs == (size_t)-1 || fe == (size_t)-1 || fe < fs) {
            fwrite(p->text + at, 1, end - at, f);  /* every other row as it is */
        } else {
            fwrite(p->text + at, 1, fs - at, f);
            for (int c = OB_COL_ERR_UPPER; c <= OB_COL_CERT_NS; c++) {
                if (c > OB_COL_ERR_UPPER)
                    fputc(',', f);
                ob_write_result_field(f, &p->jobs[i], c);
            }
            fwrite(p->text + fe, 1, end - fe, f);
        }
        at = end;
    }
    free(job_at);
    return ferror(f) ? -1 : 0;
}

/* meta.json with its certify line (and, once all are certified, its plan
 * hash and seed) replaced; every other line as it is. */
typedef struct {
    const pass *p;
    const char *text;
    size_t len;
    double wall;
    int all;
} meta_ctx;

static int starts(const char *s, size_t n, const char *pre)
{
    return n >= strlen(pre) && memcmp(s, pre, strlen(pre)) == 0;
}

static int write_meta_cb(FILE *f, void *ctx)
{
    const meta_ctx *m = ctx;
    for (size_t at = 0; at < m->len;) {
        const char *nl = memchr(m->text + at, '\n', m->len - at);
        const size_t end = nl ? (size_t)(nl - m->text) + 1 : m->len, n = end - at;
        const char *s = m->text + at;
        if (starts(s, n, "  \"certify\": "))
            ob_write_meta_certify(f, m->p->sel->mode, m->wall);
        else if (m->all && starts(s, n, "  \"plan_hash\": "))
            fprintf(f, "  \"plan_hash\": \"%016" PRIx64 "\",\n", m->p->plan_hash_cert);
        else if (m->all && starts(s, n, "  \"plan_seed\": "))
            fprintf(f, "  \"plan_seed\": \"%016" PRIx64 "\",\n", m->p->plan_seed_cert);
        else
            fwrite(s, 1, n, f);
        at = end;
    }
    return ferror(f) ? -1 : 0;
}

static int write_line_cb(FILE *f, void *ctx)
{
    fprintf(f, "%s\n", (const char *)ctx);
    return ferror(f) ? -1 : 0;
}

/* results.csv, meta.json and (all certified) results.fingerprint, all or
 * none; then the journal goes.  0, or 1 after ob_error(). */
static int write_files(pass *p, double seconds)
{
    ob_err err;
    meta_ctx m = {p, NULL, 0, p->prev_wall + seconds, all_certified(p)};
    char *mtext = NULL, *fp = NULL;
    if (ob_slurp(p->meta_path, &mtext, &m.len, &err) != 0) {
        ob_error("certify: %s", err.msg);
        return 1;
    }
    m.text = mtext;
    if (!strstr(mtext, "\n  \"certify\": ")) {
        ob_error("certify: %s has no \"certify\" line (written by another version of offbench)", p->meta_path);
        free(mtext);
        return 1;
    }
    ob_out_file outs[3];
    size_t n = 0;
    if (m.all && !p->o->certify) {  /* a run with --certify from now on (merge, resume) */
        ob_run_opts oc = *p->o;
        oc.certify = p->sel->mode;
        if (!(fp = ob_resume_fingerprint(&oc, &p->rec, p->where))) {
            ob_error("out of memory");
            free(mtext);
            return 1;
        }
        outs[n++] = (ob_out_file){"results.fingerprint", write_line_cb, fp};
    }
    outs[n++] = (ob_out_file){"meta.json", write_meta_cb, &m};
    outs[n++] = (ob_out_file){"results.csv", write_results_cb, p};
    const int rc = ob_write_set_atomically(p->dir, outs, n);
    free(mtext);
    free(fp);
    if (rc != 0)
        return 1;  /* said; the journal keeps the certificates */
    ob_journal_close(&p->jr, 0);
    remove(p->jr_path);
    return 0;
}

/* ---- the pass ------------------------------------------------------------------ */

static int same_row(const ob_job *a, const ob_job *b)
{
    return a->status == b->status && a->ctrl_points == b->ctrl_points && a->segments == b->segments &&
           a->out_degree == b->out_degree &&
           (a->max_err == b->max_err || (isnan(a->max_err) && isnan(b->max_err))) &&
           (a->max_gap == b->max_gap || (isnan(a->max_gap) && isnan(b->max_gap))) &&
           a->continuity == b->continuity;
}

/* The jobs to certify run again (their pieces), checked against their rows,
 * and certified.  Returns the exit status. */
static int certify_pass(pass *p, size_t *todo, size_t n)
{
    ob_job *pend = malloc(n * sizeof *pend);
    ob_span_log *logs = ob_span_logs_new(n);
    char *bad = calloc(n, 1);
    int st = 0;
    if (!pend || !logs || !bad) {
        ob_error("out of memory");
        st = 1;
        goto out;
    }
    for (size_t k = 0; k < n; k++) {
        const ob_job *j = &p->jobs[todo[k]];
        pend[k] = (ob_job){.curve = j->curve, .d = j->d, .method = j->method, .params = j->params,
                           .metric = j->metric, .split = j->split, .tol = j->tol};
    }
    ob_driver_opts drv = p->o->driver;
    drv.job_timeout_ns = 0;  /* the run's timeouts ended no job certified here (their status is ok or limit) */
    ob_driver_hooks h;
    memset(&h, 0, sizeof h);
    ob_backend_hooks(p->cl, &p->rec.binfo, &h);
    h.spans = logs;
    h.stop = ob_stop_flag();
    ob_info("certify %s: refitting the pieces of %zu jobs (their driver run again)", p->dir, n);
    const int drc = ob_driver_run(pend, n, &drv, &h);
    if (drc != 0) {
        if (drc < 0)
            ob_error("certify: out of memory refitting the jobs");
        const int wrc = p->nfresh ? write_files(p, 0.0) : 0;
        st = drc > 0 ? ob_stop_exit("nothing certified in this pass%s; offbench certify %s starts again",
                                    p->nfresh && wrc == 0 ? " (the journal's certificates are in results.csv)" : "",
                                    p->dir)
                     : 1;
        goto out;
    }
    size_t nbad = 0;
    for (size_t k = 0; k < n; k++) {
        const ob_job *j = &p->jobs[todo[k]];
        if (same_row(&pend[k], j) && !logs[k].oom)
            continue;
        bad[k] = 1;
        pend[k].cert_done = 1;  /* ob_certify_run leaves it */
        if (nbad++ < 5)
            ob_error("certify: %s:%d: %s d=%g %s tol=%g run again does not repeat its row (status %s, %d "
                     "segments, %ld control points, max_err %.17g; the row's %s, %d, %ld, %.17g): not certified",
                     p->res_path, p->line_of[todo[k]], j->curve->id, j->d, j->method->name, j->tol,
                     ob_status_name(pend[k].status), pend[k].segments, pend[k].ctrl_points, pend[k].max_err,
                     ob_status_name(j->status), j->segments, j->ctrl_points, j->max_err);
    }
    if ((st = start_journal(p)) != 0)
        goto out;
    double seconds = 0.0;
    const int crc = ob_certify_run(p->o->driver.samples, p->sel->mode, p->o->driver.job_timeout_ns, pend, n, logs,
                                   &p->jr, &seconds);
    size_t done = 0, yes = 0;
    for (size_t k = 0; k < n; k++) {
        if (bad[k] || !pend[k].cert_done)
            continue;
        ob_job *j = &p->jobs[todo[k]];
        j->cert_done = pend[k].cert_done;  /* done, or timed out (no verdict) */
        j->err_upper = pend[k].err_upper;
        j->err_lower = pend[k].err_lower;
        j->cert_ns = pend[k].cert_ns;
        p->fresh[todo[k]] = 1;
        done++;
        yes += ob_job_certified(j);
    }
    p->nfresh += done;
    int wrc = 0;
    if (p->nfresh)
        wrc = write_files(p, seconds);
    else  /* stopped before the first certificate: nothing to write */
        ob_journal_close(&p->jr, 1);
    if (crc > 0) {
        st = ob_stop_exit("%zu jobs certified in this pass %s %s/results.csv; offbench certify %s certifies the "
                          "other %zu", done, wrc == 0 ? "kept in" : "(in the journal; not written to)", p->dir,
                          p->dir, n - done - nbad);
        goto out;
    }
    ob_info("certify %s: %zu jobs certified in %.2f s, within tol %zu of them; %s %s", p->dir, done, seconds, yes,
            wrc == 0 ? "wrote" : "could not write", p->res_path);
    st = wrc != 0 || crc < 0 || nbad ? 1 : 0;
out:
    free(pend);
    free(bad);
    ob_export_free(logs);
    return st;
}

int ob_certify_after(ob_run_opts *o, const ob_cert_select *sel)
{
    pass p;
    memset(&p, 0, sizeof p);
    p.o = o;
    p.sel = sel;
    p.dir = o->resume_dir;
    p.lock_fd = -1;
    int st = check_dir(&p);
    if (st == 0)
        st = plan(&p);
    if (st == 0)
        st = check_identity(&p);
    if (st == 0)
        st = load_rows(&p);
    if (st == 0)
        st = check_select(&p);
    if (st == 0)
        st = take_journal(&p);
    size_t *todo = NULL, n = 0, nwant = 0, nskip = 0, nkept = 0;
    if (st == 0 && !(todo = malloc((p.njobs ? p.njobs : 1) * sizeof *todo))) {
        ob_error("out of memory");
        st = 1;
    }
    for (size_t i = 0; st == 0 && i < p.njobs; i++) {
        const ob_job *j = &p.jobs[i];
        if (!ob_certify_wants(j) || !selected(sel, j))
            continue;
        nwant++;
        if (!j->cert_done)
            todo[n++] = i;
        else if (!p.fresh[i])
            nskip++;
        else
            nkept++;  /* taken from the journal */
    }
    if (st == 0) {
        char kept[64] = "";
        if (nkept)
            snprintf(kept, sizeof kept, ", %zu from the journal", nkept);
        ob_info("certify %s: %zu jobs with an approximation selected: %zu already certified (skipped)%s, %zu to "
                "certify", p.dir, nwant, nskip, kept, n);
        if (n)
            st = certify_pass(&p, todo, n);
        else if (p.nfresh)
            st = write_files(&p, 0.0);
        else
            remove(p.jr_path);  /* a journal whose certificates are all in results.csv already */
    }
    free(todo);
    ob_journal_close(&p.jr, 0);
    free(p.fp_now);
    free(p.fp_jr);
    free(p.text);
    free(p.line_of);
    free(p.fresh);
    ob_res_free(&p.tab);
    ob_cl_close(p.cl);
    free(p.shard_idx);
    free(p.jobs);
    ob_curveset_free(&p.set);
    if (p.lock_fd >= 0)
        close(p.lock_fd);
    return st;
}
