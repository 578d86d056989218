/*
 * approx_read_svg.c - the paths of an SVG file as Bézier pieces for
 * `measure` (approx_read.h), read as scripts/svg2curves.py reads them with
 * its defaults (--y up, --units user): every <path>, <line>, <polyline> and
 * <polygon>, <circle>, <ellipse> and <rect> outside defs, symbol, clipPath, mask, marker and pattern, with
 * the transforms of the element and of its ancestors applied (matrix,
 * translate, scale, rotate, skewX, skewY), then y = -y (so the curve is as a
 * browser draws it, and an export's scale(1,-1) group gives back the base
 * curve's coordinates); the root's viewBox is not applied (user units).
 *
 * Path data follows the grammar of SVG 1.1 8.3.9: M L H V C S Q T A Z, each
 * absolute or relative, implicit repetition, L after M.  A line is a piece
 * of degree 1, a quadratic or cubic its own piece (S and T reflect the
 * previous control point), an elliptical arc exact rational quadratic pieces
 * of at most 90 degrees each (weight cos of half the piece's angle, SVG 1.1
 * F.6.5 for the centre, radii scaled up when too small), Z a line back to the
 * subpath's start when it is elsewhere.  Neighbouring pieces share their end
 * points bit for bit.  A circle, ellipse or rectangle is the path SVG 2
 * (10.2, 10.4) gives it: from its rightmost point (an ellipse) or the top
 * side's start (a rectangle), quarter arcs of sweep 1 (rounded corners),
 * lines between.  Zero-length segments, shapes of size 0, and <text>,
 * <image> and <use> elements, are skipped and noted
 * (ob_approx_note_skip).  Each piece is at the line of its element's tag; a
 * malformed attribute is an error "NAME:LINE: <path>: d: at character K
 * ('...'): reason".
 */
#include "host/io/approx_read.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { SVG_MAX_DEPTH = 256 };

/* An affine map: x' = m[0] x + m[2] y + m[4], y' = m[1] x + m[3] y + m[5]. */
typedef struct {
    double m[6];
} xform;

static const xform IDENTITY = {{1, 0, 0, 1, 0, 0}};

/* a after b: (a b)(p) = a(b(p)). */
static xform xf_mul(const xform *a, const xform *b)
{
    xform r;
    r.m[0] = a->m[0] * b->m[0] + a->m[2] * b->m[1];
    r.m[1] = a->m[1] * b->m[0] + a->m[3] * b->m[1];
    r.m[2] = a->m[0] * b->m[2] + a->m[2] * b->m[3];
    r.m[3] = a->m[1] * b->m[2] + a->m[3] * b->m[3];
    r.m[4] = a->m[0] * b->m[4] + a->m[2] * b->m[5] + a->m[4];
    r.m[5] = a->m[1] * b->m[4] + a->m[3] * b->m[5] + a->m[5];
    return r;
}

/* ---- scanning an attribute's text -------------------------------------------- */

typedef struct {
    const char *s;
    size_t i, n;
    const char *what;   /* "<path>: d" for messages */
    const char *name;
    int line;
    ob_err *err;
} scan;

static int scan_fail(scan *c, const char *why)
{
    char near[16];
    const size_t k = c->n - c->i < 12 ? c->n - c->i : 12;
    memcpy(near, c->s + c->i, k);
    near[k] = '\0';
    for (size_t j = 0; j < k; j++)
        near[j] = near[j] == '\n' || near[j] == '\r' || near[j] == '\t' ? ' ' : near[j];
    if (k)
        ob_fail(c->err, "%s:%d: %s: at character %zu ('%s'): %s", c->name, c->line, c->what, c->i + 1, near, why);
    else
        ob_fail(c->err, "%s:%d: %s: at the end: %s", c->name, c->line, c->what, why);
    return -1;
}

static void skip_wsp(scan *c)
{
    while (c->i < c->n && strchr(" \t\n\r\f", c->s[c->i]) && c->s[c->i])
        c->i++;
}

/* Whitespace, then at most one comma, then whitespace. */
static void skip_sep(scan *c)
{
    skip_wsp(c);
    if (c->i < c->n && c->s[c->i] == ',') {
        c->i++;
        skip_wsp(c);
    }
}

static int at_number(const scan *c)
{
    if (c->i >= c->n)
        return 0;
    const char ch = c->s[c->i];
    return isdigit((unsigned char)ch) || ch == '.' || ch == '+' || ch == '-';
}

