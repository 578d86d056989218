/*
 * draw_approx.c - the picture of a file's approximation and its errors
 * (draw_approx.h), written with host/view/svg.h.
 */
#include "host/view/draw_approx.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "host/view/svg.h"

enum { BASE_PTS = 200, OFFSET_PTS = 800, PIECE_PTS = 64, LEGEND_STEPS = 6, PICTURE_W = 800 };

/* World (x, y) to the picture: k (x - x0, y0 - y), y up; k makes the
 * drawing PICTURE_W units wide, as draw's figures (renderers draw text
 * badly at font sizes far below 1, which the curve's own units would need). */
typedef struct {
    double k, x0, y0;
} frame;

static double fx(const frame *w, double x) { return w->k * (x - w->x0); }
static double fy(const frame *w, double y) { return w->k * (w->y0 - y); }

static const char CSS[] =
    "text{font-family:sans-serif;fill:#222}\n"
    ".base{fill:none;stroke:#999;stroke-width:1;stroke-dasharray:4 3;vector-effect:non-scaling-stroke}\n"
    ".offset{fill:none;stroke:#000;stroke-width:0.8;vector-effect:non-scaling-stroke}\n"
    ".piece{fill:none;stroke-width:4;stroke-opacity:0.8;vector-effect:non-scaling-stroke}\n"
    ".wpt{fill:#000}\n"
    ".worst .ring{fill:none;stroke:#d00;stroke-width:2;vector-effect:non-scaling-stroke}\n"
    ".worst .gap{stroke:#d00;stroke-width:1.5;vector-effect:non-scaling-stroke}\n"
    ".legend .swatch{stroke:#444;stroke-width:0.5;vector-effect:non-scaling-stroke}\n";

/* The colour scale: blue (the smallest error) to red (the largest). */
static const double STOPS[5][3] = {
    {44, 123, 182}, {0, 166, 202}, {144, 235, 157}, {249, 208, 87}, {215, 25, 28},
};

/* The colour of error e on the log scale [lo, hi] as "#rrggbb"; magenta
 * for an error that is not finite. */
