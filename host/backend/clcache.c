/*
 * clcache.c - the OpenCL program binary cache (see clcache.h).
 *
 * File layout (native byte order: a cache belongs to one machine):
 *   "OBCLBIN1"          8 bytes, the format
 *   key length  u64, then the key text
 *   binary length u64
 *   checksum    u64     FNV-1a 64 over the key text and the binary
 *   the binary
 */
#include "host/backend/clcache.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "host/io/fsutil.h"
#include "host/io/outfile.h"
#include "host/run/shard.h"

static const char MAGIC[8] = {'O', 'B', 'C', 'L', 'B', 'I', 'N', '1'};

/* The cache directory: 0, or -1 (off, or no directory: why). */
static int cache_dir(char *dir, size_t len, char *why, size_t wlen)
{
    const char *env = getenv("OFFBENCH_CL_CACHE"), *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (env && strcmp(env, "off") == 0) {
        snprintf(why, wlen, "off (OFFBENCH_CL_CACHE=off)");
        return -1;
    }
    int n;
    if (env && *env)
        n = snprintf(dir, len, "%s", env);
    else if (xdg && xdg[0] == '/')
        n = snprintf(dir, len, "%s/offbench", xdg);
    else if (home && *home)
        n = snprintf(dir, len, "%s/.cache/offbench", home);
    else {
        snprintf(why, wlen, "off (no XDG_CACHE_HOME or HOME)");
        return -1;
    }
    if (n < 0 || (size_t)n >= len) {
        snprintf(why, wlen, "off (the cache directory's name is too long)");
        return -1;
    }
    return 0;
}

int ob_clcache_path(const char *key, char *path, size_t len, char *why, size_t wlen)
{
    char dir[4096];
    if (cache_dir(dir, sizeof dir, why, wlen) != 0)
        return -1;
    const uint64_t h = ob_fnv1a(OB_FNV_BASIS, key, strlen(key));
    const int n = snprintf(path, len, "%s/cl-%016llx.bin", dir, (unsigned long long)h);
    if (n < 0 || (size_t)n >= len) {
        snprintf(why, wlen, "off (the cache path is too long)");
        return -1;
    }
    return 0;
}

static int read_u64(FILE *f, uint64_t *v) { return fread(v, sizeof *v, 1, f) == 1 ? 0 : -1; }

unsigned char *ob_clcache_read(const char *path, const char *key, size_t *n, char *why, size_t wlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(why, wlen, "no cached binary (%s)", strerror(errno));
        return NULL;
    }
    char magic[8];
    uint64_t klen = 0, blen = 0, sum = 0;
    const size_t want = strlen(key);
    char *k = NULL;
    unsigned char *bin = NULL;
    const char *bad = NULL;
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, MAGIC, 8) != 0)
        bad = "not a cache file of this format";
    else if (read_u64(f, &klen) || klen != want || !(k = malloc(want + 1)) || fread(k, 1, want, f) != want ||
             memcmp(k, key, want) != 0)
        bad = "a binary for another source, device, driver or options";
    else if (read_u64(f, &blen) || read_u64(f, &sum) || blen == 0 || blen > ((uint64_t)1 << 31))
        bad = "a bad length";
    else if (!(bin = malloc(blen)) || fread(bin, 1, blen, f) != blen || fgetc(f) != EOF)
        bad = "truncated or too long";
    else if (ob_fnv1a(ob_fnv1a(OB_FNV_BASIS, key, want), bin, blen) != sum)
        bad = "a wrong checksum";
    fclose(f);
    free(k);
    if (bad) {
        snprintf(why, wlen, "cached binary ignored: %s", bad);
        free(bin);
        return NULL;
    }
    *n = (size_t)blen;
    return bin;
}

int ob_clcache_write(const char *path, const char *key, const unsigned char *bin, size_t n, char *why,
                     size_t wlen)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = '\0';
    if (slash && ob_mkdir_p(dir) != 0) {
        snprintf(why, wlen, "cannot create %s: %s", dir, strerror(errno));
        return -1;
    }
    ob_outfile o;  /* PATH.PID.tmp (processes share the cache), never through a link */
    ob_err err;
    if (ob_outfile_open(&o, path, 1, &err) != 0) {
        snprintf(why, wlen, "%s", err.msg);
        return -1;
    }
    FILE *f = o.f;
    const uint64_t klen = strlen(key), blen = n;
    const uint64_t sum = ob_fnv1a(ob_fnv1a(OB_FNV_BASIS, key, klen), bin, n);
    const int ok = fwrite(MAGIC, 1, 8, f) == 8 && fwrite(&klen, sizeof klen, 1, f) == 1 &&
                   fwrite(key, 1, klen, f) == klen && fwrite(&blen, sizeof blen, 1, f) == 1 &&
                   fwrite(&sum, sizeof sum, 1, f) == 1 && fwrite(bin, 1, n, f) == n;
    if (!ok) {
        snprintf(why, wlen, "cannot write %s: %s", o.tmp, strerror(errno));
        ob_outfile_discard(&o);
        return -1;
    }
    if (ob_outfile_commit(&o, 0, &err) != 0) {
        snprintf(why, wlen, "%s", err.msg);
        return -1;
    }
    return 0;
}
