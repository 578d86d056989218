/*
 * trim.h - the trimmed offset (issue 50): the parts of the untrimmed offset
 * O(t) = C(t) + d N(t) whose distance to the whole base curve C is |d|, the
 * set of points at distance |d| from C that a CAD kernel's offset ships
 * (its loops and the parts that come nearer than |d| to another part of C
 * cut away), and the two-sided distance between it and a file's pieces as
 * point sets (`measure --trimmed`, trim_measure.c).
 *
 * What is located to round-off (trim.c): the split points of O where the
 * distance to C can change from |d| to less: the cusps of O (1 - d kappa
 * changes sign, ob_bez_offset_cusps), the self-intersections of O (within a
 * segment and between segments, the wrap of a closed base included), the
 * intersections of O with the opposite offset C - d N, and for an open base
 * the crossings of O with the circles of radius |d| about its two end
 * points.  Candidates come from dense polylines (OB_TRIM_POLY chords per
 * segment), each refined by Newton's method (2x2 on O(s) - P(u) = 0, 1-D
 * on |O(t) - E|^2 = d^2) and kept only when it converges inside [0, 1]:
 * two crossings closer than the chords' spacing can be missed, and so can
 * a tangential touch (no crossing).
 * What is sampled: between two consecutive split points an arc of O is
 * kept or removed whole, decided at its midpoint by the distance to C
 * (ob_trim_base_dist: a scan of every segment refined by golden section),
 * kept when it is |d| to within OB_TRIM_REL of the curve's size.
 *
 * Corners: a joint (the wrap of a closed base too) where the unit normals
 * on its two sides differ by more than OB_TRIM_CORNER is a corner P; O
 * has a gap there, from P + d N1 to P + d N2.  On the convex side (d and
 * the tangent's turn theta of opposite signs; a reversal, theta = +-pi,
 * on both) the points at |d| from C there are the arc of the circle of
 * radius |d| about P from d N1 turning by theta (what a CAD kernel's arc
 * join fills): a kept arc of kind corner, between the two segments' arcs,
 * split where O_d, O_-d, the circles about the other corners and the open
 * ends cross it, each part kept by its midpoint as O's arcs are.  On the
 * concave side no inner point of that arc is |d| from C (the segment
 * before comes nearer), and the two offsets' crossing next to P is looked
 * for like any other (a corner's two chords share no vertex).  O_d is
 * split at the circles about the corners too.
 */
#ifndef OB_TRIM_H
#define OB_TRIM_H

#include <stdio.h>

#include "host/io/approx.h"
#include "host/measure/measure.h"
#include "methods/core/curve.h"
#include "methods/core/err.h"

enum { OB_TRIM_POLY = 2048 };
#define OB_TRIM_REL 1e-9
/* A joint is a corner when its tangent turns by more than this (radians):
 * far above the round-off of a smooth joint's two unit normals (1e-15 or
 * so, also after a B-spline's conversion to Bezier segments), and the gap
 * it leaves between the offsets' ends, |d| times the turn, below 1e-8 |d|
 * when it is taken as smooth. */
#define OB_TRIM_CORNER 1e-8

typedef enum { OB_SPLIT_CUSP = 0, OB_SPLIT_SELF, OB_SPLIT_OPPOSITE, OB_SPLIT_END } ob_split_kind;

typedef struct {
    int seg;
    double t;
    ob_split_kind kind;
} ob_trim_split;

/* A kept arc: O on base segment seg over [t0, t1] (corner 0), or (corner
 * 1) the arc of the circle about ctr = C(seg, 0) (the corner at the start
 * of segment seg: for segment 0, the wrap's joint of a closed base) of
 * radius r = |d| from angle t0 to angle t1 (radians; t1 < t0: clockwise). */
typedef struct {
    int seg;
    double t0, t1;
    int corner;
    double ctr[2], r;
} ob_trim_arc;

typedef struct {
    ob_trim_arc *arc;      /* in the base's order */
    int n;
    ob_trim_split *split;  /* every split point of O found, by segment and t (not a corner arc's) */
    int nsplit;
} ob_trim;

