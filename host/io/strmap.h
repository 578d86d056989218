/*
 * strmap.h - a map from strings to ints (hash table, open addressing).
 *
 * The readers use it wherever a key, id or name must be found among the
 * ones read before (duplicate keys of meta.json, curve ids, compare's
 * methods and values): a linear search there makes reading n items cost
 * n^2 (issue 36).  Put and get cost O(length of the key) on average.
 *
 * The map keeps its own copy of every key, so the caller's strings may
 * move or go (arrays that grow by realloc).  A zeroed map is empty and
 * ready; ob_strmap_free() makes it so again.
 */
#ifndef OB_STRMAP_H
#define OB_STRMAP_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    struct ob_strmap_slot *slot; /* cap slots, cap a power of two (or 0) */
    size_t cap;
    struct ob_strmap_entry *e;   /* the n keys in the order put (ecap) */
    size_t n, ecap;
    char *keys;                  /* the keys, NUL-terminated, back to back */
    size_t klen, kcap;
} ob_strmap;

/* Purpose: map key (len bytes, any bytes) to val unless key is there.
 * Returns: the value already mapped to key (key then keeps it), -1 when
 *          key was added, -2 out of memory (the map unchanged).
 *          val must be >= 0. */
long ob_strmap_putn(ob_strmap *m, const char *key, size_t len, long val);

/* As ob_strmap_putn, for a NUL-terminated key. */
long ob_strmap_put(ob_strmap *m, const char *key, long val);

/* The value of key (len bytes), or -1 when it is not in the map. */
long ob_strmap_getn(const ob_strmap *m, const char *key, size_t len);

/* The value of the NUL-terminated key, or -1. */
long ob_strmap_get(const ob_strmap *m, const char *key);

/* Frees everything; m is then an empty map.  Safe on a zeroed map, twice. */
void ob_strmap_free(ob_strmap *m);

#endif
