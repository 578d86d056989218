/*
 * metajson.c - see metajson.h.  A recursive-descent parser over the text;
 * every function returns 0 or -1 after writing "NAME:LINE: reason" once.
 */
#include "host/io/metajson.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/slurp.h"
#include "host/io/utf8.h"

enum { PATH_MAX_LEN = 512 };

typedef struct {
    const char *s, *end;
    const char *name;
    int line, depth;
    ob_err *err;
    ob_json_flat *out;
    char path[PATH_MAX_LEN];
} parser;

static int fail(parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(parser *p, const char *fmt, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return ob_fail(p->err, "%s:%d: %s", p->name, p->line, msg);
}

static void skip_ws(parser *p)
{
    while (p->s < p->end && (*p->s == ' ' || *p->s == '\t' || *p->s == '\n' || *p->s == '\r')) {
        if (*p->s == '\n')
            p->line++;
        p->s++;
    }
}

/* What the next character is, for messages. */
static const char *describe(parser *p, char *buf, size_t len)
{
    if (p->s >= p->end)
        return "the end of the file";
    unsigned char c = (unsigned char)*p->s;
    if (c >= 0x20 && c < 0x7f)
        snprintf(buf, len, "'%c'", c);
    else
        snprintf(buf, len, "byte 0x%02x", c);
    return buf;
}

static int add_entry(parser *p, const char *value, size_t vlen, ob_json_type type, int line)
{
    const long first = ob_strmap_put(&p->out->ix, p->path, p->out->n);
    if (first == -2)
        return fail(p, "out of memory");
    if (first >= 0)
        return fail(p, "key \"%s\" given twice (first on line %d)", p->path, p->out->v[first].line);
    if (p->out->n == p->out->cap) {
        int cap = p->out->cap ? 2 * p->out->cap : 64;
        ob_json_entry *nv = realloc(p->out->v, (size_t)cap * sizeof *nv);
        if (!nv)
            return fail(p, "out of memory");
        p->out->v = nv;
        p->out->cap = cap;
    }
    size_t plen = strlen(p->path);
    char *mem = malloc(plen + 1 + vlen + 1);
    if (!mem)
        return fail(p, "out of memory");
    memcpy(mem, p->path, plen + 1);
    memcpy(mem + plen + 1, value, vlen);
    mem[plen + 1 + vlen] = '\0';
    ob_json_entry *e = &p->out->v[p->out->n++];
    e->path = mem;
    e->value = mem + plen + 1;
    e->type = type;
    e->line = line;
    return 0;
}

static int hexval(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

static int read_hex4(parser *p, unsigned *cp)
{
    *cp = 0;
    for (int i = 0; i < 4; i++) {
        int h = p->s < p->end ? hexval(*p->s) : -1;
        if (h < 0)
            return fail(p, "\\u needs four hex digits");
        *cp = *cp * 16 + (unsigned)h;
        p->s++;
    }
    return 0;
}

static size_t put_utf8(char *o, unsigned cp)
{
    if (cp < 0x80) {
        o[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        o[0] = (char)(0xc0 | cp >> 6);
        o[1] = (char)(0x80 | (cp & 0x3f));
        return 2;
    }
    if (cp < 0x10000) {
        o[0] = (char)(0xe0 | cp >> 12);
        o[1] = (char)(0x80 | (cp >> 6 & 0x3f));
        o[2] = (char)(0x80 | (cp & 0x3f));
        return 3;
    }
    o[0] = (char)(0xf0 | cp >> 18);
    o[1] = (char)(0x80 | (cp >> 12 & 0x3f));
    o[2] = (char)(0x80 | (cp >> 6 & 0x3f));
    o[3] = (char)(0x80 | (cp & 0x3f));
    return 4;
}

/* The bytes from s up to the string's closing quote (or to end): the
 * decoded string is never longer. */
static size_t raw_len(const char *s, const char *end)
{
    const char *q = s;
    while (q < end && *q != '"')
        q += *q == '\\' && q + 1 < end ? 2 : 1;
    return (size_t)(q - s);
}

/* A string at p->s (on its opening quote), decoded into a malloc'd buffer
 * (*out, NULL when out is NULL: then only validated). */
static int parse_string(parser *p, char **out, size_t *outlen)
{
    p->s++; /* the quote */
    /* sized by this string, not the rest of the file: n strings must not
     * cost n times the file in allocations */
    char *buf = NULL, *o = NULL;
    if (out) {
        buf = o = malloc(raw_len(p->s, p->end) + 1);
        if (!buf)
            return fail(p, "out of memory");
    }
    for (;;) {
        if (p->s >= p->end) {
            free(buf);
            return fail(p, "unterminated string");
        }
        unsigned char c = (unsigned char)*p->s;
        if (c == '"') {
            p->s++;
            break;
        }
        if (c < 0x20) {
            free(buf);
            return fail(p, "control character (byte 0x%02x) in a string", c);
        }
        if (c != '\\') {
            int n = ob_utf8_len((const unsigned char *)p->s, (const unsigned char *)p->end);
            if (!n) {
                free(buf);
                return fail(p, "invalid UTF-8 in a string");
            }
            if (o) {
                memcpy(o, p->s, (size_t)n);
                o += n;
            }
            p->s += n;
            continue;
        }
        p->s++;
        char e = p->s < p->end ? *p->s : '\0';
        const char *simple = strchr("\"\\/bfnrt", e);
        if (e && simple) {
            static const char to[] = "\"\\/\b\f\n\r\t";
            if (o)
                *o++ = to[simple - "\"\\/bfnrt"];
            p->s++;
            continue;
        }
        if (e != 'u') {
            free(buf);
            return fail(p, "invalid escape in a string");
        }
        p->s++;
        unsigned cp;
        if (read_hex4(p, &cp)) {
            free(buf);
            return -1;
        }
        if (cp >= 0xd800 && cp <= 0xdbff) {
            unsigned lo;
            if (p->end - p->s < 2 || p->s[0] != '\\' || p->s[1] != 'u') {
                free(buf);
                return fail(p, "unpaired surrogate \\u%04x", cp);
            }
            p->s += 2;
            if (read_hex4(p, &lo)) {
                free(buf);
                return -1;
            }
            if (lo < 0xdc00 || lo > 0xdfff) {
                free(buf);
                return fail(p, "unpaired surrogate \\u%04x", cp);
            }
            cp = 0x10000 + ((cp - 0xd800) << 10) + (lo - 0xdc00);
        } else if (cp >= 0xdc00 && cp <= 0xdfff) {
            free(buf);
            return fail(p, "unpaired surrogate \\u%04x", cp);
        } else if (cp == 0) {
            free(buf);
            return fail(p, "\\u0000 in a string is not supported");
        }
        if (o)
            o += put_utf8(o, cp);
    }
    if (out) {
        *o = '\0';
        *out = buf;
        *outlen = (size_t)(o - buf);
    }
    return 0;
}

static int is_digit(parser *p)
{
    return p->s < p->end && *p->s >= '0' && *p->s <= '9';
}

static int parse_number(parser *p)
{
    if (p->s < p->end && *p->s == '-')
        p->s++;
    if (!is_digit(p))
        return fail(p, "malformed number");
    if (*p->s == '0') {
        p->s++;
        if (is_digit(p))
            return fail(p, "number with a leading zero");
    } else {
        while (is_digit(p))
            p->s++;
    }
    if (p->s < p->end && *p->s == '.') {
        p->s++;
        if (!is_digit(p))
            return fail(p, "malformed number: no digit after '.'");
        while (is_digit(p))
            p->s++;
    }
    if (p->s < p->end && (*p->s == 'e' || *p->s == 'E')) {
        p->s++;
        if (p->s < p->end && (*p->s == '+' || *p->s == '-'))
            p->s++;
        if (!is_digit(p))
            return fail(p, "malformed number: no digit in the exponent");
        while (is_digit(p))
            p->s++;
    }
    return 0;
}

static int parse_value(parser *p, int flatten);

/* An object at p->s (on '{'); flatten: record its members under p->path. */
static int parse_object(parser *p, int flatten)
{
    char what[32];
    int line = p->line;
    p->s++;
    skip_ws(p);
    if (p->s < p->end && *p->s == '}') {
        p->s++;
        return flatten && p->path[0] ? add_entry(p, "{}", 2, OB_JSON_OBJECT, line) : 0;
    }
    const size_t base = strlen(p->path);
    for (;;) {
        skip_ws(p);
        if (p->s >= p->end || *p->s != '"')
            return fail(p, "expected a key string, found %s", describe(p, what, sizeof what));
        char *key = NULL;
        size_t klen = 0;
        if (parse_string(p, flatten ? &key : NULL, &klen))
            return -1;
        if (flatten) {
            int fits = base + (base ? 1 : 0) + klen < PATH_MAX_LEN;
            if (fits)
                snprintf(p->path + base, PATH_MAX_LEN - base, "%s%s", base ? "." : "", key);
            free(key);
            if (!fits)
                return fail(p, "key path longer than %d characters", PATH_MAX_LEN - 1);
        }
        skip_ws(p);
        if (p->s >= p->end || *p->s != ':')
            return fail(p, "expected ':' after a key, found %s", describe(p, what, sizeof what));
        p->s++;
        if (parse_value(p, flatten))
            return -1;
        p->path[base] = '\0';
        skip_ws(p);
        if (p->s < p->end && *p->s == ',') {
            p->s++;
            continue;
        }
        if (p->s < p->end && *p->s == '}') {
            p->s++;
            return 0;
        }
        return fail(p, "expected ',' or '}' in an object, found %s", describe(p, what, sizeof what));
    }
}

static int parse_array(parser *p)
{
    char what[32];
    p->s++;
    skip_ws(p);
    if (p->s < p->end && *p->s == ']') {
        p->s++;
        return 0;
    }
    for (;;) {
        if (parse_value(p, 0))
            return -1;
        skip_ws(p);
        if (p->s < p->end && *p->s == ',') {
            p->s++;
            continue;
        }
        if (p->s < p->end && *p->s == ']') {
            p->s++;
            return 0;
        }
        return fail(p, "expected ',' or ']' in an array, found %s", describe(p, what, sizeof what));
    }
}

static int literal(parser *p, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(p->end - p->s) < n || memcmp(p->s, word, n) != 0)
        return -1;
    p->s += n;
    return 0;
}

/* Any value; flatten: record it under p->path (objects: their members). */
static int parse_value(parser *p, int flatten)
{
    char what[32];
    skip_ws(p);
    if (p->s >= p->end)
        return fail(p, "expected a value, found the end of the file");
    const char *start = p->s;
    const int line = p->line;
    int rc;
    switch (*p->s) {
    case '{':
    case '[':
        if (p->depth >= OB_JSON_MAX_DEPTH)
            return fail(p, "nested deeper than %d levels", OB_JSON_MAX_DEPTH);
        p->depth++;
        rc = *p->s == '{' ? parse_object(p, flatten) : parse_array(p);
        p->depth--;
        if (rc || !flatten || *start == '{')
            return rc;
        return add_entry(p, start, (size_t)(p->s - start), OB_JSON_ARRAY, line);
    case '"': {
        char *str = NULL;
        size_t len = 0;
        if (parse_string(p, flatten ? &str : NULL, &len))
            return -1;
        rc = flatten ? add_entry(p, str, len, OB_JSON_STRING, line) : 0;
        free(str);
        return rc;
    }
    case 't':
    case 'f':
    case 'n':
        if (literal(p, "true") == 0 || literal(p, "false") == 0)
            return flatten ? add_entry(p, start, (size_t)(p->s - start), OB_JSON_BOOL, line) : 0;
        if (literal(p, "null") == 0)
            return flatten ? add_entry(p, "null", 4, OB_JSON_NULL, line) : 0;
        break;
    default:
        if (*p->s == '-' || (*p->s >= '0' && *p->s <= '9')) {
            if (parse_number(p))
                return -1;
            return flatten ? add_entry(p, start, (size_t)(p->s - start), OB_JSON_NUMBER, line) : 0;
        }
        break;
    }
    return fail(p, "expected a value, found %s", describe(p, what, sizeof what));
}

void ob_json_free(ob_json_flat *f)
{
    if (!f)
        return;
    for (int i = 0; i < f->n; i++)
        free(f->v[i].path);
    free(f->v);
    ob_strmap_free(&f->ix);
    f->v = NULL;
    f->n = f->cap = 0;
}

int ob_json_flatten(const char *text, size_t len, const char *name, ob_json_flat *out, ob_err *err)
{
    parser p = {text, text + len, name, 1, 0, err, out, ""};
    memset(out, 0, sizeof *out);
    char what[32];
    if (len >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0)
        p.s += 3;
    skip_ws(&p);
    if (p.s >= p.end) {
        fail(&p, "empty file, expected a JSON object");
        return -1;
    }
    if (*p.s != '{') {
        fail(&p, "expected a JSON object, found %s", describe(&p, what, sizeof what));
        return -1;
    }
    if (parse_value(&p, 1)) {
        ob_json_free(out);
        return -1;
    }
    skip_ws(&p);
    if (p.s < p.end) {
        fail(&p, "text after the JSON object: %s", describe(&p, what, sizeof what));
        ob_json_free(out);
        return -1;
    }
    return 0;
}

int ob_json_load(const char *path, ob_json_flat *out, ob_err *err)
{
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    if (ob_slurp_max(path, OB_JSON_LIMIT, &text, &len, err))
        return -1;
    int rc = ob_json_flatten(text, len, path, out, err);
    free(text);
    return rc;
}

const ob_json_entry *ob_json_get(const ob_json_flat *f, const char *path)
{
    const long i = f ? ob_strmap_get(&f->ix, path) : -1;
    return i >= 0 && i < f->n ? &f->v[i] : NULL;
}

int ob_json_same(const ob_json_entry *a, const ob_json_entry *b)
{
    if (!a || !b)
        return !a && !b;
    if (a->type != b->type)
        return 0;
    if (a->type == OB_JSON_NUMBER) {
        double x = strtod(a->value, NULL), y = strtod(b->value, NULL);
        return x == y || (isnan(x) && isnan(y));
    }
    return strcmp(a->value, b->value) == 0;
}
