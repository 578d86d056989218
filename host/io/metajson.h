/*
 * metajson.h - a small, strict JSON reader for meta.json: it flattens the
 * top-level object into (key path, value text) pairs, e.g.
 *     {"opencl": {"device": "x"}, "method_params": {"tiller.k": 2}}
 * gives "opencl.device" = x and "method_params.tiller.k" = 2.  Arrays are
 * validated but kept as their raw text ("[\"a\", 1]"); an empty object is kept
 * as one entry "{}" so that its key exists.
 *
 * Strict: RFC 8259 grammar (no comments, no trailing commas, no single
 * quotes, no leading zeros, no NaN), a top-level object, UTF-8 strings with
 * valid escapes (\u0000 is refused), at most OB_JSON_MAX_DEPTH nested
 * containers, no key path given twice.
 */
#ifndef OB_METAJSON_H
#define OB_METAJSON_H

#include <stddef.h>
#include "host/io/strmap.h"
#include "methods/core/err.h"

enum { OB_JSON_MAX_DEPTH = 32 };

typedef enum {
    OB_JSON_STRING, /* value: the decoded string */
    OB_JSON_NUMBER, /* value: the number's text as written */
    OB_JSON_BOOL,   /* "true" / "false" */
    OB_JSON_NULL,   /* "null" */
    OB_JSON_ARRAY,  /* the raw text, brackets included */
    OB_JSON_OBJECT  /* "{}": an empty object */
} ob_json_type;

typedef struct {
    char *path;         /* keys joined by '.' (owned, one allocation with value) */
    char *value;
    ob_json_type type;
    int line;           /* line of the value in the file */
} ob_json_entry;

typedef struct {
    ob_json_entry *v;
    int n, cap;
    ob_strmap ix;       /* key path -> index in v: look-ups and the duplicate
                           check in constant time, not a scan of v */
} ob_json_flat;

/* Purpose: parse text[0..len) (a file named `name` for messages) and
 *          flatten it into *out, entries in file order.
 * Errors:  returns 0; -1 with "NAME:LINE: reason" in err->msg (malformed JSON, too
 *          deep, a duplicate key path, out of memory).  *out is always left
 *          safe for ob_json_free() (and empty after an error). */
int ob_json_flatten(const char *text, size_t len, const char *name, ob_json_flat *out, ob_err *err);

/* Purpose: read and flatten the file at path.
 * Errors:  as ob_json_flatten, plus "PATH: cannot open: reason". */
/* The largest meta.json ob_json_load reads (64 MiB; a run's is a few KiB). */
#define OB_JSON_LIMIT ((size_t)64 << 20)
int ob_json_load(const char *path, ob_json_flat *out, ob_err *err);

/* The entry of a key path, or NULL (a hash look-up: callers may ask for
 * every key of a large file). */
const ob_json_entry *ob_json_get(const ob_json_flat *f, const char *path);

/* 1 when a and b are the same value: numbers compared as doubles (1e1 ==
 * 10), everything else by type and text; two NULL entries are equal. */
int ob_json_same(const ob_json_entry *a, const ob_json_entry *b);

/* Always safe to call (also twice, or on a zeroed set). */
void ob_json_free(ob_json_flat *f);

#endif
