/*
 * approx_read_svg.c - the paths of an SVG file as Bézier pieces for
 * `measure` (approx_read.h), by the rules scripts/svg2curves.py follows
 * with its defaults (--y up, --units user), docs/export-measure.md
 * "Reading SVG".  The XML is read by libexpat (comments, CDATA, entity and
 * character references, attribute values holding '>' or another
 * attribute's text: all as XML says); this file walks its elements:
 *   - every <path>, <line>, <polyline>, <polygon>, <circle>, <ellipse> and
 *     <rect> (svg_path.c) in the SVG namespace or none, outside defs,
 *     symbol, clipPath, mask, marker and pattern;
 *   - with the transforms of the element and its ancestors applied, and
 *     each nested <svg>'s viewport (x, y, width, height, viewBox,
 *     preserveAspectRatio: svg_frame.c); the root's viewBox is not applied
 *     (coordinates in the root's user units); then y = -y, so the curve is
 *     as a browser draws it;
 *   - an element with display:none (attribute or style) is not drawn, nor
 *     is anything inside it: skipped and noted ("display:none <g>"); a
 *     shape whose visibility (inherited) is hidden or collapse is skipped
 *     and noted ("invisible <path>");
 *   - <text>, <image> and <use> are skipped and noted (ob_approx_note_skip).
 * Each piece is at the line of its element's tag.  A malformed attribute is
 * an error "NAME:LINE: <path>: d: at character K ('...'): reason", XML that
 * is not well formed "NAME:LINE: not well-formed XML: reason".
 */
#include "host/io/approx_read.h"

#include <expat.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "host/io/svg_read.h"

enum { SVG_MAX_DEPTH = 256 };
#define SVG_NS "http://www.w3.org/2000/svg"

/* What an element hands down to its children. */
typedef struct {
    ob_svgr_xform ctm;  /* its user units to the file's, before the y flip */
    double vp[2];      /* the size of the viewport % lengths refer to */
    int unrendered;    /* 1: in defs, symbol, ... or under display:none */
    int invisible;     /* visibility hidden or collapse (inherited) */
} svg_state;

typedef struct {
    XML_Parser xp;
    const char *name;
    ob_approx *out;
    ob_err *err;
    int rc;            /* -1 once an error is in err */
    int depth;
    svg_state st[SVG_MAX_DEPTH];
} svg_walk;

static int is_in(const char *tag, const char *const *list)
{
    for (int i = 0; list[i]; i++)
        if (!strcmp(tag, list[i]))
            return 1;
    return 0;
}

static const char *const HIDDEN[] = {"defs", "symbol", "clipPath", "mask", "marker", "pattern", NULL};
static const char *const UNREAD[] = {"text", "image", "use", NULL};
static const char *const SHAPES[] = {"path", "line", "polyline", "polygon", "circle", "ellipse", "rect", NULL};

/* An attribute (unprefixed: no namespace) of atts, or NULL. */
static const char *att(const char **atts, const char *key)
{
    for (int i = 0; atts[i]; i += 2)
        if (!strcmp(atts[i], key))
            return atts[i + 1];
    return NULL;
}

/* A presentation property: from the style attribute ("key: value; ..."),
 * which wins, else the attribute of that name; lower case, trimmed, into
 * buf; NULL when neither says. */
static const char *property(const char **atts, const char *key, char *buf, size_t size)
{
    const char *v = att(atts, key), *style = att(atts, "style");
    const size_t k = strlen(key);
    for (const char *p = style; p && *p; p = strchr(p, ';') ? strchr(p, ';') + 1 : NULL) {
        p += strspn(p, " \t\r\n");
        const char *colon = strchr(p, ':'), *semi = strchr(p, ';');
        size_t kn = colon ? (size_t)(colon - p) : 0;
        while (kn && strchr(" \t\r\n", p[kn - 1]))
            kn--;
        if (colon && (!semi || colon < semi) && kn == k && !strncasecmp(p, key, k))
            v = colon + 1;
    }
    if (!v)
        return NULL;
    v += strspn(v, " \t\r\n");
    size_t n = 0;
    while (v[n] && v[n] != ';' && v[n] != '!' && n + 1 < size)
        buf[n] = (char)(v[n] >= 'A' && v[n] <= 'Z' ? v[n] + 32 : v[n]), n++;
    while (n && strchr(" \t\r\n", buf[n - 1]))
        n--;
    buf[n] = '\0';
    return buf;
}

