/*
 * random.c - the random test families (see random.h).
 *
 * Generator: each curve has its own key, splitmix64(splitmix64(SEED + G) ^
 * (i * C + D)); draw k (k = 1, 2, ...) is splitmix64(key + k * G).  So curve i
 * of a seed depends on nothing but (SEED, i), and every redraw below is as
 * deterministic as the first draw.
 *
 * Definitions (all control points in the unit box [0,1]^2; U(a,b) uniform):
 *
 *   Well-conditioned polygon ("generic"): points U(0,1)^2, redrawn until
 *     - every leg |P_k+1 - P_k| >= 0.05 (no coincident consecutive points);
 *     - width >= 0.1, the largest distance of a control point from the line
 *       P_0 P_n (from P_0 if |P_n - P_0| < 0.05): not nearly straight;
 *     - min |C'| >= 0.05 * max |C'| over 65 parameters (no cusp, no stall).
 *   cubic, quintic, septic: generic polynomial curves of degree 3, 5, 7.
 *   rational: degree 2 or 3 (even odds), generic polygon, weights U(0.5, 2)
 *     with max/min weight >= 1.2 (truly rational).
 *   inflection: degree 3 (2/3 of them) or 5, generic, with an inflection
 *     (ob_bez_inflections) in [0.05, 0.95].
 *   tight, loop: generic cubics whose smallest radius of curvature
 *     rmin = 1 / max |kappa| lies in [0.03, 0.5].  With s the sign of kappa
 *     where |kappa| is largest (the concave side there: the centre of
 *     curvature is on the left when kappa > 0), every offset is
 *     d = s * f * rmin, f = U(0.9, 0.99) (tight) or U(1.1, 2) (loop).
 *   degenerate: degree 3 (2/3) or 5, kind (i / 8) mod 3:
 *     coincident  one leg j (uniform) of length 10^U(-8,-6) <= 1e-6, all other
 *                 legs >= 0.05, width >= 0.1;
 *     straight    P_k = A + s_k (B - A) + e_k n, |B - A| >= 0.5, s_0 = 0 <
 *                 s_1 < ... < s_n = 1 with gaps >= 0.05, e_0 = e_n = 0,
 *                 |e_k| = 10^U(-9,-6) <= 1e-6 with random signs (the curve is
 *                 straight to within 1e-6 but has tiny wiggles);
 *     short leg   as coincident with the leg 10^U(-5,-3) long.
 *   Offsets of all but tight and loop: one or two (even odds); the first is
 *   +-U(0.02, 0.25) (random sign), the second U(0.02, 0.25) on the other side,
 *   both rounded to 4 decimals (so they read well in tables).
 *   Tight and loop curves get one or two offsets of their kind.
 *
 * The redraws are bounded (MAX_TRIES = 2000); should all of them fail, a fixed
 * curve with the family's property is used.  Every family accepts at least
 * 38 % of its draws (septic polygons are the rarest), so that takes odds
 * below 0.62^2000 = 1e-415: it does not happen.
 */
#include "host/io/random.h"

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "host/io/strmap.h"

const char *const ob_random_family_names[OB_RND_NFAMILIES] = {
    "cubic", "quintic", "septic", "rational", "inflection", "tight", "loop", "degenerate"};

enum { MAX_TRIES = 2000 };
#define MIN_LEG 0.05
#define MIN_WIDTH 0.1
#define MIN_SPEED_RATIO 0.05
#define RMIN_LO 0.03
#define RMIN_HI 0.5

/* ---- the counter-based generator ------------------------------------------- */

typedef struct {
    uint64_t key, ctr;
} rng;

static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static void rng_init(rng *r, uint64_t seed, long index)
{
    r->key = mix64(mix64(seed + 0x9E3779B97F4A7C15ULL) ^
                   ((uint64_t)index * 0xD1B54A32D192ED03ULL + 0x8CB92BA72F3D8DD7ULL));
    r->ctr = 0;
}

/* Uniform in [0, 1). */
static double rng_u(rng *r)
{
    r->ctr++;
    return (double)(mix64(r->key + r->ctr * 0x9E3779B97F4A7C15ULL) >> 11) * 0x1.0p-53;
}

