/*
 * grow.c - room for one more element in a growable array (grow.h).
 */
#include "methods/core/grow.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int ob_grow(void *v, size_t *cap, size_t n, size_t elem, size_t first)
{
    if (n < *cap)
        return 0;
    const size_t nc = *cap ? 2 * *cap : first;
    if (nc <= *cap || nc > SIZE_MAX / elem)
        return -1;
    void *old;
    memcpy(&old, v, sizeof old);  /* v points at the caller's T *, of any T */
    void *nv = realloc(old, nc * elem);
    if (!nv)
        return -1;
    memcpy(v, &nv, sizeof nv);
    *cap = nc;
    return 0;
}
