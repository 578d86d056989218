/*
 * summary_write.c - the summary's three formats (summary.h).
 *
 * Markdown and LaTeX print the same tables: each is first built as a grid
 * of cell texts (grid_*), then rendered (md_grid, tex_grid).  CSV is one
 * long table written straight from the summary.
 */
#include "host/summary/summary.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/numfmt.h"

/* ---------------------------------------------------------------- numbers */

/* A count or quantile: whole numbers as such, else 6 significant digits. */
static void fmt_val(char *buf, size_t len, double v)
{
    if (v == floor(v) && fabs(v) < 1e15)
        snprintf(buf, len, "%.0f", v);
    else
        snprintf(buf, len, "%.6g", v);
}

/* A ratio or a time: 3 significant digits, whole numbers from 1000 on. */
static void fmt3(char *buf, size_t len, double v)
{
    if (fabs(v) >= 1000)
        snprintf(buf, len, "%.0f", v);
    else
        snprintf(buf, len, "%.3g", v);
}

/* new/base of two positive finite values into buf, else "-". */
static void fmt_ratio(char *buf, size_t len, double a, double b)
{
    if (isfinite(a) && isfinite(b) && a > 0 && b > 0)
        fmt3(buf, len, a / b);
    else
        snprintf(buf, len, "-");
}

/* ---------------------------------------------------------------- cells */

static int is_ok(const ob_res_row *r) { return r && strcmp(r->status, "ok") == 0; }

/* A job's cell: its control points when ok, else its status, "-" none. */
static void cell_job(char *buf, size_t len, const ob_res_row *r)
{
    if (!r)
        snprintf(buf, len, "-");
    else if (is_ok(r))
        snprintf(buf, len, "%ld", r->ctrl_points);
    else
        snprintf(buf, len, "%s", r->status);
}

/* A job's cell in a run with certificates: an ok job's control points and
 * its certified err_upper, "!" where that is over tol, "no verdict" where
 * the certificate timed out; else as cell_job. */
static void cell_job_cert(char *buf, size_t len, const ob_res_row *r)
{
    cell_job(buf, len, r);
    if (!is_ok(r) || !r->cert_done)
        return;
    const size_t k = strlen(buf);
    if (r->cert_done != 1) {
        snprintf(buf + k, len - k, " (no verdict)");
        return;
    }
    char up[40];
    ob_fmt_bound(up, sizeof up, r->err_upper, 1);
    snprintf(buf + k, len - k, " (%s%s)", up, r->err_upper <= r->tol ? "" : " !");
}

/* Whether an ok job has a certificate that does not hold it within tol
 * (over tol, unbounded, or timed out): why, else NULL. */
static const char *not_certified(const ob_res_row *r)
{
    if (!is_ok(r) || !r->cert_done)
        return NULL;
    if (r->cert_done != 1)
        return "timed out";
    if (r->err_upper <= r->tol)
        return NULL;
    return isinf(r->err_upper) ? "unbounded" : "over tol";
}

/* The ok jobs whose certificate does not hold them within tol, one at a
 * time in the curves table's order: from cell *at on, the next such job's
 * row, its cell (*p, *m, *k) and why (not_certified); NULL past the last. */
static const ob_res_row *next_cert_miss(const ob_summary *s, long *at, int *p, int *m, int *k, const char **why)
{
    for (const long n = (long)s->np * s->nm * s->nt; *at < n; ++*at) {
        *p = (int)(*at / ((long)s->nm * s->nt)), *m = (int)(*at / s->nt % s->nm), *k = (int)(*at % s->nt);
        const ob_res_row *r = s->run.cell[ob_sum_at(s, *p, *m, *k)];
        if ((*why = not_certified(r)) != NULL) {
            ++*at;
            return r;
        }
    }
    return NULL;
}

static void cell_job_ratio(char *buf, size_t len, const ob_res_row *a, const ob_res_row *b)
{
    if (is_ok(a) && is_ok(b))
        fmt_ratio(buf, len, (double)a->ctrl_points, (double)b->ctrl_points);
    else
        snprintf(buf, len, "-");
}

/* "median [q1, q3]" (fmt: how each number is written), "-" for no values. */
static void cell_quart(char *buf, size_t len, const ob_sum_quart *q, double scale,
                       void (*fmt)(char *, size_t, double))
{
    if (q->n == 0) {
        snprintf(buf, len, "-");
        return;
    }
    char a[40], b[40], c[40];
    fmt(a, sizeof a, q->median * scale);
    fmt(b, sizeof b, q->q1 * scale);
    fmt(c, sizeof c, q->q3 * scale);
    snprintf(buf, len, "%s [%s, %s]", a, b, c);
}

