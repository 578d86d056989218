/*
 * client.c - the fitting process's side of the sisl server (proto.h).
 *
 * One server per calling thread, started on first use and again after it
 * ended.  Ownership: a server belongs to the process (pid) that started
 * it.  A child forked after fits (python's multiprocessing) inherits its
 * parent's descriptors; had it used them, parent and child would read each
 * other's replies (wrong results reported ok, bogus failures).  So at a
 * fork the child closes every inherited server socket (pthread_atfork),
 * never talking to those servers or signalling them, and, should a fork
 * bypass that handler, a server whose owner is not getpid() is dropped the
 * same way on use; the child starts its own.
 *
 * Threads: a thread's server is stopped (socket closed, process reaped)
 * when the thread exits (a pthread key's destructor): 60 threads each
 * making one fit used to leave 60 servers and 120 descriptors.  The
 * servers of live threads are in one list, changed under a mutex that a
 * fork holds too (prepare/parent/child handlers), so the child's handler
 * sees every server's descriptor as it is.
 *
 * The server is the program executed afresh (fork, then exec: the child of
 * a threaded process may only make async-signal-safe calls before exec;
 * once a sanitizer's allocator lock held at the fork left a server waiting
 * for ever).  The program is /proc/self/exe unless a library user named
 * another (sisl_server.h); the handshake (proto.h) tells a program that
 * serves from one that does not.
 */
#define _GNU_SOURCE /* SOCK_CLOEXEC, getrandom */
#include "methods/sisl/proto.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "methods/method.h"
#include "methods/sisl_server.h"

typedef struct sisl_server {
    pid_t pid, owner;           /* the server, the process that started it */
    int fd;                     /* our end of its socket; -1: none */
    double reported_ns;         /* the CPU time its replies reported */
    struct sisl_server *prev, *next;
} sisl_server;

static pthread_mutex_t reg_lock = PTHREAD_MUTEX_INITIALIZER;
static sisl_server *reg_head;
static pthread_key_t reg_key;
static pthread_once_t reg_once = PTHREAD_ONCE_INIT;

static void fork_prepare(void) { pthread_mutex_lock(&reg_lock); }
static void fork_parent(void) { pthread_mutex_unlock(&reg_lock); }

/* In a forked child: every server is the parent's; close, forget. */
static void fork_child(void)
{
    for (sisl_server *s = reg_head; s; s = s->next) {
        if (s->fd >= 0)
            close(s->fd);
        s->fd = -1;
        s->pid = 0;
    }
    pthread_mutex_unlock(&reg_lock);
}

/* Our end closed and, when this process started it, the server reaped
 * (killed first with sig unless 0); never a server of another process.
 * unreported: NULL, or 1 to count as the fit's what the server spent that
 * its replies did not report (a call it did not answer). */
