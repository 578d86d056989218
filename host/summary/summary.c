/*
 * summary.c - the pivot behind `./offbench summary`: see summary.h.
 */
#include "host/summary/summary.h"
#include "host/summary/summary_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/random.h"
#include "host/io/strmap.h"
#include "methods/method.h"

const char *const ob_sum_status_names[OB_SUM_NSTATUS] = {"ok", "limit", "fail", "skip", "timeout"};

int ob_sum_status_index(const char *status)
{
    for (int i = 0; i < OB_SUM_NSTATUS; i++)
        if (strcmp(status, ob_sum_status_names[i]) == 0)
            return i;
    return -1;
}

/* ---------------------------------------------------------------- quartiles */

double ob_sum_quantile7(const double *sorted, int n, double p)
{
    const double h = (n - 1) * p;
    const int i = (int)floor(h);
    return i + 1 < n ? sorted[i] + (h - i) * (sorted[i + 1] - sorted[i]) : sorted[n - 1];
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void ob_sum_quartiles(double *v, int n, ob_sum_quart *q)
{
    q->n = n;
    if (n <= 0) {
        q->n = 0;
        q->median = q->q1 = q->q3 = NAN;
        return;
    }
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    q->q1 = ob_sum_quantile7(v, n, 0.25);
    q->median = ob_sum_quantile7(v, n, 0.5);
    q->q3 = ob_sum_quantile7(v, n, 0.75);
}

/* ---------------------------------------------------------------- lists */

void ob_sum_list_free(ob_sum_list *l)
{
    if (!l)
        return;
    for (int i = 0; i < l->n; i++)
        free(l->v[i]);
    free(l->v);
    l->v = NULL;
    l->n = 0;
}

/* The index of s in l, or -1. */
static int list_find(const ob_sum_list *l, const char *s)
{
    for (int i = 0; i < l->n; i++)
        if (strcmp(l->v[i], s) == 0)
            return i;
    return -1;
}

int ob_sum_list_parse(const char *opt, const char *text, ob_sum_list *l, ob_err *err)
{
    memset(l, 0, sizeof *l);
    if (!*text)
        return ob_fail(err, "%s: empty list", opt);
    int cap = 1;
    for (const char *p = text; *p; p++)
        cap += *p == ',';
    l->v = calloc((size_t)cap, sizeof *l->v);
    if (!l->v)
        return ob_fail(err, "%s: out of memory", opt);
    for (const char *p = text;;) {
        const char *q = strchr(p, ',');
        const size_t len = q ? (size_t)(q - p) : strlen(p);
        if (len == 0) {
            ob_sum_list_free(l);
            return ob_fail(err, "%s: an empty value in '%s'", opt, text);
        }
        char *v = strndup(p, len);
        if (!v) {
            ob_sum_list_free(l);
            return ob_fail(err, "%s: out of memory", opt);
        }
        if (list_find(l, v) >= 0) {
            ob_fail(err, "%s: '%s' is listed twice", opt, v);
            free(v);
            ob_sum_list_free(l);
            return -1;
        }
        l->v[l->n++] = v;
        if (!q)
            return 0;
        p = q + 1;
    }
}

int ob_sum_sections_parse(const char *text, ob_err *err)
{
    static const char *const names[] = {"curves", "families", "methods"};
    ob_sum_list l;
    if (ob_sum_list_parse("--sections", text, &l, err))
        return -1;
    int bits = 0;
    for (int i = 0; i < l.n; i++) {
        int b = strcmp(l.v[i], "all") == 0 ? OB_SUM_ALL : 0;
        for (int k = 0; k < 3; k++)
            if (strcmp(l.v[i], names[k]) == 0)
                b = 1 << k;
        if (!b) {
            ob_fail(err, "--sections: unknown section '%s' (curves, families, methods or all)", l.v[i]);
            ob_sum_list_free(&l);
            return -1;
        }
        bits |= b;
    }
    ob_sum_list_free(&l);
    return bits;
}

/* ---------------------------------------------------------------- families */

/* The index i of a random curve id rnd<SEED>_<i> (digits only), or -1. */
static long random_index(const char *id)
{
    if (strncmp(id, "rnd", 3) != 0)
        return -1;
    const char *p = id + 3, *us = strchr(p, '_');
    if (!us || us == p || !us[1])
        return -1;
    for (const char *q = p; q < us; q++)
        if (*q < '0' || *q > '9')
            return -1;
    long i = 0;
    for (const char *q = us + 1; *q; q++) {
        if (*q < '0' || *q > '9' || i > OB_RND_MAX_N)
            return -1;
        i = 10 * i + (*q - '0');
    }
    return i;
}

const char *ob_sum_family(const ob_res_row *r)
{
    if (r->family && *r->family)
        return r->family;
    const long i = random_index(r->curve);
    return i >= 0 ? ob_random_family_names[ob_random_family(i)] : "(none)";
}

/* ---------------------------------------------------------------- filters */

/* The distinct values of one text field of the rows (first appearance). */
typedef const char *(*row_field)(const ob_res_row *r);
static const char *field_metric(const ob_res_row *r) { return r->metric; }
static const char *field_split(const ob_res_row *r) { return r->split; }
static const char *field_method(const ob_res_row *r) { return r->method; }
static const char *field_curve(const ob_res_row *r) { return r->curve; }

/* Collects the distinct values of field over t's rows into *out (owned
 * array of pointers into t): 0, or -1 when out of memory. */
static int distinct(const ob_res_table *t, row_field field, const char ***out, int *n)
{
    ob_strmap seen = {0};
    *out = malloc((size_t)(t->n ? t->n : 1) * sizeof **out);
    *n = 0;
    if (!*out)
        return -1;
    for (int i = 0; i < t->n; i++) {
        const char *v = field(&t->v[i]);
        const long got = ob_strmap_put(&seen, v, *n);
        if (got == -2) {
            ob_strmap_free(&seen);
            return -1;
        }
        if (got == -1)
            (*out)[(*n)++] = v;
    }
    ob_strmap_free(&seen);
    return 0;
}

/* "a, b, c" of v[0..n) into buf: the first 10, then how many in all. */
static void join_names(const char **v, int n, char *buf, size_t len)
{
    enum { SHOWN = 10 };
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && i < SHOWN; i++) {
        int w = snprintf(buf + k, len - k, "%s%s", i ? ", " : "", v[i]);
        if (w < 0 || (size_t)w >= len - k)
            return;
        k += (size_t)w;
    }
    if (n > SHOWN)
        snprintf(buf + k, len - k, ", ... (%d in all)", n);
}

