/*
 * fsutil.h - output directories and files a reader never sees half-written
 * (fsutil.c), and the checks that keep a run's outputs off its inputs.
 */
#ifndef OB_FSUTIL_H
#define OB_FSUTIL_H

#include <stddef.h>
#include <stdio.h>
#include "methods/core/err.h"

/* Creates dir and its parents (mode 0777 & umask); 0 or -1 (errno set). */
int ob_mkdir_p(const char *dir);

/* Writes DIR/NAME through NAME.tmp and a rename (a reader never sees half a
 * file; a link at either name is replaced, never followed: outfile.h);
 * writer returns 0 or -1.  Returns 0, or -1 after ob_error(). */
int ob_write_atomically(const char *dir, const char *name, int (*writer)(FILE *, void *), void *ctx);

/* One file of a set written together (ob_write_set_atomically). */
typedef struct {
    const char *name;
    int (*writer)(FILE *, void *);
    void *ctx;
} ob_out_file;

/* Writes DIR/NAME of every file through NAME.tmp: all temporaries are
 * written and fsync'ed first, and only then renamed, in the order given
 * (callers give results.csv last).  A write that fails (disk full, a file
 * size limit) leaves every file as it was.  A crash between the renames
 * (no write is left then, only the renames) can leave new companions
 * beside the old results.csv, never a new results.csv beside old ones.
 * A link at any of the names is replaced, never followed (outfile.h).
 * Returns 0, or -1 after ob_error(). */
int ob_write_set_atomically(const char *dir, const ob_out_file *files, size_t n);

/* Refuses an output that is, or holds, an input (compared by device and
 * inode, so other spellings, links and "a/../a" are caught): for a file
 * out, an input that is the same file (when out does not exist yet: the
 * same directory and name); for a directory out (out_is_dir, or out is an
 * existing directory), an input that is the directory or lies anywhere
 * below it.  NULL entries of in are skipped.  Returns 0, or -1 after
 * ob_error() naming both paths (the command exits 2). */
int ob_check_out_not_input(const char *cmd, const char *out, int out_is_dir, const char *const *in, size_t nin);

/* Purpose: as ob_check_out_not_input for a directory given by option opt
 *          (e.g. "--export"): refuses a dir that is, or holds, an input;
 *          the message names opt.
 * Returns: 0, or -1 after ob_error(). */
int ob_check_dir_not_input(const char *cmd, const char *opt, const char *dir, const char *const *in, size_t nin);

/* Purpose: as ob_check_out_not_input for a file given by option opt
 *          (e.g. "--per-piece"): refuses a file that is an input, however
 *          spelled; the message names opt.
 * Returns: 0, or -1 after ob_error(). */
int ob_check_file_not_input(const char *cmd, const char *opt, const char *out, const char *const *in, size_t nin);

/* Purpose: path made absolute (the current directory before a relative
 *          one; nothing resolved), for records such as meta.json.
 * Returns: 0 with buf filled; -1 when it does not fit or the current
 *          directory cannot be read (buf then holds path as given). */
int ob_abs_path(const char *path, char *buf, size_t len);

/* Makes this process the owner of run directory dir: an exclusive lock on
 * dir/.lock (which gets our pid), held until the process ends (the kernel
 * drops it however the process ends).  Returns 0 with the descriptor in
 * *fd (keep it open); -2 when another process holds it (err names dir and
 * the holder's pid) or dir/.lock is a symbolic or hard link (refused, never
 * followed: err names it); -1 when the file cannot be created or locked. */
int ob_lock_dir(const char *dir, int *fd, ob_err *err);

/* How every command that writes a run directory (run, merge) takes it:
 * creates dir and its parents when create is set, then takes its lock
 * (ob_lock_dir), saying why not (ob_error, prefixed "cmd: --out").  Returns
 * 0 with the lock's descriptor in *fd (keep it open until the last file is
 * written); else the exit status: 2 when another process holds the lock
 * (the message names the lock file and the holder's pid), 1 when dir
 * cannot be created or locked. */
int ob_take_run_dir(const char *cmd, const char *dir, int create, int *fd);

#endif

