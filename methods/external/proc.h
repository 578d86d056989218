/*
 * proc.h - one external method worker process (docs/external-methods.md):
 * started with `/bin/sh -c COMMAND`, its stdin and stdout one end of a
 * socket pair (send with MSG_NOSIGNAL: a worker gone never raises SIGPIPE
 * in offbench, which a pipe would), stderr shared with offbench.
 */
#ifndef OB_EXT_PROC_H
#define OB_EXT_PROC_H

#include <stddef.h>
#include <sys/types.h>

/* The longest line a worker may send (a hello or an answer). */
enum { OB_EXT_MAX_LINE = 4 << 20 };

typedef struct {
    pid_t pid, owner;   /* the worker, the process that started it (0: none) */
    int fd;             /* our end; -1: none */
    char *buf;          /* what was read and not yet returned as a line */
    size_t have, cap;
    size_t last;        /* the length + 1 of the line returned last, dropped on the next read */
} ob_ext_proc;

/* Purpose: start COMMAND with its address space capped at mem_mb MiB
 *          (RLIMIT_AS, set in the child; 0: no cap).  Returns 0, or -1 with
 *          the reason in msg. */
int ob_ext_proc_start(ob_ext_proc *w, const char *command, double mem_mb, char *msg, size_t msglen);

/* Purpose: the next line (without its '\n', NUL-terminated, valid until the
 *          next call) before the monotonic deadline (s).  Returns 0; 1 timed
 *          out; -1 the worker closed its end; -2 a line longer than
 *          OB_EXT_MAX_LINE (*line then holds its start). */
int ob_ext_proc_line(ob_ext_proc *w, double deadline, char **line, size_t *len);

/* Writes all of buf: 0, or -1 when the worker is gone. */
int ob_ext_proc_send(ob_ext_proc *w, const char *buf, size_t n);

/* Purpose: end the worker: our end closed, then, when this process started
 *          it, signal sig (0: none, it ends on EOF) and reap it.  A worker of
 *          another process (a fork inherited it) is only forgotten.
 *          *wstatus (may be NULL): its wait status, -1 unknown. */
void ob_ext_proc_stop(ob_ext_proc *w, int sig, int *wstatus);

/* The worker's CPU time so far (ns: its process CPU-time clock, else
 * /proc/PID/stat in clock ticks), -1 when unknown. */
double ob_ext_proc_cpu_ns(const ob_ext_proc *w);

/* Purpose: let the worker run at most `seconds` more CPU time (RLIMIT_CPU,
 *          set from outside with prlimit: the worker is any program);
 *          past it the kernel ends it with SIGXCPU, then SIGKILL. */
void ob_ext_proc_cpu_cap(const ob_ext_proc *w, double seconds);

#endif
