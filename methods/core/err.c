/*
 * err.c - the error carrier's setters.  See err.h.
 */
#include "methods/core/err.h"

#include <stdio.h>
#include <string.h>

/* Formatted through a copy so that e->msg may be one of the arguments
 * (prefixing a callee's message in place). */
int ob_vfail(ob_err *e, const char *fmt, va_list ap)
{
    char buf[sizeof e->msg];
    if (!e)
        return -1;
    vsnprintf(buf, sizeof buf, fmt, ap);
    memcpy(e->msg, buf, sizeof buf);
    return -1;
}

int ob_fail(ob_err *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ob_vfail(e, fmt, ap);
    va_end(ap);
    return -1;
}
