/*
 * cert_curve.c - interval enclosures of a Bézier segment or of its exact
 * offset, and of their derivatives (see cert_curve.h).
 */
#include "methods/metrics/cert_curve.h"

enum { MAXK = 3 };  /* highest derivative ever needed (O'' needs C''') */

/* Derivative ranges are taken over at least this width: the subsegment's
 * k-th differences carry a rounding of eps |P| that the range divides by
 * width^k, so over a narrower interval the enclosure widens again (for the
 * offset's second derivative, eps / w^3 against |C''''| w: balanced near
 * w = 1e-4). */
#define RANGE_MIN_WIDTH 0x1p-14

typedef ob_iv hpt[3];  /* homogeneous point (w x, w y, w) */

static void load(const ob_bez *b, hpt *q)
{
    for (int i = 0; i <= b->deg; i++)
        for (int c = 0; c < 3; c++)
            q[i][c] = ob_iv_pt(b->h[i][c]);
}

static ob_iv lerp(ob_iv a, ob_iv b, ob_iv t) { return ob_iv_add(a, ob_iv_mul(t, ob_iv_sub(b, a))); }

/* The homogeneous coordinates that carry information: a polynomial
 * segment's weights are all 1 and never read (euclid). */
static int ncoords(const ob_bez *b) { return b->rational ? 3 : 2; }

/* q becomes the piece over [0, t] (descending in place: q[j] is level j's first point);
 * coordinates 0 .. nc - 1. */
static void split_left(hpt *q, int n, int nc, ob_iv t)
{
    for (int r = 1; r <= n; r++)
        for (int i = n; i >= r; i--)
            for (int c = 0; c < nc; c++)
                q[i][c] = lerp(q[i - 1][c], q[i][c], t);
}

/* q becomes the piece over [t, 1] (ascending in place: q[j] is level n - j's last point). */
static void split_right(hpt *q, int n, int nc, ob_iv t)
{
    for (int r = 1; r <= n; r++)
        for (int i = 0; i <= n - r; i++)
            for (int c = 0; c < nc; c++)
                q[i][c] = lerp(q[i][c], q[i + 1][c], t);
}

/* k-th forward difference of q[i .. i + k], coordinate c (k <= MAXK). */
static ob_iv diff(const hpt *q, int i, int k, int c)
{
    if (k == 0)
        return q[i][c];
    return ob_iv_sub(diff(q, i + 1, k - 1, c), diff(q, i, k - 1, c));
}

/* n (n - 1) ... (n - k + 1) */
static double falling(int n, int k)
{
    double f = 1.0;
    for (int j = 0; j < k; j++)
        f *= n - j;
    return f;
}

/* Homogeneous derivatives 0..K at the point t: level n - k of de Casteljau
 * holds the k-th derivative as falling(n, k) times its k-th difference. */
static void hjet_point(const ob_bez *b, double t, int K, hpt *H)
{
    const int n = b->deg, nc = ncoords(b);
    hpt q[OB_MAX_DEG + 1];
    load(b, q);
    for (int k = 0; k <= K; k++)
        for (int c = 0; c < 3; c++)
            H[k][c] = ob_iv_pt(0.0);
    for (int r = 0; r <= n; r++) {
        if (r > 0)
            for (int i = 0; i <= n - r; i++)
                for (int c = 0; c < nc; c++)
                    q[i][c] = lerp(q[i][c], q[i + 1][c], ob_iv_pt(t));
        const int k = n - r;
        if (k <= K)
            for (int c = 0; c < nc; c++)
                H[k][c] = ob_iv_scale(diff(q, 0, k, c), falling(n, k));
    }
}

/* Homogeneous derivatives 0..K enclosed over [t0, t1]: hulls of the
 * subsegment's scaled differences. */
