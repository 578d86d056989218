/*
 * method.h - the interface every offset approximation method implements.
 *
 * Each method is one .c file exporting one const ob_method.  A method turns one
 * Bézier segment of the base curve and a signed distance d into an
 * approximating curve (usually one segment; a few pieces are allowed), written
 * into caller-owned storage.  Methods keep no static state, never allocate in
 * fit() (scratch space of work_size bytes is handed in by the driver) and never
 * print: they return an ob_fit_status and, on failure, a reason in msg.
 * That msg (char *msg, size_t msglen) is the CSV message column, data and not
 * an error report, so it is not an ob_err (methods/core/err.h).
 *
 * Adding a method: copy methods/TEMPLATE.c (a small working method, every
 * field commented) to methods/NAME.c, add the line OB_METHOD(NAME) to
 * methods/registry.def, and run `make check-method M=NAME`: the contract
 * every method keeps, what the generic tests check and how a method declares
 * an exception, is methods/CONTRACT.md.
 */
#ifndef OB_METHOD_H
#define OB_METHOD_H

#include <stddef.h>
#include "methods/core/curve.h"

/* What a method's fit returns (the job's status, ob_status in
 * methods/driver/driver.h, is the driver's: it maps these onto it in one
 * place).  OB_FIT_FAIL: no approximation (a singular system, no convergence);
 * OB_FIT_SKIP: the method does not apply to this input; both with the reason
 * in msg, and both end the job (status fail / skip).  OB_FIT_RETRY_SMALLER:
 * the method has no output for this piece that it may return (e.g. more
 * pieces than OB_SPLIT_PIECES or OB_MAX_PIECES, a pole); the driver then
 * splits the piece as if its error were too large.  OB_FIT_TIMEOUT: the fit
 * was stopped by a wall-clock cap of its own (sisl's server), which depends
 * on the machine's load and not on the input: the job ends with status
 * timeout, the reason in msg, so that it does not read as the method's
 * failure. */
typedef enum { OB_FIT_OK = 0, OB_FIT_FAIL, OB_FIT_SKIP, OB_FIT_RETRY_SMALLER, OB_FIT_TIMEOUT } ob_fit_status;
/* "ok", "fail", "skip", "retry-smaller", "timeout" (messages; not a CSV column). */
const char *ob_fit_status_name(ob_fit_status s);

/* OB_MAX_PIECES: the most pieces one fit can hold (one B-spline of up to 64
 * spans, bspline-lsq, is returned whole).  OB_SPLIT_PIECES: the most pieces
 * lee, sisl and elber's adaptive variant return before they ask for a smaller
 * piece (their published counts were reproduced with it; unchanged when the
 * storage grew). */
enum { OB_MAX_PIECES = 64, OB_SPLIT_PIECES = 16 };

/* The result of one fit: n pieces; piece i approximates the offset of the base
 * segment over base parameters [t[i], t[i+1]] (t[0] = 0, t[n] = 1).  The
 * pieces are what the metrics measure.  ctrl_points: 0 when the output is the
 * pieces themselves (they count 1 + sum of degrees, plus one for each joint
 * whose ends are apart: driver.h, joints.h); otherwise the number of control
 * points of the method's own representation of the same curve, e.g. a
 * B-spline whose Bézier pieces these are (README "Output": B-splines count
 * their control points). */
typedef struct {
    int n;
    long ctrl_points;
    double t[OB_MAX_PIECES + 1];
    ob_bez seg[OB_MAX_PIECES];
} ob_fit;

/* What a fit is asked to do, besides the segment itself. */
typedef struct {
    double d;            /* signed offset distance (d > 0: left of travel) */
    double tol;          /* the job's tolerance; for methods whose own
                            construction has an accuracy (Lee's circle
                            approximation, SISL's tolerance) */
    const double *par;   /* the method's nparams parameter values */
} ob_fit_args;

