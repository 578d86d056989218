/*
 * strmap.c - see strmap.h.  Linear probing in a table kept at most half
 * full.  A slot is 8 bytes (32 bits of the key's hash and the number of
 * its entry), so that the table, read at random, stays small for the
 * caches; the entries (full hash, key, value) lie in the order put, and a
 * probe reads one only when the 32 hash bits agree.
 */
#include "host/io/strmap.h"

#include <stdlib.h>
#include <string.h>

struct ob_strmap_slot {
    uint32_t tag;   /* the hash's high 32 bits */
    uint32_t e;     /* 1 + the entry's index; 0: an empty slot */
};

struct ob_strmap_entry {
    uint64_t hash;
    size_t off, len;  /* the key in m->keys */
    long val;
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
    const uint32_t tag = (uint32_t)(h >> 32);
    for (size_t i = (size_t)h & (m->cap - 1);; i = (i + 1) & (m->cap - 1)) {
        struct ob_strmap_slot *s = &m->slot[i];
        if (!s->e)
            return s;
        const struct ob_strmap_entry *e = &m->e[s->e - 1];
        if (s->tag == tag && e->hash == h && e->len == len && memcmp(m->keys + e->off, key, len) == 0)
            return s;
    }
}

/* Doubles the table (first 16 slots: many maps are small) and puts every
 * entry back. */
static int rehash(ob_strmap *m)
{
    const size_t nc = m->cap ? 2 * m->cap : 16;
    struct ob_strmap_slot *ns;
    if (nc < m->cap || nc > SIZE_MAX / sizeof *ns || !(ns = calloc(nc, sizeof *ns)))
        return -1;
    free(m->slot);
    m->slot = ns;
    m->cap = nc;
    for (size_t i = 0; i < m->n; i++) {
        size_t k = (size_t)m->e[i].hash & (nc - 1);
        while (ns[k].e)
            k = (k + 1) & (nc - 1);
        ns[k] = (struct ob_strmap_slot){(uint32_t)(m->e[i].hash >> 32), (uint32_t)(i + 1)};
    }
    return 0;
}

/* Room for n more bytes in *buf (of *cap, *used used), doubling; 0 or -1. */
static int room(void *buf, size_t *cap, size_t used, size_t n, size_t first)
{
    if (*cap - used >= n)
        return 0;
    size_t nc = *cap ? *cap : first;
    while (nc - used < n && nc < SIZE_MAX / 2)
        nc *= 2;
    void *old;
    memcpy(&old, buf, sizeof old);
    void *nb = nc - used >= n ? realloc(old, nc) : NULL;
    if (!nb)
        return -1;
    memcpy(buf, &nb, sizeof nb);
    *cap = nc;
    return 0;
}

long ob_strmap_putn(ob_strmap *m, const char *key, size_t len, long val)
{
    const size_t esz = sizeof *m->e;
    if (m->n >= UINT32_MAX - 1 || (2 * (m->n + 1) > m->cap && rehash(m) != 0))
        return -2;
    const uint64_t h = hash_of(key, len);
    struct ob_strmap_slot *s = find(m, key, len, h);
    if (s->e)
        return m->e[s->e - 1].val;
    size_t ebytes = m->ecap * esz;
    if (room(&m->e, &ebytes, m->n * esz, esz, 16 * esz) || room(&m->keys, &m->kcap, m->klen, len + 1, 256))
        return -2;
    m->ecap = ebytes / esz;
    memcpy(m->keys + m->klen, key, len);
    m->keys[m->klen + len] = '\0';
    m->e[m->n] = (struct ob_strmap_entry){h, m->klen, len, val < 0 ? 0 : val};
    m->klen += len + 1;
    *s = (struct ob_strmap_slot){(uint32_t)(h >> 32), (uint32_t)(++m->n)};
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
    const struct ob_strmap_slot *s = find(m, key, len, hash_of(key, len));
    return s->e ? m->e[s->e - 1].val : -1;
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
    free(m->e);
    free(m->keys);
    memset(m, 0, sizeof *m);
}
