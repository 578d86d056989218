/*
 * testlib.h - small helpers shared by the C test programs.
 *
 * The reference computations here are INDEPENDENT of the library: binomials by
 * Pascal's rule, Bernstein polynomials by powers, points and derivatives of
 * homogeneous Bézier segments by direct Bernstein sums and the quotient rule.
 * They must never call the routines they are used to check (ref_eval must not
 * call ob_bez_eval, binom must not call ob_binom, ...): a test that compares
 * the library with itself proves nothing.  The only library calls allowed are
 * ob_bez_set in the curve builders (it just stores w x, w y, w).
 *
 * Random numbers: xorshift64* in [0,1).  Every program that uses urand() sets
 * its own seed with testlib_seed() at the start of main, so its random cases
 * do not depend on the other programs.
 *
 * Everything is static inline: a program that does not use a helper gets no
 * warning and no code for it.
 */
#ifndef OB_TESTLIB_H
#define OB_TESTLIB_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "methods/core/curve.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"

/* How close to 0 metric m can show an exact offset to be: round-off for
 * the sampled and symbolic metrics; for certified, an enclosure, what its
 * default budget proves on lines and circles (a few 1e-9 of the size:
 * docs/certified.md; test_certified reaches round-off with a larger one). */
static inline double testlib_exact_tol(ob_metric m) { return m == OB_METRIC_CERTIFIED ? 1e-7 : 1e-12; }

/* ---- random numbers -------------------------------------------------------- */

static uint64_t testlib_rng = 0x9E3779B97F4A7C15ULL;

static inline void testlib_seed(uint64_t seed) { testlib_rng = seed; }

