/*
 * signals.h - SIGINT and SIGTERM, for every command: blocked in every
 * thread and taken by one watcher thread (installed once, by main, before
 * any other thread), which records the signal in a process-wide flag; every
 * long loop polls it and stops at its next step; the command ends with
 * exit status 128 + the signal and a line saying what it left behind.  A
 * second signal within a second of the first is the same stop (timeout(1)
 * sends each twice); one after that acts as usual (kills), for a loop that
 * does not poll.  Children forked after it keep both blocked.
 */
#ifndef OB_SIGNALS_H
#define OB_SIGNALS_H

#include <signal.h>

/* Purpose: from now on SIGINT / SIGTERM sent to the process set the stop
 *          flag (a signal raise()d at one thread stays pending: send it with
 *          kill(getpid(), sig)). */
void ob_signals_install(void);

/* The flag the driver reads (ob_driver_hooks.stop): the signal, 0 if none. */
const volatile sig_atomic_t *ob_stop_flag(void);

/* The signal that stopped the command, 0 if none. */
int ob_stop_signal(void);

/* Records sig as the stop (when none was): another MPI rank was stopped. */
void ob_note_stop(int sig);

/* Purpose: the one way a stopped command ends: "interrupted by signal N:
 *          <what was left behind>" on stderr.
 * Returns: 128 + the signal. */
int ob_stop_exit(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Purpose: the command's output is complete (what = what it left, e.g.
 *          "the CSV is complete"): a signal seen from now on ends it with
 *          128 + the signal and that line, not "rerun the command to
 *          finish", which would send the user to redo finished work.
 *          what must outlive the command (a literal). */
void ob_stop_done(const char *what);

/* Purpose: for main, after the command: a command that was stopped but
 *          returned another status (it had no long loop left to poll, or
 *          stopped in a way that said nothing) still ends with 128 + the
 *          signal, so that no signal is ever swallowed into exit 0.
 * Returns: rc, or 128 + the signal. */
int ob_stop_status(int rc);

#endif
