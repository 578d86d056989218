/*
 * approx_dxf_curves.c - DXF LINE, ARC, CIRCLE, ELLIPSE and LWPOLYLINE as
 * exact Bézier pieces (approx_dxf.h).
 */
#include "host/io/approx_dxf.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/approx_read.h"

/* The single-valued groups, in ob_dxf_ent.g and bit k of ob_dxf_ent.have. */
static const int codes[] = {10, 20, 11, 21, 40, 41, 42, 50, 51, 70, 90, 210, 220, 230};
enum { X0, Y0, X1, Y1, G40, G41, G42, G50, G51, G70, G90, NX, NY, NZ, NCODES };
_Static_assert(sizeof codes / sizeof *codes == NCODES, "one slot per group code");

static const char *const kind_names[] = {"LINE", "ARC", "CIRCLE", "ELLIPSE", "LWPOLYLINE", "POLYLINE"};

const char *ob_dxf_kind_name(ob_dxf_kind kind) { return kind_names[kind]; }

/* A decimal number as DXF writes them: a sign, digits with at most one
 * point, an exponent; not C's hex floats, inf or nan, which strtod takes. */
static int decimal(const char *s)
{
    s += *s == '+' || *s == '-';
    const size_t i = strspn(s, "0123456789"), f = s[i] == '.' ? strspn(s + i + 1, "0123456789") : 0;
    if (i + f == 0)
        return 0;
    s += i + (s[i] == '.') + f;
    if (*s == 'e' || *s == 'E') {
        s += 1 + (s[1] == '+' || s[1] == '-');
        const size_t e = strspn(s, "0123456789");
        if (e == 0)
            return 0;
        s += e;
    }
    return *s == '\0';
}

int ob_dxf_number(const char *val, int code, int line, const char *name, double *x, ob_err *err)
{
    char *end;
    *x = strtod(val, &end);
    if (!val[0] || *end)
        return ob_fail(err, "%s:%d: group %d: '%.40s' is not a number", name, line, code, val);
    if (!decimal(val))
        return ob_fail(err, "%s:%d: group %d: '%.40s' is not a decimal number (DXF writes no others)", name, line,
                       code, val);
    if (!isfinite(*x))
        return ob_fail(err, "%s:%d: group %d: '%.40s' is out of range", name, line, code, val);
    return 0;
}

int ob_dxf_kind_of(const char *name)
{
    for (int k = 0; k < (int)(sizeof kind_names / sizeof *kind_names); k++)
        if (strcmp(name, kind_names[k]) == 0)
            return k;
    return -1;
}

void ob_dxf_ent_start(ob_dxf_ent *e, ob_dxf_kind kind, int line)
{
    memset(e, 0, sizeof *e);
    e->kind = kind;
    e->line = line;
    e->announced = -1;
}

void ob_dxf_ent_free(ob_dxf_ent *e)
{
    free(e->v);
    memset(e, 0, sizeof *e);
}

static int slot_of(int code)
{
    for (int k = 0; k < NCODES; k++)
        if (codes[k] == code)
            return k;
    return -1;
}

/* Appends vertex (x, 0) with bulge 0 at line to e; 0, or -1 with err. */
static int add_vertex(ob_dxf_ent *e, double x, int line, const char *name, ob_err *err)
{
    if (e->nv == e->cap) {
        const int cap = e->cap ? 2 * e->cap : 16;
        ob_dxf_vertex *v = cap < (1 << 24) ? realloc(e->v, (size_t)cap * sizeof *v) : NULL;
        if (!v)
            return ob_fail(err, "%s: out of memory", name);
        e->v = v;
        e->cap = cap;
    }
    e->v[e->nv++] = (ob_dxf_vertex){x, 0.0, 0.0, line, 0, {0}};
    return 0;
}

/* Group code of vertex slot k (ob_dxf_vertex.at). */
static const int vertex_codes[] = {10, 20, 42, 70};

/* Records that the last vertex has group `code` at line: an error when it
 * had it already (a value lost, or a vertex without its 10). */
static int vertex_once(ob_dxf_ent *e, int code, int line, const char *name, ob_err *err)
{
    ob_dxf_vertex *v = &e->v[e->nv - 1];
    for (int k = 0; k < 4; k++)
        if (vertex_codes[k] == code) {
            if (v->at[k])
                return ob_fail(err, "%s:%d: group %d given twice for one vertex (first at line %d)", name, line, code,
                               v->at[k]);
            v->at[k] = line;
        }
    return 0;
}

