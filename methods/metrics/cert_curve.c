/*
 * cert_curve.c - interval enclosures of a Bézier segment or of its exact
 * offset, and of their derivatives (see cert_curve.h).
 */
#include "methods/metrics/cert_curve.h"

enum { MAXK = 4 };  /* highest derivative ever needed (O''' needs C'''') */

typedef ob_iv hpt[3];  /* homogeneous derivatives (w x, w y, w) */

/* The homogeneous coordinates that carry information: a polynomial
 * segment's weights are all 1 and never read (euclid). */
static int ncoords(const ob_bez *b) { return b->rational ? 3 : 2; }

/* (1 - t) a + t b.  The convex form, not a + t (b - a): with t in [0, 1]
 * both weights are >= 0, so the result is no wider than a and b (plus
 * rounding), where a + t (b - a) adds t (|a| + |b|) of width at each level
 * and a de Casteljau of degree n near t = 1 grows the width ~3^n. */
static ob_iv lerp(ob_iv a, ob_iv b, ob_iv t, ob_iv omt) { return ob_iv_add(ob_iv_mul(omt, a), ob_iv_mul(t, b)); }

/* q[0..m] becomes the piece over [0, t] (q[j]: level j's first point). */
static void split_left(ob_iv *q, int m, ob_iv t)
{
    const ob_iv omt = ob_iv_sub(ob_iv_pt(1.0), t);
    for (int r = 1; r <= m; r++)
        for (int i = m; i >= r; i--)
            q[i] = lerp(q[i - 1], q[i], t, omt);
}

/* q[0..m] becomes the piece over [t, 1] (q[j]: level m - j's last point). */
static void split_right(ob_iv *q, int m, ob_iv t)
{
    const ob_iv omt = ob_iv_sub(ob_iv_pt(1.0), t);
    for (int r = 1; r <= m; r++)
        for (int i = 0; i <= m - r; i++)
            q[i] = lerp(q[i], q[i + 1], t, omt);
}

/* n (n - 1) ... (n - k + 1) */
static double falling(int n, int k)
{
    double f = 1.0;
    for (int j = 0; j < k; j++)
        f *= n - j;
    return f;
}

/* The Bernstein coefficients D[0..n-k] of the k-th derivative of
 * coordinate c: falling(n, k) times the k-th differences of the control
 * points.  Returns the degree n - k, or -1 (the zero polynomial) if k > n.
 * Why difference first and subdivide after (the hodograph): differences of
 * nearby control points are exact or nearly so, and subdividing them keeps
 * the rounding relative to the derivative's own size; differencing the
 * subdivided points instead carries their rounding eps |P|, divided by the
 * interval's width^k, which for a short piece (a leg of 1e-7) is larger
 * than the derivative itself. */
static int hodograph(const ob_bez *b, int k, int c, ob_iv *D)
{
    const int n = b->deg;
    if (k > n)
        return -1;
    for (int i = 0; i <= n; i++)
        D[i] = ob_iv_pt(b->h[i][c]);
    for (int l = 1; l <= k; l++)
        for (int i = 0; i + l <= n; i++)
            D[i] = ob_iv_sub(D[i + 1], D[i]);
    for (int i = 0; i <= n - k; i++)
        D[i] = ob_iv_scale(D[i], falling(n, k));
    return n - k;
}

/* Hodograph k of coordinate c into D: from the cache hd where there is one
 * (ob_cv_hodo_attach), else computed; its degree, or -1. */
static int hodo_get(const ob_bez *b, const ob_cv_hodo *hd, int k, int c, ob_iv *D)
{
    if (!hd || k > OB_CV_MAXK)
        return hodograph(b, k, c, D);
    const int m = hd->deg[k];
    for (int i = 0; i <= m; i++)
        D[i] = hd->D[k][c][i];
    return m;
}

void ob_cv_hodo_attach(ob_cv *c, ob_cv_hodo *h)
{
    const ob_bez *b = c->src ? c->src : c->b;
    for (int k = 0; k <= OB_CV_MAXK; k++) {
        h->deg[k] = k > b->deg ? -1 : b->deg - k;
        for (int i = 0; i < 3 && h->deg[k] >= 0; i++)
            hodograph(b, k, i, h->D[k][i]);
    }
    c->hodo = h;
}

