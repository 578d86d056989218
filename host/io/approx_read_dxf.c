/*
 * approx_read_dxf.c - the SPLINE entities of a DXF file (ASCII DXF, any
 * version that has SPLINE: R13 / AC1012 and later) as Bézier pieces for
 * `measure`.  Each SPLINE (degree, knots 40, weights 41, control points
 * 10/20) is cut into its Bézier segments by knot insertion (bspline.h); a
 * SPLINE given only by fit points (11/21) is refused, since its curve
 * depends on the writer's interpolation.  LINE, ARC, CIRCLE, ELLIPSE,
 * LWPOLYLINE and POLYLINE (with its VERTEX entities, to SEQEND) are read as
 * exact pieces too (approx_dxf.h).  Other entities (TEXT, HATCH, INSERT,
 * ...) are skipped and noted in the
 * approximation (ob_approx_note_skip: type, count, first line), which
 * measure names on stderr.  A 999 comment "offbench piece K base
 * segment S ..." right before a SPLINE of one Bézier segment is its base
 * link (export_dxf.c); a 999 comment anywhere else is a comment too, and
 * never ends the entity it stands in.  Only the ENTITIES section is read
 * (a file of bare entities, without sections, too): splines of block
 * definitions are not the drawing's curves.  What the reader would have
 * to guess at is refused at FILE:LINE: a line over DXF's longest string
 * (2049 characters), a NUL byte, a value that is not a decimal number, a
 * group given twice where one is taken.  An entity's z: see zinfo.
 */
#include "host/io/approx_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "host/io/approx_dxf.h"
#include "methods/core/bspline.h"

/* DXF_MAX_LINE: the longest string DXF allows (2049 bytes, R2007 and
 * later); a longer line is refused, not cut into another value. */
enum { DXF_MAX_CTRL = 100000, DXF_MAX_LINE = 2049 };

typedef struct {
    const char *s, *end, *name;
    int line;          /* line of the last value read */
    int code;
    char val[DXF_MAX_LINE + 1];
} dxfrd;

/* Next (code, value) pair; 1 at the end, 0, or -1 with err. */
static int next_pair(dxfrd *r, ob_err *err)
{
    char buf[2][DXF_MAX_LINE + 1];
    for (int k = 0; k < 2; k++) {
        if (r->s >= r->end)
            return k == 0 ? 1 : (ob_fail(err, "%s:%d: group code without a value", r->name, r->line), -1);
        const char *nl = memchr(r->s, '\n', (size_t)(r->end - r->s));
        size_t n = nl ? (size_t)(nl - r->s) : (size_t)(r->end - r->s);
        const char *a = r->s;
        r->s = nl ? nl + 1 : r->end;
        r->line++;
        while (n && (a[n - 1] == '\r' || a[n - 1] == ' ' || a[n - 1] == '\t'))
            n--;
        while (n && (*a == ' ' || *a == '\t'))
            a++, n--;
        if (n >= sizeof buf[k]) /* cut, it would be another value */
            return ob_fail(err, "%s:%d: a line of %zu characters (at most %zu)", r->name, r->line, n,
                           sizeof buf[k] - 1);
        if (memchr(a, '\0', n)) /* C's strings would end there: another value too */
            return ob_fail(err, "%s:%d: a NUL byte", r->name, r->line);
        memcpy(buf[k], a, n);
        buf[k][n] = '\0';
    }
    char *e;
    const long c = strtol(buf[0], &e, 10);
    if (!buf[0][0] || *e || c < 0 || c > 1071) {
        ob_fail(err, "%s:%d: expected a DXF group code (a whole number), got '%.40s'", r->name, r->line - 1,
                buf[0]);
        return -1;
    }
    r->code = (int)c;
    memcpy(r->val, buf[1], sizeof r->val);
    return 0;
}

