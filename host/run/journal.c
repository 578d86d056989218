/*
 * journal.c - rows saved as jobs finish, and resuming an interrupted run
 * (see journal.h).
 */
#include "host/io/columns.h"
#include "host/run/journal.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "buildinfo.h"
#include "host/io/numfmt.h"
#include "host/io/outfile.h"
#include "host/io/output.h"
#include "host/io/slurp.h"
#include "methods/external/ext.h"

static const char MAGIC[] = "#offbench-journal 1 ";

static double mono_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

char *ob_run_fingerprint(const ob_run_opts *o, const char *where, uint64_t data_hash)
{
    size_t cap = 4096 + strlen(where), n = 0; /* the data path and the hash fit */
    char *s = malloc(cap);
    if (!s)
        return NULL;
    n += (size_t)snprintf(s, cap, "samples=%d max_depth=%d max_segments=%d inflections=%d job_timeout=%.17g data=%s",
                          o->driver.samples, o->driver.max_depth, o->driver.max_segments, o->driver.inflections,
                          o->driver.job_timeout_ns, where);
    /* the curves' content, not just their path: shards or MPI ranks that
     * loaded other curves under one name get other plan hashes */
    n += (size_t)snprintf(s + n, cap - n, " data_hash=%016" PRIx64, data_hash);
    /* only when set: the plan hashes of runs without it are as before; shards
     * with and without certificates have other plan hashes (merge refuses) */
    if (o->certify)  /* the two modes give other columns: other plans */
        n += (size_t)snprintf(s + n, cap - n, " certify=%s", o->certify == OB_CERTIFY_TIGHT ? "tight" : "verdict");
    if (o->trimmed)  /* two more columns */
        n += (size_t)snprintf(s + n, cap - n, " trimmed=yes");
    /* an external method: its command and hello line (register.c), so that a
     * resume or merge refuses another program under the same name */
    for (int i = 0; i < o->nmethods; i++) {
        const ob_ext *e = ob_ext_of(o->methods[i]);
        if (e && n + 128 < cap)
            n += (size_t)snprintf(s + n, cap - n, " external.%s=%s", e->name, e->fp);
    }
    for (int m = 0; ob_methods[m]; m++)
        for (int k = 0; k < ob_methods[m]->nparams; k++) {
            char num[40];
            ob_fmt_double(num, sizeof num, o->params[m * OB_MAX_PARAMS + k]);
            const size_t need = strlen(ob_methods[m]->name) + strlen(ob_methods[m]->params[k].name) + strlen(num) + 4;
            if (n + need >= cap) {
                char *ns = realloc(s, cap *= 2);
                if (!ns) {
                    free(s);
                    return NULL;
                }
                s = ns;
            }
            n += (size_t)snprintf(s + n, cap - n, " %s.%s=%s", ob_methods[m]->name, ob_methods[m]->params[k].name,
                                  num);
        }
    for (char *p = s; *p; p++)  /* one line, whatever the data path holds */
        if (*p == '\n' || *p == '\r')
            *p = ' ';
    return s;
}

/* A growing string of " key=value" tokens; a value's spaces, '%' and line
 * ends are %-escaped, so tokens split at spaces. */
typedef struct {
    char *s;
    size_t n, cap;
    int oom;
} fpbuf;

static void fp_putc(fpbuf *b, char c)
{
    if (b->oom)
        return;
    if (b->n + 2 > b->cap) {
        size_t nc = b->cap ? 2 * b->cap : 1024;
        char *ns = realloc(b->s, nc);
        if (!ns) {
            b->oom = 1;
            return;
        }
        b->s = ns;
        b->cap = nc;
    }
    b->s[b->n++] = c;
    b->s[b->n] = '\0';
}

