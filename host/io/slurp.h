/*
 * slurp.h - read a whole (small) input file into memory, for the readers of
 * `compare` (results.csv, samples.csv, meta.json), `merge` (shard.csv), the
 * journal of --resume and the published tables.
 */
#ifndef OB_SLURP_H
#define OB_SLURP_H

#include <stddef.h>
#include "methods/core/err.h"

/* The largest file ob_slurp reads: 1 GiB (a results.csv of some 5 million
 * jobs); meta.json has its own, smaller cap (OB_JSON_LIMIT, metajson.h). */
#define OB_SLURP_LIMIT ((size_t)1 << 30)

/* Purpose: read the regular file at path (at most OB_SLURP_LIMIT bytes) into
 *          a malloc'd buffer with one spare byte and a NUL after the data
 *          (*len excludes it).
 * Errors:  returns 0; -1 with "PATH: cannot open: reason" (or "is a
 *          directory", "not a regular file", "file too large (... the limit
 *          is N MiB)", "read error", "out of memory") in err->msg and *text = NULL.
 *          A FIFO or device is refused without reading from it (so
 *          `compare BASE /dev/zero` stops at once). */
int ob_slurp(const char *path, char **text, size_t *len, ob_err *err);
/* The same with a cap of max bytes (max <= OB_SLURP_LIMIT). */
int ob_slurp_max(const char *path, size_t max, char **text, size_t *len, ob_err *err);

#endif
