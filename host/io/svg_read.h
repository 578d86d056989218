/*
 * svg_read.h - the parts of measure's SVG reader (internal to
 * host/io/approx_read_svg.c, the XML walk on libexpat; svg_path.c, path
 * data and the shapes as Bézier pieces; svg_frame.c, transforms, lengths
 * with units and viewports).  The rules are docs/export-measure.md,
 * "Reading SVG", and scripts/svg2curves.py follows the same ones.
 */
#ifndef OB_SVG_READ_H
#define OB_SVG_READ_H
#include <stddef.h>

#include "host/io/approx.h"
#include "methods/core/err.h"

/* An affine map: x' = m[0] x + m[2] y + m[4], y' = m[1] x + m[3] y + m[5]. */
typedef struct {
    double m[6];
} ob_svgr_xform;

extern const ob_svgr_xform OB_SVGR_IDENTITY;

/* a after b: (a b)(p) = a(b(p)). */
ob_svgr_xform ob_svgr_mul(const ob_svgr_xform *a, const ob_svgr_xform *b);

/* A cursor over one attribute's text, with what to name in messages:
 * "NAME:LINE: WHAT: at character K ('...'): reason". */
typedef struct {
    const char *s;
    size_t i, n;
    const char *what; /* "<path>: d" */
    const char *name;
    int line;
    ob_err *err;
} ob_svgr_scan;

int ob_svgr_fail(ob_svgr_scan *c, const char *why);
void ob_svgr_skip_wsp(ob_svgr_scan *c);
/* Whitespace, then at most one comma, then whitespace. */
void ob_svgr_skip_sep(ob_svgr_scan *c);
/* A number of the SVG grammar ([+-] digits [. digits] [e [+-] digits]),
 * finite; 0 or -1 (named). */
int ob_svgr_number(ob_svgr_scan *c, double *x);

/* Where the pieces of one element go: its line, its map to the file's
 * coordinates before the y flip. */
typedef struct {
    const char *name;
    int line;
    ob_svgr_xform ctm;
    ob_approx *out;
    ob_err *err;
} ob_svgr_emit;

/* svg_path.c: path data d, a points list (closed: a polygon), a line, an
 * ellipse and a rectangle as SVG 2 (10.2, 10.4) makes them paths. */
int ob_svgr_path(ob_svgr_scan *c, const ob_svgr_emit *e);
int ob_svgr_points(ob_svgr_scan *c, const ob_svgr_emit *e, int closed);
int ob_svgr_line(const ob_svgr_emit *e, const double p0[2], const double p1[2]);
int ob_svgr_ellipse(const ob_svgr_emit *e, double cx, double cy, double rx, double ry);
int ob_svgr_rect(const ob_svgr_emit *e, double x, double y, double w, double h, double rx, double ry);

/* svg_frame.c: a transform list into *t. */
int ob_svgr_transform(ob_svgr_scan *c, ob_svgr_xform *t);
/* A length (a number and a unit: none or px 1, in 96, cm 96/2.54, mm
 * 96/25.4, pt 4/3, pc 16, % of the viewport vp[2]'s width (axis 0), height
 * (1) or diagonal / sqrt 2 (2)) in user units; 0 or -1 (named, also a
 * unit not read: em, ex, ...). */
int ob_svgr_length(ob_svgr_scan *c, int axis, const double vp[2], double *x);
/* A nested <svg>'s viewport x, y, w, h (user units of its parent) and its
 * viewBox and preserveAspectRatio attributes (NULL: absent) into the map
 * from its user units to its parent's, *t, and its viewport size vp[2]
 * (the viewBox's); 0 or -1 (named). */
int ob_svgr_viewport(ob_svgr_scan *c, const double box[4], const char *viewbox, const char *aspect,
                    ob_svgr_xform *t, double vp[2]);
/* A viewBox attribute's four numbers (width and height > 0); 0 or -1. */
int ob_svgr_viewbox(ob_svgr_scan *c, double vb[4]);
#endif
