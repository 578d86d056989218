/*
 * givens_ls.h - weighted linear least squares by row-wise Givens QR, in
 * caller-owned memory (no allocation), shared by zhao.c and hoschek.c.
 *
 * Rows a x = b are added one at a time and rotated into an upper-triangular
 * factor R (n x n) with the rotated right-hand side beside it, so the memory
 * is O(n^2) whatever the number of rows, and the normal equations (which
 * square the condition number) are never formed.  The solution minimizes
 * sum_i w_i^2 (a_i . x - b_i)^2.
 */
#ifndef OB_GIVENS_LS_H
#define OB_GIVENS_LS_H

#include <stddef.h>

typedef struct {
    int n;          /* unknowns */
    double *R;      /* n rows of n + 1: R and the rotated right-hand side */
    double *cn2;    /* squared weighted column norms of all rows added */
    double rss;     /* weighted residual sum of squares of the LS solution */
} ob_gls;

/* Doubles of memory ob_gls_init needs for n unknowns. */
size_t ob_gls_mem(int n);

/* Start an empty problem with n unknowns in mem[ob_gls_mem(n)]. */
void ob_gls_init(ob_gls *g, int n, double *mem);

/* Add the row w (a . x = b).  a[0..n-1] is used as scratch (overwritten). */
void ob_gls_add(ob_gls *g, double *a, double b, double w);

/* Back-substitution into x[0..n-1].  Returns 0, or -1 if the system is
 * (numerically) rank deficient: some column has no component orthogonal to
 * the previous ones larger than rtol times its own norm (|R_jj| <=
 * rtol * ||column j||), or a column is all zero. */
int ob_gls_solve(const ob_gls *g, double *x, double rtol);

#endif
