/*
 * export_dir.h - what `--export DIR` may hold, and the rule that keeps it
 * this run's (README "Export and measure", "The export directory"):
 *
 * - The names the export owns: STEM.json, STEM.curves, STEM.dxf, STEM.svg
 *   (STEM of export.h's pattern CURVE__dD__METHOD__tolT), the same with
 *   ".tmp" (a write cut short), index.csv and index.shardK-of-N.csv.  No
 *   other name in DIR is ever touched.
 * - A plain run (and draw, trace) leaves DIR holding exactly its own files:
 *   its index.csv, and the four files of each of its jobs that has an
 *   approximation; owned names of any other job (an earlier run's, a job
 *   that now fails or is skipped) and every shard index are removed.
 * - A shard (--shard K/N) writes index.shardK-of-N.csv, never index.csv, and
 *   removes only the files of its own jobs that have no approximation now
 *   (and a stale index.csv): the other shards' jobs are theirs.  `merge`
 *   combines the shard indexes into index.csv and then applies the plain
 *   run's rule for the whole run (the shard indexes of this N stay).
 * - A STEM.EXT.tmp in the rule's scope always goes: it is a write cut short
 *   (the writers make and rename their own).
 * - Removing a name never follows it: a symbolic link is removed itself,
 *   its target untouched; directories and other non-files are left alone.
 * - DIR may not be a directory curves are loaded from ($OFFBENCH_DATA, the
 *   datasets/ directory the program was built from) nor hold the --curves
 *   file: the exported .curves would become input.
 */
#ifndef OB_EXPORT_DIR_H
#define OB_EXPORT_DIR_H

#include <stddef.h>

#include "host/io/strmap.h"
#include "methods/core/err.h"

/* What a directory entry's name is to the export. */
typedef enum {
    OB_XNAME_OTHER = 0,    /* not the export's: never touched */
    OB_XNAME_STEM,         /* STEM.EXT or STEM.EXT.tmp */
    OB_XNAME_INDEX,        /* index.csv */
    OB_XNAME_SHARD_INDEX,  /* index.shardK-of-N.csv */
} ob_xname;

/* Purpose: classify a directory entry's name.
 * Inputs:  name (no '/'); stem, len: where the STEM of an OB_XNAME_STEM
 *          name goes (may be NULL); k, n: K and N of a shard index (may be
 *          NULL).
 * Returns: the kind; OB_XNAME_OTHER for anything not exactly of a pattern
 *          (a stem whose d or tol is no number, a curve id with characters
 *          ids cannot hold, another extension). */
ob_xname ob_export_name_kind(const char *name, char *stem, size_t len, int *k, int *n);

/* Purpose: the index file's name: "index.csv" (shard_n 0) or
 *          "index.shardK-of-N.csv". */
void ob_export_index_name(char *buf, size_t len, int shard_k, int shard_n);

/* Which of the export's names ob_export_prune removes. */
typedef struct {
    const ob_strmap *keep;   /* stems whose files stay */
    const ob_strmap *scope;  /* NULL: every stem; else only stems in scope are removed */
    int shard_indexes;       /* -1: leave every shard index; 0: remove every one; N: remove those not of N */
    int index_csv;           /* 1: remove index.csv too */
} ob_prune_rule;

/* Purpose: remove the names of dir that the export owns and rule r does
 *          not keep (unlinkat: a link goes itself, never its target;
 *          directories and other non-files stay).
 * Outputs: *removed, the count (may be NULL).
 * Returns: 0; -1 with "DIR: reason" in err when dir cannot be read or a
 *          name cannot be removed. */
int ob_export_prune(const char *dir, const ob_prune_rule *r, long *removed, ob_err *err);

/* Purpose: refuse an export directory that would turn the export into
 *          input: dir is $OFFBENCH_DATA's directory or the datasets/
 *          directory this program was built from (their .curves files are
 *          every later default run's curves, loaded or compiled in), or
 *          dir is or holds the --curves file (curves_file, may be NULL).
 *          A subdirectory of a curve directory is fine (neither is read
 *          recursively).
 * Inputs:  cmd ("run", "draw", "trace") for the message.
 * Returns: 0, or -1 after ob_error() naming --export and the directory
 *          (the command exits 2). */
int ob_export_check_dir(const char *cmd, const char *dir, const char *curves_file);

/* The datasets/ directory this program was built from (an absolute path;
 * it may no longer exist). */
const char *ob_export_build_datasets(void);

#endif
