/*
 * compare_subset.c - NEW's selection and the rows of BASE it left out (see
 * compare_subset.h); the summary line: compare_subset_text.c.
 */
#include "host/compare/compare_subset.h"
#include "host/compare/compare_subset_impl.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/random.h"

/* ---- the items of an array ---- */

/* Calls each(item, len, ctx) for every item of a JSON array's raw text
 * (metajson.h keeps arrays so, validated), items trimmed; stops at the
 * first non-zero return, which it returns. */
static int each_item(const char *raw, int (*each)(const char *, size_t, void *), void *ctx)
{
    const char *p = raw + 1;  /* past '[' */
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
            p++;
        if (*p == ']' || !*p)
            return 0;
        const char *q = p;
        int depth = 0, str = 0;
        for (; *q && (str || depth || (*q != ',' && *q != ']')); q++) {
            if (str)
                str = *q == '\\' ? (q++, 1) : *q != '"';
            else if (*q == '"')
                str = 1;
            else
                depth += (*q == '[' || *q == '{') - (*q == ']' || *q == '}');
        }
        size_t len = (size_t)(q - p);
        while (len && (p[len - 1] == ' ' || p[len - 1] == '\n' || p[len - 1] == '\r' || p[len - 1] == '\t'))
            len--;
        const int rc = each(p, len, ctx);
        if (rc)
            return rc;
        p = *q == ',' ? q + 1 : q;
    }
}

/* A number item as a double; 0, or -1 when it is not a number. */
static int item_number(const char *item, size_t len, double *x)
{
    char buf[64], *end;
    if (len == 0 || len >= sizeof buf || !(item[0] == '-' || (item[0] >= '0' && item[0] <= '9')))
        return -1;
    memcpy(buf, item, len);
    buf[len] = '\0';
    *x = strtod(buf, &end);
    return *end ? -1 : 0;
}

static int check_number(const char *item, size_t len, void *ctx)
{
    double x;
    (void)ctx;
    return item_number(item, len, &x) ? 1 : 0;
}

/* A plain string item (no escapes: names as offbench writes them) into map; 1 not one, -2 no memory. */
static int put_name(const char *item, size_t len, void *ctx)
{
    if (len < 2 || item[0] != '"' || item[len - 1] != '"' || memchr(item, '\\', len))
        return 1;
    return ob_strmap_putn(ctx, item + 1, len - 2, 0) == -2 ? -2 : 0;
}

typedef struct {
    double x;
    int found;
} num_find;

static int find_number(const char *item, size_t len, void *ctx)
{
    num_find *f = ctx;
    double x;
    f->found = item_number(item, len, &x) == 0 && x == f->x;
    return f->found;
}

/* 1 when the array raw holds the number x (as a double: 1e-2 == 0.01). */
static int has_number(const char *raw, double x)
{
    num_find f = {x, 0};
    each_item(raw, find_number, &f);
    return f.found;
}

/* ---- reading NEW's selection ---- */

/* The array at key into map (names); 0, or -1 with why. */
static int read_names(ob_cmp_subset *s, const char *key, ob_strmap *map, int *count)
{
    const ob_json_entry *e = ob_json_get(s->meta, key);
    if (!e || e->type != OB_JSON_ARRAY) {
        snprintf(s->why, sizeof s->why, "%s is not an array", key);
        return -1;
    }
    const int rc = each_item(e->value, put_name, map);
    if (rc) {
        snprintf(s->why, sizeof s->why, rc == -2 ? "out of memory" : "%s: an item is not a plain string", key);
        return -1;
    }
    *count = (int)map->n;
    return 0;
}

static int add_tol(const char *item, size_t len, void *ctx)
{
    ob_cmp_subset *s = ctx;
    double x;
    if (item_number(item, len, &x) || s->ntols >= (int)(sizeof s->tols / sizeof s->tols[0]))
        return 1;
    s->tols[s->ntols++] = x;
    return 0;
}

