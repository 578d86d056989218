/*
 * cert_heap.h - a binary max-heap of parameter intervals keyed by a bound:
 * the work list of the certified bound's branch and bound (largest upper
 * bound first; a lower bound search keys by the negated bound).
 */
#ifndef OB_CERT_HEAP_H
#define OB_CERT_HEAP_H

#include <stddef.h>

typedef struct {
    double key;
    double a, b;    /* the interval */
    double ta, tb;  /* the feet of its ends on the other curve ... */
    double ka, kb;  /* ... and their speeds (cert_feet.h) */
    double lt, lk;  /* the line that gave key, t(u) = lt + lk (u - a), passed to the halves; lk NaN: none */
} ob_cert_item;

typedef struct {
    ob_cert_item *v;
    size_t n, cap;
} ob_cert_heap;

static inline void ob_cert_heap_push(ob_cert_heap *h, ob_cert_item it)
{
    size_t i = h->n++;
    while (i > 0 && h->v[(i - 1) / 2].key < it.key) {
        h->v[i] = h->v[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h->v[i] = it;
}

static inline ob_cert_item ob_cert_heap_pop(ob_cert_heap *h)
{
    const ob_cert_item top = h->v[0], last = h->v[--h->n];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= h->n)
            break;
        if (c + 1 < h->n && h->v[c + 1].key > h->v[c].key)
            c++;
        if (!(h->v[c].key > last.key))
            break;
        h->v[i] = h->v[c];
        i = c;
    }
    if (h->n)
        h->v[i] = last;
    return top;
}

#endif