static void fp_tok(fpbuf *b, const char *key, const char *val)
{
    if (b->n)
        fp_putc(b, ' ');
    for (const char *p = key; *p; p++)
        fp_putc(b, *p);
    fp_putc(b, '=');
    for (const unsigned char *p = (const unsigned char *)val; *p; p++) {
        if (*p == ' ' || *p == '%' || *p < 0x20) {
            char hex[4];
            snprintf(hex, sizeof hex, "%%%02X", *p);
            for (int k = 0; hex[k]; k++)
                fp_putc(b, hex[k]);
        } else {
            fp_putc(b, (char)*p);
        }
    }
}

static void fp_num(fpbuf *b, const char *key, double v)
{
    char num[40];
    ob_fmt_double(num, sizeof num, v);
    fp_tok(b, key, num);
}

char *ob_resume_fingerprint(const ob_run_opts *o, const ob_run_record *rec, const char *where)
{
    fpbuf b = {0};
    char v[64];
    fp_num(&b, "samples", o->driver.samples);
    fp_num(&b, "max_depth", o->driver.max_depth);
    fp_num(&b, "max_segments", o->driver.max_segments);
    fp_num(&b, "inflections", o->driver.inflections);
    fp_num(&b, "job_timeout", o->driver.job_timeout_ns);
    fp_tok(&b, "data", where);
    snprintf(v, sizeof v, "%016" PRIx64, rec->data_hash);
    fp_tok(&b, "data_hash", v);
    snprintf(v, sizeof v, "%016" PRIx64, rec->binfo.kernel_hash);
    fp_tok(&b, "kernel_fnv1a", v);
    if (!o->curve_ids) {
        fp_tok(&b, "curves", "all");
    } else {
        fpbuf c = {0};
        for (int i = 0; i < o->ncurve_ids; i++) {
            if (i)
                fp_putc(&c, ',');
            for (const char *p = o->curve_ids[i]; *p; p++)
                fp_putc(&c, *p);
        }
        b.oom |= c.oom;
        fp_tok(&b, "curves", c.s ? c.s : "");
        free(c.s);
    }
    {
        fpbuf m = {0};
        for (int i = 0; i < o->nmethods; i++) {
            if (i)
                fp_putc(&m, ',');
            for (const char *p = o->methods[i]->name; *p; p++)
                fp_putc(&m, *p);
        }
        b.oom |= m.oom;
        fp_tok(&b, "methods", m.s ? m.s : "");
        free(m.s);
    }
    {
        fpbuf t = {0};
        for (int i = 0; i < o->ntols; i++) {
            char num[40];
            ob_fmt_double(num, sizeof num, o->tols[i]);
            if (i)
                fp_putc(&t, ',');
            for (const char *p = num; *p; p++)
                fp_putc(&t, *p);
        }
        b.oom |= t.oom;
        fp_tok(&b, "tols", t.s ? t.s : "");
        free(t.s);
    }
    fp_tok(&b, "metric", ob_metric_name(o->metric));
    fp_tok(&b, "split", ob_split_name(o->split));
    fp_tok(&b, "certify", o->certify == OB_CERTIFY_TIGHT ? "tight" : o->certify ? "verdict" : "no");
    if (o->trimmed)  /* only when set: the fingerprints of runs without it are as before */
        fp_tok(&b, "trimmed", "yes");
    snprintf(v, sizeof v, "%d/%d", o->shard_k, o->shard_n);
    fp_tok(&b, "shard", o->shard_n > 0 ? v : "none");
    fp_tok(&b, "git", OB_GIT_COMMIT);
    fp_num(&b, "dirty", OB_GIT_DIRTY);
    fp_tok(&b, "cflags", OB_CFLAGS);
    for (int i = 0; i < o->nmethods; i++) {
        char key[96];
        snprintf(key, sizeof key, "version.%s", o->methods[i]->name);
        fp_num(&b, key, o->methods[i]->version);
        const ob_ext *e = ob_ext_of(o->methods[i]);
        if (e) {  /* the program behind an external method (as in ob_run_fingerprint) */
            snprintf(key, sizeof key, "external.%s", e->name);
            fp_tok(&b, key, e->fp);
        }
    }
    for (int m = 0; ob_methods[m]; m++)
        for (int k = 0; k < ob_methods[m]->nparams; k++) {
            char key[128];
            snprintf(key, sizeof key, "%s.%s", ob_methods[m]->name, ob_methods[m]->params[k].name);
            fp_num(&b, key, o->params[m * OB_MAX_PARAMS + k]);
        }
    if (b.oom || !b.s) {
        free(b.s);
        return NULL;
    }
    return b.s;
}

