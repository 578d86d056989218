/*
 * trim_approx.h - a method's approximation trimmed the way a CAD kernel
 * trims the offset it approximated (issue 50: `run --trimmed`).
 *
 * A method approximates the untrimmed offset O = C + dN, loops and all.  A
 * CAD kernel then trims its approximation A by A's own geometry: it cuts A
 * at its self-crossings, where it crosses the other side's offset, and
 * where it crosses the circles of radius |d| about an open base's end
 * points, and removes the arcs between two cuts that come nearer than |d|
 * to the base (trim.h does the same to the exact O, whose split points are
 * known to round-off; A's are A's own).
 *
 * How (trim_approx.c):
 *   - at each convex corner of the base (ob_trim_corner_at: a G0 joint,
 *     the offset's gap on the d side) the arc of radius |d| about it is
 *     put between the last piece over the segment before and the first
 *     over the segment after, as rational quadratics (a CAD kernel's arc
 *     join: the methods fit the segments, not the corners);
 *   - the pieces are taken in the order given (the base's), as one curve
 *     with the parameter tau = k + u (piece k, its own u in [0, 1]);
 *   - each piece is a polyline of OB_TRIMA_CHORDS chords; crossings of two
 *     chords that are not neighbours (of A with itself), and of A's chords
 *     with a polyline of the exact opposite offset C - dN, are refined by
 *     Newton's method (kept at the chords' estimate where it does not
 *     converge); the end circles' crossings are sign changes of
 *     |A - E|^2 - d^2, bisected;
 *   - every arc between two consecutive cuts is kept or removed whole:
 *     removed when one of its points comes nearer to the base than
 *     |d| - margin (ob_trim_base_dist at its middle and at
 *     OB_TRIMA_ARC_SAMPLES points a piece it covers).  A's points lie
 *     within its error e of O, so every point of an arc of A that follows
 *     the trimmed offset is at least |d| - e from the base: a margin above
 *     e keeps those arcs whole.  A region of O that comes nearer than |d|
 *     by less than the margin cannot be told from the error, and an arc of
 *     A over it is kept: where the approximation is as coarse as the
 *     loops are shallow, trimming it leaves them (run --trimmed shows it
 *     as a large trimmed_err).
 * Cuts at the piece joints are not cuts: an arc runs on across pieces.
 */
#ifndef OB_TRIM_APPROX_H
#define OB_TRIM_APPROX_H

#include "host/io/approx.h"
#include "methods/core/curve.h"
#include "methods/core/err.h"

enum { OB_TRIMA_CHORDS = 64, OB_TRIMA_OPP_CHORDS = 256, OB_TRIMA_ARC_SAMPLES = 8 };

/* Purpose: the parts of a that a CAD kernel keeps when it trims a as the
 *          d-offset of c (above).
 * Inputs:  a: the pieces, in the order of the curve (joined end to end,
 *          within the approximation's error); margin >= 0 (the run uses
 *          twice the larger of the job's tol and max_err).
 * Outputs: *kept: the kept parts, each a piece of a cut to its range by de
 *          Casteljau (has_base 0; a whole piece is copied); free it with
 *          ob_approx_free, also after an error.  *cut: the runs of removed
 *          arcs (the regions trimmed away; one across a closed curve's wrap).
 * Errors:  returns 0; -1 with a reason in err->msg: out of memory, a piece
 *          that cannot be evaluated (a point that is not finite). */
int ob_trim_approx(const ob_curve *c, double d, const ob_approx *a, double margin, ob_approx *kept, int *cut,
                   ob_err *err);

#endif