static double rng_range(rng *r, double a, double b) { return a + (b - a) * rng_u(r); }

/* 0 .. n-1 */
static int rng_int(rng *r, int n)
{
    int k = (int)(rng_u(r) * n);
    return k < n ? k : n - 1;
}

/* ---- checks ------------------------------------------------------------------ */

static double leg(const double (*p)[2], int k) { return hypot(p[k + 1][0] - p[k][0], p[k + 1][1] - p[k][1]); }

/* Legs >= MIN_LEG, except leg `skip` (-1: none). */
static int legs_ok(int n, const double (*p)[2], int skip)
{
    for (int k = 0; k < n; k++)
        if (k != skip && !(leg(p, k) >= MIN_LEG))
            return 0;
    return 1;
}

/* Largest distance of a control point from the line P_0 P_n (from P_0 if the
 * ends are closer than MIN_LEG). */
static double width(int n, const double (*p)[2])
{
    double ux = p[n][0] - p[0][0], uy = p[n][1] - p[0][1], L = hypot(ux, uy), w = 0;
    for (int k = 1; k < n; k++) {
        double vx = p[k][0] - p[0][0], vy = p[k][1] - p[0][1];
        double dk = L >= MIN_LEG ? fabs(ux * vy - uy * vx) / L : hypot(vx, vy);
        if (dk > w)
            w = dk;
    }
    return w;
}

static int speed_ok(const ob_bez *b)
{
    double lo = INFINITY, hi = 0;
    for (int i = 0; i <= 64; i++) {
        double o[2][2];
        ob_bez_eval(b, i / 64.0, 1, o);
        double s = hypot(o[1][0], o[1][1]);
        lo = s < lo ? s : lo;
        hi = s > hi ? s : hi;
    }
    return hi > 0 && lo >= MIN_SPEED_RATIO * hi;
}

static void make_bez(ob_bez *b, int n, const double (*p)[2], const double *w)
{
    memset(b, 0, sizeof *b);
    b->deg = n;
    for (int k = 0; k <= n; k++)
        ob_bez_set(b, k, p[k][0], p[k][1], w ? w[k] : 1.0);
}

/* Draws a generic polygon of degree n (and, with w, weights) into *b. */
static int draw_generic(rng *r, int n, double *w, ob_bez *b)
{
    double p[OB_MAX_DEG + 1][2];
    for (int k = 0; k <= n; k++) {
        p[k][0] = rng_u(r);
        p[k][1] = rng_u(r);
    }
    if (w) {
        double lo = 2, hi = 0;
        for (int k = 0; k <= n; k++) {
            w[k] = rng_range(r, 0.5, 2.0);
            lo = w[k] < lo ? w[k] : lo;
            hi = w[k] > hi ? w[k] : hi;
        }
        if (hi < 1.2 * lo)
            return 0;
    }
    if (!legs_ok(n, (const double (*)[2])p, -1) || width(n, (const double (*)[2])p) < MIN_WIDTH)
        return 0;
    make_bez(b, n, (const double (*)[2])p, w);
    return speed_ok(b);
}

/* Largest |kappa| over [0,1] and the sign of kappa there: a scan at 129
 * parameters, then golden-section search around every local maximum of the
 * scan within a factor 2 of the largest. */
static double max_curvature(const ob_bez *b, int *sign)
{
    enum { S = 128 };
    double k[S + 1];
    double best = 0;
    int ib = 0;
    for (int i = 0; i <= S; i++) {
        k[i] = ob_bez_curvature(b, (double)i / S);
        if (fabs(k[i]) > best) {
            best = fabs(k[i]);
            ib = i;
        }
    }
    int s = k[ib] < 0 ? -1 : 1;
    double top = best;
    for (int i = 0; i <= S; i++) {
        double ai = fabs(k[i]);
        if (ai < 0.5 * best || (i > 0 && fabs(k[i - 1]) > ai) || (i < S && fabs(k[i + 1]) > ai))
            continue;
        double si = k[i] < 0 ? -1.0 : 1.0;
        double a = (double)(i > 0 ? i - 1 : 0) / S, c = (double)(i < S ? i + 1 : S) / S;
        const double g = 0.6180339887498949;
        double x1 = c - g * (c - a), x2 = a + g * (c - a);
        double f1 = si * ob_bez_curvature(b, x1), f2 = si * ob_bez_curvature(b, x2);
        for (int it = 0; it < 48; it++) {
            if (f1 > f2) {
                c = x2;
                x2 = x1;
                f2 = f1;
                x1 = c - g * (c - a);
                f1 = si * ob_bez_curvature(b, x1);
            } else {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + g * (c - a);
                f2 = si * ob_bez_curvature(b, x2);
            }
        }
        double f = f1 > f2 ? f1 : f2;
        if (f > top) {
            top = f;
            s = (int)si;
        }
    }
    *sign = s;
    return top;
}