/* What a fingerprint key means to the user. */
static void key_label(const char *key, size_t klen, char *out, size_t len)
{
    static const struct {
        const char *key, *label;
    } names[] = {
        {"samples", "--samples"},
        {"max_depth", "--max-depth"},
        {"max_segments", "--max-segments"},
        {"inflections", "--inflections"},
        {"job_timeout", "--job-timeout"},
        {"data", "the data source (--curves / --random)"},
        {"data_hash", "the curve data (the content of the loaded curves changed)"},
        {"kernel_fnv1a", "the kernel text (kernel_fnv1a: $OFFBENCH_KERNELS or the compiled-in copy)"},
        {"curves", "--curve"},
        {"methods", "--methods"},
        {"tols", "--tols"},
        {"metric", "--metric"},
        {"split", "--split"},
        {"certify", "--certify"},
        {"trimmed", "--trimmed"},
        {"shard", "--shard"},
        {"git", "the build (git commit)"},
        {"dirty", "the build (uncommitted changes: git dirty flag)"},
        {"cflags", "the build (compiler flags)"},
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strlen(names[i].key) == klen && memcmp(names[i].key, key, klen) == 0) {
            snprintf(out, len, "%s", names[i].label);
            return;
        }
    if (klen > 8 && memcmp(key, "version.", 8) == 0)
        snprintf(out, len, "the build (method %.*s's version)", (int)(klen - 8), key + 8);
    else if (klen > 9 && memcmp(key, "external.", 9) == 0)
        snprintf(out, len, "--external %.*s (the program: its command or hello line)", (int)(klen - 9), key + 9);
    else
        snprintf(out, len, "--param %.*s", (int)klen, key);
}

/* The value of key in fingerprint fp (its length in *vlen), or NULL. */
static const char *fp_find(const char *fp, const char *key, size_t klen, size_t *vlen)
{
    for (const char *p = fp; *p;) {
        const char *end = strchr(p, ' ');
        if (!end)
            end = p + strlen(p);
        const char *eq = memchr(p, '=', (size_t)(end - p));
        if (eq && (size_t)(eq - p) == klen && memcmp(p, key, klen) == 0) {
            *vlen = (size_t)(end - eq - 1);
            return eq + 1;
        }
        p = *end ? end + 1 : end;
    }
    return NULL;
}

/* A value as fp_tok escaped it (v, n bytes), as the user wrote it: the
 * %XX escapes undone, into out (cut to len - 1 bytes). */
static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

static void unescape(const char *v, size_t n, char *out, size_t len)
{
    size_t k = 0;
    for (size_t i = 0; i < n && k + 1 < len; i++) {
        if (v[i] == '%' && i + 2 < n && hex_digit(v[i + 1]) >= 0 && hex_digit(v[i + 2]) >= 0) {
            out[k++] = (char)(16 * hex_digit(v[i + 1]) + hex_digit(v[i + 2]));
            i += 2;
        } else {
            out[k++] = v[i];
        }
    }
    out[k] = '\0';
}

char *ob_fp_get(const char *fp, const char *key)
{
    size_t vlen = 0;
    const char *v = fp_find(fp, key, strlen(key), &vlen);
    char *out = v ? malloc(vlen + 1) : NULL;
    if (out)
        unescape(v, vlen, out, vlen + 1);
    return out;
}

