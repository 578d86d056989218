/*
 * draw_approx.h - the picture of where a file's approximation is off
 * (`measure --draw FILE.svg`, `draw --approx FILE`): the base curve, its
 * exact d-offset (sampled densely), every piece of every file coloured by
 * its own hausdorff error (host/measure/perpiece.h) on a log scale with a
 * legend (value -> colour), each piece's worst point as a dot, and each
 * file's worst piece marked: a ring, the segment from the piece's point to
 * the nearest offset point, and a label with the error.  Drawn in the base
 * curve's coordinates (the file's own frame: measure takes the file's
 * coordinates as the base's), y up.
 *
 * Elements tests can find: class="base", "offset" (one polyline per base
 * segment), "piece" (one <path> per file piece, data-file = the file's
 * index in the order given, data-piece = the file's piece number,
 * data-err = its error), "wpt" (a worst point), "worst" (a file's worst
 * piece: a <g> with data-file, data-piece, data-err), "legend".
 */
#ifndef OB_DRAW_APPROX_H
#define OB_DRAW_APPROX_H

#include <stdio.h>

#include "host/measure/perpiece.h"

typedef struct {
    const ob_curve *c;
    double d;
    const ob_pp_file *files;
    int n;
} ob_draw_approx;

/* Purpose: the SVG of *ctx (an ob_draw_approx) to f (ob_pp_write's writer).
 * Returns 0, or -1 when writing failed. */
int ob_draw_approx_svg(FILE *f, const void *ctx);

#endif