typedef struct {
    int line, deg, flags, nk, nc;
    int nknots, nw, npts, nfit;
    double *knots, *w, (*pts)[3];
    int at[5];   /* lines of its groups 70 to 74, which it takes once (0: not yet) */
    int y_at;    /* line of the last control point's 20 (0: not yet) */
} spline;

static int num(dxfrd *r, double *x, ob_err *err)
{
    return ob_dxf_number(r->val, r->code, r->line, r->name, x, err);
}

/* A SPLINE's flags, degree or counts (70 to 74): a whole number, given
 * once (a second would leave the reader to pick one); 0, or -1 with err. */
static int header_group(const dxfrd *r, spline *sp, double x, ob_err *err)
{
    if (!(x >= 0 && x <= DXF_MAX_CTRL && x == (int)x))
        return ob_fail(err, "%s:%d: group %d: '%.40s' is not a whole number from 0 to %d", r->name, r->line, r->code,
                       r->val, DXF_MAX_CTRL);
    if (sp->at[r->code - 70])
        return ob_fail(err, "%s:%d: group %d given twice in one SPLINE (first at line %d)", r->name, r->line, r->code,
                       sp->at[r->code - 70]);
    sp->at[r->code - 70] = r->line;
    return 0;
}

/* One group of a SPLINE into sp. */
static int spline_group(dxfrd *r, spline *sp, ob_err *err)
{
    double x = 0.0;
    if (r->code == 71 || r->code == 70 || r->code == 72 || r->code == 73 || r->code == 74 || r->code == 40 ||
        r->code == 41 || r->code == 10 || r->code == 20)
        if (num(r, &x, err))
            return -1;
    const int cap = sp->nc > 0 ? sp->nc : 0, kcap = sp->nk > 0 ? sp->nk : 0;
    if (r->code >= 70 && r->code <= 74 && header_group(r, sp, x, err))
        return -1;
    switch (r->code) {
    case 70: sp->flags = (int)x; break;
    case 71: sp->deg = (int)x; break;
    case 72: sp->nk = (int)x; break;
    case 73: sp->nc = (int)x; break;
    case 11: sp->nfit++; break;
    case 40:
        if (sp->nknots >= kcap)
            goto count;
        sp->knots[sp->nknots++] = x;
        break;
    case 41:
        if (sp->nw >= cap)
            goto count;
        sp->w[sp->nw++] = x;
        break;
    case 10:
        if (sp->npts >= cap)
            goto count;
        sp->pts[sp->npts][0] = x;
        sp->pts[sp->npts][2] = 1.0;
        sp->npts++;
        sp->y_at = 0;
        break;
    case 20:
        if (sp->npts < 1)
            goto count;
        if (sp->y_at)
            return ob_fail(err, "%s:%d: group 20 given twice for one control point (first at line %d)", r->name,
                           r->line, sp->y_at);
        sp->y_at = r->line;
        sp->pts[sp->npts - 1][1] = x;
        break;
    }
    if (r->code == 72 && !(sp->knots = calloc((size_t)sp->nk + 1, sizeof *sp->knots)))
        goto oom;
    if (r->code == 73 && (!(sp->w = calloc((size_t)sp->nc + 1, sizeof *sp->w)) ||
                          !(sp->pts = calloc((size_t)sp->nc + 1, sizeof *sp->pts))))
        goto oom;
    return 0;
count:
    ob_fail(err, "%s:%d: group %d: more values than the SPLINE's counts (72 knots, 73 control points) "
            "announce, or a value before its count", r->name, r->line, r->code);
    return -1;
oom:
    ob_fail(err, "%s: out of memory", r->name);
    return -1;
}

/* A SPLINE that is one Bézier segment (degree + 1 control points, knots
 * clamped at both ends) taken as it is, so that weights of either sign (a
 * rational fit's, as export_dxf.c writes them) read back; *segs stays NULL
 * for any other.  0, or -1 when out of memory. */
