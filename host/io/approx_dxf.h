/*
 * approx_dxf.h - the DXF reader's entities besides SPLINE (internal to
 * host/io/approx_read_dxf.c and approx_dxf_curves.c): LINE, ARC, CIRCLE,
 * ELLIPSE and LWPOLYLINE, each turned into exact Bézier pieces:
 *   LINE        one piece of degree 1;
 *   ARC, CIRCLE the circle's rational quadratic pieces, of at most 90
 *               degrees each (end points on the circle, the middle control
 *               point where the end tangents meet, its weight the cosine of
 *               half the piece's angle), counterclockwise from group 50 to
 *               51 (degrees); a CIRCLE from 0 to 360;
 *   ELLIPSE     the same pieces mapped by the ellipse's affine map
 *               (rational Béziers are affine invariant), from parameter 41
 *               to 42 (radians);
 *   LWPOLYLINE  a piece of degree 1 per segment, an arc (as ARC) where the
 *               segment's bulge (group 42 of its first vertex: the tangent
 *               of a quarter of its angle, counterclockwise positive) is
 *               not 0; the closing segment when flag 1 of group 70 is set;
 *   POLYLINE    (the old form: a POLYLINE header, one VERTEX entity per
 *               vertex, SEQEND) the same, from each VERTEX's 10, 20 and 42
 *               (the header's 10/20 is its elevation point, no vertex);
 *               a VERTEX of flag 16 (a spline frame's control point, not
 *               drawn) is left out, so a curve- or spline-fit polyline is
 *               read as drawn; a 3D polyline or a mesh (POLYLINE flag 8, 16
 *               or 64) is skipped (named).
 * ARC, CIRCLE and LWPOLYLINE are in their object coordinate system: one
 * whose extrusion (210, 220, 230) is (0, 0, -1) is mirrored (x to -x), as
 * the arbitrary axis algorithm gives; any other extrusion than (0, 0, +-1)
 * puts the entity out of the XY plane, and it is skipped (named).  Z
 * values are the reader's (approx_read_dxf.c: one z is flattened with a
 * warning, z that differ skip the entity).  A bulge arc is built from its
 * chord and bulge, without its centre (approx_dxf_curves.c, bulge_piece).
 * Values are decimal numbers (ob_dxf_number); a group the entity takes
 * once, given twice, is an error.  Joints between the pieces of one
 * entity are exact: neighbours share their end point bit for bit (a
 * polyline's vertices are taken as they are written).
 */
#ifndef OB_APPROX_DXF_H
#define OB_APPROX_DXF_H

#include "host/io/approx.h"
#include "methods/core/err.h"

typedef enum {
    OB_DXF_LINE = 0, OB_DXF_ARC, OB_DXF_CIRCLE, OB_DXF_ELLIPSE, OB_DXF_LWPOLYLINE, OB_DXF_POLYLINE
} ob_dxf_kind;

/* One polyline vertex: point, bulge of the segment it starts, its line,
 * its flags (a POLYLINE's VERTEX group 70). */
typedef struct {
    double x, y, bulge;
    int line, flags;
    int at[4];                /* lines of its 10, 20, 42, 70 (0: not yet) */
} ob_dxf_vertex;

/* One entity being read. */
typedef struct {
    ob_dxf_kind kind;
    int line;                 /* of its name */
    int have;                 /* bit per group seen: see approx_dxf_curves.c */
    double g[16];             /* the single-valued groups */
    int gline[16];            /* the line of each */
    ob_dxf_vertex *v;         /* LWPOLYLINE and POLYLINE vertices */
    int nv, cap, announced;   /* vertices read, room, group 90 (-1 none) */
    int in_vertex;            /* POLYLINE: 1 once its first VERTEX began */
} ob_dxf_ent;

/* Purpose: the number DXF value `val` of group `code` (at `line`) holds.
 * Errors:  returns 0; -1 with "NAME:LINE: group CODE: 'VAL' is not a
 *          number" (or "not a decimal number": a hex float, inf or nan,
 *          which DXF does not write; or "out of range"). */
int ob_dxf_number(const char *val, int code, int line, const char *name, double *x, ob_err *err);

/* The entity name of kind (LINE, ARC, ...). */
const char *ob_dxf_kind_name(ob_dxf_kind kind);

/* The kind of the entity named `name`, or -1 when it is not one of these. */
int ob_dxf_kind_of(const char *name);

/* Starts an entity of `kind` whose name is at `line`. */
void ob_dxf_ent_start(ob_dxf_ent *e, ob_dxf_kind kind, int line);

/* Purpose: a VERTEX entity (its name at `line`) that continues POLYLINE e:
 *          its groups, until the next entity, are that vertex's.
 * Errors:  returns 0; -1 with "NAME: out of memory" in err. */
int ob_dxf_ent_vertex(ob_dxf_ent *e, int line, const char *name, ob_err *err);

/* Purpose: one group (code, value text) of the entity, at `line`.
 * Errors:  returns 0; -1 with "NAME:LINE: reason" in err (a number that is
 *          not a decimal one, a group given twice where the entity or its
 *          vertex takes one, naming both lines; out of memory). */
int ob_dxf_ent_group(ob_dxf_ent *e, int code, const char *val, int line, const char *name, ob_err *err);

/* Purpose: the finished entity's pieces, appended to out (unlinked, at the
 *          entity's line; a polyline's at the line of each segment's first
 *          vertex).  An entity out of the XY plane, or of no extent (a
 *          zero-length LINE, an ARC of radius 0 is an error, see below), is
 *          skipped and noted in out (ob_approx_note_skip).
 * Errors:  returns 0; -1 with "NAME:LINE: reason" in err: a group the
 *          entity needs is missing, a radius or an axis ratio that is not
 *          positive, a polyline with other than the vertices group 90
 *          announces, or with fewer than 2, out of memory. */
int ob_dxf_ent_pieces(ob_dxf_ent *e, const char *name, ob_approx *out, ob_err *err);

/* Always safe to call on a started or zeroed entity. */
void ob_dxf_ent_free(ob_dxf_ent *e);

#endif
