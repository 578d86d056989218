/*
 * curvefile.c - reading the line-based `.curves` format (see curvefile.h).
 *
 * The text is processed line by line from (pointer, length); it need not be
 * NUL-terminated and may hold any bytes.  Each line is checked (length,
 * binary bytes, UTF-8), copied into a bounded buffer, stripped of its comment
 * and dispatched on its keyword.  Curves are collected in a private list and
 * appended to the set only when the whole text parsed, so a failed parse
 * leaves the set untouched.
 *
 * Limits (beyond the format's own, README "Curve files"), to keep hostile input bounded:
 * lines <= 4096 bytes, |numbers| <= 1e12, <= 10000 control points and
 * <= 1000 offsets per curve, files <= 64 MiB.
 *
 * Scale limits, so that the metrics' double arithmetic (squared distances,
 * products of up to six lengths in the bound metric and the curvature) never
 * underflows and an offset point C + dN differs from C: every coordinate is 0
 * or of magnitude >= 1e-50 (no denormals), every weight and |d| >= 1e-50, and
 * the control polygon of the curve and of each of its Bezier segments spans
 * (largest side of its bounding box) at least 1e-50 and at least 1e-12 times
 * the largest coordinate magnitude M of the curve, which |d| must also reach.
 * A curve below them would be measured as a point: error 0, status ok.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "host/io/curvefile.h"

#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "host/io/strmap.h"
#include "methods/core/bspline.h"
#include "methods/core/grow.h"

enum {
    LINE_MAX_BYTES = 4096,
    MAX_POINTS = 10000,
    MAX_OFFSETS = 1000,
    MAX_IDLEN = 63,
};
#define VALUE_LIMIT 1e12
#define SCALE_MIN 1e-50   /* smallest nonzero coordinate, weight, |d|, extent */
#define SCALE_REL 1e-12   /* smallest extent and |d| relative to the coordinates */
#define FILE_LIMIT ((size_t)64 << 20)

/* A growable array of doubles. */
typedef struct {
    double *v;
    size_t n, cap;
} dvec;

static int dvec_push(dvec *a, double x)
{
    if (ob_grow(&a->v, &a->cap, a->n, sizeof *a->v, 16))
        return -1;
    a->v[a->n++] = x;
    return 0;
}

/* The curve block being read (between `curve` and `end`). */
typedef struct {
    int open, line;           /* inside a block; line of its `curve` */
    char id[MAX_IDLEN + 1];
    char *source, *family;
    int source_line, family_line;
    int kind, deg, deg_line;  /* kind: 0 none, 'z' bezier, 's' bspline */
    dvec knots, pts, offs;    /* pts holds x, y, w triples */
    dvec hpts;                /* the same points as homogeneous w x, w y, w
                                 (exact as given for `hpoint`) */
    int knots_line;
} block;

typedef struct {
    const char *name;
    ob_err *err;
    int line;                 /* current line */
    const ob_curveset *set;
    ob_curve *v;              /* curves parsed so far (not yet in set) */
    int n, cap;
    ob_strmap *ids;           /* id -> index: set->v[i] below set->n, then
                                 v[i - set->n] (a hash look-up per curve, not
                                 a scan of all before it) */
    block b;
    double vals[LINE_MAX_BYTES / 2 + 1]; /* numbers of the current line */
} parser;