/* An LWPOLYLINE vertex group: 10 starts a vertex, 20 and 42 set its y and bulge. */
static int vertex_group(ob_dxf_ent *e, int code, double x, int line, const char *name, ob_err *err)
{
    if (code == 10)
        return add_vertex(e, x, line, name, err) || vertex_once(e, code, line, name, err) ? -1 : 0;
    if (e->nv == 0)
        return ob_fail(err, "%s:%d: LWPOLYLINE: group %d before the first vertex (group 10)", name, line, code);
    if (vertex_once(e, code, line, name, err))
        return -1;
    if (code == 20)
        e->v[e->nv - 1].y = x;
    else
        e->v[e->nv - 1].bulge = x;
    return 0;
}

int ob_dxf_ent_vertex(ob_dxf_ent *e, int line, const char *name, ob_err *err)
{
    e->in_vertex = 1;
    return add_vertex(e, 0.0, line, name, err);
}

/* A group of a POLYLINE's VERTEX: 10, 20, 42 its point and bulge, 70 its
 * flags; the others (widths, z) are not the curve. */
static int polyvertex_group(ob_dxf_ent *e, int code, double x, int line, const char *name, ob_err *err)
{
    ob_dxf_vertex *v = &e->v[e->nv - 1];
    if (vertex_once(e, code, line, name, err))
        return -1;
    switch (code) {
    case 10: v->x = x; break;
    case 20: v->y = x; break;
    case 42: v->bulge = x; break;
    case 70: v->flags = (int)x; break;
    default: break;
    }
    return 0;
}

int ob_dxf_ent_group(ob_dxf_ent *e, int code, const char *val, int line, const char *name, ob_err *err)
{
    const int k = slot_of(code);
    if (k < 0 || (e->kind == OB_DXF_LWPOLYLINE && (code == 40 || code == 41)))
        return 0; /* layer, colour, thickness, widths (per vertex), ...: not the curve */
    double x;
    if (ob_dxf_number(val, code, line, name, &x, err))
        return -1;
    if (e->kind == OB_DXF_LWPOLYLINE && (code == 10 || code == 20 || code == 42))
        return vertex_group(e, code, x, line, name, err);
    if (e->kind == OB_DXF_POLYLINE && e->in_vertex)
        return polyvertex_group(e, code, x, line, name, err);
    if (e->kind == OB_DXF_POLYLINE && (code == 10 || code == 20 || code == 42))
        return 0; /* the header's point is the elevation, no vertex */
    if (e->have & 1 << k) /* the entity takes one: which value would be meant? */
        return ob_fail(err, "%s:%d: group %d given twice in one %s (first at line %d)", name, line, code,
                       kind_names[e->kind], e->gline[k]);
    e->g[k] = x;
    e->gline[k] = line;
    e->have |= 1 << k;
    return 0;
}

/* ---- pieces ------------------------------------------------------------------ */

/* The map of a circle or ellipse: point(a) = c + u cos a + v sin a; sx = -1
 * mirrors x afterwards (an object coordinate system of extrusion -z). */
typedef struct {
    double c[2], u[2], v[2], sx;
} conic;

static void conic_point(const conic *f, double a, double p[2])
{
    p[0] = f->c[0] + f->u[0] * cos(a) + f->v[0] * sin(a);
    p[1] = f->c[1] + f->u[1] * cos(a) + f->v[1] * sin(a);
}

static int add_piece(ob_approx *out, const ob_bez *b, int line, const char *name, ob_err *err)
{
    ob_apiece *p = ob_approx_add(out);
    if (!p)
        return ob_fail(err, "%s: out of memory", name);
    p->line = line;
    p->fit_first = 1;
    p->approx = *b;
    return ob_approx_check_piece(p, out->n - 1, name, err);
}

/* The pieces of the arc of f from angle a0 through sweep (signed, radians,
 * |sweep| <= 2 pi), at most 90 degrees each, from p0 to p1 (on the arc,
 * taken as given so that joints with neighbours are exact). */
