/*
 * offdeg.h - the exact algebraic degree of a rational curve's offset, and
 * whether the offset is rational (San Segundo, Sendra & Sendra, "Algorithms
 * for offset curves and surfaces", ICM 2006 poster).
 *
 * For a parameterization (X/W, Y/W) with gcd(X, Y, W) = 1:
 *   N1 = W X' - W' X,  N2 = W Y' - W' Y,  N = N1^2 + N2^2,
 *   n = max deg(X, Y, W),  tau = max deg(N1, N2),
 *   mu = deg gcd(N gcd(X, Y)^2, W^2 gcd(N1, N2)^2),
 *   deg O_d = 2n + 2 tau - mu   for d != 0 (and d != r for a circle of radius r).
 * The offset is rational (two rational components) exactly when ||N|| is
 * rational, i.e. when N is a perfect square (a Pythagorean-hodograph curve;
 * the seed's algorithm, step 2).
 *
 * Arithmetic is exact, on FLINT's integer polynomials: each double control
 * coordinate is converted to the rational it is exactly (a double is m 2^e),
 * so the degree is that of the curve as stored, e.g. a coordinate 0.1 is
 * 3602879701896397 / 2^55, not 1/10.  The formula needs a proper
 * parameterization (one t per point): true of Bézier segments in general, not
 * of degree-elevated or reparameterized copies of lower-degree curves.
 *
 * Cross-check (independent of the formula): the number of intersections of
 * the offset with a random line, from the polynomial whose roots are the
 * parameters of those intersections, (a X + b Y - c W)^2 N - d^2 W^2
 * (b N1 - a N2)^2, less its factors common to three random lines (they do
 * not depend on the line: spurious).
 */
#ifndef OB_OFFDEG_H
#define OB_OFFDEG_H

#include <stddef.h>

#include "methods/core/curve.h"

typedef struct {
    int degree;         /* n of the parameterization, gcd(X, Y, W) removed */
    int tau, mu;
    int offset_degree;  /* 2n + 2 tau - mu */
    int rational;       /* 1: N is a perfect square, the offset is rational */
} ob_offdeg;

/* Purpose: the offset degree and rationality of one Bézier segment (exact).
 * Method:  a straight line (the tangent keeps its direction) gives 2 for any
 *          parameterization; otherwise the parameterization must be proper
 *          (its index, from gcd(X(t)W(s) - X(s)W(t), Y(t)W(s) - Y(s)W(t)) at
 *          fixed rational s, is 1), and the formula above applies.
 * Returns: 0; -1 with the reason in msg when the segment is a point (no
 *          normal anywhere) or its parameterization is improper. */
int ob_offset_degree(const ob_bez *b, ob_offdeg *out, char *msg, size_t msglen);

/* Purpose: the degree of the offset at distance d = dnum / dden (dden > 0)
 *          counted as its intersections with random lines (see above);
 *          seed picks the lines.  Returns the count, or -1 (a point-like
 *          segment, no memory). */
long ob_offset_degree_by_lines(const ob_bez *b, long dnum, long dden, unsigned long seed);

/* Purpose: the same for a whole curve: the largest offset degree over its
 *          segments (each segment's offset is an algebraic curve of its own)
 *          and whether every segment's offset is rational.  Returns 0, or -1
 *          with the reason in msg. */
int ob_curve_offset_degree(const ob_curve *c, int *degree, int *rational, char *msg, size_t msglen);

#endif
