/*
 * offdeg.c - exact offset degree and rationality on FLINT (see offdeg.h).
 */
#include "methods/core/offdeg.h"

#include <math.h>
#include <stdio.h>

#include <flint/fmpq.h>
#include <flint/fmpq_poly.h>
#include <flint/fmpz_poly.h>

/* The rational a double is exactly: m 2^e with m a 53-bit integer. */
static void fmpq_from_double(fmpq_t q, double x)
{
    int e;
    const double f = frexp(x, &e);
    const double m = ldexp(f, 53);  /* an integer, |m| < 2^53 */
    e -= 53;
    fmpz_set_d(fmpq_numref(q), m);
    fmpz_one(fmpq_denref(q));
    if (e >= 0)
        fmpz_mul_2exp(fmpq_numref(q), fmpq_numref(q), (ulong)e);
    else
        fmpz_mul_2exp(fmpq_denref(q), fmpq_denref(q), (ulong)-e);
    fmpq_canonicalise(q);
}

/* Bernstein coefficients c[0..n] (component k of the homogeneous points) to
 * the power basis: coefficient of t^j is sum_{i<=j} c_i C(n,i) C(n-i,j-i) (-1)^(j-i). */
static void power_basis(fmpq_poly_t p, const ob_bez *b, int k)
{
    const int n = b->deg;
    fmpq_t c, t;
    fmpz_t bin;
    fmpq_init(c);
    fmpq_init(t);
    fmpz_init(bin);
    fmpq_poly_zero(p);
    for (int i = 0; i <= n; i++) {
        if (b->h[i][k] == 0.0)
            continue;
        fmpq_from_double(c, b->h[i][k]);
        for (int j = i; j <= n; j++) {
            fmpz_bin_uiui(bin, (ulong)n, (ulong)i);
            fmpq_mul_fmpz(t, c, bin);
            fmpz_bin_uiui(bin, (ulong)(n - i), (ulong)(j - i));
            fmpq_mul_fmpz(t, t, bin);
            if ((j - i) % 2)
                fmpq_neg(t, t);
            fmpq_t cur;
            fmpq_init(cur);
            fmpq_poly_get_coeff_fmpq(cur, p, j);
            fmpq_add(cur, cur, t);
            fmpq_poly_set_coeff_fmpq(p, j, cur);
            fmpq_clear(cur);
        }
    }
    fmpq_clear(c);
    fmpq_clear(t);
    fmpz_clear(bin);
}

/* X, Y, W as integer polynomials with one common denominator cleared. */
static void exact_xyw(const ob_bez *b, fmpz_poly_t X, fmpz_poly_t Y, fmpz_poly_t W)
{
    fmpq_poly_t q[3];
    fmpz_t l, s;
    fmpz_init(l);
    fmpz_init(s);
    fmpz_one(l);
    for (int k = 0; k < 3; k++) {
        fmpq_poly_init(q[k]);
        power_basis(q[k], b, k);
        fmpz_lcm(l, l, fmpq_poly_denref(q[k]));
    }
    fmpz_poly_struct *out[3] = {X, Y, W};
    for (int k = 0; k < 3; k++) {
        fmpq_poly_get_numerator(out[k], q[k]);
        fmpz_divexact(s, l, fmpq_poly_denref(q[k]));
        fmpz_poly_scalar_mul_fmpz(out[k], out[k], s);
        fmpq_poly_clear(q[k]);
    }
    fmpz_clear(l);
    fmpz_clear(s);
}

/* N1 = W A' - W' A. */
static void wronsk(fmpz_poly_t r, const fmpz_poly_t W, const fmpz_poly_t A)
{
    fmpz_poly_t dA, dW, t;
    fmpz_poly_init(dA);
    fmpz_poly_init(dW);
    fmpz_poly_init(t);
    fmpz_poly_derivative(dA, A);
    fmpz_poly_derivative(dW, W);
    fmpz_poly_mul(r, W, dA);
    fmpz_poly_mul(t, dW, A);
    fmpz_poly_sub(r, r, t);
    fmpz_poly_clear(dA);
    fmpz_poly_clear(dW);
    fmpz_poly_clear(t);
}

typedef struct {
    fmpz_poly_t X, Y, W, N1, N2, N;
} exact_curve;

/* The exact data of a segment, gcd(X, Y, W) removed.  0, or -1 when the
 * segment is a point (N = 0). */
static int exact_init(exact_curve *e, const ob_bez *b)
{
    fmpz_poly_init(e->X);
    fmpz_poly_init(e->Y);
    fmpz_poly_init(e->W);
    fmpz_poly_init(e->N1);
    fmpz_poly_init(e->N2);
    fmpz_poly_init(e->N);
    exact_xyw(b, e->X, e->Y, e->W);
    fmpz_poly_t g, t;
    fmpz_poly_init(g);
    fmpz_poly_init(t);
    fmpz_poly_gcd(g, e->X, e->Y);
    fmpz_poly_gcd(g, g, e->W);
    if (!fmpz_poly_is_zero(g) && fmpz_poly_degree(g) > 0) {
        fmpz_poly_div(e->X, e->X, g);
        fmpz_poly_div(e->Y, e->Y, g);
        fmpz_poly_div(e->W, e->W, g);
    }
    wronsk(e->N1, e->W, e->X);
    wronsk(e->N2, e->W, e->Y);
    fmpz_poly_sqr(e->N, e->N1);
    fmpz_poly_sqr(t, e->N2);
    fmpz_poly_add(e->N, e->N, t);
    fmpz_poly_clear(g);
    fmpz_poly_clear(t);
    return fmpz_poly_is_zero(e->N) ? -1 : 0;
}