static int walk_fail(svg_walk *w)
{
    w->rc = -1;
    XML_StopParser(w->xp, XML_FALSE);
    return -1;
}

/* The length attributes keys[0..n) of an element (axis of each: 0 x, 1 y,
 * 2 the diagonal, for %) into v (0 when absent), have[k] whether each is
 * there; 0 or -1 (named). */
static int lengths(const char **atts, const char *const *keys, const int *axes, int n, const svg_state *s,
                   ob_svgr_scan *c, double *v, int *have)
{
    char key[48];
    const char *what = c->what;
    for (int k = 0; k < n; k++) {
        const char *t = att(atts, keys[k]);
        v[k] = 0.0;
        have[k] = t != NULL;
        snprintf(key, sizeof key, "%s: %s", what, keys[k]);
        *c = (ob_svgr_scan){t, 0, t ? strlen(t) : 0, key, c->name, c->line, c->err};
        if (t && ob_svgr_length(c, axes[k], s->vp, &v[k]))
            return -1;
    }
    c->what = what;
    return 0;
}

/* <circle>, <ellipse> or <rect> (kind 0, 1, 2): its attributes, SVG 2's
 * rules for them (rx or ry alone stands for both, a rect's radii clamped
 * to half its sides; a size of 0 renders nothing: skipped and noted; a
 * negative one is an error), then its path. */
static int basic_shape(const ob_svgr_emit *e, int kind, const char **atts, const svg_state *s, ob_svgr_scan *c)
{
    static const char *const keys[3][6] = {{"cx", "cy", "r"}, {"cx", "cy", "rx", "ry"},
                                           {"x", "y", "width", "height", "rx", "ry"}};
    static const int axes[3][6] = {{0, 1, 2}, {0, 1, 0, 1}, {0, 1, 0, 1, 0, 1}};
    static const char *const zero[3] = {"zero-size <circle>", "zero-size <ellipse>", "zero-size <rect>"};
    static const int nkeys[3] = {3, 4, 6};
    double v[6];
    int have[6];
    if (lengths(atts, keys[kind], axes[kind], nkeys[kind], s, c, v, have))
        return -1;
    for (int k = 2; k < nkeys[kind]; k++)
        if (v[k] < 0.0)
            return ob_fail(c->err, "%s:%d: %s: %s: negative (%.17g)", c->name, c->line, c->what, keys[kind][k],
                           v[k]);
    double rx = v[2], ry = kind == 0 ? v[2] : v[3];
    if (kind == 1 && have[2] != have[3])
        rx = ry = have[2] ? v[2] : v[3];
    if (kind == 2) {
        rx = have[4] ? v[4] : have[5] ? v[5] : 0.0;
        ry = have[5] ? v[5] : rx;
        rx = fmin(rx, 0.5 * v[2]);
        ry = fmin(ry, 0.5 * v[3]);
        if (rx == 0.0 || ry == 0.0)
            rx = ry = 0.0;
    }
    const double w = kind == 2 ? v[2] : rx, h = kind == 2 ? v[3] : ry;
    if (w == 0.0 || h == 0.0) {
        ob_approx_note_skip(e->out, zero[kind], e->line);
        return 0;
    }
    return kind == 2 ? ob_svgr_rect(e, v[0], v[1], v[2], v[3], rx, ry) : ob_svgr_ellipse(e, v[0], v[1], rx, ry);
}

/* One shape element tag with attributes atts, in state s (its own
 * transform applied). */
static int shape(svg_walk *w, const char *tag, const char **atts, const svg_state *s, int line)
{
    char what[40], key[48];
    snprintf(what, sizeof what, "<%.20s>", tag);
    const ob_svgr_emit e = {w->name, line, s->ctm, w->out, w->err};
    ob_svgr_scan c = {NULL, 0, 0, what, w->name, line, w->err};
    static const char *const basic[] = {"circle", "ellipse", "rect", NULL};
    for (int k = 0; basic[k]; k++)
        if (!strcmp(tag, basic[k]))
            return basic_shape(&e, k, atts, s, &c);
    if (!strcmp(tag, "line")) {
        static const char *const keys[] = {"x1", "y1", "x2", "y2"};
        static const int axes[] = {0, 1, 0, 1};
        double p[4];
        int have[4];
        return lengths(atts, keys, axes, 4, s, &c, p, have) ? -1 : ob_svgr_line(&e, p, p + 2);
    }
    const int path = !strcmp(tag, "path");
    const char *v = att(atts, path ? "d" : "points");
    if (!v)
        return 0;
    snprintf(key, sizeof key, "%s: %s", what, path ? "d" : "points");
    c.s = v, c.n = strlen(v), c.what = key;
    return path ? ob_svgr_path(&c, &e) : ob_svgr_points(&c, &e, !strcmp(tag, "polygon"));
}

