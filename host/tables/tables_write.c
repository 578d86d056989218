/*
 * tables_write.c - tables.csv (one row per published cell and protocol),
 * tables.md (each table as in its paper, published and ours side by side,
 * then the match / close / differs count of every column) and
 * zhao_sweep.csv.
 */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "host/io/output.h"
#include "host/tables/tables.h"

const char *const ob_tab_status_names[OB_TAB_NSTATUS] = {"match", "close", "differs", "no-method", "no-data"};

/* Half a unit in the last printed digit of a published figure ("0.1030",
 * "2.9199e-5", "886"). */
static double half_ulp(const char *text)
{
    const char *e = strpbrk(text, "eE");
    const char *dot = strchr(text, '.');
    int decimals = 0;
    if (dot && (!e || dot < e))
        decimals = (int)((e ? e : text + strlen(text)) - dot - 1);
    int exp10 = e ? atoi(e + 1) : 0;
    return 0.5 * pow(10.0, exp10 - decimals);
}

int ob_tab_row_status(const ob_tab_plan *pl, const ob_tab_row *r, double *ours)
{
    if (ours)
        *ours = NAN;
    if (r->slot < 0)
        return strcmp(r->fixed, "no-method") == 0 ? OB_TAB_NO_METHOD : OB_TAB_NO_DATA;
    const ob_job *j = &pl->slots[r->slot].job;
    const ob_pub_cell *c = r->cell;
    const int errors = strcmp(c->unit, "max_err") == 0;
    double v = NAN;
    if (errors && (j->status == OB_OK || j->status == OB_LIMIT))
        v = j->max_err;
    else if (!errors && (j->status == OB_OK || j->status == OB_LIMIT))
        v = (double)j->ctrl_points;
    if (ours)
        *ours = v;
    if (isnan(v) || (!errors && j->status != OB_OK))
        return OB_TAB_DIFFERS;
    if (errors ? fabs(v - c->value) <= half_ulp(c->value_text) * (1 + 1e-12) : v == c->value)
        return OB_TAB_MATCH;
    if (fabs(v - c->value) <= 0.1 * c->value)
        return OB_TAB_CLOSE;
    return OB_TAB_DIFFERS;
}

static void put_num(FILE *f, double x)
{
    char b[64];
    if (isnan(x))
        return;
    ob_fmt_double(b, sizeof b, x);
    fputs(b, f);
}

int ob_tab_write_csv(FILE *f, void *ctx)
{
    const ob_tab_out *t = ctx;
    const ob_tab_plan *pl = t->pl;
    fputs("source,table,curve,d,tol,method,label,protocol,published,ours,ratio,status,unit,d_run,metric,split,"
          "job_status,note\n",
          f);
    for (int i = 0; i < pl->nrows; i++) {
        const ob_tab_row *r = &pl->rows[i];
        const ob_pub_cell *c = r->cell;
        double ours;
        int st = ob_tab_row_status(pl, r, &ours);
        const char *fields[] = {c->source, c->table, c->curve, c->d_text, c->tol_text, c->method, c->label,
                                ob_proto_name(r->proto), c->value_text};
        for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
            ob_csv_field(f, fields[k]);
            fputc(',', f);
        }
        put_num(f, ours);
        fputc(',', f);
        put_num(f, isnan(ours) || c->value == 0 ? NAN : ours / c->value);
        fprintf(f, ",%s,%s,", ob_tab_status_names[st], c->unit);
        if (r->slot >= 0) {
            const ob_job *j = &pl->slots[r->slot].job;
            put_num(f, r->d_run);
            fprintf(f, ",%s,%s,%s,", ob_metric_name(j->metric),
                    r->spec.single_piece ? "none" : ob_split_name(j->split), ob_status_name(j->status));
            char note[512];
            snprintf(note, sizeof note, "%s%s%s", r->spec.note, j->message[0] ? "; job: " : "", j->message);
            ob_csv_field(f, note);
        } else {
            fputs(",,,,", f);
            ob_csv_field(f, r->fixed[3] == 'm' ? "offbench has no such method" : "the curve's data is not in the seeds");
        }
        fputc('\n', f);
    }
    return ferror(f) ? -1 : 0;
}

