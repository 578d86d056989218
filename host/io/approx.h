/*
 * approx.h - one job's approximation as a list of pieces, for `run --export`
 * (host/io/export*.c) and `measure` (host/cli/cmd_measure.c).
 *
 * A piece is a Bézier segment (homogeneous, over [0, 1]) in the base curve's
 * coordinates.  When it comes from a run (or from a file offbench exported)
 * it also knows the base piece it approximates, exactly as the driver cut it:
 * base segment `seg`, the accepted span [a, b] of that segment, and the part
 * [t0, t1] of the span's fit that the piece covers (ob_fit.t).  The base
 * piece is then subsegment(subsegment(seg, a, b), t0, t1), bit for bit what
 * the driver measured (methods/driver/driver.c, measure_chunk), so measuring
 * it again gives the run's numbers.  A piece from elsewhere (a CAD system's
 * offset) has no such link (has_base 0): measure finds its base range by
 * projecting its end points onto the exact offset (approx_match.c).
 */
#ifndef OB_APPROX_H
#define OB_APPROX_H

#include <stddef.h>

#include "methods/driver/driver.h"
#include "methods/core/err.h"

typedef struct {
    int has_base;       /* 1: seg, a, b, t0, t1 are known */
    int seg;            /* base segment index */
    double a, b;        /* the accepted span of segment seg */
    double t0, t1;      /* the piece's part of the span's fit */
    int fit_first;      /* 1: the first piece of its fit */
    int line;           /* where it was read (0: not read from a file) */
    ob_bez approx;      /* the approximating piece over [0, 1] */
    int matched;        /* 1: the link was found by projection (ob_approx_match),
                           not read: it says nothing of the parameter */
    int part;           /* 0: a piece as read; k > 0: the k-th further part of
                           one that ob_approx_match cut where the base's
                           segments join (an exact subdivision: the file's
                           piece counts once, ob_approx_file_piece) */
    char entity[16];    /* what the file calls it: a DXF entity type (SPLINE,
                           LINE, ...), an SVG element (path, ...); "" else */
    char handle[24];    /* its DXF handle (group 5), "" when none */
    char id[64];        /* its SVG element's id, "" when none */
} ob_apiece;

/* Entities of a file that the reader did not take as pieces (a DXF's TEXT,
 * HATCH, ...): their type, how many, and the line of the first. */
enum { OB_APPROX_SKIP_TYPES = 8 };
typedef struct {
    char type[24];
    int count, line;
} ob_askip;

/* The first skipped entities one by one (type, why, line): what a file
 * that yields no pieces is made of, for its error (approx_read.c). */
enum { OB_APPROX_NOTES = 10 };
typedef struct {
    char type[24], why[72];
    int line;
} ob_anote;

typedef struct {
    ob_apiece *v;
    int n, cap;
    int same_param;     /* 1: the pieces share the base's parameter (the
                           method has OB_CAP_SAME_PARAM; bound and radial
                           apply); 0 unknown or not */
    int have_job;       /* 1: the file names the job that exported it */
    char job_curve[64]; /* that job's curve id and offset distance d */
    double job_d;
    ob_askip skipped[OB_APPROX_SKIP_TYPES]; /* the first types skipped, in file order */
    int nskipped_types;                     /* of them used */
    int nskipped;                           /* entities skipped, of any type */
    ob_anote notes[OB_APPROX_NOTES];        /* the first nskipped of them */
    int svg_units_px;   /* a reading option, set before ob_approx_read: 1
                           applies an SVG's root viewBox (CSS px, as
                           svg2curves.py --units px); 0 keeps its user units */
} ob_approx;

/* Always safe to call (also on a zeroed approximation). */
void ob_approx_free(ob_approx *a);

/* Appends a zeroed piece and returns it, or NULL when out of memory. */
ob_apiece *ob_approx_add(ob_approx *a);

/* Purpose: note that the reader skipped an entity of type `type` (cut to
 *          23 characters) at line `line`: counted in a->nskipped, and per
 *          type in a->skipped (the first OB_APPROX_SKIP_TYPES types; those
 *          of further types only in nskipped).  Never fails. */
void ob_approx_note_skip(ob_approx *a, const char *type, int line);

/* Purpose: as ob_approx_note_skip, with why it was skipped (cut to 71
 *          characters; NULL: "not a curve measure reads"), which the error
 *          of a file with no pieces lists (approx_read.c). */
void ob_approx_note_skip_why(ob_approx *a, const char *type, const char *why, int line);

/* Purpose: the file's number of piece k of a (0-based, in file order): k
 *          less the further parts of pieces cut at base joints before it.
 * Inputs:  0 <= k < a->n. */
int ob_approx_file_piece(const ob_approx *a, int k);

/* Purpose: the number of pieces as the file gives them (a->n less the
 *          further parts of pieces cut at base joints). */
int ob_approx_file_pieces(const ob_approx *a);

/* Copies src's entity, handle and id into dst (a part of a cut piece). */
void ob_apiece_names(ob_apiece *dst, const ob_apiece *src);

/* Purpose: the base parameter of piece p at its own parameter s in [0, 1]:
 *          span [a, b] at fit parameter t0 + (t1 - t0) s, exactly a at the
 *          start of a span (s = 0, t0 = 0) and exactly b at its end (s = 1,
 *          t1 = 1), so that the ranges of pieces that the driver cut from
 *          one segment meet bit for bit (measure's coverage check).
 * Inputs:  p with has_base set. */
double ob_apiece_base_t(const ob_apiece *p, double s);

/* Purpose: the base piece that piece p approximates (p->has_base set):
 *          segment p->seg of curve c cut to [a, b], then to [t0, t1], as the
 *          driver cuts it.  Returns 0, or -1 when p->seg is not a segment of c
 *          or the ranges are not inside [0, 1] with a < b, t0 < t1. */
int ob_apiece_base(const ob_curve *c, const ob_apiece *p, ob_bez *base);

/* Purpose: the pieces of a finished job: every accepted span of its log
 *          refitted with the job's method (fits are deterministic; this is
 *          how draw gets them too, host/view/jobview.c), in curve order.
 * Inputs:  j: a job that ended ok or limit; log: its span log.
 * Outputs: *out (appended to; same_param from the method's capabilities).
 * Errors:  returns 0; -1 with a reason in err->msg (a refit that fails or does not
 *          give the run's segment count; out of memory). */
int ob_approx_from_job(const ob_job *j, const ob_span_log *log, ob_approx *out, ob_err *err);

#endif
