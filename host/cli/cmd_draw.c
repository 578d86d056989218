/*
 * cmd_draw.c - `./offbench draw` and `./offbench trace`: one job shown.
 *
 *   draw  --curve ID --method M --tol T [--d D] [run options] --out FILE.svg
 *   trace --curve ID --method M --tol T [--d D] [run options] [--points N] [--out FILE.csv]
 *
 * Both have their own options --method, --tol, --d, --out (and trace
 * --points) and take the run options (cliopts.h: one parser, run's flag
 * table) but those that select many jobs or write a run directory, so every
 * run option (--curves, --random, --metric, --split, --samples, --param,
 * --backend, ...) means what it means for run and the job gets the figures
 * run writes into results.csv.  The job: exactly one
 * --curve; d = --d (any nonzero finite value) or the curve's first offset.
 *
 * draw writes an SVG like the papers' figures: the base curve (solid), the
 * exact offset C + d N (dashed, 400 samples per base segment, broken where the
 * normal flips at a cusp), the approximation (solid, in colour), the joints
 * of its segments (circles of class "joint": segments + 1 of them), each
 * piece's control polygon (thin, squares at the Euclidean control points),
 * a title with the job and its status, ctrl_points, segments and max_err, and
 * a legend.  y points up.  Geometry far outside the curve and its offset
 * (control points of rational pieces, a pole) is clamped and clipped.
 *
 * trace writes CSV, one row per sample, in order of u:
 *   curve,d,method,metric,split,tol,seg,piece,t,u,err,x,y
 * seg: base segment; piece: accepted output piece in curve order (0-based,
 * over every fit piece of every span); t: parameter of segment seg; u = seg
 * + t; err: the job's metric at t (jobview.h: radial |‖A − C‖ − |d||; normal
 * along the normal line; hausdorff the distance from O(t) to the
 * approximation; bound has no pointwise form and uses the radial error);
 * (x, y): the approximation point A(t) for radial and bound, the exact
 * offset point O(t) for normal and hausdorff.  --points N samples per piece
 * (default 64), evenly spaced in the base parameter, both ends included.
 * Numbers with %.17g; d and tol spelled as results.csv spells them, so rows
 * join with its rows.
 *
 * Exit status: 0 (also when the job ends fail or skip: draw then shows the
 * curve, the offset and the status, trace writes the header only; both say
 * why on stderr), 2 bad options or input, 1 output not writable.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/fsutil.h"
#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/cli/suggest.h"
#include "host/diag.h"
#include "host/io/export.h"
#include "host/io/export_dir.h"
#include "host/view/jobview.h"
#include "host/io/numfmt.h"
#include "host/io/outfile.h"
#include "host/io/output.h"
#include "host/view/svg.h"

enum { DEFAULT_POINTS = 64, MAX_POINTS = 100000 };

/* ---- options ------------------------------------------------------------- */

typedef struct {
    const char *cmd;
    int trace;
    const char *method, *tol, *out;
    int have_d;
    double d;
    int points;
} cmd_args;

enum { DO_METHOD, DO_TOL, DO_D, DO_OUT, DO_POINTS };

static const ob_flag draw_flags[] = {
    {"method", "M", "the job's method", DO_METHOD, OB_FLAG_ONCE},
    {"tol", "T", "the job's tolerance", DO_TOL, OB_FLAG_ONCE},
    {"d", "D", "the offset distance (default: the curve's first offset)", DO_D, OB_FLAG_ONCE},
    {"out", "FILE", "draw: the SVG file; trace: the CSV file (default: standard output)", DO_OUT, OB_FLAG_ONCE},
    {"points", "N", "trace: samples per piece (default 64)", DO_POINTS, OB_FLAG_ONCE},
};

/* The run options draw and trace do not take: they show one job (--method,
 * --tol) and write one file (their own --out). */
static const char RUN_SKIP[] = "methods tols out resume force shard reps certify time-fits fit-reps fit-min-time ";

