/*
 * metric_sampled.c - the sampled metrics radial, normal and hausdorff (CPU
 * reference).  Each samples S parameters t_k = k/(S-1), takes the largest
 * error and refines it by golden-section search between the neighbouring
 * samples; see metric.h for the definitions.
 */
#include "metric.h"

#include <math.h>

/* A curve that can be evaluated with its first derivative: either a Bézier
 * segment (the approximation) or the exact offset of one (d != 0). */
typedef struct {
    const ob_bez *b;
    double d;     /* 0: the segment itself; else its d-offset */
} pcurve;

/* Point P, derivative dP and, when K is not NULL, the curvature vector
 * K = kappa N (signed curvature times unit left normal) of the curve at t.
 * For the exact offset: O' = C' (1 - d kappa) since N' = -kappa C', and
 * kappa_O N_O = kappa / (1 - d kappa) N (the tangent flips where 1 - d kappa < 0). */
static void pc_eval_k(const pcurve *c, double t, double P[2], double dP[2], double K[2])
{
    double o[3][2];
    ob_bez_eval(c->b, t, (c->d != 0.0 || K) ? 2 : 1, o);
    const double sp = sqrt(o[1][0] * o[1][0] + o[1][1] * o[1][1]);
    const double s2 = sqrt(o[2][0] * o[2][0] + o[2][1] * o[2][1]);
    const int regular = sp > 1e-12 * s2 && sp > 0;
    const double kappa = regular ? (o[1][0] * o[2][1] - o[1][1] * o[2][0]) / (sp * sp * sp) : 0.0;
    double N[2] = {0.0, 0.0};
    if (regular) {
        N[0] = -o[1][1] / sp;
        N[1] = o[1][0] / sp;
    } else if (c->d != 0.0) {
        ob_bez_normal(c->b, t, N);  /* the one-sided limit at a cusp */
    }
    if (c->d == 0.0) {
        P[0] = o[0][0], P[1] = o[0][1];
        dP[0] = o[1][0], dP[1] = o[1][1];
        if (K)
            K[0] = kappa * N[0], K[1] = kappa * N[1];
        return;
    }
    const double f = 1.0 - c->d * kappa;
    P[0] = o[0][0] + c->d * N[0];
    P[1] = o[0][1] + c->d * N[1];
    dP[0] = f * o[1][0];
    dP[1] = f * o[1][1];
    if (K) {
        const double ko = f != 0.0 ? kappa / f : 0.0;
        K[0] = ko * N[0], K[1] = ko * N[1];
    }
}

static void pc_eval(const pcurve *c, double t, double P[2], double dP[2])
{
    pc_eval_k(c, t, P, dP, NULL);
}

static double dist(const double a[2], const double b[2])
{
    const double x = a[0] - b[0], y = a[1] - b[1];
    return sqrt(x * x + y * y);
}

static double dist2(const double a[2], const double b[2])
{
    const double x = a[0] - b[0], y = a[1] - b[1];
    return x * x + y * y;
}

static double sample_t(int k, int S) { return (double)k / (S - 1); }

/* Golden-section maximization of f on [a,b]; returns the max, sets *targ. */
typedef double (*errfn)(const void *ctx, double t);
static double golden_max(errfn f, const void *ctx, double a, double b, double *targ)
{
    const double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = f(ctx, x1), f2 = f(ctx, x2);
    for (int it = 0; it < 40 && b - a > 1e-13; it++) {
        if (f1 > f2) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - g * (b - a);
            f1 = f(ctx, x1);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + g * (b - a);
            f2 = f(ctx, x2);
        }
    }
    if (f1 > f2) {
        *targ = x1;
        return f1;
    }
    *targ = x2;
    return f2;
}

/* Sample, pick the largest, refine between the neighbours. */
static void sample_and_refine(errfn f, const void *ctx, int S, ob_errval *out)
{
    double best = -1.0;
    int kb = 0;
    for (int k = 0; k < S; k++) {
        double e = f(ctx, sample_t(k, S));
        if (!(e <= best)) {  /* also takes NaN/inf as worst */
            best = e;
            kb = k;
        }
        if (isnan(e) || isinf(e))
            break;
    }
    out->err = best;
    out->t = sample_t(kb, S);
    if (!isfinite(best)) {
        out->err = INFINITY;
        return;
    }
    double a = sample_t(kb > 0 ? kb - 1 : 0, S), b = sample_t(kb < S - 1 ? kb + 1 : S - 1, S);
    double tr, er = golden_max(f, ctx, a, b, &tr);
    if (er > best) {
        out->err = er;
        out->t = tr;
    }
}

/* ---- radial ------------------------------------------------------------ */

typedef struct {
    const ob_bez *base, *approx;
    double ad;
} radial_ctx;

