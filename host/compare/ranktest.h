/*
 * ranktest.h - the two-sided Mann–Whitney U (Wilcoxon rank-sum) test that
 * `compare` uses to decide whether a timing change is more than noise.
 *
 * Small samples without ties get the exact null distribution of U; larger
 * samples, or samples with ties, the normal approximation with the tie
 * correction of the variance and a continuity correction of 1/2.
 *
 * Resolution of the exact test: with n1 = n2 = 3 there are C(6,3) = 20
 * equally likely rank arrangements, so the smallest two-sided p is 2/20 = 0.1
 * and nothing can be rejected at alpha = 0.05; with 4 per side the smallest p
 * is 2/70 = 0.029.  At least 4 repetitions per side are needed at 0.05.
 */
#ifndef OB_RANKTEST_H
#define OB_RANKTEST_H

/* Largest sample size per side for which the exact distribution is used. */
enum { OB_MW_EXACT_MAX = 20 };

typedef struct {
    double u;      /* U of the first sample: pairs (x_i, y_j) with x_i > y_j, ties count 1/2 */
    double p;      /* two-sided p-value in [0, 1]; NAN when a sample is empty */
    int exact;     /* 1: exact distribution, 0: normal approximation */
} ob_mw_result;

/* Purpose: two-sided Mann–Whitney U test of x[0..n1) against y[0..n2).
 * Inputs:  finite values (NANs are not allowed: filter them out first);
 *          n1, n2 >= 0.
 * Outputs: the result; p = NAN when n1 or n2 is 0 or a value is not finite.
 *          Exact when there are no ties and n1, n2 <= OB_MW_EXACT_MAX;
 *          otherwise the normal approximation (p = 1 when every value is tied).
 *          Never fails otherwise and allocates nothing on the heap. */
ob_mw_result ob_mann_whitney(const double *x, int n1, const double *y, int n2);

/* 1 when x[0..n1) and y[0..n2) are both non-empty and every value is
 * finite: the precondition of the tests here and of hlshift.h. */
int ob_samples_usable(const double *x, int n1, const double *y, int n2);

/* The smallest two-sided p the exact test can give for sizes n1, n2
 * (2 / C(n1+n2, n1), at most 1); for the report's note about too few reps. */
double ob_mw_min_p(int n1, int n2);

/* P(U <= u) under the null for sizes n1, n2 (no ties), exactly; NAN when
 * a size is 0 or above OB_MW_EXACT_MAX.  For the interval of hlshift.h. */
double ob_mw_cdf(int n1, int n2, double u);

#endif
