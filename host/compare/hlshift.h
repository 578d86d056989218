/*
 * hlshift.h - the Hodges–Lehmann estimate of the shift between two samples
 * and its distribution-free confidence interval (Moses' interval, the one
 * that inverts the Mann–Whitney test of ranktest.h), for `compare`'s
 * timing ratios.
 *
 * Applied to log times, the shift is the log of the ratio new/base: with x
 * the log times of NEW's repetitions and y those of BASE's, exp(estimate) is
 * the median of the n1 * n2 ratios x_i / y_j and [exp(lo), exp(hi)] is a
 * confidence interval for the ratio at level >= 1 - alpha.
 *
 * The interval: the n1 n2 pairwise differences D_(1) <= ... <= D_(n1 n2),
 * lo = D_(k), hi = D_(n1 n2 + 1 - k) with k the largest whole number such
 * that P(U <= k - 1) <= alpha / 2 under the null (U the Mann–Whitney
 * statistic).  Exact null distribution up to OB_MW_EXACT_MAX per side (ties
 * are ignored: the interval is then slightly conservative), beyond that the
 * normal approximation k = floor(n1 n2 / 2 - z_{alpha/2} sqrt(n1 n2 (n1 + n2
 * + 1) / 12)).  When no k >= 1 exists (too few values: 3 vs 3 at alpha
 * 0.05) the interval is unbounded: lo = -inf, hi = +inf.
 */
#ifndef OB_HLSHIFT_H
#define OB_HLSHIFT_H

typedef struct {
    double est;     /* median of the pairwise differences x_i - y_j; NAN when a sample is empty */
    double lo, hi;  /* the interval; -inf / +inf when the samples are too small */
    int k;          /* rank of lo among the sorted differences (1-based); 0: unbounded */
    double level;   /* the interval's exact coverage 1 - 2 P(U <= k - 1) (normal: 1 - alpha) */
} ob_hl_result;

/* Purpose: the HL estimate and interval of x[0..n1) minus y[0..n2) at
 *          level 1 - alpha.
 * Inputs:  finite values, n1, n2 >= 0, 0 < alpha < 1.  At most
 *          OB_HL_MAX_PAIRS differences (the repetitions of one row, or of a
 *          method's totals, are far fewer).
 * Outputs: the result (est NAN, lo/hi NAN when a sample is empty, a value is
 *          not finite, or there are too many pairs / no memory). */
enum { OB_HL_MAX_PAIRS = 1 << 22 };
ob_hl_result ob_hl_shift(const double *x, int n1, const double *y, int n2, double alpha);

/* The k of the interval above for sizes n1, n2 at level 1 - alpha (0: no
 * bounded interval), and the coverage in *level (may be NULL). */
int ob_hl_rank(int n1, int n2, double alpha, double *level);

#endif
