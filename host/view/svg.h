/*
 * svg.h - a small SVG writer for the figures of `./offbench draw`.
 *
 * Coordinates are written as given with %.6g; the caller maps its world
 * coordinates to the picture (y up becomes y down by negation) and chooses the
 * viewBox.  Text is XML-escaped (&, <, >, quotes; control characters, which
 * XML 1.0 forbids, become '?'), so any curve id or message gives a well-formed
 * document.  Every element takes a class, which the document's <style> block
 * gives its look (and which tests can count).
 */
#ifndef OB_SVG_H
#define OB_SVG_H

#include <stddef.h>
#include <stdio.h>

/* ---- bounding boxes ------------------------------------------------------ */

typedef struct {
    double xmin, xmax, ymin, ymax;
    int empty;               /* 1: no point added yet */
} ob_bbox;

void ob_bbox_init(ob_bbox *b);
/* Adds (x, y); non-finite points are ignored. */
void ob_bbox_add(ob_bbox *b, double x, double y);
/* Widens every side by m (m >= 0). */
void ob_bbox_grow(ob_bbox *b, double m);
/* Largest side, 0 when empty. */
double ob_bbox_size(const ob_bbox *b);
/* Clamps (x, y) into b (non-empty); NaN coordinates go to the lower edge. */
void ob_bbox_clamp(const ob_bbox *b, double p[2]);
/* Pads the shorter side about the centre so that height >= min_h_w * width and
 * width >= min_w_h * height; gives a point box a size of `unit`. */
void ob_bbox_aspect(ob_bbox *b, double min_h_w, double min_w_h, double unit);

/* ---- text ------------------------------------------------------------------ */

/* Purpose: XML-escape s into buf (always NUL-terminated when len > 0).
 * Returns the length of the full escaped text (as snprintf: >= len means it
 * was truncated, never in the middle of an entity). */
size_t ob_svg_escape(char *buf, size_t len, const char *s);
/* The same, straight to a file. */
void ob_svg_put_text(FILE *f, const char *s);

/* ---- document ------------------------------------------------------------ */

/* Opens the document: viewBox (x, y, w, h), width px_w pixels (height in
 * proportion), a <title>, and the <style> block `css` (raw CSS, not escaped:
 * it must not contain "</"). */
void ob_svg_begin(FILE *f, double x, double y, double w, double h, double px_w, const char *title,
                  const char *css);
void ob_svg_end(FILE *f);
/* <g class="cls" [clip-path="url(#clip)"]> ... </g>; clip may be NULL. */
void ob_svg_group(FILE *f, const char *cls, const char *clip);
void ob_svg_group_end(FILE *f);
/* <clipPath id="id"> with one rectangle. */
void ob_svg_clip_rect(FILE *f, const char *id, double x, double y, double w, double h);
/* An XML comment; "--" inside is written as "- -". */
void ob_svg_comment(FILE *f, const char *s);

/* ---- shapes -------------------------------------------------------------- */

/* n >= 2 points xy[i] = (x, y); nothing is written for n < 2. */
void ob_svg_polyline(FILE *f, const char *cls, const double (*xy)[2], int n);
void ob_svg_line(FILE *f, const char *cls, double x1, double y1, double x2, double y2);
void ob_svg_circle(FILE *f, const char *cls, double cx, double cy, double r);
/* A rectangle with corner (x, y) and size w x h. */
void ob_svg_rect(FILE *f, const char *cls, double x, double y, double w, double h);
/* Text at (x, y) (baseline), font size `size`, anchor "start", "middle" or
 * "end"; s is escaped. */
void ob_svg_text(FILE *f, const char *cls, double x, double y, double size, const char *anchor, const char *s);

#endif
