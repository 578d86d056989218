/*
 * clcache.h - the OpenCL program binary cache: a built program's device
 * binary kept on disk, keyed by everything that can change it (the kernel
 * source, the platform, device, driver and device versions, the build
 * options), so that a driver that takes minutes to build the kernel (NVIDIA's
 * took about three on an H200, issue 35) does it once per machine.
 *
 * Where: $OFFBENCH_CL_CACHE if set (a directory; "off" disables the cache),
 * else $XDG_CACHE_HOME/offbench, else $HOME/.cache/offbench; one file per
 * key, cl-<hash>.bin.  A file is used only when its whole key matches and its
 * checksum holds: a corrupt, truncated or foreign file is ignored (and
 * replaced after the build), never trusted.  Files are written whole, through
 * a temporary file and rename, so a reader never sees half of one.
 */
#ifndef OB_CLCACHE_H
#define OB_CLCACHE_H

#include <stddef.h>

/* Purpose: the cache file for key (a text naming everything the binary
 *          depends on) into path.
 * Returns: 0; -1 when the cache is off or there is no directory for it
 *          (why says which). */
int ob_clcache_path(const char *key, char *path, size_t len, char *why, size_t wlen);

/* Purpose: the binary stored for key in path, verified (the file's key equal
 *          to key, its length and checksum right).
 * Returns: a malloc'ed binary with its size in *n, or NULL (absent, corrupt
 *          or foreign: why says which). */
unsigned char *ob_clcache_read(const char *path, const char *key, size_t *n, char *why, size_t wlen);

/* Purpose: store the binary for key in path (directories made as needed),
 *          atomically.
 * Returns: 0, or -1 with the reason in why. */
int ob_clcache_write(const char *path, const char *key, const unsigned char *bin, size_t n, char *why,
                     size_t wlen);

#endif
