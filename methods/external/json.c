/*
 * json.c - the strict one-line JSON reader of json.h.
 */
#include "methods/external/json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *s, *end;
    int nodes;
    char *err;
    size_t errlen;
    const char *start;
} parser;

static obj_node *fail(parser *p, const char *what)
{
    if (p->err && !p->err[0])
        snprintf(p->err, p->errlen, "%s at byte %ld", what, (long)(p->s - p->start));
    return NULL;
}

static void skip_ws(parser *p)
{
    while (p->s < p->end && (*p->s == ' ' || *p->s == '\t' || *p->s == '\n' || *p->s == '\r'))
        p->s++;
}

static obj_node *node(parser *p, obj_type t)
{
    if (++p->nodes > OBJ_MAX_NODES)
        return fail(p, "more than 65536 values");
    obj_node *v = calloc(1, sizeof *v);
    if (!v)
        return fail(p, "out of memory");
    v->type = t;
    return v;
}

/* Four hex digits at p->s into *u: 0, or -1 when malformed. */
static int hex4(parser *p, unsigned *u)
{
    *u = 0;
    for (int i = 0; i < 4; i++, p->s++) {
        if (p->s >= p->end)
            return -1;
        const char c = *p->s;
        const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                      : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0)
            return -1;
        *u = *u * 16 + (unsigned)d;
    }
    return 0;
}

/* A \uXXXX escape as UTF-8 (surrogate pairs joined; \u0000 refused: the
 * strings are C strings); -1 when malformed. */
static int put_u(parser *p, char *o, size_t *k)
{
    unsigned u, lo;
    if (hex4(p, &u) != 0 || u == 0 || (u >= 0xdc00 && u < 0xe000))
        return -1;
    if (u >= 0xd800 && u < 0xdc00) {  /* a high surrogate: its low half follows */
        if (p->end - p->s < 6 || p->s[0] != '\\' || p->s[1] != 'u')
            return -1;
        p->s += 2;
        if (hex4(p, &lo) != 0 || lo < 0xdc00 || lo >= 0xe000)
            return -1;
        u = 0x10000 + ((u - 0xd800) << 10) + (lo - 0xdc00);
    }
    if (u < 0x80)
        o[(*k)++] = (char)u;
    else if (u < 0x800)
        o[(*k)++] = (char)(0xc0 | u >> 6), o[(*k)++] = (char)(0x80 | (u & 0x3f));
    else if (u < 0x10000)
        o[(*k)++] = (char)(0xe0 | u >> 12), o[(*k)++] = (char)(0x80 | (u >> 6 & 0x3f)),
        o[(*k)++] = (char)(0x80 | (u & 0x3f));
    else
        o[(*k)++] = (char)(0xf0 | u >> 18), o[(*k)++] = (char)(0x80 | (u >> 12 & 0x3f)),
        o[(*k)++] = (char)(0x80 | (u >> 6 & 0x3f)), o[(*k)++] = (char)(0x80 | (u & 0x3f));
    return 0;
}

/* A string after its opening quote, decoded into a fresh buffer. */
static char *string(parser *p)
{
    static const char esc[] = "\"\"\\\\//b\bf\fn\nr\rt\t";  /* pairs: the escape, its byte */
    char *o = malloc((size_t)(p->end - p->s) + 1);
    size_t k = 0;
    int bad = !o;
    while (!bad && p->s < p->end && *p->s != '"') {
        const unsigned char c = (unsigned char)*p->s++;
        if (c < 0x20) {
            bad = 1;
        } else if (c != '\\') {
            o[k++] = (char)c;
        } else if (p->s >= p->end) {
            bad = 1;
        } else {
            const char e = *p->s++;
            const char *map = e ? strchr(esc, e) : NULL;
            if (e == 'u')
                bad = put_u(p, o, &k) != 0;
            else if (map && (map - esc) % 2 == 0)
                o[k++] = map[1];
            else
                bad = 1;
        }
    }
    if (bad || p->s >= p->end || *p->s != '"') {
        fail(p, o ? "a malformed string" : "out of memory");
        free(o);
        return NULL;
    }
    p->s++;
    o[k] = '\0';
    return o;
}