/* A family cell: the quartiles and "(k non-ok)" when there are such jobs. */
static void cell_fam(char *buf, size_t len, const ob_sum_fcell *c)
{
    cell_quart(buf, len, &c->q, 1, fmt_val);
    if (c->nonok) {
        const size_t k = strlen(buf);
        snprintf(buf + k, len - k, " (%d non-ok)", c->nonok);
    }
}

/* ---------------------------------------------------------------- grids */

enum { MAXCOL = 64 };

/* A table of cell texts: a header (md labels; for LaTeX, labels of their
 * own under optional spans), alignment, rows, and where groups start. */
typedef struct {
    int ncols;
    const char *label[MAXCOL];     /* Markdown's header */
    const char *tex_label[MAXCOL]; /* LaTeX's (second) header row */
    const char *span[MAXCOL];      /* LaTeX: a label over span_n[c] columns from c */
    int span_n[MAXCOL];
    char align[MAXCOL];            /* 'l' or 'r' */
    char **cell;                   /* nrows x ncols, owned */
    char *group;                   /* row starts a group (not the first) */
    int nrows, cap;
    int failed;                    /* out of memory on the way */
} grid;

static void grid_col(grid *g, const char *label, const char *tex_label, char align)
{
    if (g->ncols >= MAXCOL) {
        g->failed = 1;
        return;
    }
    g->label[g->ncols] = label;
    g->tex_label[g->ncols] = tex_label ? tex_label : label;
    g->align[g->ncols] = align;
    g->ncols++;
}

/* The columns of the methods, one each, or (with a baseline) three:
 * the value, the baseline's and new/base, under the method's name. */
static void grid_method_cols(grid *g, const ob_summary *s)
{
    for (int m = 0; m < s->nm; m++) {
        if (!s->has_base) {
            grid_col(g, ob_sum_label(s, m), NULL, 'r');
            continue;
        }
        if (g->ncols + 3 > MAXCOL) {
            g->failed = 1;
            return;
        }
        g->span[g->ncols] = s->methods[m];
        g->span_n[g->ncols] = 3;
        grid_col(g, s->methods[m], "new", 'r');
        grid_col(g, "base", NULL, 'r');
        grid_col(g, "new/base", NULL, 'r');
    }
}

/* Starts a row (group: it begins a group); its cells are set with
 * grid_set.  Returns the row, or -1 (g->failed). */
static int grid_row(grid *g, int group)
{
    if (g->failed)
        return -1;
    if (g->nrows == g->cap) {
        const int cap = g->cap ? 2 * g->cap : 64;
        char **c = realloc(g->cell, (size_t)cap * (size_t)g->ncols * sizeof *c);
        if (c)
            g->cell = c;
        char *gr = c ? realloc(g->group, (size_t)cap) : NULL;
        if (!gr) {
            g->failed = 1;
            return -1;
        }
        g->group = gr;
        g->cap = cap;
    }
    for (int c = 0; c < g->ncols; c++)
        g->cell[(size_t)g->nrows * (size_t)g->ncols + (size_t)c] = NULL;
    g->group[g->nrows] = (char)(group && g->nrows > 0);
    return g->nrows++;
}

static void grid_set(grid *g, int row, int col, const char *text)
{
    if (row < 0 || col >= g->ncols)
        return;
    char *t = strdup(text);
    if (!t)
        g->failed = 1;
    g->cell[(size_t)row * (size_t)g->ncols + (size_t)col] = t;
}

static const char *grid_get(const grid *g, int row, int col)
{
    const char *t = g->cell[(size_t)row * (size_t)g->ncols + (size_t)col];
    return t ? t : "";
}

static void grid_free(grid *g)
{
    for (size_t i = 0; i < (size_t)g->nrows * (size_t)g->ncols; i++)
        free(g->cell[i]);
    free(g->cell);
    free(g->group);
    memset(g, 0, sizeof *g);
}

/* ---------------------------------------------------------------- the tables */

/* Per (curve, d) and tolerance: the methods' jobs. */
static void grid_curves(grid *g, const ob_summary *s)
{
    grid_col(g, "curve", NULL, 'l');
    grid_col(g, "d", NULL, 'r');
    grid_col(g, "tol", NULL, 'r');
    grid_method_cols(g, s);
    char buf[128], d[40];
    for (int p = 0; p < s->np; p++)
        for (int k = 0; k < s->nt; k++) {
            const int row = grid_row(g, k == 0);
            const int same_curve = p > 0 && strcmp(s->pairs[p - 1].curve, s->pairs[p].curve) == 0;
            /* 6 digits, not the 17 of an exact offset (the CSV has them all) */
            snprintf(d, sizeof d, "%.6g", s->pairs[p].d);
            grid_set(g, row, 0, k == 0 && !same_curve ? s->pairs[p].curve : "");
            grid_set(g, row, 1, k == 0 ? d : "");
            grid_set(g, row, 2, s->tol_text[k]);
            int col = 3;
            for (int m = 0; m < s->nm; m++) {
                const ob_res_row *r = s->run.cell[ob_sum_at(s, p, m, k)];
                if (s->has_cert)
                    cell_job_cert(buf, sizeof buf, r);
                else
                    cell_job(buf, sizeof buf, r);
                grid_set(g, row, col++, buf);
                if (!s->has_base)
                    continue;
                const ob_res_row *b = s->base.cell[ob_sum_at(s, p, m, k)];
                cell_job(buf, sizeof buf, b);
                grid_set(g, row, col++, buf);
                cell_job_ratio(buf, sizeof buf, r, b);
                grid_set(g, row, col++, buf);
            }
        }
}