static void exact_clear(exact_curve *e)
{
    fmpz_poly_clear(e->X);
    fmpz_poly_clear(e->Y);
    fmpz_poly_clear(e->W);
    fmpz_poly_clear(e->N1);
    fmpz_poly_clear(e->N2);
    fmpz_poly_clear(e->N);
}

static long maxl(long a, long b) { return a > b ? a : b; }

/* 1 when the curve is (a piece of) a straight line: the tangent (N1, N2)
 * keeps its direction, N1 N2' - N1' N2 = 0. */
static int is_line(const exact_curve *e)
{
    fmpz_poly_t d1, d2, a, b;
    fmpz_poly_init(d1);
    fmpz_poly_init(d2);
    fmpz_poly_init(a);
    fmpz_poly_init(b);
    fmpz_poly_derivative(d1, e->N1);
    fmpz_poly_derivative(d2, e->N2);
    fmpz_poly_mul(a, e->N1, d2);
    fmpz_poly_mul(b, d1, e->N2);
    const int line = fmpz_poly_equal(a, b);
    fmpz_poly_clear(d1);
    fmpz_poly_clear(d2);
    fmpz_poly_clear(a);
    fmpz_poly_clear(b);
    return line;
}

/* The index of the parameterization (how many parameters trace a generic
 * point; 1: proper): the degree of gcd(X(t) W(s) - X(s) W(t), Y(t) W(s) -
 * Y(s) W(t)) at a fixed s, the smallest over a few s (a special s can only
 * raise it). */
static long param_index(const exact_curve *e)
{
    static const long s_num[3] = {7, -5, 13}, s_den[3] = {11, 3, 17};
    long best = -1;
    fmpq_t s, xs, ys, ws;
    fmpq_poly_t p, q, t;
    fmpz_poly_t pn, qn, g;
    fmpq_init(s), fmpq_init(xs), fmpq_init(ys), fmpq_init(ws);
    fmpq_poly_init(p), fmpq_poly_init(q), fmpq_poly_init(t);
    fmpz_poly_init(pn), fmpz_poly_init(qn), fmpz_poly_init(g);
    for (int k = 0; k < 3; k++) {
        fmpq_set_si(s, s_num[k], (ulong)s_den[k]);
        fmpz_poly_evaluate_fmpq(xs, e->X, s);
        fmpz_poly_evaluate_fmpq(ys, e->Y, s);
        fmpz_poly_evaluate_fmpq(ws, e->W, s);
        if (fmpq_is_zero(ws))
            continue;
        fmpq_poly_set_fmpz_poly(p, e->X);
        fmpq_poly_scalar_mul_fmpq(p, p, ws);
        fmpq_poly_set_fmpz_poly(t, e->W);
        fmpq_poly_scalar_mul_fmpq(t, t, xs);
        fmpq_poly_sub(p, p, t);
        fmpq_poly_set_fmpz_poly(q, e->Y);
        fmpq_poly_scalar_mul_fmpq(q, q, ws);
        fmpq_poly_set_fmpz_poly(t, e->W);
        fmpq_poly_scalar_mul_fmpq(t, t, ys);
        fmpq_poly_sub(q, q, t);
        fmpq_poly_get_numerator(pn, p);
        fmpq_poly_get_numerator(qn, q);
        fmpz_poly_gcd(g, pn, qn);
        const long d = fmpz_poly_degree(g);
        if (d >= 0 && (best < 0 || d < best))
            best = d;
    }
    fmpq_clear(s), fmpq_clear(xs), fmpq_clear(ys), fmpq_clear(ws);
    fmpq_poly_clear(p), fmpq_poly_clear(q), fmpq_poly_clear(t);
    fmpz_poly_clear(pn), fmpz_poly_clear(qn), fmpz_poly_clear(g);
    return best;
}

