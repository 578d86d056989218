/*
 * cert_bounds.h - the two certified enclosures the Hausdorff certificate is
 * made of (method in metric_certified.h): an upper bound of |P(u) - Q(t(u))|
 * over an interval of u for a linear or quadratic correspondence t(u), and a lower bound
 * of the distance from a point to a curve over an interval of t.
 */
#ifndef OB_CERT_BOUNDS_H
#define OB_CERT_BOUNDS_H

#include "methods/metrics/cert_curve.h"

/* Purpose: U >= |P(u) - Q(t(u))| for every u in [u0, u1], t(u) = tm + k (u - m),
 *          m = (u0 + u1) / 2; where t would leave [0, 1] the constant
 *          t = clamp(tm) is used instead (k = 0).
 * Method:  the least of two Taylor forms in a frame turned to e(m)
 *          (metric_certified.h): second order, e(m) + e'(m) h + E2 h^2 / 2,
 *          and third order, e(m) + e'(m) h + e''(m) h^2 / 2 + E3 h^3 / 6
 *          (E2, E3 enclosures of e'', e''' over the interval).
 * Returns: U, +inf where an enclosure cannot be bounded. */
double ob_cert_upper(const ob_cv *P, const ob_cv *Q, double u0, double u1, double tm, double k);

/* ob_cert_upper in two steps, so that several lines over one interval share
 * the enclosures of P: prep (returns -1 where P cannot be enclosed; the
 * lines then give +inf), then one line (the same number as ob_cert_upper
 * with third = 1).  third = 0: the second-order form alone (no third
 * derivatives: ~40 % less time per line, enough wherever the target is
 * well above round-off). */
typedef struct {
    double u0, u1, m;
    ob_iv hl, hr;                /* m - u0, u1 - m */
    ob_iv Pp[2], P1[2], P2m[2];  /* P(m), P'(m), P''(m) */
    ob_iv P2[2], P3[2];          /* P'', P''' over [u0, u1] */
    int bad;                     /* P cannot be enclosed: every line +inf */
    int third;                   /* P''' enclosed: the third-order form is tried */
} ob_cert_pside;
int ob_cert_upper_prep(const ob_cv *P, double u0, double u1, int third, ob_cert_pside *ps);
double ob_cert_upper_line(const ob_cert_pside *ps, const ob_cv *Q, double tm, double k);

/* ob_cert_upper_line for a quadratic correspondence t(u) = tm + k h + c h^2,
 * h = u - m (c = 0: the line): its slip along Q is O(h^3) where a line's is
 * O(h^2), which a piece 1e-10 from Q needs (the slip enters the bound as
 * slip^2 / distance).  Any map into [0, 1] gives a bound; t is held at
 * tm where the quadratic would leave [0, 1]. */
double ob_cert_upper_quad(const ob_cert_pside *ps, const ob_cv *Q, double tm, double k, double c);

/* Purpose: L <= |a - Q(t)| for every t in [t0, t1] and every a in the box a[2].
 * Method:  first-order enclosure Q(m) + Q'([t0, t1]) (t - m), exact
 *          point-to-segment distance from its centre, less the radii.
 * Returns: L >= 0 (0 where nothing can be said). */
double ob_cert_lower(const ob_cv *Q, const ob_iv a[2], double t0, double t1);

#endif