static int arc_pieces(const conic *f, double a0, double sweep, const double p0[2], const double p1[2], int line,
                      const char *name, ob_approx *out, ob_err *err)
{
    const int n = (int)fmax(1.0, ceil(fabs(sweep) / (0.5 * OB_PI) - 1e-9));
    const double step = sweep / n, w = cos(0.5 * fabs(step));
    double a[2];
    for (int i = 0; i < n; i++) {
        double q0[2], q2[2], m[2];
        if (i == 0)
            q0[0] = p0[0], q0[1] = p0[1];
        else
            q0[0] = a[0], q0[1] = a[1];
        if (i == n - 1)
            q2[0] = p1[0], q2[1] = p1[1];
        else
            conic_point(f, a0 + (i + 1) * step, q2);
        conic_point(f, a0 + (i + 0.5) * step, m);
        for (int k = 0; k < 2; k++) /* the tangents' meeting point */
            m[k] = f->c[k] + (m[k] - f->c[k]) / w;
        ob_bez b = {0};
        b.deg = 2;
        ob_bez_set(&b, 0, f->sx * q0[0], q0[1], 1.0);
        ob_bez_set(&b, 1, f->sx * m[0], m[1], w);
        ob_bez_set(&b, 2, f->sx * q2[0], q2[1], 1.0);
        if (add_piece(out, &b, line, name, err) != 0)
            return -1;
        a[0] = q2[0], a[1] = q2[1];
    }
    return 0;
}

/* The whole or part of the conic from a0 through sweep (> 0). */
static int conic_pieces(const conic *f, double a0, double sweep, int line, const char *name, ob_approx *out,
                        ob_err *err)
{
    double p0[2], p1[2];
    conic_point(f, a0, p0);
    if (sweep >= 2.0 * OB_PI * (1.0 - 1e-15))
        p1[0] = p0[0], p1[1] = p0[1]; /* closed */
    else
        conic_point(f, a0 + sweep, p1);
    return arc_pieces(f, a0, sweep, p0, p1, line, name, out, err);
}

/* x to -x under an extrusion of -z (sx = -1), +1 under +z; 0 when the
 * entity is not in the XY plane. */
static double mirror_of(const ob_dxf_ent *e)
{
    const double nx = e->have & 1 << NX ? e->g[NX] : 0.0, ny = e->have & 1 << NY ? e->g[NY] : 0.0,
                 nz = e->have & 1 << NZ ? e->g[NZ] : 1.0;
    if (!(fabs(nx) <= 1e-12 * fabs(nz) && fabs(ny) <= 1e-12 * fabs(nz)) || nz == 0.0)
        return 0.0;
    return nz < 0.0 ? -1.0 : 1.0;
}

/* The groups in `need` (bits), or an error naming the first missing. */
static int need(const ob_dxf_ent *e, int bits, const char *name, ob_err *err)
{
    for (int k = 0; k < NCODES; k++)
        if (bits & 1 << k && !(e->have & 1 << k))
            return ob_fail(err, "%s:%d: %s without group %d", name, e->line, kind_names[e->kind], codes[k]);
    return 0;
}

static int line_pieces(const ob_dxf_ent *e, const char *name, ob_approx *out, ob_err *err)
{
    if (need(e, 1 << X0 | 1 << Y0 | 1 << X1 | 1 << Y1, name, err))
        return -1;
    if (e->g[X0] == e->g[X1] && e->g[Y0] == e->g[Y1]) {
        ob_approx_note_skip_why(out, "LINE of length 0", "its two points are one", e->line);
        return 0;
    }
    const double xy[2][2] = {{e->g[X0], e->g[Y0]}, {e->g[X1], e->g[Y1]}};
    ob_bez b;
    ob_bez_from_points(&b, 1, xy);
    return add_piece(out, &b, e->line, name, err);
}

/* ARC (counterclockwise from group 50 to 51, degrees) and CIRCLE. */
static int circle_pieces(const ob_dxf_ent *e, double sx, const char *name, ob_approx *out, ob_err *err)
{
    if (need(e, 1 << X0 | 1 << Y0 | 1 << G40, name, err))
        return -1;
    const double r = e->g[G40];
    if (!(r > 0.0))
        return ob_fail(err, "%s:%d: %s of radius %.17g (it must be positive)", name, e->line, kind_names[e->kind], r);
    const conic f = {{e->g[X0], e->g[Y0]}, {r, 0.0}, {0.0, r}, sx};
    double a0 = 0.0, sweep = 360.0;
    if (e->kind == OB_DXF_ARC) {
        a0 = e->have & 1 << G50 ? e->g[G50] : 0.0;
        sweep = fmod((e->have & 1 << G51 ? e->g[G51] : 0.0) - a0, 360.0);
        sweep += sweep <= 0.0 ? 360.0 : 0.0; /* equal angles: the whole circle */
    }
    return conic_pieces(&f, a0 * (OB_PI / 180.0), sweep * (OB_PI / 180.0), e->line, name, out, err);
}