static int apply_draw_flag(void *ctx, int id, const char *opt, const char *val)
{
    cmd_args *a = ctx;
    double t;
    switch (id) {
    case DO_METHOD:
        if (!ob_method_find(val)) {
            char note[1024];
            ob_error("--method: unknown method '%s' (see './offbench list methods')%s", val,
                     ob_suggest_method_note(val, note, sizeof note));
            return -1;
        }
        a->method = val;
        return 0;
    case DO_TOL:
        if (ob_parse_double(val, &t) || !(t > 0) || t > 1e6) {
            ob_error("--tol: '%s' is not a tolerance (a number > 0 and <= 1e6)", val);
            return -1;
        }
        a->tol = val;
        return 0;
    case DO_D:
        if (ob_parse_double(val, &a->d) || a->d == 0.0) {
            ob_error("--d: '%s' is not an offset distance (a nonzero finite number)", val);
            return -1;
        }
        a->have_d = 1;
        return 0;
    case DO_OUT:
        if (!*val) {
            ob_error("--out: empty file name");
            return -1;
        }
        a->out = val;
        return 0;
    default: {
        char *end;
        errno = 0;
        const long n = strtol(val, &end, 10);
        if (!*val || *end || errno || n < 2 || n > MAX_POINTS) {
            ob_error("%s: expected a whole number from 2 to %d, got '%s'", opt, MAX_POINTS, val);
            return -1;
        }
        a->points = (int)n;
        return 0;
    }
    }
}

/* The command's own options and the run options it takes, into a and o.
 * Returns 0, 2 after ob_error(), or -1 after printing the help (--help). */
static int parse_args(const char *cmd, int trace, int argc, char **argv, cmd_args *a, ob_run_opts *o)
{
    memset(a, 0, sizeof *a);
    a->cmd = cmd;
    a->trace = trace;
    a->points = DEFAULT_POINTS;
    if (ob_run_opts_init(o, argc, argv)) {
        ob_error("%s: out of memory", cmd);
        return 2;
    }
    const ob_flagset sets[2] = {
        {draw_flags, (int)(sizeof draw_flags / sizeof draw_flags[0]) - (trace ? 0 : 1), NULL, NULL, "options",
         apply_draw_flag, a},
        {ob_run_flags, ob_run_nflags, NULL, RUN_SKIP, "run options (as for run)", ob_run_flag_apply, o},
    };
    const int rc = ob_cli_parse(trace ? "--curve ID --method M --tol T [--d D] [--points N] [--out FILE.csv] [run options]"
                                      : "--curve ID --method M --tol T [--d D] --out FILE.svg [run options]\n"
                                        "   or: ./offbench draw --approx FILE --curve ID --d D --out FILE.svg (a file's "
                                        "pieces coloured by their error: draw --approx x --help)",
                                sets, 2, argc, argv, 0, NULL, NULL);
    if (rc == OB_CLI_HELP)
        return -1;
    if (rc != OB_CLI_OK || ob_run_opts_finish(o))
        return 2;
    if (o->ncurve_ids == 0) {
        ob_error("--curve: missing; %s shows one job: --curve ID --method M --tol T", cmd);
        return 2;
    }
    if (!a->method) {
        ob_error("--method: missing; %s shows one job: --curve ID --method M --tol T", cmd);
        return 2;
    }
    if (!a->tol) {
        ob_error("--tol: missing; %s shows one job: --curve ID --method M --tol T", cmd);
        return 2;
    }
    if (!trace && !a->out) {
        ob_error("--out: missing; draw writes an SVG file (--out FILE.svg)");
        return 2;
    }
    return ob_run_opt_set(o, "methods", a->method) || ob_run_opt_set(o, "tols", a->tol) ? 2 : 0;
}

/* The one line on stderr with the figures of results.csv. */
static void report(const ob_jobview *v)
{
    char what[512], sum[256];
    ob_jobview_describe(v, what, sizeof what);
    ob_jobview_summary(v, sum, sizeof sum);
    ob_info("%s %s: %s%s%s", v->cmd, what, sum, v->job.message[0] ? ": " : "",
            v->job.message);
}

/* ---- draw ------------------------------------------------------------------ */

enum { CURVE_SAMPLES = 400, PICTURE_W = 800 };

/* Where world coordinates go: k (x - cx, cy - y) (y up) after clamping into
 * `far`.  k makes the picture PICTURE_W units wide: renderers draw text badly
 * at font sizes far below 1, as the curve's own units would need. */
typedef struct {
    double cx, cy, k;
    ob_bbox far;
} xform;

static void to_svg(const xform *X, const double p[2], double q[2])
{
    double c[2] = {p[0], p[1]};
    ob_bbox_clamp(&X->far, c);
    q[0] = X->k * (c[0] - X->cx);
    q[1] = X->k * (X->cy - c[1]);
}

