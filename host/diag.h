/*
 * diag.h - the one funnel every user-facing message goes through.
 *
 * ob_error() formats a message and hands it to the current handler (by default:
 * "offbench: MESSAGE" on stderr).  It never aborts: callers return a status.
 * Tests install a handler to capture messages.  ob_warn() ("offbench:
 * warning: MESSAGE") and ob_info() ("offbench: MESSAGE") are the lines that
 * report, not fail: always on stderr, one line each (no newline in fmt).
 * Functions below the commands do not print their errors: they fill an
 * ob_err (methods/core/err.h, included here) and return -1, and the command
 * hands err.msg to ob_error().
 */
#ifndef OB_DIAG_H
#define OB_DIAG_H

#include "methods/core/err.h"

typedef void (*ob_error_handler)(const char *message);

/* Install a handler (NULL restores the default); returns the previous one. */
ob_error_handler ob_set_error_handler(ob_error_handler h);

void ob_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void ob_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void ob_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
