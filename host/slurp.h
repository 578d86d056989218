/*
 * slurp.h - read a whole (small) input file into memory, for the readers of
 * `compare` (results.csv, samples.csv, meta.json) and the published tables.
 */
#ifndef OB_SLURP_H
#define OB_SLURP_H

#include <stddef.h>

/* Purpose: read the file at path into a malloc'd buffer with one spare byte
 *          and a NUL after the data (*len excludes it).
 * Errors:  returns 0; -1 with "PATH: cannot open: reason" (or "read error",
 *          "is a directory", "out of memory") in err and *text = NULL. */
int ob_slurp(const char *path, char **text, size_t *len, char *err, size_t errlen);

#endif