static const char *source_title(const char *s)
{
    if (strcmp(s, "liu2002") == 0)
        return "Liu & Wang 2002 (J. Software 13(3))";
    if (strcmp(s, "ahn2023") == 0)
        return "Ahn 2023 (G2/C1 Hermite interpolation of offset curves, AIMS)";
    if (strcmp(s, "zhao2017") == 0)
        return "Zhao & Zhou 2017 (Algorithms 10(3))";
    return s;
}

static const char *mark(int st)
{
    static const char *m[] = {" =", " ~", " x", "", ""};
    return m[st];
}

/* Distinct strings, in order of first appearance. */
typedef struct {
    const char *v[64];
    int n;
} strlist;

static int strlist_add(strlist *l, const char *s)
{
    for (int i = 0; i < l->n; i++)
        if (strcmp(l->v[i], s) == 0)
            return i;
    if (l->n == 64)
        return -1;
    l->v[l->n] = s;
    return l->n++;
}

/* The row key of a cell in its table: the tolerance, or for error tables
 * the curve piece. */
static const char *row_key(const ob_pub_cell *c)
{
    return strcmp(c->unit, "max_err") == 0 ? c->curve : c->tol_text;
}

static int same_table(const ob_pub_cell *a, const ob_pub_cell *b)
{
    return strcmp(a->source, b->source) == 0 && strcmp(a->table, b->table) == 0;
}

static void write_grid(FILE *f, const ob_tab_plan *pl, const ob_pub_cell *first, ob_proto p, const strlist *rows,
                       const strlist *cols)
{
    fprintf(f, "| %s |", strcmp(first->unit, "max_err") == 0 ? "curve" : "tol");
    for (int k = 0; k < cols->n; k++)
        fprintf(f, " %s |", cols->v[k]);
    fputs("\n|---|", f);
    for (int k = 0; k < cols->n; k++)
        fputs("---|", f);
    fputc('\n', f);
    for (int i = 0; i < rows->n; i++) {
        fprintf(f, "| %s |", rows->v[i]);
        for (int k = 0; k < cols->n; k++) {
            const ob_tab_row *hit = NULL;
            for (int q = 0; q < pl->nrows && !hit; q++) {
                const ob_tab_row *r = &pl->rows[q];
                if (r->proto == p && same_table(r->cell, first) && strcmp(row_key(r->cell), rows->v[i]) == 0 &&
                    strcmp(r->cell->label, cols->v[k]) == 0)
                    hit = r;
            }
            if (!hit) {
                fputs(" |", f);
                continue;
            }
            double ours;
            int st = ob_tab_row_status(pl, hit, &ours);
            char b[64] = "-";
            if (!isnan(ours)) {
                if (strcmp(hit->cell->unit, "max_err") == 0)
                    snprintf(b, sizeof b, "%.3g", ours);
                else
                    snprintf(b, sizeof b, "%.0f", ours);
            }
            const ob_job *j = hit->slot >= 0 ? &pl->slots[hit->slot].job : NULL;
            const char *flag = j && j->status != OB_OK && strcmp(hit->cell->unit, "ctrl_points") == 0
                                   ? (j->status == OB_LIMIT ? " (limit)" : " (fail)")
                                   : "";
            fprintf(f, " %s / %s%s%s |", hit->cell->value_text, st >= OB_TAB_NO_METHOD ? ob_tab_status_names[st] : b,
                    flag, mark(st));
        }
        fputc('\n', f);
    }
    fputc('\n', f);
}

/* The readings used for the columns of one table under one protocol: one
 * line per distinct reading, naming its columns. */
static void write_notes(FILE *f, const ob_tab_plan *pl, const ob_pub_cell *first, ob_proto p, const strlist *cols)
{
    strlist notes = {0};
    for (int q = 0; q < pl->nrows; q++) {
        const ob_tab_row *r = &pl->rows[q];
        if (r->proto == p && same_table(r->cell, first) && r->slot >= 0)
            strlist_add(&notes, r->spec.note);
    }
    for (int i = 0; i < notes.n; i++) {
        fputs("- ", f);
        int any = 0;
        for (int k = 0; k < cols->n; k++) {
            int uses = 0;
            for (int q = 0; q < pl->nrows && !uses; q++) {
                const ob_tab_row *r = &pl->rows[q];
                uses = r->proto == p && same_table(r->cell, first) && r->slot >= 0 &&
                       strcmp(r->cell->label, cols->v[k]) == 0 && strcmp(r->spec.note, notes.v[i]) == 0;
            }
            if (uses)
                fprintf(f, "%s%s", any++ ? ", " : "", cols->v[k]);
        }
        fprintf(f, ": %s\n", notes.v[i]);
    }
    if (notes.n)
        fputc('\n', f);
}

