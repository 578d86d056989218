/*
 * bernstein.c - scalar Bernstein polynomials on [0,1]: products, elevation,
 * evaluation and real roots.  See bernstein.h.
 */
#include "bernstein.h"

#include <math.h>
#include <string.h>

double ob_binom(int n, int k)
{
    if (k < 0 || k > n)
        return 0.0;
    if (k > n - k)
        k = n - k;
    double r = 1.0;
    for (int i = 1; i <= k; i++)
        r = r * (n - k + i) / i;  /* exact: every partial product is an integer */
    return r;
}

double ob_bern_eval(const double *a, int n, double t)
{
    if (n < 0 || n > OB_BERN_MAX)
        return NAN;
    double q[OB_BERN_MAX + 1];
    memcpy(q, a, (size_t)(n + 1) * sizeof *q);
    const double s = 1.0 - t;
    for (int r = n; r >= 1; r--)
        for (int i = 0; i < r; i++)
            q[i] = s * q[i] + t * q[i + 1];
    return q[0];
}

void ob_bern_mul(const double *a, int m, const double *b, int n, double *c)
{
    for (int k = 0; k <= m + n; k++)
        c[k] = 0.0;
    for (int i = 0; i <= m; i++) {
        const double ai = ob_binom(m, i) * a[i];
        for (int j = 0; j <= n; j++)
            c[i + j] += ai * ob_binom(n, j) * b[j];
    }
    for (int k = 0; k <= m + n; k++)
        c[k] /= ob_binom(m + n, k);
}

void ob_bern_elevate(const double *a, int m, int r, double *c)
{
    /* c_k = sum_i C(m,i) C(r-m,k-i) / C(r,k) a_i */
    for (int k = 0; k <= r; k++) {
        double s = 0.0;
        int lo = k - (r - m) > 0 ? k - (r - m) : 0, hi = k < m ? k : m;
        for (int i = lo; i <= hi; i++)
            s += ob_binom(m, i) * ob_binom(r - m, k - i) * a[i];
        c[k] = s / ob_binom(r, k);
    }
}

/* Split coefficients at the midpoint: left and right halves (same degree). */
static void split_half(const double *a, int n, double *l, double *r)
{
    double q[OB_BERN_MAX + 1];
    memcpy(q, a, (size_t)(n + 1) * sizeof *q);
    l[0] = q[0];
    r[n] = q[n];
    for (int lev = 1; lev <= n; lev++) {
        for (int i = 0; i <= n - lev; i++)
            q[i] = 0.5 * (q[i] + q[i + 1]);
        l[lev] = q[0];
        r[n - lev] = q[n - lev];
    }
}

static int sign_changes(const double *a, int n)
{
    int c = 0, prev = 0;
    for (int i = 0; i <= n; i++) {
        int s = (a[i] > 0) - (a[i] < 0);
        if (s == 0)
            continue;
        if (prev && s != prev)
            c++;
        prev = s;
    }
    return c;
}

/* Bisection of the polynomial (original coefficients) on [lo,hi] where the
 * end values have opposite signs; runs until the interval stops shrinking. */
static double bisect(const double *a, int n, double lo, double hi)
{
    double flo = ob_bern_eval(a, n, lo);
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;
        double fm = ob_bern_eval(a, n, mid);
        if (fm == 0.0)
            return mid;
        if ((fm > 0) == (flo > 0)) {
            lo = mid;
            flo = fm;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

/* Isolate on [lo,hi] using the coefficients c of the restriction. */
static void isolate(const double *orig, int n, const double *c, double lo, double hi,
                    int depth, double *roots, int *nr, int max)
{
    if (*nr >= max)
        return;
    int v = sign_changes(c, n);
    if (v == 0)
        return;
    if (v == 1 && (c[0] > 0) != (c[n] > 0) && c[0] != 0 && c[n] != 0) {
        roots[(*nr)++] = bisect(orig, n, lo, hi);
        return;
    }
    if (depth > 60 || hi - lo < 1e-15) {
        /* a cluster or multiple root: report it once if the ends differ in sign */
        double flo = ob_bern_eval(orig, n, lo), fhi = ob_bern_eval(orig, n, hi);
        if ((flo > 0) != (fhi > 0) && flo != 0 && fhi != 0)
            roots[(*nr)++] = 0.5 * (lo + hi);
        return;
    }
    double l[OB_BERN_MAX + 1], r[OB_BERN_MAX + 1];
    split_half(c, n, l, r);
    double mid = 0.5 * (lo + hi);
    isolate(orig, n, l, lo, mid, depth + 1, roots, nr, max);
    /* a root exactly at the split point: the left half ends at zero */
    if (l[n] == 0.0 && mid > 0 && mid < 1 && *nr < max) {
        double fa = ob_bern_eval(orig, n, mid - 1e-9), fb = ob_bern_eval(orig, n, mid + 1e-9);
        if ((fa > 0) != (fb > 0))
            roots[(*nr)++] = mid;
    }
    isolate(orig, n, r, mid, hi, depth + 1, roots, nr, max);
}

int ob_bern_roots(const double *a, int n, double *roots, int max)
{
    if (n < 1 || n > OB_BERN_MAX)
        return 0;
    int nr = 0;
    isolate(a, n, a, 0.0, 1.0, 0, roots, &nr, max);
    /* drop roots at the ends: only the open interval counts */
    int k = 0;
    for (int i = 0; i < nr; i++)
        if (roots[i] > 1e-12 && roots[i] < 1.0 - 1e-12)
            roots[k++] = roots[i];
    return k;
}