/* A polyline of world points, broken at non-finite ones. */
static void polyline(FILE *f, const char *cls, const xform *X, const double (*p)[2], int n, double (*buf)[2])
{
    int k = 0;
    for (int i = 0; i <= n; i++) {
        if (i == n || !isfinite(p[i][0]) || !isfinite(p[i][1])) {
            ob_svg_polyline(f, cls, (const double(*)[2])buf, k);
            k = 0;
            continue;
        }
        to_svg(X, p[i], buf[k++]);
    }
}

/* Samples of the exact offset of segment b: n + 1 points and a NaN point
 * before each sample where the normal flips (a cusp of the base): up to
 * 2 n + 2 points.  Returns their number. */
static int offset_samples(const ob_bez *b, double d, int n, double (*p)[2])
{
    int k = 0;
    double prev[2] = {0, 0};
    for (int i = 0; i <= n; i++) {
        const double t = (double)i / n;
        double nv[2];
        const int ok = ob_bez_normal(b, t, nv) == 0;
        if (i > 0 && ok && nv[0] * prev[0] + nv[1] * prev[1] < 0) {
            p[k][0] = p[k][1] = NAN;
            k++;
        }
        if (ok) {
            prev[0] = nv[0];
            prev[1] = nv[1];
        }
        ob_bez_offset_point(b, t, d, p[k++]);
    }
    return k;
}

static int approx_samples_per_piece(int npieces)
{
    const int m = 4000 / (npieces > 0 ? npieces : 1);
    return m < 24 ? 24 : m > 200 ? 200 : m;
}

typedef struct {
    const char *cls, *label;
    int kind;            /* 0 line, 1 circle, 2 control polygon */
} legend_item;

static double text_width(const char *s, double fs) { return 0.56 * fs * (double)strlen(s); }

static const char css_fmt[] =
    ".bg{fill:#ffffff}\n"
    ".base{fill:none;stroke:#111111;stroke-width:%.6g;stroke-linejoin:round;stroke-linecap:round}\n"
    ".offset{fill:none;stroke:#111111;stroke-width:%.6g;stroke-dasharray:%.6g %.6g}\n"
    ".approx{fill:none;stroke:#c62828;stroke-width:%.6g;stroke-linejoin:round;stroke-linecap:round}\n"
    ".joint,.jointkey{fill:#c62828;stroke:#ffffff;stroke-width:%.6g}\n"
    ".ctrl{fill:none;stroke:#1f5fa8;stroke-width:%.6g;stroke-opacity:0.75}\n"
    ".ctrlpt{fill:#ffffff;stroke:#1f5fa8;stroke-width:%.6g}\n"
    ".frame{fill:none;stroke:#b0b0b0;stroke-width:%.6g}\n"
    "text{font-family:'DejaVu Sans',Helvetica,Arial,sans-serif;fill:#111111}\n"
    ".title{font-weight:bold}\n"
    ".message{fill:#8a1c1c}\n";

/* The picture's frame: the base curve and its exact offset, widened by the
 * rest of the geometry (the approximation's points and control points) up
 * to half their size; beyond that it is clipped.  Sets the plot area's
 * height *ph and margin *pm in picture units (its width is PICTURE_W). */