int ob_fingerprint_diff(const char *was, const char *now, char *out, size_t len)
{
    out[0] = '\0';
    if (strcmp(was, now) == 0)
        return 0;
    /* the first key of now that was has with another value, or lacks */
    for (int pass = 0; pass < 2; pass++) {
        const char *a = pass ? was : now, *b = pass ? now : was;
        for (const char *p = a; *p;) {
            const char *end = strchr(p, ' ');
            if (!end)
                end = p + strlen(p);
            const char *eq = memchr(p, '=', (size_t)(end - p));
            if (eq) {
                const size_t klen = (size_t)(eq - p), alen = (size_t)(end - eq - 1);
                size_t blen = 0;
                const char *bv = fp_find(b, p, klen, &blen);
                if (!bv || blen != alen || memcmp(bv, eq + 1, alen) != 0) {
                    char label[160], ws[81] = "none", ns[81] = "none";
                    key_label(p, klen, label, sizeof label);
                    const char *wv = pass ? eq + 1 : bv, *nv = pass ? bv : eq + 1;
                    const size_t wl = pass ? alen : blen, nl = pass ? blen : alen;
                    if (wv)  /* as written, not %-escaped: "random 250:2026" */
                        unescape(wv, wl, ws, sizeof ws);
                    if (nv)
                        unescape(nv, nl, ns, sizeof ns);
                    snprintf(out, len, "%s differs (the run's %s, now %s)", label, ws, ns);
                    return 1;
                }
            }
            p = *end ? end + 1 : end;
        }
    }
    snprintf(out, len, "the fingerprints differ");
    return 1;
}

/* Creates the journal afresh: first line and header, through a new file
 * renamed over the name (a link there is replaced, never followed); the
 * rows go on to the same file. */
static int create(ob_journal *j, const char *fp, ob_err *err)
{
    ob_outfile o;
    if (ob_outfile_open(&o, j->path, 0, err) != 0)
        return -1;
    fprintf(o.f, "%s%s\n%s\n", MAGIC, fp, ob_results_header());
    if (fflush(o.f) != 0 || ferror(o.f)) {
        ob_fail(err, "%s: write failed", o.tmp);
        ob_outfile_discard(&o);
        return -1;
    }
    FILE *f = o.f;
    if (ob_outfile_publish(&o, err) != 0)  /* on failure it closed f */
        return -1;
    j->f = f;
    return 0;
}

/* The checks and the cut of reopen on the journal's text; takes fd (the
 * journal opened for appending): the rows go on through it, or it is
 * closed. */
static int continue_journal(ob_journal *j, int fd, const char *text, size_t len, const char *fp,
                            ob_res_table *restored, ob_err *err)
{
    const char *nl = memchr(text, '\n', len);
    if (!nl) {  /* killed while the first line was written: nothing saved */
        close(fd);
        return create(j, fp, err);
    }
    const size_t first = (size_t)(nl - text);
    if (first < sizeof MAGIC - 1 || memcmp(text, MAGIC, sizeof MAGIC - 1) != 0) {
        close(fd);
        return ob_fail(err, "%s:1: not an offbench journal", j->path);
    }
    const size_t fplen = first - (sizeof MAGIC - 1);
    if (fplen != strlen(fp) || memcmp(text + sizeof MAGIC - 1, fp, fplen) != 0) {
        char *was = strndup(text + sizeof MAGIC - 1, fplen), diff[512];
        ob_fingerprint_diff(was ? was : "", fp, diff, sizeof diff);
        free(was);
        close(fd);
        return ob_fail(err, "%s:1: the interrupted run had other options, data or build: %s; resume it with its "
                       "own options (run --resume DIR alone takes them) on the same data and build, or start "
                       "afresh (another --out, or --force)", j->path, diff);
    }
    size_t keep = len;
    while (keep > first + 1 && text[keep - 1] != '\n')
        keep--;
    const char *body = text + first + 1;
    const size_t blen = keep - (first + 1);
    const char *hend = memchr(body, '\n', blen);
    if (hend && ((size_t)(hend - body) != strlen(ob_results_header()) ||
                 memcmp(body, ob_results_header(), strlen(ob_results_header())) != 0)) {
        /* rows of another build's columns cannot be continued or restored */
        close(fd);
        return ob_fail(err, "%s:2: written by another version of offbench (its columns differ): run again "
                       "without --resume", j->path);
    }
    if (!(blen > 0 && memchr(body, '\n', blen))) {  /* not even the header line */
        close(fd);
        return create(j, fp, err);
    }
    if (ob_res_parse_at(body, blen, j->path, 2, restored, err) != 0) {  /* body is line 2 on */
        close(fd);
        return -1;
    }
    if (keep < len && ftruncate(fd, (off_t)keep) != 0) {
        ob_fail(err, "%s: cannot cut the partial last line: %s", j->path, strerror(errno));
        close(fd);
        return -1;
    }
    if (!(j->f = fdopen(fd, "a"))) {
        ob_fail(err, "%s: cannot append: %s", j->path, strerror(errno));
        close(fd);
        return -1;
    }
    return 0;
}

