/*
 * metric_core.h - the sampled error metrics, written once for both the CPU
 * reference (compiled as C11 by methods/metrics/metric_sampled.c) and the OpenCL
 * kernel (the host prepends this text to kernels/measure.cl).  One source of
 * the formulas means the two backends cannot drift apart; the tests check
 * that they agree.
 *
 * A curve is a homogeneous Bézier segment given as a flat array of (w x, w y, w)
 * triples and its degree.  Metrics (see methods/metrics/metric.h for definitions):
 *   radial     | |A(t) - C(t)| - |d| |
 *   normal     |s - d| where C(t) + s N(t) meets A nearest to t in A's
 *              parameter (Newton from u = t when no crossing lies closer,
 *              else the sign change of the cross product nearest to t)
 *   hausdorff  two-sided distance between A and the exact offset O = C + d N:
 *              nearest sample (coarse global scan + local descent), then
 *              Newton projection with the target's curvature vector, golden
 *              section where Newton cannot settle.
 *   param      Zhao-Zhou's error at the given parameter, |(A(t) - O(t)) . N(t)|
 *              with O(t) = C(t) + d N(t) (| |A - C| - |d| | where the base has
 *              no normal: a point-like segment).
 * Each samples S parameters t_k = k/(S-1), takes the largest error and refines
 * it by golden-section search between its neighbours.
 * A measurement given a stop > 0 (obc_measure) may end at the first sample
 * whose error exceeds it: the caller only needs to know that the error is
 * above stop (a piece that fails its level in a greedy search).  Its result
 * is then that sample's error and parameter (a lower bound of the full
 * error, itself above stop); wherever the full error is <= stop no sample
 * exceeds it, and the result is the full measurement's, bit for bit.
 *
 * Written in the common subset of C11 and OpenCL C 1.2: no function pointers,
 * no recursion, no library calls beyond sqrt/fabs/fmin/fmax/isnan/isinf.
 */
#ifndef OB_METRIC_CORE_H
#define OB_METRIC_CORE_H

#ifdef __OPENCL_VERSION__
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
/* no fused multiply-add: the same rounding as the C reference */
#pragma OPENCL FP_CONTRACT OFF
#define OBC_G __global
#define OBC_FN
#define OBC_FLAT_FN OBC_FN
/* A function called from many places that the kernel keeps out of line:
 * a GPU compiler that inlines every call (NVIDIA's does) made thousands of
 * copies of the curve evaluation in one kernel and took three minutes to
 * build it (issue 40; kernels/README.md "Build time").  -D OBC_INLINE_ALL
 * leaves the choice to the compiler.  A call does not change a result:
 * contraction is off, so every operation rounds as written. */
#ifdef OBC_INLINE_ALL
#define OBC_CALL_FN
#else
#define OBC_CALL_FN __attribute__((noinline))
#endif
#define OBC_INF ((double)INFINITY)
#else
#include <math.h>
#define OBC_G
#define OBC_FN static inline
/* a function whose constant arguments should reach its body (so that it
 * is compiled once per call site's constants) */
#define OBC_FLAT_FN static inline __attribute__((always_inline))
#define OBC_CALL_FN OBC_FN
#define OBC_INF ((double)INFINITY)
#endif

/* The metrics a build holds: all of them (the CPU build, and a kernel
 * built without these), or the one named by -D OBC_ONLY_RADIAL,
 * OBC_ONLY_NORMAL, OBC_ONLY_HAUSDORFF or OBC_ONLY_PARAM (the host builds
 * one program per metric a run uses, host/backend/clrt.c).  A record of
 * another metric is not measured by such a build (+inf). */
#if defined(OBC_ONLY_RADIAL) || defined(OBC_ONLY_NORMAL) || defined(OBC_ONLY_HAUSDORFF) || defined(OBC_ONLY_PARAM)
#ifdef OBC_ONLY_RADIAL
#define OBC_WANT_RADIAL 1
#else
#define OBC_WANT_RADIAL 0
#endif
#ifdef OBC_ONLY_NORMAL
#define OBC_WANT_NORMAL 1
#else
#define OBC_WANT_NORMAL 0
#endif
#ifdef OBC_ONLY_HAUSDORFF
#define OBC_WANT_HAUSDORFF 1
#else
#define OBC_WANT_HAUSDORFF 0
#endif
#ifdef OBC_ONLY_PARAM
#define OBC_WANT_PARAM 1
#else
#define OBC_WANT_PARAM 0
#endif
#else
#define OBC_WANT_RADIAL 1
#define OBC_WANT_NORMAL 1
#define OBC_WANT_HAUSDORFF 1
#define OBC_WANT_PARAM 1
#endif
/* a one-sided metric (the scan of obc_sample_refine over its own kind) */
#define OBC_WANT_SCAN (OBC_WANT_RADIAL || OBC_WANT_NORMAL || OBC_WANT_PARAM)

/* OBC_SIMD before a loop whose iterations are independent (one per sample
 * lane): the CPU compiler vectorizes it; every lane does the IEEE operations
 * of the scalar code in the same order, so the bits are the scalar ones.
 * OBC_FMIN/OBC_FMAX: the CPU build calls fmin/fmax out of line (libm); the
 * inline forms give what glibc's x86-64 fmin/fmax give: the first operand
 * on a tie (so fmax(-0, +0) = -0), the other operand when one is NaN
 * (tests/unit/test_table_lanes.c checks them against libm). */
#ifdef __OPENCL_VERSION__
#define OBC_SIMD
#define OBC_FMIN(a, b) fmin(a, b)
#define OBC_FMAX(a, b) fmax(a, b)
#else
#define OBC_SIMD _Pragma("omp simd")
static inline double obc_fmin(double x, double y) { return (x <= y || y != y) ? x : y; }
static inline double obc_fmax(double x, double y) { return (x >= y || y != y) ? x : y; }
#define OBC_FMIN(a, b) obc_fmin(a, b)
#define OBC_FMAX(a, b) obc_fmax(a, b)
#endif

#define OBC_MAX_DEG 32           /* = OB_MAX_DEG */

/* The work of a measurement, counted in floating-point operations as every
 * function below adds them to *ops: a de Casteljau evaluation of degree n
 * (n (n + 1) / 2 lerps of 3 coordinates, and the quotient rule), a distance
 * to a sample point, to a chord, to a block's circle.  The OpenCL host
 * shares a batch's time among its records by this count (one launch
 * measures them all); the bench turns it into flop/s. */
#define OBC_OPS_EVAL(n) (9 * (n) * ((n) + 1) / 2 + 30)
#define OBC_OPS_POINT 5
#define OBC_OPS_CHORD 16
#define OBC_OPS_BLOCK 7

/* metric codes: = ob_metric in methods/metrics/metric.h */
#define OBC_RADIAL 1
#define OBC_NORMAL 2
#define OBC_HAUSDORFF 3
#define OBC_PARAM 4

/* internal error kinds for sample-and-refine */
#define OBC_K_RADIAL 0
#define OBC_K_NORMAL 1
#define OBC_K_H_APPROX 2         /* from points of A to the offset O */
#define OBC_K_H_OFFSET 3         /* from points of O to A */
#define OBC_K_PARAM 4

/* ---- curves ---------------------------------------------------------- */

/* The de Casteljau levels of obc_eval on the first K coordinates of the
 * homogeneous points h (stride 3): the point q0, levels 2 (lv2) and 1
 * (lv1), kept when reached.  The levels above 2 are kept coordinate by
 * coordinate (x, y and w in arrays of their own): each lerp is the same
 * IEEE operation as in a point-by-point pass, but the three streams of a
 * level are independent, so they overlap instead of waiting on the loads
 * and stores of an interleaved array (1.7x at degree 7 and above). */