/* A nested <svg>'s viewport into s (its parent's state, its transform
 * applied); 0, 1 when it is of size 0 (nothing drawn), or -1. */
static int nested_svg(svg_walk *w, const char **atts, svg_state *s, int line)
{
    static const char *const keys[] = {"x", "y", "width", "height"};
    static const int axes[] = {0, 1, 0, 1};
    double box[4];
    int have[4];
    ob_svgr_scan c = {NULL, 0, 0, "<svg>", w->name, line, w->err};
    if (lengths(atts, keys, axes, 4, s, &c, box, have))
        return -1;
    for (int k = 2; k < 4; k++)
        if (!have[k]) /* width and height: 100% of the parent's viewport */
            box[k] = s->vp[k - 2];
    if (!(box[2] > 0.0 && box[3] > 0.0))
        return 1;
    ob_svgr_xform t;
    if (ob_svgr_viewport(&c, box, att(atts, "viewBox"), att(atts, "preserveAspectRatio"), &t, s->vp))
        return -1;
    s->ctm = ob_svgr_mul(&s->ctm, &t);
    return 0;
}

/* With svg_units_px: the root's viewBox mapped onto its width and height
 * (absolute: both known and > 0, else nothing), as svgpath.py --units px;
 * 0 or -1. */
static int root_px(const char **atts, svg_state *s, ob_svgr_scan *c)
{
    static const char *const keys[] = {"width", "height"};
    static const int axes[] = {0, 1};
    int have[2];
    double box[4] = {0, 0, 0, 0}, vp[2];
    svg_state none = *s;
    none.vp[0] = none.vp[1] = 0.0;  /* a % size is not known */
    c->what = "<svg>";
    if (lengths(atts, keys, axes, 2, &none, c, box + 2, have) || !have[0] || !have[1] || !(box[2] > 0.0) ||
        !(box[3] > 0.0))
        return 0;
    ob_svgr_xform t;
    c->what = "<svg>: viewBox";
    if (ob_svgr_viewport(c, box, att(atts, "viewBox"), att(atts, "preserveAspectRatio"), &t, vp))
        return -1;
    s->ctm = ob_svgr_mul(&s->ctm, &t);
    return 0;
}

/* The root <svg>'s viewport size (for % lengths): its viewBox's, else its
 * width and height in absolute units (0: unknown).  Its viewBox is applied
 * only with the reading option svg_units_px (root_px). */
static int root_svg(svg_walk *w, const char **atts, svg_state *s, int line)
{
    char key[32];
    const char *vb = att(atts, "viewBox");
    snprintf(key, sizeof key, "<svg>: viewBox");
    ob_svgr_scan c = {vb, 0, vb ? strlen(vb) : 0, key, w->name, line, w->err};
    double v[4];
    if (vb) {
        if (ob_svgr_viewbox(&c, v))
            return -1;
        s->vp[0] = v[2], s->vp[1] = v[3];
        return w->out->svg_units_px ? root_px(atts, s, &c) : 0;
    }
    static const char *const keys[] = {"width", "height"};
    static const int axes[] = {0, 1};
    int have[2];
    c.what = "<svg>";
    if (lengths(atts, keys, axes, 2, s, &c, s->vp, have)) /* 100%, em: the size is not known */
        s->vp[0] = s->vp[1] = 0.0;
    return 0;
}

/* The element's own state from its parent's: hidden, display:none,
 * visibility, its transform, a nested <svg>'s viewport; 0 or -1. */
static int element_state(svg_walk *w, const char *tag, const char **atts, svg_state *s, int line)
{
    char buf[32], what[48];
    const char *v = property(atts, "display", buf, sizeof buf);
    if (v && !strcmp(v, "none") && !s->unrendered) {
        snprintf(what, sizeof what, "display:none <%.9s>", tag);
        ob_approx_note_skip(w->out, what, line);
        s->unrendered = 1;
    }
    s->unrendered |= is_in(tag, HIDDEN);
    v = property(atts, "visibility", buf, sizeof buf);
    if (v && (!strcmp(v, "hidden") || !strcmp(v, "collapse") || !strcmp(v, "visible")))
        s->invisible = strcmp(v, "visible") != 0;
    if ((v = att(atts, "transform")) != NULL) {
        snprintf(what, sizeof what, "<%.20s>: transform", tag);
        ob_svgr_scan c = {v, 0, strlen(v), what, w->name, line, w->err};
        ob_svgr_xform t;
        if (ob_svgr_transform(&c, &t))
            return -1;
        s->ctm = ob_svgr_mul(&s->ctm, &t);
    }
    if (strcmp(tag, "svg") != 0)
        return 0;
    if (w->depth == 0)
        return root_svg(w, atts, s, line);
    const int rc = nested_svg(w, atts, s, line);
    if (rc == 1 && !s->unrendered)
        ob_approx_note_skip(w->out, "zero-size <svg>", line);
    s->unrendered |= rc == 1;
    return rc < 0 ? -1 : 0;
}