/* Per family and tolerance: the methods' quartiles. */
static void grid_families(grid *g, const ob_summary *s)
{
    grid_col(g, "family", NULL, 'l');
    grid_col(g, "pairs", NULL, 'r');
    grid_col(g, "tol", NULL, 'r');
    grid_method_cols(g, s);
    char buf[256];
    for (int f = 0; f < s->nf; f++)
        for (int k = 0; k < s->nt; k++) {
            const int row = grid_row(g, k == 0);
            snprintf(buf, sizeof buf, "%d", s->fam_pairs[f]);
            grid_set(g, row, 0, k == 0 ? s->families[f] : "");
            grid_set(g, row, 1, k == 0 ? buf : "");
            grid_set(g, row, 2, s->tol_text[k]);
            int col = 3;
            for (int m = 0; m < s->nm; m++) {
                const ob_sum_fcell *c = &s->run.fam[ob_sum_fat(s, f, m, k)];
                cell_fam(buf, sizeof buf, c);
                grid_set(g, row, col++, buf);
                if (!s->has_base)
                    continue;
                const ob_sum_fcell *b = &s->base.fam[ob_sum_fat(s, f, m, k)];
                cell_fam(buf, sizeof buf, b);
                grid_set(g, row, col++, buf);
                fmt_ratio(buf, sizeof buf, c->q.median, b->q.median);
                grid_set(g, row, col++, buf);
            }
        }
}

/* Per method: the jobs by status and the time per job (ms). */
static void grid_methods(grid *g, const ob_summary *s)
{
    grid_col(g, "method", NULL, 'l');
    grid_col(g, "jobs", NULL, 'r');
    for (int st = 0; st < OB_SUM_NSTATUS; st++)
        grid_col(g, ob_sum_status_names[st], NULL, 'r');
    grid_col(g, "time/job (ms)", NULL, 'r');
    if (s->has_cert) {
        grid_col(g, "certified", NULL, 'r');
        grid_col(g, "not certified", NULL, 'r');
        grid_col(g, "cert/job (ms)", NULL, 'r');
    }
    if (s->has_base) {
        grid_col(g, "base ok", NULL, 'r');
        grid_col(g, "base time/job (ms)", NULL, 'r');
        grid_col(g, "new/base", NULL, 'r');
    }
    char buf[256];
    for (int m = 0; m < s->nm; m++) {
        const ob_sum_mstat *ms = &s->run.meth[m];
        const int row = grid_row(g, 0);
        int col = 0;
        grid_set(g, row, col++, ob_sum_label(s, m));
        snprintf(buf, sizeof buf, "%d", ms->jobs);
        grid_set(g, row, col++, buf);
        for (int st = 0; st < OB_SUM_NSTATUS; st++) {
            snprintf(buf, sizeof buf, "%d", ms->status[st]);
            grid_set(g, row, col++, buf);
        }
        cell_quart(buf, sizeof buf, &ms->time_ns, 1e-6, fmt3);
        grid_set(g, row, col++, buf);
        if (s->has_cert) {
            snprintf(buf, sizeof buf, "%d", ms->cert_yes);
            grid_set(g, row, col++, buf);
            snprintf(buf, sizeof buf, "%d", ms->cert_no);
            grid_set(g, row, col++, buf);
            cell_quart(buf, sizeof buf, &ms->cert_ns, 1e-6, fmt3);
            grid_set(g, row, col++, buf);
        }
        if (!s->has_base)
            continue;
        const ob_sum_mstat *bs = &s->base.meth[m];
        snprintf(buf, sizeof buf, "%d", bs->status[OB_SUM_OK]);
        grid_set(g, row, col++, buf);
        cell_quart(buf, sizeof buf, &bs->time_ns, 1e-6, fmt3);
        grid_set(g, row, col++, buf);
        fmt_ratio(buf, sizeof buf, ms->time_ns.median, bs->time_ns.median);
        grid_set(g, row, col++, buf);
    }
}

/* Of method m's ok jobs at tolerance k that have a certificate: *n, and
 * *yes those it holds within tol. */