OBC_FLAT_FN void obc_casteljau(const OBC_G double *h, int n, double t, const int K, double q0[3], double lv2[3][3],
                          double lv1[2][3])
{
    double qxy[OBC_MAX_DEG][2], qw[OBC_MAX_DEG];
    const double s = 1.0 - t;
    if (n == 0) {
        for (int k = 0; k < K; k++)
            q0[k] = h[k];
        return;
    }
    if (n == 1) {
        for (int i = 0; i < 2; i++)
            for (int k = 0; k < K; k++)
                lv1[i][k] = h[3 * i + k];
    } else if (n == 2) {
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < K; k++)
                lv2[i][k] = h[3 * i + k];
    } else if (n == 3) {
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < K; k++)
                lv2[i][k] = s * h[3 * i + k] + t * h[3 * i + 3 + k];
    } else {
        /* level n straight from the control points (no copy), down to 4,
         * then level 3 into lv2 */
        for (int i = 0; i < n; i++) {
            for (int k = 0; k < 2; k++)
                qxy[i][k] = s * h[3 * i + k] + t * h[3 * i + 3 + k];
            if (K == 3)
                qw[i] = s * h[3 * i + 2] + t * h[3 * i + 5];
        }
        for (int r = n - 1; r >= 4; r--)
            for (int i = 0; i < r; i++) {
                for (int k = 0; k < 2; k++)
                    qxy[i][k] = s * qxy[i][k] + t * qxy[i + 1][k];
                if (K == 3)
                    qw[i] = s * qw[i] + t * qw[i + 1];
            }
        for (int i = 0; i < 3; i++) {
            for (int k = 0; k < 2; k++)
                lv2[i][k] = s * qxy[i][k] + t * qxy[i + 1][k];
            if (K == 3)
                lv2[i][2] = s * qw[i] + t * qw[i + 1];
        }
    }
    if (n >= 2)
        for (int i = 0; i < 2; i++)
            for (int k = 0; k < K; k++)
                lv1[i][k] = s * lv2[i][k] + t * lv2[i + 1][k];
    for (int k = 0; k < K; k++)
        q0[k] = s * lv1[0][k] + t * lv1[1][k];
}

/* x / w, skipping the division where w is exactly 1 (every polynomial
 * segment): x / 1 is x in IEEE arithmetic, NaN and signed zeros included,
 * so the bits are the division's, at a fraction of its latency. */
OBC_FN double obc_divw(double x, double w) { return w == 1.0 ? x : x / w; }

/* Point and derivatives up to nder (<= 2) at t: one de Casteljau pass on the
 * homogeneous points; derivatives from its last three levels; quotient rule.
 * A polynomial segment (every weight exactly 1) at t in [0,1] runs the pass
 * on x and y alone: there every level's weight is exactly 1 (fl(fl(1 - t) +
 * t) = 1 for t in [0,1]) and every derivative of the weight exactly 0, so
 * the result has the same bits as the homogeneous pass. */
OBC_CALL_FN void obc_eval(const OBC_G double *h, int n, double t, int nder, double out[][2], long *ops)
{
    double q0[3], lv2[3][3] = {{0.0}}, lv1[2][3] = {{0.0}};
    *ops += OBC_OPS_EVAL(n);
    int poly = t >= 0.0 && t <= 1.0;
    for (int i = 0; i <= n && poly; i++)
        poly = h[3 * i + 2] == 1.0;
    if (poly) {
        obc_casteljau(h, n, t, 2, q0, lv2, lv1);
        q0[2] = 1.0;
        lv1[0][2] = lv1[1][2] = 1.0;
        lv2[0][2] = lv2[1][2] = lv2[2][2] = 1.0;
    } else {
        obc_casteljau(h, n, t, 3, q0, lv2, lv1);
    }
    double H[3][3];
    for (int k = 0; k < 3; k++) {
        H[0][k] = q0[k];
        H[1][k] = n >= 1 ? n * (lv1[1][k] - lv1[0][k]) : 0.0;
        H[2][k] = n >= 2 ? n * (n - 1) * (lv2[2][k] - 2.0 * lv2[1][k] + lv2[0][k]) : 0.0;
    }
    const double w = H[0][2], w1 = H[1][2], w2 = H[2][2];
    const double P0 = obc_divw(H[0][0], w), P1 = obc_divw(H[0][1], w);
    out[0][0] = P0;
    out[0][1] = P1;
    if (nder < 1)
        return;
    const double D0 = obc_divw(H[1][0] - w1 * P0, w), D1 = obc_divw(H[1][1] - w1 * P1, w);
    out[1][0] = D0;
    out[1][1] = D1;
    if (nder < 2)
        return;
    out[2][0] = obc_divw(H[2][0] - 2.0 * w1 * D0 - w2 * P0, w);
    out[2][1] = obc_divw(H[2][1] - 2.0 * w1 * D1 - w2 * P1, w);
}

OBC_FN void obc_point(const OBC_G double *h, int n, double t, double p[2], long *ops)
{
    double o[3][2];
    obc_eval(h, n, t, 0, o, ops);
    p[0] = o[0][0];
    p[1] = o[0][1];
}

/* Tangent direction at t (not normalized), with the one-sided limit where C'
 * vanishes (C'(t+h) ~ h C'', so +C'' below t = 1, -C'' at 1).  "Vanishes" is
 * judged against |C''| (scale-free) and against the control polygon's extent
 * (round-off on a point-like segment).  Returns -1 for a point-like segment. */
/* The scale of obc_tangent's "vanishes": 1e-12 of the control polygon's
 * extent into *tiny; -1 for a point-like segment (extent round-off of its
 * magnitude), which has no tangent. */
OBC_FN int obc_tangent_scale(const OBC_G double *h, int n, double *tiny)
{
    const double x0 = h[0] / h[2], y0 = h[1] / h[2];
    double ext = 0.0, mag = 0.0;
    for (int i = 0; i <= n; i++) {
        const double x = h[3 * i] / h[3 * i + 2], y = h[3 * i + 1] / h[3 * i + 2];
        ext = OBC_FMAX(ext, OBC_FMAX(fabs(x - x0), fabs(y - y0)));
        mag = OBC_FMAX(mag, OBC_FMAX(fabs(x), fabs(y)));
    }
    *tiny = 1e-12 * ext;
    return ext <= 1e-13 * mag ? -1 : 0;
}

/* obc_tangent's choice from the point and derivatives o = obc_eval(h, n, t,
 * 2) already computed (a caller that needs the point too evaluates once). */
OBC_FN int obc_tangent_from(const OBC_G double *h, int n, double t, double tiny, double o[3][2], double v[2],
                            long *ops)
{
    const double s1 = sqrt(o[1][0] * o[1][0] + o[1][1] * o[1][1]);
    const double s2 = sqrt(o[2][0] * o[2][0] + o[2][1] * o[2][1]);
    if (s1 > 1e-12 * s2 && s1 > tiny) {
        v[0] = o[1][0];
        v[1] = o[1][1];
        return 0;
    }
    if (s2 > tiny) {
        const double sg = t >= 1.0 ? -1.0 : 1.0;
        v[0] = sg * o[2][0];
        v[1] = sg * o[2][1];
        return 0;
    }
    double o1[3][2];
    const double dh = t >= 1.0 ? -1e-6 : 1e-6;
    obc_eval(h, n, t + dh, 1, o1, ops);
    if (sqrt(o1[1][0] * o1[1][0] + o1[1][1] * o1[1][1]) > tiny) {
        v[0] = o1[1][0];
        v[1] = o1[1][1];
        return 0;
    }
    return -1;
}

OBC_FN int obc_tangent(const OBC_G double *h, int n, double t, double v[2], long *ops)
{
    double tiny, o[3][2];
    v[0] = v[1] = 0.0;
    if (obc_tangent_scale(h, n, &tiny) != 0)
        return -1;
    obc_eval(h, n, t, 2, o, ops);
    return obc_tangent_from(h, n, t, tiny, o, v, ops);
}

/* The unit left normal (-y', x') / |v| of a tangent v. */
OBC_FN void obc_unit_normal(const double v[2], double N[2])
{
    const double len = sqrt(v[0] * v[0] + v[1] * v[1]);
    N[0] = -v[1] / len;
    N[1] = v[0] / len;
}

/* Unit left normal (-y', x')/|C'|; (0,0) and -1 for a point-like segment. */
OBC_FN int obc_normal(const OBC_G double *h, int n, double t, double N[2], long *ops)
{
    double v[2];
    if (obc_tangent(h, n, t, v, ops) != 0) {
        N[0] = N[1] = 0.0;
        return -1;
    }
    obc_unit_normal(v, N);
    return 0;
}

/* Point P, derivative dP and curvature vector K = kappa N of the curve (d = 0)
 * or of its exact d-offset at t.  For the offset: O' = C' (1 - d kappa), since
 * N' = -kappa C', and kappa_O N_O = kappa / (1 - d kappa) N. */
OBC_CALL_FN void obc_pc_eval(const OBC_G double *h, int n, double d, double t, double P[2], double dP[2],
                             double K[2], long *ops)
{
    double o[3][2];
    obc_eval(h, n, t, 2, o, ops);
    const double sp = sqrt(o[1][0] * o[1][0] + o[1][1] * o[1][1]);
    const double s2 = sqrt(o[2][0] * o[2][0] + o[2][1] * o[2][1]);
    const int regular = sp > 1e-12 * s2 && sp > 0;
    const double kappa = regular ? (o[1][0] * o[2][1] - o[1][1] * o[2][0]) / (sp * sp * sp) : 0.0;
    double N[2];
    N[0] = N[1] = 0.0;
    if (regular) {
        N[0] = -o[1][1] / sp;
        N[1] = o[1][0] / sp;
    } else if (d != 0.0) {
        obc_normal(h, n, t, N, ops); /* the one-sided limit at a cusp */
    }
    if (d == 0.0) {
        P[0] = o[0][0];
        P[1] = o[0][1];
        dP[0] = o[1][0];
        dP[1] = o[1][1];
        K[0] = kappa * N[0];
        K[1] = kappa * N[1];
        return;
    }
    const double f = 1.0 - d * kappa;
    P[0] = o[0][0] + d * N[0];
    P[1] = o[0][1] + d * N[1];
    dP[0] = f * o[1][0];
    dP[1] = f * o[1][1];
    const double ko = f != 0.0 ? kappa / f : 0.0;
    K[0] = ko * N[0];
    K[1] = ko * N[1];
}

