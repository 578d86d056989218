/*
 * cert_bounds.h - the two certified enclosures the Hausdorff certificate is
 * made of (method in metric_certified.h): an upper bound of |P(u) - Q(t(u))|
 * over an interval of u for a linear correspondence t(u), and a lower bound
 * of the distance from a point to a curve over an interval of t.
 */
#ifndef OB_CERT_BOUNDS_H
#define OB_CERT_BOUNDS_H

#include "methods/metrics/cert_curve.h"

/* Purpose: U >= |P(u) - Q(t(u))| for every u in [u0, u1], t(u) = tm + k (u - m),
 *          m = (u0 + u1) / 2; where t would leave [0, 1] the constant
 *          t = clamp(tm) is used instead (k = 0).
 * Method:  second-order Taylor form in a frame turned to e(m) (metric_certified.h).
 * Returns: U, +inf where an enclosure cannot be bounded. */
double ob_cert_upper(const ob_cv *P, const ob_cv *Q, double u0, double u1, double tm, double k);

/* ob_cert_upper in two steps, so that several lines over one interval share
 * the enclosures of P: prep (returns -1 where P cannot be enclosed; the
 * lines then give +inf), then one line (the same number as ob_cert_upper). */
typedef struct {
    double u0, u1, m;
    ob_iv hl, hr;                /* m - u0, u1 - m */
    ob_iv Pp[2], P1[2], P2[2];   /* P(m), P'(m), P'' over [u0, u1] */
    int bad;
} ob_cert_pside;
int ob_cert_upper_prep(const ob_cv *P, double u0, double u1, ob_cert_pside *ps);
double ob_cert_upper_line(const ob_cert_pside *ps, const ob_cv *Q, double tm, double k);

/* Purpose: L <= |a - Q(t)| for every t in [t0, t1] and every a in the box a[2].
 * Method:  first-order enclosure Q(m) + Q'([t0, t1]) (t - m), exact
 *          point-to-segment distance from its centre, less the radii.
 * Returns: L >= 0 (0 where nothing can be said). */
double ob_cert_lower(const ob_cv *Q, const ob_iv a[2], double t0, double t1);

#endif
