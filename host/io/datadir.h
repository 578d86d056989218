/*
 * datadir.h - where the default curves come from.
 *
 * The directory in $OFFBENCH_DATA when set, else the copies of the datasets/
 * curve files compiled into the program: a datasets/ directory in the working
 * directory or beside the program is not read, so the curves do not depend on
 * where a run starts (issue 36; --curves FILE names other curves, and
 * meta.json's data_hash tells any two curve sets apart).
 */
#ifndef OB_DATADIR_H
#define OB_DATADIR_H

#include <stddef.h>
#include "host/io/curvefile.h"
#include "methods/core/err.h"

/* Purpose: load the default curve set.  *where gets a description of the
 * source ("DIR" or "embedded copy of datasets/").  Errors as ob_curves_load_dir. */
int ob_load_default_curves(ob_curveset *set, char *where, size_t wlen, ob_err *err);

/* Purpose: find a file of the tree such as results/published/X.csv: the path
 *          in $env when set, else rel from the current directory, else rel
 *          beside the executable.  Returns 0 with the path in path[], or -1
 *          when none is readable (the caller falls back to its embedded copy). */
int ob_find_tree_file(const char *rel, const char *env, char *path, size_t len);

#endif
