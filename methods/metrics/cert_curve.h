/*
 * cert_curve.h - rigorous enclosures of a Bézier segment, or of the exact
 * offset of one, and of their derivatives: the evaluations the certified
 * Hausdorff bound (metric_certified.h) is built from.
 *
 * A curve here is either a (rational) Bézier segment B(t), or the untrimmed
 * exact offset O(t) = C(t) + d N(t) of one, N = (-y', x') / |C'|.  Its
 * derivatives, from the Frenet formulas (kappa = (C' x C'') / |C'|^3):
 *   O'  = C' (1 - d kappa)
 *   O'' = C'' (1 - d kappa) - d kappa' C',
 *   O''' = C''' (1 - d kappa) - 2 d kappa' C'' - d kappa'' C',
 *   kappa' = ((C' x C''') |C'|^2 - 3 (C' x C'') (C' . C'')) / |C'|^5,
 *   kappa'' = d/dt kappa' (cert_curve.c, kappa2_num).
 * Method: the k-th derivative of each homogeneous coordinate is a
 * Bernstein polynomial whose coefficients are falling(n, k) times the k-th
 * differences of the control points (the hodograph), taken in interval
 * arithmetic (interval.h); interval de Casteljau in convex form
 * (1 - t) a + t b on it: at a point t for the value there; over [t0, t1]
 * cut to the subsegment, whose coefficients' hull encloses the derivative
 * there (the Bernstein convex-hull property: Farin, "Curves and Surfaces
 * for CAGD", ch. 5); then the quotient rule and the formulas above in
 * interval arithmetic.  The cut is at t1 and then at t0 / t1, a ratio
 * carried as an interval, so the enclosure is of the exact [t0, t1].
 * Differencing before cutting keeps the rounding relative to the
 * derivative (not eps |P| / (t1 - t0)^k), which is what lets a piece with
 * legs of 1e-7 at coordinates ~0.5 be enclosed at all.
 * Errors: -1 where the enclosure cannot be bounded: the offset where the
 * interval of |C'|^2 reaches 0 (a cusp, a collapsed end leg), a rational
 * segment whose weight interval reaches 0, an overflow.
 */
#ifndef OB_CERT_CURVE_H
#define OB_CERT_CURVE_H

#include "methods/core/curve.h"
#include "methods/metrics/interval.h"

/* The hodographs of a segment (cert_curve.c: the Bernstein coefficients
 * of its homogeneous derivatives 0..OB_CV_MAXK, interval differences of
 * its control points), computed once per curve instead of at every
 * enclosure (ob_cv_hodo_attach): the same numbers, so the same bounds. */
enum { OB_CV_MAXK = 4 };
typedef struct {
    int deg[OB_CV_MAXK + 1];  /* n - k, or -1 (the zero polynomial) */
    ob_iv D[OB_CV_MAXK + 1][3][OB_MAX_DEG + 1];
} ob_cv_hodo;

typedef struct {
    const ob_bez *b;
    double d;    /* the offset distance when `offset` */
    int offset;  /* 0: the segment itself; 1: its exact d-offset */
    /* Where b came from, when it was cut out of a stored segment: NULL, or
     * that segment, which the enclosures then read instead of b, over the
     * real parameters u = u0 + du t (ob_cv_from_src).  b itself is rounded
     * (each control point of a cut is off by ~eps |P|): on a piece with
     * legs near 1e-13 that turns its tangent, so its offset swings through
     * a fan the true offset does not have, and a zero of C' (a cusp) can be
     * rounded away.  The floating-point searches (cert_feet.h) still read b:
     * they only propose, never bound. */
    const ob_bez *src;
    ob_iv u0, du;
    const ob_cv_hodo *hodo;  /* NULL, or the hodographs of the curve read (src, else b) */
} ob_cv;

/* Purpose: compute h from the curve c's enclosures read (src, else b) and
 *          attach it to c (h must outlive c's use). */
void ob_cv_hodo_attach(ob_cv *c, ob_cv_hodo *h);

/* Where a base piece comes from: segment seg as stored, cut to the real
 * parameters u = a + (b - a) (t0 + (t1 - t0) s), s in [0, 1] (the driver's
 * span [a, b] and the fit's piece [t0, t1] of it: host/io/approx.h). */
typedef struct {
    const ob_bez *seg;
    double a, b, t0, t1;
} ob_cert_src;

/* Purpose: the curve `piece` (its offset at d when offset = 1) enclosed from
 *          src->seg as stored (src NULL: from piece itself).
 * Inputs:  piece: src->seg cut to src's range in floating point (what the
 *          feet search); 0 <= a < b <= 1, 0 <= t0 < t1 <= 1.
 * Returns: 0, or -1 when src's numbers are not such ranges. */
int ob_cv_from_src(ob_cv *c, const ob_bez *piece, const ob_cert_src *src, double d, int offset);

/* Purpose: enclosures of the point and first derivative at the float t
 *          (t in [0, 1]).  Outputs: p[2], d1[2].  Returns 0 or -1. */
int ob_cv_point(const ob_cv *c, double t, ob_iv p[2], ob_iv d1[2]);

/* Purpose: enclosures of the point and first and second derivatives at the
 *          float t (t in [0, 1]): the third-order Taylor form's jet at the
 *          midpoint (cert_bounds.c).  Outputs: p[2], d1[2], d2[2].
 *          Returns 0 or -1. */
int ob_cv_point2(const ob_cv *c, double t, ob_iv p[2], ob_iv d1[2], ob_iv d2[2]);

/* Purpose: an enclosure of the k-th derivative (k = 1, 2 or 3) over every t in

 *          [t0, t1] (0 <= t0 <= t1 <= 1).  Output: out[2].  Returns 0 or -1. */
int ob_cv_range(const ob_cv *c, double t0, double t1, int k, ob_iv out[2]);

/* Purpose: ob_cv_range for the orders k1..k2 at once (1 <= k1 <= k2 <= 3),
 *          from one enclosure of the homogeneous jet: out[k - k1][2].
 *          Returns 0 or -1. */
int ob_cv_range_n(const ob_cv *c, double t0, double t1, int k1, int k2, ob_iv out[][2]);

#endif