static double radial_err(const void *vc, double t)
{
    const radial_ctx *c = vc;
    double p[2], q[2];
    ob_bez_point(c->base, t, p);
    ob_bez_point(c->approx, t, q);
    return fabs(dist(q, p) - c->ad);
}

int ob_metric_radial(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    radial_ctx c = {base, approx, fabs(d)};
    sample_and_refine(radial_err, &c, ob_clamp_samples(S), out);
    return 0;
}

/* ---- normal (Zhao-Zhou) -------------------------------------------------- */

typedef struct {
    const ob_bez *base, *approx;
    double d;
    int S;
} normal_ctx;

static double cross2(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }

/* g(u) = (A(u) - P) x N: zero where A meets the normal line through P. */
static double normal_g(const ob_bez *A, double u, const double P[2], const double N[2], double *dg)
{
    double o[2][2];
    ob_bez_eval(A, u, 1, o);
    double r[2] = {o[0][0] - P[0], o[0][1] - P[1]};
    if (dg)
        *dg = cross2(o[1], N);
    return cross2(r, N);
}

static double normal_err(const void *vc, double t)
{
    const normal_ctx *c = vc;
    double P[2], N[2];
    ob_bez_point(c->base, t, P);
    ob_bez_normal(c->base, t, N);
    /* Newton from u = t: the approximations are parameterized close to the base */
    double u = t, g = 0, dg = 0;
    int ok = 0;
    for (int it = 0; it < 30; it++) {
        g = normal_g(c->approx, u, P, N, &dg);
        if (dg == 0.0)
            break;
        double du = g / dg;
        u -= du;
        if (u < -0.5 || u > 1.5 || !isfinite(u))
            break;
        if (fabs(du) < 1e-15) {
            ok = 1;
            break;
        }
    }
    if (ok && !(u < -0.5 || u > 1.5)) {
        /* converged */
    } else {
        /* fall back: the sign change of g nearest to t on the extended parameter
         * range, refined by bisection (the polynomial is extrapolated past [0,1]) */
        const int M = 2 * c->S;
        double best = INFINITY, ub = NAN;
        double u0 = -0.25, g0 = normal_g(c->approx, u0, P, N, NULL);
        for (int j = 1; j <= M; j++) {
            double u1 = -0.25 + 1.5 * j / M, g1 = normal_g(c->approx, u1, P, N, NULL);
            if ((g0 <= 0) != (g1 <= 0)) {
                double lo = u0, hi = u1, glo = g0;
                for (int it = 0; it < 100 && hi - lo > 1e-15; it++) {
                    double mid = 0.5 * (lo + hi), gm = normal_g(c->approx, mid, P, N, NULL);
                    if ((gm <= 0) == (glo <= 0))
                        lo = mid, glo = gm;
                    else
                        hi = mid;
                }
                double r = 0.5 * (lo + hi);
                if (fabs(r - t) < best)
                    best = fabs(r - t), ub = r;
            }
            u0 = u1, g0 = g1;
        }
        if (isnan(ub)) {
            /* A never meets this normal line: report the point mismatch */
            double q[2], O[2] = {P[0] + c->d * N[0], P[1] + c->d * N[1]};
            ob_bez_point(c->approx, t, q);
            return dist(q, O);
        }
        u = ub;
    }
    double q[2];
    ob_bez_point(c->approx, u, q);
    double s = (q[0] - P[0]) * N[0] + (q[1] - P[1]) * N[1];
    return fabs(s - c->d);
}

int ob_metric_normal(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    S = ob_clamp_samples(S);
    normal_ctx c = {base, approx, d, S};
    sample_and_refine(normal_err, &c, S, out);
    return 0;
}

/* ---- hausdorff ------------------------------------------------------------ */

/* Distance from Q to the curve c near parameter t0, within [lo,hi]; *tp gets
 * the foot parameter.  Newton on f(t) = (P - Q).P', whose derivative near the
 * foot is |P'|^2 (1 - K.(Q - P)) with K the curvature vector: quadratic
 * convergence even where the distance is comparable to the radius of
 * curvature.  It has settled when a step is below 1e-8 of the bracket (the
 * distance is then exact to far below that, being quadratic in the parameter
 * error) or stops shrinking (round-off in (P - Q).P' is the floor).  Beyond the
 * centre of curvature (1 - K.(Q - P) small or negative) Newton is not safe;
 * there, and wherever it has not settled after 20 steps, golden-section search
 * on the bracket takes over. */