/* The one value of field the summary keeps: `want` (an option; opt names
 * it) when given and present, else the only one in the rows. */
static int pick_one(const ob_res_table *t, const char *name, row_field field, const char *opt, const char *what,
                    const char *want, const char **out, ob_err *err)
{
    const char **v;
    int n;
    if (distinct(t, field, &v, &n)) {
        free(v);
        return ob_fail(err, "%s: out of memory", name);
    }
    char list[1024];
    join_names(v, n, list, sizeof list);
    int rc = 0;
    *out = NULL;
    for (int i = 0; want && i < n; i++)
        if (strcmp(v[i], want) == 0)
            *out = v[i];
    if (want && !*out)
        rc = ob_fail(err, "%s: no rows with %s '%s' in %s (it has %s)", opt, what, want, name, n ? list : "no rows");
    else if (!want && n > 1)
        rc = ob_fail(err, "%s holds the %ss %s: choose one with %s", name, what, list, opt);
    else if (!want && n == 1)
        *out = v[0];
    else if (!want)
        rc = ob_fail(err, "%s: no rows", name);
    free(v);
    return rc;
}

/* Every value of l is the field of some row of t (opt names the option). */
static int check_list(const ob_res_table *t, const char *name, const ob_sum_list *l, row_field field, const char *opt,
                      const char *what, ob_err *err)
{
    if (!l)
        return 0;
    for (int i = 0; i < l->n; i++) {
        int found = 0;
        for (int r = 0; r < t->n && !found; r++)
            found = strcmp(field(&t->v[r]), l->v[i]) == 0;
        if (found)
            continue;
        if (field == field_method && !ob_method_find(l->v[i]))
            return ob_fail(err, "%s: unknown method '%s' (see './offbench list methods')", opt, l->v[i]);
        const char **v;
        int n;
        char list[1024] = "";
        if (distinct(t, field, &v, &n) == 0)
            join_names(v, n, list, sizeof list);
        free(v);
        return ob_fail(err, "%s: no rows of %s '%s' in %s (it has %s)", opt, what, l->v[i], name, list);
    }
    return 0;
}

static int in_list(const ob_sum_list *l, const char *v) { return !l || l->n == 0 || list_find(l, v) >= 0; }

/* The row passes the filter (metric and split: the chosen ones). */
static int keep_row(const ob_res_row *r, const ob_sum_filter *f, const char *metric, const char *split)
{
    return strcmp(r->metric, metric) == 0 && strcmp(r->split, split) == 0 && in_list(f->methods, r->method) &&
           in_list(f->curves, r->curve) && in_list(f->families, ob_sum_family(r));
}

