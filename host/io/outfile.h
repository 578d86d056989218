/*
 * outfile.h - every file offbench writes, opened so that a link planted at
 * its name can never carry the write to a file elsewhere (outfile.c).
 *
 * Two ways, one rule ("never through a link"):
 * - A file written afresh (results.csv, meta.json, exports, reports,
 *   figures, the journal of a new run, the binary cache) goes to a new
 *   temporary PATH.tmp, created with O_CREAT|O_EXCL|O_NOFOLLOW after
 *   removing whatever had that name, and is then renamed over PATH.  rename
 *   replaces a symbolic or hard link at PATH itself, never its target.  A
 *   PATH that is, or leads to, no regular file (a directory, /dev/null,
 *   /dev/stdout) is refused: the rename would replace that node.
 * - A file updated in place (a run directory's .lock, the journal that
 *   --resume continues) is opened with O_NOFOLLOW and must be a regular
 *   file of one name: a link there is refused, naming the path.
 */
#ifndef OB_OUTFILE_H
#define OB_OUTFILE_H

#include <stdio.h>
#include "methods/core/err.h"

/* A file being written afresh: f writes to tmp, which becomes path. */
typedef struct {
    FILE *f;
    char path[4200];
    char tmp[4240];
} ob_outfile;

/* Purpose: start writing path afresh through a new temporary file in the
 *          same directory: PATH.tmp, or PATH.PID.tmp when per_process (for a
 *          file several processes may write at once, the binary cache).
 *          Whatever was at the temporary name (a stale file, a link) is
 *          removed, not followed.  path itself is not touched yet.
 * Returns: 0 with o->f open; -1 with "TMP: cannot write: reason" in err,
 *          or "PATH: is a directory" / "PATH: not a regular file" when path
 *          is, or is a link to, something other than a regular file (a
 *          device, a FIFO: renaming over it would replace it). */
int ob_outfile_open(ob_outfile *o, const char *path, int per_process, ob_err *err);

/* Purpose: flush (fsync too when sync) and close o->f.
 * Returns: 0; -1 with "TMP: write failed" in err, the temporary removed. */
int ob_outfile_finish(ob_outfile *o, int sync, ob_err *err);

/* Purpose: rename the temporary over path (o->f may still be open: the
 *          journal goes on writing to it).  A link at path is replaced.
 * Returns: 0; -1 with "TMP: cannot rename to PATH: reason" in err, the
 *          temporary removed. */
int ob_outfile_publish(ob_outfile *o, ob_err *err);

/* Purpose: finish, then publish (the usual end of a file).  0 or -1 (err). */
int ob_outfile_commit(ob_outfile *o, int sync, ob_err *err);

/* Purpose: give up: close o->f if open and remove the temporary (path is
 *          left as it was).  Safe on a zeroed, finished or published o. */
void ob_outfile_discard(ob_outfile *o);

/* Purpose: open an existing file to update it in place (flags: O_RDWR or
 *          O_WRONLY, optionally O_CREAT, O_APPEND), never through a link.
 * Returns: a descriptor (close-on-exec); -2 when path is a symbolic link or
 *          a file of more than one name (a hard link), with err naming path
 *          and saying to remove it; -1 for any other failure (err: "PATH:
 *          cannot open: reason", or "PATH: not a regular file"). */
int ob_open_in_place(const char *path, int flags, ob_err *err);

#endif