static void cert_count(const ob_summary *s, int m, int k, int *yes, int *n)
{
    *yes = *n = 0;
    for (int p = 0; p < s->np; p++) {
        const ob_res_row *r = s->run.cell[ob_sum_at(s, p, m, k)];
        if (!is_ok(r) || !r->cert_done)
            continue;
        ++*n;
        *yes += r->cert_done == 1 && r->err_upper <= r->tol;
    }
}

/* Per method and tolerance: the ok jobs certified within tol, of those
 * with a certificate (run --certify). */
static void grid_cert_tols(grid *g, const ob_summary *s)
{
    grid_col(g, "method", NULL, 'l');
    for (int k = 0; k < s->nt; k++)
        grid_col(g, s->tol_text[k], NULL, 'r');
    char buf[64];
    for (int m = 0; m < s->nm; m++) {
        const int row = grid_row(g, 0);
        grid_set(g, row, 0, ob_sum_label(s, m));
        for (int k = 0; k < s->nt; k++) {
            int yes, n;
            cert_count(s, m, k, &yes, &n);
            if (n)
                snprintf(buf, sizeof buf, "%d of %d", yes, n);
            else
                snprintf(buf, sizeof buf, "-");
            grid_set(g, row, 1 + k, buf);
        }
    }
}

/* The ok jobs whose certificate does not hold them within tol, in the
 * curves table's order. */
static void grid_cert_misses(grid *g, const ob_summary *s)
{
    static const char *const label[] = {"curve", "d", "method", "tol", "ctrl_points", "max_err", "err_upper",
                                        "err_lower", "why"};
    for (size_t c = 0; c < sizeof label / sizeof label[0]; c++)
        grid_col(g, label[c], NULL, c == 0 || c == 2 || c == 8 ? 'l' : 'r');
    char buf[64];
    int any = 0, p, m, k;
    const char *why;
    const ob_res_row *r;
    for (long at = 0; (r = next_cert_miss(s, &at, &p, &m, &k, &why)) != NULL;) {
        const int row = grid_row(g, 0);
        any = 1;
        grid_set(g, row, 0, s->pairs[p].curve);
        snprintf(buf, sizeof buf, "%.6g", s->pairs[p].d);
        grid_set(g, row, 1, buf);
        grid_set(g, row, 2, ob_sum_label(s, m));
        grid_set(g, row, 3, s->tol_text[k]);
        snprintf(buf, sizeof buf, "%ld", r->ctrl_points);
        grid_set(g, row, 4, buf);
        snprintf(buf, sizeof buf, "%.3g", r->max_err);
        grid_set(g, row, 5, buf);
        if (r->cert_done == 1) {
            ob_fmt_bound(buf, sizeof buf, r->err_upper, 1);
            grid_set(g, row, 6, buf);
            ob_fmt_bound(buf, sizeof buf, r->err_lower, -1);
            grid_set(g, row, 7, buf);
        }
        grid_set(g, row, 8, why);
    }
    if (!any)
        grid_set(g, grid_row(g, 0), 0, "(none)");
}

/* ---------------------------------------------------------------- text */

/* One section: its title, what its cells are, and its grid builder. */
typedef struct {
    int bit;
    const char *title;
    const char *what;       /* what a cell is */
    const char *what_base;  /* what the baseline's columns are */
    void (*build)(grid *, const ob_summary *);
    const char *what_cert;  /* what the certificate's columns are (NULL: none) */
    int cert_only;          /* written only for a run with certificates */
} section;

static const section sections[] = {
    {OB_SUM_CURVES, "Control points per curve and d",
     "Each cell: the job's control points when its status is ok, else its status (limit, fail, skip, timeout); "
     "- no such job.",
     "Beside each method: the baseline's job and new/base of the control points (both ok).", grid_curves,
     "Run --certify: beside an ok job's control points, its certified err_upper (rounded up: still a bound on the "
     "two-sided Hausdorff distance to the exact offset); ! over tol; no verdict: the certificate timed out.", 0},
    {OB_SUM_FAMILIES, "Control points per family",
     "Each cell: median [q1, q3] of the control points of the ok jobs (quartiles by linear interpolation between "
     "order statistics, R's type 7); (k non-ok): the jobs with another status, left out; - no ok job.  pairs: the "
     "family's (curve, d) pairs.",
     "Beside each method: the same over the baseline's jobs joined, and new/base of the medians.", grid_families,
     NULL, 0},
    {OB_SUM_METHODS, "Time and failures per method",
     "Jobs by status; time/job: fit_ns + eval_ns of the jobs not skipped, median [q1, q3] in milliseconds.",
     "base ok: the baseline's ok jobs among those joined; base time/job: theirs; new/base: of the median times.",
     grid_methods,
     "certified: the jobs whose certified err_upper is within tol (run --certify); not certified: the others "
     "certified (err_upper over tol, or inf); cert/job: their cert_ns, median [q1, q3] in milliseconds.", 0},
    {OB_SUM_METHODS, "Certified within tol per tolerance",
     "Run --certify: per method and tolerance, the ok jobs whose certified err_upper is within tol, of the ok jobs "
     "with a certificate; - none.",
     "The run's jobs only.", grid_cert_tols, NULL, 1},
    {OB_SUM_METHODS, "Ok but not certified within tol",
     "Run --certify: the ok jobs whose certificate does not hold them within tol: over tol (err_upper > tol), "
     "unbounded (err_upper inf: a piece whose base has a cusp) or timed out (--job-timeout: no verdict).  "
     "err_upper rounded up, err_lower down.",
     "The run's jobs only.", grid_cert_misses, NULL, 1},
};

