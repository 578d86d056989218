/*
 * test_noise.c - the statistics of "noise you can see": the Hodges–Lehmann
 * shift and its Moses interval (host/compare/hlshift.h), the exact null
 * distribution of U it uses (ob_mw_cdf), the spread columns of run --reps
 * (host/run/spread.h) and the load warning (host/run/hostinfo.h).
 *
 * The references are computed here independently: every pairwise difference
 * by a double loop and an insertion sort, the distribution of U by
 * enumerating every choice of which n1 of the n1 + n2 ranks are the first
 * sample (bit masks), quartiles by their definition on a sorted copy.  The
 * critical ranks are also checked against published table values of the
 * two-sided 0.05 Mann–Whitney test (U_crit(5,5) = 2, U_crit(10,10) = 23,
 * U_crit(8,6) = 8: k = U_crit + 1).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "tests/testlib.h"
#include "host/compare/hlshift.h"
#include "host/compare/ranktest.h"
#include "host/run/hostinfo.h"
#include "host/run/spread.h"

/* ---- independent references ---- */

static void insertion_sort(double *v, int n)
{
    for (int i = 1; i < n; i++) {
        double x = v[i];
        int j = i - 1;
        while (j >= 0 && v[j] > x) {
            v[j + 1] = v[j];
            j--;
        }
        v[j + 1] = x;
    }
}

/* count[u] = number of rank subsets of size n1 of n1 + n2 with U = u. */
static double ref_u_counts(int n1, int n2, double *count)
{
    const int n = n1 + n2;
    double total = 0;
    for (int u = 0; u <= n1 * n2; u++)
        count[u] = 0;
    for (unsigned long mask = 0; mask < (1ul << n); mask++) {
        if (__builtin_popcountl(mask) != n1)
            continue;
        int u = 0, ys_below = 0;
        for (int r = 0; r < n; r++) {
            if (mask >> r & 1)
                u += ys_below;  /* an x at rank r is above every y below it */
            else
                ys_below++;
        }
        count[u]++;
        total++;
    }
    return total;
}

static double ref_cdf(int n1, int n2, int u)
{
    double count[26 * 26], below = 0;
    const double total = ref_u_counts(n1, n2, count);
    for (int v = 0; v <= u && v <= n1 * n2; v++)
        below += count[v];
    return below / total;
}

/* The largest k with P(U <= k - 1) <= alpha / 2 (k = 0: none). */
static int ref_k(int n1, int n2, double alpha)
{
    int k = 0;
    while (k < n1 * n2 && ref_cdf(n1, n2, k) <= alpha / 2)
        k++;
    return k;
}

/* ---- tests ---- */

static void test_cdf(void)
{
    for (int n1 = 1; n1 <= 7; n1++)
        for (int n2 = 1; n2 <= 7; n2++)
            for (int u = 0; u <= n1 * n2; u += 1 + n1 * n2 / 7)
                CHECK_NEAR(ob_mw_cdf(n1, n2, u), ref_cdf(n1, n2, u), 1e-12, "P(U <= u) by enumeration");
    CHECK(isnan(ob_mw_cdf(0, 3, 0)) && isnan(ob_mw_cdf(OB_MW_EXACT_MAX + 1, 3, 0)), "cdf: out of range is NAN");
}

static void test_rank(void)
{
    CHECK(ob_hl_rank(5, 5, 0.05, NULL) == 3, "k(5,5) = U_crit 2 + 1 (got %d)", ob_hl_rank(5, 5, 0.05, NULL));
    CHECK(ob_hl_rank(10, 10, 0.05, NULL) == 24, "k(10,10) = U_crit 23 + 1 (got %d)", ob_hl_rank(10, 10, 0.05, NULL));
    CHECK(ob_hl_rank(8, 6, 0.05, NULL) == 9, "k(8,6) = U_crit 8 + 1 (got %d)", ob_hl_rank(8, 6, 0.05, NULL));
    CHECK(ob_hl_rank(3, 3, 0.05, NULL) == 0, "3 vs 3 at 0.05: no bounded interval");
    CHECK(ob_hl_rank(4, 4, 0.05, NULL) == 1, "4 vs 4 at 0.05: the extremes (P(U <= 0) = 1/70)");
    double level;
    ob_hl_rank(5, 5, 0.05, &level);
    CHECK_NEAR(level, 1 - 2 * ref_cdf(5, 5, 2), 1e-12, "coverage of the 5 vs 5 interval");
    CHECK(level >= 0.95, "coverage at least 1 - alpha (%g)", level);
    const double alphas[] = {0.01, 0.05, 0.1, 0.2};
    for (int a = 0; a < 4; a++)
        for (int n1 = 1; n1 <= 8; n1++)
            for (int n2 = 1; n2 <= 8; n2++) {
                const int k = ob_hl_rank(n1, n2, alphas[a], NULL), want = ref_k(n1, n2, alphas[a]);
                CHECK(k == want, "k(%d,%d) at alpha %g: %d, by enumeration %d", n1, n2, alphas[a], k, want);
            }
    /* beyond OB_MW_EXACT_MAX: floor(mn/2 - z sqrt(mn(m+n+1)/12)); 30 vs 30: 450 - 1.959964 * 67.6387 */
    CHECK(ob_hl_rank(30, 30, 0.05, NULL) == 317, "normal approximation k(30,30) = 317 (got %d)",
          ob_hl_rank(30, 30, 0.05, NULL));
}