/* Reads an existing journal into *restored; cuts a partial last line; goes
 * on appending to it (never through a link: ob_open_in_place). */
static int reopen(ob_journal *j, const char *fp, ob_res_table *restored, ob_err *err)
{
    char *text;
    size_t len;
    if (ob_slurp(j->path, &text, &len, err) != 0)
        return -1;
    const int fd = ob_open_in_place(j->path, O_WRONLY | O_APPEND, err);
    if (fd < 0) {
        free(text);
        return -1;
    }
    int rc = continue_journal(j, fd, text, len, fp, restored, err);
    free(text);
    return rc;
}

int ob_journal_open(ob_journal *j, const char *dir, const char *fp, int resume, ob_res_table *restored, ob_err *err)
{
    memset(j, 0, sizeof *j);
    memset(restored, 0, sizeof *restored);
    snprintf(j->path, sizeof j->path, "%s/results.journal.csv", dir);
    j->last_sync = mono_s();
    if (!resume)
        return create(j, fp, err);
    struct stat st;
    if (stat(j->path, &st) == 0)
        return reopen(j, fp, restored, err);
    char res[4200];
    snprintf(res, sizeof res, "%s/results.csv", dir);
    if (stat(res, &st) != 0) {
        ob_fail(err, "--resume: %s has neither results.journal.csv nor results.csv: nothing to resume",
                dir);
        return -1;
    }
    /* the run had finished: its rows are taken as they are */
    if (ob_res_load(res, restored, err) != 0)
        return -1;
    if (!restored->has_joints) {
        ob_fail(err, "--resume: %s was written by an older offbench (no max_gap column): run again without "
                "--resume", res);
        ob_res_free(restored);
        return -1;
    }
    /* the finished run's fingerprint, written beside its results.csv */
    char fpath[4200], *was = NULL, diff[512];
    size_t wlen = 0;
    snprintf(fpath, sizeof fpath, "%s/results.fingerprint", dir);
    if (ob_slurp(fpath, &was, &wlen, NULL) != 0) { /* its reason is not reported: the message says it */
        ob_fail(err, "--resume: %s has no results.fingerprint (the options, data and build of its run): "
                "it cannot be checked; run again without --resume", dir);
        ob_res_free(restored);
        return -1;
    }
    while (wlen > 0 && (was[wlen - 1] == '\n' || was[wlen - 1] == '\r'))
        was[--wlen] = '\0';
    if (ob_fingerprint_diff(was, fp, diff, sizeof diff) != 0) {
        ob_fail(err, "--resume: %s: the finished run had other options, data or build: %s; resume it with "
                "its own options (run --resume DIR alone takes them) on the same data and build, or run afresh "
                "(another --out)", fpath, diff);
        free(was);
        ob_res_free(restored);
        return -1;
    }
    free(was);
    j->from_results = 1;
    return create(j, fp, err);
}

