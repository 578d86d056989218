/*
 * json.h - a strict JSON reader for one line of the external-method protocol
 * (docs/external-methods.md): the whole value as a small tree.
 *
 * Why not host/io/metajson.c: it flattens an object and keeps arrays as raw
 * text, while an answer is an array of objects holding arrays of number
 * pairs; and methods/ does not depend on host/.  Why not a library
 * (jansson): the grammar needed is small and its limits (depth, node count)
 * are the supervisor's, checked before anything is allocated per node.
 *
 * Strict RFC 8259 (no NaN, no comments, no trailing commas); numbers are
 * read with strtod (correctly rounded: a number printed with 17 significant
 * digits reads back to the same double) and must be finite.
 */
#ifndef OB_EXT_JSON_H
#define OB_EXT_JSON_H

#include <stddef.h>

typedef enum { OBJ_NULL, OBJ_BOOL, OBJ_NUM, OBJ_STR, OBJ_ARR, OBJ_OBJ } obj_type;

typedef struct obj_node {
    obj_type type;
    double num;                 /* OBJ_NUM; OBJ_BOOL: 0 or 1 */
    char *str;                  /* OBJ_STR: decoded (owned by the tree) */
    char *key;                  /* the member's key in an object, else NULL */
    int n;                      /* OBJ_ARR, OBJ_OBJ: number of children */
    struct obj_node **kids;
} obj_node;

enum { OBJ_MAX_DEPTH = 8, OBJ_MAX_NODES = 1 << 16 };

/* Purpose: parse text[0..len) as one JSON value (white space around it
 *          allowed).  Returns the tree, or NULL with the reason and the
 *          byte offset in err. */
obj_node *obj_parse(const char *text, size_t len, char *err, size_t errlen);
void obj_free(obj_node *v);

/* The member called key of object v, or NULL (also when v is no object). */
const obj_node *obj_get(const obj_node *v, const char *key);

#endif
