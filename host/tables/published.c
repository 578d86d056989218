/*
 * published.c - see published.h.
 */
#include "host/tables/published.h"
#include "host/io/datadir.h"
#include "host/io/slurp.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct ob_embedded_file {
    const char *name;
    const char *text;
};
extern const struct ob_embedded_file ob_embedded_published[];

enum { MAX_FIELDS = 24, FIELD_LEN = 128 };

/* Splits one CSV record starting at *p (RFC 4180 quoting; a record ends at a
 * newline outside quotes).  Returns the field count, -1 for an unterminated
 * quote, -2 for a field too long, -3 for too many fields. */
static int split_record(const char **p, const char *end, char f[MAX_FIELDS][FIELD_LEN])
{
    const char *s = *p;
    int nf = 0;
    for (;;) {
        if (nf == MAX_FIELDS)
            return -3;
        size_t k = 0;
        char *out = f[nf++];
        if (s < end && *s == '"') {
            s++;
            for (;;) {
                if (s >= end)
                    return -1;
                if (*s == '"') {
                    if (s + 1 < end && s[1] == '"') {
                        s += 2;
                        if (k + 1 >= FIELD_LEN)
                            return -2;
                        out[k++] = '"';
                        continue;
                    }
                    s++;
                    break;
                }
                if (k + 1 >= FIELD_LEN)
                    return -2;
                out[k++] = *s++;
            }
        }
        while (s < end && *s != ',' && *s != '\n' && *s != '\r') {
            if (k + 1 >= FIELD_LEN)
                return -2;
            out[k++] = *s++;
        }
        out[k] = '\0';
        if (s < end && *s == ',') {
            s++;
            continue;
        }
        if (s < end && *s == '\r')
            s++;
        if (s < end && *s == '\n')
            s++;
        *p = s;
        return nf;
    }
}

/* A number field: empty gives NAN (when allowed); else it must parse whole
 * and be finite. */
static int parse_num(const char *t, int allow_empty, double *v)
{
    if (!*t) {
        *v = NAN;
        return allow_empty ? 0 : -1;
    }
    char *e;
    errno = 0;
    *v = strtod(t, &e);
    return (*e || e == t || errno == ERANGE || !isfinite(*v)) ? -1 : 0;
}

static int copy_field(char *dst, size_t cap, const char *src)
{
    if (strlen(src) >= cap)
        return -1;
    strcpy(dst, src);
    return 0;
}

