/*
 * spread.c - see spread.h.
 */
#include "host/run/spread.h"

#include <math.h>
#include <stdlib.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Quantile p of the sorted s[0..n) by linear interpolation (type 7). */
static double quantile7(const double *s, int n, double p)
{
    const double h = (n - 1) * p;
    const int i = (int)floor(h);
    return i + 1 < n ? s[i] + (h - i) * (s[i + 1] - s[i]) : s[n - 1];
}

void ob_spread(const double *v, int n, int stride, double *tmp, double *iqr, double *cv)
{
    *iqr = *cv = NAN;
    if (n < 2)
        return;
    double mean = 0;
    for (int r = 0; r < n; r++)
        mean += (tmp[r] = v[(size_t)r * (size_t)stride]);
    mean /= n;
    double ss = 0;
    for (int r = 0; r < n; r++)
        ss += (tmp[r] - mean) * (tmp[r] - mean);
    qsort(tmp, (size_t)n, sizeof *tmp, cmp_double);
    *iqr = quantile7(tmp, n, 0.75) - quantile7(tmp, n, 0.25);
    *cv = mean > 0 ? sqrt(ss / (n - 1)) / mean : 0;
}

double ob_median(double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, cmp_double);
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}