/* selection.random: null, or {"n": N, "seed": S, "only": null | [ids]}; 0, or -1 with why. */
static int read_random(ob_cmp_subset *s)
{
    const ob_json_entry *e = ob_json_get(s->meta, "selection.random");
    if (e && e->type == OB_JSON_NULL)
        return 0;
    const ob_json_entry *n = ob_json_get(s->meta, "selection.random.n"),
                        *seed = ob_json_get(s->meta, "selection.random.seed"),
                        *only = ob_json_get(s->meta, "selection.random.only");
    const int seed_ok = seed && seed->type == OB_JSON_NUMBER && seed->value[0] != '-';
    char *end = NULL;
    errno = 0;
    if (seed_ok)
        s->seed = strtoull(seed->value, &end, 10);
    if (!n || n->type != OB_JSON_NUMBER || !seed_ok || errno || *end || !only) {
        snprintf(s->why, sizeof s->why, "selection.random is not null or {\"n\": N, \"seed\": S, \"only\": ...}");
        return -1;
    }
    s->random = 1;
    s->n = strtol(n->value, NULL, 10);
    snprintf(s->random_text, sizeof s->random_text, "%ld:%" PRIu64, s->n, s->seed);
    int count;
    s->has_only = only->type != OB_JSON_NULL;
    return s->has_only ? read_names(s, "selection.random.only", &s->only, &count) : 0;
}

/* selection.curves: {} or {"ID": [d, ...], ...}; 0, or -1 with why. */
static int read_curves(ob_cmp_subset *s)
{
    static const char prefix[] = "selection.curves.";
    const ob_json_entry *all = ob_json_get(s->meta, "selection.curves");
    for (int i = 0; i < s->meta->n; i++) {
        const ob_json_entry *e = &s->meta->v[i];
        if (strncmp(e->path, prefix, sizeof prefix - 1) != 0)
            continue;
        if (e->type != OB_JSON_ARRAY || each_item(e->value, check_number, NULL)) {
            snprintf(s->why, sizeof s->why, "%.200s is not an array of offsets", e->path);
            return -1;
        }
        s->ncurves++;
        s->noffsets += e->value[1] != ']' && e->value[1] != '\0';  /* items: commas + 1 */
        for (const char *c = e->value; *c; c++)
            s->noffsets += *c == ',';
    }
    if (!s->ncurves && !(all && all->type == OB_JSON_OBJECT)) {
        snprintf(s->why, sizeof s->why, "selection.curves is not an object");
        return -1;
    }
    return 0;
}

/* Every part of NEW's selection; 0, or -1 with why (then not used). */
static int read_selection(ob_cmp_subset *s)
{
    if (!ob_json_get(s->meta, "selection.methods")) {
        snprintf(s->why, sizeof s->why, "NEW's meta.json records no selection (a run of an older offbench)");
        return -1;
    }
    const ob_json_entry *tols = ob_json_get(s->meta, "selection.tols");
    if (read_names(s, "selection.methods", &s->sel[SUB_METHOD], &s->nmethods) ||
        read_names(s, "selection.metrics", &s->sel[SUB_METRIC], &s->nmetrics) ||
        read_names(s, "selection.splits", &s->sel[SUB_SPLIT], &s->nsplits) || read_random(s) || read_curves(s))
        return -1;
    if (!tols || tols->type != OB_JSON_ARRAY || each_item(tols->value, add_tol, s)) {
        snprintf(s->why, sizeof s->why, "selection.tols is not an array of tolerances");
        return -1;
    }
    return 0;
}

/* ---- another seed, seen in the rows of a BASE without meta.json ---- */

/* A random curve of BASE (by its id) that NEW's random set cannot hold
 * (another seed, or no random set): the first such id in *id; 0 if none. */
static int foreign_random(const ob_cmp_side *b, const ob_cmp_subset *s, const char **id, uint64_t *seed)
{
    char key[600];
    for (int i = 0; i < b->res.n; i++) {
        long index;
        const char *c = b->res.v[i].curve;
        snprintf(key, sizeof key, "selection.curves.%s", c);
        if (ob_random_id_parse(c, seed, &index) == 0 && !ob_json_get(s->meta, key) &&
            (!s->random || *seed != s->seed)) {
            *id = c;
            return 1;
        }
    }
    return 0;
}