/* Writes "NAME:LINE: message" into the error carrier; returns -1. */
static int perr(parser *P, int line, const char *fmt, ...)
{
    char buf[sizeof P->err->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return ob_fail(P->err, "%s:%d: %s", P->name, line, buf);
}

static void block_clear(block *b)
{
    free(b->source);
    free(b->family);
    free(b->knots.v);
    free(b->pts.v);
    free(b->hpts.v);
    free(b->offs.v);
    memset(b, 0, sizeof *b);
}

static int is_space(char c) { return c == ' ' || c == '\t'; }

/* Splits off the next whitespace-separated token of *p (NUL-terminating it
 * in place); NULL when the line is exhausted. */
static char *next_tok(char **p)
{
    char *s = *p;
    while (is_space(*s))
        s++;
    if (!*s) {
        *p = s;
        return NULL;
    }
    char *e = s;
    while (*e && !is_space(*e))
        e++;
    if (*e)
        *e++ = '\0';
    *p = e;
    return s;
}

/* Length of the well-formed UTF-8 sequence at s (n > 0 bytes left), or 0. */
static size_t utf8_len(const unsigned char *s, size_t n)
{
    unsigned c = s[0];
    size_t k = c < 0x80 ? 1 : (c >= 0xC2 && c <= 0xDF) ? 2 : (c >= 0xE0 && c <= 0xEF) ? 3
             : (c >= 0xF0 && c <= 0xF4) ? 4 : 0;
    if (k == 0 || k > n)
        return 0;
    for (size_t i = 1; i < k; i++)
        if ((s[i] & 0xC0) != 0x80)
            return 0;
    /* overlong forms, UTF-16 surrogates, code points above U+10FFFF */
    if ((c == 0xE0 && s[1] < 0xA0) || (c == 0xED && s[1] > 0x9F) ||
        (c == 0xF0 && s[1] < 0x90) || (c == 0xF4 && s[1] > 0x8F))
        return 0;
    return k;
}

/* Id (and family) syntax: 1..63 of letters, digits, '_', '-', '.', '/'. */
static int check_name(parser *P, const char *what, const char *s)
{
    size_t n = strlen(s);
    if (n > MAX_IDLEN)
        return perr(P, P->line, "%s '%.20s...' is longer than %d characters", what, s,
                    (int)MAX_IDLEN);
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-' || c == '.' || c == '/'))
            return perr(P, P->line,
                        "%s '%.63s' has a bad character at position %zu "
                        "(allowed: letters, digits, '_', '-', '.', '/')",
                        what, s, i + 1);
    }
    return 0;
}

/* Parses the numbers left on the line into P->vals.  Returns their count, or
 * -1 (message written) on a bad number, a count outside [min, max], a
 * non-finite value or one beyond +-VALUE_LIMIT. */
static int numbers(parser *P, char *rest, const char *kw, int min, int max)
{
    int n = 0;
    for (char *tok; (tok = next_tok(&rest));) {
        char *end;
        double x = strtod(tok, &end);
        if (end == tok || *end)
            return perr(P, P->line, "'%s': '%.40s' is not a number", kw, tok);
        if (!isfinite(x))
            return perr(P, P->line, "'%s': '%.40s' is not a finite number", kw, tok);
        if (fabs(x) > VALUE_LIMIT)
            return perr(P, P->line, "'%s': %.40s is beyond +-1e12", kw, tok);
        if (n == max)
            return perr(P, P->line, "'%s' takes at most %d numbers", kw, max);
        P->vals[n++] = x;
    }
    if (n < min)
        return perr(P, P->line, "'%s' needs at least %d number%s, got %d", kw, min,
                    min == 1 ? "" : "s", n);
    return n;
}

/* Records id as the next curve's; the curve that already has it, or NULL
 * (*oom set when out of memory). */
static const ob_curve *claim_id(const parser *P, const char *id, int *oom)
{
    const long i = ob_strmap_put(P->ids, id, (long)P->set->n + P->n);
    *oom = i == -2;
    if (i < 0)
        return NULL;
    return i < P->set->n ? &P->set->v[i] : &P->v[i - P->set->n];
}

static int kw_curve(parser *P, char *rest)
{
    block *b = &P->b;
    if (b->open)
        return perr(P, P->line, "'curve' inside curve '%s' (line %d has no 'end')", b->id,
                    b->line);
    char *id = next_tok(&rest);
    if (!id)
        return perr(P, P->line, "'curve' needs an id");
    if (next_tok(&rest))
        return perr(P, P->line, "'curve' takes one id (no spaces)");
    if (check_name(P, "id", id))
        return -1;
    int oom;
    const ob_curve *dup = claim_id(P, id, &oom);
    if (dup)
        return perr(P, P->line, "duplicate id '%s' (first defined at %s:%d)", id, dup->file,
                    dup->line);
    if (oom)
        return perr(P, P->line, "out of memory");
    block_clear(b);
    b->open = 1;
    b->line = P->line;
    memcpy(b->id, id, strlen(id) + 1);
    return 0;
}

