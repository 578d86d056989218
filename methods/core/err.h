/*
 * err.h - ob_err, the one error carrier of offbench.
 *
 * It lives in methods/core/ (not host/) because methods/ may not include
 * host/ headers and one methods/ function reports reader errors
 * (ob_bspline_to_bezier, called by the curve and DXF readers); host/diag.h
 * includes it, so host/ code sees it with the funnel.
 *
 * Holds:     msg, one message without a newline and without the
 *            "offbench: " prefix, e.g. "data/x.curves:12: bad degree".
 * Filled by: the function that fails, with ob_fail() (its return value is
 *            the -1 it returns); a function that succeeds leaves it as it
 *            was, so a caller reads msg only after a failure.
 * Reported:  by whoever decides the run cannot go on, usually a command:
 *            ob_error("%s", err.msg) (host/diag.h).  Lines that report
 *            without failing go through ob_warn()/ob_info(), never here.
 * A method's fit message (the CSV message column) is data, not an error,
 * and keeps its char *msg, size_t msglen (methods/method.h).
 */
#ifndef OB_ERR_H
#define OB_ERR_H

#include <stdarg.h>

/* 8192 bytes: as long as the longest line the funnel prints (ob_warn,
 * ob_info), so no message is cut shorter than before the carrier (an OpenCL
 * build log runs to kilobytes).  Passed by pointer, it costs a stack frame. */
typedef struct ob_err {
    char msg[8192];
} ob_err;

/* Purpose: record a failure.
 * Inputs:  e (may be NULL: the caller wants no message), printf format.
 * Outputs: e->msg, truncated to fit; e->msg may itself be an argument
 *          (ob_fail(e, "%s: %s", path, e->msg) prefixes a callee's message).
 * Errors:  returns -1 always, so `return ob_fail(e, "...", ...);` reads as
 *          the failure it is. */
int ob_fail(ob_err *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* As ob_fail, from a va_list (for helpers that add a prefix of their own). */
int ob_vfail(ob_err *e, const char *fmt, va_list ap) __attribute__((format(printf, 2, 0)));

#endif