static void server_drop(sisl_server *s, int sig, int *wstatus, int unreported)
{
    pthread_mutex_lock(&reg_lock);
    const pid_t pid = s->owner == getpid() ? s->pid : 0;
    const double reported = s->reported_ns;
    if (s->fd >= 0)
        close(s->fd);
    s->fd = -1;
    s->pid = 0;
    pthread_mutex_unlock(&reg_lock);
    int ws = -1;
    struct rusage ru;
    memset(&ru, 0, sizeof ru);
    if (pid > 0) {
        if (sig)
            kill(pid, sig);
        while (wait4(pid, &ws, 0, &ru) < 0 && errno == EINTR)
            ;
    }
    const double cpu = 1e9 * (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                       1e3 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
    if (unreported && cpu > reported)
        ob_fit_foreign_add(cpu - reported);  /* the job's time counts it (--job-timeout) */
    if (wstatus)
        *wstatus = ws;
}

/* A thread's end: its server stopped, its entry gone. */
static void thread_gone(void *p)
{
    sisl_server *s = p;
    server_drop(s, SIGKILL, NULL, 0);
    pthread_mutex_lock(&reg_lock);
    if (s->prev)
        s->prev->next = s->next;
    else
        reg_head = s->next;
    if (s->next)
        s->next->prev = s->prev;
    pthread_mutex_unlock(&reg_lock);
    free(s);
}

static void reg_init(void)
{
    pthread_key_create(&reg_key, thread_gone);
    pthread_atfork(fork_prepare, fork_parent, fork_child);
}

/* This thread's entry (made on first use); NULL when out of memory.  One
 * whose server is another process's (a fork the handlers missed) is
 * emptied without a word to that server. */
static sisl_server *my_server(void)
{
    pthread_once(&reg_once, reg_init);
    sisl_server *s = pthread_getspecific(reg_key);
    if (!s) {
        s = calloc(1, sizeof *s);
        if (!s || pthread_setspecific(reg_key, s) != 0) {
            free(s);
            return NULL;
        }
        s->fd = -1;
        pthread_mutex_lock(&reg_lock);
        s->next = reg_head;
        if (reg_head)
            reg_head->prev = s;
        reg_head = s;
        pthread_mutex_unlock(&reg_lock);
    }
    if (s->pid > 0 && s->owner != getpid())
        server_drop(s, 0, NULL, 0);
    return s;
}

/* The program the server is executed from (sisl_server.h). */
static const char *server_exe = "/proc/self/exe";

void ob_sisl_set_server_exe(const char *path) { server_exe = path ? path : "/proc/self/exe"; }

/* The file to execute as the server, into buf: server_exe, where that is
 * /proc/self/exe the path it links to.  Why: under valgrind (and other
 * tools that load the program themselves) /proc/self/exe is the tool's own
 * image, while readlink is answered with the program's path.  A program
 * replaced since it started (a rebuild during a run) reads "PATH
 * (deleted)": then /proc/self/exe itself, still the image that runs. */
static const char *server_program(char *buf, size_t len)
{
    if (strcmp(server_exe, "/proc/self/exe") != 0)
        return server_exe;
    const ssize_t n = readlink(server_exe, buf, len - 1);
    static const char deleted[] = " (deleted)";
    const size_t dl = sizeof deleted - 1;
    if (n <= 0 || (size_t)n >= len - 1 || buf[0] != '/' ||
        ((size_t)n >= dl && memcmp(buf + n - dl, deleted, dl) == 0))
        return server_exe;
    buf[n] = '\0';
    return buf;
}

/* The server's environment: ours without OB_SISL_ENV, and var (made before
 * the fork: the child may only exec).  NULL when out of memory. */
static char **server_environ(const char *var)
{
    extern char **environ;
    size_t n = 0;
    while (environ[n])
        n++;
    char **env = malloc((n + 2) * sizeof *env);
    if (!env)
        return NULL;
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (strncmp(environ[i], OB_SISL_ENV "=", sizeof OB_SISL_ENV) != 0)
            env[k++] = environ[i];
    env[k++] = (char *)var;
    env[k] = NULL;
    return env;
}

/* Between fork and exec (async-signal-safe calls only): the socket at
 * OB_SISL_FD, everything else above the standard three closed, exec; on
 * failure OB_SISL_EXECFAIL and errno on the socket. */
static void exec_server(const char *exe, int fd, int maxfd, char *const envp[])
{
    if (fd != OB_SISL_FD)
        dup2(fd, OB_SISL_FD);  /* the copy is not close-on-exec */
    else
        fcntl(fd, F_SETFD, 0);
    for (int i = OB_SISL_FD + 1; i < maxfd; i++)
        close(i);
    char *const argv[] = {(char *)OB_SISL_ARGV0, NULL};
    execve(exe, argv, envp);
    char m[4 + sizeof(int)];
    const int e = errno;
    memcpy(m, OB_SISL_EXECFAIL, 4);
    memcpy(m + 4, &e, sizeof e);
    ssize_t w = write(OB_SISL_FD, m, sizeof m);
    (void)w;
    _exit(127);
}

/* A fresh secret, hex, into hex[OB_SISL_SECRET + 1]; -1 without one. */
static int make_secret(char *hex)
{
    unsigned char b[OB_SISL_SECRET / 2];
    if (getrandom(b, sizeof b, 0) != (ssize_t)sizeof b)
        return -1;
    for (size_t i = 0; i < sizeof b; i++)
        snprintf(hex + 2 * i, 3, "%02x", b[i]);
    return 0;
}

/* The handshake from the started process within `wall` seconds: 0, or -1
 * with the reason in msg (and the process reaped). */
static int handshake(sisl_server *s, const char *exe, const char *secret, double wall, char *msg, size_t msglen)
{
    char got[4 + OB_SISL_SECRET];
    int e = 0;
    const int rc = ob_sisl_read_deadline(s->fd, got, 4 + sizeof e, ob_sisl_now() + wall);
    if (rc == 0 && memcmp(got, OB_SISL_EXECFAIL, 4) == 0) {
        memcpy(&e, got + 4, sizeof e);
        server_drop(s, SIGKILL, NULL, 0);
        ob_method_msg(msg, msglen, "cannot start the SISL process: exec %s: %s", exe, strerror(e));
        return -1;
    }
    if (rc == 0 && memcmp(got, OB_SISL_HELLO, 4) == 0 &&
        ob_sisl_read_deadline(s->fd, got + 4 + sizeof e, sizeof got - 4 - sizeof e, ob_sisl_now() + wall) == 0 &&
        memcmp(got + 4, secret, OB_SISL_SECRET) == 0)
        return 0;
    int ws = -1;
    server_drop(s, rc == 1 ? SIGKILL : 0, &ws, 0);
    char how[80] = "no handshake within the wall-clock cap";
    if (rc != 1)
        ob_sisl_describe_wait(ws, how, sizeof how);
    ob_method_msg(msg, msglen, "cannot start the SISL process: %s is not offbench's SISL server or ended (%s)",
                  exe, how);
    return -1;
}

void ob_sisl_describe_wait(int ws, char *buf, size_t len)
{
    if (ws != -1 && WIFSIGNALED(ws))
        snprintf(buf, len, "killed by signal %d (%s)", WTERMSIG(ws), strsignal(WTERMSIG(ws)));
    else if (ws != -1 && WIFEXITED(ws))
        snprintf(buf, len, "exit status %d", WEXITSTATUS(ws));
    else
        snprintf(buf, len, "status unknown");
}

/* Purpose: start s's server (the file's comment); 0, or -1 with the reason
 *          in msg. */
static int server_start(sisl_server *s, double wall, char *msg, size_t msglen)
{
    char secret[OB_SISL_SECRET + 1], var[sizeof OB_SISL_ENV + OB_SISL_SECRET + 1], path[4096];
    int sv[2];
    if (make_secret(secret) != 0 || socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
        ob_method_msg(msg, msglen, "cannot start the SISL process: %s", strerror(errno));
        return -1;
    }
    snprintf(var, sizeof var, OB_SISL_ENV "=%s", secret);
    char **envp = server_environ(var);
    const long om = sysconf(_SC_OPEN_MAX);
    const int maxfd = om > 0 && om < 65536 ? (int)om : 1024;
    const char *exe = server_program(path, sizeof path);
    const pid_t pid = envp ? fork() : -1;
    if (pid == 0)
        exec_server(exe, sv[1], maxfd, envp);
    const int e = envp ? errno : ENOMEM;
    free(envp);
    close(sv[1]);
    if (pid < 0) {
        close(sv[0]);
        ob_method_msg(msg, msglen, "cannot start the SISL process: fork: %s", strerror(e));
        return -1;
    }
    pthread_mutex_lock(&reg_lock);
    s->pid = pid, s->owner = getpid(), s->fd = sv[0], s->reported_ns = 0.0;
    pthread_mutex_unlock(&reg_lock);
    return handshake(s, exe, secret, wall, msg, msglen);
}

/* The reply's arrays, after its header h (checked: a broken reply must not
 * make a huge allocation): 0, 1 timed out, -1 EOF, -2 malformed or no memory. */
static int read_curve(int fd, const sisl_reply_hdr *h, sisl_result *r, double deadline)
{
    r->stat = h->stat, r->ik = h->ik, r->in = h->in, r->idim = h->idim, r->ikind = h->ikind;
    if (h->ik == 0)
        return 0;
    if (h->ik < 1 || h->ik > OB_SISL_MAX_ORDER || h->in < 1 || h->in > OB_SISL_MAX_VERTICES || h->idim < 1 ||
        h->idim > OB_SISL_MAX_DIM)
        return -2;
    const size_t nk = (size_t)(h->in + h->ik), nc = (size_t)h->in * (size_t)h->idim;
    r->et = malloc(nk * sizeof(double));
    r->ecoef = malloc(nc * sizeof(double));
    if (!r->et || !r->ecoef)
        return -2;
    const int rc = ob_sisl_read_deadline(fd, r->et, nk * sizeof(double), deadline);
    return rc ? rc : ob_sisl_read_deadline(fd, r->ecoef, nc * sizeof(double), deadline);
}

/* One round trip on a running server: 0, 1 timed out, -1 EOF (the server
 * ended), -2 malformed, -3 the request could not be sent. */
static int round_trip(sisl_server *s, const sisl_request *q, double deadline, sisl_result *r)
{
    if (ob_sisl_send_all(s->fd, q, sizeof *q) != 0)
        return -3;
    sisl_reply_hdr h;
    double spent = 0.0;
    int rc = ob_sisl_read_deadline(s->fd, &h, sizeof h, deadline);
    if (rc == 0)
        rc = ob_sisl_read_deadline(s->fd, &spent, sizeof spent, deadline);
    if (rc == 0 && !(spent >= 0.0 && spent < 1e18))
        rc = -2;
    if (rc == 0) {
        ob_fit_foreign_add(spent);  /* the fit's time in the server: the method's own (method.h) */
        s->reported_ns += spent;
        rc = read_curve(s->fd, &h, r, deadline);
    }
    if (rc == 0 && h.restart)
        server_drop(s, SIGKILL, NULL, 0);  /* grown large: started afresh next time */
    return rc;
}

ob_sisl_outcome ob_sisl_call(const sisl_request *q, double wall, sisl_result *r, int *wstatus, char *msg,
                             size_t msglen)
{
    memset(r, 0, sizeof *r);
    *wstatus = -1;
    sisl_server *s = my_server();
    if (!s) {
        ob_method_msg(msg, msglen, "cannot start the SISL process: out of memory");
        return OB_SISL_ERROR;
    }
    const double deadline = ob_sisl_now() + wall;
    int rc = -3;
    /* a server that ended while idle had not seen the request: once more on a fresh one */
    for (int attempt = 0; attempt < 2 && rc == -3; attempt++) {
        if (s->pid <= 0 && server_start(s, wall, msg, msglen) != 0)
            return OB_SISL_ERROR;
        rc = round_trip(s, q, deadline, r);
        if (rc == -3)
            server_drop(s, 0, wstatus, 0);
    }
    if (rc == 0)
        return OB_SISL_OK;
    free(r->et), free(r->ecoef);
    r->et = r->ecoef = NULL;
    server_drop(s, rc == -1 || rc == -3 ? 0 : SIGKILL, wstatus, 1);  /* ended by itself: how, not our kill */
    if (rc == -2)
        ob_method_msg(msg, msglen, "SISL's server sent a malformed reply (stopped)");
    return rc == 1 ? OB_SISL_WALL : rc == -2 ? OB_SISL_ERROR : OB_SISL_DIED;
}
