/*
 * measure_more.h - measure's frame and verdict options (issue 50 items 2
 * and 4), in a flag table of their own beside cmd_measure.c's:
 *   --transform a,b,c,d,e,f   x' = a x + c y + e, y' = b x + d y + f (SVG's
 *                             matrix order), file -> base coordinates
 *   --translate X,Y           x' = x + X, y' = y + Y
 *   --scale S | SX,SY         x' = SX x, y' = SY y
 *   --flip-y                  y' = -y
 *   --svg-units user|px       an SVG's root user units (default) or CSS px
 *                             (its viewBox applied, as svg2curves.py)
 *   --tol T                   the verdict: exit 1 when a file's deciding
 *                             error is above T
 * The frame options make one map, applied to each point in this fixed
 * order whatever the order on the command line: --transform, then
 * --translate, then --scale, then --flip-y.
 */
#ifndef OB_MEASURE_MORE_H
#define OB_MEASURE_MORE_H

#include "host/cli/cliopts.h"
#include "host/measure/frame.h"
#include "host/measure/measure.h"

typedef struct {
    ob_frame transform;       /* --transform (identity when not given) */
    double translate[2];      /* --translate (0, 0) */
    double scale[2];          /* --scale (1, 1) */
    int flip_y;               /* --flip-y */
    int have_frame;           /* any of them given */
    int svg_px;               /* --svg-units px: an SVG's root viewBox applied */
    int have_tol;
    double tol;               /* --tol */
} ob_measure_more;

/* Purpose: the flag table of these options over *x (reset to the
 *          defaults), for ob_cli_parse. */
ob_flagset ob_measure_more_flags(ob_measure_more *x);

/* Purpose: the one map of the frame options (see the top). */
ob_frame ob_measure_more_frame(const ob_measure_more *x);

/* The per-piece metric whose row decides --tol's verdict under --metric
 * named (NULL: not given): that metric, or OB_METRIC_COUNT for the
 * hausdorff-whole row (not given, all, hausdorff-whole). */
int ob_measure_decider(const char *named);

/* The deciding row of out under decider dm, and its name. */
const ob_mres *ob_measure_decided(const ob_measure_out *out, int dm, const char **name);

/* Purpose: refuse a verdict that a file's n/a row cannot give: 0, or 2
 *          after ob_error() naming --tol, the file and why. */
int ob_measure_verdict_check(const ob_measure_more *x, int dm, const ob_measure_out *out, const char *name);

/* Purpose: one line on stderr, "measure: FILE: within/over tolerance T:
 *          METRIC = E"; 1 when over (an error that is not finite too),
 *          else 0. */
int ob_measure_verdict(const ob_measure_more *x, int dm, const ob_measure_out *out, const char *name);
/* The same for the row r named metric (--trimmed's trimmed-hausdorff). */
int ob_measure_verdict_row(const ob_measure_more *x, const ob_mres *r, const char *metric, const char *name);

/* Purpose: the rows of out that are n/a, left out of the default CSV,
 *          named once on stderr with why (want[]/whole: the rows asked). */
void ob_measure_say_hidden(const int *want, const ob_measure_out *out, const char *name);

#endif