OBC_FN double obc_dist(const double a[2], const double b[2])
{
    const double x = a[0] - b[0], y = a[1] - b[1];
    return sqrt(x * x + y * y);
}

/* ---- the error at one parameter -------------------------------------- */

/* Everything an error evaluation needs, passed by value (no pointers to
 * structs across OpenCL address spaces). */
#define OBC_ARGS const OBC_G double *hb, int nb, const OBC_G double *ha, int na, double d, int S, \
                 const OBC_G double *tgt, const OBC_G double *qry, long *ops
#define OBC_PASS hb, nb, ha, na, d, S, tgt, qry, ops

/* Hausdorff sample tables.  Per sample k, OBC_REC doubles at [OBC_REC k]:
 * point, derivative and curvature vector (obc_pc_eval) of the offset O or
 * of the approximation A at t_k, and at OBC_MARGIN the margin of span k
 * (samples k, k+1; see obc_fill_table).  Kept so that a query at a sample
 * point and the first Newton step of its projection cost no curve
 * evaluation.  After the S rows, per block of OBC_BLK spans, a circle
 * (centre x, y, radius, unused) holding the block's part of the curve: the
 * nearest-foot search skips blocks that cannot hold a nearer point. */
#define OBC_REC 8
#define OBC_MARGIN 6
#define OBC_BLK 16
#define OBC_NBLK(S) (((S) + OBC_BLK - 2) / OBC_BLK)
#define OBC_TABLE_SIZE(S) (OBC_REC * (S) + 4 * OBC_NBLK(S))
#define OBC_MAX_CAND 8 /* spans refined per query beyond the nearest sample's (obc_side_dist) */
#define OBC_NO_HINT (-0x40000000) /* obc_side_dist: no foot found yet */
#define OBC_LB_CACHE 32 /* block bounds kept per query (obc_side_dist): all of them up to S = 513 */

OBC_FN double obc_sample_t(int k, int S) { return (double)k / (S - 1); }

/* The rows of sample table T (see obc_fill_table), one obc_pc_eval per
 * sample: the scalar reference of obc_table_rows. */
OBC_FN void obc_table_rows_ref(const OBC_G double *h, int n, double dc, int S, OBC_G double *T, long *ops)
{
    for (int k = 0; k < S; k++) {
        double P[2], dP[2], K[2];
        obc_pc_eval(h, n, dc, obc_sample_t(k, S), P, dP, K, ops);
        OBC_G double *r = T + OBC_REC * k;
        r[0] = P[0], r[1] = P[1], r[2] = dP[0], r[3] = dP[1], r[4] = K[0], r[5] = K[1];
        r[6] = r[7] = 0.0;
    }
}

/* ---- the sample tables, OBC_LANES samples at a time ------------------- */

#define OBC_LANES 4

/* obc_casteljau for OBC_LANES parameters t[l] at once on the first K
 * coordinates: q0[k][l], levels 2 (l2[k][i][l]) and 1 (l1[k][i][l]).  Each
 * lane runs the scalar pass's lerps in its order (the levels of one
 * coordinate before the next: the coordinates do not mix). */
OBC_FN void obc_casteljau_lanes(const OBC_G double *h, int n, const double *t, const int K,
                                double q0[3][OBC_LANES], double l2[3][3][OBC_LANES], double l1[3][2][OBC_LANES])
{
    double s[OBC_LANES], q[OBC_MAX_DEG][OBC_LANES];
    OBC_SIMD
    for (int l = 0; l < OBC_LANES; l++)
        s[l] = 1.0 - t[l];
    for (int k = 0; k < K; k++) {
        if (n == 0) {
            for (int l = 0; l < OBC_LANES; l++)
                q0[k][l] = h[k];
            continue;
        }
        if (n == 1) {
            for (int i = 0; i < 2; i++)
                for (int l = 0; l < OBC_LANES; l++)
                    l1[k][i][l] = h[3 * i + k];
        } else if (n == 2) {
            for (int i = 0; i < 3; i++)
                for (int l = 0; l < OBC_LANES; l++)
                    l2[k][i][l] = h[3 * i + k];
        } else {
            /* level n straight from the control points, then down to 3 */
            for (int i = 0; i < n; i++) {
                const double a = h[3 * i + k], b = h[3 * i + 3 + k];
                OBC_SIMD
                for (int l = 0; l < OBC_LANES; l++)
                    q[i][l] = s[l] * a + t[l] * b;
            }
            for (int r = n - 1; r >= 3; r--)
                for (int i = 0; i < r; i++) {
                    OBC_SIMD
                    for (int l = 0; l < OBC_LANES; l++)
                        q[i][l] = s[l] * q[i][l] + t[l] * q[i + 1][l];
                }
            for (int i = 0; i < 3; i++)
                for (int l = 0; l < OBC_LANES; l++)
                    l2[k][i][l] = q[i][l];
        }
        if (n >= 2)
            for (int i = 0; i < 2; i++) {
                OBC_SIMD
                for (int l = 0; l < OBC_LANES; l++)
                    l1[k][i][l] = s[l] * l2[k][i][l] + t[l] * l2[k][i + 1][l];
            }
        OBC_SIMD
        for (int l = 0; l < OBC_LANES; l++)
            q0[k][l] = s[l] * l1[k][0][l] + t[l] * l1[k][1][l];
    }
}

/* obc_pc_eval at OBC_LANES parameters t[l]: R[0..5][l] = P, dP, K, and what
 * obc_lane_ok needs (R[6..8]: |C'|, |C''|, 1 - d kappa).  Where obc_lane_ok
 * says no, R is not obc_pc_eval's (the one-sided limit at a cusp needs
 * obc_normal): the caller evaluates that lane with obc_pc_eval.  poly: every
 * weight is 1 (the shortcut of obc_eval; every t here is in [0,1]).  Each
 * lane runs obc_eval's and obc_pc_eval's operations in their order, so the
 * bits are theirs; no branch per lane, so the loops vectorize. */
OBC_FN void obc_pc_lanes(const OBC_G double *h, int n, int poly, double d, const double *t,
                         double R[9][OBC_LANES])
{
    double q0[3][OBC_LANES], l2[3][3][OBC_LANES], l1[3][2][OBC_LANES];
    for (int k = 0; k < 3; k++)
        for (int l = 0; l < OBC_LANES; l++) /* what obc_eval's zeroed levels hold below degree 2 */
            l2[k][0][l] = l2[k][1][l] = l2[k][2][l] = l1[k][0][l] = l1[k][1][l] = 0.0;
    obc_casteljau_lanes(h, n, t, poly ? 2 : 3, q0, l2, l1);
    if (poly)
        for (int l = 0; l < OBC_LANES; l++) {
            q0[2][l] = 1.0;
            l1[2][0][l] = l1[2][1][l] = 1.0;
            l2[2][0][l] = l2[2][1][l] = l2[2][2][l] = 1.0;
        }
    const double dn = n, dnn = n * (n - 1);
    double H1[3][OBC_LANES], H2[3][OBC_LANES], kappa[OBC_LANES], N0[OBC_LANES], N1[OBC_LANES];
    for (int k = 0; k < 3; k++) {
        OBC_SIMD
        for (int l = 0; l < OBC_LANES; l++)
            H1[k][l] = H2[k][l] = 0.0;
        if (n >= 1) {
            OBC_SIMD
            for (int l = 0; l < OBC_LANES; l++)
                H1[k][l] = dn * (l1[k][1][l] - l1[k][0][l]);
        }
        if (n >= 2) {
            OBC_SIMD
            for (int l = 0; l < OBC_LANES; l++)
                H2[k][l] = dnn * (l2[k][2][l] - 2.0 * l2[k][1][l] + l2[k][0][l]);
        }
    }
    OBC_SIMD
    for (int l = 0; l < OBC_LANES; l++) {
        const double w = q0[2][l], w1 = H1[2][l], w2 = H2[2][l];
        const double P0 = q0[0][l] / w, P1 = q0[1][l] / w;
        const double D0 = (H1[0][l] - w1 * P0) / w, D1 = (H1[1][l] - w1 * P1) / w;
        const double E0 = (H2[0][l] - 2.0 * w1 * D0 - w2 * P0) / w, E1 = (H2[1][l] - 2.0 * w1 * D1 - w2 * P1) / w;
        const double sp = sqrt(D0 * D0 + D1 * D1), s2 = sqrt(E0 * E0 + E1 * E1);
        kappa[l] = (D0 * E1 - D1 * E0) / (sp * sp * sp);
        N0[l] = -D1 / sp;
        N1[l] = D0 / sp;
        R[0][l] = P0, R[1][l] = P1, R[2][l] = D0, R[3][l] = D1;
        R[6][l] = sp, R[7][l] = s2;
    }
    if (d == 0.0) {
        OBC_SIMD
        for (int l = 0; l < OBC_LANES; l++) {
            R[4][l] = kappa[l] * N0[l];
            R[5][l] = kappa[l] * N1[l];
        }
        return;
    }
    OBC_SIMD
    for (int l = 0; l < OBC_LANES; l++) {
        const double f = 1.0 - d * kappa[l], ko = kappa[l] / f;
        R[0][l] = R[0][l] + d * N0[l];
        R[1][l] = R[1][l] + d * N1[l];
        R[2][l] = f * R[2][l];
        R[3][l] = f * R[3][l];
        R[4][l] = ko * N0[l];
        R[5][l] = ko * N1[l];
        R[8][l] = f;
    }
}

