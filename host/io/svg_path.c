/*
 * svg_path.c - SVG path data and shapes as exact Bézier pieces (svg_read.h).
 *
 * Path data follows the grammar of SVG 1.1 8.3.9: M L H V C S Q T A Z, each
 * absolute or relative, implicit repetition, L after M.  A line is a piece
 * of degree 1, a quadratic or cubic its own piece (S and T reflect the
 * previous control point), an elliptical arc exact rational quadratic pieces
 * of at most 90 degrees each (add_arc), Z a line back to the subpath's start
 * when it is elsewhere.  Neighbouring pieces share their end points bit for
 * bit.  Zero-length segments are skipped and noted.  scripts/svgpath.py is
 * the same code in Python, for scripts/svg2curves.py.
 */
#include "host/io/svg_read.h"

#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/approx_read.h"

/* ---- scanning an attribute's text ---- */

int ob_svgr_fail(ob_svgr_scan *c, const char *why)
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

void ob_svgr_skip_wsp(ob_svgr_scan *c)
{
    while (c->i < c->n && strchr(" \t\n\r\f", c->s[c->i]) && c->s[c->i])
        c->i++;
}

/* Whitespace, then at most one comma, then whitespace. */
void ob_svgr_skip_sep(ob_svgr_scan *c)
{
    ob_svgr_skip_wsp(c);
    if (c->i < c->n && c->s[c->i] == ',') {
        c->i++;
        ob_svgr_skip_wsp(c);
    }
}

static int at_number(const ob_svgr_scan *c)
{
    if (c->i >= c->n)
        return 0;
    const char ch = c->s[c->i];
    return isdigit((unsigned char)ch) || ch == '.' || ch == '+' || ch == '-';
}

/* A number of the SVG grammar ([+-] digits [. digits] [e [+-] digits]). */
int ob_svgr_number(ob_svgr_scan *c, double *x)
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
        return ob_svgr_fail(c, "expected a number");
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
        return ob_svgr_fail(c, "a number too long");
    memcpy(buf, c->s + c->i, j - c->i);
    buf[j - c->i] = '\0';
    *x = strtod(buf, NULL);
    if (!isfinite(*x))
        return ob_svgr_fail(c, "a number out of range");
    c->i = j;
    return 0;
}

/* An arc flag: one character 0 or 1. */
static int flag(ob_svgr_scan *c, double *x)
{
    if (c->i >= c->n || (c->s[c->i] != '0' && c->s[c->i] != '1'))
        return ob_svgr_fail(c, "expected an arc flag (0 or 1)");
    *x = c->s[c->i++] - '0';
    return 0;
}

/* ---- pieces ---- */

/* Appends the piece of degree deg with Euclidean control points p and
 * weights w (NULL: all 1), mapped by e->ctm and y = -y; a piece whose
 * points all coincide is skipped and noted.  0 or -1. */
static int add_piece(const ob_svgr_emit *e, int deg, const double (*p)[2], const double *w)
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

int ob_svgr_line(const ob_svgr_emit *e, const double p0[2], const double p1[2])
{
    const double p[2][2] = {{p0[0], p0[1]}, {p1[0], p1[1]}};
    return add_piece(e, 1, p, NULL);
}

/* One piece of the arc in the frame where the ellipse is the unit circle,
 * points u[3][2] relative to the chord's midpoint mid, mapped back by the
 * ellipse's axes (rx, ry, rotated by cos cp, sin sp); the piece's ends
 * where q0 and q2 say (NULL: from u), its middle weight w1. */
typedef struct {
    double mid[2], rx, ry, cp, sp;
} arc_frame;

static void arc_point(const arc_frame *f, const double u[2], double q[2])
{
    q[0] = f->mid[0] + f->cp * f->rx * u[0] - f->sp * f->ry * u[1];
    q[1] = f->mid[1] + f->sp * f->rx * u[0] + f->cp * f->ry * u[1];
}

