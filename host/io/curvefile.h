/*
 * curvefile.h - the line-based `.curves` format (see README "Curve files").
 *
 *   curve ID                  # letters, digits, '_', '-', '.', '/'
 *     source TEXT
 *     family NAME             # optional, default "user" (OB_DEFAULT_FAMILY)
 *     bezier DEGREE           # or: bspline DEGREE
 *     knots K0 K1 ...         # bspline only (may span several `knots` lines)
 *     point X Y [W]           # one per control point, W > 0 (default 1)
 *     offset D [D ...]        # one or more signed distances, d != 0
 *   end
 *
 * '#' starts a comment, blank lines are ignored, CRLF is accepted.
 */
#ifndef OB_CURVEFILE_H
#define OB_CURVEFILE_H

/* The family of a curve whose file gives none: the user's own curves (the
 * published ones say `family published`, the Offset Atlas `family atlas`). */
#define OB_DEFAULT_FAMILY "user"

#include <stddef.h>
#include "methods/core/curve.h"
#include "methods/core/err.h"

typedef struct {
    ob_curve *v;
    int n, cap;
} ob_curveset;

/* Always safe to call (also on a zeroed set). */
void ob_curveset_free(ob_curveset *s);

/* Purpose: parse curves from a text buffer and append them to *set.
 * Inputs:  name, used in messages as "NAME:LINE: message".
 * Errors:  returns 0, or -1 after writing one "NAME:LINE: message" line into
 *          err (the first error; nothing is appended then).  Duplicate ids
 *          against curves already in *set are errors.  Never crashes on any
 *          input bytes. */
int ob_curves_parse(const char *text, size_t len, const char *name,
                    ob_curveset *set, ob_err *err);

/* Same, reading the file at path (messages name the path). */
int ob_curves_load_file(const char *path, ob_curveset *set, ob_err *err);

/* Purpose: load every `*.curves` file in directory dir, in name order.
 * Errors:  -1 with message as above; -1 with "DIR: ..." if unreadable. */
int ob_curves_load_dir(const char *dir, ob_curveset *set, ob_err *err);

/* Purpose: the one check of an offset distance d, for every command that
 *          takes one: a curve file's `offset` line, and --d of draw, trace
 *          and measure (so none of them takes a d the format refuses).
 * Inputs:  d; coord_max, the largest |coordinate| of the curve
 *          (ob_curve.coord_max; 0: only the absolute limits apply).
 * Rules:   d finite and != 0; 1e-50 <= |d| <= 1e12 (the format's number
 *          range; below, C + dN rounds to C or underflows the metrics);
 *          |d| >= 1e-12 coord_max (below, d is round-off of the
 *          coordinates: the offset is measured as the curve itself).
 * Returns: 0; -1 with the reason in why (no FILE:LINE or option: the caller
 *          says where, e.g. "offset distance 1e-60 is too small (|d| must
 *          be 1e-50 to 1e12)"). */
int ob_offset_check(double d, double coord_max, char *why, size_t len);

/* Index of the curve with this id, or -1. */
int ob_curveset_find(const ob_curveset *set, const char *id);

#endif