/* HL estimate and interval against all pairwise differences, sorted here. */
static void check_hl(const double *x, int n1, const double *y, int n2, double alpha)
{
    double d[64];
    int m = 0;
    for (int i = 0; i < n1; i++)
        for (int j = 0; j < n2; j++)
            d[m++] = x[i] - y[j];
    insertion_sort(d, m);
    const double med = m % 2 ? d[m / 2] : (d[m / 2 - 1] + d[m / 2]) / 2;
    const int k = ref_k(n1, n2, alpha);
    const ob_hl_result h = ob_hl_shift(x, n1, y, n2, alpha);
    CHECK_NEAR(h.est, med, 1e-15, "HL estimate = median of the differences");
    CHECK(h.k == k, "rank %d vs %d (%d vs %d)", h.k, k, n1, n2);
    if (k) {
        CHECK(h.lo == d[k - 1] && h.hi == d[m - k], "interval [D_(k), D_(mn+1-k)]: [%g, %g] vs [%g, %g]", h.lo,
              h.hi, d[k - 1], d[m - k]);
    } else {
        CHECK(isinf(h.lo) && h.lo < 0 && isinf(h.hi) && h.hi > 0, "unbounded interval");
    }
}

static void test_hl(void)
{
    /* a worked case: x = y + 10 exactly, so every interval holds 10 and the estimate is 10 */
    const double y[] = {1, 2, 3, 4, 5}, x[] = {11, 12, 13, 14, 15};
    ob_hl_result h = ob_hl_shift(x, 5, y, 5, 0.05);
    CHECK(h.est == 10 && h.lo < 10 && h.hi > 10 && h.lo == 7 && h.hi == 13,
          "shift 10: est %g in [%g, %g] (differences 10 + i - j: D_(3) = 7, D_(23) = 13)", h.est, h.lo, h.hi);
    for (int t = 0; t < 300; t++) {
        double a[8], b[8];
        const int n1 = 1 + (int)(urand() * 8), n2 = 1 + (int)(urand() * 8);
        for (int i = 0; i < n1; i++)
            a[i] = 1 + urand();
        for (int j = 0; j < n2; j++)
            b[j] = urand() < 0.2 && j ? b[j - 1] : 1 + urand(); /* some ties */
        check_hl(a, n1, b, n2, t % 3 ? 0.05 : 0.2);
    }
    CHECK(isnan(ob_hl_shift(x, 0, y, 5, 0.05).est), "empty sample: NAN");
    const double bad[] = {1, NAN};
    CHECK(isnan(ob_hl_shift(bad, 2, y, 5, 0.05).est), "a NAN value: NAN");
}

static void test_spread(void)
{
    const double v[] = {4, 1, 3, 2};
    double tmp[8], iqr, cv;
    ob_spread(v, 4, 1, tmp, &iqr, &cv);
    CHECK_NEAR(iqr, 1.5, 1e-15, "IQR of 1..4: Q3 3.25 - Q1 1.75");
    CHECK_NEAR(cv, sqrt(5.0 / 3) / 2.5, 1e-15, "CV of 1..4: sd sqrt(5/3) / mean 2.5");
    /* strided: every other value of {10, x, 20, x, 30, x} */
    const double w[] = {10, -1, 30, -1, 20, -1};
    ob_spread(w, 3, 2, tmp, &iqr, &cv);
    CHECK_NEAR(iqr, 10, 1e-12, "IQR of 10, 20, 30: 25 - 15");
    CHECK_NEAR(cv, 10.0 / 20, 1e-15, "CV of 10, 20, 30");
    ob_spread(v, 1, 1, tmp, &iqr, &cv);
    CHECK(isnan(iqr) && isnan(cv), "one repetition: no spread");
    const double z[] = {0, 0, 0};
    ob_spread(z, 3, 1, tmp, &iqr, &cv);
    CHECK(iqr == 0 && cv == 0, "all zero: IQR 0, CV 0");
}

static void test_load(void)
{
    ob_loadavg l = {NAN, NAN, NAN, 0};
    char buf[512];
    CHECK(!ob_load_warning(&l, 5, 2, buf, sizeof buf), "never read: no warning");
    l = (ob_loadavg){1.0, 1.5, 2.5, 3};
    CHECK(ob_load_warning(&l, 5, 2, buf, sizeof buf) && strstr(buf, "2.50") && strstr(buf, "2 cores"),
          "max 2.5 over 2 cores: %s", buf);
    CHECK(!ob_load_warning(&l, 0, 2, buf, sizeof buf), "no --reps: no warning");
    CHECK(!ob_load_warning(&l, 5, 4, buf, sizeof buf), "within 4 cores: no warning");
}

int main(void)
{
    testlib_seed(20);
    test_cdf();
    test_rank();
    test_hl();
    test_spread();
    test_load();
    return check_done();
}
