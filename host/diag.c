/*
 * diag.c - error funnel.  See diag.h.
 */
#include "diag.h"

#include <stdarg.h>
#include <stdio.h>

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
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    handler(buf);
}