/* The sections bits selects, each built into a grid and written by emit
 * (Markdown or LaTeX: one loop, two formats); 0, or -1 when a grid could
 * not be built or the stream failed. */
static int each_section(FILE *f, const ob_summary *s, int bits,
                        void (*emit)(FILE *, const ob_summary *, const section *, const grid *))
{
    int rc = 0;
    for (size_t i = 0; i < sizeof sections / sizeof sections[0] && rc == 0; i++) {
        if (!(bits & sections[i].bit) || (sections[i].cert_only && !s->has_cert))
            continue;
        grid g;
        memset(&g, 0, sizeof g);
        sections[i].build(&g, s);
        if (g.failed)
            rc = -1;
        else
            emit(f, s, &sections[i], &g);
        grid_free(&g);
    }
    return rc || ferror(f) ? -1 : 0;
}

/* "a, b, c" of v[0..n) to f. */
static void put_names(FILE *f, const char *const *v, int n)
{
    for (int i = 0; i < n; i++)
        fprintf(f, "%s%s", i ? ", " : "", v[i]);
}

/* The line that says what was summarized (prefix: "" or "% "). */
static void put_scope(FILE *f, const ob_summary *s, const char *prefix)
{
    fprintf(f, "%s%d jobs on %d (curve, d) pair%s of %d curve%s in %d famil%s; methods ", prefix, s->run.njobs, s->np,
            s->np == 1 ? "" : "s", s->ncurves, s->ncurves == 1 ? "" : "s", s->nf, s->nf == 1 ? "y" : "ies");
    put_names(f, s->methods, s->has_archive ? s->nm_run : s->nm);  /* the run's: the archive's have their lines */
    fputs("; tolerances ", f);
    put_names(f, s->tol_text, s->nt);
    fprintf(f, "; metric %s, split %s.\n", s->run.metric, s->run.split);
    if (s->has_base)
        fprintf(f, "%sBaseline: %s (metric %s, split %s): %d of %d jobs joined.\n", prefix, s->base.name, s->base.metric,
                s->base.split, s->base.njobs, s->run.njobs);
    for (int i = 0; i < s->alines.n; i++)
        fprintf(f, "%s%s\n", prefix, s->alines.v[i]);
}

/* ---------------------------------------------------------------- Markdown */

static void md_text(FILE *f, const char *t)
{
    for (; *t; t++) {
        if (*t == '|')
            fputc('\\', f);
        fputc(*t == '\n' ? ' ' : *t, f);
    }
}

static void md_grid(FILE *f, const grid *g)
{
    for (int c = 0; c < g->ncols; c++) {
        fputs("| ", f);
        md_text(f, g->label[c]);
        fputc(' ', f);
    }
    fputs("|\n", f);
    for (int c = 0; c < g->ncols; c++)
        fputs(g->align[c] == 'r' ? "|---:" : "|---", f);
    fputs("|\n", f);
    for (int r = 0; r < g->nrows; r++) {
        for (int c = 0; c < g->ncols; c++) {
            fputs("| ", f);
            md_text(f, grid_get(g, r, c));
            fputc(' ', f);
        }
        fputs("|\n", f);
    }
}

static void md_section(FILE *f, const ob_summary *s, const section *sec, const grid *g)
{
    const int cert = s->has_cert && sec->what_cert;
    fprintf(f, "\n## %s\n\n%s%s%s%s%s\n\n", sec->title, sec->what, cert ? "  " : "", cert ? sec->what_cert : "",
            s->has_base ? "  " : "", s->has_base ? sec->what_base : "");
    md_grid(f, g);
}

int ob_summary_write_md(FILE *f, const ob_summary *s, int bits)
{
    fprintf(f, "# Summary of %s\n\n", s->run.name ? s->run.name : "results.csv");
    put_scope(f, s, "");
    return each_section(f, s, bits, md_section);
}

/* ---------------------------------------------------------------- LaTeX */

