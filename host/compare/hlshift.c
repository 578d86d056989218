/*
 * hlshift.c - see hlshift.h.  The differences are all formed and sorted
 * (O(n1 n2 log(n1 n2)); a row has a handful of repetitions).  The critical
 * rank comes from the exact null distribution of U (ob_mw_cdf, ranktest.c)
 * for small samples, the normal approximation otherwise.
 */
#include "host/compare/hlshift.h"

#include <math.h>
#include <stdlib.h>

#include "host/compare/ranktest.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The upper alpha/2 quantile of the standard normal, by bisection on erfc
 * (P(Z > z) = erfc(z / sqrt 2) / 2); exact enough for a rank. */
static double z_upper(double half_alpha)
{
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; i++) {
        double mid = 0.5 * (lo + hi);
        if (0.5 * erfc(mid / sqrt(2.0)) > half_alpha)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

int ob_hl_rank(int n1, int n2, double alpha, double *level)
{
    if (level)
        *level = NAN;
    if (n1 <= 0 || n2 <= 0 || !(alpha > 0 && alpha < 1))
        return 0;
    const int mn = n1 * n2;
    int k = 0;
    if (n1 <= OB_MW_EXACT_MAX && n2 <= OB_MW_EXACT_MAX) {
        /* largest k with P(U <= k - 1) <= alpha / 2; the cdf rises with k
         * (and passes 1/2 by k = (mn + 1) / 2, the distribution is symmetric) */
        while (k < (mn + 1) / 2 && ob_mw_cdf(n1, n2, k) <= alpha / 2)
            k++;
        if (level)
            *level = k ? 1 - 2 * ob_mw_cdf(n1, n2, k - 1) : 0;
        return k;
    }
    const double c = 0.5 * mn - z_upper(alpha / 2) * sqrt((double)mn * (n1 + n2 + 1) / 12.0);
    k = c < 1 ? 0 : (int)floor(c);
    if (level)
        *level = k ? 1 - alpha : 0;
    return k;
}

ob_hl_result ob_hl_shift(const double *x, int n1, const double *y, int n2, double alpha)
{
    ob_hl_result r = {NAN, NAN, NAN, 0, NAN};
    if (!ob_samples_usable(x, n1, y, n2) || (double)n1 * n2 > OB_HL_MAX_PAIRS)
        return r;
    const size_t mn = (size_t)n1 * (size_t)n2;
    double *d = malloc(mn * sizeof *d);
    if (!d)
        return r;
    for (int i = 0; i < n1; i++)
        for (int j = 0; j < n2; j++)
            d[(size_t)i * n2 + j] = x[i] - y[j];
    qsort(d, mn, sizeof *d, cmp_double);
    r.est = mn % 2 ? d[mn / 2] : 0.5 * (d[mn / 2 - 1] + d[mn / 2]);
    r.k = ob_hl_rank(n1, n2, alpha, &r.level);
    if (r.k) {
        r.lo = d[r.k - 1];
        r.hi = d[mn - (size_t)r.k];
    } else {
        r.lo = -INFINITY;
        r.hi = INFINITY;
    }
    free(d);
    return r;
}
