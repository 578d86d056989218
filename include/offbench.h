/*
 * offbench.h - the C API of liboffbench (issue 39): offbench's curves,
 * methods, driver and metrics as a library.
 *
 *   cc prog.c -Iinclude -Lbuild -loffbench      (build/liboffbench.so, make lib)
 *
 * What it gives:
 *   curves    a read-only set of test curves: from a `.curves` file, the
 *             built-in datasets, or arrays of Bézier segments;
 *   methods   the registered offset approximation methods and their
 *             parameters (name, default, range, meaning);
 *   fit       one job: one method on one curve at (d, tol, metric, split),
 *             run by the same driver as `offbench run`: the job's numbers
 *             (its results.csv row) and its pieces;
 *   batch     many jobs at once, with a progress callback;
 *   measure   any approximation (pieces given as arrays) against a curve's
 *             exact offset under any metric, as `offbench measure` does,
 *             or against its trimmed offset (--trimmed), and each piece's
 *             own error and worst point (--per-piece).
 *
 * Conventions:
 *   - Every type is opaque or declared here; no internal offbench type
 *     appears in this header, so the library's internals may change without
 *     breaking a caller (the ABI changes only with OBX_VERSION_MAJOR, which
 *     is the SONAME's number: liboffbench.so.0).
 *   - Errors: every function that can fail takes an obx_error *err (may be
 *     NULL) and returns 0 on success, -1 on failure with err->code (an
 *     obx_code) and err->message (one line, no newline, e.g.
 *     "data/x.curves:12: bad degree") set.  On success err is left as it
 *     was.  Accessors of a valid handle cannot fail and take no err.
 *   - Points are Euclidean: a segment of degree n has n + 1 control points,
 *     given as xy[2 k], xy[2 k + 1]; weights (rational segments) w[k] > 0,
 *     NULL for polynomial segments (all weights 1).
 *   - Thread safety: a curve set is read-only once made: any number of
 *     threads may read it, fit on it and measure against it at once.
 *     Results are owned by their caller (one thread at a time, or read-only
 *     sharing).  The method list is constant but for
 *     obx_external_register, which appends to it.  obx_fit and obx_measure may
 *     run on several threads at once; each obx_fit uses OpenMP threads of
 *     its own (OMP_NUM_THREADS).
 *   - The method `sisl` runs its fits in a server process (SINTEF's SISL
 *     can abort or loop on hostile input): the library starts the program
 *     named by $OFFBENCH_SISL_EXE, else offbench-sisl-server beside the
 *     library (build/; found through the library's own path), else in the
 *     library's directory's offbench/ (make install: LIBDIR/offbench/), one
 *     per calling thread; without any, obx_fit with `sisl` fails with
 *     OBX_E_UNSUPPORTED.
 */
#ifndef OFFBENCH_H
#define OFFBENCH_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- version ------------------------------------------------------------ */

#define OBX_VERSION_MAJOR 0
#define OBX_VERSION_MINOR 7
#define OBX_VERSION_PATCH 0
#define OBX_VERSION "0.7.0"

/* Purpose: the library's version as "MAJOR.MINOR.PATCH" (the library that
 *          is loaded, which may be newer than the header compiled against:
 *          same MAJOR means compatible; MINOR counts additions: 0.2 added
 *          obx_curves_segment_count, obx_curves_segment, obx_curves_family;
 *          0.5: obx_measure refuses pieces that do not cover the offset
 *          once, obx_run_batch_stop; 0.6: obx_external_register; 0.7:
 *          obx_measure's trimmed-hausdorff, obx_measure_pieces).
 *          Thread-safe. */
const char *obx_version(void);

/* ---- errors ------------------------------------------------------------- */

typedef enum {
    OBX_OK = 0,
    OBX_E_INVALID,      /* a bad argument: NULL, NaN, out of range, unknown name */
    OBX_E_PARSE,        /* a curve file or array that is not a valid curve */
    OBX_E_IO,           /* a file that cannot be read */
    OBX_E_NOMEM,        /* out of memory */
    OBX_E_UNSUPPORTED,  /* valid, but not available here (sisl without its server) */
    OBX_E_MEASURE,      /* an approximation that cannot be measured or matched */
    OBX_E_STOPPED       /* a batch its progress callback stopped (since 0.5) */
} obx_code;

/* The one error carrier: filled by the call that fails. */
typedef struct {
    int code;           /* an obx_code */
    char message[512];  /* one line, without newline */
} obx_error;