/* ---- the families -------------------------------------------------------------- */

/* Fallback polygon: points on an arc of radius 0.4 about the box centre,
 * spanning 3 rad (generic for every degree used here). */
static void arc_polygon(int n, double start, double (*p)[2])
{
    for (int k = 0; k <= n; k++) {
        double a = start + 3.0 * k / n;
        p[k][0] = 0.5 + 0.4 * cos(a);
        p[k][1] = 0.5 + 0.4 * sin(a);
    }
}

static void gen_polynomial(rng *r, int n, ob_bez *b)
{
    for (int t = 0; t < MAX_TRIES; t++)
        if (draw_generic(r, n, NULL, b))
            return;
    double p[OB_MAX_DEG + 1][2];
    arc_polygon(n, 0.3, p);
    make_bez(b, n, (const double (*)[2])p, NULL);
}

static void gen_rational(rng *r, ob_bez *b)
{
    int n = rng_u(r) < 0.5 ? 2 : 3;
    double w[OB_MAX_DEG + 1];
    for (int t = 0; t < MAX_TRIES; t++)
        if (draw_generic(r, n, w, b))
            return;
    double p[OB_MAX_DEG + 1][2], wf[4] = {1, 1.5, 0.75, 1};
    arc_polygon(n, 0.3, p);
    make_bez(b, n, (const double (*)[2])p, wf);
}

static int has_inflection(const ob_bez *b)
{
    double ts[2 * OB_MAX_DEG];
    int m = ob_bez_inflections(b, ts, 2 * OB_MAX_DEG);
    for (int i = 0; i < m; i++)
        if (ts[i] >= 0.05 && ts[i] <= 0.95)
            return 1;
    return 0;
}

static void gen_inflection(rng *r, ob_bez *b)
{
    int n = rng_u(r) < 2.0 / 3.0 ? 3 : 5;
    for (int t = 0; t < MAX_TRIES; t++)
        if (draw_generic(r, n, NULL, b) && has_inflection(b))
            return;
    /* an S: symmetric about its midpoint, inflection at t = 0.5 */
    double p[6][2] = {{0.1, 0.2}, {0.35, 0.9}, {0.65, 0.1}, {0.9, 0.8}};
    if (n == 5) {
        double q[6][2] = {{0.1, 0.2}, {0.2, 0.8}, {0.4, 0.95}, {0.6, 0.05}, {0.8, 0.2}, {0.9, 0.8}};
        memcpy(p, q, sizeof p);
    }
    make_bez(b, n, (const double (*)[2])p, NULL);
}

/* A generic cubic with rmin in [RMIN_LO, RMIN_HI]: returns rmin, *s the side. */
static double gen_curved(rng *r, ob_bez *b, int *s)
{
    for (int t = 0; t < MAX_TRIES; t++) {
        if (!draw_generic(r, 3, NULL, b))
            continue;
        double k = max_curvature(b, s);
        if (k > 0 && 1.0 / k >= RMIN_LO && 1.0 / k <= RMIN_HI)
            return 1.0 / k;
    }
    double p[4][2] = {{0.1, 0.1}, {0.9, 0.1}, {0.9, 0.9}, {0.6, 0.5}};
    make_bez(b, 3, (const double (*)[2])p, NULL);
    return 1.0 / max_curvature(b, s);
}

