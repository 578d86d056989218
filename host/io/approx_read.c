/*
 * approx_read.c - the approximation readers' common part and the .curves
 * reader (approx_read.h).  The .curves text goes through offbench's own
 * reader (curvefile.c), so a file measure takes is a file run takes.
 */
#include "host/io/approx_read.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "host/io/curvefile.h"
#include "host/io/numfmt.h"
#include "host/io/slurp.h"

static int ends_with(const char *s, const char *ext)
{
    const size_t n = strlen(s), k = strlen(ext);
    return n >= k && strcasecmp(s + n - k, ext) == 0;
}

ob_afmt ob_approx_format(const char *path, const char *text, size_t len)
{
    if (ends_with(path, ".json"))
        return OB_AFMT_JSON;
    if (ends_with(path, ".dxf"))
        return OB_AFMT_DXF;
    if (ends_with(path, ".curves"))
        return OB_AFMT_CURVES;
    if (ends_with(path, ".svg"))
        return OB_AFMT_SVG;
    size_t i = 0;
    while (i < len && isspace((unsigned char)text[i]))
        i++;
    if (i < len && text[i] == '{')
        return OB_AFMT_JSON;
    if ((i + 4 <= len && !strncmp(text + i, "<svg", 4)) || (i + 5 <= len && !strncmp(text + i, "<?xml", 5)))
        return OB_AFMT_SVG;
    if (i + 1 < len && text[i] == '0' && (text[i + 1] == '\n' || text[i + 1] == '\r'))
        return OB_AFMT_DXF;
    if (i + 3 < len && !strncmp(text + i, "999", 3) && (text[i + 3] == '\n' || text[i + 3] == '\r'))
        return OB_AFMT_DXF;
    return OB_AFMT_CURVES;
}

int ob_approx_parse_link(const char *s, ob_apiece *p)
{
    const char *q = strstr(s, "base segment ");
    int seg, n = 0;
    double a, b, t0, t1;
    if (!q || sscanf(q, "base segment %d span %lf %lf fit %lf %lf%n", &seg, &a, &b, &t0, &t1, &n) != 5 || n == 0)
        return 0;
    p->has_base = 1;
    p->seg = seg;
    p->a = a;
    p->b = b;
    p->t0 = t0;
    p->t1 = t1;
    return 1;
}

