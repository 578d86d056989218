/*
 * signals.c - the process-wide stop flag (see signals.h).
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "host/diag.h"
#include "host/run/signals.h"

static volatile sig_atomic_t stop_signal = 0;
/* set once a line said what the stop left behind: main adds none */
static int stop_said = 0;

static void on_stop_signal(int sig)
{
    stop_signal = sig;
}

/* SA_RESETHAND: a second signal kills, should a loop not poll.  SA_RESTART:
 * system calls (writes of a file being committed) are not cut short. */
void ob_signals_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sa.sa_flags = SA_RESETHAND | SA_RESTART;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

const volatile sig_atomic_t *ob_stop_flag(void) { return &stop_signal; }

int ob_stop_signal(void) { return (int)stop_signal; }

void ob_note_stop(int sig)
{
    if (!stop_signal)
        stop_signal = sig;
}

int ob_stop_exit(const char *fmt, ...)
{
    char what[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    ob_error("interrupted by signal %d: %s", (int)stop_signal, what);
    stop_said = 1;
    return 128 + stop_signal;
}

int ob_stop_status(int rc)
{
    if (!stop_signal)
        return rc;
    if (!stop_said)
        ob_stop_exit("every file written was complete when it was renamed into place; rerun the command to "
                     "finish");
    return 128 + stop_signal;
}
