/*
 * bspline.h - B-spline (optionally rational) to Bézier segments.
 */
#ifndef OB_BSPLINE_H
#define OB_BSPLINE_H

#include "curve.h"

/* Purpose: convert a B-spline of degree p with npts control points to its
 *          Bézier segments (one per non-empty knot span inside the domain
 *          [knots[p], knots[npts]]), each reparameterized to [0,1].
 * Inputs:  p >= 1, npts >= p+1, knots[npts+p+1] non-decreasing with
 *          knots[p] < knots[npts]; pts[npts][3] = Euclidean x, y and weight w > 0.
 * Outputs: *segs (malloc'd, caller frees), *nseg.
 * Method:  knot insertion (Boehm) on homogeneous points until every interior
 *          knot has multiplicity p, then read off the segments.  Works for
 *          uniform, non-uniform, clamped and unclamped knot vectors.
 * Errors:  returns 0; -1 on bad arguments (message in err), -2 on no memory. */
int ob_bspline_to_bezier(int p, int npts, const double *knots,
                         const double (*pts)[3], ob_bez **segs, int *nseg,
                         char *err, size_t errlen);

#endif
