/*
 * method.h - the interface every offset approximation method implements.
 *
 * Each method is one .c file exporting one const ob_method.  A method turns one
 * Bézier segment of the base curve and a signed distance d into an
 * approximating curve (usually one segment; a few pieces are allowed), written
 * into caller-owned storage.  Methods keep no static state, never allocate in
 * fit() (scratch space of work_size bytes is handed in by the driver) and never
 * print: they return a status and, on failure, a reason in msg.
 *
 * Adding a method: write methods/NAME.c exporting `const ob_method
 * ob_method_NAME`, and add one line to methods/registry.c.
 */
#ifndef OB_METHOD_H
#define OB_METHOD_H

#include <stddef.h>
#include "curve.h"

/* Job and fit status, in the spelling of the CSV `status` column. */
typedef enum { OB_OK = 0, OB_LIMIT, OB_FAIL, OB_SKIP } ob_status;
const char *ob_status_name(ob_status s);

enum { OB_MAX_PIECES = 8 };

/* The result of one fit: n pieces; piece i approximates the offset of the base
 * segment over base parameters [t[i], t[i+1]] (t[0] = 0, t[n] = 1). */
typedef struct {
    int n;
    double t[OB_MAX_PIECES + 1];
    ob_bez seg[OB_MAX_PIECES];
} ob_fit;

/* A parameter of a method: a choice the paper leaves open.  `def` is the
 * paper's reading; `./offbench run --param METHOD.NAME=VALUE` overrides it. */
typedef struct {
    const char *name;
    double def;
    const char *doc;   /* what the values mean, and where the default comes from */
} ob_param;

enum { OB_MAX_PARAMS = 8 };

/* Capability flags. */
enum {
    OB_CAP_POLY_OUT     = 1u << 0,  /* output is polynomial for polynomial input */
    OB_CAP_RATIONAL_OUT = 1u << 1,  /* output is rational */
    OB_CAP_RATIONAL_IN  = 1u << 2,  /* accepts rational input segments */
    OB_CAP_CONVEX       = 1u << 3,  /* needs pieces without inflections */
    OB_CAP_SAME_PARAM   = 1u << 4,  /* output shares the base's parameter (bound/radial metrics apply) */
};

typedef struct ob_method {
    const char *name;       /* CLI and CSV name */
    const char *citation;   /* short reference */
    const char *continuity; /* of the approximation at segment joints, e.g. "G0", "C1/G2" */
    unsigned caps;
    /* >0: the driver splits pieces so the tangent turns by less than this (rad) */
    double max_turn;
    /* degree of the output for an input of degree n (rational_in: weights != 1) */
    int (*out_degree)(int n, int rational_in);
    size_t work_size;       /* bytes of scratch per fit call */
    const ob_param *params; /* NULL, or nparams (<= OB_MAX_PARAMS) entries */
    int nparams;
    /* Purpose: approximate the d-offset of `base` over its whole [0,1].
     * Inputs:  par: the nparams parameter values (defaults unless overridden).
     * Returns OB_OK, OB_FAIL (singular system, no convergence; reason in msg)
     * or OB_SKIP (not applicable to this input; reason in msg). */
    ob_status (*fit)(const ob_bez *base, double d, const double *par, void *work,
                     ob_fit *out, char *msg, size_t msglen);
} ob_method;

/* ---- registry (methods/registry.c) ------------------------------------ */

extern const ob_method *const ob_methods[];   /* NULL-terminated */
const ob_method *ob_method_find(const char *name);
int ob_method_count(void);
/* Position of m in ob_methods, or -1. */
int ob_method_index(const ob_method *m);
/* Index of the parameter called name, or -1. */
int ob_param_find(const ob_method *m, const char *name);
/* The method's default parameter values, into par[OB_MAX_PARAMS]. */
void ob_param_defaults(const ob_method *m, double *par);

/* Helpers shared by method files. */
void ob_fit_single(ob_fit *out, const ob_bez *seg);
/* out_degree for methods whose output has the input's degree. */
int ob_degree_same(int n, int rational_in);
int ob_method_msg(char *msg, size_t msglen, const char *fmt, ...);

#endif
