/*
 * merge_meta.c - the merged run's meta.json (merge.h): shard 0's, with what
 * differs between the shards said, not hidden.  A shard's meta.json holds
 * one top-level key per line (output.c writes it so); each line is
 * "  \"KEY\": VALUE" with a comma unless it is the last.
 */
#include <stdlib.h>
#include <string.h>

#include "host/cli/merge.h"
#include "host/io/output.h"

/* The keys every shard's object in "shards" holds: what one process of the
 * run had or did (its machine, backend, threads, time, command line). */
static const char *const per_shard[] = {"jobs",   "wall_seconds", "backend",   "opencl",         "cpu_because",
                                        "cpu_model", "omp_threads", "host",    "engine",         "warnings",
                                        "rep_mismatches", "export_dir", "argv", "timestamp"};

/* One top-level entry of a meta.json text. */
typedef struct {
    char key[128];
    const char *val;   /* into the text */
    size_t vlen;       /* without the comma and newline */
} entry;

typedef struct {
    entry *v;
    int n;
} entries;

/* The line p[0..len) as a top-level entry; 0, or -1 when it is not one. */
static int parse_entry(const char *p, size_t len, entry *e)
{
    if (len < 6 || strncmp(p, "  \"", 3) != 0)
        return -1;
    const char *q = memchr(p + 3, '"', len - 3);
    if (!q || (size_t)(q - p) + 3 > len || strncmp(q, "\": ", 3) != 0 || (size_t)(q - p - 3) >= sizeof e->key)
        return -1;
    memcpy(e->key, p + 3, (size_t)(q - p - 3));
    e->key[q - p - 3] = '\0';
    e->val = q + 3;
    e->vlen = len - (size_t)(e->val - p);
    while (e->vlen && (e->val[e->vlen - 1] == '\n' || e->val[e->vlen - 1] == '\r'))
        e->vlen--;
    if (e->vlen && e->val[e->vlen - 1] == ',')
        e->vlen--;
    return 0;
}

/* Every top-level entry of text[0..len); 0, or -1 out of memory. */
static int parse_entries(const char *text, size_t len, entries *out)
{
    out->n = 0;
    out->v = malloc((len / 8 + 1) * sizeof *out->v);  /* a line is at least 8 bytes */
    if (!out->v)
        return -1;
    for (const char *p = text, *end = text + len; p < end;) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const size_t l = nl ? (size_t)(nl - p) + 1 : (size_t)(end - p);
        if (parse_entry(p, l, &out->v[out->n]) == 0)
            out->n++;
        p += l;
    }
    return 0;
}

static const entry *find(const entries *es, const char *key)
{
    for (int i = 0; i < es->n; i++)
        if (strcmp(es->v[i].key, key) == 0)
            return &es->v[i];
    return NULL;
}

static int same_val(const entry *a, const entry *b)
{
    return a && b && a->vlen == b->vlen && memcmp(a->val, b->val, a->vlen) == 0;
}

/* Whether key's value differs between any two shards. */
static int differs(const entries *es, int nsh, const char *key)
{
    const entry *a = find(&es[0], key);
    for (int i = 1; i < nsh; i++) {
        const entry *b = find(&es[i], key);
        if ((a || b) && !same_val(a, b))
            return 1;
    }
    return 0;
}

static int is_per_shard(const char *key)
{
    for (size_t i = 0; i < sizeof per_shard / sizeof per_shard[0]; i++)
        if (strcmp(per_shard[i], key) == 0)
            return 1;
    return 0;
}

/* The keys merge writes itself, never "mixed". */
static int is_rewritten(const char *key)
{
    static const char *const own[] = {"shard", "jobs", "wall_seconds", "rep_mismatches", "warnings",
                                      "timestamp", "merged_shards", "shards", "backends"};
    for (size_t i = 0; i < sizeof own / sizeof own[0]; i++)
        if (strcmp(own[i], key) == 0)
            return 1;
    return 0;
}

