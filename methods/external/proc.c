/*
 * proc.c - an external method's worker process (proc.h).
 *
 * Started as the sisl server is (methods/sisl/client.c): fork, then only
 * async-signal-safe calls (dup2, setrlimit, close, execve) before exec,
 * since the caller is a threaded process; the transfers reuse the sisl
 * protocol's socket helpers (methods/sisl/io.c).
 */
#define _GNU_SOURCE /* SOCK_CLOEXEC, prlimit */
#include "methods/external/proc.h"

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "methods/method.h"
#include "methods/sisl/proto.h"

/* Between fork and exec: the socket as stdin and stdout, every other
 * descriptor above stderr closed, the memory cap, exec. */
static void exec_worker(const char *command, int fd, int maxfd, double mem_mb, char *const envp[])
{
    dup2(fd, 0);
    dup2(fd, 1);
    for (int i = 3; i < maxfd; i++)
        close(i);
    if (mem_mb > 0) {
        const rlim_t b = (rlim_t)(mem_mb * 1048576.0);
        const struct rlimit rl = {b, b};
        setrlimit(RLIMIT_AS, &rl);
    }
    setpgid(0, 0);  /* its own group: a kill reaches what the command started */
    char *const argv[] = {"sh", "-c", (char *)command, NULL};
    execve("/bin/sh", argv, envp);
    _exit(127);
}

#if defined(__SANITIZE_ADDRESS__)
/* 1 when command's program (its first word, a path) is this program's
 * file (`offbench worker ...` started by offbench itself). */
static int runs_self(const char *command)
{
    char prog[4096];
    const size_t n = strcspn(command, " \t");
    struct stat a, b;
    if (n == 0 || n >= sizeof prog)
        return 0;
    memcpy(prog, command, n);
    prog[n] = '\0';
    if (prog[0] == '\'' && n > 1 && prog[n - 1] == '\'') { /* quoted for sh: bench's own worker */
        memmove(prog, prog + 1, n - 2);
        prog[n - 2] = '\0';
    }
    return stat(prog, &a) == 0 && stat("/proc/self/exe", &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}
#endif

/* A worker that will start under AddressSanitizer: libasan preloaded (as a
 * sanitized Python test runs its interpreter and so its workers), or, in a
 * build with it (make SAN=1), this program itself as a worker (`offbench
 * worker`).  ASan reserves terabytes of shadow address space at start and
 * cannot start under RLIMIT_AS at all, so such a worker gets no
 * address-space cap; any other worker keeps it. */
static int asan_worker(const char *command)
{
    const char *p = getenv("LD_PRELOAD");
    if (p && strstr(p, "libasan") != NULL)
        return 1;
#if defined(__SANITIZE_ADDRESS__)
    return runs_self(command);
#else
    (void)command;
    return 0;
#endif
}

int ob_ext_proc_start(ob_ext_proc *w, const char *command, double mem_mb, char *msg, size_t msglen)
{
    extern char **environ;
    if (asan_worker(command))
        mem_mb = 0;
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
        ob_method_msg(msg, msglen, "cannot start the worker: socketpair: %s", strerror(errno));
        return -1;
    }
    const long om = sysconf(_SC_OPEN_MAX);
    const int maxfd = om > 0 && om < 65536 ? (int)om : 1024;
    /* a simple command replaces the shell (dash forks for `sh -c CMD`), so
     * that the worker is the process whose CPU time is read and capped */
    char *cmd = malloc(strlen(command) + 6);
    if (!cmd) {
        close(sv[0]), close(sv[1]);
        ob_method_msg(msg, msglen, "cannot start the worker: out of memory");
        return -1;
    }
    sprintf(cmd, "%s%s", strpbrk(command, ";&|<>()`$\n") ? "" : "exec ", command);
    const pid_t pid = fork();
    if (pid == 0)
        exec_worker(cmd, sv[1], maxfd, mem_mb, environ);
    free(cmd);
    if (pid > 0)
        setpgid(pid, pid);  /* as the child does: no kill of the group can come before it */
    const int e = errno;
    close(sv[1]);
    if (pid < 0) {
        close(sv[0]);
        ob_method_msg(msg, msglen, "cannot start the worker: fork: %s", strerror(e));
        return -1;
    }
    w->pid = pid, w->owner = getpid(), w->fd = sv[0], w->have = 0, w->last = 0;
    return 0;
}

/* The line that ends in buf, if one does: its length, else -1. */
static long line_end(const ob_ext_proc *w)
{
    const char *nl = w->have ? memchr(w->buf, '\n', w->have) : NULL;
    return nl ? nl - w->buf : -1;
}