/* The arc of SVG's endpoint form from p0 to p1 (SVG 1.1 F.6.5, F.6.6) as
 * rational quadratic pieces of at most 90 degrees, computed in the frame
 * where the ellipse is the unit circle and the chord's midpoint the origin:
 * the half chord (ux, uy) of length s = sin a, a half the small arc's angle,
 * and the centre at distance c = cos a = sqrt(1 - ux^2 - uy^2) across it.
 * An arc of one piece (a <= 45 degrees) is built from the chord alone, its
 * middle control point s^2 / c off the midpoint (no far-away centre whose
 * round-off would swamp a near-straight arc); when that offset is below
 * round-off against the half chord, the arc is its chord, a line.  Radii
 * too small are scaled up (s > 1: the half ellipse on the chord); a radius
 * 0 makes a line (F.6.2). */
static int add_arc(const ob_svgr_emit *e, const double p0[2], double rx, double ry, double phi_deg, int large,
                   int sweep, const double p1[2])
{
    if (p0[0] == p1[0] && p0[1] == p1[1])
        return 0; /* SVG: an arc to its own start is no arc */
    rx = fabs(rx), ry = fabs(ry);
    if (rx == 0.0 || ry == 0.0)
        return ob_svgr_line(e, p0, p1);
    const double phi = fmod(phi_deg, 360.0) * (OB_PI / 180.0);
    arc_frame f = {{0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1])}, rx, ry, cos(phi), sin(phi)};
    const double dx2 = 0.5 * (p0[0] - p1[0]), dy2 = 0.5 * (p0[1] - p1[1]);
    double ux = (f.cp * dx2 + f.sp * dy2) / rx, uy = (-f.sp * dx2 + f.cp * dy2) / ry;
    double s = hypot(ux, uy);
    if (s == 0.0)
        return ob_svgr_line(e, p0, p1); /* radii beyond the chord by 2^1000: straight */
    if (s >= 1.0) {
        f.rx *= s, f.ry *= s, ux /= s, uy /= s, s = 1.0;
    }
    /* c^2 = 1 - s^2 from the half chord's parts: exactly 1/2 for a quarter
     * of a circle, so its weight is cos(pi/4) rounded once */
    const double c = s == 1.0 ? 0.0 : sqrt(fmax(0.0, 1.0 - ux * ux - uy * uy)), sgn = large != sweep ? 1.0 : -1.0;
    const double theta = large ? 2.0 * OB_PI - 2.0 * atan2(s, c) : 2.0 * atan2(s, c);
    const int n = (int)fmax(1.0, ceil(theta / (0.5 * OB_PI) - 1e-9));
    if (n == 1) {
        const double u1[2] = {-sgn * uy * s / c, sgn * ux * s / c};
        double q[3][2] = {{p0[0], p0[1]}, {0, 0}, {p1[0], p1[1]}};
        arc_point(&f, u1, q[1]);
        if (hypot(q[1][0] - f.mid[0], q[1][1] - f.mid[1]) <= DBL_EPSILON * hypot(dx2, dy2))
            return ob_svgr_line(e, p0, p1);
        const double w[3] = {1.0, c, 1.0};
        return add_piece(e, 2, (const double(*)[2])q, w);
    }
    const double cu[2] = {sgn * c * uy / s, -sgn * c * ux / s}; /* the centre */
    const double t1 = atan2(uy - cu[1], ux - cu[0]), h = 0.5 * (sweep ? theta : -theta) / n;
    const double w[3] = {1.0, cos(h), 1.0};
    double prev[2] = {p0[0], p0[1]};
    for (int i = 0; i < n; i++) {
        const double a0 = t1 + 2.0 * h * i;
        const double u1[2] = {cu[0] + cos(a0 + h) / cos(h), cu[1] + sin(a0 + h) / cos(h)};
        const double u2[2] = {cu[0] + cos(a0 + 2.0 * h), cu[1] + sin(a0 + 2.0 * h)};
        double q[3][2] = {{prev[0], prev[1]}, {0, 0}, {p1[0], p1[1]}};
        arc_point(&f, u1, q[1]);
        if (i < n - 1)
            arc_point(&f, u2, q[2]);
        if (add_piece(e, 2, (const double(*)[2])q, w))
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
static int args(ob_svgr_scan *c, const char *kinds, double *a)
{
    for (int k = 0; kinds[k]; k++) {
        if (k)
            ob_svgr_skip_sep(c);
        if ((kinds[k] == 'f' ? flag(c, &a[k]) : ob_svgr_number(c, &a[k])) != 0)
            return -1;
    }
    return 0;
}

/* Executes one command (upper case up, relative rel) with arguments a. */
static int command(const ob_svgr_emit *e, pen *p, char up, int rel, const double *a)
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
        rc = ob_svgr_line(e, q[0], q[1]);
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
            rc = ob_svgr_line(e, q[0], q[1]);
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
int ob_svgr_path(ob_svgr_scan *c, const ob_svgr_emit *e)
{
    pen p = {{0, 0}, {0, 0}, {0, 0}, 0};
    char cmd = 0;
    ob_svgr_skip_wsp(c);
    while (c->i < c->n) {
        const char ch = c->s[c->i];
        const char up = (char)toupper((unsigned char)ch);
        if (isalpha((unsigned char)ch)) {
            if (!kinds_of(up))
                return ob_svgr_fail(c, "not a path command (M L H V C S Q T A Z, or lower case)");
            if (!cmd && up != 'M')
                return ob_svgr_fail(c, "path data must begin with M or m");
            cmd = ch;
            c->i++;
            ob_svgr_skip_wsp(c);
        } else if (!cmd || toupper((unsigned char)cmd) == 'Z' || !at_number(c)) {
            return ob_svgr_fail(c, cmd ? "expected a command" : "path data must begin with M or m");
        }
        const char cu = (char)toupper((unsigned char)cmd);
        double a[7];
        if (args(c, kinds_of(cu), a) || command(e, &p, cu, islower((unsigned char)cmd), a))
            return -1;
        if (cu == 'M')
            cmd = cmd == 'm' ? 'l' : 'L';  /* pairs after a moveto are linetos */
        if (cu != 'Z')
            ob_svgr_skip_sep(c);
        else
            ob_svgr_skip_wsp(c);
    }
    return 0;
}

/* The points attribute of a polyline (closed 0) or polygon (closed 1). */
int ob_svgr_points(ob_svgr_scan *c, const ob_svgr_emit *e, int closed)
{
    double first[2] = {0, 0}, prev[2] = {0, 0}, q[2];
    int n = 0;
    ob_svgr_skip_wsp(c);
    while (c->i < c->n) {
        if (ob_svgr_number(c, &q[0]))
            return -1;
        ob_svgr_skip_sep(c);
        if (ob_svgr_number(c, &q[1]))
            return -1;
        ob_svgr_skip_sep(c);
        if (n == 0)
            first[0] = q[0], first[1] = q[1];
        else if (ob_svgr_line(e, prev, q))
            return -1;
        prev[0] = q[0], prev[1] = q[1];
        n++;
    }
    if (closed && n > 1 && (prev[0] != first[0] || prev[1] != first[1]))
        return ob_svgr_line(e, prev, first);
    return 0;
}

/* An ellipse of radii rx, ry about (cx, cy) as SVG 2 (10.4) makes it a
 * path: from (cx + rx, cy) four quarter arcs of sweep 1, one exact rational
 * quadratic each. */
int ob_svgr_ellipse(const ob_svgr_emit *e, double cx, double cy, double rx, double ry)
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
int ob_svgr_rect(const ob_svgr_emit *e, double x, double y, double w, double h, double rx, double ry)
{
    const double X = x + w, Y = y + h;
    const double p[9][2] = {{x + rx, y}, {X - rx, y}, {X, y + ry}, {X, Y - ry}, {X - rx, Y},
                            {x + rx, Y}, {x, Y - ry}, {x, y + ry}, {x + rx, y}};
    for (int k = 0; k < 8; k++) {
        const int corner = k % 2 == 1;
        if (p[k][0] == p[k + 1][0] && p[k][1] == p[k + 1][1])
            continue;
        if (corner ? add_arc(e, p[k], rx, ry, 0.0, 0, 1, p[k + 1]) : ob_svgr_line(e, p[k], p[k + 1]))
            return -1;
    }
    return 0;
}