int ob_offset_degree(const ob_bez *b, ob_offdeg *out, char *msg, size_t msglen)
{
    exact_curve e;
    if (exact_init(&e, b) != 0) {
        exact_clear(&e);
        snprintf(msg, msglen, "the segment is a point: no normal, no offset curve");
        return -1;
    }
    if (is_line(&e)) {  /* whatever its parameterization: two parallel lines */
        out->degree = 1;
        out->tau = out->mu = 0;
        out->offset_degree = 2;
        out->rational = 1;
        exact_clear(&e);
        return 0;
    }
    const long index = param_index(&e);
    if (index != 1) {
        snprintf(msg, msglen, "improper parameterization (each point traced %ld times): the degree formula needs a "
                 "proper one", index);
        exact_clear(&e);
        return -1;
    }
    fmpz_poly_t gxy, g12, A, B, g, s;
    fmpz_poly_init(gxy);
    fmpz_poly_init(g12);
    fmpz_poly_init(A);
    fmpz_poly_init(B);
    fmpz_poly_init(g);
    fmpz_poly_init(s);
    const long n = maxl(maxl(fmpz_poly_degree(e.X), fmpz_poly_degree(e.Y)), fmpz_poly_degree(e.W));
    const long tau = maxl(fmpz_poly_degree(e.N1), fmpz_poly_degree(e.N2));
    fmpz_poly_gcd(gxy, e.X, e.Y);
    fmpz_poly_gcd(g12, e.N1, e.N2);
    fmpz_poly_sqr(A, gxy);
    fmpz_poly_mul(A, A, e.N);
    fmpz_poly_sqr(B, g12);
    fmpz_poly_mul(B, B, e.W);
    fmpz_poly_mul(B, B, e.W);
    fmpz_poly_gcd(g, A, B);
    const long mu = fmpz_poly_degree(g);
    out->degree = (int)n;
    out->tau = (int)tau;
    out->mu = (int)mu;
    out->offset_degree = (int)(2 * n + 2 * tau - mu);
    out->rational = fmpz_poly_sqrt(s, e.N) != 0;
    fmpz_poly_clear(gxy);
    fmpz_poly_clear(g12);
    fmpz_poly_clear(A);
    fmpz_poly_clear(B);
    fmpz_poly_clear(g);
    fmpz_poly_clear(s);
    exact_clear(&e);
    return 0;
}

/* (a X + b Y - c W)^2 N dden^2 - dnum^2 W^2 (b N1 - a N2)^2 for the line
 * a x + b y = c: its roots are the parameters where the offset meets it. */
static void line_poly(fmpz_poly_t R, const exact_curve *e, long a, long b, long c, long dnum, long dden)
{
    fmpz_poly_t L, M, t;
    fmpz_poly_init(L);
    fmpz_poly_init(M);
    fmpz_poly_init(t);
    fmpz_poly_scalar_mul_si(L, e->X, a);
    fmpz_poly_scalar_mul_si(t, e->Y, b);
    fmpz_poly_add(L, L, t);
    fmpz_poly_scalar_mul_si(t, e->W, c);
    fmpz_poly_sub(L, L, t);
    fmpz_poly_sqr(L, L);
    fmpz_poly_mul(L, L, e->N);
    fmpz_poly_scalar_mul_si(L, L, dden * dden);
    fmpz_poly_scalar_mul_si(M, e->N1, b);
    fmpz_poly_scalar_mul_si(t, e->N2, a);
    fmpz_poly_sub(M, M, t);
    fmpz_poly_mul(M, M, e->W);
    fmpz_poly_sqr(M, M);
    fmpz_poly_scalar_mul_si(M, M, dnum * dnum);
    fmpz_poly_sub(R, L, M);
    fmpz_poly_clear(L);
    fmpz_poly_clear(M);
    fmpz_poly_clear(t);
}

long ob_offset_degree_by_lines(const ob_bez *b, long dnum, long dden, unsigned long seed)
{
    exact_curve e;
    if (dden <= 0 || exact_init(&e, b) != 0) {
        if (dden > 0)
            exact_clear(&e);
        return -1;
    }
    fmpz_poly_t R[3], g;
    fmpz_poly_init(g);
    unsigned long s = seed * 2654435761UL + 12345UL;
    for (int k = 0; k < 3; k++) {
        long v[3];
        for (int i = 0; i < 3; i++) {
            s = s * 6364136223846793005UL + 1442695040888963407UL;
            v[i] = (long)((s >> 33) % 2001) - 1000;  /* small random integers */
        }
        fmpz_poly_init(R[k]);
        line_poly(R[k], &e, v[0], v[1], v[2], dnum, dden);
    }
    fmpz_poly_gcd(g, R[0], R[1]);
    fmpz_poly_gcd(g, g, R[2]);
    const long deg = fmpz_poly_degree(R[0]) - (fmpz_poly_is_zero(g) ? 0 : fmpz_poly_degree(g));
    for (int k = 0; k < 3; k++)
        fmpz_poly_clear(R[k]);
    fmpz_poly_clear(g);
    exact_clear(&e);
    return deg;
}

int ob_curve_offset_degree(const ob_curve *c, int *degree, int *rational, char *msg, size_t msglen)
{
    *degree = -1;
    *rational = 1;
    int rc = 0;
    for (int s = 0; s < c->nseg && rc == 0; s++) {
        ob_offdeg od;
        if (ob_offset_degree(&c->seg[s], &od, msg, msglen) != 0) {
            rc = -1;
            break;
        }
        if (od.offset_degree > *degree)
            *degree = od.offset_degree;
        *rational = *rational && od.rational;
    }
    /* FLINT keeps a per-thread cache of big integers; the run calls this from
     * OpenMP workers that live until exit, where the cache would be lost
     * (valgrind: definitely lost): give it back after each curve */
    flint_cleanup();
    return rc;
}
