/*
 * perpiece_csv.c - the --per-piece CSV (perpiece.h): one row per piece of
 * each file, in the files' order and the file's own piece order.
 */
#include "host/measure/perpiece.h"

#include <math.h>

#include "host/diag.h"
#include "host/io/numfmt.h"
#include "host/io/outfile.h"
#include "host/io/output.h"

const char ob_perpiece_header[] =
    "file,piece,entity,handle,id,line,degree,seg0,t0,seg1,t1,max_err,seg,t,x,y,x_off,y_off";

/* ",X": a number in results.csv's form; empty when it is not finite and
 * blank is set. */
static void num(FILE *f, double x, int blank)
{
    char b[40] = "";
    if (isfinite(x) || !blank)
        ob_fmt_double(b, sizeof b, x);
    fprintf(f, ",%s", b);
}

static void text(FILE *f, const char *s)
{
    fputc(',', f);
    ob_csv_field(f, s);
}

static void row(FILE *f, const char *name, const ob_approx *a, const ob_pp_row *r)
{
    const ob_apiece *p0 = &a->v[r->first], *p1 = &a->v[r->last];
    ob_csv_field(f, name);
    fprintf(f, ",%d", r->piece);
    text(f, p0->entity);
    text(f, p0->handle);
    text(f, p0->id);
    fprintf(f, ",%d,%d,%d", p0->line, p0->approx.deg, p0->seg);
    num(f, ob_apiece_base_t(p0, 0.0), 0);
    fprintf(f, ",%d", p1->seg);
    num(f, ob_apiece_base_t(p1, 1.0), 0);
    num(f, r->err, 0);
    fprintf(f, ",%d", r->seg);
    num(f, r->t, 1);
    num(f, r->x, 1);
    num(f, r->y, 1);
    num(f, r->xo, 1);
    num(f, r->yo, 1);
    fputc('\n', f);
}

int ob_perpiece_csv(FILE *f, const ob_pp_file *files, int n)
{
    fprintf(f, "%s\n", ob_perpiece_header);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < files[i].pp->n; k++)
            row(f, files[i].name, files[i].ap, &files[i].pp->v[k]);
    return ferror(f) ? -1 : 0;
}

int ob_pp_write(const char *opt, const char *path, int (*writer)(FILE *, const void *), const void *ctx)
{
    ob_outfile of = {0};
    ob_err err;
    if (ob_outfile_open(&of, path, 0, &err) != 0) {
        ob_error("%s: %s", opt, err.msg);
        return 1;
    }
    if (writer(of.f, ctx) != 0) {
        ob_error("%s: writing '%s' failed", opt, path);
        ob_outfile_discard(&of);
        return 1;
    }
    if (ob_outfile_commit(&of, 0, &err) != 0) {
        ob_error("%s: %s", opt, err.msg);
        ob_outfile_discard(&of);
        return 1;
    }
    return 0;
}