static int seed_check(const ob_cmp_side *b, const ob_cmp_subset *s, ob_cmp_result *r)
{
    const char *id;
    uint64_t seed;
    if (b->has_meta || !foreign_random(b, s, &id, &seed))
        return 0;
    return ob_strlist_addf(&r->incomparable, "BASE (no meta.json) has random curves of seed %" PRIu64 " (%s), NEW's "
                           "random set is %s: another seed makes other curves (a smaller N of the same seed is a "
                           "subset)", seed, id, s->random ? s->random_text : "none");
}

int ob_cmp_subset_load(const ob_cmp_side *b, const ob_cmp_side *n, ob_cmp_result *r)
{
    ob_cmp_subset *s = calloc(1, sizeof *s);
    if (!s)
        return -1;
    r->subset = s;
    s->meta = &n->meta;
    if (!n->has_meta) {
        snprintf(s->why, sizeof s->why, "NEW has no meta.json, so what it set out to run is unknown");
        return 0;
    }
    s->has = read_selection(s) == 0;
    if (!s->has && strcmp(s->why, "out of memory") == 0)
        return -1;
    if (!s->has && strncmp(s->why, "NEW's", 5) != 0) {  /* a selection there, but not one this build reads */
        char why[sizeof s->why];
        snprintf(why, sizeof why, "NEW's meta.json has a selection that cannot be read (%.200s): not used", s->why);
        snprintf(s->why, sizeof s->why, "%s", why);
    }
    return s->has ? seed_check(b, s, r) : 0;
}

/* ---- the rows ---- */

/* 1: row b's curve and offset are in the selection; 0: its curve is not
 * (*random: it is a random id); -1: the curve is, its offset d is not. */
static int curve_in(const ob_cmp_subset *s, const ob_res_row *b, int *random)
{
    char key[600];
    snprintf(key, sizeof key, "selection.curves.%s", b->curve);
    const ob_json_entry *e = ob_json_get(s->meta, key);
    *random = 0;
    if (e)
        return has_number(e->value, b->d) ? 1 : -1;
    uint64_t seed;
    long index;
    *random = ob_random_id_parse(b->curve, &seed, &index) == 0;
    if (!*random || !s->random || seed != s->seed || index >= s->n)
        return 0;
    return !s->has_only || ob_strmap_get(&s->only, b->curve) >= 0;
}

static int tol_in(const ob_cmp_subset *s, double tol)
{
    for (int i = 0; i < s->ntols; i++)
        if (s->tols[i] == tol)
            return 1;
    return 0;
}

int ob_cmp_subset_left_out(ob_cmp_result *r, const ob_res_row *b)
{
    ob_cmp_subset *s = r->subset;
    if (!s || !s->has)
        return 0;
    char offset[600];
    int random, out = 0, rc = 0;
    const int c = curve_in(s, b, &random);
    snprintf(offset, sizeof offset, "%s d=%s", b->curve, b->d_text);
    if (c <= 0)
        rc |= ob_cmp_subset_note(s, c < 0 ? SUB_OFFSET : random ? SUB_RANDOM : SUB_CURVE, c < 0 ? offset : b->curve,
                                 &out);
    if (ob_strmap_get(&s->sel[SUB_METHOD], b->method) < 0)
        rc |= ob_cmp_subset_note(s, SUB_METHOD, b->method, &out);
    if (ob_strmap_get(&s->sel[SUB_METRIC], b->metric) < 0)
        rc |= ob_cmp_subset_note(s, SUB_METRIC, b->metric, &out);
    if (ob_strmap_get(&s->sel[SUB_SPLIT], b->split) < 0)
        rc |= ob_cmp_subset_note(s, SUB_SPLIT, b->split, &out);
    if (!tol_in(s, b->tol))
        rc |= ob_cmp_subset_note(s, SUB_TOL, b->tol_text, &out);
    if (rc)
        return -1;
    r->n_left_out += out;
    return out;
}

void ob_cmp_subset_free(ob_cmp_subset *s)
{
    if (!s)
        return;
    for (int k = 0; k < SUB_NDIMS; k++) {
        ob_strmap_free(&s->sel[k]);
        ob_strmap_free(&s->seen[k]);
        ob_strlist_free(&s->out[k]);
    }
    ob_strmap_free(&s->only);
    free(s);
}