/* Whether lane l of obc_pc_lanes holds obc_pc_eval's bits: a regular point
 * (|C'| > 1e-12 |C''| and > 0), and off the offset's cusp (1 - d kappa != 0),
 * where obc_pc_eval takes other branches. */
OBC_FN int obc_lane_ok(double R[9][OBC_LANES], double d, int l)
{
    const double sp = R[6][l], s2 = R[7][l];
    return sp > 1e-12 * s2 && sp > 0 && (d == 0.0 || R[8][l] != 0.0);
}

/* 1 when every weight of (h, n) is 1: obc_pc_lanes' polynomial branch. */
OBC_FN int obc_table_poly(const OBC_G double *h, int n)
{
    int poly = 1;
    for (int i = 0; i <= n && poly; i++)
        poly = h[3 * i + 2] == 1.0;
    return poly;
}

/* Rows k0 .. k0 + OBC_LANES - 1 (those below S) of sample table T in one
 * obc_pc_lanes call, k0 a multiple of OBC_LANES; a lane that obc_lane_ok
 * refuses by obc_pc_eval.  poly: obc_table_poly(h, n).  Rows of different
 * k0 are independent: the kernel shares them out over work-items. */
OBC_FN void obc_table_lanes(const OBC_G double *h, int n, int poly, double dc, int S, int k0, OBC_G double *T,
                            long *ops)
{
    double t[OBC_LANES], R[9][OBC_LANES];
    for (int l = 0; l < OBC_LANES; l++) /* lanes past the end repeat the last sample */
        t[l] = obc_sample_t(k0 + l < S ? k0 + l : S - 1, S);
    obc_pc_lanes(h, n, poly, dc, t, R);
    for (int l = 0; l < OBC_LANES && k0 + l < S; l++) {
        OBC_G double *r = T + OBC_REC * (k0 + l);
        if (obc_lane_ok(R, dc, l)) {
            *ops += OBC_OPS_EVAL(n);
            for (int c = 0; c < 6; c++)
                r[c] = R[c][l];
        } else {
            double P[2], dP[2], K[2];
            obc_pc_eval(h, n, dc, t[l], P, dP, K, ops);
            r[0] = P[0], r[1] = P[1], r[2] = dP[0], r[3] = dP[1], r[4] = K[0], r[5] = K[1];
        }
        r[6] = r[7] = 0.0;
    }
}

/* The rows of sample table T, OBC_LANES samples at a time (obc_table_lanes).
 * The same bits and the same count of work as obc_table_rows_ref. */
OBC_FN void obc_table_rows(const OBC_G double *h, int n, double dc, int S, OBC_G double *T, long *ops)
{
    const int poly = obc_table_poly(h, n);
    for (int k0 = 0; k0 < S; k0 += OBC_LANES)
        obc_table_lanes(h, n, poly, dc, S, k0, T, ops);
}

/* The margin of span j (rows j, j + 1) of table T: see obc_fill_table. */
OBC_FLAT_FN void obc_table_margin(int S, OBC_G double *T, int j)
{
    const double hs = 1.0 / (S - 1);
    OBC_G double *a = T + OBC_REC * j;
    const OBC_G double *b = a + OBC_REC;
    const double c0 = (b[0] - a[0]) / hs, c1 = (b[1] - a[1]) / hs;
    const double e0 = sqrt((a[2] - c0) * (a[2] - c0) + (a[3] - c1) * (a[3] - c1));
    const double e1 = sqrt((b[2] - c0) * (b[2] - c0) + (b[3] - c1) * (b[3] - c1));
    a[OBC_MARGIN] = 0.5 * hs * (e0 + e1);
}

/* The circle of block bk of table T from its rows and margins. */
OBC_FN void obc_table_block(int S, OBC_G double *T, int bk)
{
    const int j0 = OBC_BLK * bk, j1 = j0 + OBC_BLK < S - 1 ? j0 + OBC_BLK : S - 1;
    double x0 = OBC_INF, x1 = -OBC_INF, y0 = OBC_INF, y1 = -OBC_INF, m = 0.0;
    for (int j = j0; j <= j1; j++) {
        const OBC_G double *r = T + OBC_REC * j;
        x0 = OBC_FMIN(x0, r[0]), x1 = OBC_FMAX(x1, r[0]);
        y0 = OBC_FMIN(y0, r[1]), y1 = OBC_FMAX(y1, r[1]);
        if (j < j1)
            m = OBC_FMAX(m, r[OBC_MARGIN]);
    }
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    double rad = 0.0;
    for (int j = j0; j <= j1; j++) {
        const double x = T[OBC_REC * j] - cx, y = T[OBC_REC * j + 1] - cy;
        rad = OBC_FMAX(rad, sqrt(x * x + y * y));
    }
    OBC_G double *c = T + OBC_REC * S + 4 * bk;
    c[0] = cx, c[1] = cy, c[2] = rad + m, c[3] = 0.0;
}

/* The margins and block circles of table T from its rows (see obc_fill_table):
 * every margin first, the circles read them. */
OBC_FN void obc_table_bounds(int S, OBC_G double *T)
{
    OBC_SIMD
    for (int j = 0; j < S - 1; j++)
        obc_table_margin(S, T, j);
    for (int bk = 0; bk < OBC_NBLK(S); bk++)
        obc_table_block(S, T, bk);
}

/* Purpose: the sample table T of curve (h, n) or of its exact dc-offset,
 * rows by obc_table_rows (the same bits as obc_table_rows_ref, the scalar
 * reference kept for the tests), then margins and block circles.
 * The margin of span j bounds how far the curve strays from the chord
 * P_j P_{j+1}: a cubic Hermite arc with end derivatives m0, m1 over a span
 * of parameter length h strays at most (4/27) h (|m0 - c| + |m1 - c|) from
 * its chord (c = chord / h); the margin takes 0.5 instead of 4/27 to cover
 * the curve's departure from its Hermite arc.  A block's circle holds its
 * sample points (hence its chords) widened by its largest margin. */
OBC_FN void obc_fill_table(const OBC_G double *h, int n, double dc, int S, OBC_G double *T, long *ops)
{
    obc_table_rows(h, n, dc, S, T, ops);
    obc_table_bounds(S, T);
}

/* obc_fill_table with the scalar rows: the reference of the tests. */
OBC_FN void obc_fill_table_ref(const OBC_G double *h, int n, double dc, int S, OBC_G double *T, long *ops)
{
    obc_table_rows_ref(h, n, dc, S, T, ops);
    obc_table_bounds(S, T);
}

OBC_FN double obc_radial_err(OBC_ARGS, double t)
{
    (void)S, (void)tgt, (void)qry;
    double p[2], q[2];
    obc_point(hb, nb, t, p, ops);
    obc_point(ha, na, t, q, ops);
    return fabs(obc_dist(q, p) - fabs(d));
}

/* g(u) = (A(u) - P) x N: zero where A meets the normal line through P. */
OBC_FN double obc_normal_g(const OBC_G double *ha, int na, double u, const double P[2], const double N[2],
                           double *dg, long *ops)
{
    double o[3][2];
    obc_eval(ha, na, u, 1, o, ops);
    const double r0 = o[0][0] - P[0], r1 = o[0][1] - P[1];
    *dg = o[1][0] * N[1] - o[1][1] * N[0];
    return r0 * N[1] - r1 * N[0];
}