static double project(const pcurve *c, const double Q[2], double t0, double lo, double hi, double *tp)
{
    double t = t0, P[2], dP[2], K[2];
    pc_eval_k(c, t, P, dP, K);
    double best = dist(Q, P), tb = t;
    int settled = 0;
    double prev = INFINITY;
    for (int it = 0; it < 20 && !settled; it++) {
        const double dd = dP[0] * dP[0] + dP[1] * dP[1];
        const double r[2] = {Q[0] - P[0], Q[1] - P[1]};
        const double den = 1.0 - (K[0] * r[0] + K[1] * r[1]);
        if (dd == 0.0 || !(den > 0.2))
            break;
        const double step = (r[0] * dP[0] + r[1] * dP[1]) / (dd * den);
        const double tn = fmin(hi, fmax(lo, t + step));
        settled = fabs(tn - t) <= 1e-8 * (hi - lo) || fabs(step) >= prev;
        prev = fabs(step);
        if (tn == t)
            break;
        t = tn;
        pc_eval_k(c, t, P, dP, K);
        const double e = dist(Q, P);
        if (e < best) {
            best = e;
            tb = t;
        }
    }
    if (!settled) {
        const double g = 0.6180339887498949;
        double a = lo, b = hi, x1 = b - g * (b - a), x2 = a + g * (b - a);
        pc_eval(c, x1, P, dP);
        double f1 = dist(Q, P);
        pc_eval(c, x2, P, dP);
        double f2 = dist(Q, P);
        for (int it = 0; it < 60 && b - a > 1e-14; it++) {
            if (f1 < f2) {
                b = x2, x2 = x1, f2 = f1;
                x1 = b - g * (b - a);
                pc_eval(c, x1, P, dP);
                f1 = dist(Q, P);
            } else {
                a = x1, x1 = x2, f1 = f2;
                x2 = a + g * (b - a);
                pc_eval(c, x2, P, dP);
                f2 = dist(Q, P);
            }
        }
        double fm = f1 < f2 ? f1 : f2, xm = f1 < f2 ? x1 : x2;
        if (fm < best) {
            best = fm;
            tb = xm;
        }
    }
    *tp = tb;
    return best;
}

typedef struct {
    pcurve from, to;      /* distances from points of `from` to the curve `to` */
    const double (*tp)[2];/* samples of `to` */
    int S;
    int from_is_offset;   /* report base parameters: of `from` or of the foot */
} hside;

/* Nearest sample of `to` to Q: coarse global scan, then local descent
 * (squared distances: only their order matters). */
static int nearest_sample(const hside *h, const double Q[2])
{
    const int S = h->S, stride = 4;
    int jb = 0;
    double db = INFINITY;
    for (int j = 0; j < S; j += stride) {
        double e = dist2(Q, h->tp[j]);
        if (e < db)
            db = e, jb = j;
    }
    for (;;) {
        int moved = 0;
        for (int s = -1; s <= 1; s += 2) {
            int j = jb + s;
            if (j < 0 || j >= S)
                continue;
            double e = dist2(Q, h->tp[j]);
            if (e < db)
                db = e, jb = j, moved = 1;
        }
        if (!moved)
            break;
    }
    return jb;
}

static double side_dist(const hside *h, double u, double *tfoot)
{
    double Q[2], dQ[2];
    pc_eval(&h->from, u, Q, dQ);
    int j = nearest_sample(h, Q);
    double lo = sample_t(j > 0 ? j - 1 : 0, h->S), hi = sample_t(j < h->S - 1 ? j + 1 : h->S - 1, h->S);
    return project(&h->to, Q, sample_t(j, h->S), lo, hi, tfoot);
}

static double side_err(const void *vc, double u)
{
    double tf;
    return side_dist(vc, u, &tf);
}

static void one_side(const hside *h, ob_errval *out)
{
    sample_and_refine(side_err, h, h->S, out);
    if (!h->from_is_offset) {  /* convert the approximation's parameter to the base's */
        double tf;
        side_dist(h, out->t, &tf);
        out->t = tf;
    }
}

int ob_metric_hausdorff(const ob_bez *base, const ob_bez *approx, double d, int S, ob_errval *out)
{
    S = ob_clamp_samples(S);
    double O[OB_MAX_SAMPLES][2], A[OB_MAX_SAMPLES][2], dummy[2];
    pcurve off = {base, d}, app = {approx, 0.0};
    for (int k = 0; k < S; k++) {
        pc_eval(&off, sample_t(k, S), O[k], dummy);
        pc_eval(&app, sample_t(k, S), A[k], dummy);
    }
    hside s1 = {app, off, (const double (*)[2])O, S, 0};
    hside s2 = {off, app, (const double (*)[2])A, S, 1};
    ob_errval e1, e2;
    one_side(&s1, &e1);
    one_side(&s2, &e2);
    *out = e1.err >= e2.err ? e1 : e2;
    return 0;
}
