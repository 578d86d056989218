/*
 * clcache.c - the OpenCL program binary cache (see clcache.h).
 *
 * File layout (native byte order: a cache belongs to one machine):
 *   "OBCLBIN2"          8 bytes, the format
 *   key length  u64, then the key text
 *   binary length u64
 *   SHA-256             32 bytes, of the key text and then the binary
 *   the binary
 *
 * SHA-256 (Nettle, Debian's nettle-dev): names that cannot collide by
 * accident (the FNV-1a of format 1 could), and a checksum no weaker than
 * the name.  Every file is opened relative to a descriptor of the checked
 * directory, so the directory cannot be swapped between check and use.
 */
#include "host/backend/clcache.h"

#include <errno.h>
#include <fcntl.h>
#include <nettle/sha2.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/io/fsutil.h"

static const char MAGIC[8] = {'O', 'B', 'C', 'L', 'B', 'I', 'N', '2'};

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

/* SHA-256 of a then b (b may be NULL) into d. */
static void sha256_2(const void *a, size_t na, const void *b, size_t nb, uint8_t d[SHA256_DIGEST_SIZE])
{
    struct sha256_ctx ctx;
    sha256_init(&ctx);
    sha256_update(&ctx, na, a);
    if (b)
        sha256_update(&ctx, nb, b);
    sha256_digest(&ctx, SHA256_DIGEST_SIZE, d);
}

void ob_sha256_hex(const void *p, size_t n, char hex[OB_SHA256_HEX])
{
    uint8_t d[SHA256_DIGEST_SIZE];
    sha256_2(p, n, NULL, 0, d);
    for (int i = 0; i < SHA256_DIGEST_SIZE; i++)
        snprintf(hex + 2 * i, 3, "%02x", d[i]);
}

int ob_clcache_path(const char *key, char *path, size_t len, char *why, size_t wlen)
{
    char dir[4096], hex[OB_SHA256_HEX];
    if (cache_dir(dir, sizeof dir, why, wlen) != 0)
        return -1;
    ob_sha256_hex(key, strlen(key), hex);
    const int n = snprintf(path, len, "%s/cl-%s.bin", dir, hex);
    if (n < 0 || (size_t)n >= len) {
        snprintf(why, wlen, "off (the cache path is too long)");
        return -1;
    }
    return 0;
}

/* ---- trust: the user's own directory and file, never through a link ---- */

/* Why st is not to be trusted as a directory (dir) or a regular file, in
 * buf, or NULL: another type, another owner, writable by group or others. */
static const char *untrusted(const struct stat *st, int dir, char *buf, size_t len)
{
    if (dir ? !S_ISDIR(st->st_mode) : !S_ISREG(st->st_mode))
        return dir ? "not a directory" : "not a regular file";
    if (st->st_uid != geteuid())
        snprintf(buf, len, "owned by another user (uid %ld, this run's %ld)", (long)st->st_uid, (long)geteuid());
    else if (st->st_mode & (S_IWGRP | S_IWOTH))
        snprintf(buf, len, "writable by others (group or world: mode %04o)", (unsigned)(st->st_mode & 07777));
    else
        return NULL;
    return buf;
}

/* Split path into its directory (dir) and file name (*name, in path). */
static void split(const char *path, char *dir, size_t len, const char **name)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(dir, len, ".");
        *name = path;
    } else {
        snprintf(dir, len, "%.*s", slash == path ? 1 : (int)(slash - path), path);
        *name = slash + 1;
    }
}

/* Why opening at dfd/name (dfd AT_FDCWD: name a path) failed with errno e,
 * the way the user knows it: a link is named as one. */
static const char *open_failure(int dfd, const char *name, int e)
{
    struct stat st;
    if ((e == ELOOP || e == ENOTDIR || e == EMLINK) && fstatat(dfd, name, &st, AT_SYMLINK_NOFOLLOW) == 0 &&
        S_ISLNK(st.st_mode))
        return "a symbolic link";
    return strerror(e);
}

/* The cache directory opened and checked: its descriptor; -1 when it is
 * absent (why says so, *unsafe 0) or not to be trusted (*unsafe 1). */
static int open_dir(const char *dir, int *unsafe, char *why, size_t wlen)
{
    *unsafe = 0;
    const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    struct stat st;
    const char *bad = NULL;
    char buf[120];
    if (fd < 0 && errno == ENOENT) {
        snprintf(why, wlen, "no cached binary (%s: no such directory)", dir);
        return -1;
    }
    if (fd < 0)
        bad = open_failure(AT_FDCWD, dir, errno);
    else if (fstat(fd, &st) != 0)
        bad = strerror(errno);
    else
        bad = untrusted(&st, 1, buf, sizeof buf);
    if (!bad)
        return fd;
    if (fd >= 0)
        close(fd);
    *unsafe = 1;
    snprintf(why, wlen, "the cache directory %.3000s: %s", dir, bad);
    return -1;
}

/* name in the checked directory dfd, opened to read: a stream; NULL with
 * why, in buf or static (*absent 1: there is no such file). */