/* ---- curves ------------------------------------------------------------- */

typedef struct obx_curveset obx_curveset;

/* Purpose: load the curves of one `.curves` file (README "Curve files").
 * Outputs: *out, a new set (free with obx_curves_free).
 * Errors:  OBX_E_IO (unreadable: "PATH: reason"), OBX_E_PARSE
 *          ("PATH:LINE: reason", the first error); OBX_E_INVALID for NULL.
 * Threads: safe (each call makes its own set). */
int obx_curves_load_file(const char *path, obx_curveset **out, obx_error *err);

/* Purpose: the built-in curve set, as `offbench run` uses by default ($OFFBENCH_DATA
 *          when set, else the datasets/ compiled into the library).
 * Outputs, errors, threads: as obx_curves_load_file. */
int obx_curves_load_default(obx_curveset **out, obx_error *err);

/* Purpose: a set of one curve made of nseg Bézier segments joined end to
 *          end (a gap between segments is allowed, as in a curve file).
 * Inputs:  id (letters, digits, '_', '-', '.', '/', at most 63 bytes);
 *          degrees[nseg], each 1..20; xy: the segments' control points one
 *          after the other (sum of (degrees[i] + 1) points, 2 doubles
 *          each); w: as many weights (> 0, finite), or NULL.
 * Outputs: *out (free with obx_curves_free); the curve has no offsets of its
 *          own: fits and measurements name d.
 * Errors:  OBX_E_INVALID (bad id, count, degree, point or weight: the
 *          message names the segment and point; a segment the curve-file
 *          reader refuses, e.g. one whose points coincide, is named
 *          "obx_curves_from_arrays segment S:" when nseg > 1); OBX_E_NOMEM.
 * Threads: safe. */
int obx_curves_from_arrays(const char *id, int nseg, const int *degrees, const double *xy, const double *w,
                           obx_curveset **out, obx_error *err);

/* Always safe to call, also with NULL.  Not while another thread uses the set. */
void obx_curves_free(obx_curveset *set);

/* The number of curves; 0 for NULL. */
int obx_curves_count(const obx_curveset *set);

/* The id of curve i, or NULL when i is out of range.  Valid while the set is. */
const char *obx_curves_id(const obx_curveset *set, int i);

/* The index of the curve with this id, or -1. */
int obx_curves_find(const obx_curveset *set, const char *id);

/* The offset distances curve i's file lists (the default jobs' d): their
 *          number, and in *d (when not NULL) a pointer to them, valid while
 *          the set is; 0 when i is out of range. */
int obx_curves_offsets(const obx_curveset *set, int i, const double **d);

/* The number of Bézier segments of curve i (a B-spline of its file counts
 *          as the segments it was converted to); 0 when i is out of range. */
int obx_curves_segment_count(const obx_curveset *set, int i);

/* Purpose: segment k of curve i: its degree, and (when the buffers are not
 *          NULL) its control points into xy[2 (degree + 1)] and weights into
 *          w[degree + 1] (all 1 for a polynomial segment), when cap (the
 *          number of points the buffers hold) is at least degree + 1; as
 *          obx_result_piece does for a fit's pieces.
 * Returns: the degree (>= 1); -1 with OBX_E_INVALID when i or k is out of
 *          range or the buffers are too small (the degree is then in the
 *          message).
 * Threads: safe (the set is read-only). */
int obx_curves_segment(const obx_curveset *set, int i, int k, double *xy, double *w, int cap, obx_error *err);

/* Curve i's family (its file's `family` line, "user" without one, as
 *          results.csv's family column), or NULL when i is out of range. */
const char *obx_curves_family(const obx_curveset *set, int i);

/* ---- methods ------------------------------------------------------------ */

/* The number of registered methods (grows only by obx_external_register). */
int obx_method_count(void);

/* Method i's name (as `offbench list methods`), or NULL when out of range. */
const char *obx_method_name(int i);

/* Method i's short reference, or NULL when out of range. */
const char *obx_method_citation(int i);

/* One parameter of a method: a choice its paper leaves open. */
typedef struct {
    const char *name;
    double def;         /* the paper's reading */
    double min, max;    /* the accepted values, both included */
    int integer;        /* 1: whole numbers only */
    const char *doc;    /* what the values mean */
} obx_param_info;

