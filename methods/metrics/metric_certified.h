/*
 * metric_certified.h - a certified enclosure of the two-sided Hausdorff
 * distance between an approximation A and the exact offset of its base.
 *
 * Purpose: lower <= H(A, O) <= upper, by construction, for
 *          H(A, O) = max( sup_s min_t |A(s) - O(t)|, sup_t min_s |O(t) - A(s)| ),
 *          O(t) = C(t) + d N(t), s, t in [0, 1], N the left unit normal: the
 *          quantity the sampled `hausdorff` metric estimates (metric.h).
 * Inputs:  base C and approx A: polynomial or rational (positive weights),
 *          any degree up to OB_MAX_DEG; d != 0; samples S (clamped to
 *          [OB_MIN_SAMPLES, OB_MAX_SAMPLES]), the grid the search starts
 *          from; opts (NULL: ob_cert_defaults).
 * Outputs: *out (below).
 * Method:  every number that makes a bound is computed in outward-rounded
 *          interval arithmetic (interval.h: nextafter-like widening by one
 *          ulp, Moore 1966) from enclosures of the curves and their
 *          derivatives (cert_curve.h: interval de Casteljau and the
 *          Bernstein convex-hull property).
 *   upper:  any correspondence s -> t(s) into [0, 1] gives
 *           min_t |A(s) - O(t)| <= |A(s) - O(t(s))|, and each piece of the
 *           parameter domain may choose its own.  The feet of S samples
 *           (cert_feet.h) give, per sample interval, three lines: the
 *           interpolation of its two feet and the continuation of each
 *           foot with its local speed (so a foot that jumps across a fold
 *           or a swallowtail of the offset is followed from both sides),
 *           and a quadratic through both feet whose slope goes from one
 *           foot's speed to the other's (a line slips along O by O(h^2),
 *           which a piece 1e-10 from O cannot afford; the quadratic by
 *           O(h^3)), clamped to a constant where one would leave [0, 1];
 *           a half of a bisected interval also tries the line that bounded
 *           its parent, and its new foot is searched around that line too.
 *           On an interval [s0, s1] with midpoint m and a map t(s), the
 *           error e(s) = A(s) - O(t(s)) is enclosed by the second-order
 *           Taylor form e(m) + e'(m) h + E2 h^2 / 2 (E2 an interval
 *           enclosure of e'' = A'' - t'^2 O'' - t'' O' over the interval;
 *           componentwise remainder) and, where the target is within 1e4
 *           round-off floors, also the third-order form
 *           e(m) + e'(m) h + e''(m) h^2 / 2 + E3 h^3 / 6 (the least of the
 *           two), in a frame turned to e(m), so that a tangential
 *           slip of the correspondence enters as the square it is:
 *           |e| <= sqrt(max N^2 + max T^2).  The interval's bound is the
 *           least over its lines.  Intervals are bisected, largest bound
 *           first (branch and bound), until the largest is within rtol of
 *           the lower bound (or below floor) or the budget is spent; with
 *           opts->decide, also until the enclosure is on one side of it.  The
 *           same the other way round (points of O, correspondence into A).
 *   lower:  a distance actually attained: a point a (of A, or of O) and a
 *           certified L <= min_t |a - O(t)| (or to A), by branch and bound
 *           over t with a first-order enclosure of the other curve on each
 *           interval (the exact distance from a to the segment
 *           O(m) + mid(O') [t0 - m, t1 - m], less the radii).  Candidates:
 *           the sampled maximum refined by golden section, and the middle
 *           of the interval holding the largest upper bound as the search
 *           goes (which finds a spike the samples missed).
 * Reference: R. E. Moore, Interval Analysis (1966); G. Farin, Curves and
 *          Surfaces for CAGD, ch. 5 (subdivision, convex hull); the
 *          symbolic alternative, bounding ||A - C||^2 - d^2 by Bernstein
 *          coefficients (Elber & Cohen 1991; Elber, Lee & Kim 1997, the
 *          `bound` metric), needs A in C's parameter; the correspondence
 *          here removes that need and the square root is enclosed by
 *          interval evaluation instead.
 * Errors:  returns -1 (and out->upper = +inf, met = 0) where no bound
 *          exists: an interval where |C'| cannot be bounded away from 0
 *          (a cusp of C), a weight interval reaching 0, overflow, no
 *          memory.  The lower bound is then still valid.  Returns 0
 *          otherwise, also when the budget ran out (met = 0, bounds valid).
 */
#ifndef OB_METRIC_CERTIFIED_H
#define OB_METRIC_CERTIFIED_H

#include "methods/core/curve.h"

typedef struct {
    double lower, upper;        /* lower <= H(A, O) <= upper */
    double upper_ao, upper_oa;  /* one-sided: sup over A of dist to O; over O of dist to A */
    int lower_side;             /* the lower bound's point: 0 on A, 1 on O */
    double lower_param;         /* ... at this parameter */
    long leaves;                /* intervals enclosed (the work) */
    int met;                    /* 1: upper <= max(lower (1 + rtol), floor); with
                                   opts->verdict: the verdict is reached */
    int cancelled;              /* 1: opts->cancel stopped the search (bounds valid) */
} ob_certified;

typedef struct {
    double rtol;       /* stop refining when upper <= lower (1 + rtol) */
    double floor_rel;  /* ... or when upper <= floor_rel x the curves' size */
    long budget;       /* at most this many interval enclosures per side */
    double decide;     /* > 0: a tolerance to decide against: refine on (within
                          budget) while lower <= decide < upper, until upper <=
                          decide or lower > decide; 0: off */
    int verdict;       /* with decide > 0: decide and no more.  The search stops
                          as soon as upper <= decide (within) or lower > decide
                          (over: one distance attained above it is the proof),
                          not refined to rtol: both ends stay proofs, neither
                          need be tight.  0: tight (to rtol), as without it */
    int grid;          /* > 0: the search starts from this many intervals of
                          the sample grid (their ends on samples) and only
                          their ends' feet are searched first; 0: every
                          sample interval, or OB_CERT_VERDICT_GRID in
                          verdict mode (a verdict rarely needs the
                          resolution of the samples: bisection finds it
                          where it does) */
    int no_lower;      /* with verdict: seek a lower bound only where it could
                          prove lower > decide (the job's other pieces) */
    int (*cancel)(void *ctx);  /* NULL, or asked every few hundred enclosures:
                                  nonzero stops the search (out->cancelled) */
    void *cancel_ctx;
} ob_cert_opts;

enum { OB_CERT_VERDICT_GRID = 8 };

/* rtol 1e-3, floor 1e-13, budget 20000, decide 0 (off), verdict 0, no_lower 0,
 * cancel NULL */
void ob_cert_defaults(ob_cert_opts *o);

int ob_certify_hausdorff(const ob_bez *base, const ob_bez *approx, double d, int samples, ob_certified *out);
int ob_certify_hausdorff_opts(const ob_bez *base, const ob_bez *approx, double d, int samples,
                              const ob_cert_opts *opts, ob_certified *out);

#endif