/* A number of the SVG grammar ([+-] digits [. digits] [e [+-] digits]). */
static int number(scan *c, double *x)
{
    size_t j = c->i, digits = 0;
    if (j < c->n && (c->s[j] == '+' || c->s[j] == '-'))
        j++;
    while (j < c->n && isdigit((unsigned char)c->s[j]))
        j++, digits++;
    if (j < c->n && c->s[j] == '.') {
        j++;
        while (j < c->n && isdigit((unsigned char)c->s[j]))
            j++, digits++;
    }
    if (!digits)
        return scan_fail(c, "expected a number");
    if (j < c->n && (c->s[j] == 'e' || c->s[j] == 'E')) {
        size_t k = j + 1;
        if (k < c->n && (c->s[k] == '+' || c->s[k] == '-'))
            k++;
        if (k < c->n && isdigit((unsigned char)c->s[k])) {
            while (k < c->n && isdigit((unsigned char)c->s[k]))
                k++;
            j = k;
        }
    }
    char buf[64];
    if (j - c->i >= sizeof buf)
        return scan_fail(c, "a number too long");
    memcpy(buf, c->s + c->i, j - c->i);
    buf[j - c->i] = '\0';
    *x = strtod(buf, NULL);
    if (!isfinite(*x))
        return scan_fail(c, "a number out of range");
    c->i = j;
    return 0;
}

/* An arc flag: one character 0 or 1. */
static int flag(scan *c, double *x)
{
    if (c->i >= c->n || (c->s[c->i] != '0' && c->s[c->i] != '1'))
        return scan_fail(c, "expected an arc flag (0 or 1)");
    *x = c->s[c->i++] - '0';
    return 0;
}

/* ---- transforms ------------------------------------------------------------------- */

/* One transform function's arguments (between the parentheses) into a[],
 * *na of them; 0 or -1. */
static int transform_args(scan *c, double *a, int *na)
{
    *na = 0;
    skip_wsp(c);
    while (c->i < c->n && c->s[c->i] != ')') {
        if (*na == 6)
            return scan_fail(c, "too many arguments");
        if (number(c, &a[(*na)++]))
            return -1;
        skip_sep(c);
    }
    if (c->i >= c->n)
        return scan_fail(c, "expected ')'");
    c->i++;
    return 0;
}

/* The map of one transform function name(a[0..na)); 0, or -1 for a wrong
 * count. */