OBC_FN double obc_normal_err(OBC_ARGS, double t)
{
    (void)tgt, (void)qry;
    double P[2], N[2], dg = 0.0;
    obc_point(hb, nb, t, P, ops);
    obc_normal(hb, nb, t, N, ops);
    /* Newton from u = t: the approximations are parameterized close to the base */
    double u = t, g;
    int ok = 0;
    for (int it = 0; it < 30; it++) {
        g = obc_normal_g(ha, na, u, P, N, &dg, ops);
        if (dg == 0.0)
            break;
        const double du = g / dg;
        u -= du;
        if (u < -0.5 || u > 1.5 || isnan(u) || isinf(u))
            break;
        if (fabs(du) < 1e-15) {
            ok = 1;
            break;
        }
    }
    if (ok) {
        /* Newton may jump past nearer crossings to a far one (an extension of
         * A far from the offset): keep its root only when g has no sign
         * change strictly closer to t, checked on the scan's grid */
        const double w = fabs(u - t) * (1.0 - 1e-9), h = 1.5 / (2 * S);
        const int m = (int)ceil(2.0 * w / h) + 1;
        double gp = obc_normal_g(ha, na, t - w, P, N, &dg, ops);
        for (int j = 1; j <= m && ok; j++) {
            const double gj = obc_normal_g(ha, na, t - w + 2.0 * w * j / m, P, N, &dg, ops);
            if ((gp <= 0) != (gj <= 0))
                ok = 0;
            gp = gj;
        }
    }
    if (!(ok && !(u < -0.5 || u > 1.5))) {
        /* the sign change of g nearest to t on the extended parameter range,
         * refined by bisection (the polynomial is extrapolated past [0,1]);
         * a rational A also changes sign through a pole, where |g| grows
         * instead of vanishing: such a crossing is not an intersection */
        const int M = 2 * S;
        double best = OBC_INF, ub = -1e300;
        double u0 = -0.25, g0 = obc_normal_g(ha, na, u0, P, N, &dg, ops);
        for (int j = 1; j <= M; j++) {
            const double u1 = -0.25 + 1.5 * j / M;
            const double g1 = obc_normal_g(ha, na, u1, P, N, &dg, ops);
            if ((g0 <= 0) != (g1 <= 0)) {
                double lo = u0, hi = u1, glo = g0;
                for (int it = 0; it < 100 && hi - lo > 1e-15; it++) {
                    const double mid = 0.5 * (lo + hi);
                    const double gm = obc_normal_g(ha, na, mid, P, N, &dg, ops);
                    if ((gm <= 0) == (glo <= 0)) {
                        lo = mid;
                        glo = gm;
                    } else {
                        hi = mid;
                    }
                }
                const double r = 0.5 * (lo + hi);
                const double gr = fabs(obc_normal_g(ha, na, r, P, N, &dg, ops));
                if (gr <= 1e-6 * OBC_FMAX(fabs(g0), fabs(g1)) && fabs(r - t) < best) {
                    best = fabs(r - t);
                    ub = r;
                }
            }
            u0 = u1;
            g0 = g1;
        }
        if (ub == -1e300) {
            /* A never meets this normal line: report the point mismatch */
            double q[2], O[2];
            O[0] = P[0] + d * N[0];
            O[1] = P[1] + d * N[1];
            obc_point(ha, na, t, q, ops);
            return obc_dist(q, O);
        }
        u = ub;
    }
    double q[2];
    obc_point(ha, na, u, q, ops);
    const double s = (q[0] - P[0]) * N[0] + (q[1] - P[1]) * N[1];
    return fabs(s - d);
}

/* Zhao & Zhou 2017, section 3: "The error e(t) is measured as the distance
 * between the two parameter points R(A, t) and C_r(t), which are located on
 * the same normal curve N(t), so it could be represented as
 * e(t) = (R(A, t) - C_r(t)) . N(t)".  Here |e(t)| with R = A and C_r = the
 * exact offset O = C + d N at the same t.  Where the base has no normal (a
 * point-like segment, obc_normal fails) the radial error stands in. */
OBC_FN double obc_param_err(OBC_ARGS, double t)
{
    (void)S, (void)tgt, (void)qry;
    double P[2], N[2], q[2];
    obc_point(hb, nb, t, P, ops);
    obc_point(ha, na, t, q, ops);
    if (obc_normal(hb, nb, t, N, ops) != 0)
        return fabs(obc_dist(q, P) - fabs(d));
    const double r0 = q[0] - (P[0] + d * N[0]), r1 = q[1] - (P[1] + d * N[1]);
    return fabs(r0 * N[0] + r1 * N[1]);
}

/* Distance from Q to the target curve (hc, nc, dc: a segment, or its offset
 * when dc != 0) near t0 within [lo,hi]; *tp gets the foot parameter.  Newton on
 * f(t) = (P - Q).P', whose derivative near the foot is |P'|^2 (1 - K.(Q - P)):
 * quadratic convergence even where the distance is comparable to the radius
 * of curvature.  start: P, P', K at t0 if known (else NULL).
 * first: NULL, or the curve at the first Newton step from start, when the
 * caller has evaluated it (t, P, P', K: 7 doubles; used where t is that step).
 * cut: the caller only needs distances above cut.  The result never exceeds
 * the distance to any point tried, so once that is <= cut it is returned at
 * once: an upper bound that the caller's comparison treats exactly like the
 * settled distance (branch and bound; pass a negative cut for the exact
 * distance).  Settled when a step is below 1e-8 of the bracket (the
 * distance is then exact far below that, being quadratic in the parameter
 * error) or stops shrinking while below 1e-6 of it (round-off in (P - Q).P'
 * is the floor).  A step that stops shrinking before that is Newton stalling
 * at a cusp of the target, where P' vanishes (the foot is often the cusp
 * itself): golden section settles it.  Beyond
 * the centre of curvature (1 - K.(Q - P) small or negative) Newton is not
 * safe; there, and wherever it has not settled in 20 steps, golden-section
 * search on the bracket takes over. */
OBC_CALL_FN double obc_project(const OBC_G double *hc, int nc, double dc, const double Q[2], double t0, double lo,
                               double hi, const OBC_G double *start, const double *first, double cut, double *tp,
                               long *ops)
{
    double t = t0, P[2], dP[2], K[2];
    if (start) {
        P[0] = start[0], P[1] = start[1];
        dP[0] = start[2], dP[1] = start[3];
        K[0] = start[4], K[1] = start[5];
    } else {
        obc_pc_eval(hc, nc, dc, t, P, dP, K, ops);
    }
    double best = obc_dist(Q, P), tb = t, prev = OBC_INF;
    int settled = 0;
    if (best <= cut) {
        *tp = tb;
        return best;
    }
    for (int it = 0; it < 20 && !settled; it++) {
        const double dd = dP[0] * dP[0] + dP[1] * dP[1];
        const double r0 = Q[0] - P[0], r1 = Q[1] - P[1];
        const double den = 1.0 - (K[0] * r0 + K[1] * r1);
        if (dd == 0.0 || !(den > 0.2))
            break;
        const double step = (r0 * dP[0] + r1 * dP[1]) / (dd * den);
        const double tn = OBC_FMIN(hi, OBC_FMAX(lo, t + step));
        settled = fabs(tn - t) <= 1e-8 * (hi - lo) || (fabs(step) >= prev && fabs(step) <= 1e-6 * (hi - lo));
        prev = fabs(step);
        if (tn == t)
            break;
        t = tn;
        if (it == 0 && first && first[0] == t) { /* evaluated by the caller */
            P[0] = first[1], P[1] = first[2], dP[0] = first[3], dP[1] = first[4], K[0] = first[5], K[1] = first[6];
        } else {
            obc_pc_eval(hc, nc, dc, t, P, dP, K, ops);
        }
        const double e = obc_dist(Q, P);
        if (e < best) {
            best = e;
            tb = t;
        }
        if (best <= cut)
            break;
    }
    if (!settled && !(best <= cut)) {
        const double g = 0.6180339887498949;
        double a = lo, b = hi, x1 = b - g * (b - a), x2 = a + g * (b - a);
        obc_pc_eval(hc, nc, dc, x1, P, dP, K, ops);
        double f1 = obc_dist(Q, P);
        obc_pc_eval(hc, nc, dc, x2, P, dP, K, ops);
        double f2 = obc_dist(Q, P);
        for (int it = 0; it < 60 && b - a > 1e-14; it++) {
            if (f1 < f2) {
                b = x2;
                x2 = x1;
                f2 = f1;
                x1 = b - g * (b - a);
                obc_pc_eval(hc, nc, dc, x1, P, dP, K, ops);
                f1 = obc_dist(Q, P);
            } else {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + g * (b - a);
                obc_pc_eval(hc, nc, dc, x2, P, dP, K, ops);
                f2 = obc_dist(Q, P);
            }
        }
        const double fm = f1 < f2 ? f1 : f2, xm = f1 < f2 ? x1 : x2;
        if (fm < best) {
            best = fm;
            tb = xm;
        }
    }
    *tp = tb;
    return best;
}