/* "shards": one object per shard, in K order (sh[ix[K]] is shard K, es[K]
 * its entries). */
static void write_shards(FILE *f, const ob_shard_in *sh, const int *ix, const entries *es, int nsh)
{
    fputs("  \"shards\": [", f);
    for (int k = 0; k < nsh; k++) {
        const ob_shard_in *s = &sh[ix[k]];
        fprintf(f, "%s{\"shard\": \"%d/%d\", \"dir\": ", k ? ", " : "", s->k, s->n);
        ob_json_string(f, s->dir);
        for (int i = 0; i < es[0].n; i++) {
            const char *key = es[0].v[i].key;
            if (strcmp(key, "shard") == 0 || !(is_per_shard(key) || differs(es, nsh, key)))
                continue;
            const entry *e = find(&es[k], key);
            fprintf(f, ", \"%s\": ", key);
            if (e)
                fwrite(e->val, 1, e->vlen, f);
            else
                fputs("null", f);
        }
        fputc('}', f);
    }
    fputs("],\n", f);
}

/* Shard es's value of key when it is an array ("[...]" on its line), else NULL. */
static const entry *array_of(const entries *es, const char *key)
{
    const entry *e = find(es, key);
    return e && e->vlen >= 2 && e->val[0] == '[' && e->val[e->vlen - 1] == ']' ? e : NULL;
}

/* Every shard's warnings, in K order, as one array. */
static void write_warnings(FILE *f, const entries *es, int nsh)
{
    int any = 0;
    fputc('[', f);
    for (int k = 0; k < nsh; k++) {
        const entry *e = array_of(&es[k], "warnings");
        if (!e)
            continue;
        const char *a = e->val + 1, *b = e->val + e->vlen - 1;
        while (a < b && *a == ' ')
            a++;
        if (a == b)
            continue;
        fprintf(f, "%s%.*s", any ? ", " : "", (int)(b - a), a);
        any = 1;
    }
    fputc(']', f);
}

static long sum_of(const entries *es, int nsh, const char *key)
{
    long sum = 0;
    for (int k = 0; k < nsh; k++) {
        const entry *e = find(&es[k], key);
        if (e)
            sum += strtol(e->val, NULL, 10);
    }
    return sum;
}

/* The end of the JSON value at p (a string, an object or array with
 * everything nested, or a bare word), or NULL when it runs past end. */
static const char *value_end(const char *p, const char *end)
{
    int depth = 0, str = 0;
    for (; p < end; p++) {
        if (str) {
            if (*p == '\\')
                p++;
            else if (*p == '"')
                str = 0;
            if (!str && depth == 0)
                return p + 1;
            continue;
        }
        if (*p == '"')
            str = 1;
        else if (*p == '{' || *p == '[')
            depth++;
        else if (*p == '}' || *p == ']') {
            if (--depth == 0)
                return p + 1;
            if (depth < 0)
                return p;
        } else if (depth == 0 && (*p == ',' || *p == ' '))
            return p;
    }
    return depth == 0 && !str ? p : NULL;
}

/* Every shard's "backends" entries (backends.h), in K order, each once, as
 * one array: the backends that computed rows of the merged run. */
static void write_backends(FILE *f, const entries *es, int nsh)
{
    enum { MAX = 64 };
    const char *seen[MAX];
    size_t slen[MAX];
    int ns = 0;
    fputc('[', f);
    for (int k = 0; k < nsh; k++) {
        const entry *e = array_of(&es[k], "backends");
        if (!e)
            continue;
        for (const char *p = e->val + 1, *end = e->val + e->vlen - 1, *q; p < end; p = q) {
            while (p < end && (*p == ' ' || *p == ','))
                p++;
            if (p >= end || !(q = value_end(p, end)) || q == p)
                break;
            int dup = 0;
            for (int i = 0; i < ns && !dup; i++)
                dup = slen[i] == (size_t)(q - p) && memcmp(seen[i], p, slen[i]) == 0;
            if (dup || ns == MAX)
                continue;
            fprintf(f, "%s%.*s", ns ? ", " : "", (int)(q - p), p);
            seen[ns] = p;
            slen[ns++] = (size_t)(q - p);
        }
    }
    fputc(']', f);
}

