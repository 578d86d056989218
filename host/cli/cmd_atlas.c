/*
 * cmd_atlas.c - ./offbench atlas [--out DIR]: the Offset Atlas of San
 * Segundo, Sendra & Sendra ("Algorithms for offset curves and surfaces", ICM
 * 2006 poster, its table of curves) against our exact offset degrees.
 *
 * The atlas' figures come from results/published/offset_atlas.csv (found like
 * the published tables: $OFFBENCH_ATLAS, ./results/published, beside the
 * program, or the copy compiled in); its rational curves from
 * datasets/atlas.curves (family `atlas`, each curve's source names its atlas
 * row: "Offset Atlas: NAME; ...").  For each atlas row: the degree of the
 * curve (n of its proper parameterization) and of its offset (2n + 2 tau -
 * mu, methods/core/offdeg.h), the offset's degree counted by intersections with
 * random lines at d = 1/8 (an independent check), whether it is rational, and
 * a status: match (both degrees equal the atlas'), differs, or not-covered
 * with the reason.  Writes DIR/atlas.csv (default out/atlas) and prints the
 * table.  Exit 0; 2 on bad options or unreadable data; 1 when the output
 * cannot be written.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/fsutil.h"
#include "methods/core/offdeg.h"
#include "host/cli/commands.h"
#include "host/io/datadir.h"
#include "host/cli/cliopts.h"
#include "host/diag.h"
#include "host/io/output.h"
#include "host/io/slurp.h"

struct ob_embedded_file {
    const char *name;
    const char *text;
};
extern const struct ob_embedded_file ob_embedded_published[];

enum { MAX_ROWS = 256 };

typedef struct {
    char name[96], kind[32];
    int degree, terms, offset_degree, offset_terms;
} atlas_row;

/* Why a row has no exact rational curve here. */
static const struct {
    const char *name, *why;
} not_covered[] = {
    {"x^4 + y^4 - y^2", "not rational (a quartic with a tacnode at the origin: genus 1); the implicit-case formula "
                        "with resultants is not built"},
};

/* Parses the atlas CSV (header name,kind,degree,terms,offset_degree,offset_terms). */
static int parse_atlas(const char *text, const char *name, atlas_row *rows, int *n)
{
    *n = 0;
    int line = 0;
    const char *p = text;
    while (*p) {
        const char *e = strchr(p, '\n');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        char buf[512];
        line++;
        if (len >= sizeof buf) {
            ob_error("%s:%d: line too long", name, line);
            return -1;
        }
        memcpy(buf, p, len);
        buf[len] = '\0';
        if (len && buf[len - 1] == '\r')
            buf[len - 1] = '\0';
        p = e ? e + 1 : p + len;
        if (line == 1) {
            if (strcmp(buf, "name,kind,degree,terms,offset_degree,offset_terms") != 0) {
                ob_error("%s:1: expected the header name,kind,degree,terms,offset_degree,offset_terms", name);
                return -1;
            }
            continue;
        }
        if (!buf[0])
            continue;
        if (*n >= MAX_ROWS) {
            ob_error("%s:%d: more than %d rows", name, line, MAX_ROWS);
            return -1;
        }
        atlas_row *r = &rows[*n];
        char extra;
        if (sscanf(buf, "%95[^,],%31[^,],%d,%d,%d,%d%c", r->name, r->kind, &r->degree, &r->terms,
                   &r->offset_degree, &r->offset_terms, &extra) != 6) {
            ob_error("%s:%d: expected name,kind and four whole numbers", name, line);
            return -1;
        }
        (*n)++;
    }
    return 0;
}

/* The atlas figures, found as the published tables are. */
static int load_atlas(atlas_row *rows, int *n, char *where, size_t wlen)
{
    static const char rel[] = "results/published/offset_atlas.csv";
    char path[4200] = "";
    ob_err err;
    if (ob_find_tree_file(rel, "OFFBENCH_ATLAS", path, sizeof path) != 0)
        path[0] = '\0';
    if (path[0]) {
        char *text;
        size_t len;
        if (ob_slurp(path, &text, &len, &err) != 0) {
            ob_error("%s", err.msg);
            return -1;
        }
        int rc = parse_atlas(text, path, rows, n);
        free(text);
        snprintf(where, wlen, "%s", path);
        return rc;
    }
    for (int i = 0; ob_embedded_published[i].name; i++)
        if (strstr(ob_embedded_published[i].name, "offset_atlas.csv")) {
            snprintf(where, wlen, "embedded copy of %s", ob_embedded_published[i].name);
            return parse_atlas(ob_embedded_published[i].text, ob_embedded_published[i].name, rows, n);
        }
    ob_error("no atlas figures: %s not found and none compiled in", rel);
    return -1;
}

/* The atlas curve whose source names this row, or NULL. */
static const ob_curve *find_curve(const ob_curveset *set, const char *name)
{
    char want[160];
    snprintf(want, sizeof want, "Offset Atlas: %.120s;", name);
    for (int i = 0; i < set->n; i++)
        if (set->v[i].family && strcmp(set->v[i].family, "atlas") == 0 && set->v[i].source &&
            strncmp(set->v[i].source, want, strlen(want)) == 0)
            return &set->v[i];
    return NULL;
}

typedef struct {
    const atlas_row *r;
    int covered, degree, offset_degree, rational;
    long lines;
    const char *status;
    char note[320];
} atlas_out;

typedef struct {
    const atlas_out *v;
    int n;
} atlas_tab;