/* A parameter of a method: a choice the paper leaves open.  `def` is the
 * paper's reading; `./offbench run --param METHOD.NAME=VALUE` overrides it.
 * Every value the method accepts lies in [min, max] (and is a whole number
 * when `integer`); `--param` refuses any other before a job runs
 * (ob_param_check), so fit() never sees one.  The ranges are what each fit()
 * checks itself; the method contract test holds every default inside its
 * range. */
typedef struct {
    const char *name;
    double def;
    const char *doc;   /* what the values mean, and where the default comes from */
    double min, max;   /* the accepted values, both included */
    int integer;       /* 1: only whole numbers */
} ob_param;

enum { OB_MAX_PARAMS = 8 };

/* Capability flags.  Some only tell the generic contract test
 * (methods/CONTRACT.md) what to expect: OB_CAP_INTERP_ENDS turns a check on,
 * OB_CAP_ORIENTED, OB_CAP_TOL_DRIVEN and OB_CAP_NONMONOTONE each turn one
 * off.  None of those changes what a run computes. */
enum {
    OB_CAP_POLY_OUT     = 1u << 0,  /* output is polynomial for polynomial input */
    OB_CAP_RATIONAL_OUT = 1u << 1,  /* output is rational */
    OB_CAP_RATIONAL_IN  = 1u << 2,  /* accepts rational input segments */
    OB_CAP_CONVEX       = 1u << 3,  /* needs pieces without inflections */
    OB_CAP_SAME_PARAM   = 1u << 4,  /* output shares the base's parameter (bound/radial metrics apply) */
    OB_CAP_ORIENTED     = 1u << 5,  /* the result depends on the parameter's direction (e.g. a
                                       normalization at t = 0): the reversed curve gets another
                                       approximation */
    OB_CAP_TOL_DRIVEN   = 1u << 6,  /* the accuracy comes from the job's tolerance through the
                                       method's own construction (Lee's circle, SISL), not only
                                       from the piece's size: halving need not reduce the error */
    OB_CAP_CUSP_BREAKS  = 1u << 7,  /* the driver cuts the initial pieces at the offset's cusps
                                       (ob_bez_offset_cusps): the method fits up to a cusp, not
                                       across it */
    OB_CAP_INTERP_ENDS  = 1u << 8,  /* the approximation passes through the exact offset's end
                                       points C(0) + d N(0) and C(1) + d N(1) (the contract test
                                       checks it to 1e-12) */
    OB_CAP_NONMONOTONE  = 1u << 9,  /* halving a piece need not lower the method's error (for a
                                       reason other than OB_CAP_TOL_DRIVEN): the contract test's
                                       halving rule is not applied; the driver still splits */
};

typedef struct ob_method {
    const char *name;       /* CLI and CSV name */
    const char *citation;   /* short reference */
    /* Bumped whenever the method's output changes on purpose (a fix, another
     * reading of the paper), so that runs of different versions are not
     * compared for regressions (meta.json method_versions; compare exit 3). */
    int version;
    /* claimed for the approximation at segment joints, e.g. "G0", "C1/G2",
     * "none" (the pieces are not made to meet); what a run reaches is
     * measured (joints.h: results.csv max_gap, max_kink, continuity) */
    const char *continuity;
    unsigned caps;
    /* >0: the driver splits pieces so the tangent turns by less than this (rad) */
    double max_turn;
    /* Degree of every output piece for an input of degree n (rational_in:
     * weights != 1) under the parameter values par (never NULL: callers go
     * through ob_method_out_degree, which supplies the defaults); a method
     * with a degree parameter (zhao, hoschek) reads it here.  The method
     * contract test checks every fit against it, at the defaults and at
     * both ends of every parameter's range. */
    int (*out_degree)(int n, int rational_in, const double *par);
    /* Median thread time per job (ms) in the nightly baseline's random set
     * (hausdorff, mid, five tolerances: results/plots/
     * nightly_time_per_job.png): the cost model of --shard (host/run/shard.c);
     * 0 counts as 2 ms. */
    double cost_ms;
    size_t work_size;       /* bytes of scratch per fit call */
    /* NULL when fit() ignores the tolerance (the output depends on the piece,
     * d and the parameters only); else 1 when it reads it with these
     * parameter values.  Jobs that differ only in their tolerance share the
     * fits and measurements of the pieces they have in common when it is
     * NULL or returns 0 (the driver's shared pieces; the method contract
     * test checks the claim). */
    int (*fit_uses_tol)(const double *par);
    const ob_param *params; /* NULL, or nparams (<= OB_MAX_PARAMS) entries */
    int nparams;
    /* Purpose: approximate the d-offset of `base` over its whole [0,1].
     * Inputs:  a: distance, tolerance and parameter values.
     * Returns OB_FIT_OK, OB_FIT_FAIL (singular system, no convergence; reason
     * in msg), OB_FIT_SKIP (not applicable to this input; reason in msg) or
     * OB_FIT_RETRY_SMALLER (see ob_fit_status). */
    ob_fit_status (*fit)(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                         char *msg, size_t msglen);
} ob_method;

