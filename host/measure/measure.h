/*
 * measure.h - the error of an approximation read from a file (`measure`),
 * with the run's engine: each piece against its base piece by ob_measure
 * (methods/metrics/metric.h), the largest over the pieces, as the driver
 * computes a job's max_err (methods/driver/driver.c, measure_chunk).
 *
 * Pieces that carry their base link (files offbench exported: approx.h) are
 * measured against exactly the base piece the run measured, so the result
 * is the run's max_err (the CPU backend's; tests/e2e/e2e_export.sh).  Pieces
 * without one are matched first (ob_approx_match).
 */
#ifndef OB_MEASURE_H
#define OB_MEASURE_H

#include <stddef.h>

#include "host/io/approx.h"
#include "methods/core/err.h"

/* Purpose: give every piece without a base link one, by projection: each
 *          end point goes to the base parameter whose exact offset point
 *          C(t) + d N(t) is nearest (a scan of 512 parameters per base
 *          segment, then golden-section refinement); the piece is reversed
 *          first (its control points in the other order, an exact
 *          reparameterization) when it runs against the base.  Both ends on
 *          one segment: linked to span [ta, tb] of it (fit [0, 1]).  Ends
 *          on segments s0 < s1: cut (de Casteljau, exact) where it crosses
 *          the line through each joint between them along the mean of the
 *          two segments' normals there, on d's side; the parts, inserted in
 *          a->v in its place, are linked to [ta, 1], [0, 1] ..., [0, tb] of
 *          s0 ... s1 and carry part = 0, 1, ... (ob_approx_file_piece gives
 *          the file's number back).  On a closed base (its end point its
 *          start point) segments are taken cyclically: a piece may run over
 *          the start, the way round its middle lies on.
 * Errors:  returns 0; -1 with "NAME:LINE: piece K: reason" in err->msg when both
 *          ends fall on one point, when the piece does not cross a joint's
 *          line, or out of memory.
 * Note:    on an offset with loops (cusps) the nearest point can lie on the
 *          wrong branch; such files should carry the link. */
int ob_approx_match(const ob_curve *c, double d, ob_approx *a, const char *name, ob_err *err);

/* ---- coverage (cover.c) --------------------------------------------------
 * A measured approximation must cover the whole offset once: the pieces'
 * base ranges must tile every base segment's [0, 1], without gaps,
 * overlaps or duplicates.  The base range of a piece is
 * [ob_apiece_base_t(p, 0), ob_apiece_base_t(p, 1)] of segment p->seg.
 *   Read links (files offbench exported) must tile exactly, bit for bit:
 *   the driver cuts a segment at [a, m], [m, b] with one m, and a fit's
 *   parts at one t[] array from t[0] = 0 to t[n] = 1, so every joint of
 *   an export is exact (ob_apiece_base_t keeps the ends exact).
 *   Links found by projection (ob_approx_match) meet where the pieces'
 *   ends do: two ends at one point project to one parameter, bit for bit;
 *   ends apart project apart, and an end can lie off the offset along it
 *   farther than across it (lee's first end at 1e-3: 4.4e-3 along, 5e-4
 *   across), which the pieces' own errors against their projected ranges
 *   do not see.  A stretch of offset between two such pieces (or between
 *   the first or last piece and the curve's end) fails when it is longer
 *   than OB_COVER_REL times the curve's size (ob_joint_size: the box of the
 *   control points grown by |d|), than twice the largest of the pieces'
 *   own errors (hausdorff, each against its base piece) and than a quarter
 *   of the shorter piece beside it (lengths along the offset): a piece
 *   missing, repeated or reaching into another leaves a stretch about as
 *   long as a piece.  A stretch longer than the first only is noted: the
 *   stretches of the default job's approximations without their links
 *   (ends off the offset along it, open joints) reach 16 times the
 *   pieces' own error (lee at 1e-5) and a third of a piece (lee at 1e-2
 *   on a line).  Either way ob_approx_hausdorff_whole measures the whole
 *   offset, those stretches included.  (On offsets with cusps the nearest
 *   point can lie on another branch, and the projected ranges of pieces
 *   near a cusp cross: such files fail, and need their links.)
 * Pieces out of order are not an error: the check, and the measurement,
 * take them in the base's order (sorted by segment, then start); each
 * piece that comes after a piece that lies after it on the base is noted. */