/* Purpose: register an external method, exactly as `offbench run
 *          --external NAME=COMMAND` does (docs/external-methods.md): start
 *          COMMAND once (`/bin/sh -c`), read its hello line (the method's
 *          metadata), and list the method last, as NAME.  Its fits run in
 *          worker processes started from COMMAND, one per fitting thread.
 * Inputs:  name: 1 to 63 characters, no ',', '.', '=' or space; command:
 *          a shell command line.
 * Outputs: none; the same name with the same command again does nothing
 *          and returns 0 (a caller may register before every run).
 * Errors:  OBX_E_INVALID: NULL name or command, a name taken by a built-in
 *          method ("the name 'NAME' is a built-in method") or by another
 *          command ("... registered with another command `COMMAND`"), a bad
 *          name, more external methods than the registry holds (8), or a
 *          COMMAND that does not start or whose hello line is wrong (the
 *          reason, as --external says it, e.g. "no hello line from
 *          `COMMAND` (...)"); every message begins "obx_external_register
 *          NAME: ".
 * Threads: not while a fit or batch runs (the method list is read without
 *          a lock): between runs.  Since 0.6. */
int obx_external_register(const char *name, const char *command, obx_error *err);

/* The number of parameters of method i (0 when out of range). */
int obx_method_param_count(int i);

/* Purpose: parameter k of method i into *out (strings constant).
 * Errors:  OBX_E_INVALID when i or k is out of range. */
int obx_method_param(int i, int k, obx_param_info *out, obx_error *err);

/* ---- fit: one job --------------------------------------------------------- */

typedef struct obx_result obx_result;

/* Purpose: run one job, exactly as one row of `offbench run` (the driver's
 *          default settings: 256 samples, depth 40, 20000 segments,
 *          inflections first): method `method` on curve `curve` of set at
 *          offset d and tolerance tol, measured under metric `metric`
 *          ("bound", "radial", "normal", "hausdorff", "param"; NULL:
 *          hausdorff), pieces split by rule `split` ("mid", "maxerr",
 *          "greedy", "optimal"; NULL: mid).
 * Inputs:  params: NULL (the defaults) or "NAME=VALUE[,NAME=VALUE...]" for
 *          the method's parameters (as run's --param METHOD.NAME=VALUE).
 * Outputs: *out (free with obx_result_free), also when the job itself ends
 *          fail, skip or limit: that is its status, not an error.
 * Errors:  OBX_E_INVALID: set NULL, curve out of range, unknown method,
 *          metric, split or parameter (the message lists the names), d not
 *          finite or 0 or out of the curve's range, tol not finite and > 0;
 *          OBX_E_UNSUPPORTED: sisl without its server program;
 *          OBX_E_NOMEM.
 * Threads: safe, also on one shared set. */
int obx_fit(const obx_curveset *set, int curve, const char *method, double d, double tol, const char *metric,
            const char *split, const char *params, obx_result **out, obx_error *err);

/* Always safe to call, also with NULL. */
void obx_result_free(obx_result *r);

/* The job's status: "ok", "limit", "fail", "skip" or "timeout". */
const char *obx_result_status(const obx_result *r);
/* Its largest measured error over the accepted pieces. */
double obx_result_max_err(const obx_result *r);
/* Control points as the papers count them (README "Output"). */
long obx_result_ctrl_points(const obx_result *r);
/* Accepted segments. */
int obx_result_segments(const obx_result *r);
/* The job's message ("" when none). */
const char *obx_result_message(const obx_result *r);

/* The job's results.csv row (no newline), as `offbench run` writes it
 * (its timing columns are this call's), and the header it goes under. */
const char *obx_result_row(const obx_result *r);
const char *obx_results_header(void);

/* The number of pieces of the approximation (0 when the job ended fail or
 * skip), in curve order. */
int obx_result_piece_count(const obx_result *r);

/* Purpose: piece k: its degree, and (when the buffers are not NULL) its
 *          control points into xy[2 (degree + 1)] and weights into
 *          w[degree + 1] (all 1 for a polynomial piece), when cap (the
 *          number of points the buffers hold) is at least degree + 1.
 * Returns: the degree (>= 0); -1 with OBX_E_INVALID when k is out of range
 *          or the buffers are too small (the degree is then in the message). */
int obx_result_piece(const obx_result *r, int k, double *xy, double *w, int cap, obx_error *err);

/* ---- certify (since 0.4) ------------------------------------------------------ */