static void write_counts(FILE *f, const ob_tab_plan *pl, const ob_pub_cell *first, const strlist *cols)
{
    fputs("| column | paper | rigorous | best |\n|---|---|---|---|\n", f);
    for (int k = 0; k < cols->n; k++) {
        fprintf(f, "| %s |", cols->v[k]);
        for (int p = 0; p < OB_PROTO_COUNT; p++) {
            int cnt[OB_TAB_NSTATUS] = {0};
            for (int q = 0; q < pl->nrows; q++) {
                const ob_tab_row *r = &pl->rows[q];
                if (r->proto == (ob_proto)p && same_table(r->cell, first) && strcmp(r->cell->label, cols->v[k]) == 0)
                    cnt[ob_tab_row_status(pl, r, NULL)]++;
            }
            int total = 0;
            for (int k2 = 0; k2 < OB_TAB_NSTATUS; k2++)
                total += cnt[k2];
            if (total == 0)
                fputs(" - |", f);
            else if (cnt[OB_TAB_NO_METHOD] || cnt[OB_TAB_NO_DATA])
                fprintf(f, " %s |", cnt[OB_TAB_NO_METHOD] ? "no-method" : "no-data");
            else
                fprintf(f, " %d / %d / %d |", cnt[OB_TAB_MATCH], cnt[OB_TAB_CLOSE], cnt[OB_TAB_DIFFERS]);
        }
        fputc('\n', f);
    }
    fputc('\n', f);
}

static void write_sweep_md(FILE *f, const ob_tab_plan *pl)
{
    if (pl->nsweep == 0)
        return;
    fputs("## Zhao & Zhou 2017, Table 1: the quintic's radius\n\n"
          "The radius of the quintic example is not published. Errors of one fit per piece (C: the whole "
          "curve; C1, C2: its halves at t = 1/2) for a range of d, under the paper's normal-direction "
          "error and under the Hausdorff distance (rigorous). Published: Lee's 1.24 / 0.0443 / 0.0256, "
          "Our Algorithm 0.0033 / 2.9199e-5 / 4.9096e-5. Nor is the cut point published: zhao_sweep.csv "
          "also has C1 and C2 cut at t = 0.3, 0.4, 0.6 and 0.7 (pieces C1@X, C2@X).\n\n| d |",
          f);
    strlist cols = {0};
    char names[64][48];
    for (int i = 0; i < pl->nsweep; i++) {
        const ob_tab_sweep *w = &pl->sweep[i];
        if (strchr(w->piece, '@'))  /* the other cut points: zhao_sweep.csv only */
            continue;
        snprintf(names[cols.n < 64 ? cols.n : 63], 48, "%s %s (%s)", w->method, w->piece,
                 w->proto == OB_PROTO_PAPER ? "normal" : "hausdorff");
        int before = cols.n;
        int k = strlist_add(&cols, names[cols.n < 64 ? cols.n : 63]);
        if (k == before && cols.n > before)
            continue;
    }
    for (int k = 0; k < cols.n; k++)
        fprintf(f, " %s |", cols.v[k]);
    fputs("\n|---|", f);
    for (int k = 0; k < cols.n; k++)
        fputs("---|", f);
    fputc('\n', f);
    strlist ds = {0};
    char dtext[64][24];
    for (int i = 0; i < pl->nsweep; i++) {
        snprintf(dtext[ds.n < 64 ? ds.n : 63], 24, "%g", pl->sweep[i].d);
        strlist_add(&ds, dtext[ds.n < 64 ? ds.n : 63]);
    }
    for (int r = 0; r < ds.n; r++) {
        fprintf(f, "| %s |", ds.v[r]);
        for (int k = 0; k < cols.n; k++) {
            const ob_tab_sweep *hit = NULL;
            for (int i = 0; i < pl->nsweep && !hit; i++) {
                const ob_tab_sweep *w = &pl->sweep[i];
                char nm[48], dt[24];
                snprintf(nm, sizeof nm, "%s %s (%s)", w->method, w->piece,
                         w->proto == OB_PROTO_PAPER ? "normal" : "hausdorff");
                snprintf(dt, sizeof dt, "%g", w->d);
                if (strcmp(nm, cols.v[k]) == 0 && strcmp(dt, ds.v[r]) == 0)
                    hit = w;
            }
            const ob_job *j = hit ? &pl->slots[hit->slot].job : NULL;
            if (j && (j->status == OB_OK || j->status == OB_LIMIT))
                fprintf(f, " %.3g |", j->max_err);
            else
                fprintf(f, " %s |", j ? ob_status_name(j->status) : "");
        }
        fputc('\n', f);
    }
    fputc('\n', f);
}