static int transform_of(const char *fn, const double *a, int na, xform *t)
{
    *t = IDENTITY;
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
        const xform rot = {{cos(r), sin(r), -sin(r), cos(r), 0, 0}};
        const xform to = {{1, 0, 0, 1, na == 3 ? a[1] : 0, na == 3 ? a[2] : 0}};
        const xform back = {{1, 0, 0, 1, -to.m[4], -to.m[5]}};
        const xform tr = xf_mul(&rot, &back);
        *t = xf_mul(&to, &tr);
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
static int parse_transform(scan *c, xform *t)
{
    *t = IDENTITY;
    skip_sep(c);
    while (c->i < c->n) {
        char fn[16];
        size_t k = 0;
        while (c->i < c->n && isalpha((unsigned char)c->s[c->i]) && k + 1 < sizeof fn)
            fn[k++] = c->s[c->i++];
        fn[k] = '\0';
        skip_wsp(c);
        if (!k || c->i >= c->n || c->s[c->i] != '(')
            return scan_fail(c, "expected a transform (matrix, translate, scale, rotate, skewX, skewY) and '('");
        c->i++;
        double a[6];
        int na;
        xform f;
        if (transform_args(c, a, &na))
            return -1;
        if (transform_of(fn, a, na, &f))
            return scan_fail(c, "a transform with a wrong number of arguments, or an unknown one");
        *t = xf_mul(t, &f);
        skip_sep(c);
    }
    return 0;
}

/* ---- pieces ------------------------------------------------------------------------ */

typedef struct {
    const char *name;
    int line;                 /* of the element's tag */
    xform ctm;                /* user space to the file's, before the y flip */
    ob_approx *out;
    ob_err *err;
} emit;

/* Appends the piece of degree deg with Euclidean control points p and
 * weights w (NULL: all 1), mapped by e->ctm and y = -y; a piece whose
 * points all coincide is skipped and noted.  0 or -1. */
static int add_piece(const emit *e, int deg, const double (*p)[2], const double *w)
{
    int same = 1;
    for (int i = 1; i <= deg; i++)
        same &= p[i][0] == p[0][0] && p[i][1] == p[0][1];
    if (same) {
        ob_approx_note_skip(e->out, "zero-length segment", e->line);
        return 0;
    }
    ob_apiece *a = ob_approx_add(e->out);
    if (!a)
        return ob_fail(e->err, "%s: out of memory", e->name);
    a->line = e->line;
    a->fit_first = 1;
    a->approx.deg = deg;
    const double *m = e->ctm.m;
    for (int i = 0; i <= deg; i++) {
        const double x = m[0] * p[i][0] + m[2] * p[i][1] + m[4], y = m[1] * p[i][0] + m[3] * p[i][1] + m[5];
        const double wi = w ? w[i] : 1.0;
        ob_bez_set(&a->approx, i, x, -y, wi);
    }
    return ob_approx_check_piece(a, e->out->n - 1, e->name, e->err);
}

static int add_line(const emit *e, const double p0[2], const double p1[2])
{
    const double p[2][2] = {{p0[0], p0[1]}, {p1[0], p1[1]}};
    return add_piece(e, 1, p, NULL);
}

/* The arc of SVG's endpoint form from p0 to p1 (SVG 1.1 F.6.5) as rational
 * quadratic pieces of at most 90 degrees; radii 0: a line. */
static int add_arc(const emit *e, const double p0[2], double rx, double ry, double phi_deg, int large, int sweep,
                   const double p1[2])
{
    if (p0[0] == p1[0] && p0[1] == p1[1])
        return 0; /* SVG: an arc to its own start is no arc */
    rx = fabs(rx), ry = fabs(ry);
    if (rx == 0.0 || ry == 0.0)
        return add_line(e, p0, p1);
    const double phi = fmod(phi_deg, 360.0) * (OB_PI / 180.0), cp = cos(phi), sp = sin(phi);
    const double dx2 = 0.5 * (p0[0] - p1[0]), dy2 = 0.5 * (p0[1] - p1[1]);
    const double x1 = cp * dx2 + sp * dy2, y1 = -sp * dx2 + cp * dy2;
    const double lam = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry);
    if (lam > 1.0)
        rx *= sqrt(lam), ry *= sqrt(lam);
    const double num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    const double den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
    double k = den > 0.0 && num > 0.0 ? sqrt(num / den) : 0.0;
    k = large != sweep ? k : -k;
    const double cxp = k * rx * y1 / ry, cyp = -k * ry * x1 / rx;
    const double cx = cp * cxp - sp * cyp + 0.5 * (p0[0] + p1[0]), cy = sp * cxp + cp * cyp + 0.5 * (p0[1] + p1[1]);
    const double t1 = atan2((y1 - cyp) / ry, (x1 - cxp) / rx), t2 = atan2((-y1 - cyp) / ry, (-x1 - cxp) / rx);
    double dt = t2 - t1;
    if (sweep && dt < 0.0)
        dt += 2.0 * OB_PI;
    else if (!sweep && dt > 0.0)
        dt -= 2.0 * OB_PI;
    const int n = (int)fmax(1.0, ceil(fabs(dt) / (0.5 * OB_PI) - 1e-9));
    const double h = 0.5 * dt / n, w[3] = {1.0, cos(h), 1.0};
    double prev[2] = {p0[0], p0[1]};
    for (int i = 0; i < n; i++) {
        const double a0 = t1 + 2.0 * h * i, u[2][2] = {{cos(a0 + h) / cos(h), sin(a0 + h) / cos(h)},
                                                      {cos(a0 + 2.0 * h), sin(a0 + 2.0 * h)}};
        double q[3][2] = {{prev[0], prev[1]}, {0, 0}, {0, 0}};
        for (int j = 0; j < 2; j++) {
            q[j + 1][0] = cx + cp * rx * u[j][0] - sp * ry * u[j][1];
            q[j + 1][1] = cy + sp * rx * u[j][0] + cp * ry * u[j][1];
        }
        if (i == n - 1)
            q[2][0] = p1[0], q[2][1] = p1[1];
        if (add_piece(e, 2, q, w))
            return -1;
        prev[0] = q[2][0], prev[1] = q[2][1];
    }
    return 0;
}

/* ---- path data ---------------------------------------------------------------------- */

typedef struct {
    double cur[2], start[2], ctrl[2];
    char last;                /* the previous command, upper case */
} pen;