/* Purpose: certify a result's error, as `offbench run --certify` certifies
 *          its row (docs/certified.md): err_lower <= H <= err_upper, H the
 *          two-sided Hausdorff distance of the pieces to the exact offsets
 *          of their base pieces (each enclosed from the segment as stored),
 *          whatever the job's metric.
 * Inputs:  r from obx_fit or obx_run_batch; mode: NULL or "verdict" (run
 *          --certify's default: refined only until err_upper <= tol or
 *          err_lower > tol, neither end need be tight) or "tight" (run
 *          --certify=tight: until err_upper <= err_lower (1 + 1e-3), and on
 *          while tol lies between them).
 * Outputs: r's row (obx_result_row) gains err_upper, err_lower, certified
 *          (yes: err_upper <= tol) and cert_ns (this call's thread CPU
 *          time); *upper and *lower (each may be NULL): the enclosure
 *          (+inf upper: a piece unbounded, a cusp of the base).  A job
 *          without an approximation (fail, skip, timeout) has nothing to
 *          certify: not an error, *upper and *lower NAN, its columns stay
 *          empty.  A second call in the same mode gives the first's
 *          certificate; in the other mode it certifies again.
 * Errors:  OBX_E_INVALID: r NULL, an unknown mode; OBX_E_NOMEM.
 * Threads: safe on distinct results. */
int obx_result_certify(obx_result *r, const char *mode, double *upper, double *lower, obx_error *err);

/* ---- batch: many jobs at once --------------------------------------------- */

/* One job of a batch: the arguments of obx_fit. */
typedef struct {
    int curve;
    const char *method;
    double d, tol;
    const char *metric;     /* NULL: hausdorff */
    const char *split;      /* NULL: mid */
    const char *params;     /* NULL: the defaults; else "NAME=VALUE,..." */
} obx_job_spec;

/* Told the jobs finished so far (done of total) as the batch runs. */
typedef void (*obx_progress_fn)(void *ctx, size_t done, size_t total);
/* The same; a nonzero return stops the batch (obx_run_batch_stop). */
typedef int (*obx_progress_stop_fn)(void *ctx, size_t done, size_t total);

/* Purpose: run n jobs together, as one `offbench run` runs its jobs (OpenMP
 *          threads over all of them; jobs that differ only in tol share
 *          pieces): every result is what obx_fit gives for its spec.
 * Inputs:  jobs[n]; progress (NULL: none), called with ctx by the calling
 *          thread (since 0.5; before, from a driver thread inside its lock)
 *          as jobs finish, done rising strictly to total, outside every
 *          lock of the library: it may call obx_fit, obx_measure or
 *          obx_run_batch itself.  (With a callback the driver runs on a
 *          thread of the library's own, kept for the next batch.)
 * Outputs: out[n], one result per job, in the specs' order (free each
 *          with obx_result_free); all NULL after an error.
 * Errors:  as obx_fit, the message prefixed "job I: " for the first bad
 *          spec (no job runs then); OBX_E_INVALID for n 0 or NULL arrays.
 * Threads: safe, also on one shared set. */
int obx_run_batch(const obx_curveset *set, const obx_job_spec *jobs, size_t n, obx_progress_fn progress, void *ctx,
                  obx_result **out, obx_error *err);

/* Purpose: obx_run_batch whose progress callback can stop the batch (since
 *          0.5): a nonzero return stops it at its next batch of work
 *          (the way `offbench run` stops on SIGINT), and progress is not
 *          called again.  A language binding answers 1 where its callback
 *          raised (Python's KeyboardInterrupt) and re-raises after.
 * Errors:  as obx_run_batch; OBX_E_STOPPED when the callback stopped it
 *          (also when every job had finished: out is all NULL). */
int obx_run_batch_stop(const obx_curveset *set, const obx_job_spec *jobs, size_t n, obx_progress_stop_fn progress,
                       void *ctx, obx_result **out, obx_error *err);

/* ---- measure -------------------------------------------------------------- */

typedef struct {
    double max_err;     /* the largest error over the pieces (+inf: not finite) */
    int piece;          /* where it is largest */
    char status[8];     /* "ok", "n/a" (the metric does not apply), "fail" */
    char why[160];      /* for n/a and fail: why; else "" */
} obx_measurement;