static int write_csv(FILE *f, void *ctx)
{
    const atlas_tab *t = ctx;
    fprintf(f, "name,kind,degree,offset_degree,atlas_degree,atlas_offset_degree,lines_degree,offset_rational,"
               "atlas_terms,atlas_offset_terms,status,note\n");
    for (int i = 0; i < t->n; i++) {
        const atlas_out *o = &t->v[i];
        ob_csv_field(f, o->r->name);
        fprintf(f, ",%s,", o->r->kind);
        if (o->covered)
            fprintf(f, "%d,%d,", o->degree, o->offset_degree);
        else
            fprintf(f, ",,");
        fprintf(f, "%d,%d,", o->r->degree, o->r->offset_degree);
        if (o->covered)
            fprintf(f, "%ld,%s,", o->lines, o->rational ? "yes" : "no");
        else
            fprintf(f, ",,");
        fprintf(f, "%d,%d,%s,", o->r->terms, o->r->offset_terms, o->status);
        ob_csv_field(f, o->note);
        fputc('\n', f);
    }
    return ferror(f) ? -1 : 0;
}

static const ob_flag out_flag[] = {{"out", "DIR", "output directory (default out/atlas)", 0, OB_FLAG_ONCE}};

int ob_cmd_atlas(int argc, char **argv)
{
    const char *out = "out/atlas";
    const ob_flagset flags = {out_flag, 1, NULL, NULL, "options", ob_cli_apply_dir, &out};
    const int prc = ob_cli_parse("[--out DIR]   (the Offset Atlas: exact offset degrees)", &flags, 1, argc, argv, 0,
                                 NULL, NULL);
    if (prc != OB_CLI_OK)
        return prc == OB_CLI_HELP ? 0 : 2;
    atlas_row rows[MAX_ROWS];
    atlas_out res[MAX_ROWS];
    int n = 0, status = 2;
    char where[4200], cwhere[4096];
    ob_err cerr;
    ob_curveset set = {0};
    if (load_atlas(rows, &n, where, sizeof where) != 0)
        goto done;
    if (ob_load_default_curves(&set, cwhere, sizeof cwhere, &cerr) != 0) {
        ob_error("%s", cerr.msg);
        goto done;
    }
    int cnt[3] = {0};
    for (int i = 0; i < n; i++) {
        atlas_out *o = &res[i];
        memset(o, 0, sizeof *o);
        o->r = &rows[i];
        const ob_curve *c = strcmp(rows[i].kind, "curve") == 0 ? find_curve(&set, rows[i].name) : NULL;
        if (!c) {
            o->status = "not-covered";
            if (strcmp(rows[i].kind, "curve") != 0)
                snprintf(o->note, sizeof o->note, "a %s: the degree formula is for plane curves", rows[i].kind);
            else {
                snprintf(o->note, sizeof o->note, "no exact rational curve for it in datasets/atlas.curves");
                for (size_t k = 0; k < sizeof not_covered / sizeof not_covered[0]; k++)
                    if (strcmp(not_covered[k].name, rows[i].name) == 0)
                        snprintf(o->note, sizeof o->note, "%s", not_covered[k].why);
            }
            cnt[2]++;
            continue;
        }
        ob_offdeg od;
        char msg[160];
        if (c->nseg != 1 || ob_offset_degree(&c->seg[0], &od, msg, sizeof msg) != 0) {
            o->status = "not-covered";
            snprintf(o->note, sizeof o->note, "%s: %s", c->id, c->nseg != 1 ? "not one Bezier segment" : msg);
            cnt[2]++;
            continue;
        }
        o->covered = 1;
        o->degree = od.degree;
        o->offset_degree = od.offset_degree;
        o->rational = od.rational;
        o->lines = ob_offset_degree_by_lines(&c->seg[0], 1, 8, 1);
        const int same = od.degree == rows[i].degree && od.offset_degree == rows[i].offset_degree;
        o->status = same ? "match" : "differs";
        snprintf(o->note, sizeof o->note, "%s (n %d, tau %d, mu %d)%s", c->id, od.degree, od.tau, od.mu,
                 o->lines != od.offset_degree ? "; the line count disagrees" : "");
        cnt[same ? 0 : 1]++;
    }
    if (ob_mkdir_p(out) != 0) {
        ob_error("atlas: --out: cannot create '%s': %s", out, strerror(errno));
        status = 1;
        goto done;
    }
    atlas_tab t = {res, n};
    if (ob_write_atomically(out, "atlas.csv", write_csv, &t) != 0) {
        status = 1;
        goto done;
    }
    printf("Offset Atlas (San Segundo & Sendra, ICM 2006) from %s; curves from %s\n", where, cwhere);
    printf("exact arithmetic (FLINT) on the curves' exact rational control points; offset degree 2n + 2tau - mu\n\n");
    printf("%-28s %-8s %6s %6s %8s %8s %6s %5s  %s\n", "name", "kind", "deg", "atlas", "off.deg", "atlas", "lines",
           "rat.", "status");
    for (int i = 0; i < n; i++) {
        const atlas_out *o = &res[i];
        char d[16] = "-", od[16] = "-", li[16] = "-";
        if (o->covered) {
            snprintf(d, sizeof d, "%d", o->degree);
            snprintf(od, sizeof od, "%d", o->offset_degree);
            snprintf(li, sizeof li, "%ld", o->lines);
        }
        printf("%-28s %-8s %6s %6d %8s %8d %6s %5s  %s%s%s\n", o->r->name, o->r->kind, d, o->r->degree, od,
               o->r->offset_degree, li, o->covered ? (o->rational ? "yes" : "no") : "-", o->status,
               o->covered ? "" : ": ", o->covered ? "" : o->note);
    }
    printf("\n%d match, %d differ, %d not covered; wrote %s/atlas.csv\n", cnt[0], cnt[1], cnt[2], out);
    status = 0;
done:
    ob_curveset_free(&set);
    return status;
}