/* `bezier DEGREE` (kind 'z') or `bspline DEGREE` (kind 's'). */
static int kw_degree(parser *P, const char *kw, int kind, char *rest)
{
    block *b = &P->b;
    if (b->kind)
        return perr(P, P->line, "second degree line (first at line %d)", b->deg_line);
    char *tok = next_tok(&rest);
    if (!tok)
        return perr(P, P->line, "'%s' needs a degree", kw);
    if (next_tok(&rest))
        return perr(P, P->line, "'%s' takes one degree", kw);
    char *end;
    errno = 0;
    long d = strtol(tok, &end, 10);
    if (end == tok || *end || errno)
        return perr(P, P->line, "'%s': degree '%.40s' is not a valid integer", kw, tok);
    if (d < 1 || d > OB_MAX_IN_DEG)
        return perr(P, P->line, "'%s': degree %ld outside 1..%d", kw, d, (int)OB_MAX_IN_DEG);
    b->kind = kind;
    b->deg = (int)d;
    b->deg_line = P->line;
    return 0;
}

static int kw_knots(parser *P, char *rest)
{
    block *b = &P->b;
    int n = numbers(P, rest, "knots", 1, INT_MAX);
    if (n < 0)
        return -1;
    if (!b->knots_line)
        b->knots_line = P->line;
    for (int i = 0; i < n; i++) {
        double u = P->vals[i];
        /* checked as they come, so the message names the line of the drop */
        if (b->knots.n && u < b->knots.v[b->knots.n - 1])
            return perr(P, P->line, "knots decrease (%.17g after %.17g)", u,
                        b->knots.v[b->knots.n - 1]);
        if (b->knots.n > MAX_POINTS + OB_MAX_IN_DEG + 1)
            return perr(P, P->line, "too many knots");
        if (dvec_push(&b->knots, u))
            return perr(P, P->line, "out of memory");
    }
    return 0;
}

/* `point X Y [W]` (Euclidean, weight W) or, homogeneous = 1, `hpoint WX WY W`
 * (homogeneous coordinates: exact for integers, so that exact rational
 * parameterizations such as (1 - t^2, 2t, 1 + t^2) can be given; the
 * Bézier segment keeps them as written). */
static int kw_point(parser *P, char *rest, int homogeneous)
{
    block *b = &P->b;
    const char *kw = homogeneous ? "hpoint" : "point";
    int n = numbers(P, rest, kw, homogeneous ? 3 : 2, 3);
    if (n < 0)
        return -1;
    double w = n == 3 ? P->vals[2] : 1.0;
    if (!(w > 0))
        return perr(P, P->line, "weight %.17g must be > 0", w);
    if (b->pts.n / 3 >= MAX_POINTS)
        return perr(P, P->line, "more than %d control points", (int)MAX_POINTS);
    const double x = homogeneous ? P->vals[0] / w : P->vals[0], y = homogeneous ? P->vals[1] / w : P->vals[1];
    const double wx = homogeneous ? P->vals[0] : w * x, wy = homogeneous ? P->vals[1] : w * y;
    if (!isfinite(x) || !isfinite(y))
        return perr(P, P->line, "%s: the point is not finite", kw);
    if (w < SCALE_MIN)
        return perr(P, P->line, "%s: weight %.17g is below 1e-50", kw, w);
    for (int c = 0; c < 2; c++) {
        const double v = c ? y : x;
        if (fabs(v) > VALUE_LIMIT)
            return perr(P, P->line, "%s: coordinate %.17g is beyond +-1e12", kw, v);
        if (v != 0 && fabs(v) < SCALE_MIN)
            return perr(P, P->line,
                        "%s: coordinate %.17g is too small (a coordinate is 0 or of magnitude 1e-50 to 1e12)", kw,
                        v);
    }
    if (dvec_push(&b->pts, x) || dvec_push(&b->pts, y) || dvec_push(&b->pts, w) || dvec_push(&b->hpts, wx) ||
        dvec_push(&b->hpts, wy) || dvec_push(&b->hpts, w))
        return perr(P, P->line, "out of memory");
    return 0;
}