#define OB_COVER_REL 1e-9

typedef enum {
    OB_COVER_GAP = 0,   /* a base range no piece covers */
    OB_COVER_OVERLAP,   /* a base range two pieces cover */
    OB_COVER_DUPLICATE, /* a piece over the same range as another */
    OB_COVER_ORDER,     /* (a note) a piece after one that lies after it on the base */
    OB_COVER_NEAR_GAP,  /* (a note) a gap within the tolerance of matched links */
    OB_COVER_NEAR_OVERLAP, /* (a note) an overlap within it */
    OB_COVER_KINDS
} ob_cover_kind;

/* One problem: where it shows (piece, file index; the other piece it
 * involves, or -1) and the base range it concerns, from t0 of segment seg0
 * to t1 of segment seg1. */
typedef struct {
    ob_cover_kind kind;
    int piece, other;
    int seg0, seg1;
    double t0, t1;
} ob_cover_issue;

enum { OB_COVER_KEEP = 5 };

typedef struct {
    int n;              /* pieces */
    int *order;         /* the pieces (file indices) in the base's order */
    double *lo, *hi;    /* per piece (file index): its tile of base segment
                           v[k].seg; the tiles cover every segment once
                           (set when nothing fails) */
    int count[OB_COVER_KINDS];           /* problems of each kind */
    ob_cover_issue fail[OB_COVER_KEEP];  /* the first gaps, overlaps, duplicates */
    ob_cover_issue note[OB_COVER_KEEP];  /* the first notes (out of order, near) */
    int nfail, nnote;                    /* of them kept */
} ob_cover;

/* Purpose: check that the pieces of a (every piece linked: read or
 *          matched) cover the d-offset of curve c once (see above); S
 *          samples for the pieces' own errors where a link was matched
 *          (the tolerance).
 * Outputs: *cv (free with ob_cover_free, also after an error): the base
 *          order, the problems, and when there are no failing ones
 *          (ob_cover_fails 0) the tiles.
 * Errors:  returns 0 (also when the file fails the check); -1 with
 *          "NAME:LINE: piece K: reason" in err->msg when a link names a
 *          segment c does not have or an empty range; -1 out of memory. */
int ob_approx_cover(const ob_curve *c, double d, const ob_approx *a, int samples, const char *name, ob_cover *cv,
                    ob_err *err);

/* The number of gaps, overlaps and duplicates (0: the pieces cover the
 * offset once). */
int ob_cover_fails(const ob_cover *cv);

/* Purpose: one problem as a line "NAME:LINE: piece K: ..." (the pieces'
 *          lines and numbers from a), into buf (cut to len). */
void ob_cover_text(const ob_cover_issue *is, const ob_approx *a, const char *name, char *buf, size_t len);

/* Always safe to call (also on a zeroed cover). */
void ob_cover_free(ob_cover *cv);

/* One metric's result. */
typedef struct {
    int applies;        /* 0: why says why not */
    const char *why;
    double err;         /* the largest error over the pieces */
    int piece;          /* where: the piece, its base segment and base parameter */
    int seg;
    double t;
    int ok;             /* applies and err is finite (ob_err_can_pass); else why says why not */
    const char *note;   /* for a result that applies: a remark, or "" */
} ob_mres;

/* The status `measure` writes for r: "ok", "n/a" (the metric does not
 * apply) or "fail" (an error that is not finite is never ok). */
const char *ob_mres_status(const ob_mres *r);