/* Reads the n arguments of command cmd (kinds "n" number, "f" flag) into a. */
static int args(scan *c, const char *kinds, double *a)
{
    for (int k = 0; kinds[k]; k++) {
        if (k)
            skip_sep(c);
        if ((kinds[k] == 'f' ? flag(c, &a[k]) : number(c, &a[k])) != 0)
            return -1;
    }
    return 0;
}

/* Executes one command (upper case up, relative rel) with arguments a. */
static int command(const emit *e, pen *p, char up, int rel, const double *a)
{
    const double ox = rel ? p->cur[0] : 0.0, oy = rel ? p->cur[1] : 0.0;
    double q[4][2] = {{p->cur[0], p->cur[1]}};
    int rc = 0;
    switch (up) {
    case 'M':
        p->cur[0] = p->start[0] = a[0] + ox, p->cur[1] = p->start[1] = a[1] + oy;
        break;
    case 'L': case 'H': case 'V':
        q[1][0] = up == 'V' ? p->cur[0] : a[0] + ox;
        q[1][1] = up == 'H' ? p->cur[1] : up == 'V' ? a[0] + oy : a[1] + oy;
        rc = add_line(e, q[0], q[1]);
        break;
    case 'C': case 'S': case 'Q': case 'T': {
        const int cubic = up == 'C' || up == 'S', smooth = up == 'S' || up == 'T';
        const int reflect = smooth && p->last == (cubic ? 'C' : 'Q');
        int k = 0;  /* next argument */
        if (smooth) {
            q[1][0] = reflect ? 2.0 * p->cur[0] - p->ctrl[0] : p->cur[0];
            q[1][1] = reflect ? 2.0 * p->cur[1] - p->ctrl[1] : p->cur[1];
        }
        for (int j = smooth ? 2 : 1; j <= (cubic ? 3 : 2); j++, k += 2)
            q[j][0] = a[k] + ox, q[j][1] = a[k + 1] + oy;
        const int deg = cubic ? 3 : 2;
        rc = add_piece(e, deg, (const double(*)[2])q, NULL);
        p->ctrl[0] = q[deg - 1][0], p->ctrl[1] = q[deg - 1][1];
        q[1][0] = q[deg][0], q[1][1] = q[deg][1];
        break;
    }
    case 'A':
        q[1][0] = a[5] + ox, q[1][1] = a[6] + oy;
        rc = add_arc(e, q[0], a[0], a[1], a[2], a[3] != 0.0, a[4] != 0.0, q[1]);
        break;
    default: /* Z */
        q[1][0] = p->start[0], q[1][1] = p->start[1];
        if (q[0][0] != q[1][0] || q[0][1] != q[1][1])
            rc = add_line(e, q[0], q[1]);
        break;
    }
    if (up != 'M')
        p->cur[0] = q[1][0], p->cur[1] = q[1][1];
    p->last = up == 'S' ? 'C' : up == 'T' ? 'Q' : up;
    return rc;
}

/* The argument kinds of a command (upper case), or NULL: not a command. */
static const char *kinds_of(char up)
{
    switch (up) {
    case 'M': case 'L': case 'T': return "nn";
    case 'H': case 'V': return "n";
    case 'C': return "nnnnnn";
    case 'S': case 'Q': return "nnnn";
    case 'A': return "nnnffnn";
    case 'Z': return "";
    default: return NULL;
    }
}

/* The path data d of one element. */
static int parse_path(scan *c, const emit *e)
{
    pen p = {{0, 0}, {0, 0}, {0, 0}, 0};
    char cmd = 0;
    skip_wsp(c);
    while (c->i < c->n) {
        const char ch = c->s[c->i];
        const char up = (char)toupper((unsigned char)ch);
        if (isalpha((unsigned char)ch)) {
            if (!kinds_of(up))
                return scan_fail(c, "not a path command (M L H V C S Q T A Z, or lower case)");
            if (!cmd && up != 'M')
                return scan_fail(c, "path data must begin with M or m");
            cmd = ch;
            c->i++;
            skip_wsp(c);
        } else if (!cmd || toupper((unsigned char)cmd) == 'Z' || !at_number(c)) {
            return scan_fail(c, cmd ? "expected a command" : "path data must begin with M or m");
        }
        const char cu = (char)toupper((unsigned char)cmd);
        double a[7];
        if (args(c, kinds_of(cu), a) || command(e, &p, cu, islower((unsigned char)cmd), a))
            return -1;
        if (cu == 'M')
            cmd = cmd == 'm' ? 'l' : 'L';  /* pairs after a moveto are linetos */
        if (cu != 'Z')
            skip_sep(c);
        else
            skip_wsp(c);
    }
    return 0;
}