/* The members of the one-line object v[0..n): key i is keys[i] (without
 * quotes), its value vals[i] (vlens[i] bytes); at most cap.  Their count,
 * or -1 when v is not such an object. */
static int members(const char *v, size_t n, const char **keys, size_t *klens, const char **vals, size_t *vlens,
                   int cap)
{
    const char *p = v, *end = v + n;
    int k = 0;
    if (n < 2 || *p != '{' || end[-1] != '}')
        return -1;
    for (p++, end--; p < end && k < cap;) {
        while (p < end && (*p == ' ' || *p == ','))
            p++;
        if (p == end)
            break;
        const char *ke = *p == '"' ? value_end(p, end) : NULL;
        if (!ke || ke + 2 > end || ke[0] != ':' || ke[1] != ' ')
            return -1;
        keys[k] = p + 1;
        klens[k] = (size_t)(ke - p - 2);
        vals[k] = ke + 2;
        const char *ve = value_end(vals[k], end);
        if (!ve || ve == vals[k])
            return -1;
        vlens[k] = (size_t)(ve - vals[k]);
        k++;
        p = ve;
    }
    return p < end ? -1 : k;
}

enum { MAX_MEMBERS = 64 };

/* An object every shard has (host, engine, opencl on one device kind):
 * member by member, each member's value when every shard has that value,
 * else "mixed".  0, or -1 when a value is no such object (the caller
 * then writes "mixed" for the whole). */
static int write_object(FILE *f, const entries *es, int nsh, const char *key)
{
    const char *k0[MAX_MEMBERS], *v0[MAX_MEMBERS], *ki[MAX_MEMBERS], *vi[MAX_MEMBERS];
    size_t kl0[MAX_MEMBERS], vl0[MAX_MEMBERS], kli[MAX_MEMBERS], vli[MAX_MEMBERS];
    int same[MAX_MEMBERS];
    const entry *e0 = find(&es[0], key);
    const int n0 = e0 ? members(e0->val, e0->vlen, k0, kl0, v0, vl0, MAX_MEMBERS) : -1;
    if (n0 < 0)
        return -1;
    for (int m = 0; m < n0; m++)
        same[m] = 1;
    for (int s = 1; s < nsh; s++) {
        const entry *e = find(&es[s], key);
        const int ni = e ? members(e->val, e->vlen, ki, kli, vi, vli, MAX_MEMBERS) : -1;
        if (ni < 0)
            return -1;
        for (int m = 0; m < n0; m++) {
            int found = 0;
            for (int q = 0; q < ni && !found; q++)
                found = kli[q] == kl0[m] && memcmp(ki[q], k0[m], kl0[m]) == 0 && vli[q] == vl0[m] &&
                        memcmp(vi[q], v0[m], vl0[m]) == 0;
            same[m] &= found;
        }
    }
    fputc('{', f);
    for (int m = 0; m < n0; m++) {
        fprintf(f, "%s\"%.*s\": ", m ? ", " : "", (int)kl0[m], k0[m]);
        if (same[m])
            fwrite(v0[m], 1, vl0[m], f);
        else
            fputs("\"mixed\"", f);
    }
    fputc('}', f);
    return 0;
}

/* The latest of the shards' values of key (ISO 8601 times in UTC sort as
 * text): the merged run ends when its last shard did. */