static void tex_text(FILE *f, const char *t)
{
    /* "-" alone, or before a space, is "none": an en dash */
    if (t[0] == '-' && (t[1] == '\0' || t[1] == ' ')) {
        fputs("--", f);
        t++;
    }
    for (; *t; t++) {
        switch (*t) {
        case '\\': fputs("\\textbackslash{}", f); break;
        case '~': fputs("\\textasciitilde{}", f); break;
        case '^': fputs("\\textasciicircum{}", f); break;
        case '_': case '&': case '%': case '$': case '#': case '{': case '}':
            fputc('\\', f);
            fputc(*t, f);
            break;
        case '\n': fputc(' ', f); break;
        default: fputc(*t, f);
        }
    }
}

/* The spans' header row and its \cmidrules, when the grid has spans. */
static void tex_spans(FILE *f, const grid *g)
{
    int any = 0;
    for (int c = 0; c < g->ncols; c++)
        any |= g->span[c] != NULL;
    if (!any)
        return;
    for (int c = 0; c < g->ncols;) {
        fputs(c ? " & " : "", f);
        if (!g->span[c]) {
            c++;
            continue;
        }
        fprintf(f, "\\multicolumn{%d}{c}{", g->span_n[c]);
        tex_text(f, g->span[c]);
        fputc('}', f);
        c += g->span_n[c];
    }
    fputs(" \\\\\n", f);
    for (int c = 0; c < g->ncols; c++)
        if (g->span[c])
            fprintf(f, "\\cmidrule(lr){%d-%d}", c + 1, c + g->span_n[c]);
    fputc('\n', f);
}

static void tex_grid(FILE *f, const grid *g)
{
    fputs("\\begin{tabular}{", f);
    for (int c = 0; c < g->ncols; c++)
        fputc(g->align[c], f);
    fputs("}\n\\toprule\n", f);
    tex_spans(f, g);
    for (int c = 0; c < g->ncols; c++) {
        fputs(c ? " & " : "", f);
        tex_text(f, g->tex_label[c]);
    }
    fputs(" \\\\\n\\midrule\n", f);
    for (int r = 0; r < g->nrows; r++) {
        if (g->group[r])
            fputs("\\addlinespace\n", f);
        for (int c = 0; c < g->ncols; c++) {
            fputs(c ? " & " : "", f);
            tex_text(f, grid_get(g, r, c));
        }
        fputs(" \\\\\n", f);
    }
    fputs("\\bottomrule\n\\end{tabular}\n", f);
}

/* A comment line: '%' and the text with its newlines turned to spaces. */
static void tex_comment(FILE *f, const char *t)
{
    fputs("% ", f);
    for (; *t; t++)
        fputc(*t == '\n' || *t == '\r' ? ' ' : *t, f);
    fputc('\n', f);
}

static void tex_section(FILE *f, const ob_summary *s, const section *sec, const grid *g)
{
    fputc('\n', f);
    tex_comment(f, sec->title);
    tex_comment(f, sec->what);
    if (s->has_cert && sec->what_cert)
        tex_comment(f, sec->what_cert);
    if (s->has_base)
        tex_comment(f, sec->what_base);
    tex_grid(f, g);
}

int ob_summary_write_latex(FILE *f, const ob_summary *s, int bits)
{
    char line[4400];
    snprintf(line, sizeof line, "offbench summary of %s (needs \\usepackage{booktabs})",
             s->run.name ? s->run.name : "results.csv");
    tex_comment(f, line);
    put_scope(f, s, "% ");
    return each_section(f, s, bits, tex_section);
}

/* ---------------------------------------------------------------- CSV */

enum {
    CV_SECTION, CV_FAMILY, CV_CURVE, CV_D, CV_METHOD, CV_TOL, CV_STATUS, CV_VALUE, CV_Q1, CV_Q3, CV_N, CV_NONOK,
    CV_BSTATUS, CV_BVALUE, CV_BQ1, CV_BQ3, CV_BN, CV_RATIO,
    CV_EUP, CV_ELO, CV_CERT, /* a run with certificates only: its header has them */
    CV_NCOL
};

static const char *const csv_header =
    "section,family,curve,d,method,tol,status,value,q1,q3,n,n_nonok,base_status,base_value,base_q1,base_q3,base_n,"
    "ratio";

/* One CSV line of fields (NULL: empty), quoted where needed. */
typedef struct {
    char f[CV_NCOL][64];
    const char *text[CV_NCOL]; /* long text fields (names), else f[] */
    int ncol;                  /* the fields written: CV_NCOL with certificates, else up to ratio */
    const ob_summary *s;       /* with an archive, csv_put adds the method's source */
} csv_line;

static int csv_ncol(const ob_summary *s) { return s->has_cert ? CV_NCOL : CV_RATIO + 1; }

static void csv_clear(csv_line *l, const ob_summary *s)
{
    l->ncol = csv_ncol(s);
    l->s = s;
    for (int c = 0; c < CV_NCOL; c++) {
        l->f[c][0] = '\0';
        l->text[c] = NULL;
    }
}