static xform picture_frame(const ob_jobview *v, int np, int ms, double *ph, double *pm)
{
    const ob_curve *c = v->curve;
    const double d = v->job.d;
    ob_bbox core, plot;
    ob_bbox_init(&core);
    for (int s = 0; s < c->nseg; s++) {
        double p[2];
        for (int i = 0; i <= CURVE_SAMPLES; i++) {
            const double t = (double)i / CURVE_SAMPLES;
            ob_bez_point(&c->seg[s], t, p);
            ob_bbox_add(&core, p[0], p[1]);
            ob_bez_offset_point(&c->seg[s], t, d, p);
            ob_bbox_add(&core, p[0], p[1]);
        }
    }
    if (core.empty)
        ob_bbox_add(&core, 0.0, 0.0);
    const double size0 = ob_bbox_size(&core) > 0 ? ob_bbox_size(&core) : fabs(d);
    ob_bbox limit = core, far = core;
    ob_bbox_grow(&limit, 0.5 * size0);
    ob_bbox_grow(&far, 20.0 * size0);
    plot = core;
    for (int k = 0; k < np; k++) {
        const ob_bez *a = &v->pieces[k].approx;
        for (int i = 0; i <= a->deg + ms + 1; i++) { /* control points, then ms + 1 points */
            double p[2];
            if (i <= a->deg)
                ob_bez_ctrl(a, i, p);
            else
                ob_bez_point(a, (double)(i - a->deg - 1) / ms, p);
            if (isfinite(p[0]) && isfinite(p[1])) {
                ob_bbox_clamp(&limit, p);
                ob_bbox_add(&plot, p[0], p[1]);
            }
        }
    }
    ob_bbox_aspect(&plot, 0.35, 0.8, size0 > 0 ? size0 : 1.0);
    const double margin = 0.05 * ob_bbox_size(&plot);
    const double wx = plot.xmax - plot.xmin + 2 * margin, wy = plot.ymax - plot.ymin + 2 * margin;
    const xform X = {0.5 * (plot.xmin + plot.xmax), 0.5 * (plot.ymin + plot.ymax), PICTURE_W / wx, far};
    *ph = X.k * wy;
    *pm = X.k * margin;
    return X;
}

/* The title block: the job, its result, and the row's message if any, in
 * a font size that fits the width pw. */
typedef struct {
    char l1[512], l2[256], l3[256];
    double fs, fs3, h;
} svg_title;

static void title_layout(const ob_jobview *v, double pw, svg_title *t)
{
    t->l3[0] = '\0';
    ob_jobview_describe(v, t->l1, sizeof t->l1);
    ob_jobview_summary(v, t->l2, sizeof t->l2);
    if (v->job.message[0])
        snprintf(t->l3, sizeof t->l3, "%s", v->job.message);
    const double w1 = text_width(t->l1, 1.0) * 1.08, w2 = text_width(t->l2, 1.0);
    t->fs = 15.0;
    if (t->fs * (w1 > w2 ? w1 : w2) > 0.96 * pw)
        t->fs = 0.96 * pw / (w1 > w2 ? w1 : w2);
    t->fs3 = 0.85 * t->fs;
    if (t->l3[0] && t->fs3 * text_width(t->l3, 1.0) > 0.96 * pw)
        t->fs3 = 0.96 * pw / text_width(t->l3, 1.0);
    t->h = 0.6 * t->fs + 1.35 * t->fs * 2 + (t->l3[0] ? 1.35 * t->fs3 : 0.0) + 0.5 * t->fs;
}

/* The legend: symbols and labels, wrapped into rows of the width pw - 2 pm.
 * The items' labels point into the struct: fill it in place. */
typedef struct {
    char lo[96], la[96], lj[96];
    legend_item items[5];
    int n, rows;
    double lfs, sym, gap, x[5], y[5], h;
} svg_legend;

static void legend_layout(const ob_jobview *v, int np, double fs, double pw, double pm, svg_legend *g)
{
    char dtxt[40];
    ob_fmt_double(dtxt, sizeof dtxt, v->job.d);
    snprintf(g->lo, sizeof g->lo, "exact offset, d = %s", dtxt);
    snprintf(g->la, sizeof g->la, "approximation (%s)", v->job.method->name);
    snprintf(g->lj, sizeof g->lj, "joints (%d)", np + (np > 0));
    g->n = 0;
    g->items[g->n++] = (legend_item){"base", "base curve", 0};
    g->items[g->n++] = (legend_item){"offset", g->lo, 0};
    if (np > 0) {
        g->items[g->n++] = (legend_item){"approx", g->la, 0};
        g->items[g->n++] = (legend_item){"jointkey", g->lj, 1};
        g->items[g->n++] = (legend_item){"ctrl", "control polygons", 2};
    }
    g->lfs = 0.85 * fs;
    g->sym = 2.6 * g->lfs;
    g->gap = 0.5 * g->lfs;
    const double sep = 1.6 * g->lfs;
    double x = 0;
    g->rows = 1;
    for (int i = 0; i < g->n; i++) {
        const double w = g->sym + g->gap + text_width(g->items[i].label, g->lfs);
        if (x > 0 && x + w > pw - 2 * pm) {
            g->rows++;
            x = 0;
        }
        g->x[i] = x;
        g->y[i] = g->rows - 1;
        x += w + sep;
    }
    g->h = g->rows * 1.6 * g->lfs + 0.8 * g->lfs;
}