int ob_offset_check(double d, double coord_max, char *why, size_t len)
{
    if (d == 0)
        snprintf(why, len, "offset distance 0 (must be != 0)");
    else if (!isfinite(d))
        snprintf(why, len, "offset distance %g is not a finite number", d);
    else if (fabs(d) < SCALE_MIN)
        snprintf(why, len, "offset distance %.17g is too small (|d| must be 1e-50 to 1e12)", d);
    else if (fabs(d) > VALUE_LIMIT)
        snprintf(why, len, "offset distance %.17g is too large (|d| must be 1e-50 to 1e12)", d);
    else if (!(fabs(d) >= SCALE_REL * coord_max))
        snprintf(why, len, "offset %.17g is below 1e-12 times its largest coordinate %.3g", d, coord_max);
    else
        return 0;
    return -1;
}

static int kw_offset(parser *P, char *rest)
{
    block *b = &P->b;
    int n = numbers(P, rest, "offset", 1, INT_MAX);
    if (n < 0)
        return -1;
    char why[200];
    for (int i = 0; i < n; i++) {
        if (ob_offset_check(P->vals[i], 0.0, why, sizeof why) != 0)  /* the scale's part at `end` */
            return perr(P, P->line, "%s", why);
        /* a job is (curve, d, method, tol): the same d twice would be two
         * jobs with one key, which compare and --resume refuse */
        for (size_t k = 0; k < b->offs.n; k++)
            if (b->offs.v[k] == P->vals[i])
                return perr(P, P->line, "offset %.17g given twice (every d of a curve must differ)",
                            P->vals[i]);
        if (b->offs.n >= MAX_OFFSETS)
            return perr(P, P->line, "more than %d offsets", (int)MAX_OFFSETS);
        if (dvec_push(&b->offs, P->vals[i]))
            return perr(P, P->line, "out of memory");
    }
    return 0;
}

/* `source TEXT` (the rest of the line) or, with fam, `family NAME`. */
static int kw_text(parser *P, const char *kw, int fam, char *rest)
{
    block *b = &P->b;
    char **dst = fam ? &b->family : &b->source;
    int *at = fam ? &b->family_line : &b->source_line;
    if (*dst)
        return perr(P, P->line, "second '%s' line (first at line %d)", kw, *at);
    while (is_space(*rest))
        rest++;
    size_t n = strlen(rest);
    while (n && is_space(rest[n - 1]))
        rest[--n] = '\0';
    if (!n)
        return perr(P, P->line, "'%s' needs a value", kw);
    if (fam) {
        char *tok = next_tok(&rest);
        if (next_tok(&rest))
            return perr(P, P->line, "'family' takes one name");
        if (check_name(P, "family", tok))
            return -1;
        rest = tok;
    }
    if (!(*dst = strdup(rest)))
        return perr(P, P->line, "out of memory");
    *at = P->line;
    return 0;
}