/* Purpose: measure an approximation, npieces Bézier pieces given as arrays
 *          (degrees[], xy[], w[] or NULL as in obx_curves_from_arrays),
 *          against the exact d-offset of curve `curve` under `metric`
 *          (NULL: hausdorff; also "hausdorff-whole", the two-sided
 *          distance of the whole approximation; since 0.3), as `offbench
 *          measure` does for a file without
 *          base links: each piece's base range is found by projecting its
 *          ends on the offset (a piece whose ends lie over different base
 *          segments is cut where it crosses each joint's normal line; piece
 *          stays its index in the arrays), then each piece is measured
 *          against its base piece, 256 samples.  The pieces must cover
 *          the offset once, whatever the metric (since 0.5: the CLI's check,
 *          by the same code, host/measure/measure.h): one piece of several,
 *          copies of a piece, a gap or an overlap are OBX_E_MEASURE; pieces
 *          out of order or reversed are measured.  bound and radial read the pieces at the
 *          base's parameter and so do not apply (status "n/a"); param needs
 *          read links and does not apply either.
 *          "trimmed-hausdorff" (since 0.7) is `offbench measure --trimmed`'s
 *          row, by its code (host/measure/trim.h, ob_measure_trimmed, 256
 *          samples): the two-sided distance between the pieces as a point
 *          set and the trimmed offset (the points at distance |d| from the
 *          base: the untrimmed offset's loops, and its parts nearer than |d|
 *          to another part of the base, cut away).  No match and no cover
 *          check: a trimmed approximation does not cover the untrimmed
 *          offset, and a missing part shows as a large distance; piece is
 *          the piece at or nearest the worst point.
 * Outputs: *m.
 * Errors:  OBX_E_INVALID (arguments as obx_fit, a bad piece), OBX_E_MEASURE
 *          (a piece that cannot be matched: "piece K: reason"; pieces that
 *          do not cover the offset once: "measure: pieces does not cover the
 *          d = D offset of curve ID once (G gaps, O overlaps, U duplicates);
 *          the first: piece K: ..."; trimmed-hausdorff: a trimmed offset
 *          that is empty, every point of it nearer than |d| to the base),
 *          OBX_E_NOMEM.
 * Threads: safe. */
int obx_measure(const obx_curveset *set, int curve, double d, int npieces, const int *degrees, const double *xy,
                const double *w, const char *metric, obx_measurement *m, obx_error *err);

/* One piece's own error (obx_measure_pieces), as a row of `offbench
 * measure --per-piece` (since 0.7). */
typedef struct {
    double max_err;         /* its hausdorff error against its base piece (+inf: not finite) */
    int seg0;               /* its base range: from parameter t0 of base segment seg0 */
    double t0;
    int seg1;               /* to t1 of segment seg1 (a piece over a joint of the base spans two) */
    double t1;
    int seg;                /* where the error is largest: the base segment and parameter t of */
    double t;               /* the exact offset point O(t) = C(t) + d N(t) there */
    double x, y;            /* the point of the piece nearest to O(t) (NAN when max_err is not finite) */
    double x_off, y_off;    /* O(t) itself: |(x, y) - (x_off, y_off)| is max_err */
    char status[8];         /* "ok", or "fail" (the error is not finite) */
    char why[160];          /* for fail: why; else "" */
} obx_piece_error;

/* Purpose: where an approximation's error is: each piece's own error and
 *          worst point, as `offbench measure --per-piece` writes them, by
 *          its code (host/measure/perpiece.h): the pieces (as obx_measure
 *          takes them) are matched and checked to cover the d-offset of
 *          curve `curve` once, exactly as obx_measure does, then each is
 *          measured under hausdorff against its base piece, 256 samples (a
 *          piece cut at a joint of the base is one row, its largest part's
 *          error).  The largest max_err over the rows is obx_measure's
 *          hausdorff max_err, bit for bit, at its piece.
 * Inputs:  set, curve, d, npieces, degrees[npieces], xy, w (NULL: all
 *          weights 1): as obx_measure.
 * Outputs: out[npieces]: row k is piece k of the arrays (pieces out of order
 *          or reversed are measured; each keeps its index); left as it was
 *          on an error.
 * Errors:  OBX_E_INVALID: set NULL, curve out of range, d not finite or 0
 *          or out of the curve's range, out NULL, npieces < 1, degrees or xy
 *          NULL, a degree out of range, a point not finite or a weight not
 *          > 0 ("piece K: point I ..."); OBX_E_MEASURE: a piece that
 *          cannot be matched or measured ("...piece K: reason"), pieces that
 *          do not cover the offset once (obx_measure's message);
 *          OBX_E_NOMEM.
 * Threads: safe.  Since 0.7. */
int obx_measure_pieces(const obx_curveset *set, int curve, double d, int npieces, const int *degrees,
                       const double *xy, const double *w, obx_piece_error *out, obx_error *err);

#ifdef __cplusplus
}
#endif

#endif