/* The plot: control polygons behind everything, the base curve, the
 * approximation, the exact offset dashed over it (both stay visible), and
 * the joints (each piece's start, and the last one's end).  pts and buf
 * hold ms + 1 and 2 CURVE_SAMPLES + 2 points at least. */
static void draw_figure(FILE *f, const ob_jobview *v, const xform *X, int np, int ms, double (*pts)[2],
                        double (*buf)[2])
{
    const ob_curve *c = v->curve;
    const double u = 1.0; /* one pixel at the natural size */
    for (int k = 0; k < np; k++) {
        const ob_bez *a = &v->pieces[k].approx;
        for (int i = 0; i <= a->deg; i++)
            ob_bez_ctrl(a, i, pts[i]);
        polyline(f, "ctrl", X, (const double(*)[2])pts, a->deg + 1, buf);
        for (int i = 0; i <= a->deg; i++) {
            double q[2];
            if (!isfinite(pts[i][0]) || !isfinite(pts[i][1]))
                continue;
            to_svg(X, pts[i], q);
            ob_svg_rect(f, "ctrlpt", q[0] - 1.4 * u, q[1] - 1.4 * u, 2.8 * u, 2.8 * u);
        }
    }
    for (int s = 0; s < c->nseg; s++) {
        for (int i = 0; i <= CURVE_SAMPLES; i++)
            ob_bez_point(&c->seg[s], (double)i / CURVE_SAMPLES, pts[i]);
        polyline(f, "base", X, (const double(*)[2])pts, CURVE_SAMPLES + 1, buf);
    }
    for (int k = 0; k < np; k++) {
        for (int i = 0; i <= ms; i++)
            ob_bez_point(&v->pieces[k].approx, (double)i / ms, pts[i]);
        polyline(f, "approx", X, (const double(*)[2])pts, ms + 1, buf);
    }
    for (int s = 0; s < c->nseg; s++) {
        const int n = offset_samples(&c->seg[s], v->job.d, CURVE_SAMPLES, pts);
        polyline(f, "offset", X, (const double(*)[2])pts, n, buf);
    }
    for (int k = 0; k <= np && np > 0; k++) {
        double p[2], q[2];
        ob_bez_point(&v->pieces[k < np ? k : np - 1].approx, k < np ? 0.0 : 1.0, p);
        to_svg(X, p, q);
        ob_svg_circle(f, "joint", q[0], q[1], 2.6 * u);
    }
}

/* The legend's rows below the plot area (of height ph), from x0 + pm. */
static void draw_legend(FILE *f, const svg_legend *g, double x0, double pm, double ph)
{
    const double u = 1.0, lfs = g->lfs, sym = g->sym;
    const double ly0 = 0.5 * ph + 0.8 * lfs;
    for (int i = 0; i < g->n; i++) {
        const double sx = x0 + pm + g->x[i], sy = ly0 + g->y[i] * 1.6 * lfs + 0.5 * lfs;
        if (g->items[i].kind == 0) {
            ob_svg_line(f, g->items[i].cls, sx, sy, sx + sym, sy);
        } else if (g->items[i].kind == 1) {
            ob_svg_circle(f, g->items[i].cls, sx + 0.5 * sym, sy, 2.6 * u);
        } else {
            ob_svg_line(f, "ctrl", sx, sy + 0.25 * lfs, sx + sym, sy - 0.25 * lfs);
            ob_svg_rect(f, "ctrlpt", sx - 1.4 * u, sy + 0.25 * lfs - 1.4 * u, 2.8 * u, 2.8 * u);
            ob_svg_rect(f, "ctrlpt", sx + sym - 1.4 * u, sy - 0.25 * lfs - 1.4 * u, 2.8 * u, 2.8 * u);
        }
        ob_svg_text(f, "label", sx + sym + g->gap, sy + 0.35 * lfs, lfs, "start", g->items[i].label);
    }
}

/* The document's head: size, title, style, the coordinate note, the
 * background, the plot area's clip path and frame. */
