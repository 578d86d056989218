/*
 * bernstein.c - scalar Bernstein polynomials on [0,1]: products, elevation,
 * evaluation and real roots.  See bernstein.h.
 */
#include "methods/core/bernstein.h"

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

void ob_bern_basis(int n, double t, double *B)
{
    const double s = 1.0 - t;
    B[0] = 1.0;
    for (int k = 1; k <= n; k++) {
        B[k] = t * B[k - 1];
        for (int j = k - 1; j >= 1; j--)
            B[j] = s * B[j] + t * B[j - 1];
        B[0] *= s;
    }
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

/* Bisection on the local representation c (degree n) of the polynomial over
 * [lo,hi], whose end values are exactly c[0] and c[n]: the sign change that
 * isolated the root is the one bisected, whatever the round-off elsewhere. */
static double bisect_local(const double *c, int n, double lo, double hi)
{
    double a = 0.0, b = 1.0, fa = c[0];
    for (int it = 0; it < 200; it++) {
        double m = 0.5 * (a + b);
        if (m <= a || m >= b)
            break;
        double fm = ob_bern_eval(c, n, m);
        if (fm == 0.0) {
            a = b = m;
            break;
        }
        if ((fm > 0) == (fa > 0)) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    return lo + (hi - lo) * 0.5 * (a + b);
}

/* Sign of the first non-zero coefficient walking from index i by step. */
static int sign_from(const double *c, int n, int i, int step)
{
    for (; i >= 0 && i <= n; i += step)
        if (c[i] != 0.0)
            return c[i] > 0 ? 1 : -1;
    return 0;
}

/* Isolate on [lo,hi] using the coefficients c of the restriction. */
static void isolate(const double *c, int n, double lo, double hi, int depth, double *roots, int *nr, int max)
{
    if (*nr >= max)
        return;
    int v = sign_changes(c, n);
    if (v == 0)
        return;
    if (v == 1 && c[0] != 0 && c[n] != 0) {
        roots[(*nr)++] = bisect_local(c, n, lo, hi);
        return;
    }
    if (depth > 60 || hi - lo < 1e-15) {
        /* a cluster below resolution: a root if the ends differ in sign */
        int s0 = sign_from(c, n, 0, 1), s1 = sign_from(c, n, n, -1);
        if (s0 && s1 && s0 != s1)
            roots[(*nr)++] = 0.5 * (lo + hi);
        return;
    }
    double l[OB_BERN_MAX + 1], r[OB_BERN_MAX + 1];
    split_half(c, n, l, r);
    double mid = 0.5 * (lo + hi);
    isolate(l, n, lo, mid, depth + 1, roots, nr, max);
    /* a root exactly at the split point: the halves' coefficients next to it
     * tell whether the sign changes there (a double root does not) */
    if (l[n] == 0.0 && *nr < max) {
        int sl = sign_from(l, n, n, -1), sr = sign_from(r, n, 0, 1);
        if (sl && sr && sl != sr)
            roots[(*nr)++] = mid;
    }
    isolate(r, n, mid, hi, depth + 1, roots, nr, max);
}

/* Round-off splits a double root into two nearby simple roots (or none): a
 * cluster of roots closer than this is one crossing if odd, none if even. */
static const double CLUSTER = 1e-7;

int ob_bern_roots(const double *a, int n, double *roots, int max)
{
    if (n < 1 || n > OB_BERN_MAX || max < 1)
        return 0;
    double tmp[OB_BERN_MAX + 1];
    int nr = 0;
    isolate(a, n, 0.0, 1.0, 0, tmp, &nr, max < OB_BERN_MAX ? max : OB_BERN_MAX);
    int k = 0;
    for (int i = 0; i < nr;) {
        int j = i + 1;
        while (j < nr && tmp[j] - tmp[j - 1] < CLUSTER)
            j++;
        double root = tmp[i + (j - i) / 2];
        /* only the open interval counts */
        if ((j - i) % 2 == 1 && root > 1e-12 && root < 1.0 - 1e-12)
            roots[k++] = root;
        i = j;
    }
    return k;
}
