/*
 * commands.h - the subcommands of ./offbench.  Each takes the arguments after
 * the program name (argv[0] is the subcommand) and returns the exit status:
 * 0 success, 1 a run-time failure (e.g. output not writable), 2 bad input.
 */
#ifndef OB_COMMANDS_H
#define OB_COMMANDS_H

#include <stdio.h>

#include "host/backend/clrt.h"
#include "host/io/curvefile.h"
#include "host/run/options.h"

int ob_cmd_run(int argc, char **argv, int full_argc, char **full_argv);
int ob_cmd_list(int argc, char **argv);
int ob_cmd_bench(int argc, char **argv);

/* compare BASE NEW: 0 no regression, 1 regression, 2 error, 3 not comparable. */
int ob_cmd_compare(int argc, char **argv);
/* draw: an SVG of one job's approximation; trace: its error along the
 * parameter as CSV.  0, 1 (output not writable) or 2 (bad input). */
int ob_cmd_draw(int argc, char **argv);
int ob_cmd_trace(int argc, char **argv);

/* merge DIR... --out DIR: shards of one run into its results.csv (0; 2 a
 * refused set or bad input; 1 output not writable). */
int ob_cmd_merge(int argc, char **argv);

/* atlas [--out DIR]: the Offset Atlas against the exact offset degrees. */
int ob_cmd_atlas(int argc, char **argv);

int ob_cmd_tables(int argc, char **argv, int full_argc, char **full_argv);

/* Creates dir and its parents (mode 0777 & umask); 0 or -1 (errno set). */
int ob_mkdir_p(const char *dir);

/* Writes DIR/NAME through NAME.tmp and a rename (a reader never sees half a
 * file); writer returns 0 or -1.  Returns 0, or -1 after ob_error(). */
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

/* Makes this process the owner of run directory dir: an exclusive lock on
 * dir/.lock (which gets our pid), held until the process ends (the kernel
 * drops it however the process ends).  Returns 0 with the descriptor in
 * *fd (keep it open); -2 when another process holds it (err names dir and
 * the holder's pid); -1 when the file cannot be created or locked (err). */
int ob_lock_dir(const char *dir, int *fd, char *err, size_t errlen);

/* Loads the curves a run's options select: --curves FILE, then the --random
 * curves; the default set (datasets/ or the embedded copy) when neither is
 * given; checks that every --curve ID exists.  `where` names the source for
 * messages and meta.json.  Returns 0, or -1 after ob_error(). */
int ob_load_run_curves(const ob_run_opts *o, ob_curveset *set, char *where, size_t wlen);

/* Opens the backend o->backend asks for (the kernel built once, here) and
 * plugs it into o->driver; fills o->binfo.  auto falls back to the CPU and
 * says why in binfo.why_cpu.  Returns 0, or -1 after ob_error() when opencl
 * was required and is not available. */
int ob_open_backend(ob_run_opts *o, ob_cl **cl);

#endif
