/*
 * convolution.h - offsets through an approximate normal field whose
 * derivative is parallel to C' (Ahn & Hoffmann; Kim, Lee & Ahn 2018; Ahn 2023).
 *
 * For a polynomial Bézier segment C of degree n and a scalar polynomial alpha
 * of degree p in Bernstein form, the approximate normal field
 *     N^a(t) = N(0) + int_0^t C'(u) alpha(u) du
 * is a polynomial of degree n + p (C' alpha has degree n + p - 1) whose
 * derivative is parallel to C', so C + d N^a (the convolution of C and d N^a)
 * is a polynomial of degree n + p sharing C's parameter.  The methods choose
 * alpha; the shared parts are the moments int_0^1 C' B_i^p, the 2x2 solve
 * for two unknown coefficients, and the construction of C + d N^a.
 */
#ifndef OB_CONVOLUTION_H
#define OB_CONVOLUTION_H

#include "methods/core/curve.h"
#include "methods/method.h"

/* Purpose: the moments w_i = int_0^1 C'(t) B_i^p(t) dt, i = 0..p, of a
 *          polynomial segment C of degree n >= 1:
 *          w_i = n/(n+p) sum_j C(n-1,j) C(p,i) / C(n+p-1,i+j) Delta b_j.
 * Inputs:  base (polynomial, weights 1), p >= 0 with n + p <= OB_MAX_DEG.
 * Outputs: w[0..p][2]. */
void ob_conv_moments(const ob_bez *base, int p, double w[][2]);

/* Purpose: solve v1 a1 + v2 a2 = v.  Regular case: Cramer's rule (Ahn eq. 3.4).
 *          When v1 and v2 are parallel (a straight piece, where C' keeps one
 *          direction) the system is singular but consistent if v is parallel to
 *          them too; then the minimum-norm solution is taken, which for a
 *          straight piece is a1 = a2 = 0 and gives the exact offset.
 * Returns: 0, or -1 if the system is singular and inconsistent. */
int ob_conv_solve2(const double v1[2], const double v2[2], const double v[2], double *a1,
                   double *a2);

/* Purpose: out = C + d N^a with N^a(t) = N0 + int_0^t C'(u) alpha(u) du.
 * Inputs:  base polynomial of degree n >= 1; alpha[0..p] Bernstein
 *          coefficients; N0 the start value of the field (normally N(0)).
 * Outputs: *out, polynomial of degree n + p.
 * Returns: 0, or -1 if n + p > OB_MAX_DEG or n < 1 (out untouched). */
int ob_conv_offset(const ob_bez *base, const double *alpha, int p, const double N0[2], double d,
                   ob_bez *out);

/* Purpose: the preconditions shared by the normal-field convolution methods
 *          (ahn, kim2018) and the end normals N(0), N(1).
 * Returns: OB_FIT_OK; OB_FIT_SKIP for rational input or an output degree out_deg
 *          past OB_MAX_DEG; OB_FIT_FAIL where C' vanishes at an end (a cusp); the
 *          reason in msg. */
ob_fit_status ob_conv_prepare(const ob_bez *base, int out_deg, double N0[2], double N1[2], char *msg,
                              size_t msglen);

#endif