static int one_bezier(const spline *sp, ob_bez **segs, int *nseg)
{
    const int p = sp->deg;
    if (sp->nc != p + 1 || !(sp->knots[0] < sp->knots[2 * p + 1]))
        return 0;
    for (int i = 0; i <= p; i++)
        if (sp->knots[i] != sp->knots[0] || sp->knots[p + 1 + i] != sp->knots[2 * p + 1])
            return 0;
    for (int i = 0; i <= p; i++)
        if (!(sp->pts[i][2] != 0.0))
            return 0;  /* the B-spline path says why */
    if (!(*segs = calloc(1, sizeof **segs)))
        return -1;
    (*segs)->deg = p;
    for (int i = 0; i <= p; i++)
        ob_bez_set(*segs, i, sp->pts[i][0], sp->pts[i][1], sp->pts[i][2]);
    *nseg = 1;
    return 0;
}

/* Turns a complete SPLINE into pieces. */
static int spline_pieces(const dxfrd *r, spline *sp, const ob_apiece *link, ob_approx *out, ob_err *err)
{
    const int L = sp->line;
    if (sp->npts == 0 && sp->nfit > 0) {
        ob_fail(err, "%s:%d: SPLINE given by fit points only: measure needs its control points", r->name, L);
        return -1;
    }
    if (sp->deg < 1 || sp->deg > OB_MAX_IN_DEG || sp->npts != sp->nc || sp->nknots != sp->nk ||
        sp->nk != sp->nc + sp->deg + 1 || (sp->nw != 0 && sp->nw != sp->nc)) {
        ob_fail(err, "%s:%d: SPLINE of degree %d (1 to %d) with %d of %d control points, %d of %d knots "
                "(needs control points + degree + 1) and %d weights (none or one per control point)",
                r->name, L, sp->deg, OB_MAX_IN_DEG, sp->npts, sp->nc, sp->nknots, sp->nk, sp->nw);
        return -1;
    }
    for (int i = 0; i < sp->nw; i++)
        sp->pts[i][2] = sp->w[i];
    ob_bez *segs = NULL;
    int nseg = 0;
    ob_err why;
    if (one_bezier(sp, &segs, &nseg) != 0) {
        ob_fail(err, "%s: out of memory", r->name);
        return -1;
    }
    if (!segs && ob_bspline_to_bezier(sp->deg, sp->nc, sp->knots, (const double(*)[3])sp->pts, &segs, &nseg,
                                      &why) != 0) {
        ob_fail(err, "%s:%d: SPLINE: %s", r->name, L, why.msg);
        free(segs);
        return -1;
    }
    int rc = 0;
    for (int k = 0; k < nseg && rc == 0; k++) {
        ob_apiece *p = ob_approx_add(out);
        if (!p) {
            ob_fail(err, "%s: out of memory", r->name);
            rc = -1;
            break;
        }
        if (link->has_base && nseg == 1)
            *p = *link;
        p->line = L;
        p->fit_first = k == 0;
        p->approx = segs[k];
        rc = ob_approx_check_piece(p, out->n - 1, r->name, err);
    }
    free(segs);
    return rc;
}

static void spline_free(spline *sp)
{
    free(sp->knots);
    free(sp->w);
    free(sp->pts);
    memset(sp, 0, sizeof *sp);
}

/* Entities that belong to one before them (a POLYLINE's, an INSERT's):
 * not counted as skipped on their own. */
static int sub_entity(const char *name)
{
    return !strcmp(name, "VERTEX") || !strcmp(name, "SEQEND") || !strcmp(name, "ATTRIB");
}

enum { IN_NONE = 0, IN_SPLINE, IN_CURVE };

/* The z of an entity: its points' z (LINE 30 and 31, the others' 30, an
 * LWPOLYLINE's elevation 38; not a POLYLINE's VERTEX 30, which a 2D one
 * leaves 0 and its header's elevation overrides), and an ELLIPSE's major
 * axis' z (31, from its centre).  One z for all: the curve lies in a plane
 * parallel to XY and its projection is the same curve, so it is read,
 * flattened, with a warning; z that differ (or a tilted axis): its
 * projection is another curve, so it is skipped. */
