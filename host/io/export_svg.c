/*
 * export_svg.c - a job's approximation as SVG paths (export.h), in the base
 * curve's coordinates (a y-up flip in a transform, the path data itself
 * untouched).  Polynomial pieces of degree 1, 2 and 3 are native path
 * commands (L, Q, C: the control points themselves); SVG has no command
 * for a rational or a higher-degree Bézier, so those are polylines of 64
 * chords through points of the piece (class "sampled").  One <path> per
 * piece, with data-piece and data-seg attributes.
 */
#include "host/io/export.h"

#include <math.h>

#include "host/view/svg.h"

enum { CHORDS = 64 };

static void pt(FILE *f, const double p[2])
{
    fputc(' ', f);
    ob_export_num(f, p[0], 0);
    fputc(' ', f);
    ob_export_num(f, p[1], 0);
}

static void path(FILE *f, const ob_apiece *p, int k)
{
    const ob_bez *b = &p->approx;
    const int native = !b->rational && b->deg >= 1 && b->deg <= 3;
    fprintf(f, "<path vector-effect=\"non-scaling-stroke\" class=\"%s\" data-piece=\"%d\" data-seg=\"%d\" d=\"M",
            native ? "native" : "sampled", k, p->seg);
    double q[2];
    ob_bez_ctrl(b, 0, q);
    pt(f, q);
    if (native) {
        fputs(b->deg == 1 ? " L" : b->deg == 2 ? " Q" : " C", f);
        for (int i = 1; i <= b->deg; i++) {
            ob_bez_ctrl(b, i, q);
            pt(f, q);
        }
    } else {
        fputs(" L", f);
        for (int i = 1; i <= CHORDS; i++) {
            ob_bez_point(b, (double)i / CHORDS, q);
            pt(f, q);
        }
    }
    fputs("\"/>\n", f);
}

int ob_export_write_svg(FILE *f, const ob_job *j, const ob_approx *a)
{
    ob_bbox bb;
    ob_bbox_init(&bb);
    for (int i = 0; i < a->n; i++)
        for (int k = 0; k <= a->v[i].approx.deg; k++) {
            double q[2];
            ob_bez_ctrl(&a->v[i].approx, k, q);
            if (isfinite(q[0]) && isfinite(q[1]))
                ob_bbox_add(&bb, q[0], q[1]);
        }
    double s = ob_bbox_size(&bb);
    s = s > 0 && isfinite(s) ? s : 1.0;
    ob_bbox_grow(&bb, 0.05 * s);
    char stem[400];
    ob_export_stem(stem, sizeof stem, j);
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"", f);
    ob_export_num(f, bb.xmin, 0);  /* y up: the flip below maps [ymin, ymax] to [-ymax, -ymin] */
    const double rest[3] = {-bb.ymax, bb.xmax - bb.xmin, bb.ymax - bb.ymin};
    for (int i = 0; i < 3; i++) {
        fputc(' ', f);
        ob_export_num(f, rest[i], 0);
    }
    fputs("\" width=\"800\">\n<title>offbench export: ", f);
    ob_svg_put_text(f, stem);
    fputs("</title>\n<g transform=\"scale(1,-1)\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"2\">\n", f);
    for (int i = 0; i < a->n; i++)
        path(f, &a->v[i], i);
    fputs("</g>\n</svg>\n", f);
    return ferror(f) ? -1 : 0;
}
