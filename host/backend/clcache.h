/*
 * clcache.h - the OpenCL program binary cache: a built program's device
 * binary kept on disk, keyed by everything that can change it (the kernel
 * source, the platform, device, driver and device versions, the build
 * options), so that a driver that takes minutes to build the kernel (NVIDIA's
 * took about three on an H200, issue 35) does it once per machine.
 *
 * Where: $OFFBENCH_CL_CACHE if set (a directory; "off" disables the cache),
 * else $XDG_CACHE_HOME/offbench, else $HOME/.cache/offbench; one file per
 * key, cl-<SHA-256 of the key>.bin.  A binary is native code the driver
 * runs, so the cache is trusted only as far as its directory and file are
 * the user's own: the directory (mode 0700 when made here) and the file
 * (0600) must be owned by the effective user, not writable by group or
 * others, and are opened without following links (a FIFO or device named
 * like a file is refused, never waited on).  A directory that fails that is
 * not used at all (the cache is off); a file that fails it, or whose key,
 * length or SHA-256 is wrong, is not loaded and is replaced after the build.
 * The checksum only catches corruption: whoever can write the file can
 * recompute it; the ownership checks are what stop a planted binary.
 * Files are written whole, through a temporary file in the same directory
 * and rename, so a reader never sees half of one.
 */
#ifndef OB_CLCACHE_H
#define OB_CLCACHE_H

#include <stddef.h>

/* Purpose: the cache file for key (a text naming everything the binary
 *          depends on) into path.
 * Returns: 0; -1 when the cache is off or there is no directory for it
 *          (why says which). */
int ob_clcache_path(const char *key, char *path, size_t len, char *why, size_t wlen);

/* The SHA-256 of p[0 .. n - 1] in lower-case hex, 64 digits and a NUL. */
enum { OB_SHA256_HEX = 65 };
void ob_sha256_hex(const void *p, size_t n, char hex[OB_SHA256_HEX]);

/* What ob_clcache_read found. */
typedef enum {
    OB_CLCACHE_HIT = 0,   /* the binary, verified */
    OB_CLCACHE_ABSENT,    /* no file yet (or no directory): build and store */
    OB_CLCACHE_BAD,       /* a file not to load (foreign, corrupt, a link, not the
                             user's own...): warn, build, replace it */
    OB_CLCACHE_UNSAFE     /* the directory is not the user's own: warn, cache off */
} ob_clcache_status;

/* Purpose: the binary stored for key in path, verified (the directory and
 *          file the user's own, the file's key equal to key, its length
 *          and SHA-256 right).
 * Outputs: on a hit a malloc'ed binary in *bin, its size in *n; otherwise
 *          *bin NULL and why says what was found, naming the path.
 * Returns: what was found. */
ob_clcache_status ob_clcache_read(const char *path, const char *key, unsigned char **bin, size_t *n, char *why,
                                  size_t wlen);

/* Purpose: store the binary for key in path (directories made as needed,
 *          the cache's own 0700), atomically, as a 0600 file; never into a
 *          directory that is not the user's own.
 * Returns: 0, or -1 with the reason in why. */
int ob_clcache_write(const char *path, const char *key, const unsigned char *bin, size_t n, char *why,
                     size_t wlen);

#endif