typedef struct {
    int seen, vary;
    double z;
} zinfo;

/* One group of the entity being read, if it is a z; 0, or -1 with err. */
static int z_group(const dxfrd *r, int in, const ob_dxf_ent *ent, zinfo *z, ob_err *err)
{
    const int lw = in == IN_CURVE && ent->kind == OB_DXF_LWPOLYLINE;
    const int axis = in == IN_CURVE && ent->kind == OB_DXF_ELLIPSE && r->code == 31;
    const int point = r->code == 30 || (r->code == 31 && in == IN_CURVE && ent->kind == OB_DXF_LINE);
    if (lw ? r->code != 38 : !(point || axis) || (in == IN_CURVE && ent->in_vertex))
        return 0;
    double x;
    if (ob_dxf_number(r->val, r->code, r->line, r->name, &x, err))
        return -1;
    if (axis)
        z->vary |= x != 0.0;
    else if (z->seen)
        z->vary |= x != z->z;
    else
        z->seen = 1, z->z = x;
    return 0;
}

/* The state of one read. */
typedef struct {
    dxfrd r;
    ob_approx *out;
    spline sp;
    ob_dxf_ent ent;
    zinfo z;
    ob_apiece link, next; /* the link of the SPLINE being read; a comment's, for the next one */
    int link_sp, next_sp; /* their "same_param 1" */
    int in, all_sp;
    int sect;  /* 0 none seen (bare entities), 1 SECTION opened, 2 ENTITIES, 3 another, 4 after ENDSEC */
    char handle[24]; /* the handle (group 5) of the entity being read, "" none yet */
} dxfst;

/* The pieces out->v[n0 ..] of one entity: its type and handle (approx.h). */
static void name_pieces(ob_approx *out, int n0, const char *kind, const char *handle)
{
    for (int i = n0; i < out->n; i++) {
        snprintf(out->v[i].entity, sizeof out->v[i].entity, "%s", kind);
        snprintf(out->v[i].handle, sizeof out->v[i].handle, "%s", handle);
    }
}

/* The entity being read is complete: its pieces, unless its z say it is
 * no planar curve parallel to XY. */
static int entity_end(dxfst *st, ob_err *err)
{
    const char *kind = st->in == IN_SPLINE ? "SPLINE" : ob_dxf_kind_name(st->ent.kind);
    const int line = st->in == IN_SPLINE ? st->sp.line : st->ent.line, n0 = st->out->n;
    int rc = 0;
    if (st->z.vary) {
        char what[24];
        snprintf(what, sizeof what, "%.10s sloped in z", kind);
        ob_approx_note_skip_why(st->out, what, "z differs along it: its projection on XY is another curve", line);
        st->all_sp = 0;
    } else if (st->in == IN_SPLINE) {
        rc = spline_pieces(&st->r, &st->sp, &st->link, st->out, err);
        st->all_sp &= st->link.has_base && st->link_sp;
    } else {
        rc = ob_dxf_ent_pieces(&st->ent, st->r.name, st->out, err);
        st->all_sp = 0;
    }
    if (rc == 0)
        name_pieces(st->out, n0, kind, st->handle);
    st->handle[0] = '\0';
    if (rc == 0 && st->out->n > n0 && st->z.z != 0.0)
        ob_warn("%s:%d: %s at z = %.17g: flattened onto the XY plane (the same curve)", st->r.name, line, kind,
                st->z.z);
    spline_free(&st->sp);
    ob_dxf_ent_free(&st->ent);
    memset(&st->link, 0, sizeof st->link);
    memset(&st->z, 0, sizeof st->z);
    st->in = IN_NONE;
    return rc;
}

/* An entity named r->val starts (in the drawing's entities): which state
 * reads its groups; any other entity is noted as skipped.  A SPLINE takes
 * the link of the comment before it. */