/* `end`: checks the block as a whole and turns it into a curve. */
/* The block's kind, points, knots and offsets agree with each other. */
static int check_block_shape(parser *P)
{
    const block *b = &P->b;
    const int L = b->line, npts = (int)(b->pts.n / 3), nk = (int)b->knots.n;
    if (!b->kind)
        return perr(P, L, "curve '%s' has no 'bezier DEGREE' or 'bspline DEGREE' line", b->id);
    if (!npts)
        return perr(P, L, "curve '%s' has no 'point' lines", b->id);
    if (!b->offs.n)
        return perr(P, L, "curve '%s' has no 'offset' line", b->id);
    if (b->kind == 'z') {
        if (nk)
            return perr(P, b->knots_line, "'knots' given for a bezier curve");
        if (npts != b->deg + 1)
            return perr(P, b->deg_line, "bezier of degree %d needs %d points, got %d", b->deg,
                        b->deg + 1, npts);
    } else {
        if (!nk)
            return perr(P, L, "bspline curve '%s' has no 'knots' line", b->id);
        if (npts < b->deg + 1)
            return perr(P, b->deg_line, "bspline of degree %d needs at least %d points, got %d",
                        b->deg, b->deg + 1, npts);
        if (nk != npts + b->deg + 1)
            return perr(P, b->knots_line,
                        "bspline of degree %d with %d points needs %d knots, got %d", b->deg,
                        npts, npts + b->deg + 1, nk);
        if (!(b->knots.v[b->deg] < b->knots.v[npts]))
            return perr(P, b->knots_line, "empty domain: knots[%d] = knots[%d] = %.17g", b->deg,
                        npts, b->knots.v[b->deg]);
    }
    return 0;
}

/* The control polygon moves, spans enough to be measured, and every offset
 * is above round-off; *M: the largest coordinate. */
static int check_block_scale(parser *P, double *M_out)
{
    const block *b = &P->b;
    const int L = b->line, npts = (int)(b->pts.n / 3);
    const double *pt = b->pts.v;
    int moves = 0;
    for (int i = 1; i < npts && !moves; i++)
        moves = pt[3 * i] != pt[0] || pt[3 * i + 1] != pt[1];
    if (!moves)
        return perr(P, L, "curve '%s': all control points coincide (zero-length curve)", b->id);
    double M = 0, lo[2] = {pt[0], pt[1]}, hi[2] = {pt[0], pt[1]};
    for (int i = 0; i < npts; i++)
        for (int c = 0; c < 2; c++) {
            M = fmax(M, fabs(pt[3 * i + c]));
            lo[c] = fmin(lo[c], pt[3 * i + c]);
            hi[c] = fmax(hi[c], pt[3 * i + c]);
        }
    const double E = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(E >= SCALE_MIN) || !(E >= SCALE_REL * M))
        return perr(P, L,
                    "curve '%s': its control polygon spans %.3g, too small to measure (at least 1e-50 and 1e-12 "
                    "times its largest coordinate %.3g)",
                    b->id, E, M);
    char why[200];
    for (size_t k = 0; k < b->offs.n; k++)
        if (ob_offset_check(b->offs.v[k], M, why, sizeof why) != 0)
            return perr(P, L, "curve '%s': %s", b->id, why);
    *M_out = M;
    return 0;
}

/* The block's Bezier segments into c (a B-spline split at its knots, each
 * segment spanning enough to be measured; M: the largest coordinate). */
static int block_segments(parser *P, ob_curve *c, double M)
{
    const block *b = &P->b;
    const int L = b->line, npts = (int)(b->pts.n / 3);
    const double *pt = b->pts.v;
    if (b->kind == 'z') {
        if ((c->seg = calloc(1, sizeof *c->seg))) {
            c->nseg = 1;
            c->seg->deg = b->deg;
            for (int i = 0; i < npts; i++) {
                memcpy(c->seg->h[i], b->hpts.v + 3 * i, sizeof c->seg->h[i]);
                if (c->seg->h[i][2] != 1.0)
                    c->seg->rational = 1;
            }
        }
    } else {
        ob_err why;
        int rc = ob_bspline_to_bezier(b->deg, npts, b->knots.v, (const double(*)[3])pt,
                                      &c->seg, &c->nseg, &why);
        if (rc == -1) /* not expected after the checks above */
            return perr(P, L, "%s", why.msg);
        /* each segment is measured on its own: it must span enough too */
        for (int k = 0; c->seg && k < c->nseg; k++) {
            const ob_bez *sg = &c->seg[k];
            double slo[2] = {0, 0}, shi[2] = {0, 0};
            for (int i = 0; i <= sg->deg; i++)
                for (int q = 0; q < 2; q++) {
                    const double v = sg->h[i][q] / sg->h[i][2];
                    slo[q] = i ? fmin(slo[q], v) : v;
                    shi[q] = i ? fmax(shi[q], v) : v;
                }
            const double se = fmax(shi[0] - slo[0], shi[1] - slo[1]);
            if (!(se >= SCALE_MIN) || !(se >= SCALE_REL * M)) {
                ob_curve_free(c);
                return perr(P, b->knots_line,
                            "curve '%s': its Bezier segment %d spans %.3g, too small to measure (at least 1e-50 "
                            "and 1e-12 times the largest coordinate %.3g)",
                            b->id, k, se, M);
            }
        }
    }
    return 0;
}

