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
 * link (export_dxf.c).  Only the ENTITIES section is read (a file of bare
 * entities, without sections, too): splines of block definitions are not
 * the drawing's curves.
 */
#include "host/io/approx_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/approx_dxf.h"
#include "methods/core/bspline.h"

enum { DXF_MAX_CTRL = 100000 };

typedef struct {
    const char *s, *end, *name;
    int line;          /* line of the last value read */
    int code;
    char val[512];
} dxfrd;

/* Next (code, value) pair; 1 at the end, 0, or -1 with err. */
static int next_pair(dxfrd *r, ob_err *err)
{
    char buf[2][512];
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
        if (n >= sizeof buf[k])
            n = sizeof buf[k] - 1;
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
} spline;

static int num(dxfrd *r, double *x, ob_err *err)
{
    char *e;
    *x = strtod(r->val, &e);
    if (!r->val[0] || *e) {
        ob_fail(err, "%s:%d: group %d: '%.40s' is not a number", r->name, r->line, r->code, r->val);
        return -1;
    }
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
    if (r->code >= 70 && r->code <= 74 && !(x >= 0 && x <= DXF_MAX_CTRL && x == (int)x)) {
        ob_fail(err, "%s:%d: group %d: '%.40s' is not a whole number from 0 to %d", r->name, r->line,
                r->code, r->val, DXF_MAX_CTRL);
        return -1;
    }
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
        break;
    case 20:
        if (sp->npts < 1)
            goto count;
        sp->pts[sp->npts - 1][1] = x;
        break;
    }
    if ((r->code == 72 && sp->knots) || (r->code == 73 && sp->pts)) {
        ob_fail(err, "%s:%d: group %d given twice in one SPLINE", r->name, r->line, r->code);
        return -1;
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

/* An entity named r->val starts (in the drawing's entities): which state
 * reads its groups; any other entity is noted as skipped. */
static int entity_start(const dxfrd *r, spline *sp, ob_dxf_ent *ent, ob_approx *out)
{
    const int kind = ob_dxf_kind_of(r->val);
    if (strcmp(r->val, "SPLINE") == 0) {
        sp->line = r->line;
        return IN_SPLINE;
    }
    if (kind >= 0) {
        ob_dxf_ent_start(ent, (ob_dxf_kind)kind, r->line);
        return IN_CURVE;
    }
    if (strcmp(r->val, "SECTION") != 0 && strcmp(r->val, "ENDSEC") != 0 && !sub_entity(r->val))
        ob_approx_note_skip(out, r->val, r->line);
    return IN_NONE;
}

int ob_approx_read_dxf(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err)
{
    dxfrd r = {text, text + len, name, 0, 0, ""};
    spline sp = {0};
    ob_dxf_ent ent = {0};
    ob_apiece link = {0};
    int in = IN_NONE, rc = 0, eof = 0, link_sp = 0, all_sp = 1;
    int sect = 0;  /* 0 none seen (bare entities), 1 SECTION opened, 2 ENTITIES, 3 another, 4 after ENDSEC */
    while (rc == 0 && !eof) {
        const int st = next_pair(&r, err);
        if (st < 0) {
            rc = -1;
            break;
        }
        eof = st == 1 || (r.code == 0 && strcmp(r.val, "EOF") == 0);
        if (in == IN_CURVE && ent.kind == OB_DXF_POLYLINE && r.code == 0 && strcmp(r.val, "VERTEX") == 0) {
            rc = ob_dxf_ent_vertex(&ent, r.line, name, err);  /* the POLYLINE goes on, to SEQEND */
            continue;
        }
        if (in && (eof || r.code == 0 || r.code == 999)) {  /* an entity ends at the next one or a comment */
            if (in == IN_SPLINE) {
                rc = spline_pieces(&r, &sp, &link, out, err);
                all_sp &= link.has_base && link_sp;
            } else {
                rc = ob_dxf_ent_pieces(&ent, name, out, err);
                all_sp = 0;
            }
            spline_free(&sp);
            ob_dxf_ent_free(&ent);
            memset(&link, 0, sizeof link);
            in = IN_NONE;
        }
        if (rc || eof)
            break;
        if (r.code == 999) {
            if (!out->have_job)
                ob_approx_parse_job(r.val, out);
            memset(&link, 0, sizeof link);
            link_sp = ob_approx_parse_link(r.val, &link) && strstr(r.val, "same_param 1") != NULL;
        } else if (r.code == 2 && sect == 1) {
            sect = strcmp(r.val, "ENTITIES") == 0 ? 2 : 3;
        } else if (r.code == 0) {
            sect = strcmp(r.val, "SECTION") == 0 ? 1 : strcmp(r.val, "ENDSEC") == 0 ? 4 : sect;
            /* only the drawing's own entities: not block definitions */
            in = sect == 0 || sect == 2 ? entity_start(&r, &sp, &ent, out) : IN_NONE;
            if (in != IN_SPLINE)  /* a link belongs to the SPLINE right after it */
                memset(&link, 0, sizeof link);
        } else if (in == IN_SPLINE) {
            rc = spline_group(&r, &sp, err);
        } else if (in == IN_CURVE) {
            rc = ob_dxf_ent_group(&ent, r.code, r.val, r.line, name, err);
        }
    }
    spline_free(&sp);
    ob_dxf_ent_free(&ent);
    for (int i = 0; rc == 0 && i < out->n; i++)
        all_sp &= out->v[i].has_base;
    out->same_param = rc == 0 && out->n > 0 && all_sp;
    return rc;
}