static void hjet_range(const ob_bez *b, double t0, double t1, int K, hpt *H)
{
    const int n = b->deg, nc = ncoords(b);
    hpt q[OB_MAX_DEG + 1];
    load(b, q);
    if (t1 < 1.0)
        split_left(q, n, nc, ob_iv_pt(t1));
    if (t0 > 0.0)
        split_right(q, n, nc, ob_iv_div(ob_iv_pt(t0), ob_iv_pt(t1)));
    const ob_iv len = ob_iv_sub(ob_iv_pt(t1), ob_iv_pt(t0));
    ob_iv scale[MAXK + 1];
    scale[0] = ob_iv_pt(1.0);
    for (int k = 1; k <= K; k++)
        scale[k] = ob_iv_div(scale[k - 1], len);
    for (int k = 0; k <= K; k++)
        H[k][2] = ob_iv_pt(0.0);  /* unread unless rational */
    for (int c = 0; c < nc; c++) {
        /* the difference table, level k in place: D[i] = diff(q, i, k, c),
         * the same operations as diff() without its recomputation */
        ob_iv D[OB_MAX_DEG + 1];
        for (int i = 0; i <= n; i++)
            D[i] = q[i][c];
        for (int k = 0; k <= K; k++) {
            if (k > n) {
                H[k][c] = ob_iv_pt(0.0);
                continue;
            }
            if (k > 0)
                for (int i = 0; i + k <= n; i++)
                    D[i] = ob_iv_sub(D[i + 1], D[i]);
            ob_iv h = D[0];
            for (int i = 1; i + k <= n; i++)
                h = ob_iv_hull(h, D[i]);
            H[k][c] = ob_iv_mul(ob_iv_scale(h, falling(n, k)), scale[k]);
        }
    }
}

/* Euclidean derivatives 0..K from homogeneous ones: E_k = (X_k - sum_{i=1..k}
 * C(k,i) W_i E_{k-i}) / W (Leibniz on X = W E). */
static int euclid(const ob_bez *b, const hpt *H, int K, ob_iv E[][2])
{
    static const double binom[MAXK + 1][MAXK + 1] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}};
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

/* The offset's derivative k (0..2) from the base's Euclidean jet E[0..k+1]. */
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
            const ob_iv num = ob_iv_sub(ob_iv_mul(cross(E[1], E[3]), s2),
                                        ob_iv_scale(ob_iv_mul(cr, dot(E[1], E[2])), 3.0));
            const ob_iv dk = ob_iv_mul(D, ob_iv_div(num, ob_iv_mul(ob_iv_sqr(s2), sp)));
            for (int c = 0; c < 2; c++)
                out[c] = ob_iv_sub(ob_iv_mul(E[2][c], f), ob_iv_mul(dk, E[1][c]));
        }
    }
    return ob_iv_bad(out[0]) || ob_iv_bad(out[1]) ? -1 : 0;
}

int ob_cv_point(const ob_cv *c, double t, ob_iv p[2], ob_iv d1[2])
{
    hpt H[MAXK + 1];
    ob_iv E[MAXK + 1][2];
    const int K = c->offset ? 2 : 1;
    hjet_point(c->b, t, K, H);
    if (euclid(c->b, H, K, E))
        return -1;
    if (!c->offset) {
        p[0] = E[0][0], p[1] = E[0][1], d1[0] = E[1][0], d1[1] = E[1][1];
        return 0;
    }
    return offset_jet(E, c->d, 0, p) || offset_jet(E, c->d, 1, d1) ? -1 : 0;
}

int ob_cv_range(const ob_cv *c, double t0, double t1, int k, ob_iv out[2])
{
    hpt H[MAXK + 1];
    ob_iv E[MAXK + 1][2];
    const int K = c->offset ? k + 1 : k;
    if (!(t0 <= t1) || k < 1 || k > 2)
        return -1;
    if (t0 < t1 && t1 - t0 < RANGE_MIN_WIDTH) {  /* a wider interval's enclosure holds */
        const double m = 0.5 * (t0 + t1);
        t0 = fmax(0.0, fmin(m - 0.5 * RANGE_MIN_WIDTH, 1.0 - RANGE_MIN_WIDTH));
        t1 = t0 + RANGE_MIN_WIDTH;
    }
    if (t0 == t1)
        hjet_point(c->b, t0, K, H);
    else
        hjet_range(c->b, t0, t1, K, H);
    if (euclid(c->b, H, K, E))
        return -1;
    if (!c->offset) {
        out[0] = E[k][0], out[1] = E[k][1];
        return 0;
    }
    return offset_jet(E, c->d, k, out);
}