/* ---------------------------------------------------------------- the axes */

int ob_sum_find_tol(const ob_summary *s, double tol)
{
    for (int k = 0; k < s->nt; k++)
        if (s->tols[k] == tol)
            return k;
    return -1;
}

int ob_sum_find_name(const char **v, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(v[i], name) == 0)
            return i;
    return -1;
}

/* The key of a (curve, d) pair in the pair map: the curve, a NUL, d's bits
 * (-0 as 0, so that the map agrees with d == d).  Written into buf when it
 * fits, else into memory the caller frees (key != buf); NULL: no memory. */
static char *pair_key(const char *curve, double d, char *buf, size_t len, size_t *klen)
{
    const size_t n = strlen(curve);
    *klen = n + 1 + sizeof d;
    char *key = *klen <= len ? buf : malloc(*klen);
    if (!key)
        return NULL;
    if (d == 0)
        d = 0;
    memcpy(key, curve, n + 1);
    memcpy(key + n + 1, &d, sizeof d);
    return key;
}

/* The pair map's value of row r (put: add it as pair `val` when new; see
 * ob_strmap_putn), or -2 when out of memory. */
long ob_sum_pair_lookup(ob_strmap *pairs, const ob_res_row *r, long put_val)
{
    char buf[512];
    size_t klen;
    char *key = pair_key(r->curve, r->d, buf, sizeof buf, &klen);
    if (!key)
        return -2;
    const long got = put_val >= 0 ? ob_strmap_putn(pairs, key, klen, put_val) : ob_strmap_getn(pairs, key, klen);
    if (key != buf)
        free(key);
    return got;
}

