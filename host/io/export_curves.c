/*
 * export_curves.c - a job's approximation as a `.curves` file (export.h),
 * read by offbench's own reader (host/io/curvefile.c): one `curve` block per
 * piece, its control points as `hpoint WX WY W` (the homogeneous values
 * themselves, so the file holds the pieces exactly), its `offset` the
 * job's d (the format needs one; `measure` takes d from --d).
 *
 * The `source` line of each block says which base piece it approximates, in
 * a fixed form that measure reads (approx_read.c):
 *   source offbench export: KEY; piece K of N; base segment S span A B fit T0 T1; same_param yes|no
 * (approx.h: the driver's span [A, B] of segment S, cut to [T0, T1]).
 */
#include "host/io/export.h"

#include "host/io/numfmt.h"

int ob_export_write_curves(FILE *f, const ob_job *j, const ob_approx *a)
{
    char stem[400], err[40];
    ob_export_stem(stem, sizeof stem, j);
    ob_fmt_double(err, sizeof err, j->max_err);
    fprintf(f, "# offbench export: the approximation of job %s\n", stem);
    fprintf(f, "# status %s, max_err %s (metric %s), %d pieces, %ld control points\n", ob_status_name(j->status),
            err, ob_metric_name(j->metric), a->n, j->ctrl_points);
    for (int i = 0; i < a->n; i++)
        for (int k = 0; k <= a->v[i].approx.deg; k++)
            if (!(a->v[i].approx.h[k][2] > 0)) {
                fprintf(f, "# note: piece %d has a weight <= 0, which the .curves format refuses (W > 0):\n"
                        "# this file does not read back; the .json and .dxf files hold every piece\n", i);
                break;
            }
    for (int i = 0; i < a->n; i++) {
        const ob_apiece *p = &a->v[i];
        fprintf(f, "curve %s.p%04d\n  source offbench export: %s; piece %d of %d; base segment %d ",
                j->method->name, i, stem, i, a->n, p->seg);
        ob_export_span(f, p);
        fprintf(f, "; same_param %s\n  family export\n  bezier %d\n", a->same_param ? "yes" : "no",
                p->approx.deg);
        for (int k = 0; k <= p->approx.deg; k++) {
            fputs("  hpoint", f);
            for (int c = 0; c < 3; c++) {
                fputc(' ', f);
                ob_export_num(f, p->approx.h[k][c], 0);
            }
            fputc('\n', f);
        }
        fputs("  offset ", f);
        ob_export_num(f, j->d, 0);
        fputs("\nend\n", f);
    }
    return ferror(f) ? -1 : 0;
}
