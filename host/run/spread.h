/*
 * spread.h - how much a job's timed repetitions (run --reps N) spread:
 * results.csv's time_iqr_ns and time_cv columns.
 *
 * Both are of the per-repetition totals t = fit_ns + eval_ns (the quantity
 * compare judges).  IQR: Q3 - Q1, the quartiles by linear interpolation
 * between order statistics (Q(p) at position (n - 1) p of the sorted values,
 * 0-based: R's type 7, numpy's default).  CV: the sample standard deviation
 * (n - 1 in the denominator) over the mean; 0 when the mean is 0.
 */
#ifndef OB_SPREAD_H
#define OB_SPREAD_H

/* Purpose: IQR and CV of v[0], v[stride], ... (n values); tmp has room for n.
 * Outputs: *iqr and *cv; both NAN when n < 2. */
void ob_spread(const double *v, int n, int stride, double *tmp, double *iqr, double *cv);

/* Purpose: the median of x[0..n) (n >= 1; the mean of the middle two when n
 *          is even).  Sorts x. */
double ob_median(double *x, int n);

#endif