/* Homogeneous derivatives k0..K at the parameter T (a point, or the few
 * ulps a mapped parameter is known to): de Casteljau on each hodograph; the
 * others are left 0. */
static void hjet_point(const ob_bez *b, const ob_cv_hodo *hd, ob_iv T, int k0, int K, hpt *H)
{
    const int nc = ncoords(b);
    const ob_iv omt = ob_iv_sub(ob_iv_pt(1.0), T);
    for (int k = 0; k <= K; k++)
        for (int c = 0; c < 3; c++) {
            H[k][c] = ob_iv_pt(0.0);
            ob_iv D[OB_MAX_DEG + 1];
            const int m = k >= k0 && c < nc ? hodo_get(b, hd, k, c, D) : -1;
            if (m < 0)
                continue;
            for (int r = 1; r <= m; r++)
                for (int i = 0; i <= m - r; i++)
                    D[i] = lerp(D[i], D[i + 1], T, omt);
            H[k][c] = D[0];
        }
}

/* Homogeneous derivatives k0..K enclosed over [t0, t1] (t0 < t1): each
 * hodograph cut to [t0, t1] (at t1, then at t0 / t1, a ratio carried as an
 * interval, so the cut is of the exact [t0, t1]) and the hull of its
 * coefficients (the Bernstein convex-hull property); the others are 0. */
static void hjet_range(const ob_bez *b, const ob_cv_hodo *hd, double t0, double t1, int k0, int K, hpt *H)
{
    const int nc = ncoords(b);
    const ob_iv ratio = ob_iv_div(ob_iv_pt(t0), ob_iv_pt(t1));
    for (int k = 0; k <= K; k++)
        for (int c = 0; c < 3; c++) {
            H[k][c] = ob_iv_pt(0.0);
            ob_iv D[OB_MAX_DEG + 1];
            const int m = k >= k0 && c < nc ? hodo_get(b, hd, k, c, D) : -1;
            if (m < 0)
                continue;
            if (t1 < 1.0)
                split_left(D, m, ob_iv_pt(t1));
            if (t0 > 0.0)
                split_right(D, m, ratio);
            ob_iv h = D[0];
            for (int i = 1; i <= m; i++)
                h = ob_iv_hull(h, D[i]);
            H[k][c] = h;
        }
}

/* Euclidean derivatives 0..K from homogeneous ones: E_k = (X_k - sum_{i=1..k}
 * C(k,i) W_i E_{k-i}) / W (Leibniz on X = W E). */
static int euclid(const ob_bez *b, const hpt *H, int K, ob_iv E[][2])
{
    static const double binom[MAXK + 1][MAXK + 1] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}};
    for (int k = 0; k <= K; k++)
        for (int c = 0; c < 2; c++) {
            ob_iv x = H[k][c];
            if (b->rational) {
                for (int i = 1; i <= k; i++)
                    x = ob_iv_sub(x, ob_iv_mul(ob_iv_scale(H[i][2], binom[k][i]), E[k - i][c]));
                x = ob_iv_div(x, H[0][2]);
            }
            if (ob_iv_bad(x))
                return -1;
            E[k][c] = x;
        }
    return 0;
}

static ob_iv cross(const ob_iv a[2], const ob_iv b[2]) { return ob_iv_sub(ob_iv_mul(a[0], b[1]), ob_iv_mul(a[1], b[0])); }
static ob_iv dot(const ob_iv a[2], const ob_iv b[2]) { return ob_iv_add(ob_iv_mul(a[0], b[0]), ob_iv_mul(a[1], b[1])); }

/* kappa'' times |C'|^7: (num' |C'|^2 - 5 num q), with num = kappa' |C'|^5 =
 * (C' x C''') |C'|^2 - 3 (C' x C'') q, q = C' . C'', and its derivative
 * num' = (C'' x C''' + C' x C'''') |C'|^2 - (C' x C''') q
 *        - 3 (C' x C'') (|C''|^2 + C' . C''')
 * (d/dt |C'|^2 = 2 q, d/dt (C' x C'') = C' x C''', d/dt q = |C''|^2 + C' . C''').
 * Only the third derivative of the offset needs it. */
