/*
 * diag.c - the message funnel.  See diag.h.
 */
#include "host/diag.h"

#include <stdarg.h>
#include <stdio.h>

/* The funnel's own prints: the only fprintf(stderr) for messages. */
static void default_handler(const char *message) { fprintf(stderr, "offbench: %s\n", message); }

static ob_error_handler handler = default_handler;

ob_error_handler ob_set_error_handler(ob_error_handler h)
{
    ob_error_handler old = handler;
    handler = h ? h : default_handler;
    return old;
}

void ob_error(const char *fmt, ...)
{
    char buf[8192]; /* an ob_err's msg whole (err.h): a list of skipped entities runs past 1024 */
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    handler(buf);
}

/* Informational lines are not errors: they go to stderr whatever handler
 * the errors have (a test capturing errors still sees the run's figures). */
static void vnote(const char *prefix, const char *fmt, va_list ap)
{
    char buf[8192];
    vsnprintf(buf, sizeof buf, fmt, ap);
    fprintf(stderr, "offbench: %s%s\n", prefix, buf);
}

void ob_warn(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vnote("warning: ", fmt, ap);
    va_end(ap);
}

void ob_info(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vnote("", fmt, ap);
    va_end(ap);
}