static void entity_start(dxfst *st)
{
    const dxfrd *r = &st->r;
    const int kind = ob_dxf_kind_of(r->val);
    st->in = IN_NONE;
    if (strcmp(r->val, "SPLINE") == 0) {
        st->sp.line = r->line;
        st->link = st->next;
        st->link_sp = st->next_sp;
        st->in = IN_SPLINE;
    } else if (kind >= 0) {
        ob_dxf_ent_start(&st->ent, (ob_dxf_kind)kind, r->line);
        st->in = IN_CURVE;
    } else if (strcmp(r->val, "INSERT") == 0) {
        ob_approx_note_skip_why(st->out, r->val, "a block reference: measure reads no block's curves", r->line);
    } else if (strcmp(r->val, "SECTION") != 0 && strcmp(r->val, "ENDSEC") != 0 && !sub_entity(r->val)) {
        ob_approx_note_skip(st->out, r->val, r->line);
    }
}

/* A 999 comment: the job that exported the file, or the base link of
 * the SPLINE after it; never the end of the entity it is in. */
static void comment(dxfst *st)
{
    if (!st->out->have_job)
        ob_approx_parse_job(st->r.val, st->out);
    memset(&st->next, 0, sizeof st->next);
    st->next_sp = ob_approx_parse_link(st->r.val, &st->next) && strstr(st->r.val, "same_param 1") != NULL;
}

/* One (code, value) pair that is not a comment; 0, or -1 with err. */
static int pair(dxfst *st, ob_err *err)
{
    dxfrd *r = &st->r;
    if (st->in == IN_CURVE && st->ent.kind == OB_DXF_POLYLINE && r->code == 0 && strcmp(r->val, "VERTEX") == 0)
        return ob_dxf_ent_vertex(&st->ent, r->line, r->name, err); /* the POLYLINE goes on, to SEQEND */
    if (st->in && r->code == 0 && entity_end(st, err))
        return -1;
    if (r->code == 2 && st->sect == 1) {
        st->sect = strcmp(r->val, "ENTITIES") == 0 ? 2 : 3;
    } else if (r->code == 0) {
        st->sect = strcmp(r->val, "SECTION") == 0 ? 1 : strcmp(r->val, "ENDSEC") == 0 ? 4 : st->sect;
        if (st->sect == 0 || st->sect == 2) /* only the drawing's own entities: not block definitions */
            entity_start(st);
        memset(&st->next, 0, sizeof st->next); /* a link belongs to the SPLINE right after it */
        st->next_sp = 0;
    } else if (st->in && r->code == 5 && !st->handle[0] && !(st->in == IN_CURVE && st->ent.in_vertex)) {
        snprintf(st->handle, sizeof st->handle, "%s", r->val); /* the entity's own, not a VERTEX's */
    } else if (st->in && z_group(r, st->in, &st->ent, &st->z, err)) {
        return -1;
    } else if (st->in == IN_SPLINE) {
        return spline_group(r, &st->sp, err);
    } else if (st->in == IN_CURVE) {
        return ob_dxf_ent_group(&st->ent, r->code, r->val, r->line, r->name, err);
    }
    return 0;
}

int ob_approx_read_dxf(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err)
{
    dxfst st = {.r = {text, text + len, name, 0, 0, ""}, .out = out, .all_sp = 1};
    int rc = 0;
    for (;;) {
        const int got = next_pair(&st.r, err);
        if (got < 0) {
            rc = -1;
            break;
        }
        if (got == 1 || (st.r.code == 0 && strcmp(st.r.val, "EOF") == 0)) {
            rc = st.in ? entity_end(&st, err) : 0;
            break;
        }
        if ((rc = st.r.code == 999 ? (comment(&st), 0) : pair(&st, err)) != 0)
            break;
    }
    spline_free(&st.sp);
    ob_dxf_ent_free(&st.ent);
    for (int i = 0; rc == 0 && i < out->n; i++)
        st.all_sp &= out->v[i].has_base;
    out->same_param = rc == 0 && out->n > 0 && st.all_sp;
    return rc;
}
