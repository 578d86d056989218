/*
 * signals.c - the process-wide stop flag (see signals.h).
 */
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "host/diag.h"
#include "host/run/signals.h"

static volatile sig_atomic_t stop_signal = 0;
/* set once a line said what the stop left behind: main adds none */
static int stop_said = 0;
/* what ob_stop_status says once the command's output is complete (ob_stop_done) */
static const char *done_note = NULL;

/* when the first stop came, in CLOCK_MONOTONIC milliseconds */
static volatile long long stop_at_ms = 0;

static long long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);  /* async-signal-safe (POSIX) */
    return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* The first signal is the stop.  A second one within OB_STOP_REPEAT_MS is
 * the same stop: timeout(1) sends its signal to the command and then to
 * the command's process group, so a program run under it gets each stop
 * twice.  A later one acts as usual (kills), should a loop not poll.
 * Called from the watcher thread, or from the handler (async-signal-safe). */
#define OB_STOP_REPEAT_MS 1000
static void take_signal(int sig)
{
    if (!stop_signal) {
        stop_at_ms = now_ms();
        stop_signal = sig;
        return;
    }
    if (now_ms() - stop_at_ms < OB_STOP_REPEAT_MS)
        return;
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    signal(sig, SIG_DFL);
    pthread_sigmask(SIG_UNBLOCK, &one, NULL);
    raise(sig);
}

static void on_stop_signal(int sig) { take_signal(sig); }

static void *watch_signals(void *set)
{
    for (;;) {
        int sig = 0;
        if (sigwait((const sigset_t *)set, &sig) == 0)
            take_signal(sig);
    }
    return NULL;
}

/* Why a thread and not only a handler: a library loaded later may install
 * its own handler over ours (LLVM, which PoCL loads, installs one with
 * SA_RESETHAND that re-raises into the previous one; a second signal in
 * that window meets the default action and kills the process silently).
 * With INT and TERM blocked in this thread, before any other thread exists,
 * every thread (OpenMP, MPI, PoCL) inherits the block, no handler runs, and
 * the watcher takes each signal with sigwait.  A child forked for SISL
 * inherits the block too: a terminal's Ctrl-C to the process group does not
 * kill it under the parent, which ends it when it stops.  The handler stays
 * for a thread that was started before this and does not block them. */
void ob_signals_install(void)
{
    static sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sa.sa_flags = SA_RESTART;  /* writes of a file being committed are not cut short */
    sa.sa_mask = set;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    pthread_attr_t at;
    pthread_t th;
    pthread_sigmask(SIG_BLOCK, &set, NULL);
    if (pthread_attr_init(&at) == 0) {
        pthread_attr_setdetachstate(&at, PTHREAD_CREATE_DETACHED);
        pthread_attr_setstacksize(&at, 64 * 1024);
        int rc = pthread_create(&th, &at, watch_signals, &set);
        pthread_attr_destroy(&at);
        if (rc == 0)
            return;
    }
    pthread_sigmask(SIG_UNBLOCK, &set, NULL);  /* no watcher: the handler takes them */
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

void ob_stop_done(const char *what) { done_note = what; }

int ob_stop_status(int rc)
{
    if (!stop_signal)
        return rc;
    if (!stop_said && done_note)
        ob_stop_exit("%s", done_note);
    else if (!stop_said)
        ob_stop_exit("every file written was complete when it was renamed into place; rerun the command to "
                     "finish");
    return 128 + stop_signal;
}
