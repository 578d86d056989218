/*
 * svg_frame.c - where an SVG element's user units lie (svg_read.h): the
 * transform attribute (SVG 1.1 7.6: matrix, translate, scale, rotate,
 * skewX, skewY, a list applied left to right), lengths with units (CSS:
 * 96 px per inch) and a nested <svg>'s viewport (SVG 1.1 7.7, 7.8:
 * viewBox, preserveAspectRatio).  scripts/svgpath.py has the same rules.
 */
#include "host/io/svg_read.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "methods/core/curve.h"

const ob_svgr_xform OB_SVGR_IDENTITY = {{1, 0, 0, 1, 0, 0}};

/* a after b: (a b)(p) = a(b(p)). */
ob_svgr_xform ob_svgr_mul(const ob_svgr_xform *a, const ob_svgr_xform *b)
{
    ob_svgr_xform r;
    r.m[0] = a->m[0] * b->m[0] + a->m[2] * b->m[1];
    r.m[1] = a->m[1] * b->m[0] + a->m[3] * b->m[1];
    r.m[2] = a->m[0] * b->m[2] + a->m[2] * b->m[3];
    r.m[3] = a->m[1] * b->m[2] + a->m[3] * b->m[3];
    r.m[4] = a->m[0] * b->m[4] + a->m[2] * b->m[5] + a->m[4];
    r.m[5] = a->m[1] * b->m[4] + a->m[3] * b->m[5] + a->m[5];
    return r;
}

/* One transform function's arguments (between the parentheses) into a[],
 * *na of them; 0 or -1. */
static int transform_args(ob_svgr_scan *c, double *a, int *na)
{
    *na = 0;
    ob_svgr_skip_wsp(c);
    while (c->i < c->n && c->s[c->i] != ')') {
        if (*na == 6)
            return ob_svgr_fail(c, "too many arguments");
        if (ob_svgr_number(c, &a[(*na)++]))
            return -1;
        ob_svgr_skip_sep(c);
    }
    if (c->i >= c->n)
        return ob_svgr_fail(c, "expected ')'");
    c->i++;
    return 0;
}

/* The map of one transform function name(a[0..na)); 0, or -1 for a wrong
 * count. */
static int transform_of(const char *fn, const double *a, int na, ob_svgr_xform *t)
{
    *t = OB_SVGR_IDENTITY;
    const double r = na ? a[0] * (OB_PI / 180.0) : 0.0;
    if (!strcmp(fn, "matrix") && na == 6) {
        memcpy(t->m, a, sizeof t->m);
    } else if (!strcmp(fn, "translate") && (na == 1 || na == 2)) {
        t->m[4] = a[0];
        t->m[5] = na == 2 ? a[1] : 0.0;
    } else if (!strcmp(fn, "scale") && (na == 1 || na == 2)) {
        t->m[0] = a[0];
        t->m[3] = na == 2 ? a[1] : a[0];
    } else if (!strcmp(fn, "rotate") && (na == 1 || na == 3)) {
        const ob_svgr_xform rot = {{cos(r), sin(r), -sin(r), cos(r), 0, 0}};
        const ob_svgr_xform to = {{1, 0, 0, 1, na == 3 ? a[1] : 0, na == 3 ? a[2] : 0}};
        const ob_svgr_xform back = {{1, 0, 0, 1, -to.m[4], -to.m[5]}};
        const ob_svgr_xform tr = ob_svgr_mul(&rot, &back);
        *t = ob_svgr_mul(&to, &tr);
    } else if (!strcmp(fn, "skewX") && na == 1) {
        t->m[2] = tan(r);
    } else if (!strcmp(fn, "skewY") && na == 1) {
        t->m[1] = tan(r);
    } else {
        return -1;
    }
    return 0;
}

/* A transform attribute (a list of functions) into *t; 0 or -1. */
int ob_svgr_transform(ob_svgr_scan *c, ob_svgr_xform *t)
{
    *t = OB_SVGR_IDENTITY;
    ob_svgr_skip_sep(c);
    while (c->i < c->n) {
        char fn[16];
        size_t k = 0;
        while (c->i < c->n && isalpha((unsigned char)c->s[c->i]) && k + 1 < sizeof fn)
            fn[k++] = c->s[c->i++];
        fn[k] = '\0';
        ob_svgr_skip_wsp(c);
        if (!k || c->i >= c->n || c->s[c->i] != '(')
            return ob_svgr_fail(c, "expected a transform (matrix, translate, scale, rotate, skewX, skewY) and '('");
        c->i++;
        double a[6];
        int na;
        ob_svgr_xform f;
        if (transform_args(c, a, &na))
            return -1;
        if (transform_of(fn, a, na, &f))
            return ob_svgr_fail(c, "a transform with a wrong number of arguments, or an unknown one");
        *t = ob_svgr_mul(t, &f);
        ob_svgr_skip_sep(c);
    }
    return 0;
}


/* ---- lengths ------------------------------------------------------------------------ */

/* The units of a length and user units (px) per unit; % is the viewport's. */
static const struct {
    const char *unit;
    double px;
} UNITS[] = {{"", 1.0}, {"px", 1.0}, {"in", 96.0}, {"cm", 96.0 / 2.54}, {"mm", 96.0 / 25.4},
             {"pt", 96.0 / 72.0}, {"pc", 16.0}, {"%", 0.0}};