/* A corner: the G0 joint at the start of segment seg (segment 0: the
 * wrap's joint of a closed base), its point P, the angle a0 of d N at the
 * end of the segment before and the turn of the tangent there (signed,
 * the arc's sweep); convex: the arc is on the d side. */
typedef struct {
    int seg, convex;
    double P[2], a0, sweep;
} ob_trim_corner;

/* Purpose: whether the joint at the start of segment k of c (k = 0: the
 *          wrap's, when closed) is a corner (its normals differ by more
 *          than OB_TRIM_CORNER), and if so *cn for the d side.
 * Returns: 1 (a corner, *cn filled), else 0. */
int ob_trim_corner_at(const ob_curve *c, double d, int k, int closed, ob_trim_corner *cn);

/* The scale the trims' round-off allowances are relative to: the diagonal
 * of the box of c's control points, plus |d|. */
double ob_trim_curve_size(const ob_curve *c, double d);

/* Purpose: the trimmed d-offset of c (above).
 * Outputs: *tr (free with ob_trim_free, also after an error); no arc at all
 *          when every point of O comes nearer than |d| to C.
 * Errors:  returns 0; -1 with a reason in err->msg: out of memory. */
int ob_trim_offset(const ob_curve *c, double d, ob_trim *tr, ob_err *err);

void ob_trim_free(ob_trim *tr);

/* Purpose: the point of kept arc ar of the trimmed d-offset of c at u in
 *          [0, 1] (u = 0 its start, 1 its end): O(t0 + (t1 - t0) u) on its
 *          segment, or for a corner arc ctr + r (cos a, sin a) at the angle
 *          a = t0 + (t1 - t0) u.
 * Outputs: p.  Errors: none. */
void ob_trim_arc_point(const ob_curve *c, double d, const ob_trim_arc *ar, double u, double p[2]);

/* The distance from p to the whole base curve c (every segment over [0, 1],
 * end points included): each segment scanned at 256 parameters, every local
 * minimum refined by golden section. */
double ob_trim_base_dist(const ob_curve *c, const double p[2]);

/* Purpose: the two-sided Hausdorff distance between the pieces of a as a
 *          point set and the trimmed offset tr as a point set (no parameter
 *          match, no cover check): each side sampled at S parameters per
 *          piece (arc), the nearest point on the other side found on a grid
 *          of its samples and refined by golden section, the largest
 *          sample of each piece (arc) refined by golden section.
 * Outputs: *r: err, piece (the file's piece nearest the worst point, or at
 *          it), seg and t (of the trimmed offset's point at it, or nearest
 *          to it; on a corner arc the corner's, seg at t = 0), note: msg,
 *          which says which side and where (x, y).
 * Errors:  returns 0; -1 with a reason in err->msg: tr has no arc, a has no
 *          piece, out of memory. */
int ob_trimmed_hausdorff(const ob_curve *c, double d, const ob_trim *tr, const ob_approx *a, int samples,
                         ob_mres *r, char *msg, size_t len, ob_err *err);

/* Purpose: `measure --trimmed`'s path: the trimmed d-offset of c
 *          (ob_trim_offset), written to dump when not NULL (ob_trim_dump),
 *          and the pieces of a measured against it (ob_trimmed_hausdorff).
 * Errors:  returns 0; -1 with a reason in err->msg (an empty trimmed
 *          offset, a dump that cannot be written, out of memory). */
int ob_measure_trimmed(const ob_curve *c, double d, const ob_approx *a, int samples, const char *dump, ob_mres *r,
                       char *msg, size_t len, ob_err *err);

/* Purpose: the trimmed offset as CSV, for checks (`measure --trim-dump`):
 *          a header, then one row per kept arc (kind arc: seg, t0, t1 and
 *          the end points x0, y0, x1, y1; kind corner: seg, the angles
 *          t0, t1 and the end points) and per split point of O (kind
 *          cusp, self, opposite or end: seg, t0 = t1 = t, its point
 *          twice; a corner arc's split points are not kept).
 * Returns: 0, or -1 when writing fails. */
int ob_trim_dump(FILE *f, const ob_curve *c, double d, const ob_trim *tr);

#endif