static int kw_end(parser *P, char *rest)
{
    block *b = &P->b;
    if (next_tok(&rest))
        return perr(P, P->line, "'end' takes no arguments");
    const int L = b->line;
    double M = 0.0;
    if (check_block_shape(P) || check_block_scale(P, &M))
        return -1;
    if (P->n == P->cap) {
        int cap = P->cap ? 2 * P->cap : 8;
        ob_curve *v = P->cap < INT_MAX / 4 ? realloc(P->v, (size_t)cap * sizeof *v) : NULL;
        if (!v)
            return perr(P, L, "out of memory");
        P->v = v;
        P->cap = cap;
    }
    ob_curve *c = &P->v[P->n];
    memset(c, 0, sizeof *c);
    if (block_segments(P, c, M))
        return -1;
    c->d = malloc(b->offs.n * sizeof *c->d);
    c->source = strdup(b->source ? b->source : "");
    c->family = strdup(b->family ? b->family : OB_DEFAULT_FAMILY);
    if (!c->seg || !c->d || !c->source || !c->family) {
        ob_curve_free(c);
        return perr(P, L, "out of memory");
    }
    memcpy(c->d, b->offs.v, b->offs.n * sizeof *c->d);
    c->nd = (int)b->offs.n;
    memcpy(c->id, b->id, sizeof c->id);
    size_t k = strlen(P->name);
    if (k >= sizeof c->file)
        k = sizeof c->file - 1;
    memcpy(c->file, P->name, k);
    c->file[k] = '\0';
    c->line = L;
    c->coord_max = M;
    P->n++;
    block_clear(b);
    return 0;
}

/* One line, already NUL-terminated and stripped of its comment. */
static int parse_line(parser *P, char *s)
{
    char *kw = next_tok(&s);
    if (!kw)
        return 0;
    enum { CURVE, SOURCE, FAMILY, BEZIER, BSPLINE, KNOTS, POINT, HPOINT, OFFSET, END, NKW };
    static const char *const known[NKW] = {"curve", "source", "family", "bezier", "bspline",
                                           "knots", "point",  "hpoint", "offset", "end"};
    int i = 0;
    while (i < NKW && strcmp(kw, known[i]))
        i++;
    if (i == NKW)
        return perr(P, P->line, "unknown keyword '%.40s'", kw);
    if (i == CURVE)
        return kw_curve(P, s);
    if (!P->b.open)
        return perr(P, P->line, "'%s' outside a curve block (no open 'curve' before it)", kw);
    switch (i) {
    case SOURCE:  return kw_text(P, kw, 0, s);
    case FAMILY:  return kw_text(P, kw, 1, s);
    case BEZIER:  return kw_degree(P, kw, 'z', s);
    case BSPLINE: return kw_degree(P, kw, 's', s);
    case KNOTS:   return kw_knots(P, s);
    case POINT:   return kw_point(P, s, 0);
    case HPOINT:  return kw_point(P, s, 1);
    case OFFSET:  return kw_offset(P, s);
    default:      return kw_end(P, s);
    }
}