/* A polygon with one tiny leg j of length len in (0, 1e-3], else generic. */
static int draw_short_leg(rng *r, int n, double lo_exp, double hi_exp, ob_bez *b)
{
    double p[OB_MAX_DEG + 1][2];
    for (int k = 0; k <= n; k++) {
        p[k][0] = rng_u(r);
        p[k][1] = rng_u(r);
    }
    int j = rng_int(r, n);
    double len = pow(10.0, rng_range(r, lo_exp, hi_exp)), th = rng_range(r, 0, OB_PI / 2);
    /* toward the box centre, so the point stays in the box */
    p[j + 1][0] = p[j][0] + (p[j][0] < 0.5 ? 1 : -1) * len * cos(th);
    p[j + 1][1] = p[j][1] + (p[j][1] < 0.5 ? 1 : -1) * len * sin(th);
    if (!legs_ok(n, (const double (*)[2])p, j) || width(n, (const double (*)[2])p) < MIN_WIDTH)
        return 0;
    make_bez(b, n, (const double (*)[2])p, NULL);
    return 1;
}

static int draw_straight(rng *r, int n, ob_bez *b)
{
    double A[2] = {rng_range(r, 0.01, 0.99), rng_range(r, 0.01, 0.99)};
    double B[2] = {rng_range(r, 0.01, 0.99), rng_range(r, 0.01, 0.99)};
    double L = hypot(B[0] - A[0], B[1] - A[1]);
    if (L < 0.5)
        return 0;
    double nx = -(B[1] - A[1]) / L, ny = (B[0] - A[0]) / L;
    double s[OB_MAX_DEG + 1];
    s[0] = 0;
    s[n] = 1;
    for (int k = 1; k < n; k++)
        s[k] = (k + rng_range(r, -0.3, 0.3)) / n;
    for (int k = 0; k < n; k++)
        if (s[k + 1] - s[k] < 0.05)
            return 0;
    double p[OB_MAX_DEG + 1][2];
    for (int k = 0; k <= n; k++) {
        double e = 0;
        if (k > 0 && k < n)
            e = (rng_u(r) < 0.5 ? -1 : 1) * pow(10.0, rng_range(r, -9, -6));
        p[k][0] = A[0] + s[k] * (B[0] - A[0]) + e * nx;
        p[k][1] = A[1] + s[k] * (B[1] - A[1]) + e * ny;
    }
    make_bez(b, n, (const double (*)[2])p, NULL);
    return 1;
}

static void gen_degenerate(rng *r, int kind, ob_bez *b)
{
    int n = rng_u(r) < 2.0 / 3.0 ? 3 : 5;
    for (int t = 0; t < MAX_TRIES; t++) {
        int ok = kind == OB_RND_DEGEN_STRAIGHT ? draw_straight(r, n, b)
               : kind == OB_RND_DEGEN_COINCIDENT ? draw_short_leg(r, n, -8, -6, b)
                                                 : draw_short_leg(r, n, -5, -3, b);
        if (ok)
            return;
    }
    double p[OB_MAX_DEG + 1][2];
    arc_polygon(n, 0.3, p);
    if (kind == OB_RND_DEGEN_STRAIGHT)
        for (int k = 0; k <= n; k++) {
            p[k][0] = 0.1 + 0.8 * k / n;
            p[k][1] = 0.5 + (k > 0 && k < n ? 1e-7 : 0);
        }
    else {
        p[1][0] = p[0][0] - (kind == OB_RND_DEGEN_COINCIDENT ? 1e-7 : 1e-4);
        p[1][1] = p[0][1];
    }
    make_bez(b, n, (const double (*)[2])p, NULL);
}

/* ---- public -------------------------------------------------------------------- */

int ob_random_family(long index) { return (int)(index % OB_RND_NFAMILIES); }

int ob_random_degenerate_kind(long index) { return (int)((index / OB_RND_NFAMILIES) % 3); }

void ob_random_id(uint64_t seed, long index, char *buf, size_t len)
{
    snprintf(buf, len, "rnd%" PRIu64 "_%06ld", seed, index);
}