/* Distance from Q to the chord of span j (samples j, j+1) of table T. */
OBC_FN double obc_chord_dist2(const double Q[2], const OBC_G double *T, int j, long *ops)
{
    const OBC_G double *a = T + OBC_REC * j, *b = a + OBC_REC;
    *ops += OBC_OPS_CHORD;
    const double vx = b[0] - a[0], vy = b[1] - a[1], wx = Q[0] - a[0], wy = Q[1] - a[1];
    const double vv = vx * vx + vy * vy;
    const double s = vv > 0.0 ? OBC_FMIN(1.0, OBC_FMAX(0.0, (wx * vx + wy * vy) / vv)) : 0.0;
    const double x = wx - s * vx, y = wy - s * vy;
    return x * x + y * y;
}

OBC_FN double obc_sample_dist2(const double Q[2], const OBC_G double *T, int j)
{
    const double x = Q[0] - T[OBC_REC * j], y = Q[1] - T[OBC_REC * j + 1];
    return x * x + y * y;
}

/* Lower bound of the distance from Q to block bk of table T (S samples). */
OBC_FN double obc_block_lb(const double Q[2], const OBC_G double *T, int S, int bk, long *ops)
{
    const OBC_G double *c = T + OBC_REC * S + 4 * bk;
    const double x = Q[0] - c[0], y = Q[1] - c[1];
    *ops += OBC_OPS_BLOCK;
    return sqrt(x * x + y * y) - c[2];
}

/* The nearest sample point of block bk to Q, if nearer than *db (squared). */
OBC_FN void obc_block_nearest(const double Q[2], const OBC_G double *T, int S, int bk, double *db, int *jb, long *ops)
{
    const int j0 = OBC_BLK * bk, j1 = j0 + OBC_BLK < S - 1 ? j0 + OBC_BLK : S - 1;
    *ops += OBC_OPS_POINT * (j1 - j0 + 1);
    for (int j = j0; j <= j1; j++) {
        const double e = obc_sample_dist2(Q, T, j);
        if (e < *db) {
            *db = e;
            *jb = j;
        }
    }
}

/* The cheap settlements of a query Q near the last foot (obc_side_dist):
 * the samples of target table T beside sample `hint`, then one Newton step
 * of the projection from the nearest of them (one curve evaluation: the
 * step obc_project would take first from there).  Either gives the
 * distance to a point of the target, an upper bound of the query's
 * distance; when it is <= cut that is all the caller asks for (see
 * obc_project), so it is returned, with *tfoot its parameter.  Else -1.
 * *db, *jb: the nearest of those samples (squared distance, index), where
 * the global search starts; first: the evaluation of the Newton step from
 * jb when it did not settle the query (as obc_project's `first`).  Without this step every query the running
 * maximum settles paid for the search over all blocks first. */
OBC_FN double obc_near_hint(const OBC_G double *hc, int nc, double dc, const double Q[2], const OBC_G double *T,
                            int S, int hint, double cut, double *db, int *jb, double *tfoot, double first[7],
                            long *ops)
{
    *ops += 3 * OBC_OPS_POINT;
    for (int j = hint - 1; j <= hint + 1; j++)
        if (j >= 0 && j < S && obc_sample_dist2(Q, T, j) < *db) {
            *db = obc_sample_dist2(Q, T, j);
            *jb = j;
        }
    if (*jb < 0 || !(cut >= 0.0))
        return -1.0;
    if (*db <= cut * cut) {
        *tfoot = obc_sample_t(*jb, S);
        return sqrt(*db);
    }
    const OBC_G double *r = T + OBC_REC * *jb;
    const double dd = r[2] * r[2] + r[3] * r[3];
    const double r0 = Q[0] - r[0], r1 = Q[1] - r[1];
    const double den = 1.0 - (r[4] * r0 + r[5] * r1);
    if (dd == 0.0 || !(den > 0.2))
        return -1.0;
    const double lo = obc_sample_t(*jb > 0 ? *jb - 1 : 0, S), hi = obc_sample_t(*jb < S - 1 ? *jb + 1 : S - 1, S);
    const double t = OBC_FMIN(hi, OBC_FMAX(lo, obc_sample_t(*jb, S) + (r0 * r[2] + r1 * r[3]) / (dd * den)));
    double P[2], dP[2], K[2];
    obc_pc_eval(hc, nc, dc, t, P, dP, K, ops);
    const double e = obc_dist(Q, P);
    if (!(e <= cut)) { /* kept for the projection from sample jb, if the search ends there */
        first[0] = t, first[1] = P[0], first[2] = P[1], first[3] = dP[0], first[4] = dP[1];
        first[5] = K[0], first[6] = K[1];
        return -1.0;
    }
    *tfoot = t;
    return e;
}

/* obc_side_dist's query point Q: sample k of the query table when k >= 0,
 * else the query curve at u (the approximation for OBC_K_H_APPROX, the
 * offset for OBC_K_H_OFFSET). */
OBC_FN void obc_query_point(int kind, const OBC_G double *hb, int nb, const OBC_G double *ha, int na, double d,
                           const OBC_G double *qry, double u, int k, double Q[2], long *ops)
{
    double dQ[2], K[2];
    if (k >= 0) {
        Q[0] = qry[OBC_REC * k];
        Q[1] = qry[OBC_REC * k + 1];
    } else if (kind == OBC_K_H_APPROX) {
        obc_pc_eval(ha, na, 0.0, u, Q, dQ, K, ops);
    } else {
        obc_pc_eval(hb, nb, d, u, Q, dQ, K, ops);
    }
}

/* obc_side_dist's step (1): the nearest sample of the target table T to Q
 * into *db (squared) and *jb (-1: none finite; both as the caller set them
 * otherwise): the block whose circle comes nearest, then any other block
 * that can hold a nearer one.  lbc gets the bounds of the first
 * OBC_LB_CACHE blocks, which step (3) asks again. */
OBC_FN void obc_nearest_sample(const double Q[2], const OBC_G double *T, int S, double *lbc, double *db, int *jb,
                               long *ops)
{
    const int nblk = OBC_NBLK(S);
    int b0 = 0;
    double lb0 = OBC_INF;
    const int ncache = nblk < OBC_LB_CACHE ? nblk : OBC_LB_CACHE;
    const OBC_G double *circ = T + OBC_REC * S;
    *ops += OBC_OPS_BLOCK * ncache;
    OBC_SIMD /* obc_block_lb of the cached blocks, all at once */
    for (int bk = 0; bk < ncache; bk++) {
        const double x = Q[0] - circ[4 * bk], y = Q[1] - circ[4 * bk + 1];
        lbc[bk] = sqrt(x * x + y * y) - circ[4 * bk + 2];
    }
    for (int bk = 0; bk < nblk; bk++) {
        const double lb = bk < OBC_LB_CACHE ? lbc[bk] : obc_block_lb(Q, T, S, bk, ops);
        if (lb < lb0) {
            lb0 = lb;
            b0 = bk;
        }
    }
    obc_block_nearest(Q, T, S, b0, db, jb, ops);
    double rdb = sqrt(*db); /* kept while *db is */
    for (int bk = 0; bk < nblk; bk++)
        if (bk != b0 && (bk < OBC_LB_CACHE ? lbc[bk] : obc_block_lb(Q, T, S, bk, ops)) < rdb) {
            obc_block_nearest(Q, T, S, bk, db, jb, ops);
            rdb = sqrt(*db);
        }
}

/* obc_side_dist's step (3): the feet on spans other than [ja, jz) of the
 * target (curve hc, nc, dc; table T) that may be nearer to Q than best, at
 * most OBC_MAX_CAND of them, each refined by Newton; lbc as step (1) left
 * it.  Returns the least distance, its foot in *tb (kept when none is
 * nearer). */