static int parse_all(parser *P, const char *text, size_t len)
{
    char line[LINE_MAX_BYTES + 1];
    size_t pos = 0;
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) /* UTF-8 byte order mark */
        pos = 3;
    while (pos < len) {
        if (P->line == INT_MAX)
            return perr(P, P->line, "too many lines");
        P->line++;
        const char *s = text + pos;
        const char *nl = memchr(s, '\n', len - pos);
        size_t n = nl ? (size_t)(nl - s) : len - pos;
        pos += n + (nl != NULL);
        if (n && s[n - 1] == '\r')
            n--;
        if (n > LINE_MAX_BYTES)
            return perr(P, P->line, "line longer than %d bytes", (int)LINE_MAX_BYTES);
        for (size_t i = 0; i < n;) {
            unsigned char c = (unsigned char)s[i];
            size_t k = utf8_len((const unsigned char *)s + i, n - i);
            if ((c < 0x20 && c != '\t') || c == 0x7f)
                return perr(P, P->line, "binary data: control byte 0x%02x at column %zu%s", c,
                            i + 1, c == '\r' ? " (stray carriage return)" : "");
            if (k == 0)
                return perr(P, P->line, "not UTF-8 text: byte 0x%02x at column %zu", c, i + 1);
            i += k;
        }
        memcpy(line, s, n);
        line[n] = '\0';
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        if (parse_line(P, line))
            return -1;
    }
    if (P->b.open)
        return perr(P, P->b.line, "curve '%s' has no 'end'", P->b.id);
    return 0;
}

/* ob_curves_parse with ids, the index of set's ids (claim_id), which
 * gets the ids of the text's curves too (also when it fails: then the
 * caller drops it). */
static int parse_indexed(const char *text, size_t len, const char *name, ob_curveset *set, ob_strmap *ids,
                         ob_err *err)
{
    parser *P = calloc(1, sizeof *P);
    if (!P)
        return ob_fail(err, "%s:0: out of memory", name ? name : "<input>");
    P->name = name ? name : "<input>";
    P->err = err;
    P->set = set;
    P->ids = ids;
    int rc = -1;
    if (!set)
        perr(P, 0, "no curve set given");
    else if (!text && len)
        perr(P, 0, "no text given");
    else if (!parse_all(P, text, len)) {
        rc = 0;
        if (P->n > INT_MAX - set->n) {
            rc = perr(P, P->line, "too many curves");
        } else if (set->n + P->n > set->cap) {
            int cap = set->n + P->n;
            if (cap < INT_MAX / 2)
                cap = cap < 16 ? 16 : 2 * cap;
            ob_curve *v = realloc(set->v, (size_t)cap * sizeof *v);
            if (!v) {
                rc = perr(P, P->line, "out of memory");
            } else {
                set->v = v;
                set->cap = cap;
            }
        }
        if (rc == 0 && P->n) {
            memcpy(set->v + set->n, P->v, (size_t)P->n * sizeof *P->v);
            set->n += P->n;
            P->n = 0; /* now owned by the set */
        }
    }
    for (int i = 0; i < P->n; i++)
        ob_curve_free(&P->v[i]);
    free(P->v);
    block_clear(&P->b);
    free(P);
    return rc;
}

/* The index of the ids of set (claim_id); 0, or -1 out of memory. */
static int index_ids(const ob_curveset *set, ob_strmap *ids)
{
    for (int i = 0; set && i < set->n; i++)
        if (ob_strmap_put(ids, set->v[i].id, i) == -2)
            return -1;
    return 0;
}

int ob_curves_parse(const char *text, size_t len, const char *name,
                    ob_curveset *set, ob_err *err)
{
    ob_strmap ids = {0};
    int rc = index_ids(set, &ids) ? ob_fail(err, "%s:0: out of memory", name ? name : "<input>")
                                  : parse_indexed(text, len, name, set, &ids, err);
    ob_strmap_free(&ids);
    return rc;
}

