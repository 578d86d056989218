/*
 * results_csv.c - see results_csv.h.
 *
 * The file is read into one buffer and split in place: a field's unquoted
 * text is written back over its source (it is never longer) and
 * NUL-terminated, so rows point into the buffer and freeing is one free().
 */
#include "host/io/results_csv.h"

#include "host/io/columns.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "host/io/slurp.h"
#include "methods/driver/driver.h"
#include "methods/metrics/metric.h"

enum { MAX_REP = 100000 };

typedef struct {
    char *s, *end;      /* the unread rest of the buffer */
    int line;           /* line number at s */
    const char *name;
    char **f;           /* field pointers, room for nmax */
    int nmax;
    ob_err *err;
} csv_reader;

static int csv_fail(csv_reader *r, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int csv_fail(csv_reader *r, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return ob_fail(r->err, "%s:%d: %s", r->name, line, msg);
}

/* The next record (blank lines skipped) into r->f: returns its field count
 * (fields past r->nmax are counted, not kept) with its first line in *line,
 * 0 at the end of the text, -1 after csv_fail(). */
static int csv_next(csv_reader *r, int *line)
{
    while (r->s < r->end && (*r->s == '\n' || *r->s == '\r')) {
        if (*r->s == '\r' && r->s + 1 < r->end && r->s[1] == '\n')
            r->s++;
        r->s++;
        r->line++;
    }
    if (r->s >= r->end)
        return 0;
    *line = r->line;
    char *s = r->s, *w = r->s;
    int nf = 0;
    for (;;) {
        if (nf < r->nmax)
            r->f[nf] = w;
        nf++;
        if (s < r->end && *s == '"') {
            s++;
            for (;;) {
                if (s >= r->end)
                    return csv_fail(r, *line, "unterminated quote");
                if (*s == '"') {
                    if (s + 1 < r->end && s[1] == '"') {
                        *w++ = '"';
                        s += 2;
                        continue;
                    }
                    s++;
                    break;
                }
                if (*s == '\n')
                    r->line++;
                *w++ = *s++;
            }
            if (s < r->end && *s != ',' && *s != '\n' && *s != '\r')
                return csv_fail(r, *line, "text after the closing quote of field %d", nf);
        } else {
            while (s < r->end && *s != ',' && *s != '\n' && *s != '\r') {
                if (*s == '"')
                    return csv_fail(r, *line, "a quote inside unquoted field %d", nf);
                *w++ = *s++;
            }
        }
        char c = s < r->end ? *s : '\n';
        *w++ = '\0'; /* w <= s: at worst this overwrites the delimiter, read above */
        if (s < r->end)
            s++;
        if (c == ',') {
            w = s;
            continue;
        }
        if (c == '\r' && s < r->end && *s == '\n')
            s++;
        r->line++;
        r->s = s;
        return nf;
    }
}

/* Reads the header: at[c] = the index of column cols[c] (-1 when absent and
 * optional, an error when required).  Returns the field count, or -1. */
static int csv_header(csv_reader *r, const char *const *cols, int ncols, int nrequired, int *at)
{
    int line = r->line;
    if (r->end - r->s >= 3 && memcmp(r->s, "\xef\xbb\xbf", 3) == 0)
        r->s += 3;
    /* count the header's fields first: they size r->f */
    int n = 1, inq = 0;
    for (const char *p = r->s; p < r->end && (inq || (*p != '\n' && *p != '\r')); p++) {
        inq ^= *p == '"';
        n += !inq && *p == ',';
    }
    r->f = malloc((size_t)(n + 1) * sizeof *r->f);
    if (!r->f)
        return csv_fail(r, r->line, "out of memory");
    r->nmax = n + 1;
    int nh = csv_next(r, &line);
    if (nh < 0)
        return -1;
    if (nh == 0)
        return csv_fail(r, line, "empty file, expected a header line");
    if (nh > r->nmax)
        return csv_fail(r, line, "malformed header");
    for (int c = 0; c < ncols; c++) {
        at[c] = -1;
        for (int i = 0; i < nh; i++) {
            if (strcmp(r->f[i], cols[c]) != 0)
                continue;
            if (at[c] >= 0)
                return csv_fail(r, line, "column '%s' appears twice in the header", cols[c]);
            at[c] = i;
        }
        if (at[c] < 0 && c < nrequired)
            return csv_fail(r, line, "no column '%s' in the header", cols[c]);
    }
    return nh;
}

/* A whole number in [lo, hi]. */
static int parse_long(const char *s, long lo, long hi, long *v)
{
    char *e;
    errno = 0;
    *v = strtol(s, &e, 10);
    return !*s || *e || errno || *v < lo || *v > hi ? -1 : 0;
}

/* max_err: a number >= 0, inf, or nan / empty (NAN). */
static int parse_err(const char *s, double *v)
{
    char *e;
    if (!*s) {
        *v = NAN;
        return 0;
    }
    *v = strtod(s, &e);
    return *e || *v < 0 ? -1 : 0;
}

static int parse_ns(const char *s, double *v)
{
    return ob_parse_double(s, v) || *v < 0 ? -1 : 0;
}

int ob_res_key_cmp(const ob_res_row *a, const ob_res_row *b)
{
    int c = strcmp(a->curve, b->curve);
    if (c)
        return c;
    if (a->d != b->d)
        return a->d < b->d ? -1 : 1;
    if ((c = strcmp(a->method, b->method)) || (c = strcmp(a->metric, b->metric)) ||
        (c = strcmp(a->split, b->split)))
        return c;
    if (a->tol != b->tol)
        return a->tol < b->tol ? -1 : 1;
    return 0;
}

static int cmp_ptr(const void *a, const void *b)
{
    const ob_res_row *x = *(const ob_res_row *const *)a, *y = *(const ob_res_row *const *)b;
    int c = ob_res_key_cmp(x, y);
    return c ? c : (x->line > y->line) - (x->line < y->line);
}

const ob_res_row *ob_res_find(const ob_res_table *t, const ob_res_row *key)
{
    size_t lo = 0, hi = (size_t)t->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = ob_res_key_cmp(t->sorted[mid], key);
        if (c == 0)
            return t->sorted[mid];
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

void ob_res_free(ob_res_table *t)
{
    if (!t)
        return;
    free(t->text);
    free(t->v);
    free(t->sorted);
    free(t->rep_t);
    free(t->rep_e);
    free(t->round_m);
    memset(t, 0, sizeof *t);
}

/* Fills the key fields of row from the fields f at the columns at[0..5]
 * (curve, d, method, metric, split, tol); the reason, or NULL. */
static const char *read_key(char **f, const int *at, ob_res_row *row)
{
    row->curve = f[at[0]];
    row->d_text = f[at[1]];
    row->method = f[at[2]];
    row->metric = f[at[3]];
    row->split = f[at[4]];
    row->tol_text = f[at[5]];
    if (!*row->curve || !*row->method || !*row->metric || !*row->split)
        return "curve, method, metric and split must not be empty";
    if (ob_parse_double(row->d_text, &row->d))
        return "d is not a finite number";
    if (ob_parse_double(row->tol_text, &row->tol))
        return "tol is not a finite number";
    return NULL;
}

/* The next data row, which must have the header's nh fields: 1, 0 at the
 * end, or -1 after csv_fail(). */
static int csv_row(csv_reader *r, int *line, int nh)
{
    const int nf = csv_next(r, line);
    if (nf > 0 && nf != nh) {
        csv_fail(r, *line, "%d fields, the header has %d", nf, nh);
        return -1;
    }
    return nf > 0 ? 1 : nf;
}

/* Parses buf[0..len) (owned by t from here on, with room for a NUL). */
/* The fields of one row (f, at[]: the header's column of each name) into
 * row.  Returns NULL, or what is wrong with the row. */
static const char *read_row(char **f, const int *at, int has_joints, ob_res_row *row)
{
    const char *bad = read_key(f, at, row);
    row->family = at[17] >= 0 ? f[at[17]] : "";
    row->certified = "";
    row->err_upper = row->err_lower = row->cert_ns = NAN;
    row->status = f[at[10]];
    row->message = f[at[13]];
    row->max_err_text = f[at[9]];
    row->max_gap = row->max_kink = NAN;
    row->continuity = has_joints ? f[at[16]] : "";
    if (bad)
        ;
    else if (parse_long(f[at[6]], 0, 1000000000L, &row->ctrl_points))
        bad = "ctrl_points is not a whole number >= 0";
    else if (parse_long(f[at[7]], 0, 1000000000L, &row->segments) ||
             parse_long(f[at[8]], 0, 1000000L, &row->out_degree))
        bad = "segments and out_degree must be whole numbers >= 0";
    else if (parse_err(row->max_err_text, &row->max_err))
        bad = "max_err is not a number >= 0 (nan or empty for none)";
    else if (has_joints && (parse_err(f[at[14]], &row->max_gap) || parse_err(f[at[15]], &row->max_kink)))
        bad = "max_gap and max_kink must be numbers >= 0 (empty for none)";
    else if (has_joints && strcmp(row->continuity, "") && strcmp(row->continuity, "open") &&
             strcmp(row->continuity, "G0") && strcmp(row->continuity, "G1"))
        bad = "continuity is not empty, open, G0 or G1";
    if (bad)
        ;
    else if (parse_ns(f[at[11]], &row->fit_ns) || parse_ns(f[at[12]], &row->eval_ns))
        bad = "fit_ns and eval_ns must be finite numbers >= 0";
    else if (strcmp(row->status, "ok") && strcmp(row->status, "limit") && strcmp(row->status, "fail") &&
             strcmp(row->status, "skip") && strcmp(row->status, "timeout"))
        bad = "status is not ok, limit, fail, skip or timeout";
    else if (strcmp(row->status, "ok") == 0 && !ob_err_can_pass(row->max_err))
        bad = "status ok with a max_err that is not a finite number (an error that is not finite is never ok)";
    return bad;
}

/* The certificate's columns of a row (at[18..21]): all empty, or all set
 * and consistent (err_lower <= err_upper, certified = yes exactly when
 * err_upper <= tol, status ok or limit: a job with an approximation), or only cert_ns set: a certificate stopped by
 * --job-timeout (cert_done OB_CERT_TIMEOUT, no verdict).  Returns NULL, or
 * what is wrong. */
static const char *read_cert(char **f, const int *at, ob_res_row *row)
{
    const char *up = f[at[18]], *lo = f[at[19]], *ns = f[at[21]];
    row->certified = f[at[20]];
    row->err_upper = row->err_lower = row->cert_ns = NAN;
    const int nset = (*up != 0) + (*lo != 0) + (*row->certified != 0) + (*ns != 0);
    if (nset == 0)
        return NULL;
    if (nset == 1 && *ns) {  /* timed out */
        if (parse_ns(ns, &row->cert_ns))
            return "cert_ns is not a finite number >= 0";
        row->cert_done = OB_CERT_TIMEOUT;
        return NULL;
    }
    if (nset != 4)
        return "err_upper, err_lower, certified and cert_ns are all empty or all set (or cert_ns alone: a "
               "certificate stopped by --job-timeout)";
    if (strcmp(row->status, "ok") && strcmp(row->status, "limit")) {  /* fail, skip, timeout */
        static _Thread_local char msg[160];
        snprintf(msg, sizeof msg, "status %s has no approximation to certify: err_upper, err_lower, certified and "
                 "cert_ns must be empty", row->status);
        return msg;
    }
    if (parse_err(up, &row->err_upper) || isnan(row->err_upper))
        return "err_upper is not a number >= 0 (inf: unbounded)";
    if (ob_parse_double(lo, &row->err_lower) || row->err_lower < 0 || row->err_lower > row->err_upper)
        return "err_lower is not a finite number from 0 to err_upper";
    if (strcmp(row->certified, "yes") && strcmp(row->certified, "no"))
        return "certified is not empty, yes or no";
    if ((strcmp(row->certified, "yes") == 0) != (row->err_upper <= row->tol))
        return "certified must be yes exactly when err_upper <= tol";
    if (parse_ns(ns, &row->cert_ns))
        return "cert_ns is not a finite number >= 0";
    row->cert_done = OB_CERT_DONE;
    return NULL;
}

/* The method time's columns of a row (at[22..24], run --time-fits):
 * fit_calls and method_ns both empty or both set, method_iqr_ns empty
 * (one round) or set with them.  Returns NULL, or what is wrong. */
static const char *read_method_time(char **f, const int *at, ob_res_row *row)
{
    const char *calls = f[at[22]], *ns = f[at[23]], *iqr = f[at[24]];
    if (!*calls && !*ns && !*iqr)
        return NULL;
    if (!*calls || !*ns)
        return "fit_calls and method_ns are both empty or both set (method_iqr_ns only with them)";
    long k;
    if (parse_long(calls, 1, 1000000000L, &k))
        return "fit_calls is not a whole number >= 1";
    if (parse_ns(ns, &row->method_ns) || (*iqr && parse_ns(iqr, &row->method_iqr_ns)))
        return "method_ns and method_iqr_ns must be finite numbers >= 0";
    row->fit_calls = k;
    return NULL;
}

/* t->sorted: the rows by job key; two rows of one job are refused. */
static int index_rows(ob_res_table *t, csv_reader *r, int line)
{
    t->sorted = malloc((size_t)(t->n ? t->n : 1) * sizeof *t->sorted);
    if (!t->sorted) {
        csv_fail(r, line, "out of memory");
        return -1;
    }
    for (int i = 0; i < t->n; i++)
        t->sorted[i] = &t->v[i];
    qsort(t->sorted, (size_t)t->n, sizeof *t->sorted, cmp_ptr);
    for (int i = 1; i < t->n; i++)
        if (ob_res_key_cmp(t->sorted[i - 1], t->sorted[i]) == 0) {
            const ob_res_row *a = t->sorted[i - 1], *b = t->sorted[i];
            csv_fail(r, b->line, "duplicate job %s,%s,%s,%s,%s,%s (first on line %d)", b->curve, b->d_text,
                     b->method, b->metric, b->split, b->tol_text, a->line);
            return -1;
        }
    return 0;
}

static int parse_owned(char *buf, size_t len, const char *name, int first_line, ob_res_table *t, ob_err *err)
{
    /* required, then the optional joint columns and family (NREQ on) */
    /* the names from the column table (columns.h), in the order of at[] */
    const char *const cols[] = {
        ob_columns[OB_COL_CURVE].name,      ob_columns[OB_COL_D].name,          ob_columns[OB_COL_METHOD].name,
        ob_columns[OB_COL_METRIC].name,     ob_columns[OB_COL_SPLIT].name,      ob_columns[OB_COL_TOL].name,
        ob_columns[OB_COL_CTRL_POINTS].name, ob_columns[OB_COL_SEGMENTS].name,  ob_columns[OB_COL_OUT_DEGREE].name,
        ob_columns[OB_COL_MAX_ERR].name,    ob_columns[OB_COL_STATUS].name,     ob_columns[OB_COL_FIT_NS].name,
        ob_columns[OB_COL_EVAL_NS].name,    ob_columns[OB_COL_MESSAGE].name,    ob_columns[OB_COL_MAX_GAP].name,
        ob_columns[OB_COL_MAX_KINK].name,   ob_columns[OB_COL_CONTINUITY].name, ob_columns[OB_COL_FAMILY].name,
        ob_columns[OB_COL_ERR_UPPER].name,  ob_columns[OB_COL_ERR_LOWER].name,  ob_columns[OB_COL_CERTIFIED].name,
        ob_columns[OB_COL_CERT_NS].name,    ob_columns[OB_COL_FIT_CALLS].name,  ob_columns[OB_COL_METHOD_NS].name,
        ob_columns[OB_COL_METHOD_IQR_NS].name};
    enum { NCOL = sizeof cols / sizeof cols[0], NREQ = 14 };
    int at[NCOL];
    memset(t, 0, sizeof *t);
    t->text = buf;
    csv_reader r = {buf, buf + len, first_line, name, NULL, 0, err};
    int cap = 0, line = 0;
    int nh = csv_header(&r, cols, NCOL, NREQ, at);
    if (nh < 0)
        goto fail;
    const int njc = (at[14] >= 0) + (at[15] >= 0) + (at[16] >= 0);
    if (njc != 0 && njc != 3) {
        csv_fail(&r, first_line, "the joint columns max_gap, max_kink and continuity come together (this header has %d of them)",
                 njc);
        goto fail;
    }
    t->has_joints = njc == 3;
    t->has_family = at[17] >= 0;
    const int ncc = (at[18] >= 0) + (at[19] >= 0) + (at[20] >= 0) + (at[21] >= 0);
    if (ncc != 0 && ncc != 4) {
        csv_fail(&r, first_line, "the certificate's columns err_upper, err_lower, certified and cert_ns come together "
                 "(this header has %d of them)", ncc);
        goto fail;
    }
    t->has_cert = ncc == 4;
    const int nfc = (at[22] >= 0) + (at[23] >= 0) + (at[24] >= 0);
    if (nfc != 0 && nfc != 3) {
        csv_fail(&r, first_line, "the method time's columns fit_calls, method_ns and method_iqr_ns come together "
                 "(this header has %d of them)", nfc);
        goto fail;
    }
    t->has_method_time = nfc == 3;
    for (;;) {
        const int got = csv_row(&r, &line, nh);
        if (got == 0)
            break;
        if (got < 0)
            goto fail;
        if (t->n == cap) {
            cap = cap ? 2 * cap : 256;
            ob_res_row *nv = realloc(t->v, (size_t)cap * sizeof *nv);
            if (!nv) {
                csv_fail(&r, line, "out of memory");
                goto fail;
            }
            t->v = nv;
        }
        ob_res_row *row = &t->v[t->n];
        memset(row, 0, sizeof *row);
        row->line = line;
        const char *bad = read_row(r.f, at, t->has_joints, row);
        if (!bad && t->has_cert)
            bad = read_cert(r.f, at, row);
        row->method_ns = row->method_iqr_ns = NAN;
        if (!bad && t->has_method_time)
            bad = read_method_time(r.f, at, row);
        t->method_timed += row->fit_calls > 0;
        if (bad) {
            csv_fail(&r, line, "%s", bad);
            goto fail;
        }
        t->n++;
    }
    if (index_rows(t, &r, line) != 0)
        goto fail;
    free(r.f);
    return 0;
fail:
    free(r.f);
    ob_res_free(t);
    return -1;
}

int ob_res_parse(const char *text, size_t len, const char *name, ob_res_table *t, ob_err *err)
{
    return ob_res_parse_at(text, len, name, 1, t, err);
}

int ob_res_parse_at(const char *text, size_t len, const char *name, int first_line, ob_res_table *t, ob_err *err)
{
    memset(t, 0, sizeof *t);
    char *buf = malloc(len + 1);
    if (!buf) {
        ob_fail(err, "%s: out of memory", name);
        return -1;
    }
    memcpy(buf, text, len);
    buf[len] = '\0';
    return parse_owned(buf, len, name, first_line, t, err);
}

int ob_res_load(const char *path, ob_res_table *t, ob_err *err)
{
    char *buf;
    size_t len;
    memset(t, 0, sizeof *t);
    if (ob_slurp(path, &buf, &len, err))
        return -1;
    return parse_owned(buf, len, path, 1, t, err);
}

/* A file of per-repetition timings beside results.csv: its index column
 * and its two value columns.  samples.csv: rep, fit_ns, eval_ns; fits.csv:
 * round, fit_calls (checked against the row), method_ns. */
typedef struct {
    const char *idx, *v0, *v1;
    int v0_is_calls;
} series_spec;

static const series_spec SAMPLES_SPEC = {"rep", "fit_ns", "eval_ns", 0};
static const series_spec FITS_SPEC = {"round", "fit_calls", "method_ns", 1};

typedef struct {
    int row, rep, line;
    double a, b;    /* the two values */
} sample;

/* The samples of the file (after its header), each checked against t. */
typedef struct {
    sample *s;
    int n, cap, maxrep, line;
} sample_list;

static const char *read_sample(csv_reader *r, const int *at, const series_spec *sp, const ob_res_table *t,
                               sample *out)
{
    ob_res_row key;
    long rep;
    const char *bad = read_key(r->f, at, &key);
    if (bad)
        return bad;
    if (parse_long(r->f[at[6]], 1, MAX_REP, &rep))
        return sp->v0_is_calls ? "round is not a whole number from 1 to 100000"
                               : "rep is not a whole number from 1 to 100000";
    if (parse_ns(r->f[at[7]], &out->a) || parse_ns(r->f[at[8]], &out->b))
        return sp->v0_is_calls ? "fit_calls and method_ns must be finite numbers >= 0"
                               : "fit_ns and eval_ns must be finite numbers >= 0";
    const ob_res_row *row = ob_res_find(t, &key);
    if (!row)
        return "this job is not in results.csv";
    if (sp->v0_is_calls && out->a != (double)row->fit_calls)
        return "fit_calls differs from the job's in results.csv";
    out->row = (int)(row - t->v);
    out->rep = (int)rep;
    return NULL;
}

static int read_samples(csv_reader *r, const series_spec *sp, const ob_res_table *t, sample_list *l)
{
    const char *const cols[] = {"curve", "d", "method", "metric", "split", "tol", sp->idx, sp->v0, sp->v1};
    enum { NCOL = sizeof cols / sizeof cols[0] };
    int at[NCOL];
    const int nh = csv_header(r, cols, NCOL, NCOL, at);
    if (nh < 0)
        return -1;
    for (;;) {
        const int got = csv_row(r, &l->line, nh);
        if (got <= 0)
            return got;
        sample sm;
        const char *bad = read_sample(r, at, sp, t, &sm);
        if (bad)
            return csv_fail(r, l->line, "%s", bad);
        if (l->n == l->cap) {
            l->cap = l->cap ? 2 * l->cap : 1024;
            sample *ns = realloc(l->s, (size_t)l->cap * sizeof *ns);
            if (!ns)
                return csv_fail(r, l->line, "out of memory");
            l->s = ns;
        }
        sm.line = l->line;
        l->s[l->n++] = sm;
        if (sm.rep > l->maxrep)
            l->maxrep = sm.rep;
    }
}

/* A rows x maxrep matrix of NAN (NULL without memory or when too large). */
static double *nan_matrix(int rows, int maxrep)
{
    const size_t cells = (size_t)rows * (size_t)maxrep;
    if (!maxrep || cells / (size_t)maxrep != (size_t)rows || cells > ((size_t)1 << 28))
        return NULL;
    double *m = malloc((cells ? cells : 1) * sizeof *m);
    for (size_t i = 0; m && i < cells; i++)
        m[i] = NAN;
    return m;
}

/* Fills m0 (and m1 when not NULL) from the samples: m0 = a + b, m1 = b
 * (samples.csv: fit + eval, eval), or m0 = b (fits.csv); a (key, rep)
 * given twice is refused. */
static int fill_matrices(csv_reader *r, const sample_list *l, const series_spec *sp, double *m0, double *m1)
{
    for (int i = 0; i < l->n; i++) {
        const size_t k = (size_t)l->s[i].row * (size_t)l->maxrep + (size_t)(l->s[i].rep - 1);
        if (!isnan(m0[k]))
            return csv_fail(r, l->s[i].line, "%s %d of this job given twice", sp->v0_is_calls ? "round" : "repetition",
                            l->s[i].rep);
        m0[k] = sp->v0_is_calls ? l->s[i].b : l->s[i].a + l->s[i].b;
        if (m1)
            m1[k] = l->s[i].b;
    }
    return 0;
}

/* Each row's pointer into matrix m (NULL without), and its count present. */
static void point_rows(ob_res_table *t, double *m, int maxrep, int fits)
{
    for (int i = 0; i < t->n; i++) {
        ob_res_row *row = &t->v[i];
        const double *p = maxrep ? &m[(size_t)i * (size_t)maxrep] : NULL;
        if (fits) {
            row->round_m = p;
            continue;
        }
        row->rep_t = p;
        row->rep_e = maxrep ? &t->rep_e[(size_t)i * (size_t)maxrep] : NULL;
        row->nsamples = 0;
        for (int k = 0; k < maxrep; k++)
            row->nsamples += !isnan(p[k]);
    }
}

static int attach_owned(ob_res_table *t, char *buf, size_t len, const char *name, const series_spec *sp, ob_err *err)
{
    const int fits = sp->v0_is_calls;
    sample_list l = {0};
    double *m0 = NULL, *m1 = NULL;
    int rc = -1;
    csv_reader r = {buf, buf + len, 1, name, NULL, 0, err};
    if (read_samples(&r, sp, t, &l) != 0)
        goto done;
    if (l.maxrep > 0) {
        m0 = nan_matrix(t->n, l.maxrep);
        m1 = fits ? NULL : nan_matrix(t->n, l.maxrep);
        if (!m0 || (!fits && !m1)) {
            csv_fail(&r, l.line, "out of memory (%d rows x %d repetitions)", t->n, l.maxrep);
            goto done;
        }
        if (fill_matrices(&r, &l, sp, m0, m1) != 0)
            goto done;
    }
    if (fits) {
        free(t->round_m);
        t->round_m = m0;
        t->maxround = l.maxrep;
    } else {
        free(t->rep_t);
        free(t->rep_e);
        t->rep_t = m0;
        t->rep_e = m1;
        t->maxrep = l.maxrep;
    }
    point_rows(t, m0, l.maxrep, fits);
    m0 = m1 = NULL;
    rc = 0;
done:
    free(m0);
    free(m1);
    free(l.s);
    free(r.f);
    free(buf);
    return rc;
}

int ob_res_attach_samples(ob_res_table *t, const char *text, size_t len, const char *name, ob_err *err)
{
    char *buf = malloc(len + 1);
    if (!buf) {
        ob_fail(err, "%s: out of memory", name);
        return -1;
    }
    memcpy(buf, text, len);
    buf[len] = '\0';
    return attach_owned(t, buf, len, name, &SAMPLES_SPEC, err);
}

int ob_res_load_samples(ob_res_table *t, const char *path, ob_err *err)
{
    char *buf;
    size_t len;
    if (ob_slurp(path, &buf, &len, err))
        return -1;
    return attach_owned(t, buf, len, path, &SAMPLES_SPEC, err);
}

int ob_res_load_fits(ob_res_table *t, const char *path, ob_err *err)
{
    char *buf;
    size_t len;
    if (ob_slurp(path, &buf, &len, err))
        return -1;
    return attach_owned(t, buf, len, path, &FITS_SPEC, err);
}