static obj_node *number(parser *p)
{
    const char *a = p->s;
    if (p->s < p->end && *p->s == '-')
        p->s++;
    if (p->s < p->end && *p->s == '0')
        p->s++;
    else if (p->s < p->end && *p->s >= '1' && *p->s <= '9')
        while (p->s < p->end && *p->s >= '0' && *p->s <= '9')
            p->s++;
    else
        return fail(p, "not a JSON value");
    if (p->s < p->end && *p->s == '.') {
        if (++p->s >= p->end || *p->s < '0' || *p->s > '9')
            return fail(p, "a malformed number");
        while (p->s < p->end && *p->s >= '0' && *p->s <= '9')
            p->s++;
    }
    if (p->s < p->end && (*p->s == 'e' || *p->s == 'E')) {
        p->s++;
        if (p->s < p->end && (*p->s == '+' || *p->s == '-'))
            p->s++;
        if (p->s >= p->end || *p->s < '0' || *p->s > '9')
            return fail(p, "a malformed number");
        while (p->s < p->end && *p->s >= '0' && *p->s <= '9')
            p->s++;
    }
    char buf[64];
    if (p->s - a >= (long)sizeof buf)
        return fail(p, "a number of more than 63 characters");
    memcpy(buf, a, (size_t)(p->s - a));
    buf[p->s - a] = '\0';
    const double v = strtod(buf, NULL);
    if (!isfinite(v))
        return fail(p, "a number out of the double range");
    obj_node *n = node(p, OBJ_NUM);
    if (n)
        n->num = v;
    return n;
}

static obj_node *value(parser *p, int depth);

/* An array or object after its opening bracket. */
static obj_node *container(parser *p, int depth, int is_obj)
{
    obj_node *v = node(p, is_obj ? OBJ_OBJ : OBJ_ARR);
    int cap = 0;
    skip_ws(p);
    if (v && p->s < p->end && *p->s == (is_obj ? '}' : ']')) {
        p->s++;
        return v;
    }
    while (v) {
        char *key = NULL;
        skip_ws(p);
        if (is_obj && (p->s >= p->end || *p->s++ != '"' || !(key = string(p)))) {
            fail(p, "a member without a quoted key");
            break;
        }
        skip_ws(p);
        if (is_obj && (p->s >= p->end || *p->s++ != ':')) {
            free(key);
            fail(p, "a key without ':'");
            break;
        }
        obj_node *kid = value(p, depth + 1);
        if (v->n == cap) {
            obj_node **nk = realloc(v->kids, (size_t)(cap = cap ? 2 * cap : 4) * sizeof *nk);
            if (nk)
                v->kids = nk;
            else
                obj_free(kid), kid = fail(p, "out of memory");
        }
        if (!kid) {
            free(key);
            break;
        }
        kid->key = key;
        v->kids[v->n++] = kid;
        skip_ws(p);
        if (p->s < p->end && *p->s == ',') {
            p->s++;
            continue;
        }
        if (p->s < p->end && *p->s == (is_obj ? '}' : ']')) {
            p->s++;
            return v;
        }
        fail(p, is_obj ? "an object without '}'" : "an array without ']'");
        break;
    }
    obj_free(v);
    return NULL;
}

static obj_node *value(parser *p, int depth)
{
    skip_ws(p);
    if (depth > OBJ_MAX_DEPTH)
        return fail(p, "nested too deep");
    if (p->s >= p->end)
        return fail(p, "the value is missing");
    const char c = *p->s;
    static const char *const words[] = {"null", "false", "true"};
    for (int i = 0; i < 3; i++) {
        const size_t wl = strlen(words[i]);
        if ((size_t)(p->end - p->s) >= wl && memcmp(p->s, words[i], wl) == 0) {
            p->s += wl;
            obj_node *v = node(p, i ? OBJ_BOOL : OBJ_NULL);
            if (v)
                v->num = i == 2;
            return v;
        }
    }
    if (c == '{' || c == '[') {
        p->s++;
        return container(p, depth, c == '{');
    }
    if (c == '"') {
        p->s++;
        char *s = string(p);
        obj_node *v = s ? node(p, OBJ_STR) : NULL;
        if (v)
            v->str = s;
        else
            free(s);
        return v;
    }
    return number(p);
}

obj_node *obj_parse(const char *text, size_t len, char *err, size_t errlen)
{
    parser p = {text, text + len, 0, err, errlen, text};
    if (err && errlen)
        err[0] = '\0';
    obj_node *v = value(&p, 0);
    skip_ws(&p);
    if (v && p.s != p.end) {
        obj_free(v);
        return fail(&p, "text after the value");
    }
    return v;
}

void obj_free(obj_node *v)
{
    if (!v)
        return;
    for (int i = 0; i < v->n; i++)
        obj_free(v->kids[i]);
    free(v->kids);
    free(v->str);
    free(v->key);
    free(v);
}

const obj_node *obj_get(const obj_node *v, const char *key)
{
    if (!v || v->type != OBJ_OBJ)
        return NULL;
    for (int i = 0; i < v->n; i++)
        if (strcmp(v->kids[i]->key, key) == 0)
            return v->kids[i];
    return NULL;
}
