/*
 * frame.h - the drawing frame of a file `measure` reads: an affine map from
 * the file's coordinates to the base curve's, applied to every piece right
 * after reading (before matching), and the similarity fit that guesses such
 * a map when a file lies far from the offset (diagnose.c).
 *
 * A map is six numbers a,b,c,d,e,f in SVG's matrix order:
 *   x' = a x + c y + e,   y' = b x + d y + f.
 * On homogeneous control points (w x, w y, w) it is linear:
 *   (w x)' = a (w x) + c (w y) + e w, (w y)' likewise, w' = w,
 * so a rational piece keeps its weights and maps exactly.
 */
#ifndef OB_FRAME_H
#define OB_FRAME_H

#include <stddef.h>

#include "host/io/approx.h"
#include "host/io/svg_read.h"

/* The SVG reader's affine map (svg_read.h), a, b, c, d, e, f: one type and
 * one product for both. */
typedef ob_svgr_xform ob_frame;

extern const ob_frame OB_FRAME_IDENTITY;

/* a after b: (a b)(p) = a(b(p)). */
ob_frame ob_frame_mul(const ob_frame *a, const ob_frame *b);

/* The image of point p under f. */
void ob_frame_point(const ob_frame *f, const double p[2], double q[2]);

/* a d - b c, the determinant of the linear part (< 0: a reflection). */
double ob_frame_det(const ob_frame *f);

/* Purpose: NULL when f is usable (every number finite, the linear part not
 *          singular: |det| > 1e-12 times the square of its largest entry),
 *          else why not. */
const char *ob_frame_refuse(const ob_frame *f);

/* Purpose: parse exactly n (1 <= n <= 6) comma-separated finite numbers
 *          from s into v; 0, or -1 (a count other than n, a word that is
 *          not a finite number). */
int ob_frame_parse_list(const char *s, double *v, int n);

/* Purpose: map every piece of a by f (its control points, weights kept). */
void ob_frame_apply(const ob_frame *f, ob_approx *a);

/* Purpose: f in --transform syntax, "a,b,c,d,e,f" (%.9g), into buf. */
void ob_frame_text(const ob_frame *f, char *buf, size_t len);

/* ---- the similarity fit (similarity.c) -------------------------------------
 * Purpose: the similarity (rotation, uniform scale, translation; with
 *          reflect, a reflection y -> -y first) that maps the points p[i]
 *          onto q[i] (i < n, n >= 2) with the least sum of squared
 *          distances (Procrustes / Umeyama in the plane: centroids, then
 *          the rotation from the cross-covariance, the scale from it and
 *          the spread of p).
 * Returns: 0 with *f; -1 when the points p all coincide. */
int ob_similarity_fit(const double (*p)[2], const double (*q)[2], int n, int reflect, ob_frame *f);

#endif
