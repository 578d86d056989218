/*
 * cert_feet.h - nearest points ("feet") in plain floating point: where the
 * certified bound (metric_certified.h) looks.  Nothing here is rigorous and
 * nothing needs to be: a foot only chooses the correspondence whose bound is
 * then certified, or the point whose distance is then certified; a poor foot
 * makes a bound looser, never wrong.
 */
#ifndef OB_CERT_FEET_H
#define OB_CERT_FEET_H

#include "methods/metrics/cert_curve.h"

/* Point and first derivative of curve c at t, in floating point (the
 * offset's derivative C' (1 - d kappa); 0 where C' vanishes). */
void ob_cert_eval(const ob_cv *c, double t, double p[2], double d1[2]);

/* Purpose: the nearest point to p on curve q found by a scan of tab (q at
 *          the M >= 2 parameters k / (M - 1)), then regula falsi on
 *          (p - q(t)) . q'(t) over the nearest row's two spans (after a
 *          golden section there where the slope does not change sign once).
 * Outputs: *t, its parameter.  Returns: the distance |p - q(t)|. */
double ob_cert_nearest(const ob_cv *q, const double p[2], const double (*tab)[2], int M, double *t);

/* ob_cert_nearest with a hint in [0, 1] (outside: none): the spans around
 *          it are searched too and the nearer point kept, so a foot that the
 *          table's nearest row puts on another branch of a self-intersecting
 *          offset is still found where the correspondence continues. */
double ob_cert_nearest_hint(const ob_cv *q, const double p[2], const double (*tab)[2], int M, double hint, double *t);

/* Purpose: the foot on q of p(u): its parameter *t, the distance (returned)
 *          and *slope, an estimate of the foot's speed dt/du,
 *          (p' . q') / |q'|^2, 0 where the foot is an end of q. */
double ob_cert_foot(const ob_cv *p, const ob_cv *q, double u, const double (*tab)[2], int M, double *t,
                    double *slope);

/* ob_cert_foot with ob_cert_nearest_hint's hint. */
double ob_cert_foot_hint(const ob_cv *p, const ob_cv *q, double u, const double (*tab)[2], int M, double hint,
                         double *t, double *slope);

/* Purpose: the feet on q of S samples u_j = j / (S - 1) of curve p.
 * Outputs: foot[j], dist[j], slope[j], as ob_cert_foot.
 * Inputs:  tab: q at S parameters, as ob_cert_nearest. */
void ob_cert_feet(const ob_cv *p, const ob_cv *q, int S, const double (*tab)[2], double *foot, double *dist,
                  double *slope);

/* tab[k] = c(k / (M - 1)), k < M. */
void ob_cert_table(const ob_cv *c, int M, double (*tab)[2]);

#endif