/* The points attribute of a polyline (closed 0) or polygon (closed 1). */
static int parse_points(scan *c, const emit *e, int closed)
{
    double first[2] = {0, 0}, prev[2] = {0, 0}, q[2];
    int n = 0;
    skip_wsp(c);
    while (c->i < c->n) {
        if (number(c, &q[0]))
            return -1;
        skip_sep(c);
        if (number(c, &q[1]))
            return -1;
        skip_sep(c);
        if (n == 0)
            first[0] = q[0], first[1] = q[1];
        else if (add_line(e, prev, q))
            return -1;
        prev[0] = q[0], prev[1] = q[1];
        n++;
    }
    if (closed && n > 1 && (prev[0] != first[0] || prev[1] != first[1]))
        return add_line(e, prev, first);
    return 0;
}

/* ---- the XML ------------------------------------------------------------------------- */

typedef struct {
    const char *s, *end, *name;
    const char *lpos;         /* where line was counted to */
    int line;
    ob_approx *out;
    ob_err *err;
    xform ctm[SVG_MAX_DEPTH];
    int hidden[SVG_MAX_DEPTH];
    int depth;
} svgrd;

static int line_at(svgrd *r, const char *p)
{
    for (; r->lpos < p; r->lpos++)
        r->line += *r->lpos == '\n';
    return r->line;
}

/* The value of attribute `key` in the tag text [a, b), unquoted, into buf;
 * 1 found, 0 not. */
static int attr(const char *a, const char *b, const char *key, char **val, size_t *len)
{
    const size_t k = strlen(key);
    for (const char *p = a; p + k < b; p++) {
        if (strncmp(p, key, k) != 0 || !strchr(" \t\n\r", p[-1]))
            continue;
        const char *q = p + k;
        while (q < b && strchr(" \t\n\r", *q))
            q++;
        if (q >= b || *q != '=')
            continue;
        q++;
        while (q < b && strchr(" \t\n\r", *q))
            q++;
        if (q >= b || (*q != '"' && *q != '\''))
            continue;
        const char *v = q + 1, *z = memchr(v, *q, (size_t)(b - v));
        if (!z)
            return 0;
        *val = (char *)v;
        *len = (size_t)(z - v);
        return 1;
    }
    return 0;
}

static int is_tag(const char *name, size_t n, const char *const *list)
{
    for (int i = 0; list[i]; i++)
        if (strlen(list[i]) == n && !strncmp(name, list[i], n))
            return 1;
    return 0;
}

static const char *const HIDDEN[] = {"defs", "symbol", "clipPath", "mask", "marker", "pattern", NULL};
static const char *const UNREAD[] = {"text", "image", "use", NULL};
static const char *const SHAPES[] = {"path", "line", "polyline", "polygon", "circle", "ellipse", "rect", NULL};

/* A number attribute of a <line> (0 when absent). */
static int line_coord(const char *a, const char *b, const char *key, scan *c, double *x)
{
    char *v;
    size_t n;
    *x = 0.0;
    if (!attr(a, b, key, &v, &n))
        return 0;
    scan s = *c;
    s.s = v, s.i = 0, s.n = n;
    skip_wsp(&s);
    return number(&s, x);
}

/* The number attributes keys[0..n) of an element into v (0 when absent),
 * have[k] whether each is there; 0 or -1 (a malformed number, named). */
static int coords(const char *a, const char *b, const char *const *keys, int n, scan *c, double *v, int *have)
{
    char key[48], *x;
    size_t len;
    const char *what = c->what;
    int rc = 0;
    for (int k = 0; k < n && rc == 0; k++) {
        snprintf(key, sizeof key, "%s: %s", what, keys[k]);
        c->what = key;
        have[k] = attr(a, b, keys[k], &x, &len);
        if (line_coord(a, b, keys[k], c, &v[k]))
            rc = -1;
        else if (!isfinite(v[k]))
            rc = ob_fail(c->err, "%s:%d: %s: not a finite number", c->name, c->line, key);
    }
    c->what = what;
    return rc;
}

