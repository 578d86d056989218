/*
 * bernstein.h - scalar polynomials in Bernstein form on [0,1].
 *
 * A polynomial of degree n is an array a[0..n] of Bernstein coefficients.
 * These are the building blocks of the symbolic error bound (products),
 * of degree matching (elevation) and of inflection finding (roots).
 */
#ifndef OB_BERNSTEIN_H
#define OB_BERNSTEIN_H

/* Largest degree handled: squares of products of two OB_MAX_DEG rationals. */
enum { OB_BERN_MAX = 128 };

/* Binomial coefficient C(n,k) as a double (exact for n <= 66, correctly
 * rounded to a few ulps beyond). */
double ob_binom(int n, int k);

/* The basis values B_i^n(t), i = 0..n, into B[0..n] (de Casteljau triangle). */
void ob_bern_basis(int n, double t, double *B);

/* Value at t by de Casteljau (stable for t in [0,1]). */
double ob_bern_eval(const double *a, int n, double t);

/* Purpose: product c = a*b.  a has degree m, b degree n, c gets degree m+n.
 * Method:  c_k = sum_{i+j=k} C(m,i) C(n,j) / C(m+n,k) a_i b_j.
 * c must not alias a or b. */
void ob_bern_mul(const double *a, int m, const double *b, int n, double *c);

/* Purpose: degree elevation of a (degree m) to degree r >= m, into c.
 * c must not alias a. */
void ob_bern_elevate(const double *a, int m, int r, double *c);

/* Purpose: roots of a (degree n) in the open interval (0,1) where the sign
 * changes, ascending.  Method: recursive de Casteljau subdivision guided by
 * the variation-diminishing property, then bisection to full precision.
 * Resolution: round-off splits a double root into two close simple roots, so
 * roots closer than 1e-7 form a cluster that counts as one sign change if odd
 * and none if even (two true crossings closer than 1e-7 are dropped).
 * Returns the number of roots written (<= max). */
int ob_bern_roots(const double *a, int n, double *roots, int max);

#endif
