/*
 * diagnose.h - what a file that lies far from the offset looks like
 * instead (`measure`, issue 50 item 2): the offset on the other side (a
 * wrong sign of d), or the offset in another frame (a similarity away:
 * a CAD drawing's units, y axis, origin).  Only words: it changes no
 * measurement and no exit status.
 *
 * The rule: a file is far when its match or cover fails, or when its
 * error is above OB_DIAG_FAR times the curve's size (ob_joint_size: the
 * box of the control points grown by |d|).  Then
 *   - its sample points' largest distance to the offset at -d, X: when X
 *     is within OB_DIAG_FAR of the size and under a tenth of the same
 *     distance to the offset at d, the file is "within X of the offset at
 *     d = -D: wrong sign of --d?";
 *   - else the flip y' = -y, and the best similarity (rotation, uniform
 *     scale, translation, with or without a reflection) by nearest-point
 *     ICP from the points' moments (centroid, spread, principal axis, each
 *     quarter turn): when one maps the points within OB_DIAG_FAR of the
 *     size of the offset both ways (the two-sided distance of the sample
 *     polylines, R), "a similarity maps it onto the offset within R: try
 *     --transform a,b,c,d,e,f" (that map composed after the frame given).
 */
#ifndef OB_DIAGNOSE_H
#define OB_DIAGNOSE_H

#include <stddef.h>

#include "host/io/approx.h"
#include "host/measure/frame.h"

#define OB_DIAG_FAR 1e-2

/* 1 when an error err of an approximation of c at d counts as far. */
int ob_diag_far(const ob_curve *c, double d, double err);

/* Purpose: the diagnosis of file name (pieces a, in base coordinates
 *          after the frame given, given: composed into a suggested map).
 * Outputs: buf: one line without "measure: " (empty when nothing fits).
 * Returns: 1 when it found what the file looks like, 0 when not, -1 out
 *          of memory (buf empty). */
int ob_diagnose(const ob_curve *c, double d, const ob_approx *a, const ob_frame *given, const char *name, char *buf,
                size_t len);

#endif