static FILE *open_file(int dfd, const char *name, int *absent, const char **why, char *buf, size_t len)
{
    /* O_NONBLOCK: a FIFO planted under the name opens at once (and is
     * refused as no regular file) instead of waiting for a writer */
    const int fd = openat(dfd, name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    struct stat st;
    *absent = fd < 0 && errno == ENOENT;
    if (fd < 0) {
        *why = open_failure(dfd, name, errno);
        return NULL;
    }
    *why = fstat(fd, &st) != 0 ? strerror(errno) : untrusted(&st, 0, buf, len);
    FILE *f = *why ? NULL : fdopen(fd, "rb");
    if (!f) {
        if (!*why)
            *why = strerror(errno);
        close(fd);
    }
    return f;
}

static int read_u64(FILE *f, uint64_t *v) { return fread(v, sizeof *v, 1, f) == 1 ? 0 : -1; }

/* The binary for key from f, checked: malloc'ed, or NULL with why. */
static unsigned char *read_verified(FILE *f, const char *key, size_t *n, const char **bad)
{
    char magic[8];
    uint8_t sum[SHA256_DIGEST_SIZE], want_sum[SHA256_DIGEST_SIZE];
    uint64_t klen = 0, blen = 0;
    const size_t want = strlen(key);
    char *k = NULL;
    unsigned char *bin = NULL;
    *bad = NULL;
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, MAGIC, 8) != 0)
        *bad = "not a cache file of this format";
    else if (read_u64(f, &klen) || klen != want || !(k = malloc(want + 1)) || fread(k, 1, want, f) != want ||
             memcmp(k, key, want) != 0)
        *bad = "a binary for another source, device, driver or options";
    else if (read_u64(f, &blen) || fread(sum, 1, sizeof sum, f) != sizeof sum || blen == 0 ||
             blen > ((uint64_t)1 << 31))
        *bad = "a bad length";
    else if (!(bin = malloc(blen)) || fread(bin, 1, blen, f) != blen || fgetc(f) != EOF)
        *bad = "truncated or too long";
    else if (sha256_2(key, want, bin, blen, want_sum), memcmp(sum, want_sum, sizeof sum) != 0)
        *bad = "a wrong checksum (SHA-256)";
    free(k);
    if (*bad) {
        free(bin);
        return NULL;
    }
    *n = (size_t)blen;
    return bin;
}

ob_clcache_status ob_clcache_read(const char *path, const char *key, unsigned char **bin, size_t *n, char *why,
                                  size_t wlen)
{
    char dir[4096], buf[120];
    const char *name, *bad = NULL;
    int unsafe, absent;
    *bin = NULL;
    split(path, dir, sizeof dir, &name);
    const int dfd = open_dir(dir, &unsafe, why, wlen);
    if (dfd < 0)
        return unsafe ? OB_CLCACHE_UNSAFE : OB_CLCACHE_ABSENT;
    FILE *f = open_file(dfd, name, &absent, &bad, buf, sizeof buf);
    close(dfd);
    if (f) {
        *bin = read_verified(f, key, n, &bad);
        fclose(f);
    }
    if (*bin)
        return OB_CLCACHE_HIT;
    if (absent)
        snprintf(why, wlen, "no cached binary (%.3000s)", path);
    else
        snprintf(why, wlen, "the cache file %.3000s: %s", path, bad);
    return absent ? OB_CLCACHE_ABSENT : OB_CLCACHE_BAD;
}

/* The cache directory for writing: made (0700, its parents as the umask
 * says) when absent, then checked as a reader checks it; its descriptor, or
 * -1 with why. */
static int dir_for_write(const char *dir, char *why, size_t wlen)
{
    char parent[4096];
    const char *name;
    split(dir, parent, sizeof parent, &name);
    if ((ob_mkdir_p(parent) != 0 || (mkdir(dir, 0700) != 0 && errno != EEXIST))) {
        snprintf(why, wlen, "cannot create %.3000s: %s", dir, strerror(errno));
        return -1;
    }
    int unsafe;
    return open_dir(dir, &unsafe, why, wlen);
}

/* The file f holds: the header and the binary.  0, or -1. */
static int write_all(FILE *f, const char *key, const unsigned char *bin, size_t n)
{
    const uint64_t klen = strlen(key), blen = n;
    uint8_t sum[SHA256_DIGEST_SIZE];
    sha256_2(key, klen, bin, n, sum);
    return fwrite(MAGIC, 1, 8, f) == 8 && fwrite(&klen, sizeof klen, 1, f) == 1 && fwrite(key, 1, klen, f) == klen &&
                   fwrite(&blen, sizeof blen, 1, f) == 1 && fwrite(sum, 1, sizeof sum, f) == sizeof sum &&
                   fwrite(bin, 1, n, f) == n
               ? 0
               : -1;
}

int ob_clcache_write(const char *path, const char *key, const unsigned char *bin, size_t n, char *why,
                     size_t wlen)
{
    char dir[4096], tmp[300];
    const char *name;
    split(path, dir, sizeof dir, &name);
    const int dfd = dir_for_write(dir, why, wlen);
    if (dfd < 0)
        return -1;
    /* NAME.PID.tmp: processes share the cache; whatever had that name (a
     * link included) is removed, and O_EXCL never writes through one */
    snprintf(tmp, sizeof tmp, "%.200s.%ld.tmp", name, (long)getpid());
    unlinkat(dfd, tmp, 0);
    const int fd = openat(dfd, tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    int rc = -1;
    if (!f)
        snprintf(why, wlen, "cannot create %.3000s/%s: %s", dir, tmp, strerror(errno));
    else if (write_all(f, key, bin, n) != 0 || fflush(f) != 0 || fsync(fd) != 0)
        snprintf(why, wlen, "cannot write %.3000s/%s: %s", dir, tmp, strerror(errno));
    else if (renameat(dfd, tmp, dfd, name) != 0)
        snprintf(why, wlen, "cannot rename %.3000s/%s: %s", dir, tmp, strerror(errno));
    else
        rc = 0;
    if (f)
        fclose(f);
    else if (fd >= 0)
        close(fd);
    if (rc != 0)
        unlinkat(dfd, tmp, 0);
    close(dfd);
    return rc;
}