/* ELLIPSE: centre 10/20, end of the major axis 11/21 (from the centre),
 * minor over major 40, parameters 41 to 42 (radians); world coordinates,
 * the minor axis on the extrusion's left of the major one. */
static int ellipse_pieces(const ob_dxf_ent *e, double sx, const char *name, ob_approx *out, ob_err *err)
{
    if (need(e, 1 << X0 | 1 << Y0 | 1 << X1 | 1 << Y1 | 1 << G40, name, err))
        return -1;
    const double q = e->g[G40], mx = e->g[X1], my = e->g[Y1];
    if (!(q > 0.0) || (mx == 0.0 && my == 0.0))
        return ob_fail(err, "%s:%d: ELLIPSE with axis ratio %.17g and major axis (%.17g, %.17g) (a positive ratio and "
                       "a major axis of nonzero length)", name, e->line, q, mx, my);
    const conic f = {{e->g[X0], e->g[Y0]}, {mx, my}, {-sx * q * my, sx * q * mx}, 1.0};
    const double a0 = e->have & 1 << G41 ? e->g[G41] : 0.0;
    double sweep = fmod((e->have & 1 << G42 ? e->g[G42] : 2.0 * OB_PI) - a0, 2.0 * OB_PI);
    sweep += sweep <= 1e-15 ? 2.0 * OB_PI : 0.0;
    return conic_pieces(&f, a0, sweep, e->line, name, out, err);
}

/* An arc of at most 90 degrees from P to Q of bulge b (object
 * coordinates; x times sx) as one rational quadratic, built from the chord
 * alone: no centre, whose distance grows as 1/b and whose use cancels when
 * b is small.  The middle control point is where the end tangents meet:
 * the chord's middle moved right of P->Q (left when b < 0) by half the
 * chord times tan(theta/2) = 2b / (1 - b^2), that is by (dy, -dx) b /
 * (1 - b^2); its weight cos(theta/2) = (1 - b^2) / (1 + b^2) (theta = 4
 * atan b).  As b goes to 0 this goes continuously to the chord. */
static int chord_arc(const double P[2], const double Q[2], double b, double sx, int line, const char *name,
                     ob_approx *out, ob_err *err)
{
    const double dx = Q[0] - P[0], dy = Q[1] - P[1], bb = b * b, s = b / (1.0 - bb);
    ob_bez z = {0};
    z.deg = 2;
    ob_bez_set(&z, 0, sx * P[0], P[1], 1.0);
    ob_bez_set(&z, 1, sx * (0.5 * (P[0] + Q[0]) + dy * s), 0.5 * (P[1] + Q[1]) - dx * s, (1.0 - bb) / (1.0 + bb));
    ob_bez_set(&z, 2, sx * Q[0], Q[1], 1.0);
    return add_piece(out, &z, line, name, err);
}

/* The chord P->Q as one piece of degree 1 (x times sx). */
static int chord_line(const double P[2], const double Q[2], double sx, int line, const char *name, ob_approx *out,
                      ob_err *err)
{
    const double xy[2][2] = {{sx * P[0], P[1]}, {sx * Q[0], Q[1]}};
    ob_bez s;
    ob_bez_from_points(&s, 1, xy);
    return add_piece(out, &s, line, name, err);
}

/* One polyline segment from vertex p to q with p's bulge b.  An arc of
 * more than 90 degrees is cut in n <= 4 equal ones; their joints, at
 * angle a from P of the arc's theta, are P + sin(a/2) / sin(theta/2) times
 * the chord turned by (a - theta)/2, sin(theta/2) = 2 / (b + 1/b): no
 * centre either, and the angles are large there, so nothing cancels. */