/* Purpose: the error of every piece of a (all pieces linked) against the
 *          d-offset of curve c under metric m, S samples, the largest kept.
 *          bound and radial apply only when a->same_param (the pieces share
 *          the base's parameter); param only when every link was read, none
 *          matched (it reads a piece at the base parameter its link maps it
 *          to, which a projection does not give).
 *          r->ok 0 with r->why when the largest error is not finite (a
 *          piece the metric cannot bound: a pole of a rational piece).
 * Returns: 0; -1 with "NAME:LINE: piece K: reason" in err->msg when a piece
 *          cannot be measured (a link to a segment c does not have; bound
 *          past its degree). */
int ob_approx_measure(const ob_curve *c, double d, const ob_approx *a, ob_metric m, int samples, const char *name,
                      ob_mres *r, ob_err *err);

/* Purpose: the two-sided Hausdorff distance between the whole
 *          approximation (every piece of a) and the whole exact d-offset of
 *          c (every base segment over [0, 1], untrimmed), under the cover cv
 *          (ob_approx_cover, with no failing problem):
 *            max( max over points p of the pieces of dist(p, whole offset),
 *                 max over points q of the offset of dist(q, all pieces) ).
 *          The offset is taken as the union of the tiles of cv (the base
 *          pieces themselves for read links), each sampled like a piece;
 *          each side samples every piece (tile) at S parameters and refines
 *          its largest sample by golden section, as the hausdorff metric
 *          does for one piece, with the nearest point searched on every
 *          piece (tile) whose bounding circle can hold a nearer point than
 *          the piece's own (kernels/metric_core.h, obc_side_dist).  A point
 *          nearer to a neighbour's part than to its own gives the whole a
 *          smaller distance than the per-piece metric: this is at most the
 *          hausdorff row's max_err (to round-off).
 * Outputs: *r: err, and where: on the approximation's side the piece and
 *          the base segment and parameter of the nearest offset point; on
 *          the offset's side the point's tile (piece), segment and
 *          parameter; r->note says which side.
 * Errors:  returns 0; -1 with a reason in err->msg when out of memory. */
int ob_approx_hausdorff_whole(const ob_curve *c, double d, const ob_approx *a, const ob_cover *cv, int samples,
                              ob_mres *r, ob_err *err);

/* ---- measure's one path (pipeline.c) --------------------------------------
 * What `measure` does with one approximation, for the CLI and the C API
 * (obx_measure) alike, so that what one refuses the other refuses. */
typedef struct {
    int want[OB_METRIC_COUNT];  /* the per-piece metrics asked */
    int whole;                  /* 1: hausdorff-whole too */
    int samples;                /* per piece (ob_clamp_samples'd) */
} ob_measure_ask;

typedef struct {
    ob_mres res[OB_METRIC_COUNT];  /* res[m] where want[m] */
    ob_mres whole;                 /* where whole */
} ob_measure_out;

/* Purpose: match the pieces of a without a link (ob_approx_match), check
 *          that the pieces cover the d-offset of c once (ob_approx_cover),
 *          then measure every metric asked (ob_approx_measure) and
 *          hausdorff-whole (ob_approx_hausdorff_whole).
 * Outputs: *cv (free with ob_cover_free, also after an error): its notes
 *          and failures, for the caller to show (ob_cover_text); *out.
 * Errors:  returns 0; -1 with err->msg: a piece that cannot be matched or
 *          measured ("NAME:LINE: piece K: reason"); pieces that do not
 *          cover the offset once ("measure: NAME does not cover the d = D
 *          offset of curve ID once (G gaps, O overlaps, U duplicates): ...",
 *          cv->fail says where); out of memory. */
/* How the cover failure's hint about cusps begins (the CLI cuts it when
 * its diagnosis explains the file otherwise: host/measure/diagnose.h). */
#define OB_MEASURE_CUSP_HINT " (its pieces were matched"

int ob_measure_approx(const ob_curve *c, double d, ob_approx *a, const ob_measure_ask *ask, const char *name,
                      ob_cover *cv, ob_measure_out *out, ob_err *err);

#endif
