/*
 * normalfit.h - the normal-curve approximations of Liu & Wang 2002, §2,
 * shared by methods/liu.c, methods/chebyshev.c and methods/lstsq.c.
 *
 * Liu-Wang §2.1: shifting the control points P_i of a Bézier segment by D_i
 * gives the error e(t) = D(t) - N_d(t), D(t) = sum D_i B_i^n(t), N_d = d N(t).
 * So the offset problem is: approximate the vector function f(t) (the normal
 * curve; for rational input, §2.4, W(t) N_d(t) with W the weight polynomial)
 * by a polynomial S_n of degree n with S_n(0) = f(0), S_n(1) = f(1).
 *
 * §2.3, eq. (6)-(7), the end-constrained construction: with
 *   f^(t) = f(t) - f0 B_0^n(t) - f1 B_n^n(t)   (zero at both ends) and
 *   f~(t) = f^(t) / ((1 - t) t),
 * approximate f~ by a polynomial S~ of degree n-2 with Bernstein coefficients
 * s~_0..s~_{n-2}; then S_n = f0 B_0^n + (1-t) t S~ + f1 B_n^n has the Bernstein
 * coefficients s_0 = f0, s_i = C(n-2,i-1)/C(n,i) s~_{i-1} (i = 1..n-1), s_n = f1.
 * How S~ is obtained is what distinguishes the three methods:
 *   legendre   the best L2 approximation of f~ on [0,1] with weight 1: its
 *              truncated Legendre series (eq. 3-5) with coefficients by M-node
 *              Gauss-Legendre quadrature, converted to Bernstein form with
 *              P_k(2t-1) = sum_i (-1)^(k+i) C(k,i) B_i^k(t)  (§2.2)
 *   chebyshev  the truncated Chebyshev series of f~ (weight 1/sqrt(1-x^2) on
 *              [-1,1], x = 2t-1), coefficients by M-node Gauss-Chebyshev
 *              quadrature; T_k(2t-1) = sum_i (-1)^(k-i) C(2k,2i)/C(k,i) B_i^k(t)
 *   lstsq      discrete least squares on M uniform interior samples t_j =
 *              j/(M+1), j = 1..M, of the normal curve itself (the end values
 *              are interpolated), or of f~ (row weight 1/(t(1-t))), solved by
 *              Givens QR on the Bernstein basis.
 * None of them evaluates f~ at t = 0 or 1 (where it is only a limit): the Gauss
 * nodes and the samples all lie inside (0,1).
 *
 * The approximation is then P_i^a = P_i + s_i / w_i, i.e. the homogeneous
 * control point w_i P_i + s_i with weight w_i kept (§2.4).
 */
#ifndef OB_NORMALFIT_H
#define OB_NORMALFIT_H

#include <stddef.h>

#include "methods/core/curve.h"
#include "methods/method.h"

/* A vector function of t in [0,1]: writes f(t), returns 0 or -1 (undefined). */
typedef int (*ob_nf_fn)(const void *ctx, double t, double f[2]);

/* The normal-curve target of §2.1/§2.4: f(t) = W(t) d N(t), W the weight
 * polynomial of the (rational) segment (W = 1 for polynomial segments). */
typedef struct {
    const ob_bez *base;
    double d;
} ob_nf_target;
int ob_nf_target_eval(const void *ctx, double t, double f[2]);

/* Purpose: M-point Gauss-Legendre rule on [0,1]: ascending nodes x[M] in (0,1),
 *          weights w[M] (sum 1), exact for polynomials of degree <= 2M-1.
 * Method:  Newton iteration on P_M from the asymptotic guesses, the node pairs
 *          mirrored about 1/2 so the rule is exactly symmetric. */
void ob_nf_gauss_legendre(int M, double *x, double *w);

/* Largest node / sample count accepted by the fits below. */
enum { OB_NF_MAX_NODES = 1024 };

/* Scratch the fits need for M nodes (bytes). */
size_t ob_nf_work_legendre(int M);
size_t ob_nf_work_chebyshev(int M);

/* Purpose: the end-constrained approximation S_n of f (see the top of this
 *          file), degree n in 1..OB_MAX_DEG, as Bernstein coefficients s[0..n].
 * Inputs:  f, ctx; n; M nodes / samples (1..OB_NF_MAX_NODES); work of the
 *          size given above (lstsq needs none); lstsq: ftilde = 0 fits the
 *          samples of f, 1 those of f~.
 * Returns: 0, or -1 if f is undefined somewhere it is needed, M is out of
 *          range or (lstsq) the system is rank deficient (M < n - 1). */
int ob_nf_fit_legendre(ob_nf_fn f, const void *ctx, int n, int M, void *work, double (*s)[2]);
int ob_nf_fit_chebyshev(ob_nf_fn f, const void *ctx, int n, int M, void *work, double (*s)[2]);
int ob_nf_fit_lstsq(ob_nf_fn f, const void *ctx, int n, int M, int ftilde, double (*s)[2]);

/* The kinds of S~, for ob_nf_method_fit. */
typedef enum { OB_NF_LEGENDRE = 0, OB_NF_CHEBYSHEV, OB_NF_LSTSQ } ob_nf_kind;

/* Purpose: the whole fit of one method: validate the parameters
 *          (par[0] = node / sample count, par[1] = lstsq target), fit
 *          S_n to W d N of `base`, and write the segment with homogeneous
 *          control points w_i P_i + s_i (weights kept) into out.
 * Returns: OB_FIT_OK, or OB_FIT_FAIL with the reason in msg. */
ob_fit_status ob_nf_method_fit(ob_nf_kind kind, const ob_bez *base, const ob_fit_args *a, void *work,
                               ob_fit *out, char *msg, size_t msglen);

#endif
