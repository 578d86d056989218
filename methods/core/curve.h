/*
 * curve.h - piecewise rational Bézier curves in homogeneous form.
 *
 * One segment type serves polynomial and rational Bézier curves alike: control
 * points are stored homogeneously as (w*x, w*y, w).  A polynomial segment has
 * every w = 1 and `rational` = 0.  B-splines are converted to Bézier segments on
 * input (bspline.h), so everything downstream sees only ob_bez.
 *
 * Storage is fixed-size so that methods and the driver never allocate in the
 * timed path; OB_MAX_DEG bounds the degree of any segment (input or output).
 *
 * Conventions: t in [0,1] on every segment; the unit normal is the LEFT normal
 * N = (-y', x') / |C'| (Liu-Wang, Zhao-Zhou); d > 0 offsets to the left of the
 * direction of travel; signed curvature kappa = (x' y'' - y' x'') / |C'|^3.
 */
#ifndef OB_CURVE_H
#define OB_CURVE_H

#include <stddef.h>

enum { OB_MAX_DEG = 32 };    /* largest degree a segment can hold */
enum { OB_MAX_IN_DEG = 20 }; /* largest degree accepted from curve files */

#define OB_PI 3.14159265358979323846

typedef struct {
    int deg;                        /* polynomial degree n, 0 <= n <= OB_MAX_DEG */
    int rational;                   /* 0: all weights are exactly 1 */
    double h[OB_MAX_DEG + 1][3];    /* homogeneous control points (w x, w y, w) */
} ob_bez;

/* A named test curve: Bézier segments joined end to end, with its offsets. */
typedef struct {
    char id[64];
    char *source;       /* free text: paper, figure, page (owned) */
    char *family;       /* "published", or a random family name (owned) */
    int nseg;
    ob_bez *seg;        /* owned */
    int nd;
    double *d;          /* signed offset distances (owned) */
    char file[256];     /* where it was defined, for messages */
    int line;
    /* the largest |coordinate| of its control points as defined (a
     * B-spline's, before conversion): the scale the offset limits are
     * relative to (ob_offset_check, host/io/curvefile.h); 0 when unknown */
    double coord_max;
    /* the exact algebraic degree of its offset and whether the offset is
     * rational (offdeg.h); filled by the run command, offset_known 0 before */
    int offset_known, offset_degree, offset_rational;
} ob_curve;

/* ---- construction and access ------------------------------------------ */

/* Purpose: make a polynomial segment of degree `deg` from Euclidean points.
 * Inputs:  xy[deg+1][2].  Output: *b.  Errors: none (deg is clamped by caller). */
void ob_bez_from_points(ob_bez *b, int deg, const double (*xy)[2]);

/* Purpose: set control point i from Euclidean (x, y) and weight w (w > 0);
 * updates b->rational when w != 1. */
void ob_bez_set(ob_bez *b, int i, double x, double y, double w);

/* Euclidean control point i and its weight. */
void ob_bez_ctrl(const ob_bez *b, int i, double p[2]);
double ob_bez_weight(const ob_bez *b, int i);

/* ---- evaluation -------------------------------------------------------- */

/* Purpose: point and derivatives of the (rational) segment at t.
 * Inputs:  t (any real: outside [0,1] the polynomial is extrapolated),
 *          nder in 0..2.
 * Outputs: out[0] = C(t), out[1] = C'(t), out[2] = C''(t) (Euclidean).
 * Method:  one de Casteljau pass on homogeneous points; derivatives from the
 *          last three levels; quotient rule for rational segments. */
void ob_bez_eval(const ob_bez *b, double t, int nder, double out[][2]);

/* Euclidean point only. */
void ob_bez_point(const ob_bez *b, double t, double p[2]);

/* Purpose: unit left normal N(t) = (-y', x')/|C'|.
 * Where C'(t) vanishes (a cusp or a collapsed end leg) the direction of the
 * first non-vanishing higher derivative is used, which is the limit of the
 * normal from inside the segment.  Returns 0, or -1 if no direction exists
 * (a point-like segment); n is then (0,0). */
int ob_bez_normal(const ob_bez *b, double t, double n[2]);

/* Signed curvature at t (0 where C' vanishes). */
double ob_bez_curvature(const ob_bez *b, double t);

/* Exact offset point C(t) + d N(t). */
void ob_bez_offset_point(const ob_bez *b, double t, double d, double p[2]);

/* Purpose: the exact offset point (ob_bez_offset_point's, bit for bit) and
 *          its derivative in t, C'(t) (1 - d kappa(t)) (0 where C'
 *          vanishes), for Newton's method on crossings of offsets. */
void ob_bez_offset_point_d(const ob_bez *b, double t, double d, double p[2], double dp[2]);

/* ---- subdivision and degree ------------------------------------------- */

/* Purpose: de Casteljau split at t in (0,1) into left [0,t] and right [t,1].
 * Either output may be NULL.  Works on homogeneous points, so exact for rational. */
void ob_bez_split(const ob_bez *b, double t, ob_bez *left, ob_bez *right);

/* Purpose: the piece of b over [a,b] (0 <= a < b <= 1), reparameterized to [0,1]. */
void ob_bez_subsegment(const ob_bez *src, double a, double b, ob_bez *out);

/* Purpose: degree elevation to `to` >= deg.  Returns 0, or -1 if to > OB_MAX_DEG
 * or to < deg (out untouched). */
int ob_bez_elevate(const ob_bez *b, int to, ob_bez *out);

/* ---- shape analysis --------------------------------------------------- */

/* Purpose: inflection parameters in the open interval (0,1), ascending.
 * Method:  roots of det(P, P', P'') (homogeneous; for polynomial segments
 *          x'y'' - y'x''), a Bernstein polynomial, isolated by subdivision and
 *          polished by bisection to full precision; roots of even multiplicity
 *          (no sign change) are not inflections and are dropped.
 * Returns: number of parameters written (<= max). */
int ob_bez_inflections(const ob_bez *b, double *ts, int max);

/* Purpose: the cusps of the untrimmed d-offset: parameters in (0,1) where
 *          1 - d kappa changes sign (the offset's derivative C' (1 - d kappa)
 *          reverses), ascending.
 * Method:  signs at 64 midpoints of equal intervals, each change bisected
 *          to full precision; |1 - d kappa| <= 1e-12 is round-off of zero,
 *          not a sign (an offset that collapses to a point has no cusps).
 *          Two cusps closer than the spacing are missed.
 * Returns: the number written (<= max), or max + 1 when there are more. */
int ob_bez_offset_cusps(const ob_bez *b, double d, double *ts, int max);

/* Purpose: total turning of the tangent over [0,1] in radians (>= 0),
 * summed over `samples` sub-intervals (angle increments are < pi there). */
double ob_bez_turn(const ob_bez *b, int samples);

/* Purpose: parameter where the tangent has turned by `angle` from t = 0,
 * for a segment without inflections.  Bisection on the turn function. */
double ob_bez_turn_param(const ob_bez *b, double angle);

/* ---- whole curves ----------------------------------------------------- */

/* Always safe to call; frees what the curve owns and zeroes it. */
void ob_curve_free(ob_curve *c);

/* Purpose: count of distinct control points of k segments of degrees m_i
 * joined end to end: 1 + sum m_i (shared end points counted once). */
long ob_count_ctrl_points(const int *degs, int k);

#endif