static void begin_document(FILE *f, const xform *X, const svg_title *t, double x0, double top, double pw,
                           double ph, double H)
{
    const double u = 1.0;
    char title[sizeof t->l1 + sizeof t->l2 + sizeof t->l3 + 8];
    snprintf(title, sizeof title, "%s; %s%s%s", t->l1, t->l2, t->l3[0] ? "; " : "", t->l3);
    char css[2048];
    snprintf(css, sizeof css, css_fmt, 1.7 * u, 1.1 * u, 5 * u, 3.5 * u, 1.7 * u, 0.7 * u, 0.8 * u, 0.8 * u,
             0.8 * u);
    ob_svg_begin(f, x0, top, pw, H, PICTURE_W, title, css);
    char note[256];
    snprintf(note, sizeof note, "offbench draw: picture coordinates are %.17g (x - %.17g, %.17g - y) of the curve's plane",
             X->k, X->cx, X->cy);
    ob_svg_comment(f, note);
    ob_svg_rect(f, "bg", x0, top, pw, H);
    ob_svg_clip_rect(f, "plot", -0.5 * pw, -0.5 * ph, pw, ph);
    ob_svg_rect(f, "frame", -0.5 * pw, -0.5 * ph, pw, ph);
}

static int write_svg(FILE *f, const ob_jobview *v)
{
    const int np = ob_jobview_has_approx(v) ? v->npieces : 0;
    const int ms = approx_samples_per_piece(np);
    const int cap = 2 * CURVE_SAMPLES + 2 > ms + 1 ? 2 * CURVE_SAMPLES + 2 : ms + 1;
    double(*pts)[2] = malloc((size_t)cap * sizeof *pts);
    double(*buf)[2] = malloc((size_t)(cap > OB_MAX_DEG + 1 ? cap : OB_MAX_DEG + 1) * sizeof *buf);
    svg_title t;
    svg_legend g;
    if (!pts || !buf) {
        free(pts);
        free(buf);
        ob_error("draw: out of memory");
        return -1;
    }
    double ph, pm;
    const xform X = picture_frame(v, np, ms, &ph, &pm);
    const double pw = PICTURE_W;
    title_layout(v, pw, &t);
    legend_layout(v, np, t.fs, pw, pm, &g);
    /* the document: the plot area is centred on the origin */
    const double x0 = -0.5 * pw, top = -0.5 * ph - t.h, H = ph + t.h + g.h;
    begin_document(f, &X, &t, x0, top, pw, ph, H);
    ob_svg_group(f, "figure", "plot");
    draw_figure(f, v, &X, np, ms, pts, buf);
    ob_svg_group_end(f);
    double y = top + 0.6 * t.fs + t.fs;
    ob_svg_text(f, "title", x0 + pm, y, t.fs, "start", t.l1);
    y += 1.35 * t.fs;
    ob_svg_text(f, "summary", x0 + pm, y, t.fs, "start", t.l2);
    if (t.l3[0])
        ob_svg_text(f, "message", x0 + pm, y + 1.35 * t.fs3, t.fs3, "start", t.l3);
    ob_svg_group(f, "legend", NULL);
    draw_legend(f, &g, x0, pm, ph);
    ob_svg_group_end(f);
    ob_svg_end(f);
    free(pts);
    free(buf);
    return ferror(f) ? -1 : 0;
}

/* ---- trace ---------------------------------------------------------------- */

static int write_trace(FILE *f, const ob_jobview *v, int points)
{
    fputs("curve,d,method,metric,split,tol,seg,piece,t,u,err,x,y\n", f);
    if (!ob_jobview_has_approx(v))
        return ferror(f) ? -1 : 0;
    double *scratch = malloc(ob_jobview_scratch(v) * sizeof *scratch);
    if (!scratch) {
        ob_error("trace: out of memory");
        return -1;
    }
    char d[40], tol[40];
    ob_fmt_double(d, sizeof d, v->job.d);
    ob_fmt_double(tol, sizeof tol, v->job.tol);
    for (int k = 0; k < v->npieces; k++) {
        const ob_jv_piece *p = &v->pieces[k];
        ob_jobview_prepare(v, p, scratch);
        for (int i = 0; i < points; i++) {
            const double s = i == points - 1 ? 1.0 : (double)i / (points - 1);
            /* the ends exactly, so u never steps back from one piece to the next */
            const double t = i == 0 ? p->ta : i == points - 1 ? p->tb : fmin(p->tb, fmax(p->ta, p->ta + (p->tb - p->ta) * s));
            double xy[2];
            const double err = ob_jobview_err_at(v, p, scratch, s, xy);
            ob_csv_field(f, v->curve->id);
            fprintf(f, ",%s,%s,%s,%s,%s,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g\n", d, v->job.method->name,
                    ob_metric_name(v->job.metric), ob_split_name(v->job.split), tol, p->seg, k, t, p->seg + t, err,
                    xy[0], xy[1]);
        }
    }
    free(scratch);
    return ferror(f) ? -1 : 0;
}

