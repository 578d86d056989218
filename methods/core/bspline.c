/*
 * bspline.c - B-spline (optionally rational) to Bézier segments.
 *
 * Each non-empty span [u_k, u_{k+1}] of the domain is converted on its own.
 * Inserting u_k and u_{k+1} until each has multiplicity p turns the p+1
 * control points that act on the span into its Bézier control points; the
 * Bézier point j is then the blossom of the span at (u_k^(p-j), u_{k+1}^j),
 * which is what the triangle of insertions below computes (one insertion of
 * the knot x_r per level r, as in de Boor's algorithm).  Working span by span
 * needs no global knot bookkeeping, treats clamped and unclamped vectors
 * alike, and every denominator is at least u_{k+1} - u_k > 0.
 * Rational curves are handled by doing all of this on (w x, w y, w).
 */
#include "methods/core/bspline.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Checks everything ob_bspline_to_bezier promises to reject.
 * Returns 0 or -1 with a message. */
static int validate(int p, int npts, const double *knots, const double (*pts)[3],
                    ob_err *err)
{
    if (p < 1 || p > OB_MAX_IN_DEG)
        return ob_fail(err, "bspline degree %d outside 1..%d", p, (int)OB_MAX_IN_DEG);
    if (npts < p + 1)
        return ob_fail(err, "bspline of degree %d needs at least %d control points, got %d",
                    p, p + 1, npts);
    if (npts > INT_MAX - p - 1)
        return ob_fail(err, "too many control points (%d)", npts);
    if (!knots || !pts)
        return ob_fail(err, "bspline: missing knots or control points");
    const int nk = npts + p + 1;
    for (int i = 0; i < nk; i++) {
        if (!isfinite(knots[i]))
            return ob_fail(err, "knot %d is not finite", i);
        if (i > 0 && knots[i] < knots[i - 1])
            return ob_fail(err, "knots decrease at index %d (%.17g < %.17g)", i,
                        knots[i], knots[i - 1]);
    }
    if (!(knots[p] < knots[npts]))
        return ob_fail(err, "empty domain: knots[%d] = knots[%d] = %.17g", p, npts,
                    knots[p]);
    for (int i = 0; i < npts; i++) {
        if (!isfinite(pts[i][0]) || !isfinite(pts[i][1]) || !isfinite(pts[i][2]))
            return ob_fail(err, "control point %d is not finite", i);
        if (!(pts[i][2] > 0))
            return ob_fail(err, "control point %d has weight %.17g (must be > 0)", i,
                        pts[i][2]);
    }
    return 0;
}

int ob_bspline_span_to_bezier(int p, int k, const double *U, const double (*pts)[3],
                              int rational, ob_bez *out)
{
    const double a = U[k], b = U[k + 1];
    /* local knots t[1..2p] = U[k-p+1 .. k+p]; t[p] = a, t[p+1] = b */
    const double *t = U + (k - p);
    double q[OB_MAX_IN_DEG + 1][3];

    out->deg = p;
    out->rational = 0;
    for (int j = 0; j <= p; j++) {
        for (int i = 0; i <= p; i++) {
            const double *P = pts[k - p + i];
            q[i][0] = P[0] * P[2];
            q[i][1] = P[1] * P[2];
            q[i][2] = P[2];
        }
        /* level r inserts x_r = a for r <= p-j, else b; the order does not
         * matter (the blossom is symmetric) */
        for (int r = 1; r <= p; r++) {
            const double x = r <= p - j ? a : b;
            for (int i = p; i >= r; i--) {
                const double lo = t[i], hi = t[i + p + 1 - r];
                const double al = (x - lo) / (hi - lo); /* hi - lo >= b - a > 0 */
                for (int c = 0; c < 3; c++)
                    q[i][c] = (1.0 - al) * q[i - 1][c] + al * q[i][c];
            }
        }
        const double w = rational ? q[p][2] : 1.0;
        const double x = q[p][0] / w, y = q[p][1] / w;
        if (!isfinite(x) || !isfinite(y) || !(w > 0) || !isfinite(w))
            return -1;
        ob_bez_set(out, j, x, y, w);
    }
    return 0;
}

int ob_bspline_to_bezier(int p, int npts, const double *knots,
                         const double (*pts)[3], ob_bez **segs, int *nseg,
                         ob_err *err)
{
    if (!segs || !nseg)
        return ob_fail(err, "bspline: missing output arguments");
    *segs = NULL;
    *nseg = 0;
    if (validate(p, npts, knots, pts, err))
        return -1;

    int n = 0;
    for (int k = p; k < npts; k++)
        n += knots[k] < knots[k + 1];
    ob_bez *s = calloc((size_t)n, sizeof *s);
    if (!s) {
        ob_fail(err, "bspline: out of memory (%d segments)", n);
        return -2;
    }

    int m = 0;
    for (int k = p; k < npts; k++) {
        if (!(knots[k] < knots[k + 1]))
            continue;
        /* polynomial on this span iff the weights acting on it are all 1 */
        int rational = 0;
        for (int i = k - p; i <= k; i++)
            rational |= pts[i][2] != 1.0;
        if (ob_bspline_span_to_bezier(p, k, knots, pts, rational, &s[m])) {
            free(s);
            return ob_fail(err, "bspline: overflow converting span %d", k);
        }
        m++;
    }
    *segs = s;
    *nseg = m;
    return 0;
}
