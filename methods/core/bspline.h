/*
 * bspline.h - B-spline (optionally rational) to Bézier segments.
 */
#ifndef OB_BSPLINE_H
#define OB_BSPLINE_H

#include "methods/core/curve.h"
#include "methods/core/err.h"

/* Purpose: convert a B-spline of degree p with npts control points to its
 *          Bézier segments (one per non-empty knot span inside the domain
 *          [knots[p], knots[npts]]), each reparameterized to [0,1].
 * Inputs:  p >= 1, npts >= p+1, knots[npts+p+1] non-decreasing with
 *          knots[p] < knots[npts]; pts[npts][3] = Euclidean x, y and weight w > 0.
 * Outputs: *segs (malloc'd, caller frees), *nseg.
 * Method:  knot insertion (Boehm) on homogeneous points until every interior
 *          knot has multiplicity p, then read off the segments.  Works for
 *          uniform, non-uniform, clamped and unclamped knot vectors.
 * Errors:  returns 0; -1 on bad arguments (message in err->msg; err may be NULL), -2 on no memory. */
int ob_bspline_to_bezier(int p, int npts, const double *knots,
                         const double (*pts)[3], ob_bez **segs, int *nseg,
                         ob_err *err);

/* Purpose: the Bézier segment of one non-empty knot span [U[k], U[k+1]]
 *          (p <= k, U[k] < U[k+1]) of a B-spline of degree p, reparameterized
 *          to [0,1]; no allocation (a method's fit may call it).
 * Inputs:  p in 1..OB_MAX_IN_DEG; U with at least k + p + 1 entries around the
 *          span (U[k-p+1 .. k+p]); pts[k-p .. k] = Euclidean x, y, weight > 0;
 *          rational 0 forces every output weight to exactly 1 (the affine
 *          sums would otherwise leave 1 +- 1 ulp).
 * Outputs: *out, of degree p.
 * Method:  Bézier point j is the blossom of the span at (U[k]^(p-j), U[k+1]^j),
 *          one knot insertion per level as in de Boor's algorithm, on
 *          homogeneous points.
 * Errors:  returns 0, or -1 if a value overflowed (out then incomplete). */
int ob_bspline_span_to_bezier(int p, int k, const double *U, const double (*pts)[3],
                              int rational, ob_bez *out);

#endif