int ob_random_curve(uint64_t seed, long index, ob_curve *c)
{
    memset(c, 0, sizeof *c);
    if (index < 0)
        return -1;
    rng r;
    rng_init(&r, seed, index);
    const int fam = ob_random_family(index);
    ob_bez b;
    double d[2];
    int nd = rng_u(&r) < 0.5 ? 1 : 2;
    if (fam == OB_RND_TIGHT || fam == OB_RND_LOOP) {
        int s;
        double rmin = gen_curved(&r, &b, &s);
        double lo = fam == OB_RND_TIGHT ? 0.9 : 1.1, hi = fam == OB_RND_TIGHT ? 0.99 : 2.0;
        for (int k = 0; k < nd; k++)
            d[k] = s * rng_range(&r, lo, hi) * rmin;
    } else {
        switch (fam) {
        case OB_RND_CUBIC: gen_polynomial(&r, 3, &b); break;
        case OB_RND_QUINTIC: gen_polynomial(&r, 5, &b); break;
        case OB_RND_SEPTIC: gen_polynomial(&r, 7, &b); break;
        case OB_RND_RATIONAL: gen_rational(&r, &b); break;
        case OB_RND_INFLECTION: gen_inflection(&r, &b); break;
        default: gen_degenerate(&r, ob_random_degenerate_kind(index), &b); break;
        }
        d[0] = (rng_u(&r) < 0.5 ? -1 : 1) * round(rng_range(&r, 0.02, 0.25) * 1e4) / 1e4;
        d[1] = (d[0] < 0 ? 1 : -1) * round(rng_range(&r, 0.02, 0.25) * 1e4) / 1e4;
    }
    char src[160];
    snprintf(src, sizeof src, "random family %s, seed %" PRIu64 ", index %ld", ob_random_family_names[fam],
             seed, index);
    c->seg = malloc(sizeof *c->seg);
    c->d = malloc((size_t)nd * sizeof *c->d);
    c->source = strdup(src);
    c->family = strdup(ob_random_family_names[fam]);
    if (!c->seg || !c->d || !c->source || !c->family) {
        ob_curve_free(c);
        return -1;
    }
    *c->seg = b;
    c->nseg = 1;
    memcpy(c->d, d, (size_t)nd * sizeof *d);
    c->nd = nd;
    for (int i = 0; i <= b.deg; i++) {  /* the scale of ob_offset_check */
        double p[2];
        ob_bez_ctrl(&b, i, p);
        c->coord_max = fmax(c->coord_max, fmax(fabs(p[0]), fabs(p[1])));
    }
    ob_random_id(seed, index, c->id, sizeof c->id);
    snprintf(c->file, sizeof c->file, "--random");
    c->line = 0;
    return 0;
}

/* Digits only, no sign, no spaces; 0 or -1. */
static int parse_u64(const char *s, uint64_t *v)
{
    if (!*s)
        return -1;
    for (const char *p = s; *p; p++)
        if (*p < '0' || *p > '9')
            return -1;
    errno = 0;
    char *end;
    unsigned long long x = strtoull(s, &end, 10);
    if (errno || *end)
        return -1;
    *v = (uint64_t)x;
    return 0;
}

int ob_random_id_parse(const char *id, uint64_t *seed, long *index)
{
    char digits[32], canon[64];
    const char *us = strncmp(id, "rnd", 3) == 0 ? strchr(id + 3, '_') : NULL;
    if (!us || (size_t)(us - id - 3) >= sizeof digits)
        return -1;
    memcpy(digits, id + 3, (size_t)(us - id - 3));
    digits[us - id - 3] = '\0';
    const size_t nd = strlen(us + 1);
    if (parse_u64(digits, seed) != 0 || nd == 0 || nd > 9 || strspn(us + 1, "0123456789") != nd)
        return -1;
    *index = strtol(us + 1, NULL, 10);
    ob_random_id(*seed, *index, canon, sizeof canon);
    return strcmp(canon, id) == 0 ? 0 : -1;
}

int ob_random_parse(const char *opt, const char *spec, long *n, uint64_t *seed)
{
    char buf[64];
    uint64_t nv = 0, sv = 1;
    const char *colon = strchr(spec, ':');
    size_t nlen = colon ? (size_t)(colon - spec) : strlen(spec);
    int bad = nlen >= sizeof buf;
    if (!bad) {
        memcpy(buf, spec, nlen);
        buf[nlen] = '\0';
        bad = parse_u64(buf, &nv) != 0 || nv < 1 || nv > (uint64_t)OB_RND_MAX_N;
    }
    if (bad) {
        ob_error("%s: expected N[:SEED] with N a whole number from 1 to %ld, got '%s'", opt,
                 OB_RND_MAX_N, spec);
        return -1;
    }
    if (colon && parse_u64(colon + 1, &sv) != 0) {
        ob_error("%s: SEED must be a whole number from 0 to 18446744073709551615, got '%s'", opt, spec);
        return -1;
    }
    *n = (long)nv;
    *seed = sv;
    return 0;
}

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