/* A cleared line of section `what` keyed by cell (p, m, k): curve, d,
 * method and tol. */
static void csv_cell(csv_line *l, const ob_summary *s, const char *what, int p, int m, int k)
{
    csv_clear(l, s);
    l->text[CV_SECTION] = what;
    l->text[CV_FAMILY] = s->pairs[p].family;
    l->text[CV_CURVE] = s->pairs[p].curve;
    l->text[CV_D] = s->pairs[p].d_text;
    l->text[CV_METHOD] = s->methods[m];
    l->text[CV_TOL] = s->tol_text[k];
}

static void csv_num(csv_line *l, int c, double v)
{
    if (isfinite(v))
        ob_fmt_double(l->f[c], sizeof l->f[c], v);
}

static void csv_int(csv_line *l, int c, long v) { snprintf(l->f[c], sizeof l->f[c], "%ld", v); }

static void csv_field(FILE *f, const char *t)
{
    if (!strpbrk(t, ",\"\n\r")) {
        fputs(t, f);
        return;
    }
    fputc('"', f);
    for (; *t; t++) {
        if (*t == '"')
            fputc('"', f);
        fputc(*t, f);
    }
    fputc('"', f);
}

/* The source column (--archive): the results.csv a method's rows come from. */
static const char *csv_source(const ob_summary *s, const char *method)
{
    for (int m = method ? 0 : s->nm; m < s->nm; m++)
        if (strcmp(s->methods[m], method) == 0)
            return s->msrc[m] ? s->msrc[m] : s->run.name;
    return "";
}

static void csv_put(FILE *f, const csv_line *l)
{
    for (int c = 0; c < l->ncol; c++) {
        if (c)
            fputc(',', f);
        csv_field(f, l->text[c] ? l->text[c] : l->f[c]);
    }
    if (l->s->has_archive) {
        fputc(',', f);
        csv_field(f, csv_source(l->s, l->text[CV_METHOD]));
    }
    fputc('\n', f);
}

/* A quartile summary into value, q1, q3 (n, n_nonok too) from column at. */
static void csv_quart(csv_line *l, int at, const ob_sum_quart *q)
{
    csv_num(l, at, q->median);
    csv_num(l, at + 1, q->q1);
    csv_num(l, at + 2, q->q3);
}

/* A job's certificate into err_upper, err_lower, certified (empty
 * without one, or when it timed out). */
static void csv_job_cert(csv_line *l, const ob_res_row *r)
{
    if (r->cert_done != 1)
        return;
    if (isinf(r->err_upper))
        l->text[CV_EUP] = "inf";
    else
        csv_num(l, CV_EUP, r->err_upper);
    csv_num(l, CV_ELO, r->err_lower);
    l->text[CV_CERT] = r->certified;
}

static void csv_curves(FILE *f, const ob_summary *s)
{
    csv_line l;
    for (int p = 0; p < s->np; p++)
        for (int m = 0; m < s->nm; m++)
            for (int k = 0; k < s->nt; k++) {
                const ob_res_row *r = s->run.cell[ob_sum_at(s, p, m, k)];
                if (!r)
                    continue;
                csv_cell(&l, s, "curve", p, m, k);
                l.text[CV_STATUS] = r->status;
                if (is_ok(r))
                    csv_int(&l, CV_VALUE, r->ctrl_points);
                csv_job_cert(&l, r);
                if (s->has_base) {
                    const ob_res_row *b = s->base.cell[ob_sum_at(s, p, m, k)];
                    l.text[CV_BSTATUS] = b ? b->status : "missing";
                    if (is_ok(b))
                        csv_int(&l, CV_BVALUE, b->ctrl_points);
                    if (is_ok(r) && is_ok(b) && b->ctrl_points > 0)
                        csv_num(&l, CV_RATIO, (double)r->ctrl_points / (double)b->ctrl_points);
                }
                csv_put(f, &l);
            }
}

static void csv_families(FILE *f, const ob_summary *s)
{
    csv_line l;
    for (int fi = 0; fi < s->nf; fi++)
        for (int m = 0; m < s->nm; m++)
            for (int k = 0; k < s->nt; k++) {
                const ob_sum_fcell *c = &s->run.fam[ob_sum_fat(s, fi, m, k)];
                csv_clear(&l, s);
                l.text[CV_SECTION] = "family";
                l.text[CV_FAMILY] = s->families[fi];
                l.text[CV_METHOD] = s->methods[m];
                l.text[CV_TOL] = s->tol_text[k];
                csv_quart(&l, CV_VALUE, &c->q);
                csv_int(&l, CV_N, c->q.n);
                csv_int(&l, CV_NONOK, c->nonok);
                if (s->has_base) {
                    const ob_sum_fcell *b = &s->base.fam[ob_sum_fat(s, fi, m, k)];
                    csv_quart(&l, CV_BVALUE, &b->q);
                    csv_int(&l, CV_BN, b->q.n);
                    if (c->q.median > 0 && b->q.median > 0)
                        csv_num(&l, CV_RATIO, c->q.median / b->q.median);
                }
                csv_put(f, &l);
            }
}