static inline double urand(void)  /* xorshift64*, uniform in [0,1) */
{
    testlib_rng ^= testlib_rng >> 12;
    testlib_rng ^= testlib_rng << 25;
    testlib_rng ^= testlib_rng >> 27;
    return (double)((testlib_rng * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
}

static inline double urange(double a, double b) { return a + (b - a) * urand(); }

/* ---- Bernstein reference ----------------------------------------------------- */

enum { TESTLIB_BINOM_N = 100 };

/* C(n, k) from Pascal's triangle built by additions (exact to n = 56); 0
 * outside 0 <= k <= n. */
static inline double binom(int n, int k)
{
    static double T[TESTLIB_BINOM_N][TESTLIB_BINOM_N];
    static int init;
    if (!init) {
        for (int i = 0; i < TESTLIB_BINOM_N; i++) {
            T[i][0] = T[i][i] = 1.0;
            for (int j = 1; j < i; j++)
                T[i][j] = T[i - 1][j - 1] + T[i - 1][j];
        }
        init = 1;
    }
    if (n < 0 || k < 0 || k > n)
        return 0.0;
    if (n >= TESTLIB_BINOM_N) {
        fprintf(stderr, "testlib: binom(%d, %d) beyond the table\n", n, k);
        abort();
    }
    return T[n][k];
}

/* B_i^n(t) by powers, valid for any real t; 0 outside 0 <= i <= n. */
static inline double bern(int n, int i, double t)
{
    if (n < 0 || i < 0 || i > n)
        return 0.0;
    double r = binom(n, i);
    for (int j = 0; j < i; j++)
        r *= t;
    for (int j = 0; j < n - i; j++)
        r *= 1.0 - t;
    return r;
}

/* k-th derivative (k = 0..2) of B_i^n. */
static inline double dbern(int n, int i, int k, double t)
{
    if (k == 0)
        return bern(n, i, t);
    if (k == 1)
        return n * (bern(n - 1, i - 1, t) - bern(n - 1, i, t));
    return n * (n - 1.0) * (bern(n - 2, i - 2, t) - 2.0 * bern(n - 2, i - 1, t) + bern(n - 2, i, t));
}

/* Point and derivatives 1..nder (nder = 0..2) of a homogeneous Bézier segment
 * into o[0..nder]: homogeneous sums, then the quotient rule
 * x' = (X'W - XW')/W^2, x'' = (X''W^2 - 2X'W'W - XW''W + 2XW'^2)/W^3. */
static inline void ref_eval(const ob_bez *b, double t, int nder, double (*o)[2])
{
    double H[3][3] = {{0}};
    for (int k = 0; k <= nder; k++)
        for (int i = 0; i <= b->deg; i++) {
            double bk = dbern(b->deg, i, k, t);
            for (int c = 0; c < 3; c++)
                H[k][c] += b->h[i][c] * bk;
        }
    const double W = H[0][2], W1 = H[1][2], W2 = H[2][2];
    for (int c = 0; c < 2; c++) {
        const double X = H[0][c], X1 = H[1][c], X2 = H[2][c];
        o[0][c] = X / W;
        if (nder >= 1)
            o[1][c] = (X1 * W - X * W1) / (W * W);
        if (nder >= 2)
            o[2][c] = (X2 * W * W - 2.0 * X1 * W1 * W - X * W2 * W + 2.0 * X * W1 * W1) / (W * W * W);
    }
}

static inline void ref_point(const ob_bez *b, double t, double p[2])
{
    double o[1][2];
    ref_eval(b, t, 0, o);
    p[0] = o[0][0];
    p[1] = o[0][1];
}

/* Exact offset point O = C(t) + d N(t) and the unit left normal N =
 * (-y', x')/|C'|. */
static inline void ref_offset_normal(const ob_bez *b, double t, double d, double O[2], double N[2])
{
    double o[2][2];
    ref_eval(b, t, 1, o);
    const double sp = hypot(o[1][0], o[1][1]);
    N[0] = -o[1][1] / sp;
    N[1] = o[1][0] / sp;
    O[0] = o[0][0] + d * N[0];
    O[1] = o[0][1] + d * N[1];
}

/* Exact offset point C(t) + d N(t). */
static inline void ref_offset(const ob_bez *b, double t, double d, double O[2])
{
    double N[2];
    ref_offset_normal(b, t, d, O, N);
}

/* Point of a method's fit at base parameter t (the piece containing t). */
static inline void fit_point(const ob_fit *f, double t, double p[2])
{
    int i = 0;
    while (i < f->n - 1 && t > f->t[i + 1])
        i++;
    ref_point(&f->seg[i], (t - f->t[i]) / (f->t[i + 1] - f->t[i]), p);
}

/* ---- curve builders ------------------------------------------------------------ */

/* Degree-deg segment through the points xy[0..deg] with weights w (NULL: all 1). */
static inline ob_bez make(int deg, const double (*xy)[2], const double *w)
{
    ob_bez b;
    memset(&b, 0, sizeof b);
    b.deg = deg;
    for (int i = 0; i <= deg; i++)
        ob_bez_set(&b, i, xy[i][0], xy[i][1], w ? w[i] : 1.0);
    return b;
}

/* Rational quadratic quarter circle of radius r, centre 0, from (r, 0) to
 * (0, r) (counterclockwise) or, if `clockwise`, from (0, r) to (r, 0). */
static inline ob_bez quarter_circle(double r, int clockwise)
{
    const double s2 = sqrt(2.0) / 2.0;
    double xy[3][2] = {{r, 0}, {r, r}, {0, r}}, w[3] = {1, s2, 1};
    if (clockwise) {
        double rev[3][2] = {{0, r}, {r, r}, {r, 0}};
        return make(2, (const double (*)[2])rev, w);
    }
    return make(2, (const double (*)[2])xy, w);
}

/* The same segment traversed the other way (control points in reverse order). */
static inline ob_bez reversed(const ob_bez *b)
{
    ob_bez r = *b;
    for (int i = 0; i <= b->deg; i++)
        memcpy(r.h[i], b->h[b->deg - i], sizeof r.h[i]);
    return r;
}

/* A curve of n segments seg (not copied, not owned) called id. */
static inline ob_curve curve_of(ob_bez *seg, int n, const char *id)
{
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "%s", id);
    c.nseg = n;
    c.seg = seg;
    return c;
}

static inline double dist2d(const double a[2], const double b[2]) { return hypot(a[0] - b[0], a[1] - b[1]); }

/* ---- crash containment --------------------------------------------------------- */

/* Runs fn in a child process: its exit status, or 128 + signal if it died. */
static inline int in_child(int (*fn)(void))
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0)
        _exit(fn());
    int st = 0;
    if (waitpid(pid, &st, 0) != pid)
        return -1;
    if (WIFEXITED(st))
        return WEXITSTATUS(st);
    if (WIFSIGNALED(st))
        return 128 + WTERMSIG(st);
    return -1;
}

#endif