/* Drops the line of length n (and its '\n') returned last time. */
static void consume(ob_ext_proc *w, size_t n)
{
    memmove(w->buf, w->buf + n, w->have - n);
    w->have -= n;
}

int ob_ext_proc_line(ob_ext_proc *w, double deadline, char **line, size_t *len)
{
    if (w->last && w->last <= w->have)
        consume(w, w->last);
    w->last = 0;
    long n;
    while ((n = line_end(w)) < 0) {
        if (w->have >= OB_EXT_MAX_LINE) {
            w->buf[OB_EXT_MAX_LINE - 1] = '\0';
            *line = w->buf, *len = w->have;
            return -2;
        }
        if (w->cap - w->have < 65536 + 1) {
            const size_t nc = w->cap ? 2 * w->cap : 65536 * 2;
            char *nb = realloc(w->buf, nc);
            if (!nb)
                return -1;
            w->buf = nb, w->cap = nc;
        }
        const double left = deadline - ob_sisl_now();
        if (left <= 0)
            return 1;
        struct pollfd pf = {w->fd, POLLIN, 0};
        const int pr = poll(&pf, 1, left > 86400 ? 86400000 : (int)(left * 1000) + 1);
        if (pr <= 0) {
            if (pr < 0 && errno != EINTR)
                return -1;
            continue;
        }
        const ssize_t r = read(w->fd, w->buf + w->have, w->cap - w->have - 1);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        w->have += (size_t)r;
    }
    w->buf[n] = '\0';
    *line = w->buf, *len = (size_t)n;
    w->last = (size_t)n + 1;
    return 0;
}

int ob_ext_proc_send(ob_ext_proc *w, const char *buf, size_t n)
{
    return w->fd >= 0 ? ob_sisl_send_all(w->fd, buf, n) : -1;
}

void ob_ext_proc_stop(ob_ext_proc *w, int sig, int *wstatus)
{
    int ws = -1;
    if (w->fd >= 0)
        close(w->fd);
    if (w->pid > 0 && w->owner == getpid()) {
        if (sig)
            kill(-w->pid, sig), kill(w->pid, sig);  /* the group (exec_worker): a shell's children too */
        while (waitpid(w->pid, &ws, 0) < 0 && errno == EINTR)
            ;
    }
    w->fd = -1, w->pid = 0, w->have = 0, w->last = 0;
    if (wstatus)
        *wstatus = ws;
}

/* The worker's CPU time from /proc/PID/stat: in clock ticks (10 ms), the
 * fallback where its CPU clock cannot be read. */
static double cpu_ns_proc(const ob_ext_proc *w)
{
    char path[64], buf[1024];
    snprintf(path, sizeof path, "/proc/%d/stat", (int)w->pid);
    FILE *f = w->pid > 0 ? fopen(path, "r") : NULL;
    const size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f)
        fclose(f);
    buf[n] = '\0';
    const char *p = strrchr(buf, ')');  /* the command name may hold spaces */
    unsigned long ut, st;
    /* after ")": state ppid pgrp session tty tpgid flags minflt cminflt majflt cmajflt utime stime */
    if (!p || sscanf(p + 1, " %*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %lu %lu", &ut, &st) != 2)
        return -1.0;
    return 1e9 * (double)(ut + st) / (double)sysconf(_SC_CLK_TCK);
}

/* The process CPU-time clock of the worker (all its threads), in ns: a fit
 * of 100 us shows as 100 us, where /proc's ticks would give 0 or 10 ms,
 * and one system call instead of a file opened, read and parsed. */
double ob_ext_proc_cpu_ns(const ob_ext_proc *w)
{
    clockid_t id;
    struct timespec ts;
    if (w->pid > 0 && clock_getcpuclockid(w->pid, &id) == 0 && clock_gettime(id, &ts) == 0)
        return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
    return cpu_ns_proc(w);
}

void ob_ext_proc_cpu_cap(const ob_ext_proc *w, double seconds)
{
    const double used = ob_ext_proc_cpu_ns(w);
    struct rlimit rl;
    if (used < 0 || prlimit(w->pid, RLIMIT_CPU, NULL, &rl) != 0)
        return;
    /* only the soft limit: a hard one, once lowered, could not be raised
     * again for the next request */
    rl.rlim_cur = (rlim_t)ceil(1e-9 * used + (seconds < 1 ? 1 : seconds));
    if (rl.rlim_max != RLIM_INFINITY && rl.rlim_cur > rl.rlim_max)
        rl.rlim_cur = rl.rlim_max;
    prlimit(w->pid, RLIMIT_CPU, &rl, NULL);
}