static ob_iv kappa2_num(const ob_iv E[][2], ob_iv s2, ob_iv cr, ob_iv q, ob_iv num)
{
    const ob_iv x13 = cross(E[1], E[3]);
    const ob_iv dnum = ob_iv_sub(ob_iv_sub(ob_iv_mul(ob_iv_add(cross(E[2], E[3]), cross(E[1], E[4])), s2),
                                           ob_iv_mul(x13, q)),
                                 ob_iv_scale(ob_iv_mul(cr, ob_iv_add(dot(E[2], E[2]), dot(E[1], E[3]))), 3.0));
    return ob_iv_sub(ob_iv_mul(dnum, s2), ob_iv_scale(ob_iv_mul(num, q), 5.0));
}

/* The offset's derivative k (0..3) from the base's Euclidean jet E[0..k+1]
 * (the Frenet formulas of cert_curve.h; the third differentiates the second
 * once more: O''' = C''' (1 - d kappa) - 2 d kappa' C'' - d kappa'' C'). */
static int offset_jet(const ob_iv E[][2], double d, int k, ob_iv out[2])
{
    const ob_iv s2 = ob_iv_add(ob_iv_sqr(E[1][0]), ob_iv_sqr(E[1][1]));
    if (!(s2.lo > 0) || ob_iv_bad(s2))
        return -1;
    const ob_iv sp = ob_iv_sqrt(s2), D = ob_iv_pt(d);
    if (k == 0) {
        out[0] = ob_iv_sub(E[0][0], ob_iv_div(ob_iv_mul(D, E[1][1]), sp));
        out[1] = ob_iv_add(E[0][1], ob_iv_div(ob_iv_mul(D, E[1][0]), sp));
    } else {
        const ob_iv cr = cross(E[1], E[2]);
        const ob_iv f = ob_iv_sub(ob_iv_pt(1.0), ob_iv_mul(D, ob_iv_div(cr, ob_iv_mul(s2, sp))));
        if (k == 1) {
            out[0] = ob_iv_mul(E[1][0], f);
            out[1] = ob_iv_mul(E[1][1], f);
        } else {
            const ob_iv q = dot(E[1], E[2]);
            const ob_iv num = ob_iv_sub(ob_iv_mul(cross(E[1], E[3]), s2), ob_iv_scale(ob_iv_mul(cr, q), 3.0));
            const ob_iv s4 = ob_iv_sqr(s2);
            const ob_iv dk = ob_iv_mul(D, ob_iv_div(num, ob_iv_mul(s4, sp)));  /* d kappa' */
            if (k == 2) {
                for (int c = 0; c < 2; c++)
                    out[c] = ob_iv_sub(ob_iv_mul(E[2][c], f), ob_iv_mul(dk, E[1][c]));
            } else {
                const ob_iv dkk = ob_iv_mul(D, ob_iv_div(kappa2_num(E, s2, cr, q, num),
                                                         ob_iv_mul(ob_iv_mul(s4, s2), sp)));  /* d kappa'' */
                for (int c = 0; c < 2; c++)
                    out[c] = ob_iv_sub(ob_iv_sub(ob_iv_mul(E[3][c], f), ob_iv_scale(ob_iv_mul(dk, E[2][c]), 2.0)),
                                       ob_iv_mul(dkk, E[1][c]));
            }
        }
    }
    return ob_iv_bad(out[0]) || ob_iv_bad(out[1]) ? -1 : 0;
}

/* The curve the enclosures read: the stored segment where there is one. */
static const ob_bez *stored(const ob_cv *c) { return c->src ? c->src : c->b; }

/* The parameter of the curve the enclosures read, at the piece's t0 (and
 * t1 >= t0): [t0, t1] itself, or the stored segment's u0 + du [t0, t1],
 * rounded outward and kept in [0, 1] (the exact range is inside it). */
static ob_iv src_range(const ob_cv *c, double t0, double t1)
{
    if (!c->src)
        return (ob_iv){t0, t1};
    const ob_iv lo = ob_iv_add(c->u0, ob_iv_mul(c->du, ob_iv_pt(t0)));
    const ob_iv hi = t1 == t0 ? lo : ob_iv_add(c->u0, ob_iv_mul(c->du, ob_iv_pt(t1)));
    return (ob_iv){fmin(fmax(lo.lo, 0.0), 1.0), fmin(fmax(hi.hi, 0.0), 1.0)};
}

