/*
 * strmap.c - see strmap.h.  Linear probing in a table kept at most half
 * full; each slot holds the key's full hash, so a probe compares strings
 * only when the hashes agree.
 */
#include "host/io/strmap.h"

#include <stdlib.h>
#include <string.h>

struct ob_strmap_slot {
    uint64_t hash;
    size_t off;     /* the key in m->keys */
    size_t len;
    long val;       /* -1: an empty slot */
};

/* FNV-1a, then a final mix (MurmurHash3's fmix64) so that the low bits
 * that pick the slot depend on every byte of the key. */
static uint64_t hash_of(const char *s, size_t len)
{
    uint64_t h = 0xcbf29ce484222325ULL;
    for (size_t i = 0; i < len; i++)
        h = (h ^ (unsigned char)s[i]) * 0x100000001b3ULL;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    return h ^ (h >> 33);
}

/* The slot of key: where it is, or the empty slot where it would go. */
static struct ob_strmap_slot *find(const ob_strmap *m, const char *key, size_t len, uint64_t h)
{
    size_t i = (size_t)h & (m->cap - 1);
    for (;; i = (i + 1) & (m->cap - 1)) {
        struct ob_strmap_slot *s = &m->slot[i];
        if (s->val < 0 || (s->hash == h && s->len == len && memcmp(m->keys + s->off, key, len) == 0))
            return s;
    }
}

/* Doubles the table (first 16 slots: many maps are small) and puts every key back. */
static int rehash(ob_strmap *m)
{
    const size_t nc = m->cap ? 2 * m->cap : 16;
    struct ob_strmap_slot *old = m->slot, *ns;
    if (nc < m->cap || nc > SIZE_MAX / sizeof *ns || !(ns = malloc(nc * sizeof *ns)))
        return -1;
    for (size_t i = 0; i < nc; i++)
        ns[i].val = -1;
    const size_t oc = m->cap;
    m->slot = ns;
    m->cap = nc;
    for (size_t i = 0; i < oc; i++)
        if (old[i].val >= 0)
            *find(m, m->keys + old[i].off, old[i].len, old[i].hash) = old[i];
    free(old);
    return 0;
}

/* A copy of key at the end of m->keys; its offset in *off. */
static int keep_key(ob_strmap *m, const char *key, size_t len, size_t *off)
{
    if (m->kcap - m->klen < len + 1) {
        size_t nc = m->kcap ? m->kcap : 256;
        while (nc - m->klen < len + 1 && nc < SIZE_MAX / 2)
            nc *= 2;
        char *nk = nc - m->klen >= len + 1 ? realloc(m->keys, nc) : NULL;
        if (!nk)
            return -1;
        m->keys = nk;
        m->kcap = nc;
    }
    memcpy(m->keys + m->klen, key, len);
    m->keys[m->klen + len] = '\0';
    *off = m->klen;
    m->klen += len + 1;
    return 0;
}

long ob_strmap_putn(ob_strmap *m, const char *key, size_t len, long val)
{
    if (2 * (m->n + 1) > m->cap && rehash(m) != 0)
        return -2;
    const uint64_t h = hash_of(key, len);
    struct ob_strmap_slot *s = find(m, key, len, h);
    if (s->val >= 0)
        return s->val;
    size_t off;
    if (keep_key(m, key, len, &off) != 0)
        return -2;
    *s = (struct ob_strmap_slot){h, off, len, val < 0 ? 0 : val};
    m->n++;
    return -1;
}

long ob_strmap_put(ob_strmap *m, const char *key, long val)
{
    return ob_strmap_putn(m, key, strlen(key), val);
}

long ob_strmap_getn(const ob_strmap *m, const char *key, size_t len)
{
    if (!m || !m->cap)
        return -1;
    return find(m, key, len, hash_of(key, len))->val;
}

long ob_strmap_get(const ob_strmap *m, const char *key)
{
    return ob_strmap_getn(m, key, strlen(key));
}

void ob_strmap_free(ob_strmap *m)
{
    if (!m)
        return;
    free(m->slot);
    free(m->keys);
    memset(m, 0, sizeof *m);
}