static void colour(double e, double lo, double hi, char out[8])
{
    if (!isfinite(e)) {
        snprintf(out, 8, "#ff00ff");
        return;
    }
    double u = e > 0.0 ? (log10(e) - log10(lo)) / (log10(hi) - log10(lo)) : 0.0;
    u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
    const int i = u >= 1.0 ? 3 : (int)(u * 4.0);
    const double s = u * 4.0 - i;
    int rgb[3];
    for (int k = 0; k < 3; k++)
        rgb[k] = (int)lround(STOPS[i][k] + s * (STOPS[i + 1][k] - STOPS[i][k]));
    snprintf(out, 8, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
}

/* The scale's ends: the smallest and largest finite positive errors (lo =
 * hi / 10 when they are equal, so that one error still has a scale): the
 * colours spread over the errors there are, the legend says how far. */
static void scale(const ob_draw_approx *v, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = 0.0;
    for (int i = 0; i < v->n; i++)
        for (int k = 0; k < v->files[i].pp->n; k++) {
            const double e = v->files[i].pp->v[k].err;
            if (isfinite(e) && e > 0.0)
                *lo = fmin(*lo, e), *hi = fmax(*hi, e);
        }
    if (!(*hi > 0.0))
        *hi = 1e-15;
    if (!(*lo < *hi))
        *lo = *hi / 10.0;
}

/* The box of the base, the offset and the pieces. */
static ob_bbox extent(const ob_draw_approx *v)
{
    ob_bbox b;
    ob_bbox_init(&b);
    double p[2];
    for (int s = 0; s < v->c->nseg; s++)
        for (int k = 0; k <= BASE_PTS; k++) {
            ob_bez_point(&v->c->seg[s], (double)k / BASE_PTS, p);
            ob_bbox_add(&b, p[0], p[1]);
            ob_bez_offset_point(&v->c->seg[s], (double)k / BASE_PTS, v->d, p);
            ob_bbox_add(&b, p[0], p[1]);
        }
    for (int i = 0; i < v->n; i++)
        for (int k = 0; k < v->files[i].ap->n; k++)
            for (int j = 0; j <= PIECE_PTS; j++) {
                ob_bez_point(&v->files[i].ap->v[k].approx, (double)j / PIECE_PTS, p);
                ob_bbox_add(&b, p[0], p[1]);
            }
    if (b.empty)
        ob_bbox_add(&b, 0.0, 0.0);
    ob_bbox_aspect(&b, 0.5, 0.5, 1.0);
    return b;
}

/* One curve as a polyline of n + 1 points, y flipped (offset: its d-offset). */
static int curve_line(FILE *f, const frame *w, const char *cls, const ob_bez *b, int offset, double d, int n)
{
    double(*xy)[2] = malloc((size_t)(n + 1) * sizeof *xy);
    if (!xy)
        return -1;
    for (int k = 0; k <= n; k++) {
        if (offset)
            ob_bez_offset_point(b, (double)k / n, d, xy[k]);
        else
            ob_bez_point(b, (double)k / n, xy[k]);
        xy[k][0] = fx(w, xy[k][0]);
        xy[k][1] = fy(w, xy[k][1]);
    }
    ob_svg_polyline(f, cls, (const double(*)[2])xy, n + 1);
    free(xy);
    return 0;
}

/* One file piece (all its parts) as a <path>, in its error's colour. */
static void piece_path(FILE *f, const frame *w, int file, const ob_approx *a, const ob_pp_row *r, double lo, double hi)
{
    char col[8], es[40];
    colour(r->err, lo, hi, col);
    ob_fmt_double(es, sizeof es, r->err);
    fprintf(f, "<path class=\"piece\" data-file=\"%d\" data-piece=\"%d\" data-err=\"%s\" stroke=\"%s\" d=\"", file,
            r->piece, es, col);
    for (int k = r->first; k <= r->last; k++)
        for (int j = 0; j <= PIECE_PTS; j++) {
            double p[2];
            ob_bez_point(&a->v[k].approx, (double)j / PIECE_PTS, p);
            fprintf(f, "%s%.7g %.7g", j == 0 ? (k == r->first ? "M" : " M") : " L", fx(w, p[0]), fy(w, p[1]));
        }
    fputs("\"/>\n", f);
}

/* The worst piece of file i: a ring, the gap to the offset, a label. */
static void worst_mark(FILE *f, const frame *fr, int i, const ob_pp_file *pf)
{
    const ob_pp_row *w = NULL;
    const double size = PICTURE_W;
    for (int k = 0; k < pf->pp->n; k++)
        if (!w || !(pf->pp->v[k].err <= w->err))
            w = &pf->pp->v[k];
    if (!w || !isfinite(w->x))
        return;
    char es[40], label[160];
    ob_fmt_double(es, sizeof es, w->err);
    fprintf(f, "<g class=\"worst\" data-file=\"%d\" data-piece=\"%d\" data-err=\"%s\">\n", i, w->piece, es);
    const double x = fx(fr, w->x), y = fy(fr, w->y);
    ob_svg_line(f, "gap", x, y, fx(fr, w->xo), fy(fr, w->yo));
    ob_svg_circle(f, "ring", x, y, 0.015 * size);
    snprintf(label, sizeof label, "piece %d: %.3g", w->piece, w->err);
    ob_svg_text(f, "label", x + 0.02 * size, y - 0.02 * size, 0.02 * size, "start", label);
    ob_svg_group_end(f);
}

/* The legend at (x, y) (top left, picture coordinates): value -> colour. */
static void legend(FILE *f, double x, double y, double lo, double hi)
{
    const double fs = 14.0, h = 24.0;
    ob_svg_group(f, "legend", NULL);
    ob_svg_text(f, "caption", x, y, fs, "start", "piece error (hausdorff), log scale");
    for (int k = 0; k < LEGEND_STEPS; k++) {
        const double e = pow(10.0, log10(hi) - k * (log10(hi) - log10(lo)) / (LEGEND_STEPS - 1));
        char col[8], label[40];
        colour(e, lo, hi, col);
        snprintf(label, sizeof label, "%.3g", e);
        fprintf(f, "<rect class=\"swatch\" x=\"%.6g\" y=\"%.6g\" width=\"%.6g\" height=\"%.6g\" fill=\"%s\"/>\n", x,
                y + 0.5 * fs + k * h, h, h, col);
        ob_svg_text(f, "value", x + 1.3 * h, y + 0.5 * fs + k * h + 0.7 * h, fs, "start", label);
    }
    ob_svg_group_end(f);
}

/* The title: the files, the curve, d, and the frame. */
static void title(const ob_draw_approx *v, char *buf, size_t len)
{
    char ds[40];
    ob_fmt_double(ds, sizeof ds, v->d);
    size_t n = (size_t)snprintf(buf, len, "%s", v->files[0].name);
    for (int i = 1; i < v->n && n < len; i++)
        n += (size_t)snprintf(buf + n, len - n, ", %s", v->files[i].name);
    if (n < len)
        snprintf(buf + n, len - n, " against the d = %s offset of curve %s (base coordinates)", ds, v->c->id);
}

int ob_draw_approx_svg(FILE *f, const void *ctx)
{
    const ob_draw_approx *v = ctx;
    const ob_bbox b = extent(v);
    const frame w = {PICTURE_W / (b.xmax - b.xmin), b.xmin, b.ymax};
    const double m = 40.0, top = 40.0, lw = 260.0, H = fy(&w, b.ymin);
    double lo, hi;
    scale(v, &lo, &hi);
    char t[2048];
    title(v, t, sizeof t);
    ob_svg_begin(f, -m, -m - top, PICTURE_W + 2 * m + lw, H + 2 * m + top, PICTURE_W + 2 * m + lw, t, CSS);
    ob_svg_text(f, "title", 0, -m - top + 24.0, 14.0, "start", t);
    int rc = 0;
    for (int s = 0; s < v->c->nseg && rc == 0; s++)
        rc = curve_line(f, &w, "base", &v->c->seg[s], 0, v->d, BASE_PTS) ||
             curve_line(f, &w, "offset", &v->c->seg[s], 1, v->d, OFFSET_PTS);
    for (int i = 0; i < v->n; i++)
        for (int k = 0; k < v->files[i].pp->n; k++)
            piece_path(f, &w, i, v->files[i].ap, &v->files[i].pp->v[k], lo, hi);
    for (int i = 0; i < v->n; i++)
        for (int k = 0; k < v->files[i].pp->n; k++)
            if (isfinite(v->files[i].pp->v[k].x))
                ob_svg_circle(f, "wpt", fx(&w, v->files[i].pp->v[k].x), fy(&w, v->files[i].pp->v[k].y), 3.0);
    for (int i = 0; i < v->n; i++)
        worst_mark(f, &w, i, &v->files[i]);
    legend(f, PICTURE_W + m, 0.0, lo, hi);
    ob_svg_end(f);
    return rc || ferror(f) ? -1 : 0;
}