/* ---- the two commands ------------------------------------------------------ */

static int run_cmd(int trace, int argc, char **argv)
{
    const char *cmd = trace ? "trace" : "draw";
    cmd_args a;
    ob_jobview v;
    memset(&v, 0, sizeof v);
    int status = parse_args(cmd, trace, argc, argv, &a, &v.o);
    if (status != 0) {
        ob_run_opts_free(&v.o);
        return status < 0 ? 0 : status;  /* -1: --help */
    }
    status = ob_jobview_open(&v, cmd, a.have_d, a.d);
    FILE *f = NULL;
    ob_outfile of = {0};  /* --out FILE: written afresh, never through a link */
    ob_err err;
    const int to_stdout = trace && (!a.out || strcmp(a.out, "-") == 0);
    if (status == 0 && !to_stdout) {
        const char *const inputs[] = {v.o.curves_file};
        if (ob_check_out_not_input(cmd, a.out, 0, inputs, 1) != 0)
            status = 2;
    }
    if (status == 0 && v.o.export_dir && ob_export_check_dir(cmd, v.o.export_dir, v.o.curves_file) != 0)
        status = 2;  /* the export would become input (export_dir.h) */
    if (status == 0) {
        if (!to_stdout && ob_outfile_open(&of, a.out, 0, &err) != 0) {
            ob_error("--out: %s", err.msg);
            status = 1;
        }
        f = to_stdout ? stdout : of.f;
    }
    if (status == 0)
        status = ob_jobview_run(&v);
    if (status == 0) {
        report(&v);
        if (trace && ob_jobview_has_approx(&v))
            ob_info("trace: err is the %s error at t%s; x,y is the %s",
                    v.job.metric == OB_METRIC_BOUND       ? "radial"
                    : v.job.metric == OB_METRIC_CERTIFIED ? "hausdorff"
                                                          : ob_metric_name(v.job.metric),
                    v.job.metric == OB_METRIC_BOUND       ? " (bound has no pointwise form)"
                    : v.job.metric == OB_METRIC_CERTIFIED ? " (certified has no pointwise form)"
                                                          : "",
                    ob_jobview_point_is_approx(&v) ? "approximation point A(t)" : "exact offset point O(t)");
        if (trace && !ob_jobview_has_approx(&v))
            ob_info("trace: the job ended %s, so there is no approximation to trace",
                    ob_status_name(v.job.status));
        if (!trace && !ob_jobview_has_approx(&v))
            ob_info("draw: the job ended %s; the figure shows the curve and its offset only",
                    ob_status_name(v.job.status));
        const int wrc = trace ? write_trace(f, &v, a.points) : write_svg(f, &v);
        if (wrc != 0) {
            ob_error("%s: writing '%s' failed", cmd, to_stdout ? "standard output" : a.out);
            status = 1;
        }
        if (status == 0 && v.o.export_dir)  /* --export DIR: the job's approximation (host/io/export.h) */
            status = ob_export_single(v.o.export_dir, &v.job, v.samples, &v.spans);
    }
    if (f && !to_stdout && status == 0 && ob_outfile_commit(&of, 0, &err) != 0) {
        ob_error("%s: %s", cmd, err.msg);
        status = 1;
    }
    if (f && to_stdout && fflush(stdout) != 0 && status == 0) {
        ob_error("%s: writing standard output failed", cmd);
        status = 1;
    }
    if (!to_stdout)
        ob_outfile_discard(&of);  /* a failed draw leaves --out as it was */
    ob_jobview_close(&v);
    return status;
}

/* Does the command line ask for a file's approximation (--approx)? */
static int wants_approx(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--approx") == 0 || strncmp(argv[i], "--approx=", 9) == 0)
            return 1;
    return 0;
}

int ob_cmd_draw(int argc, char **argv)
{
    return wants_approx(argc, argv) ? ob_cmd_draw_approx(argc, argv) : run_cmd(0, argc, argv);
}

int ob_cmd_trace(int argc, char **argv) { return run_cmd(1, argc, argv); }