static int cmp_tol_desc(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

/* Methods (the filter's order, else first appearance), tolerances, pairs,
 * families and curves of the kept rows. */
static int collect_axes(ob_summary *s, const ob_res_table *t, const char *kept, int nkept, const ob_sum_filter *f,
                        ob_strmap *pairs)
{
    const int cap = nkept + (f->methods ? f->methods->n : 0);
    s->methods = malloc((size_t)cap * sizeof *s->methods);
    s->tols = malloc((size_t)cap * sizeof *s->tols);
    s->tol_text = malloc((size_t)cap * sizeof *s->tol_text);
    s->pairs = malloc((size_t)cap * sizeof *s->pairs);
    s->families = malloc((size_t)cap * sizeof *s->families);
    s->fam_pairs = calloc((size_t)cap, sizeof *s->fam_pairs);
    if (!s->methods || !s->tols || !s->tol_text || !s->pairs || !s->families || !s->fam_pairs)
        return -1;
    if (f->methods && f->methods->n)
        for (int i = 0; i < f->methods->n; i++)
            s->methods[s->nm++] = f->methods->v[i];
    ob_strmap curves = {0};
    int rc = 0;
    for (int i = 0; i < t->n && rc == 0; i++) {
        const ob_res_row *r = &t->v[i];
        if (!kept[i])
            continue;
        if (ob_sum_find_name(s->methods, s->nm, r->method) < 0)
            s->methods[s->nm++] = r->method;
        if (ob_sum_find_tol(s, r->tol) < 0)
            s->tols[s->nt++] = r->tol;
        const long got = ob_sum_pair_lookup(pairs, r, s->np);
        const long gotc = ob_strmap_put(&curves, r->curve, s->ncurves);
        if (got == -2 || gotc == -2) {
            rc = -1;
            break;
        }
        s->ncurves += gotc == -1;
        if (got != -1)
            continue;
        const char *fam = ob_sum_family(r);
        int fi = ob_sum_find_name(s->families, s->nf, fam);
        if (fi < 0)
            s->families[fi = s->nf++] = fam;
        s->fam_pairs[fi]++;
        s->pairs[s->np++] = (ob_sum_pair){r->curve, r->d_text, fam, r->d, fi};
    }
    ob_strmap_free(&curves);
    if (rc)
        return rc;
    qsort(s->tols, (size_t)s->nt, sizeof *s->tols, cmp_tol_desc);
    for (int k = 0; k < s->nt; k++)
        for (int i = 0; i < t->n; i++)
            if (kept[i] && t->v[i].tol == s->tols[k]) {
                s->tol_text[k] = t->v[i].tol_text;
                break;
            }
    return 0;
}

/* ---------------------------------------------------------------- statistics */

/* Family cells of side from its cells: quartiles of the ok jobs' control
 * points, the count of the others.  tmp has room for np values. */
static void family_stats(const ob_summary *s, ob_sum_side *side, double *tmp)
{
    for (int fi = 0; fi < s->nf; fi++)
        for (int m = 0; m < s->nm; m++)
            for (int k = 0; k < s->nt; k++) {
                int n = 0, nonok = 0;
                for (int p = 0; p < s->np; p++) {
                    const ob_res_row *r = s->pairs[p].fam == fi ? side->cell[ob_sum_at(s, p, m, k)] : NULL;
                    if (r && strcmp(r->status, "ok") == 0)
                        tmp[n++] = (double)r->ctrl_points;
                    else if (r)
                        nonok++;
                }
                ob_sum_fcell *c = &side->fam[ob_sum_fat(s, fi, m, k)];
                ob_sum_quartiles(tmp, n, &c->q);
                c->nonok = nonok;
            }
}

/* Method statistics of side: jobs by status, time per job of the jobs not
 * skipped.  tmp has room for np * nt values. */
static void method_stats(const ob_summary *s, ob_sum_side *side, double *tmp)
{
    for (int m = 0; m < s->nm; m++) {
        ob_sum_mstat *ms = &side->meth[m];
        memset(ms, 0, sizeof *ms);
        int n = 0;
        for (int p = 0; p < s->np; p++)
            for (int k = 0; k < s->nt; k++) {
                const ob_res_row *r = side->cell[ob_sum_at(s, p, m, k)];
                if (!r)
                    continue;
                ms->jobs++;
                const int st = ob_sum_status_index(r->status);
                if (st >= 0)
                    ms->status[st]++;
                if (st != OB_SUM_SKIP)
                    tmp[n++] = r->fit_ns + r->eval_ns;
            }
        ob_sum_quartiles(tmp, n, &ms->time_ns);
        n = 0;  /* the certificates (run --certify) */
        for (int p = 0; p < s->np; p++)
            for (int k = 0; k < s->nt; k++) {
                const ob_res_row *r = side->cell[ob_sum_at(s, p, m, k)];
                if (!r || !r->cert_done)
                    continue;
                ms->cert_yes += r->err_upper <= r->tol;
                ms->cert_no += !(r->err_upper <= r->tol);
                tmp[n++] = r->cert_ns;
            }
        ob_sum_quartiles(tmp, n, &ms->cert_ns);
    }
}

/* Allocates side's arrays for s's shape. */
int ob_sum_side_alloc(const ob_summary *s, ob_sum_side *side)
{
    const size_t ncell = (size_t)s->np * (size_t)s->nm * (size_t)s->nt;
    side->cell = calloc(ncell ? ncell : 1, sizeof *side->cell);
    side->fam = calloc((size_t)s->nf * (size_t)s->nm * (size_t)s->nt + 1, sizeof *side->fam);
    side->meth = calloc((size_t)s->nm + 1, sizeof *side->meth);
    return side->cell && side->fam && side->meth ? 0 : -1;
}

/* The statistics of a side whose cells are filled. */
int ob_sum_side_stats(const ob_summary *s, ob_sum_side *side)
{
    const size_t n = (size_t)s->np * (size_t)s->nt + 1;
    double *tmp = malloc(n * sizeof *tmp);
    if (!tmp)
        return -1;
    family_stats(s, side, tmp);
    method_stats(s, side, tmp);
    free(tmp);
    return 0;
}

void ob_sum_side_free(ob_sum_side *side)
{
    free(side->cell);
    free(side->fam);
    free(side->meth);
    memset(side, 0, sizeof *side);
}

/* ---------------------------------------------------------------- build */

/* Fills s->run.cell from the kept rows. */
static int fill_cells(ob_summary *s, const ob_res_table *t, const char *kept, ob_strmap *pairs)
{
    for (int i = 0; i < t->n; i++) {
        if (!kept[i])
            continue;
        const ob_res_row *r = &t->v[i];
        const int p = (int)ob_sum_pair_lookup(pairs, r, -1);
        if (p < 0)
            return -1;
        const int m = ob_sum_find_name(s->methods, s->nm, r->method), k = ob_sum_find_tol(s, r->tol);
        s->run.cell[ob_sum_at(s, p, m, k)] = r;
        s->run.njobs++;
    }
    return 0;
}

static int check_filter(const ob_res_table *t, const char *name, const ob_sum_filter *f, const char **metric,
                        const char **split, ob_err *err)
{
    if (pick_one(t, name, field_metric, "--metric", "metric", f->metric, metric, err) ||
        pick_one(t, name, field_split, "--split", "split", f->split, split, err) ||
        check_list(t, name, f->methods, field_method, "--methods", "method", err) ||
        check_list(t, name, f->curves, field_curve, "--curves", "curve", err) ||
        check_list(t, name, f->families, ob_sum_family, "--family", "family", err))
        return -1;
    return 0;
}

/* Every value of l has a kept row (a value whose rows are all of another
 * metric, split, or left out by another list would be a silent gap). */
static int check_kept(const ob_res_table *t, const char *name, const char *kept, const ob_sum_list *l, row_field field,
                      const char *opt, const char *what, ob_err *err)
{
    for (int i = 0; l && i < l->n; i++) {
        int found = 0;
        for (int r = 0; r < t->n && !found; r++)
            found = kept[r] && strcmp(field(&t->v[r]), l->v[i]) == 0;
        if (!found)
            return ob_fail(err, "%s: the rows of %s '%s' in %s are all left out by the other filters (--metric, --split, "
                           "--methods, --curves, --family)", opt, what, l->v[i], name);
    }
    return 0;
}

int ob_summary_build(const ob_res_table *t, const char *name, const ob_sum_filter *f, ob_summary *s, ob_err *err)
{
    memset(s, 0, sizeof *s);
    const char *metric, *split;
    if (check_filter(t, name, f, &metric, &split, err))
        return -1;
    char *kept = malloc((size_t)(t->n ? t->n : 1));
    if (!kept)
        return ob_fail(err, "%s: out of memory", name);
    int nkept = 0;
    for (int i = 0; i < t->n; i++)
        nkept += kept[i] = (char)keep_row(&t->v[i], f, metric, split);
    if (nkept == 0) {
        free(kept);
        return ob_fail(err, "%s: no rows left after the filters (metric %s, split %s and the lists given)", name, metric,
                       split);
    }
    if (check_kept(t, name, kept, f->methods, field_method, "--methods", "method", err) ||
        check_kept(t, name, kept, f->curves, field_curve, "--curves", "curve", err) ||
        check_kept(t, name, kept, f->families, ob_sum_family, "--family", "family", err)) {
        free(kept);
        return -1;
    }
    ob_strmap pairs = {0};
    int rc = collect_axes(s, t, kept, nkept, f, &pairs);
    s->run.name = name;
    s->run.metric = metric;
    s->run.split = split;
    if (rc == 0 && ob_sum_side_alloc(s, &s->run) == 0) {
        rc = fill_cells(s, t, kept, &pairs) || ob_sum_side_stats(s, &s->run) ? -1 : 0;
        for (int m = 0; rc == 0 && m < s->nm; m++)
            s->has_cert |= s->run.meth[m].cert_yes + s->run.meth[m].cert_no > 0;
    } else {
        rc = -1;
    }
    ob_strmap_free(&pairs);
    free(kept);
    if (rc) {
        ob_summary_free(s);
        return ob_fail(err, "%s: out of memory", name);
    }
    return 0;
}

int ob_summary_join(ob_summary *s, const ob_res_table *b, const char *name, const ob_sum_filter *f, ob_err *err)
{
    const char *metric, *split;
    if (pick_one(b, name, field_metric, "--metric", "metric", f->metric, &metric, err) ||
        pick_one(b, name, field_split, "--split", "split", f->split, &split, err))
        return -1;
    ob_sum_side_free(&s->base);
    s->has_base = 0;
    if (ob_sum_side_alloc(s, &s->base)) {
        ob_sum_side_free(&s->base);
        return ob_fail(err, "%s: out of memory", name);
    }
    for (int p = 0; p < s->np; p++)
        for (int m = 0; m < s->nm; m++)
            for (int k = 0; k < s->nt; k++) {
                const ob_res_row *r = s->run.cell[ob_sum_at(s, p, m, k)];
                if (!r)
                    continue;
                ob_res_row key = *r;
                key.metric = metric;
                key.split = split;
                const ob_res_row *br = ob_res_find(b, &key);
                s->base.cell[ob_sum_at(s, p, m, k)] = br;
                s->base.njobs += br != NULL;
            }
    if (ob_sum_side_stats(s, &s->base)) {
        ob_sum_side_free(&s->base);
        return ob_fail(err, "%s: out of memory", name);
    }
    s->base.name = name;
    s->base.metric = metric;
    s->base.split = split;
    s->has_base = 1;
    return 0;
}

void ob_summary_free(ob_summary *s)
{
    if (!s)
        return;
    free(s->methods);
    free(s->tols);
    free(s->tol_text);
    free(s->pairs);
    free(s->families);
    free(s->fam_pairs);
    ob_sum_side_free(&s->run);
    ob_sum_side_free(&s->base);
    ob_sum_archive_free(s);
    memset(s, 0, sizeof *s);
}
