/*
 * compare_subset_text.c - what was left out and what NEW selected, in words
 * (compare_subset.h): the report's "Left out:" line, its context and notes.
 */
#include "host/compare/compare_subset.h"
#include "host/compare/compare_subset_impl.h"

#include <stdio.h>
#include <string.h>

int ob_cmp_subset_note(ob_cmp_subset *s, int dim, const char *value, int *out)
{
    *out = 1;
    const long had = ob_strmap_put(&s->seen[dim], value, s->out[dim].n);
    if (had == -2)
        return -1;
    return had >= 0 ? 0 : ob_strlist_addf(&s->out[dim], "%s", value);
}

/* v with thousands separated by commas, as the docs write counts ("33,620"). */
static const char *thousands(long v, char *buf, size_t len)
{
    char digits[32];
    const int n = snprintf(digits, sizeof digits, "%ld", v);
    size_t k = 0;
    for (int i = 0; i < n && k + 2 < len; i++) {
        if (i && (n - i) % 3 == 0 && digits[i - 1] != '-')
            buf[k++] = ',';
        buf[k++] = digits[i];
    }
    buf[k] = '\0';
    return buf;
}

/* "a, b, c, ..." : the first max values of l, or "first ... last" (range). */
static size_t list(const ob_strlist *l, int max, int range, char *buf, size_t len, size_t used)
{
    if (range && l->n > 1)
        return used + (size_t)snprintf(buf + used, len - used, "%s ... %s", l->v[0], l->v[l->n - 1]);
    for (int i = 0; i < l->n && i < max && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "", l->v[i]);
    if (l->n > max && used < len)
        used += (size_t)snprintf(buf + used, len - used, ", ... (%d in all)", l->n);
    return used;
}

/* One part of the summary ("2 random curves (a ... b)", "methods x, y"). */
static size_t part(const ob_cmp_subset *s, int dim, char *buf, size_t len, size_t used)
{
    static const char *const name[SUB_NDIMS] = {"curve", "random curve", "offset", "method", "metric", "split", "tol"};
    const ob_strlist *l = &s->out[dim];
    if (!l->n || used >= len)
        return used;
    const char *plural = l->n == 1 ? "" : "s";
    if (dim == SUB_METHOD || dim == SUB_METRIC || dim == SUB_SPLIT || dim == SUB_TOL) {
        used += (size_t)snprintf(buf + used, len - used, "%s%s%s ", used ? ", " : "", name[dim], plural);
        return used < len ? list(l, 6, 0, buf, len, used) : used;
    }
    used += (size_t)snprintf(buf + used, len - used, "%s%d %s%s (", used ? ", " : "", l->n, name[dim], plural);
    used = used < len ? list(l, dim == SUB_CURVE ? 4 : 3, dim == SUB_RANDOM, buf, len, used) : used;
    return used < len ? used + (size_t)snprintf(buf + used, len - used, ")") : used;
}

/* NEW's selection in words (the report's context). */
static void selection_words(ob_cmp_subset *s)
{
    char rnd[128] = "no random set", files[96] = "no curves from files";
    if (s->random)
        snprintf(rnd, sizeof rnd, "random %s%s", s->random_text, s->has_only ? " (only the ids --curve listed)" : "");
    if (s->ncurves)
        snprintf(files, sizeof files, "%d curve%s from files (%d offset%s)", s->ncurves, s->ncurves == 1 ? "" : "s",
                 s->noffsets, s->noffsets == 1 ? "" : "s");
    snprintf(s->sel_text, sizeof s->sel_text, "%s, %s, %d method%s, %d metric%s, %d split%s, %d tol%s", files, rnd,
             s->nmethods, s->nmethods == 1 ? "" : "s", s->nmetrics, s->nmetrics == 1 ? "" : "s", s->nsplits,
             s->nsplits == 1 ? "" : "s", s->ntols, s->ntols == 1 ? "" : "s");
}

int ob_cmp_subset_finish(ob_cmp_result *r)
{
    ob_cmp_subset *s = r->subset;
    if (!s)
        return 0;
    if (!s->has)
        return r->n_missing ? ob_strlist_addf(&r->notes, "%s: every row of BASE missing from NEW counts as "
                                              "missing, a regression, as before (a run of this offbench records "
                                              "its selection in meta.json: rows of BASE outside it are left out, "
                                              "not regressions)", s->why) : 0;
    selection_words(s);
    size_t used = 0;
    char n[32];
    for (int dim = 0; dim < SUB_NDIMS; dim++)
        used = part(s, dim, s->text, sizeof s->text, used);
    if (used < sizeof s->text)
        snprintf(s->text + used, sizeof s->text - used, ": %s row%s left out", thousands(r->n_left_out, n, sizeof n),
                 r->n_left_out == 1 ? "" : "s");
    return 0;
}

const char *ob_cmp_left_out_text(const ob_cmp_result *r)
{
    return r->subset && r->subset->has && r->n_left_out ? r->subset->text : NULL;
}

const char *ob_cmp_selection_text(const ob_cmp_result *r)
{
    return r->subset && r->subset->has && r->subset->sel_text[0] ? r->subset->sel_text : NULL;
}