int ob_svgr_length(ob_svgr_scan *c, int axis, const double vp[2], double *x)
{
    ob_svgr_skip_wsp(c);
    if (ob_svgr_number(c, x))
        return -1;
    const size_t at = c->i;
    while (c->i < c->n && (isalpha((unsigned char)c->s[c->i]) || c->s[c->i] == '%'))
        c->i++;
    const size_t k = c->i - at;
    size_t u = 0;
    while (u < sizeof UNITS / sizeof *UNITS && !(strlen(UNITS[u].unit) == k && !strncasecmp(UNITS[u].unit, c->s + at, k)))
        u++;
    if (u == sizeof UNITS / sizeof *UNITS) {
        c->i = at;
        return ob_svgr_fail(c, "a unit measure does not read (lengths: user units, px, in, cm, mm, pt, pc, %)");
    }
    ob_svgr_skip_wsp(c);
    if (c->i < c->n)
        return ob_svgr_fail(c, "text after the length");
    if (UNITS[u].unit[0] != '%') {
        *x *= UNITS[u].px;
        return 0;
    }
    const double ref = axis == 2 ? sqrt(0.5 * (vp[0] * vp[0] + vp[1] * vp[1])) : vp[axis];
    if (!(ref > 0.0)) {
        c->i = at;
        return ob_svgr_fail(c, "a percentage of a viewport whose size is not known (give the <svg> a viewBox)");
    }
    *x *= 0.01 * ref;
    return 0;
}

/* ---- viewports ---------------------------------------------------------------------- */

int ob_svgr_viewbox(ob_svgr_scan *c, double vb[4])
{
    ob_svgr_skip_wsp(c);
    for (int k = 0; k < 4; k++) {
        if (k)
            ob_svgr_skip_sep(c);
        if (ob_svgr_number(c, &vb[k]))
            return -1;
    }
    ob_svgr_skip_wsp(c);
    if (c->i < c->n)
        return ob_svgr_fail(c, "text after the four numbers");
    if (!(vb[2] > 0.0 && vb[3] > 0.0))
        return ob_svgr_fail(c, "a width or height not above 0");
    return 0;
}

/* preserveAspectRatio: align[0..1] each 0 min, 1 mid, 2 max (-1: none),
 * *slice; 0 or -1. */
static int aspect_of(ob_svgr_scan *c, int align[2], int *slice)
{
    static const char *const pos[3] = {"Min", "Mid", "Max"};
    char w[3][16] = {{0}};
    int nw = 0;
    while (nw < 3 && sscanf(c->s + c->i, " %15[A-Za-z]", w[nw]) == 1) {
        c->i = (size_t)(strstr(c->s + c->i, w[nw]) - c->s) + strlen(w[nw]);
        nw++;
    }
    int k = !strcmp(w[0], "defer");
    *slice = 0;
    align[0] = align[1] = 1;
    if (nw > k && !strcmp(w[k], "none"))
        align[0] = align[1] = -1;
    else if (nw > k) {
        int ok = strlen(w[k]) == 8 && w[k][0] == 'x' && w[k][4] == 'Y';
        for (int a = 0; a < 2 && ok; a++) {
            align[a] = -1;
            for (int p = 0; p < 3; p++)
                if (!strncmp(w[k] + 1 + 4 * a, pos[p], 3))
                    align[a] = p;
            ok = align[a] >= 0;
        }
        if (!ok)
            return ob_svgr_fail(c, "expected none or xMinYMin ... xMaxYMax");
    }
    if (nw > k + 1 && strcmp(w[k + 1], "meet") && strcmp(w[k + 1], "slice"))
        return ob_svgr_fail(c, "expected meet or slice");
    *slice = nw > k + 1 && !strcmp(w[k + 1], "slice");
    return 0;
}

int ob_svgr_viewport(ob_svgr_scan *c, const double box[4], const char *viewbox, const char *aspect,
                    ob_svgr_xform *t, double vp[2])
{
    *t = (ob_svgr_xform){{1, 0, 0, 1, box[0], box[1]}};
    vp[0] = box[2], vp[1] = box[3];
    if (!viewbox)
        return 0;
    double vb[4];
    const char *what = c->what;
    char key[48];
    snprintf(key, sizeof key, "%s: viewBox", what);
    *c = (ob_svgr_scan){viewbox, 0, strlen(viewbox), key, c->name, c->line, c->err};
    if (ob_svgr_viewbox(c, vb))
        return -1;
    int align[2], slice;
    snprintf(key, sizeof key, "%s: preserveAspectRatio", what);
    *c = (ob_svgr_scan){aspect ? aspect : "", 0, aspect ? strlen(aspect) : 0, key, c->name, c->line, c->err};
    if (aspect_of(c, align, &slice))
        return -1;
    double sx = box[2] / vb[2], sy = box[3] / vb[3];
    if (align[0] >= 0)
        sx = sy = slice ? fmax(sx, sy) : fmin(sx, sy);
    const double s[2] = {sx, sy};
    for (int a = 0; a < 2; a++)
        t->m[4 + a] = box[a] - vb[a] * s[a] + (align[a] > 0 ? 0.5 * align[a] * (box[2 + a] - vb[2 + a] * s[a]) : 0.0);
    t->m[0] = sx, t->m[3] = sy;
    vp[0] = vb[2], vp[1] = vb[3];
    return 0;
}