OBC_FN double obc_far_spans(const OBC_G double *hc, int nc, double dc, const double Q[2], const OBC_G double *T,
                            int S, const double *lbc, int ja, int jz, double cut, double best, double *tb,
                            long *ops)
{
    const int nblk = OBC_NBLK(S);
    int ncand = 0;
    for (int bk = 0; bk < nblk && !(best <= cut) && ncand < OBC_MAX_CAND; bk++) {
        if (!((bk < OBC_LB_CACHE ? lbc[bk] : obc_block_lb(Q, T, S, bk, ops)) < best))
            continue;
        const int j0 = OBC_BLK * bk, j1 = j0 + OBC_BLK < S - 1 ? j0 + OBC_BLK : S - 1;
        for (int j = j0; j < j1 && !(best <= cut) && ncand < OBC_MAX_CAND; j++) {
            if (j >= ja && j < jz)
                continue;
            const double reach = best + T[OBC_REC * j + OBC_MARGIN];
            if (!(obc_chord_dist2(Q, T, j, ops) < reach * reach))
                continue;
            const int js = obc_sample_dist2(Q, T, j + 1) < obc_sample_dist2(Q, T, j) ? j + 1 : j;
            ncand++;
            double tp;
            const double e = obc_project(hc, nc, dc, Q, obc_sample_t(js, S), obc_sample_t(j, S),
                                         obc_sample_t(j + 1, S), T + OBC_REC * js, 0, cut, &tp, ops);
            if (e < best) {
                best = e;
                *tb = tp;
            }
        }
    }
    return best;
}

/* Hausdorff, one side: distance from the query curve's point at u to the
 * target curve, whose sample table is tgt.  kind OBC_K_H_APPROX: query A,
 * target O; OBC_K_H_OFFSET: query O, target A.  k >= 0: u is sample k and the
 * query point is read from the query table qry.  cut: as in obc_project.
 * *hint: where the last query's nearest target sample lay, as an offset
 * from that query's own sample (OBC_NO_HINT: no query yet); the target
 * samples at the same offset from this query's (the feet of consecutive
 * samples move together) are tried first, and it is updated.  *tfoot: the
 * foot.
 * Method: the nearest foot is searched globally.  (1) The nearest sample
 * point, over the blocks whose circle comes nearer than the best so far
 * (the nearest block first).  (2) Newton projection from it on its two
 * spans.  (3) Every other span whose chord comes within its margin of the
 * best distance so far (in a block that can) is refined likewise.  A local
 * search from the nearest sample alone (what was done before) lands on a
 * foot that is not the nearest one where the target folds back on itself:
 * the swallowtail of an offset near its cusps.  A fold brings a few spans
 * within reach (two or three branches, two spans each); more than
 * OBC_MAX_CAND means the target is all but equidistant from Q over many
 * spans (an arc about Q: the offset of a piece that has shrunk to a point),
 * where every span gives the distance to within its margin, and refining
 * them all would cost S projections for each query. */
OBC_CALL_FN double obc_side_dist(int kind, OBC_ARGS, double u, int k, double cut, int *hint, double *tfoot)
{
    const int to_offset = kind == OBC_K_H_APPROX;
    const OBC_G double *hc = to_offset ? hb : ha;
    const int nc = to_offset ? nb : na;
    const double dc = to_offset ? d : 0.0;
    double Q[2];
    obc_query_point(kind, hb, nb, ha, na, d, qry, u, k, Q, ops);
    const double cut2 = cut >= 0.0 ? cut * cut : -1.0;
    int jb = -1;
    double db = OBC_INF;
    /* near the last foot first: a distance under the cut settles the query */
    const int kq = k >= 0 ? k : (int)(u * (S - 1) + 0.5); /* the sample nearest u */
    double first[7] = {-1.0}; /* the Newton step from sample jh, if evaluated */
    int jh = -1;
    if (*hint != OBC_NO_HINT) {
        const int c = kq + *hint;
        const double e = obc_near_hint(hc, nc, dc, Q, tgt, S, c < 0 ? 0 : c < S ? c : S - 1, cut, &db, &jb,
                                       tfoot, first, ops);
        jh = jb;
        if (e >= 0.0) {
            *hint = jb - kq;
            return e;
        }
        /* not settled: the search below starts afresh, so that its nearest
         * sample (the first of equal ones in its own order) is the one a
         * query without a hint finds: a distance above the cut is the same
         * whatever the last query was (the group kernel computes a side's
         * samples out of order, kernels/measure.cl) */
        db = OBC_INF;
        jb = -1;
    }
    double lbc[OBC_LB_CACHE]; /* the bounds of the first blocks, asked again in (3) */
    obc_nearest_sample(Q, tgt, S, lbc, &db, &jb, ops);
    if (jb < 0) { /* no finite sample */
        *tfoot = 0.0;
        return OBC_INF;
    }
    *hint = jb - kq;
    if (db <= cut2) {
        *tfoot = obc_sample_t(jb, S);
        return sqrt(db);
    }
    /* (2) the foot near the nearest sample */
    const int ja = jb > 0 ? jb - 1 : 0, jz = jb < S - 1 ? jb + 1 : S - 1;
    double tb;
    const double best = obc_project(hc, nc, dc, Q, obc_sample_t(jb, S), obc_sample_t(ja, S), obc_sample_t(jz, S),
                                    tgt + OBC_REC * jb, jb == jh ? first : 0, cut, &tb, ops);
    /* (3) feet on other spans that may be nearer */
    *tfoot = tb;
    return obc_far_spans(hc, nc, dc, Q, tgt, S, lbc, ja, jz, cut, best, tfoot, ops);
}

/* The error at t; k >= 0 when t is sample k (Hausdorff reuses its tables);
 * Hausdorff may return any value <= cut when the error is <= cut. */
OBC_FN double obc_err_at(int kind, OBC_ARGS, double t, int k, double cut, int *hint)
{
    double tf;
    (void)tf;
    switch (kind) {
#if OBC_WANT_RADIAL
    case OBC_K_RADIAL: return obc_radial_err(OBC_PASS, t);
#endif
#if OBC_WANT_NORMAL
    case OBC_K_NORMAL: return obc_normal_err(OBC_PASS, t);
#endif
#if OBC_WANT_PARAM
    case OBC_K_PARAM: return obc_param_err(OBC_PASS, t);
#endif
#if OBC_WANT_HAUSDORFF
    case OBC_K_H_APPROX:
    case OBC_K_H_OFFSET: return obc_side_dist(kind, OBC_PASS, t, k, cut, hint, &tf);
#endif
    default: return OBC_INF; /* a kind this build does not hold */
    }
}

/* Golden-section maximization of the error on [a,b].  Each new point is
 * compared with the point kept from the last step, and when it loses, its
 * value is not used again: it is asked only for errors above the kept
 * value (the cut, as in obc_sample_refine), which lets the Hausdorff search
 * stop early without changing the result. */
OBC_FN double obc_golden_max(int kind, OBC_ARGS, double a, double b, int *hint, double *targ)
{
    const double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = obc_err_at(kind, OBC_PASS, x1, -1, -1.0, hint), f2 = obc_err_at(kind, OBC_PASS, x2, -1, -1.0, hint);
    for (int it = 0; it < 40 && b - a > 1e-13; it++) {
        if (f1 > f2) {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            /* only whether f1 > f2 matters unless it is: f2 as the cut */
            f1 = obc_err_at(kind, OBC_PASS, x1, -1, f2, hint);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            /* only whether f2 < f1 matters unless f2 >= f1 (a tie goes to
             * x2): a cut strictly below f1 */
            f2 = obc_err_at(kind, OBC_PASS, x2, -1, f1 - fabs(f1) * 0x1p-51, hint);
        }
    }
    if (f1 > f2) {
        *targ = x1;
        return f1;
    }
    *targ = x2;
    return f2;
}

/* Sample S parameters, take the largest error, refine it between the
 * neighbours.  A NaN or infinite sample ends the scan as the worst.  Each
 * sample is asked only for errors above the running maximum (the cut), which
 * lets the Hausdorff search stop early without changing the result.  A
 * running maximum above stop (the first sample above it, in scan order)
 * ends the scan without the refinement: that sample is the result. */
#define OBC_COARSE 8

/* Takes sample k's error e into the scan's running maximum (best, kb), the
 * first of equal maxima kept.  Returns 1 when e ends the scan: NaN or inf,
 * the worst, kept with its sample. */
OBC_FN int obc_scan_take(double e, int k, double *best, int *kb)
{
    if (!(e <= *best)) {
        *best = e;
        *kb = k;
    }
    return isnan(e) || isinf(e);
}

/* The end of a scan whose maximum is best at sample kb: +inf when that is
 * not finite, else the larger of it and the golden-section maximum between
 * the neighbouring samples. */
OBC_FN void obc_scan_refine(int kind, OBC_ARGS, double best, int kb, int *hint, double *err, double *targ)
{
    *err = best;
    *targ = obc_sample_t(kb, S);
    if (isnan(best) || isinf(best)) {
        *err = OBC_INF;
        return;
    }
    const double a = obc_sample_t(kb > 0 ? kb - 1 : 0, S), b = obc_sample_t(kb < S - 1 ? kb + 1 : S - 1, S);
    double tr;
    const double er = obc_golden_max(kind, OBC_PASS, a, b, hint, &tr);
    if (er > best) {
        *err = er;
        *targ = tr;
    }
}