/* The first line of the regular file at path (at most max bytes; the end
 * of the file ends it when eof_ends), malloc'd; NULL without one.  Opened
 * without blocking and checked first: a FIFO there is not read from. */
static char *first_line(const char *path, size_t max, int eof_ends)
{
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return NULL;
    struct stat st;
    char *buf = NULL;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && (buf = malloc(max + 1))) {
        size_t n = 0;
        ssize_t r;
        while (n < max && ((r = read(fd, buf + n, max - n)) > 0 || (r < 0 && errno == EINTR)))
            n += r > 0 ? (size_t)r : 0;
        char *nl = memchr(buf, '\n', n);
        if (nl || (eof_ends && n < max)) {
            buf[nl ? (size_t)(nl - buf) : n] = '\0';
        } else {
            free(buf);
            buf = NULL;
        }
    }
    close(fd);
    return buf;
}

char *ob_stored_fingerprint(const char *dir, char *path, size_t plen, int *journal_there)
{
    struct stat st;
    snprintf(path, plen, "%s/results.journal.csv", dir);
    *journal_there = stat(path, &st) == 0;
    if (*journal_there) {
        char *line = first_line(path, (size_t)1 << 20, 0);
        if (line && strncmp(line, MAGIC, sizeof MAGIC - 1) == 0) {
            memmove(line, line + sizeof MAGIC - 1, strlen(line + sizeof MAGIC - 1) + 1);
            return line;
        }
        free(line);
        return NULL;
    }
    snprintf(path, plen, "%s/results.fingerprint", dir);
    char *fp = first_line(path, (size_t)1 << 20, 1);
    if (fp && fp[0] && fp[strlen(fp) - 1] == '\r')
        fp[strlen(fp) - 1] = '\0';
    return fp;
}

int ob_journal_add(ob_journal *j, const ob_job *job)
{
    if (!j->f)
        return -1;
    if (ob_write_result_row(j->f, job) != 0 || fflush(j->f) != 0)
        return -1;
    const double now = mono_s();
    if (now - j->last_sync >= 1.0) {
        fsync(fileno(j->f));
        j->last_sync = now;
    }
    return 0;
}

void ob_journal_close(ob_journal *j, int remove_it)
{
    if (!j)
        return;
    if (j->f) {
        fflush(j->f);
        fsync(fileno(j->f));
        fclose(j->f);
        j->f = NULL;
    }
    if (remove_it && j->path[0])
        remove(j->path);
}

int ob_job_from_row(ob_job *job, const ob_res_row *row)
{
    static const ob_status st[] = {OB_OK, OB_LIMIT, OB_FAIL, OB_SKIP, OB_TIMEOUT};
    int k = -1;
    for (int i = 0; i < (int)(sizeof st / sizeof st[0]); i++)
        if (strcmp(row->status, ob_status_name(st[i])) == 0)
            k = i;
    if (k < 0)
        return -1;
    job->status = st[k];
    job->ctrl_points = row->ctrl_points;
    job->segments = (int)row->segments;
    job->out_degree = (int)row->out_degree;
    job->max_err = row->max_err;
    job->fit_ns = row->fit_ns;
    job->eval_ns = row->eval_ns;
    snprintf(job->message, sizeof job->message, "%s", row->message);
    job->max_gap = row->max_gap;
    job->max_kink = row->max_kink;
    if (ob_cont_parse(row->continuity ? row->continuity : "", &job->continuity) != 0)
        job->continuity = OB_CONT_NONE;
    job->cert_done = row->cert_done;
    job->err_upper = row->err_upper;
    job->err_lower = row->err_lower;
    job->cert_ns = row->cert_ns;
    return 0;
}
