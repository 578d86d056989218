/*
 * grow.h - room for one more element in a growable array.
 */
#ifndef OB_GROW_H
#define OB_GROW_H

#include <stddef.h>

/* Purpose: make room for element n of the array *v of *cap elements of
 *          elem bytes each: when n == *cap, double the capacity (first
 *          elements the first time) with realloc.
 * Output:  *v and *cap updated when it grew.
 * Returns: 0, or -1 when out of memory or the size would overflow (*v and
 *          *cap then unchanged, the array still valid).
 * Method:  doubling keeps n pushes O(n) in all. */
int ob_grow(void *v, size_t *cap, size_t n, size_t elem, size_t first);

#endif