/* The stem's characters: those of an id, '~' for its '/', and a number's. */
static size_t stem_len(const char *s)
{
    return strspn(s, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.~+");
}

/* The last occurrence of pat in s that starts before end, or NULL. */
static char *last_before(char *s, const char *end, const char *pat)
{
    char *hit = NULL;
    for (char *p = s; (p = strstr(p, pat)) != NULL && p < end; p++)
        hit = p;
    return hit;
}

int ob_approx_parse_job(const char *s, ob_approx *out)
{
    const char *q = strstr(s, "of job ");
    q = q ? q + 7 : (q = strstr(s, "export: ")) ? q + 8 : NULL;
    if (!q)
        return 0;
    char stem[256];
    const size_t n = stem_len(q);
    if (n == 0 || n >= sizeof stem)
        return 0;
    memcpy(stem, q, n);
    stem[n] = '\0';
    /* from the right: the tolerance, the method and d hold no "__" */
    char *tol = last_before(stem, stem + n, "__tol");
    char *meth = tol ? last_before(stem, tol, "__") : NULL;
    char *d = meth ? last_before(stem, meth, "__d") : NULL;
    if (!d || (size_t)(d - stem) >= sizeof out->job_curve)
        return 0;
    *meth = '\0';
    double x;
    if (ob_parse_double(d + 3, &x))
        return 0;
    *d = '\0';
    for (char *p = stem; *p; p++)
        if (*p == '~')
            *p = '/';
    memcpy(out->job_curve, stem, (size_t)(d - stem) + 1);
    out->job_d = x;
    out->have_job = 1;
    return 1;
}

int ob_approx_check_piece(ob_apiece *p, int k, const char *name, ob_err *err)
{
    ob_bez *b = &p->approx;
    if (b->deg < 1 || b->deg > OB_MAX_DEG) {
        ob_fail(err, "%s:%d: piece %d: degree %d (measure takes 1 to %d)", name, p->line, k, b->deg,
                OB_MAX_DEG);
        return -1;
    }
    b->rational = 0;
    for (int i = 0; i <= b->deg; i++) {
        /* weights of any sign: rational fits may have negative interior
         * weights (zhao-rational does), and the run measured them */
        if (!isfinite(b->h[i][0]) || !isfinite(b->h[i][1]) || !isfinite(b->h[i][2])) {
            ob_fail(err, "%s:%d: piece %d: control point %d is not finite", name, p->line, k, i);
            return -1;
        }
        b->rational |= b->h[i][2] != 1.0;
    }
    if (p->has_base && !(p->a < p->b && p->t0 < p->t1)) {
        ob_fail(err, "%s:%d: piece %d: its base piece (span %.17g %.17g, fit %.17g %.17g) is empty", name,
                p->line, k, p->a, p->b, p->t0, p->t1);
        return -1;
    }
    return 0;
}

int ob_approx_read_curves(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err)
{
    ob_curveset set = {0};
    if (ob_curves_parse(text, len, name, &set, err) != 0)
        return -1;
    int rc = 0, linked = 0;
    for (int c = 0; c < set.n && rc == 0; c++) {
        const ob_curve *cv = &set.v[c];
        for (int s = 0; s < cv->nseg && rc == 0; s++) {
            ob_apiece *p = ob_approx_add(out);
            if (!p) {
                ob_fail(err, "%s: out of memory", name);
                rc = -1;
                break;
            }
            p->line = cv->line;
            p->approx = cv->seg[s];
            p->fit_first = 1;
            /* the link of an export: one Bézier segment per curve block */
            if (!out->have_job)
                ob_approx_parse_job(cv->source, out);
            if (cv->nseg == 1 && ob_approx_parse_link(cv->source, p))
                linked += strstr(cv->source, "same_param yes") != NULL;
            rc = ob_approx_check_piece(p, out->n - 1, name, err);
        }
    }
    out->same_param = rc == 0 && out->n > 0 && linked == out->n;
    ob_curveset_free(&set);
    return rc;
}

/* The error of file `name` that gave no pieces: says so, then lists the
 * first OB_APPROX_NOTES entities the reader skipped (NAME:LINE: TYPE
 * (WHY)) and how many more, since they are why (an INSERT whose block
 * holds the curves, a tilted ARC, an SVG <use>).  Returns -1. */
static int no_pieces(const ob_approx *a, const char *name, ob_err *err)
{
    char list[4096] = "";
    size_t n = 0;
    const int shown = a->nskipped < OB_APPROX_NOTES ? a->nskipped : OB_APPROX_NOTES;
    for (int i = 0; i < shown && n < sizeof list; i++)
        n += (size_t)snprintf(list + n, sizeof list - n, "; %s:%d: %s (%s)", name, a->notes[i].line,
                              a->notes[i].type, a->notes[i].why);
    if (a->nskipped > shown && n < sizeof list)
        snprintf(list + n, sizeof list - n, "; and %d more", a->nskipped - shown);
    if (a->nskipped == 0)
        return ob_fail(err, "%s: no pieces (no Bézier segments, DXF curves or SVG paths) in the file", name);
    return ob_fail(err, "%s: no pieces (no Bézier segments, DXF curves or SVG paths) in the file; it skipped "
                   "%d entit%s: %s", name, a->nskipped, a->nskipped == 1 ? "y" : "ies", list + 2);
}

int ob_approx_read(const char *path, ob_approx *out, ob_err *err)
{
    char *text = NULL;
    size_t len = 0;
    if (ob_slurp(path, &text, &len, err) != 0)
        return -1;
    int rc;
    switch (ob_approx_format(path, text, len)) {
    case OB_AFMT_JSON: rc = ob_approx_read_json(text, len, path, out, err); break;
    case OB_AFMT_DXF: rc = ob_approx_read_dxf(text, len, path, out, err); break;
    case OB_AFMT_SVG: rc = ob_approx_read_svg(text, len, path, out, err); break;
    default: rc = ob_approx_read_curves(text, len, path, out, err); break;
    }
    free(text);
    if (rc == 0 && out->n == 0)  /* the skip notes say why: an INSERT, a tilted ARC, a <use> */
        rc = no_pieces(out, path, err);
    return rc;
}
