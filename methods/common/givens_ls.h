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
    int nrhs;       /* right-hand sides solved together (1 unless ob_gls_init_rhs) */
    double *R;      /* n rows of n + nrhs: R and the rotated right-hand sides */
    double *cn2;    /* squared weighted column norms of all rows added */
    double rss;     /* weighted residual sum of squares of the LS solutions, summed */
    int maxcol;     /* the last column any row added so far had nonzero (-1: none):
                       R is zero beyond it, so rotations stop there */
} ob_gls;

/* Doubles of memory ob_gls_init needs for n unknowns. */
size_t ob_gls_mem(int n);
/* The same for n unknowns and nrhs right-hand sides. */
size_t ob_gls_mem_rhs(int n, int nrhs);

/* Start an empty problem with n unknowns in mem[ob_gls_mem(n)]. */
void ob_gls_init(ob_gls *g, int n, double *mem);
enum { OB_GLS_MAX_RHS = 8 };

/* Start one with nrhs (1 .. OB_GLS_MAX_RHS) right-hand sides sharing the matrix (the x and y of a
 * fit to points) in mem[ob_gls_mem_rhs(n, nrhs)]: each is rotated with the
 * same rotations, so each solution has the bits that a problem of its own
 * would give. */
void ob_gls_init_rhs(ob_gls *g, int n, int nrhs, double *mem);

/* Add the row w (a . x = b) of a problem with one right-hand side (nrhs 1).  a[0..n-1] is
 * used as scratch (overwritten). */
void ob_gls_add(ob_gls *g, double *a, double b, double w);

/* Purpose: add the row w (a . x = b[k]), k < nrhs, whose only nonzeros are
 *          a[lo..hi] (a banded design: B-spline basis rows).
 * Inputs:  a[0..n-1] with zeros outside [lo, hi] (used as scratch); b[nrhs].
 * Method:  the rotations of ob_gls_add, restricted to the columns lo ..
 *          maxcol where the row or R can be nonzero: the same values as the
 *          dense loop (which multiplies zeros there), at O(band^2) instead of
 *          O(n^2) per row when the rows come in order of their band. */
void ob_gls_add_band(ob_gls *g, double *a, int lo, int hi, const double *b, double w);

/* Back-substitution into x[0..n-1].  Returns 0, or -1 if the system is
 * (numerically) rank deficient: some column has no component orthogonal to
 * the previous ones larger than rtol times its own norm (|R_jj| <=
 * rtol * ||column j||), or a column is all zero. */
int ob_gls_solve(const ob_gls *g, double *x, double rtol);
/* The same for right-hand side k (< nrhs). */
int ob_gls_solve_rhs(const ob_gls *g, int k, double *x, double rtol);

#endif
