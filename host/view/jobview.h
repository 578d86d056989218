/*
 * jobview.h - one job of `draw` and `trace`: run it as `run` would, then
 * refit its accepted pieces to get the very approximation the run measured,
 * and evaluate the job's metric at single parameters.
 *
 * The job is (curve, d, method, metric, split, tol) from `run` options that
 * select exactly one curve, one method and one tolerance.  The driver logs
 * the accepted spans (seg, a, b); refitting span (a, b) of segment seg with
 * the method gives fit pieces over sub-parameters [t_i, t_{i+1}] of that
 * span, each measured by the driver against the base cut to the same range.
 * Those (base piece, approximating piece) pairs are kept here in curve order,
 * so the pointwise error below is exactly the function whose maximum the run
 * reported (kernels/metric_core.h, obc_err_at).
 */
#ifndef OB_JOBVIEW_H
#define OB_JOBVIEW_H

#include <stddef.h>

#include "host/backend/clrt.h"
#include "host/io/curvefile.h"
#include "host/run/options.h"

/* One accepted output piece. */
typedef struct {
    int seg;          /* base segment index */
    double ta, tb;    /* base parameters it covers in segment seg */
    ob_bez base;      /* segment seg over [ta, tb], cut as the driver cut it */
    ob_bez approx;    /* the approximating piece, over [0, 1] like base */
    int fit_first;    /* 1: the first piece of its fit (span) */
    int own_count;    /* 1: its fit counts its own representation (ob_fit.ctrl_points) */
} ob_jv_piece;

typedef struct {
    const char *cmd;        /* "draw" or "trace", for messages */
    ob_run_opts o;
    ob_curveset set;
    ob_cl *cl;
    ob_backend_info binfo;  /* what measures (ob_open_backend) */
    const ob_curve *curve;
    ob_job job;
    ob_span_log spans;
    ob_jv_piece *pieces;    /* npieces accepted pieces in curve order (after run) */
    int npieces;
    int samples;            /* S of the sampled metrics, as the driver used it */
} ob_jobview;

/* Purpose: from the run options in v->o (parsed by the caller, with one
 * method and one tolerance; the rest of *v zeroed), load the curves, pick
 * the one curve and set up the job.  d: the offset if have_d, else the
 * curve's first one.
 * Returns 0, or the exit status (2 bad input, 1 out of memory) after
 * ob_error().  Always call ob_jobview_close() afterwards. */
int ob_jobview_open(ob_jobview *v, const char *cmd, int have_d, double d);

/* Purpose: run the job (backend and threads as the options say), then refit
 * its spans when it ended ok or limit.  Returns 0 (also when the job itself
 * ended fail or skip: see v->job.status), or the exit status after ob_error():
 * 2 (the backend the options require is not available), 1 (out of memory; the
 * refit does not reproduce the run's counts: segments, and control points
 * with the open joints counted twice as the driver counts them). */
int ob_jobview_run(ob_jobview *v);

void ob_jobview_close(ob_jobview *v);

/* 1 when the job produced an approximation (status ok or limit). */
int ob_jobview_has_approx(const ob_jobview *v);

/* "CURVE: METHOD, d = D, tol = T, metric M, split S" */
void ob_jobview_describe(const ob_jobview *v, char *buf, size_t len);
/* "status ok, ctrl_points = N, segments = N, max_err = E, max_gap = G,
 * continuity = C": the figures of results.csv, written as it writes them
 * ("-" where its field is empty: max_err for fail and skip, max_gap and
 * continuity without joints). */
void ob_jobview_summary(const ob_jobview *v, char *buf, size_t len);

/* ---- the error at one parameter ------------------------------------------ */

/* Pointwise error of each metric:
 *   radial     | ||A(t) - C(t)|| - |d| |; the point is A(t);
 *   bound      has no pointwise form: the radial error is used (the bound
 *              of a piece is >= its radial maximum); the point is A(t);
 *   normal     |s - d| where the normal line C(t) + s N(t) meets A; the point
 *              is the exact offset O(t) = C(t) + d N(t);
 *   hausdorff  the distance from O(t) to the approximating piece (the
 *              offset-to-approximation side of the Hausdorff distance at that
 *              base parameter); the point is O(t). */

/* 1 when the point the error reports is A(t), 0 when it is O(t). */
int ob_jobview_point_is_approx(const ob_jobview *v);
/* Doubles of scratch one piece's evaluation needs (>= 1). */
size_t ob_jobview_scratch(const ob_jobview *v);
/* Fills scratch for piece p (the Hausdorff sample table of its approximation). */
void ob_jobview_prepare(const ob_jobview *v, const ob_jv_piece *p, double *scratch);
/* Error at piece parameter s in [0, 1] (base parameter ta + (tb - ta) s);
 * xy gets the point described above. */
double ob_jobview_err_at(const ob_jobview *v, const ob_jv_piece *p, const double *scratch, double s, double xy[2]);

#endif