int ob_tab_write_md(FILE *f, void *ctx)
{
    const ob_tab_out *t = ctx;
    const ob_tab_plan *pl = t->pl;
    fprintf(f, "# Reproduced tables\n\n"
               "Generated by `./offbench tables` from %s (curves: %s). Each cell: published / ours, "
               "then `=` match, `~` close (within 10 %%), `x` differs; `(limit)`: the job stopped at a "
               "limit before reaching the tolerance. Protocols: **paper** (the paper's own error measure "
               "and split rule), **rigorous** (two-sided Hausdorff distance, dense, midpoint split), "
               "**best** (the same metric, greedy split: the fewest segments a method can reach).\n\n",
            t->pub->where, t->curves_from);
    for (int i = 0; i < t->pub->n; i++) {
        const ob_pub_cell *first = &t->pub->v[i];
        int seen = 0;
        for (int q = 0; q < i && !seen; q++)
            seen = same_table(&t->pub->v[q], first);
        int planned = 0;  /* --table: only the tables asked for */
        for (int q = 0; q < pl->nrows && !planned; q++)
            planned = same_table(pl->rows[q].cell, first);
        if (seen || !planned)
            continue;
        strlist rows = {0}, cols = {0};
        for (int q = i; q < t->pub->n; q++)
            if (same_table(&t->pub->v[q], first)) {
                strlist_add(&rows, row_key(&t->pub->v[q]));
                strlist_add(&cols, t->pub->v[q].label);
            }
        fprintf(f, "## %s, Table %s\n\n", source_title(first->source), first->table);
        fprintf(f, "Curve `%s`%s%s; %s.\n\n", first->curve, first->d_text[0] ? ", d = " : "", first->d_text,
                strcmp(first->unit, "max_err") == 0 ? "figures are errors" : "figures are control points");
        for (int p = 0; p < OB_PROTO_COUNT; p++) {
            int present = 0;
            for (int q = 0; q < pl->nrows && !present; q++)
                present = pl->rows[q].proto == (ob_proto)p && same_table(pl->rows[q].cell, first);
            if (!present)
                continue;
            fprintf(f, "**%s**\n\n", ob_proto_name((ob_proto)p));
            write_notes(f, pl, first, (ob_proto)p, &cols);
            write_grid(f, pl, first, (ob_proto)p, &rows, &cols);
        }
        fputs("Per column, match / close / differs:\n\n", f);
        write_counts(f, pl, first, &cols);
    }
    write_sweep_md(f, pl);
    return ferror(f) ? -1 : 0;
}

int ob_tab_write_sweep(FILE *f, void *ctx)
{
    const ob_tab_out *t = ctx;
    const ob_tab_plan *pl = t->pl;
    fputs("curve,piece,d,method,protocol,metric,max_err,status\n", f);
    for (int i = 0; i < pl->nsweep; i++) {
        const ob_tab_sweep *w = &pl->sweep[i];
        const ob_job *j = &pl->slots[w->slot].job;
        fprintf(f, "zhao2017_quintic,%s,", w->piece);
        put_num(f, w->d);
        fprintf(f, ",%s,%s,%s,", w->method, ob_proto_name(w->proto), ob_metric_name(w->metric));
        put_num(f, j->max_err);
        fprintf(f, ",%s\n", ob_status_name(j->status));
    }
    return ferror(f) ? -1 : 0;
}
