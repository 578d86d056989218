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
          "job_status,note,err_upper,err_lower,certified\n",
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
            if (j->cert_done == OB_CERT_DONE) {  /* tables --certify (host/run/certify.h); timed out: empty */
                fputc(',', f);
                put_num(f, j->err_upper);
                fputc(',', f);
                put_num(f, j->err_lower);
                fprintf(f, ",%s", ob_job_certified(j) ? "yes" : "no");
            } else {
                fputs(",,,", f);
            }
        } else {
            fputs(",,,,", f);
            ob_csv_field(f, r->fixed[3] == 'm' ? "offbench has no such method" : "the paper does not print the curve's data");
            fputs(",,,", f);
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

/* --certify: an ok job's certificate as its cell shows it: " (err_upper)"
 * rounded up, " (err_upper !)" over tol, " (no verdict)" timed out; ""
 * for none. */
static void cert_note(char *buf, size_t len, const ob_job *j)
{
    if (!j || j->status != OB_OK || !j->cert_done)
        return;
    if (j->cert_done != OB_CERT_DONE) {
        snprintf(buf, len, " (no verdict)");
        return;
    }
    char up[40];
    ob_fmt_bound(up, sizeof up, j->err_upper, 1);
    snprintf(buf, len, " (%s%s)", up, ob_job_certified(j) ? "" : " !");
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
            char cert[64] = "";
            cert_note(cert, sizeof cert, j);
            fprintf(f, " %s / %s%s%s%s |", hit->cell->value_text, st >= OB_TAB_NO_METHOD ? ob_tab_status_names[st] : b,
                    flag, cert, mark(st));
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

/* The sweep job of (method, piece, metric, d), or NULL. */
static const ob_job *sweep_job(const ob_tab_plan *pl, const char *method, const char *piece, ob_metric metric,
                               const char *variant, double d)
{
    for (int i = 0; i < pl->nsweep; i++) {
        const ob_tab_sweep *w = &pl->sweep[i];
        if (w->metric == metric && w->d == d && strcmp(w->method, method) == 0 && strcmp(w->piece, piece) == 0 &&
            strcmp(w->variant, variant) == 0)
            return &pl->slots[w->slot].job;
    }
    return NULL;
}

static int sweep_ok(const ob_job *j) { return j && (j->status == OB_OK || j->status == OB_LIMIT); }

/* The distinct values of the sweep, in plan order: radii (what = 0) or cut
 * points of the C1@X pieces (what = 1, 0.5 for plain C1). */
static int sweep_values(const ob_tab_plan *pl, int what, double *v, int cap)
{
    int n = 0;
    for (int i = 0; i < pl->nsweep; i++) {
        const ob_tab_sweep *w = &pl->sweep[i];
        double x = w->d;
        if (what) {
            if (strncmp(w->piece, "C1", 2) != 0)
                continue;
            x = w->piece[2] == '@' ? atof(w->piece + 3) : 0.5;
        }
        int seen = 0;
        for (int k = 0; k < n && !seen; k++)
            seen = v[k] == x;
        if (!seen && n < cap)
            v[n++] = x;
    }
    return n;
}

/* One table per metric (and variant): the halves at t = 1/2, by radius. */
static void write_sweep_radius(FILE *f, const ob_tab_plan *pl, ob_metric metric, const char *variant,
                               const char *what)
{
    static const char *methods[2] = {"lee", "zhao-rational"}, *pieces[3] = {"C", "C1", "C2"};
    double ds[64];
    const int nd = sweep_values(pl, 0, ds, 64);
    int any = 0;
    for (int r = 0; r < nd && !any; r++)
        any = sweep_job(pl, "zhao-rational", "C", metric, variant, ds[r]) != NULL;
    if (!any)
        return;
    fprintf(f, "`%s`%s%s (%s):\n\n| d |", ob_metric_name(metric), variant[0] ? ", " : "", variant, what);
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 3; k++)
            fprintf(f, " %s %s |", methods[m], pieces[k]);
    fputs("\n|---|---|---|---|---|---|---|\n", f);
    for (int r = 0; r < nd; r++) {
        fprintf(f, "| %g |", ds[r]);
        for (int m = 0; m < 2; m++)
            for (int k = 0; k < 3; k++) {
                const ob_job *j = sweep_job(pl, methods[m], pieces[k], metric, variant, ds[r]);
                if (sweep_ok(j))
                    fprintf(f, " %.3g |", j->max_err);
                else
                    fprintf(f, " %s |", j ? ob_status_name(j->status) : "");
            }
        fputc('\n', f);
    }
    fputc('\n', f);
}

/* Under the paper's metric, per method: C1 and C2 as ratios ours / published
 * for every cut point (rows) and radius (columns); ** where both are within
 * 10 %. */
static void write_sweep_cuts(FILE *f, const ob_tab_plan *pl, ob_metric metric, const char *method, double pub1,
                             double pub2)
{
    double ds[64], cuts[64];
    const int nd = sweep_values(pl, 0, ds, 64), nc = sweep_values(pl, 1, cuts, 64);
    if (nc < 2)
        return;
    fprintf(f, "`%s`, %s: C1 / published %g, C2 / published %g, by cut point (rows) and d (columns)\n\n| cut |",
            ob_metric_name(metric), method, pub1, pub2);
    for (int r = 0; r < nd; r++)
        fprintf(f, " %g |", ds[r]);
    fputs("\n|---|", f);
    for (int r = 0; r < nd; r++)
        fputs("---|", f);
    fputc('\n', f);
    for (int c = 0; c < nc; c++) {
        char p1[24], p2[24];
        if (cuts[c] == 0.5) {
            snprintf(p1, sizeof p1, "C1");
            snprintf(p2, sizeof p2, "C2");
        } else {
            snprintf(p1, sizeof p1, "C1@%g", cuts[c]);
            snprintf(p2, sizeof p2, "C2@%g", cuts[c]);
        }
        fprintf(f, "| %g |", cuts[c]);
        for (int r = 0; r < nd; r++) {
            const ob_job *a = sweep_job(pl, method, p1, metric, "", ds[r]);
            const ob_job *b = sweep_job(pl, method, p2, metric, "", ds[r]);
            if (!sweep_ok(a) || !sweep_ok(b)) {
                fprintf(f, " %s |", !sweep_ok(a) ? (a ? ob_status_name(a->status) : "") : ob_status_name(b->status));
                continue;
            }
            const double r1 = a->max_err / pub1, r2 = b->max_err / pub2;
            const int both = fabs(r1 - 1.0) <= 0.1 && fabs(r2 - 1.0) <= 0.1;
            fprintf(f, " %s%.2g / %.2g%s |", both ? "**" : "", r1, r2, both ? "**" : "");
        }
        fputc('\n', f);
    }
    fputc('\n', f);
}

static void write_sweep_md(FILE *f, const ob_tab_plan *pl)
{
    if (pl->nsweep == 0)
        return;
    fputs("## Zhao & Zhou 2017, Table 1: the quintic's radius and cut point\n\n"
          "The radius of the quintic example is not published, nor where it was cut into C1 and C2. Errors of "
          "one fit per piece (C: the whole curve; C1, C2: its halves at t = 1/2) for a range of d, under the "
          "paper's error at the given parameter (`param`, the paper protocol), the normal-line error (`normal`, "
          "the reading before) and the Hausdorff distance (rigorous); then, under `param`, C1 and C2 cut at other "
          "points, as ratios to the published figures. Published: Lee's 1.24 / 0.0443 / 0.0256, Our Algorithm "
          "0.0033 / 2.9199e-5 / 4.9096e-5. Every figure is in zhao_sweep.csv.\n\n",
          f);
    write_sweep_radius(f, pl, OB_METRIC_PARAM, "", "paper");
    write_sweep_radius(f, pl, OB_METRIC_NORMAL, "", "the paper protocol's reading before");
    write_sweep_radius(f, pl, OB_METRIC_HAUSDORFF, "", "rigorous");
    write_sweep_radius(f, pl, OB_METRIC_PARAM, "zhao-rational.weighted=0",
                       "paper, with the unweighted solves of the paper's steps as written: tried, not adopted");
    write_sweep_cuts(f, pl, OB_METRIC_PARAM, "zhao-rational", 2.9199e-5, 4.9096e-5);
    write_sweep_cuts(f, pl, OB_METRIC_PARAM, "lee", 0.0443, 0.0256);
}

/* tables --certify: the ok cells whose certificate does not hold them
 * within tol (nothing when there is none). */
static void write_cert_misses(FILE *f, const ob_tab_plan *pl)
{
    int any = 0;
    for (int q = 0; q < pl->nrows; q++) {
        const ob_tab_row *r = &pl->rows[q];
        const ob_job *j = r->slot >= 0 ? &pl->slots[r->slot].job : NULL;
        if (!j || j->status != OB_OK || !j->cert_done || ob_job_certified(j))
            continue;
        if (!any++)
            fputs("Not certified within tol (ok cells):\n\n"
                  "| source | table | column | row | protocol | ours | err_upper | err_lower | why |\n"
                  "|---|---|---|---|---|---|---|---|---|\n", f);
        char up[40] = "", lo[40] = "", ours[40];
        const char *why = "timed out";
        if (j->cert_done == OB_CERT_DONE) {
            ob_fmt_bound(up, sizeof up, j->err_upper, 1);
            ob_fmt_bound(lo, sizeof lo, j->err_lower, -1);
            why = isinf(j->err_upper) ? "unbounded" : "over tol";
        }
        if (strcmp(r->cell->unit, "max_err") == 0)
            snprintf(ours, sizeof ours, "%.3g", j->max_err);
        else
            snprintf(ours, sizeof ours, "%ld", j->ctrl_points);
        fprintf(f, "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r->cell->source, r->cell->table, r->cell->label,
                row_key(r->cell), ob_proto_name(r->proto), ours, up, lo, why);
    }
    if (any)
        fputc('\n', f);
}

/* tables --certify: per protocol, the ok jobs whose certified two-sided
 * Hausdorff distance is within tol (nothing without certificates). */
static void write_cert_md(FILE *f, const ob_tab_plan *pl)
{
    int yes[OB_PROTO_COUNT] = {0}, n[OB_PROTO_COUNT] = {0}, any = 0;
    for (int q = 0; q < pl->nrows; q++) {
        const ob_tab_row *r = &pl->rows[q];
        const ob_job *j = r->slot >= 0 ? &pl->slots[r->slot].job : NULL;
        if (!j || j->status != OB_OK || !j->cert_done)
            continue;
        n[r->proto]++;
        yes[r->proto] += ob_job_certified(j);
        any = 1;
    }
    if (!any)
        return;
    fputs("Certified (`--certify`, docs/certified.md): of the cells whose job is ok, those whose certified "
          "two-sided Hausdorff distance to the exact offset (err_upper in tables.csv) is within the tolerance:", f);
    for (int p = 0; p < OB_PROTO_COUNT; p++)
        fprintf(f, "%s %s %d of %d", p ? "," : "", ob_proto_name((ob_proto)p), yes[p], n[p]);
    fputs(". Beside ours, a cell whose job is ok shows its certified err_upper (rounded up: still a bound); "
          "`!` marks one that is ok under its protocol's measure but not within tol by the certified "
          "distance (a paper's radial or symbolic measure is not the distance to the offset; or the enclosure "
          "straddles tol); `no verdict`: its certificate passed --job-timeout.\n\n", f);
    write_cert_misses(f, pl);
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
               "**best** (the same metric, the `optimal` split: the fewest pieces a method can reach, their "
               "errors equalized).\n\n",
            t->pub->where, t->curves_from);
    write_cert_md(f, pl);
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
    fputs("curve,piece,d,method,protocol,metric,max_err,status,variant\n", f);
    for (int i = 0; i < pl->nsweep; i++) {
        const ob_tab_sweep *w = &pl->sweep[i];
        const ob_job *j = &pl->slots[w->slot].job;
        fprintf(f, "zhao2017_quintic,%s,", w->piece);
        put_num(f, w->d);
        fprintf(f, ",%s,%s,%s,", w->method, ob_proto_name(w->proto), ob_metric_name(w->metric));
        put_num(f, j->max_err);
        fprintf(f, ",%s,%s\n", ob_status_name(j->status), w->variant);
    }
    return ferror(f) ? -1 : 0;
}
