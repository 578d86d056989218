/*
 * approx_read.h - read an approximation for `measure` (README "Export and
 * measure"): a `.curves` file (every curve's Bézier segments, in file order),
 * the JSON of `--export`, the entities of a DXF file, or the paths of an SVG
 * file.
 *
 * Files offbench exported say which base piece each piece approximates (the
 * .curves `source` line, the JSON's seg/span/t, the DXF's 999 comment before
 * each SPLINE; approx.h); pieces without that link have has_base 0 and are
 * matched to the base by projection (host/measure/measure.h).
 */
#ifndef OB_APPROX_READ_H
#define OB_APPROX_READ_H

#include <stddef.h>

#include "host/io/approx.h"
#include "methods/core/err.h"

typedef enum { OB_AFMT_CURVES = 0, OB_AFMT_JSON, OB_AFMT_DXF, OB_AFMT_SVG } ob_afmt;

/* The format of path: by its extension (.curves, .json, .dxf, .svg, any
 * case), else by its first bytes ('{' JSON; a DXF group code line "0" or
 * "999"; "<svg" or "<?xml" SVG; anything else .curves). */
ob_afmt ob_approx_format(const char *path, const char *text, size_t len);

/* Purpose: read the approximation in the file at path into *out.
 * Errors:  returns 0; -1 with "PATH:LINE: reason" (or "PATH: reason") in
 *          err: a file that cannot be read, malformed contents, a piece
 *          that is not a Bézier segment offbench can hold (degree 1 to
 *          OB_MAX_DEG, finite coordinates; weights of either sign, as
 *          rational fits make them), no pieces. */
int ob_approx_read(const char *path, ob_approx *out, ob_err *err);

/* The readers behind it, on a file's text (name for messages). */
int ob_approx_read_json(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err);
int ob_approx_read_dxf(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err);
int ob_approx_read_curves(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err);
/* The paths of an SVG file, as scripts/svg2curves.py reads them with its
 * defaults (approx_read_svg.c). */
int ob_approx_read_svg(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err);

/* Parses the link "base segment S span A B fit T0 T1" (the text of the
 * exports' .curves source line and DXF comment, found anywhere in s) into
 * p (has_base 1).  Returns 1 when found, else 0. */
int ob_approx_parse_link(const char *s, ob_apiece *p);

/* Parses the exporting job's name (the stem "ID__dD__METHOD__tolT" of
 * export.h, found after "job " or "export: " in s; '~' in ID stands for '/')
 * into out's job_curve and job_d (have_job 1).  Returns 1 when found,
 * else 0 (out unchanged). */
int ob_approx_parse_job(const char *s, ob_approx *out);

/* Checks piece p read at line (finite homogeneous points, degree 1 ..
 * OB_MAX_DEG) and sets its rational flag; 0, or -1 with
 * "NAME:LINE: piece K: reason" in err->msg. */
int ob_approx_check_piece(ob_apiece *p, int k, const char *name, ob_err *err);

#endif