int ob_pub_parse(const char *text, size_t len, const char *name, ob_pub_set *s, ob_err *err)
{
    static const char *cols[] = {"source", "table", "curve", "d", "tol", "method", "label", "value", "unit"};
    enum { NCOL = 9 };
    int at[NCOL];
    char f[MAX_FIELDS][FIELD_LEN];
    const char *p = text, *end = text + len;
    int line = 1, nhead = 0;
    s->v = NULL;
    s->n = 0;
    /* header */
    nhead = split_record(&p, end, f);
    if (nhead <= 0) {
        ob_fail(err, "%s:1: %s", name, nhead == 0 ? "empty file" : "malformed header");
        return -1;
    }
    for (int c = 0; c < NCOL; c++) {
        at[c] = -1;
        for (int i = 0; i < nhead; i++)
            if (strcmp(f[i], cols[c]) == 0)
                at[c] = i;
        if (at[c] < 0) {
            ob_fail(err, "%s:1: no column '%s' in the header", name, cols[c]);
            return -1;
        }
    }
    int cap = 0;
    while (p < end) {
        line++;
        if (*p == '\n' || *p == '\r') { /* blank line */
            p += (*p == '\r' && p + 1 < end && p[1] == '\n') ? 2 : 1;
            continue;
        }
        int nf = split_record(&p, end, f);
        static const char *why[] = {"", "unterminated quote", "field longer than 127 characters",
                                    "more than 24 fields"};
        if (nf < 0) {
            ob_fail(err, "%s:%d: %s", name, line, why[-nf]);
            goto fail;
        }
        if (nf != nhead) {
            ob_fail(err, "%s:%d: %d fields, the header has %d", name, line, nf, nhead);
            goto fail;
        }
        if (s->n == cap) {
            cap = cap ? 2 * cap : 256;
            ob_pub_cell *nv = realloc(s->v, (size_t)cap * sizeof *nv);
            if (!nv) {
                ob_fail(err, "%s:%d: out of memory", name, line);
                goto fail;
            }
            s->v = nv;
        }
        ob_pub_cell *c = &s->v[s->n];
        memset(c, 0, sizeof *c);
        c->line = line;
        const char *bad = NULL;
        if (copy_field(c->source, sizeof c->source, f[at[0]]) || copy_field(c->table, sizeof c->table, f[at[1]]) ||
            copy_field(c->curve, sizeof c->curve, f[at[2]]) || copy_field(c->d_text, sizeof c->d_text, f[at[3]]) ||
            copy_field(c->tol_text, sizeof c->tol_text, f[at[4]]) ||
            copy_field(c->method, sizeof c->method, f[at[5]]) || copy_field(c->label, sizeof c->label, f[at[6]]) ||
            copy_field(c->value_text, sizeof c->value_text, f[at[7]]) ||
            copy_field(c->unit, sizeof c->unit, f[at[8]]))
            bad = "a field is too long for its column";
        else if (!c->source[0] || !c->table[0] || !c->curve[0] || !c->method[0])
            bad = "source, table, curve and method must not be empty";
        else if (parse_num(c->d_text, 1, &c->d))
            bad = "d is not a finite number";
        else if (parse_num(c->tol_text, 1, &c->tol) || (c->tol_text[0] && !(c->tol > 0)))
            bad = "tol is not a positive number";
        else if (parse_num(c->value_text, 0, &c->value) || c->value < 0)
            bad = "value is not a finite number >= 0";
        else if (strcmp(c->unit, "ctrl_points") != 0 && strcmp(c->unit, "max_err") != 0)
            bad = "unit must be ctrl_points or max_err";
        else if (strcmp(c->unit, "ctrl_points") == 0 && !c->tol_text[0])
            bad = "a ctrl_points figure needs a tolerance";
        if (bad) {
            ob_fail(err, "%s:%d: %s", name, line, bad);
            goto fail;
        }
        s->n++;
    }
    if (s->n == 0) {
        ob_fail(err, "%s: no figures", name);
        goto fail;
    }
    return 0;
fail:
    ob_pub_free(s);
    return -1;
}

static int load_file(const char *path, ob_pub_set *s, ob_err *err)
{
    char *buf;
    size_t n;
    if (ob_slurp(path, &buf, &n, err) != 0)
        return -1;
    int rc = ob_pub_parse(buf, n, path, s, err);
    free(buf);
    if (rc == 0)
        snprintf(s->where, sizeof s->where, "%.500s", path);
    return rc;
}

int ob_pub_load(ob_pub_set *s, ob_err *err)
{
    static const char rel[] = "results/published/published_tables.csv";
    char path[4200];
    s->v = NULL;
    s->n = 0;
    if (ob_find_tree_file(rel, "OFFBENCH_PUBLISHED", path, sizeof path) == 0)
        return load_file(path, s, err);
    const struct ob_embedded_file *e = &ob_embedded_published[0];
    if (!e->name) {
        ob_fail(err, "no published figures: %s not found and none compiled in", rel);
        return -1;
    }
    int rc = ob_pub_parse(e->text, strlen(e->text), e->name, s, err);
    if (rc == 0)
        snprintf(s->where, sizeof s->where, "embedded copy of %s", e->name);
    return rc;
}

void ob_pub_free(ob_pub_set *s)
{
    if (!s)
        return;
    free(s->v);
    s->v = NULL;
    s->n = 0;
}