/* A method's certificates (run --certify): rows "certified" with status
 * yes and no (the counts), and "cert_time" (cert_ns quartiles). */
static void csv_cert(FILE *f, const ob_summary *s, const char *method, const ob_sum_mstat *ms, const ob_sum_mstat *bs)
{
    csv_line l;
    for (int yes = 1; yes >= 0; yes--) {
        csv_clear(&l, s);
        l.text[CV_SECTION] = "certified";
        l.text[CV_METHOD] = method;
        l.text[CV_STATUS] = yes ? "yes" : "no";
        csv_int(&l, CV_VALUE, yes ? ms->cert_yes : ms->cert_no);
        if (bs && bs->cert_yes + bs->cert_no > 0)
            csv_int(&l, CV_BVALUE, yes ? bs->cert_yes : bs->cert_no);
        csv_put(f, &l);
    }
    csv_clear(&l, s);
    l.text[CV_SECTION] = "cert_time";
    l.text[CV_METHOD] = method;
    csv_quart(&l, CV_VALUE, &ms->cert_ns);
    csv_int(&l, CV_N, ms->cert_ns.n);
    csv_put(f, &l);
}

/* Run --certify: per method and tolerance, rows certified_tol (value: the
 * ok jobs certified within tol, n: those with a certificate); then a row
 * not_certified per ok job not held within tol (status: why, value: its
 * control points, and its certificate). */
static void csv_cert_tables(FILE *f, const ob_summary *s)
{
    csv_line l;
    for (int m = 0; m < s->nm; m++)
        for (int k = 0; k < s->nt; k++) {
            int yes, n;
            cert_count(s, m, k, &yes, &n);
            csv_clear(&l, s);
            l.text[CV_SECTION] = "certified_tol";
            l.text[CV_METHOD] = s->methods[m];
            l.text[CV_TOL] = s->tol_text[k];
            csv_int(&l, CV_VALUE, yes);
            csv_int(&l, CV_N, n);
            csv_put(f, &l);
        }
    int p, m, k;
    const char *why;
    const ob_res_row *r;
    for (long at = 0; (r = next_cert_miss(s, &at, &p, &m, &k, &why)) != NULL;) {
        csv_cell(&l, s, "not_certified", p, m, k);
        l.text[CV_STATUS] = why;
        csv_int(&l, CV_VALUE, r->ctrl_points);
        csv_job_cert(&l, r);
        csv_put(f, &l);
    }
}

static void csv_methods(FILE *f, const ob_summary *s)
{
    csv_line l;
    for (int m = 0; m < s->nm; m++) {
        const ob_sum_mstat *ms = &s->run.meth[m], *bs = s->has_base ? &s->base.meth[m] : NULL;
        csv_clear(&l, s);
        l.text[CV_SECTION] = "time";
        l.text[CV_METHOD] = s->methods[m];
        csv_quart(&l, CV_VALUE, &ms->time_ns);
        csv_int(&l, CV_N, ms->time_ns.n);
        if (bs) {
            csv_quart(&l, CV_BVALUE, &bs->time_ns);
            csv_int(&l, CV_BN, bs->time_ns.n);
            if (ms->time_ns.median > 0 && bs->time_ns.median > 0)
                csv_num(&l, CV_RATIO, ms->time_ns.median / bs->time_ns.median);
        }
        csv_put(f, &l);
        for (int st = 0; st < OB_SUM_NSTATUS; st++) {
            csv_clear(&l, s);
            l.text[CV_SECTION] = "status";
            l.text[CV_METHOD] = s->methods[m];
            l.text[CV_STATUS] = ob_sum_status_names[st];
            csv_int(&l, CV_VALUE, ms->status[st]);
            if (bs)
                csv_int(&l, CV_BVALUE, bs->status[st]);
            csv_put(f, &l);
        }
        if (s->has_cert)
            csv_cert(f, s, s->methods[m], ms, bs);
    }
}

int ob_summary_write_csv(FILE *f, const ob_summary *s, int bits)
{
    fprintf(f, "%s%s%s\n", csv_header, s->has_cert ? ",err_upper,err_lower,certified" : "",
            s->has_archive ? ",source" : "");
    if (bits & OB_SUM_CURVES)
        csv_curves(f, s);
    if (bits & OB_SUM_FAMILIES)
        csv_families(f, s);
    if (bits & OB_SUM_METHODS)
        csv_methods(f, s);
    if ((bits & OB_SUM_METHODS) && s->has_cert)
        csv_cert_tables(f, s);
    return ferror(f) ? -1 : 0;
}
