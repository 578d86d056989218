/*
 * ranktest.c - see ranktest.h.
 *
 * U is counted pair by pair (O(n1 n2), no sorting, no allocation); the tie
 * groups of the pooled sample are counted the same way: summing t_e^2 - 1
 * over the elements e (t_e the size of e's tie group) gives the
 * sum over groups of t^3 - t that the variance correction needs.
 *
 * Exact distribution: under the null hypothesis every choice of which n1 of
 * the N = n1 + n2 ranks belong to x is equally likely.  Walking the ranks in
 * increasing order, taking rank i (0-based) as the (k+1)-th x adds i - k to U
 * (the y's below it), so cnt[k][u] - the number of ways to pick k x's so far
 * with U = u - is a small knapsack.  Counts stay below C(40, 20) < 2^53, so
 * they are exact in doubles.
 */
#include "host/compare/ranktest.h"

#include <math.h>

enum { UMAX = OB_MW_EXACT_MAX * OB_MW_EXACT_MAX };

/* P(U <= u) and P(U >= u) under the null, by counting. */
static void exact_tails(int n1, int n2, double u, double *lo, double *hi)
{
    double cnt[OB_MW_EXACT_MAX + 1][UMAX + 1];
    const int umax = n1 * n2, n = n1 + n2;
    for (int k = 0; k <= n1; k++)
        for (int v = 0; v <= umax; v++)
            cnt[k][v] = 0;
    cnt[0][0] = 1;
    for (int i = 0; i < n; i++) {
        /* k descending: each rank is taken at most once */
        int kmax = i < n1 ? i : n1 - 1;
        for (int k = kmax; k >= 0; k--) {
            int add = i - k; /* y's below rank i when it is the (k+1)-th x */
            if (add < 0 || add > n2)
                continue;
            for (int v = umax - add; v >= 0; v--)
                cnt[k + 1][v + add] += cnt[k][v];
        }
    }
    double total = 0, below = 0, above = 0;
    for (int v = 0; v <= umax; v++) {
        total += cnt[n1][v];
        if (v <= u)
            below += cnt[n1][v];
        if (v >= u)
            above += cnt[n1][v];
    }
    *lo = below / total;
    *hi = above / total;
}

int ob_samples_usable(const double *x, int n1, const double *y, int n2)
{
    if (n1 <= 0 || n2 <= 0)
        return 0;
    for (int i = 0; i < n1; i++)
        if (!isfinite(x[i]))
            return 0;
    for (int j = 0; j < n2; j++)
        if (!isfinite(y[j]))
            return 0;
    return 1;
}

ob_mw_result ob_mann_whitney(const double *x, int n1, const double *y, int n2)
{
    ob_mw_result r = {NAN, NAN, 0};
    if (!ob_samples_usable(x, n1, y, n2))
        return r;
    double u = 0;
    for (int i = 0; i < n1; i++)
        for (int j = 0; j < n2; j++)
            u += x[i] > y[j] ? 1.0 : x[i] == y[j] ? 0.5 : 0.0;
    /* tie groups of the pooled sample: sum over elements of t_e^2 - 1 */
    double ties = 0;
    const int n = n1 + n2;
    for (int e = 0; e < n; e++) {
        double v = e < n1 ? x[e] : y[e - n1];
        double t = 0;
        for (int i = 0; i < n1; i++)
            t += x[i] == v;
        for (int j = 0; j < n2; j++)
            t += y[j] == v;
        ties += t * t - 1;
    }
    r.u = u;
    if (ties == 0 && n1 <= OB_MW_EXACT_MAX && n2 <= OB_MW_EXACT_MAX) {
        double lo, hi;
        exact_tails(n1, n2, u, &lo, &hi);
        r.exact = 1;
        r.p = fmin(1.0, 2 * fmin(lo, hi));
        return r;
    }
    const double mu = 0.5 * n1 * n2;
    const double var = (double)n1 * n2 / 12.0 * ((n + 1) - ties / ((double)n * (n - 1)));
    if (!(var > 0)) { /* every value tied: no evidence of a difference */
        r.p = 1;
        return r;
    }
    double z = (fabs(u - mu) - 0.5) / sqrt(var);
    if (z < 0)
        z = 0;
    r.p = fmin(1.0, erfc(z / sqrt(2.0)));
    return r;
}

double ob_mw_cdf(int n1, int n2, double u)
{
    if (n1 <= 0 || n2 <= 0 || n1 > OB_MW_EXACT_MAX || n2 > OB_MW_EXACT_MAX)
        return NAN;
    double lo, hi;
    exact_tails(n1, n2, u, &lo, &hi);
    return lo;
}

double ob_mw_min_p(int n1, int n2)
{
    if (n1 <= 0 || n2 <= 0)
        return 1;
    double c = 1; /* C(n1 + n2, n1), built up exactly enough for small sizes */
    for (int i = 1; i <= n1; i++)
        c = c * (n2 + i) / i;
    return fmin(1.0, 2 / c);
}