/* An ellipse of radii rx, ry about (cx, cy) as SVG 2 (10.4) makes it a
 * path: from (cx + rx, cy) four quarter arcs of sweep 1, one exact rational
 * quadratic each. */
static int add_ellipse(const emit *e, double cx, double cy, double rx, double ry)
{
    const double p[5][2] = {{cx + rx, cy}, {cx, cy + ry}, {cx - rx, cy}, {cx, cy - ry}, {cx + rx, cy}};
    for (int k = 0; k < 4; k++)
        if (add_arc(e, p[k], rx, ry, 0.0, 0, 1, p[k + 1]))
            return -1;
    return 0;
}

/* A rectangle as SVG 2 (10.2) makes it a path: from (x + rx, y) along the
 * top, its corners quarter arcs of radii rx, ry (none when either is 0),
 * sides of zero length left out. */
static int add_rect(const emit *e, double x, double y, double w, double h, double rx, double ry)
{
    const double X = x + w, Y = y + h;
    const double p[9][2] = {{x + rx, y}, {X - rx, y}, {X, y + ry}, {X, Y - ry}, {X - rx, Y},
                            {x + rx, Y}, {x, Y - ry}, {x, y + ry}, {x + rx, y}};
    for (int k = 0; k < 8; k++) {
        const int corner = k % 2 == 1;
        if (p[k][0] == p[k + 1][0] && p[k][1] == p[k + 1][1])
            continue;
        if (corner ? add_arc(e, p[k], rx, ry, 0.0, 0, 1, p[k + 1]) : add_line(e, p[k], p[k + 1]))
            return -1;
    }
    return 0;
}

/* <circle>, <ellipse> or <rect> (kind 0, 1, 2): its attributes, SVG 2's
 * rules for them (rx or ry alone stands for both, a rect's radii clamped
 * to half its sides; a size of 0 renders nothing: skipped and noted; a
 * negative one is an error), then its path. */
static int basic_shape(const emit *e, int kind, const char *a, const char *b, scan *c)
{
    static const char *const keys[3][6] = {{"cx", "cy", "r"}, {"cx", "cy", "rx", "ry"},
                                           {"x", "y", "width", "height", "rx", "ry"}};
    static const char *const zero[3] = {"zero-size <circle>", "zero-size <ellipse>", "zero-size <rect>"};
    static const int nkeys[3] = {3, 4, 6};
    double v[6];
    int have[6];
    if (coords(a, b, keys[kind], nkeys[kind], c, v, have))
        return -1;
    for (int k = 2; k < nkeys[kind]; k++)
        if (v[k] < 0.0)
            return ob_fail(c->err, "%s:%d: %s: %s: negative (%.17g)", c->name, c->line, c->what, keys[kind][k],
                           v[k]);
    double rx = v[2], ry = kind == 0 ? v[2] : v[3];
    if (kind == 1 && have[2] != have[3])
        rx = ry = have[2] ? v[2] : v[3];
    if (kind == 2) {
        rx = have[4] ? v[4] : have[5] ? v[5] : 0.0;
        ry = have[5] ? v[5] : rx;
        rx = fmin(rx, 0.5 * v[2]);
        ry = fmin(ry, 0.5 * v[3]);
        if (rx == 0.0 || ry == 0.0)
            rx = ry = 0.0;
    }
    const double w = kind == 2 ? v[2] : rx, h = kind == 2 ? v[3] : ry;
    if (w == 0.0 || h == 0.0) {
        ob_approx_note_skip(e->out, zero[kind], e->line);
        return 0;
    }
    return kind == 2 ? add_rect(e, v[0], v[1], v[2], v[3], rx, ry) : add_ellipse(e, v[0], v[1], rx, ry);
}