/* The curve's homogeneous jet 0..K (k0..K read) at or over the piece's
 * [t0, t1], in the piece's parameter: read from the stored segment, the
 * k-th derivative is du^k times the segment's (u = u0 + du t). */
static void hjet(const ob_cv *c, double t0, double t1, int k0, int K, hpt *H)
{
    const ob_bez *b = stored(c);
    const ob_iv U = src_range(c, t0, t1);
    if (t0 == t1)
        hjet_point(b, c->hodo, U, k0, K, H);
    else
        hjet_range(b, c->hodo, U.lo, U.hi, k0, K, H);
    ob_iv f = ob_iv_pt(1.0);
    for (int k = 1; k <= K && c->src; k++) {
        f = ob_iv_mul(f, c->du);
        for (int i = 0; i < 3; i++)
            H[k][i] = ob_iv_mul(H[k][i], f);
    }
}

int ob_cv_from_src(ob_cv *c, const ob_bez *piece, const ob_cert_src *src, double d, int offset)
{
    *c = (ob_cv){piece, d, offset, NULL, {0, 0}, {0, 0}, NULL};
    if (!src)
        return 0;
    if (!src->seg || !(0.0 <= src->a && src->a < src->b && src->b <= 1.0 && 0.0 <= src->t0 && src->t0 < src->t1 &&
                       src->t1 <= 1.0))
        return -1;
    const ob_iv w = ob_iv_sub(ob_iv_pt(src->b), ob_iv_pt(src->a));
    c->src = src->seg;
    c->u0 = ob_iv_add(ob_iv_pt(src->a), ob_iv_mul(w, ob_iv_pt(src->t0)));
    c->du = ob_iv_mul(w, ob_iv_sub(ob_iv_pt(src->t1), ob_iv_pt(src->t0)));
    return 0;
}

int ob_cv_point(const ob_cv *c, double t, ob_iv p[2], ob_iv d1[2])
{
    hpt H[MAXK + 1];
    ob_iv E[MAXK + 1][2];
    const int K = c->offset ? 2 : 1;
    hjet(c, t, t, 0, K, H);
    if (euclid(stored(c), H, K, E))
        return -1;
    if (!c->offset) {
        p[0] = E[0][0], p[1] = E[0][1], d1[0] = E[1][0], d1[1] = E[1][1];
        return 0;
    }
    return offset_jet(E, c->d, 0, p) || offset_jet(E, c->d, 1, d1) ? -1 : 0;
}

int ob_cv_point2(const ob_cv *c, double t, ob_iv p[2], ob_iv d1[2], ob_iv d2[2])
{
    hpt H[MAXK + 1];
    ob_iv E[MAXK + 1][2];
    const int K = c->offset ? 3 : 2;
    hjet(c, t, t, 0, K, H);
    if (euclid(stored(c), H, K, E))
        return -1;
    if (!c->offset) {
        for (int i = 0; i < 2; i++)
            p[i] = E[0][i], d1[i] = E[1][i], d2[i] = E[2][i];
        return 0;
    }
    return offset_jet(E, c->d, 0, p) || offset_jet(E, c->d, 1, d1) || offset_jet(E, c->d, 2, d2) ? -1 : 0;
}

int ob_cv_range_n(const ob_cv *c, double t0, double t1, int k1, int k2, ob_iv out[][2])
{
    hpt H[MAXK + 1];
    ob_iv E[MAXK + 1][2];
    if (!(t0 <= t1) || k1 < 1 || k2 < k1 || k2 > 3)
        return -1;
    const int K = c->offset ? k2 + 1 : k2;
    /* the orders read: a rational segment's quotient rule needs them all,
     * a polynomial's offset C' .. C^(k2+1), a polynomial its k1-th .. k2-th */
    const int k0 = stored(c)->rational ? 0 : c->offset ? 1 : k1;
    hjet(c, t0, t1, k0, K, H);
    if (euclid(stored(c), H, K, E))
        return -1;
    for (int k = k1; k <= k2; k++) {
        if (!c->offset)
            out[k - k1][0] = E[k][0], out[k - k1][1] = E[k][1];
        else if (offset_jet(E, c->d, k, out[k - k1]))
            return -1;
    }
    return 0;
}

int ob_cv_range(const ob_cv *c, double t0, double t1, int k, ob_iv out[2])
{
    return ob_cv_range_n(c, t0, t1, k, k, (ob_iv (*)[2])out);
}