/* The local name of an element in the SVG namespace or none ("NS|name"
 * from the namespace-aware parser), or NULL: another namespace's. */
static const char *svg_tag(const char *name)
{
    const char *bar = strchr(name, '|');
    if (!bar)
        return name;
    return (size_t)(bar - name) == strlen(SVG_NS) && !strncmp(name, SVG_NS, strlen(SVG_NS)) ? bar + 1 : NULL;
}

/* The pieces out->v[n0 ..] of one element: its tag and id (approx.h). */
static void name_pieces(ob_approx *out, int n0, const char *tag, const char *id)
{
    for (int i = n0; i < out->n; i++) {
        snprintf(out->v[i].entity, sizeof out->v[i].entity, "%s", tag);
        snprintf(out->v[i].id, sizeof out->v[i].id, "%s", id ? id : "");
    }
}

static void XMLCALL on_start(void *ud, const char *name, const char **atts)
{
    svg_walk *w = ud;
    const int line = (int)XML_GetCurrentLineNumber(w->xp);
    const char *tag = svg_tag(name);
    if (w->depth == 0 && (!tag || strcmp(tag, "svg") != 0)) {
        ob_fail(w->err, "%s:%d: the root element is <%.40s>, not <svg>: not an SVG document", w->name, line,
                tag ? tag : name);
        walk_fail(w);
        return;
    }
    if (w->depth + 1 >= SVG_MAX_DEPTH) {
        ob_fail(w->err, "%s:%d: elements nested deeper than %d", w->name, line, SVG_MAX_DEPTH - 2);
        walk_fail(w);
        return;
    }
    svg_state s = w->st[w->depth];
    int rc = tag ? element_state(w, tag, atts, &s, line) : 0;
    if (rc == 0 && tag && !s.unrendered && is_in(tag, UNREAD)) {
        char what[24];
        snprintf(what, sizeof what, "<%.20s>", tag);
        ob_approx_note_skip(w->out, what, line);
    } else if (rc == 0 && tag && !s.unrendered && is_in(tag, SHAPES)) {
        if (s.invisible) {
            char what[24];
            snprintf(what, sizeof what, "invisible <%.10s>", tag);
            ob_approx_note_skip(w->out, what, line);
        } else {
            const int n0 = w->out->n;
            rc = shape(w, tag, atts, &s, line);
            name_pieces(w->out, n0, tag, att(atts, "id"));
        }
    }
    if (rc)
        walk_fail(w);
    w->st[++w->depth] = s;
}

static void XMLCALL on_end(void *ud, const char *name)
{
    (void)name;
    svg_walk *w = ud;
    w->depth -= w->depth > 0;
}

int ob_approx_read_svg(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err)
{
    if (len > INT_MAX)
        return ob_fail(err, "%s: too large for the XML parser", name);
    svg_walk *w = calloc(1, sizeof *w);
    XML_Parser xp = w ? XML_ParserCreateNS(NULL, '|') : NULL;
    if (!xp) {
        free(w);
        return ob_fail(err, "%s: out of memory", name);
    }
    *w = (svg_walk){xp, name, out, err, 0, 0, {{OB_SVGR_IDENTITY, {0, 0}, 0, 0}}};
    XML_SetUserData(xp, w);
    XML_SetElementHandler(xp, on_start, on_end);
    if (XML_Parse(xp, text, (int)len, XML_TRUE) == XML_STATUS_ERROR && w->rc == 0)
        w->rc = ob_fail(err, "%s:%lu: not well-formed XML: %s", name, (unsigned long)XML_GetCurrentLineNumber(xp),
                        XML_ErrorString(XML_GetErrorCode(xp)));
    const int rc = w->rc;
    XML_ParserFree(xp);
    free(w);
    return rc;
}