OBC_FN void obc_sample_refine(int kind, OBC_ARGS, double stop, double *err, double *targ)
{
    double best = -1.0;
    int kb = 0, hint = OBC_NO_HINT, bad = 0;
    /* Hausdorff: every OBC_COARSE-th sample first, so that the running
     * maximum is near the final one early and most samples are settled by
     * the cut; the others in order */
    const int step = kind == OBC_K_H_APPROX || kind == OBC_K_H_OFFSET ? OBC_COARSE : 1;
    for (int pass = 0; pass < (step > 1 ? 2 : 1) && !bad; pass++) {
        for (int k = pass ? 1 : 0; k < S && !bad; k += pass ? 1 : step) {
            if (pass && k % step == 0)
                continue;
            bad = obc_scan_take(obc_err_at(kind, OBC_PASS, obc_sample_t(k, S), k, best, &hint), k, &best, &kb);
            if (best > stop) { /* exact: best is never a value settled by the cut */
                *err = best;
                *targ = obc_sample_t(kb, S);
                return;
            }
        }
    }
    obc_scan_refine(kind, OBC_PASS, best, kb, &hint, err, targ);
}

/* ---- one side's scan, data-parallel (the group kernel) ---------------- */

/* The scan above, in an order-free form: a GPU work-group computes a side's
 * sample errors all at once (kernels/measure.cl) and must find what the
 * serial scan finds, bit for bit.  It can, because a query's distance above
 * its cut does not depend on the query's history: the hint only seeds the
 * nearest-sample search, which starts afresh when the hint does not settle
 * the query (obc_side_dist), and a cut only lets a query return early with
 * a value at or below it.  So:
 *   phase 1  the coarse samples (every OBC_COARSE-th), each exact (no cut);
 *   replay   the serial scan's bookkeeping over them (obc_scan_replay);
 *   phase 2  the other samples, each asked only for errors above the
 *            coarse maximum: the serial running maximum is never below it
 *            at that point, so a value at or below it is one the serial scan
 *            does not take either, and a value above it is exact in both;
 *   replay   over them, from where the first replay ended;
 *   end      obc_scan_finish: the sample above stop, the non-finite one, or
 *            the golden-section refinement, as obc_sample_refine ends.
 * A side's distance is never NaN (a finite query point has a finite
 * distance to its nearest sample, from which every search starts), so a
 * value settled by the cut in one order is finite in every order. */

/* Samples in the coarse pass of the scan: k = 0, OBC_COARSE, ... < S. */
OBC_FN int obc_scan_ncoarse(int S) { return (S + OBC_COARSE - 1) / OBC_COARSE; }

/* The sample at position i of the scan's order (the coarse pass, then the
 * rest in increasing k). */
OBC_FN int obc_scan_at(int i, int S)
{
    const int nc = obc_scan_ncoarse(S);
    if (i < nc)
        return OBC_COARSE * i;
    const int j = i - nc; /* the j-th sample that is no multiple of OBC_COARSE */
    return j + j / (OBC_COARSE - 1) + 1;
}

/* Sample k's distance to the target, asked only above cut (< 0: exact), as
 * a query with no history makes it. */
OBC_FN double obc_side_query(int kind, OBC_ARGS, int k, double cut)
{
    int hint = OBC_NO_HINT;
    double tf;
    return obc_side_dist(kind, OBC_PASS, obc_sample_t(k, S), k, cut, &hint, &tf);
}

/* The serial scan's bookkeeping (obc_scan_take, then the stop) over the
 * errors E[k] of scan positions i0 .. i1 - 1, on the running maximum
 * (*best, *kb).  Returns 1 where the scan ends there (a NaN or inf sample,
 * or a maximum above stop), else 0. */
OBC_FN int obc_scan_replay(const OBC_G double *E, int S, int i0, int i1, double stop, double *best, int *kb)
{
    for (int i = i0; i < i1; i++) {
        const int k = obc_scan_at(i, S);
        if (obc_scan_take(E[k], k, best, kb) || *best > stop)
            return 1;
    }
    return 0;
}

/* The end of a replayed scan, as obc_sample_refine ends: a maximum above
 * stop is the result at its sample; else the refinement (a non-finite
 * maximum gives +inf there). */
OBC_FN void obc_scan_finish(int kind, OBC_ARGS, double stop, double best, int kb, double *err, double *targ)
{
    if (best > stop) {
        *err = best;
        *targ = obc_sample_t(kb, S);
        return;
    }
    int hint = OBC_NO_HINT;
    obc_scan_refine(kind, OBC_PASS, best, kb, &hint, err, targ);
}

/* The foot on O of A's point at t (A's side reports that parameter). */
OBC_FN double obc_h_foot(OBC_ARGS, double t)
{
    int hint = OBC_NO_HINT;
    double tf;
    obc_side_dist(OBC_K_H_APPROX, OBC_PASS, t, -1, -1.0, &hint, &tf);
    return tf;
}

/* ---- the two sides of the Hausdorff distance ------------------------- */

/* From A to O (tgt = O's table, qry = A's): the largest distance and, where
 * it is finite, the parameter of its foot on O (stop: obc_sample_refine). */
OBC_FN void obc_h_side_approx(OBC_ARGS, double stop, double *e, double *t)
{
    obc_sample_refine(OBC_K_H_APPROX, OBC_PASS, stop, e, t);
    if (!(isnan(*e) || isinf(*e)))
        *t = obc_h_foot(OBC_PASS, *t);
}

/* From O to A (tgt = A's table, qry = O's): the largest distance and its
 * parameter on O (stop: obc_sample_refine). */
OBC_FN void obc_h_side_offset(OBC_ARGS, double stop, double *e, double *t)
{
    obc_sample_refine(OBC_K_H_OFFSET, OBC_PASS, stop, e, t);
}

/* The Hausdorff distance: the larger side, A's side on a tie; A's side alone
 * when it is above stop (the O side is then not needed). */
OBC_FN void obc_h_pick(double e1, double t1, double e2, double t2, double stop, double *err, double *t)
{
    if (e1 > stop || e1 >= e2) {
        *err = e1;
        *t = t1;
    } else {
        *err = e2;
        *t = t2;
    }
}

/* The error kind the one-sided metrics (radial, normal, param) scan; -1 for
 * hausdorff and codes that are no sampled metric. */
OBC_FN int obc_scan_kind(int metric)
{
    return metric == OBC_RADIAL ? OBC_K_RADIAL
           : metric == OBC_NORMAL ? OBC_K_NORMAL
           : metric == OBC_PARAM  ? OBC_K_PARAM
                                  : -1;
}

/* ---- one whole measurement ------------------------------------------- */

/* The stop a measurement runs under: stop_in when it is > 0, else none
 * (+inf: the full measurement; a zeroed record asks for that). */
OBC_FN double obc_stop_of(double stop_in) { return stop_in > 0.0 ? stop_in : OBC_INF; }

/* Purpose: the error of approximation (ha, na) against the exact d-offset of
 * base (hb, nb) under a sampled metric, and the base parameter of its maximum.
 * stop: > 0 to allow the early end above it (see the head of this file);
 * else the full measurement.
 * scratch: 2 OBC_TABLE_SIZE(S) doubles (hausdorff: the sample tables of O
 * and of A).  S >= 2.  *ops: the work done is added (OBC_OPS_*). */
OBC_FN void obc_measure(int metric, const OBC_G double *hb, int nb, const OBC_G double *ha, int na, double d,
                        int S, double stop_in, OBC_G double *scratch, double *err, double *t, long *ops)
{
    const int kind = obc_scan_kind(metric);
    const double stop = obc_stop_of(stop_in);
    (void)kind;
#if OBC_WANT_SCAN
    if (kind >= 0) {
        obc_sample_refine(kind, hb, nb, ha, na, d, S, scratch, scratch, ops, stop, err, t);
        return;
    }
#endif
#if OBC_WANT_HAUSDORFF
    if (metric != OBC_HAUSDORFF) {
#else
    {  /* not a metric of this build */
#endif
        *err = OBC_INF;
        *t = 0.0;
        return;
    }
#if OBC_WANT_HAUSDORFF
    OBC_G double *O = scratch, *A = scratch + OBC_TABLE_SIZE(S);
    obc_fill_table(hb, nb, d, S, O, ops);
    obc_fill_table(ha, na, 0.0, S, A, ops);
    double e1, t1, e2 = -1.0, t2 = 0.0;
    obc_h_side_approx(hb, nb, ha, na, d, S, O, A, ops, stop, &e1, &t1);
    if (!(e1 > stop))
        obc_h_side_offset(hb, nb, ha, na, d, S, A, O, ops, stop, &e2, &t2);
    obc_h_pick(e1, t1, e2, t2, stop, err, t);
#endif
}

#endif