/* One shape element (tag name [nm, nm + nn), attributes [a, b)). */
static int shape(svgrd *r, const char *nm, size_t nn, const char *a, const char *b, const xform *ctm, int line)
{
    char what[40];
    snprintf(what, sizeof what, "<%.*s>", (int)(nn < 20 ? nn : 20), nm);
    const emit e = {r->name, line, *ctm, r->out, r->err};
    scan c = {NULL, 0, 0, what, r->name, line, r->err};
    char *v;
    size_t n;
    char key[48];
    if (nn == 4 && !strncmp(nm, "path", 4)) {
        if (!attr(a, b, "d", &v, &n))
            return 0;
        snprintf(key, sizeof key, "%s: d", what);
        c.s = v, c.n = n, c.what = key;
        return parse_path(&c, &e);
    }
    if ((nn == 8 && !strncmp(nm, "polyline", 8)) || (nn == 7 && !strncmp(nm, "polygon", 7))) {
        if (!attr(a, b, "points", &v, &n))
            return 0;
        snprintf(key, sizeof key, "%s: points", what);
        c.s = v, c.n = n, c.what = key;
        return parse_points(&c, &e, nn == 7);
    }
    static const char *const basic[] = {"circle", "ellipse", "rect"};
    for (int k = 0; k < 3; k++)
        if (nn == strlen(basic[k]) && !strncmp(nm, basic[k], nn))
            return basic_shape(&e, k, a, b, &c);
    double p[4];
    static const char *const keys[] = {"x1", "y1", "x2", "y2"};
    for (int k = 0; k < 4; k++) {
        snprintf(key, sizeof key, "%s: %s", what, keys[k]);
        c.what = key;
        if (line_coord(a, b, keys[k], &c, &p[k]))
            return -1;
    }
    return add_line(&e, p, p + 2);
}

/* One start tag [t, gt] (t after '<'); 0 or -1. */
static int start_tag(svgrd *r, const char *t, const char *gt)
{
    const char *nm = t;
    while (nm < gt && !strchr(" \t\n\r/>", *nm))
        nm++;
    const size_t nn = (size_t)(nm - t);
    const char *colon = memchr(t, ':', nn);  /* svg:path */
    const char *base = colon ? colon + 1 : t;
    const size_t bn = (size_t)(nm - base);
    const int self = gt > t && gt[-1] == '/', line = line_at(r, t);
    const int hidden = r->hidden[r->depth] || is_tag(base, bn, HIDDEN);
    xform ctm = r->ctm[r->depth];
    char *v;
    size_t n;
    if (attr(nm, gt, "transform", &v, &n)) {
        char what[48];
        snprintf(what, sizeof what, "<%.*s>: transform", (int)(bn < 20 ? bn : 20), base);
        scan c = {v, 0, n, what, r->name, line, r->err};
        xform t2;
        if (parse_transform(&c, &t2))
            return -1;
        ctm = xf_mul(&ctm, &t2);
    }
    int rc = 0;
    if (!hidden && is_tag(base, bn, SHAPES))
        rc = shape(r, base, bn, nm, gt, &ctm, line);
    else if (!hidden && is_tag(base, bn, UNREAD)) {
        char what[24];
        snprintf(what, sizeof what, "<%.*s>", (int)(bn < 20 ? bn : 20), base);
        ob_approx_note_skip(r->out, what, line);
    }
    if (!self) {
        if (r->depth + 1 >= SVG_MAX_DEPTH)
            return ob_fail(r->err, "%s:%d: elements nested deeper than %d", r->name, line, SVG_MAX_DEPTH - 1);
        r->depth++;
        r->ctm[r->depth] = ctm;
        r->hidden[r->depth] = hidden;
    }
    return rc;
}

/* Skips from p past the text `close`; NULL when it never comes. */
static const char *past(const char *p, const char *end, const char *close)
{
    const size_t k = strlen(close);
    for (; p + k <= end; p++)
        if (!memcmp(p, close, k))
            return p + k;
    return NULL;
}

int ob_approx_read_svg(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err)
{
    svgrd *r = calloc(1, sizeof *r);
    if (!r)
        return ob_fail(err, "%s: out of memory", name);
    *r = (svgrd){text, text + len, name, text, 1, out, err, {IDENTITY}, {0}, 0};
    int rc = 0;
    const char *p = text;
    while (rc == 0 && (p = memchr(p, '<', (size_t)(r->end - p))) != NULL) {
        static const char *const opens[] = {"<!--", "<?", "<![CDATA[", "<!"};
        static const char *const closes[] = {"-->", "?>", "]]>", ">"};
        int k = 0;
        while (k < 4 && strncmp(p, opens[k], strlen(opens[k])) != 0)
            k++;
        const char *q = past(p + 1, r->end, k < 4 ? closes[k] : ">");
        if (!q) {
            rc = ob_fail(err, "%s:%d: a markup that is not closed", name, line_at(r, p));
            break;
        }
        if (k == 4 && p[1] == '/')
            r->depth -= r->depth > 0;
        else if (k == 4)
            rc = start_tag(r, p + 1, q - 1);
        p = q;
    }
    free(r);
    return rc;
}