static const entry *latest(const entries *es, int nsh, const char *key)
{
    const entry *best = NULL;
    for (int s = 0; s < nsh; s++) {
        const entry *e = find(&es[s], key);
        if (e && (!best || (e->vlen == best->vlen && memcmp(e->val, best->val, e->vlen) > 0)))
            best = e;
    }
    return best;
}

/* What the merge writes: the shards (sh[ix[K]] is shard K, es[K] its
 * entries), the run's job count and wall time. */
typedef struct {
    const ob_shard_in *sh;
    const int *ix;
    const entries *es;
    int nsh;
    size_t total;
    double wall;
} merged_meta;

/* One top-level line of shard 0's text: its key's merged value, then the
 * line's rest (comma, newline).  *seen gets the bits of the keys merge must
 * find. */
static void write_line(FILE *f, const entry *e, const char *rest, size_t rlen, const merged_meta *m, int *seen)
{
    if (strcmp(e->key, "shard") == 0) {
        fprintf(f, "  \"shard\": null,\n  \"merged_shards\": %d,\n", m->nsh);
        write_shards(f, m->sh, m->ix, m->es, m->nsh);
        *seen |= 1;
        return;
    }
    fprintf(f, "  \"%s\": ", e->key);
    if (strcmp(e->key, "jobs") == 0) {
        fprintf(f, "%zu", m->total);
        *seen |= 2;
    } else if (strcmp(e->key, "wall_seconds") == 0) {
        fprintf(f, "%.3f", m->wall);
        *seen |= 4;
    } else if (strcmp(e->key, "rep_mismatches") == 0) {
        fprintf(f, "%ld", sum_of(m->es, m->nsh, e->key));
    } else if (strcmp(e->key, "warnings") == 0) {
        write_warnings(f, m->es, m->nsh);
    } else if (strcmp(e->key, "backends") == 0) {
        write_backends(f, m->es, m->nsh);
    } else if (strcmp(e->key, "timestamp") == 0) {
        const entry *t = latest(m->es, m->nsh, e->key);
        fwrite(t->val, 1, t->vlen, f);
    } else if (!is_rewritten(e->key) && differs(m->es, m->nsh, e->key)) {
        if (write_object(f, m->es, m->nsh, e->key) != 0)
            fputs("\"mixed\"", f);
    } else {
        fwrite(e->val, 1, e->vlen, f);
    }
    fwrite(rest, 1, rlen, f);
}

int ob_merge_write_meta(FILE *f, const ob_shard_in *sh, int nsh, size_t total, double wall)
{
    entries *es = calloc((size_t)nsh, sizeof *es);
    int *ix = calloc((size_t)nsh, sizeof *ix);
    int rc = !es || !ix ? -1 : 0, seen = 0;
    for (int i = 0; rc == 0 && i < nsh; i++)
        if (sh[i].k < 0 || sh[i].k >= nsh)
            rc = -1;  /* not a complete set (checked before: never here) */
        else
            ix[sh[i].k] = i;
    for (int k = 0; rc == 0 && k < nsh; k++)
        rc = parse_entries(sh[ix[k]].meta_text, sh[ix[k]].meta_len, &es[k]);
    const merged_meta m = {sh, ix, es, nsh, total, wall};
    const ob_shard_in *s0 = rc == 0 ? &sh[ix[0]] : NULL;
    for (const char *p = s0 ? s0->meta_text : NULL, *end = p ? p + s0->meta_len : NULL; p && p < end;) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const size_t len = nl ? (size_t)(nl - p) + 1 : (size_t)(end - p);
        entry e;
        if (parse_entry(p, len, &e) == 0) {
            const char *rest = e.val + e.vlen;
            write_line(f, &e, rest, (size_t)(p + len - rest), &m, &seen);
        } else {
            fwrite(p, 1, len, f);
        }
        p += len;
    }
    for (int k = 0; es && k < nsh; k++)
        free(es[k].v);
    free(es);
    free(ix);
    return rc == 0 && seen == 7 && !ferror(f) ? 0 : -1;
}
