/*
 * where_out.h - the files that say where an approximation's error is, for
 * `measure --per-piece FILE.csv --draw FILE.svg` and `draw --approx`
 * (host/measure/perpiece.h, host/view/draw_approx.h): their paths checked
 * against the inputs and each other, and their writing.
 */
#ifndef OB_WHERE_OUT_H
#define OB_WHERE_OUT_H

#include "host/measure/perpiece.h"

typedef struct {
    const char *per_piece;  /* --per-piece FILE.csv, or NULL */
    const char *draw;       /* --draw FILE.svg (draw: --out), or NULL */
    const char *draw_opt;   /* the option that names draw ("--draw", "--out") */
} ob_where_out;

/* Purpose: refuse paths that collide: per_piece or draw that is one of the
 *          n inputs (the --approx files, the --curves file; NULL entries
 *          skipped), however spelled, and per_piece and draw one file.
 * Returns: 0, or 2 after ob_error() naming the option. */
int ob_where_check(const char *cmd, const ob_where_out *o, const char *const *in, int n);

/* Purpose: write the files asked (files: every measured file, in order).
 * Returns: 0, or 1 after ob_error() (a file that cannot be written is
 *          left as it was). */
int ob_where_write(const ob_where_out *o, const ob_curve *c, double d, const ob_pp_file *files, int n);

#endif
