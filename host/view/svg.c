/*
 * svg.c - see svg.h.
 */
#include "host/view/svg.h"

#include <math.h>
#include <string.h>

void ob_bbox_init(ob_bbox *b)
{
    b->xmin = b->xmax = b->ymin = b->ymax = 0.0;
    b->empty = 1;
}

void ob_bbox_add(ob_bbox *b, double x, double y)
{
    if (!isfinite(x) || !isfinite(y))
        return;
    if (b->empty) {
        b->xmin = b->xmax = x;
        b->ymin = b->ymax = y;
        b->empty = 0;
        return;
    }
    b->xmin = fmin(b->xmin, x);
    b->xmax = fmax(b->xmax, x);
    b->ymin = fmin(b->ymin, y);
    b->ymax = fmax(b->ymax, y);
}

void ob_bbox_grow(ob_bbox *b, double m)
{
    if (b->empty)
        return;
    b->xmin -= m;
    b->xmax += m;
    b->ymin -= m;
    b->ymax += m;
}

double ob_bbox_size(const ob_bbox *b)
{
    return b->empty ? 0.0 : fmax(b->xmax - b->xmin, b->ymax - b->ymin);
}

void ob_bbox_clamp(const ob_bbox *b, double p[2])
{
    p[0] = isnan(p[0]) ? b->xmin : fmin(b->xmax, fmax(b->xmin, p[0]));
    p[1] = isnan(p[1]) ? b->ymin : fmin(b->ymax, fmax(b->ymin, p[1]));
}

void ob_bbox_aspect(ob_bbox *b, double min_h_w, double min_w_h, double unit)
{
    if (b->empty) {
        b->xmin = b->ymin = 0.0;
        b->xmax = b->ymax = 0.0;
        b->empty = 0;
    }
    double w = b->xmax - b->xmin, h = b->ymax - b->ymin;
    if (w <= 0 && h <= 0) {
        w = h = unit;
        b->xmin -= 0.5 * unit;
        b->xmax += 0.5 * unit;
        b->ymin -= 0.5 * unit;
        b->ymax += 0.5 * unit;
    }
    if (h < min_h_w * w) {
        const double pad = 0.5 * (min_h_w * w - h);
        b->ymin -= pad;
        b->ymax += pad;
        h = b->ymax - b->ymin;
    }
    if (w < min_w_h * h) {
        const double pad = 0.5 * (min_w_h * h - w);
        b->xmin -= pad;
        b->xmax += pad;
    }
}

/* The escaped form of one byte, or NULL when it stands for itself. */
static const char *entity(unsigned char c)
{
    switch (c) {
    case '&': return "&amp;";
    case '<': return "&lt;";
    case '>': return "&gt;";
    case '"': return "&quot;";
    case '\'': return "&apos;";
    default: return c < 0x20 && c != '\t' && c != '\n' && c != '\r' ? "?" : NULL;
    }
}

size_t ob_svg_escape(char *buf, size_t len, const char *s)
{
    size_t n = 0, w = 0;  /* full length; bytes written (whole pieces only) */
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        const char *e = entity(*p);
        char one[2] = {(char)*p, '\0'};
        const char *piece = e ? e : one;
        const size_t k = strlen(piece);
        if (w == n && n + k < len) {
            memcpy(buf + n, piece, k);
            w += k;
        }
        n += k;
    }
    if (len > 0)
        buf[w] = '\0';
    return n;
}

void ob_svg_put_text(FILE *f, const char *s)
{
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        const char *e = entity(*p);
        if (e)
            fputs(e, f);
        else
            fputc(*p, f);
    }
}

void ob_svg_begin(FILE *f, double x, double y, double w, double h, double px_w, const char *title,
                  const char *css)
{
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" viewBox=\"%.6g %.6g %.6g %.6g\" "
            "width=\"%.6g\" height=\"%.6g\">\n",
            x, y, w, h, px_w, px_w * h / w);
    fputs("<title>", f);
    ob_svg_put_text(f, title);
    fputs("</title>\n", f);
    if (css && *css)
        fprintf(f, "<style>\n%s</style>\n", css);
}

void ob_svg_end(FILE *f) { fputs("</svg>\n", f); }

void ob_svg_group(FILE *f, const char *cls, const char *clip)
{
    fprintf(f, "<g class=\"%s\"", cls);
    if (clip)
        fprintf(f, " clip-path=\"url(#%s)\"", clip);
    fputs(">\n", f);
}

void ob_svg_group_end(FILE *f) { fputs("</g>\n", f); }

void ob_svg_clip_rect(FILE *f, const char *id, double x, double y, double w, double h)
{
    fprintf(f, "<clipPath id=\"%s\"><rect x=\"%.6g\" y=\"%.6g\" width=\"%.6g\" height=\"%.6g\"/></clipPath>\n", id, x,
            y, w, h);
}

void ob_svg_comment(FILE *f, const char *s)
{
    fputs("<!-- ", f);
    for (const char *p = s; *p; p++) {
        fputc(*p, f);
        if (*p == '-' && (p[1] == '-' || p[1] == '\0'))
            fputc(' ', f);
    }
    fputs(" -->\n", f);
}

void ob_svg_polyline(FILE *f, const char *cls, const double (*xy)[2], int n)
{
    if (n < 2)
        return;
    fprintf(f, "<polyline class=\"%s\" points=\"", cls);
    for (int i = 0; i < n; i++)
        fprintf(f, "%s%.6g,%.6g", i ? " " : "", xy[i][0], xy[i][1]);
    fputs("\"/>\n", f);
}

void ob_svg_line(FILE *f, const char *cls, double x1, double y1, double x2, double y2)
{
    fprintf(f, "<line class=\"%s\" x1=\"%.6g\" y1=\"%.6g\" x2=\"%.6g\" y2=\"%.6g\"/>\n", cls, x1, y1, x2, y2);
}

void ob_svg_circle(FILE *f, const char *cls, double cx, double cy, double r)
{
    fprintf(f, "<circle class=\"%s\" cx=\"%.6g\" cy=\"%.6g\" r=\"%.6g\"/>\n", cls, cx, cy, r);
}

void ob_svg_rect(FILE *f, const char *cls, double x, double y, double w, double h)
{
    fprintf(f, "<rect class=\"%s\" x=\"%.6g\" y=\"%.6g\" width=\"%.6g\" height=\"%.6g\"/>\n", cls, x, y, w, h);
}

void ob_svg_text(FILE *f, const char *cls, double x, double y, double size, const char *anchor, const char *s)
{
    fprintf(f, "<text class=\"%s\" x=\"%.6g\" y=\"%.6g\" font-size=\"%.6g\" text-anchor=\"%s\">", cls, x, y, size,
            anchor);
    ob_svg_put_text(f, s);
    fputs("</text>\n", f);
}
