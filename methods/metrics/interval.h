/*
 * interval.h - outward-rounded interval arithmetic on doubles, for the
 * certified Hausdorff bound (metric_certified.h).
 *
 * An ob_iv [lo, hi] encloses a real number.  Every operation computes its
 * endpoints in round-to-nearest and then widens them by one unit in the last
 * place (ob_iv_dn, ob_iv_up): a correctly rounded operation (+ - * / sqrt in
 * IEEE 754) is off by at most half a unit, so the widened interval encloses
 * the exact result (Moore, "Interval Analysis", 1966; the inclusion property).
 *
 * Why widening and not fesetround: the build compiles with plain -O2 (no
 * -frounding-math), under which GCC may fold and move floating-point code
 * across a rounding-mode change; the widening works in the default mode,
 * costs two flops, and is thread-safe.  It costs a factor ~2 in width over
 * directed rounding, which is far below every enclosure width that matters
 * here.  The build is ISO C11 (-std=c11), where GCC does not contract a * b + c
 * into a fused multiply-add; a contraction would only make results tighter.
 *
 * Overflow gives inf or NaN endpoints; callers treat a NaN as "unbounded".
 */
#ifndef OB_INTERVAL_H
#define OB_INTERVAL_H

#include <math.h>

typedef struct {
    double lo, hi;
} ob_iv;

/* r minus at least one ulp of r (ulp(r) <= |r| 2^-52 for normal r; the
 * 2^-1074 term covers zero and subnormals).  The subtraction itself rounds to
 * nearest, which is monotone, so the result is still <= r - ulp(r). */
static inline double ob_iv_dn(double r) { return r - (fabs(r) * 0x1p-52 + 0x1p-1074); }
static inline double ob_iv_up(double r) { return r + (fabs(r) * 0x1p-52 + 0x1p-1074); }

/* min and max that propagate a NaN from either side (fmin and fmax drop
 * one): a NaN endpoint (inf x 0 of an unbounded enclosure) then reaches
 * ob_iv_bad instead of being lost.  Inline because libm's fmin and fmax
 * are calls under plain -O2 (their NaN and signed-zero rules keep GCC from
 * using minsd / maxsd): a quarter of the certificate's time went there. */
static inline double ob_iv_min(double a, double b) { return b < a || b != b ? b : a; }
static inline double ob_iv_max(double a, double b) { return b > a || b != b ? b : a; }

static inline ob_iv ob_iv_pt(double x) { return (ob_iv){x, x}; }
static inline ob_iv ob_iv_make(double a, double b) { return (ob_iv){ob_iv_min(a, b), ob_iv_max(a, b)}; }

static inline ob_iv ob_iv_add(ob_iv a, ob_iv b) { return (ob_iv){ob_iv_dn(a.lo + b.lo), ob_iv_up(a.hi + b.hi)}; }
static inline ob_iv ob_iv_sub(ob_iv a, ob_iv b) { return (ob_iv){ob_iv_dn(a.lo - b.hi), ob_iv_up(a.hi - b.lo)}; }
static inline ob_iv ob_iv_neg(ob_iv a) { return (ob_iv){-a.hi, -a.lo}; }

static inline ob_iv ob_iv_mul(ob_iv a, ob_iv b)
{
    const double p1 = a.lo * b.lo, p2 = a.lo * b.hi, p3 = a.hi * b.lo, p4 = a.hi * b.hi;
    return (ob_iv){ob_iv_dn(ob_iv_min(ob_iv_min(p1, p2), ob_iv_min(p3, p4))),
                   ob_iv_up(ob_iv_max(ob_iv_max(p1, p2), ob_iv_max(p3, p4)))};
}

/* x^2 >= 0: tighter than ob_iv_mul(a, a) when a holds 0. */
static inline ob_iv ob_iv_sqr(ob_iv a)
{
    const double l = fabs(a.lo), h = fabs(a.hi);
    const double big = ob_iv_max(l, h), small = (a.lo <= 0 && a.hi >= 0) ? 0.0 : ob_iv_min(l, h);
    return (ob_iv){ob_iv_max(0.0, ob_iv_dn(small * small)), ob_iv_up(big * big)};
}

/* a / b; the whole line when b holds 0 (the caller then cannot certify). */
static inline ob_iv ob_iv_div(ob_iv a, ob_iv b)
{
    if (!(b.lo > 0 || b.hi < 0))
        return (ob_iv){-INFINITY, INFINITY};
    const double q1 = a.lo / b.lo, q2 = a.lo / b.hi, q3 = a.hi / b.lo, q4 = a.hi / b.hi;
    return (ob_iv){ob_iv_dn(ob_iv_min(ob_iv_min(q1, q2), ob_iv_min(q3, q4))),
                   ob_iv_up(ob_iv_max(ob_iv_max(q1, q2), ob_iv_max(q3, q4)))};
}

static inline ob_iv ob_iv_sqrt(ob_iv a)
{
    return (ob_iv){ob_iv_dn(sqrt(ob_iv_max(a.lo, 0.0))), ob_iv_up(sqrt(ob_iv_max(a.hi, 0.0)))};
}

static inline ob_iv ob_iv_scale(ob_iv a, double s) { return ob_iv_mul(a, ob_iv_pt(s)); }
static inline ob_iv ob_iv_hull(ob_iv a, ob_iv b) { return (ob_iv){ob_iv_min(a.lo, b.lo), ob_iv_max(a.hi, b.hi)}; }
/* the largest |x| over a */
static inline double ob_iv_mag(ob_iv a) { return ob_iv_max(fabs(a.lo), fabs(a.hi)); }
static inline int ob_iv_bad(ob_iv a) { return !(a.lo <= a.hi) || isinf(a.lo) || isinf(a.hi); }

#endif