/* The indices, ascending and unique, of the ids that name curves of this set. */
static long *selected_indices(uint64_t seed, long n, char *const *ids, int nids, long *count)
{
    long *v = malloc((size_t)(nids > 0 ? nids : 1) * sizeof *v);
    if (!v)
        return NULL;
    long m = 0;
    char prefix[32], canon[64];
    int plen = snprintf(prefix, sizeof prefix, "rnd%" PRIu64 "_", seed);
    for (int i = 0; i < nids; i++) {
        const char *id = ids[i];
        if (strncmp(id, prefix, (size_t)plen) != 0)
            continue;
        const char *p = id + plen;
        if (!*p || strlen(p) > 9 || strspn(p, "0123456789") != strlen(p))
            continue;
        long k = strtol(p, NULL, 10);
        ob_random_id(seed, k, canon, sizeof canon);
        if (k < n && strcmp(canon, id) == 0)
            v[m++] = k;
    }
    qsort(v, (size_t)m, sizeof *v, cmp_long);
    long u = 0;
    for (long i = 0; i < m; i++)
        if (u == 0 || v[u - 1] != v[i])
            v[u++] = v[i];
    *count = u;
    return v;
}

/* Ids must stay unique across everything loaded: 0 when no curve before n0
 * (only those that look like random ids can) has the id of one from n0 on,
 * else -1 with the message.  The new ids go into a hash map, so that a
 * file of n "rnd" ids and n random curves cost n, not n x n. */
static int random_ids_clash(const ob_curveset *set, int n0, ob_err *err)
{
    ob_strmap fresh = {0};
    int rc = 0;
    for (int k = n0; k < set->n && rc == 0; k++)
        if (ob_strmap_put(&fresh, set->v[k].id, k) == -2)
            rc = ob_fail(err, "--random: out of memory");
    for (int i = 0; i < n0 && rc == 0; i++)
        if (strncmp(set->v[i].id, "rnd", 3) == 0 && ob_strmap_get(&fresh, set->v[i].id) >= 0)
            rc = ob_fail(err, "--random: curve id '%s' is also defined at %s:%d", set->v[i].id, set->v[i].file,
                         set->v[i].line);
    ob_strmap_free(&fresh);
    return rc;
}

int ob_random_append(ob_curveset *set, uint64_t seed, long n, char *const *ids, int nids,
                     ob_err *err)
{
    long *sel = NULL, count = n;
    if (nids > 0) {
        sel = selected_indices(seed, n, ids, nids, &count);
        if (!sel) {
            ob_fail(err, "--random: out of memory");
            return -1;
        }
    }
    const int n0 = set->n;
    if (count > INT_MAX - n0 - 1) {
        free(sel);
        ob_fail(err, "--random: too many curves");
        return -1;
    }
    if (n0 + count > set->cap) {
        ob_curve *v = realloc(set->v, (size_t)(n0 + count) * sizeof *v);
        if (!v) {
            free(sel);
            ob_fail(err, "--random: out of memory for %ld curves", count);
            return -1;
        }
        set->v = v;
        set->cap = (int)(n0 + count);
    }
    int failed = 0;
#pragma omp parallel for schedule(static) reduction(| : failed)
    for (long k = 0; k < count; k++)
        failed |= ob_random_curve(seed, sel ? sel[k] : k, &set->v[n0 + k]) != 0;
    free(sel);
    if (failed) {
        for (long k = 0; k < count; k++)
            ob_curve_free(&set->v[n0 + k]);
        ob_fail(err, "--random: out of memory generating %ld curves", count);
        return -1;
    }
    set->n = (int)(n0 + count);
    if (random_ids_clash(set, n0, err) == 0)
        return 0;
    for (long q = 0; q < count; q++)
        ob_curve_free(&set->v[n0 + q]);
    set->n = n0;
    return -1;
}