/* ---- work done outside the calling thread ------------------------------ */

/* A method whose fit runs its work elsewhere (sisl: s1360 in a server
 * process) adds the CPU time spent there for the calling thread, so that a
 * timer reading the thread's CPU clock can count it too (the method's own
 * time, host/run/fittime.c); the total is the calling thread's, never reset. */
void ob_fit_foreign_add(double ns);
double ob_fit_foreign_ns(void);

/* The CPU time the job of the calling thread's next fit has left under
 * --job-timeout (0: no limit), set by the driver before each fit: a method
 * whose fit runs its work elsewhere (sisl) stops that work past it and
 * returns OB_FIT_TIMEOUT, as the driver would end the job. */
void ob_fit_budget_set(double ns);
double ob_fit_budget_ns(void);

/* ---- registry (methods/registry.c) ------------------------------------ */

/* NULL-terminated: the built-ins of registry.def, then those registered at
 * run time.  Written only by ob_method_register, before any run starts. */
extern const ob_method *ob_methods[];
/* The most methods registered at run time (external methods). */
enum { OB_MAX_EXTERNAL = 8 };
/* Purpose: append m to ob_methods (m must outlive every use).  Returns 0,
 *          or -1 when the name is taken or the table is full. */
int ob_method_register(const ob_method *m);
const ob_method *ob_method_find(const char *name);
int ob_method_count(void);
/* Position of m in ob_methods, or -1. */
int ob_method_index(const ob_method *m);
/* Index of the parameter called name, or -1. */
int ob_param_find(const ob_method *m, const char *name);
/* 0 when v is an accepted value of parameter p (finite, in [min, max], whole
 * if p->integer); else -1 with "METHOD.NAME = V is out of range: ..." in msg. */
int ob_param_check(const ob_method *m, const ob_param *p, double v, char *msg, size_t msglen);
/* The method's default parameter values, into par[OB_MAX_PARAMS]. */
void ob_param_defaults(const ob_method *m, double *par);

/* Helpers shared by method files. */
void ob_fit_single(ob_fit *out, const ob_bez *seg);
/* out_degree for methods whose output has the input's degree. */
int ob_degree_same(int n, int rational_in, const double *par);
/* out_degree for methods whose output is cubic whatever the input. */
int ob_degree_three(int n, int rational_in, const double *par);
/* The output degree of a method with a degree parameter: pd rounded when
 * pd >= 0.5, else (0: "the base's degree") n.  The fit and out_degree read
 * it through this one rule. */
int ob_degree_or_param(int n, double pd);
/* The degree of method m's output pieces for an input of degree n with
 * parameter values par (NULL: the defaults). */
int ob_method_out_degree(const ob_method *m, int n, int rational_in, const double *par);
/* fit_uses_tol for methods that always read the tolerance. */
int ob_fit_uses_tol_always(const double *par);
/* 1 when method m's fit reads the tolerance with parameter values par (NULL:
 * the defaults). */
int ob_method_fit_uses_tol(const ob_method *m, const double *par);
int ob_method_msg(char *msg, size_t msglen, const char *fmt, ...);

#endif