/* "PATH: message" for errors that are not about a line; returns -1. */
static int ferr(ob_err *err, const char *path, const char *fmt, ...)
{
    char buf[sizeof err->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return ob_fail(err, "%s: %s", path, buf);
}

/* ob_curves_load_file with ids, the index of set's ids (parse_indexed). */
static int load_indexed(const char *path, ob_curveset *set, ob_strmap *ids, ob_err *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return ferr(err, path, "cannot open: %s", strerror(errno));
    struct stat st;
    if (fstat(fileno(f), &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            fclose(f);
            return ferr(err, path, "is a directory");
        }
        if (S_ISREG(st.st_mode) && (unsigned long long)st.st_size > FILE_LIMIT) {
            fclose(f);
            return ferr(err, path, "file too large (%lld bytes; the limit is 64 MiB)",
                        (long long)st.st_size);
        }
    }
    /* read in chunks: the size from fstat is not trusted (pipes, growing files) */
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            /* the buffer stops at LIMIT + 1 bytes: filling it means too large */
            if (cap > FILE_LIMIT) {
                free(buf);
                fclose(f);
                return ferr(err, path, "file too large (the limit is 64 MiB)");
            }
            cap = cap ? 2 * cap : 65536;
            if (cap > FILE_LIMIT + 1)
                cap = FILE_LIMIT + 1;
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(f);
                return ferr(err, path, "out of memory");
            }
            buf = nb;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    int bad = ferror(f);
    int e = errno;
    fclose(f);
    if (bad) {
        free(buf);
        return ferr(err, path, "read error: %s", strerror(e));
    }
    if (n > FILE_LIMIT) {
        free(buf);
        return ferr(err, path, "file too large (the limit is 64 MiB)");
    }
    int rc = parse_indexed(buf, n, path, set, ids, err);
    free(buf);
    return rc;
}

int ob_curves_load_file(const char *path, ob_curveset *set, ob_err *err)
{
    ob_strmap ids = {0};
    int rc = index_ids(set, &ids) ? ferr(err, path, "out of memory") : load_indexed(path, set, &ids, err);
    ob_strmap_free(&ids);
    return rc;
}

static int cmp_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int ob_curves_load_dir(const char *dir, ob_curveset *set, ob_err *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return ferr(err, dir, "cannot open directory: %s", strerror(errno));
    char **names = NULL;
    size_t n = 0, cap = 0;
    int rc = 0;
    struct dirent *de;
    errno = 0;
    while ((de = readdir(d))) {
        size_t k = strlen(de->d_name);
        if (de->d_name[0] == '.' || k <= 7 || strcmp(de->d_name + k - 7, ".curves"))
            continue;
        if (ob_grow(&names, &cap, n, sizeof *names, 16)) {
            rc = ferr(err, dir, "out of memory");
            break;
        }
        if (!(names[n] = strdup(de->d_name))) {
            rc = ferr(err, dir, "out of memory");
            break;
        }
        n++;
        errno = 0;
    }
    if (!rc && errno)
        rc = ferr(err, dir, "cannot read directory: %s", strerror(errno));
    closedir(d);
    if (names)
        qsort(names, n, sizeof *names, cmp_names);

    /* all or nothing: curves of files loaded before a failing one are dropped */
    const int n0 = set ? set->n : 0;
    /* one index of ids for all the files: indexing the set afresh for each
     * would cost files x curves */
    ob_strmap ids = {0};
    if (!rc && index_ids(set, &ids))
        rc = ferr(err, dir, "out of memory");
    size_t dl = strlen(dir);
    int slash = dl && dir[dl - 1] == '/';
    for (size_t i = 0; i < n && !rc; i++) {
        size_t len = dl + 1 + strlen(names[i]) + 1;
        char *path = malloc(len);
        if (!path) {
            rc = ferr(err, dir, "out of memory");
            break;
        }
        snprintf(path, len, "%s%s%s", dir, slash ? "" : "/", names[i]);
        rc = load_indexed(path, set, &ids, err);
        free(path);
    }
    ob_strmap_free(&ids);
    if (rc && set) {
        for (int i = n0; i < set->n; i++)
            ob_curve_free(&set->v[i]);
        set->n = n0;
    }
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
    return rc;
}

void ob_curveset_free(ob_curveset *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->n; i++)
        ob_curve_free(&s->v[i]);
    free(s->v);
    memset(s, 0, sizeof *s);
}

int ob_curveset_find(const ob_curveset *set, const char *id)
{
    if (!set || !id)
        return -1;
    for (int i = 0; i < set->n; i++)
        if (!strcmp(set->v[i].id, id))
            return i;
    return -1;
}
