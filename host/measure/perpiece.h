/*
 * perpiece.h - where an approximation's error is (`measure --per-piece`,
 * `measure --draw`, `draw --approx`): each piece of the file, as the file
 * numbers them, with its own hausdorff error against its base piece and
 * the worst point, on the piece and on the exact offset.
 *
 * The error of a row is the largest over the piece's parts (a piece that
 * ob_approx_match cut at base joints is one row), each part measured as
 * ob_approx_measure measures it under hausdorff (the same call, the same
 * base piece, the same samples), so the largest over the rows is the
 * hausdorff row's max_err, bit for bit.  This is a second pass over the
 * pieces: the rows of `measure` are computed as before and do not change.
 * The worst point: the metric gives the base parameter t of the exact
 * offset point O(t) = C(t) + d N(t) where the part's two-sided distance is
 * largest (on the approximation's side the foot of its farthest point, on
 * the offset's side the farthest offset point itself); x, y is the point of
 * the part nearest to O(t) (dense samples refined by golden section), so
 * |(x, y) - O(t)| is the error to the search's precision.
 */
#ifndef OB_PERPIECE_H
#define OB_PERPIECE_H

#include <stdio.h>

#include "host/io/approx.h"
#include "methods/core/err.h"

typedef struct {
    int piece;          /* the file's number (ob_approx_file_piece) */
    int first, last;    /* its parts: a->v[first .. last] */
    double err;         /* the largest hausdorff error of its parts */
    int worst;          /* the part where it is */
    int seg;            /* there: the base segment and its parameter of O(t) */
    double t;
    double x, y;        /* the piece's point at the error: nearest to O(t), or (a bump
                           of the piece) the one whose foot is O(t) (perpiece.c) */
    double xo, yo;      /* O(t) */
} ob_pp_row;

typedef struct {
    ob_pp_row *v;
    int n;
} ob_perpiece;

/* Purpose: one row per file piece of a (matched and covering: after
 *          ob_measure_approx), S samples.
 * Errors:  returns 0; -1 with "NAME:LINE: piece K: reason" in err->msg (a
 *          piece that cannot be measured), or out of memory. */
int ob_approx_per_piece(const ob_curve *c, double d, const ob_approx *a, int samples, const char *name,
                        ob_perpiece *pp, ob_err *err);

/* Always safe to call (also on a zeroed one). */
void ob_perpiece_free(ob_perpiece *pp);

/* One measured file: its name as given, its pieces and their rows. */
typedef struct {
    const char *name;
    const ob_approx *ap;
    const ob_perpiece *pp;
} ob_pp_file;

/* The header of the --per-piece CSV (no line end). */
extern const char ob_perpiece_header[];

/* Purpose: the --per-piece CSV of files (n of them, in order) to f.
 * Returns 0, or -1 when writing failed. */
int ob_perpiece_csv(FILE *f, const ob_pp_file *files, int n);

/* Purpose: write the file path afresh (host/io/outfile.h) with writer.
 * Returns 0; 1 after ob_error() naming opt and path when it cannot be
 *          written (path left as it was). */
int ob_pp_write(const char *opt, const char *path, int (*writer)(FILE *, const void *), const void *ctx);

#endif