static int bulge_piece(const ob_dxf_vertex *p, const ob_dxf_vertex *q, double sx, const char *name, ob_approx *out,
                       ob_err *err)
{
    const double P[2] = {p->x, p->y}, Q[2] = {q->x, q->y}, dx = Q[0] - P[0], dy = Q[1] - P[1], b = p->bulge;
    if (dx == 0.0 && dy == 0.0) {
        ob_approx_note_skip_why(out, "polyline segment of length 0", "its two vertices are one", p->line);
        return 0;
    }
    /* a sagitta (|b| L / 2) under the round-off of the vertices: the arc
     * and its chord are the same doubles */
    const double scale = fmax(fmax(fabs(P[0]), fabs(P[1])), fmax(fabs(Q[0]), fabs(Q[1])));
    if (fabs(b) * hypot(dx, dy) <= DBL_EPSILON * scale || b == 0.0)
        return chord_line(P, Q, sx, p->line, name, out, err);
    const double theta = 4.0 * atan(b);
    const int n = (int)fmax(1.0, ceil(fabs(theta) / (0.5 * OB_PI) - 1e-9));
    if (n == 1)
        return chord_arc(P, Q, b, sx, p->line, name, out, err);
    const double bs = tan(theta / (4.0 * n)), sh = 2.0 / (b + 1.0 / b);
    double K0[2] = {P[0], P[1]};
    for (int k = 1; k <= n; k++) {
        const double a = theta * k / n, f = sin(0.5 * a) / sh, c = cos(0.5 * (a - theta)), s = sin(0.5 * (a - theta));
        double K1[2] = {Q[0], Q[1]};
        if (k < n)
            K1[0] = P[0] + f * (c * dx - s * dy), K1[1] = P[1] + f * (s * dx + c * dy);
        if (chord_arc(K0, K1, bs, sx, p->line, name, out, err) != 0)
            return -1;
        K0[0] = K1[0], K0[1] = K1[1];
    }
    return 0;
}

/* Leaves out a POLYLINE's vertices of flag 16 (a spline frame's control
 * points: not drawn). */
static void drop_frame_vertices(ob_dxf_ent *e)
{
    int n = 0;
    for (int i = 0; i < e->nv; i++)
        if (!(e->v[i].flags & 16))
            e->v[n++] = e->v[i];
    e->nv = n;
}

static int polyline_pieces(ob_dxf_ent *e, double sx, const char *name, ob_approx *out, ob_err *err)
{
    const long flags = e->have & 1 << G70 ? (long)e->g[G70] : 0;
    if (e->kind == OB_DXF_POLYLINE) {
        if (flags & (8 | 16 | 64)) {
            ob_approx_note_skip_why(out, "POLYLINE 3D or mesh", "flag 8, 16 or 64 of group 70: no planar curve",
                                    e->line);
            return 0;
        }
        drop_frame_vertices(e);
        if (e->nv < 2)
            return ob_fail(err, "%s:%d: POLYLINE with %d VERTEX entities (at least 2, SEQEND after them)", name,
                           e->line, e->nv);
    }
    const int closed = (int)(flags & 1);
    if (e->nv < 2 || (e->announced >= 0 && e->announced != e->nv))
        return ob_fail(err, "%s:%d: LWPOLYLINE with %d vertices (group 90 announces %d; at least 2)", name, e->line,
                       e->nv, e->announced);
    for (int i = 0; i + 1 < e->nv + closed; i++)
        if (bulge_piece(&e->v[i], &e->v[(i + 1) % e->nv], sx, name, out, err) != 0)
            return -1;
    return 0;
}

int ob_dxf_ent_pieces(ob_dxf_ent *e, const char *name, ob_approx *out, ob_err *err)
{
    if (e->have & 1 << G90) {
        const double n = e->g[G90];
        e->announced = n >= 0 && n < 1e9 && n == (int)n ? (int)n : -2;
    }
    if (e->kind == OB_DXF_LINE)
        return line_pieces(e, name, out, err);
    const double sx = mirror_of(e);
    if (sx == 0.0) {
        char what[24], why[96];
        snprintf(what, sizeof what, "%s off the XY plane", kind_names[e->kind]);
        snprintf(why, sizeof why, "extrusion %.6g, %.6g, %.6g: another plane", e->g[NX], e->g[NY],
                 e->have & 1 << NZ ? e->g[NZ] : 1.0);
        ob_approx_note_skip_why(out, what, why, e->line);
        return 0;
    }
    switch (e->kind) {
    case OB_DXF_ARC:
    case OB_DXF_CIRCLE: return circle_pieces(e, sx, name, out, err);
    case OB_DXF_ELLIPSE: return ellipse_pieces(e, sx, name, out, err);
    default: return polyline_pieces(e, sx, name, out, err);
    }
}
