/*
 * server.c - the sisl method's server process (proto.h): s1360 runs here,
 * not in the fitting process, because it does not always return (it loops
 * on some inputs, growing an array without end: methods/sisl.c).
 *
 * Who serves: only a process executed by the client for the purpose
 * (client.c).  The check runs before main in every program that links the
 * method (offbench, the tests, liboffbench, offbench-sisl-server), so it
 * must let every other process go on untouched: it serves only when
 * argv[0] is exactly OB_SISL_ARGV0, OB_SISL_ENV holds a secret of
 * OB_SISL_SECRET hex digits, and descriptor OB_SISL_FD is a socket whose
 * peer is the parent process (SO_PEERCRED: the socketpair's maker); it then
 * echoes the secret over that socket, which the parent compares.  An
 * inherited OB_SISL_ENV alone does nothing (it used to make any offbench
 * process, python with liboffbench included, exit 126 or serve on
 * whatever pipes it had).
 *
 * Every field of a request is checked before use (ob_sisl_check_request):
 * the degree indexes fixed arrays (a crafted one overflowed the stack).
 *
 * Limits per call: RLIMIT_CPU (the request's timeout, whole seconds rounded
 * up; past it SIGXCPU ends the server with exit status 3) and, outside the
 * sanitizer builds, 1 GiB more data than the server holds when the call
 * starts (RLIMIT_DATA).  Both are the call's own, not the server's history.
 */
#define _GNU_SOURCE /* SO_PEERCRED, struct ucred */
#include "methods/sisl/proto.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <sisl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* A server holding this much more data than when it started asks to be
 * started afresh (sisl_reply_hdr.restart). */
#define SERVER_RESTART_BYTES (256UL << 20)

/* The data the server holds now (VmData: what RLIMIT_DATA counts), bytes;
 * 0 when /proc cannot tell. */
static unsigned long data_bytes(void)
{
    char buf[256];
    ssize_t n = -1;
    const int fd = open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        n = read(fd, buf, sizeof buf - 1);
        close(fd);
    }
    if (n <= 0)
        return 0;
    buf[n] = '\0';
    /* size resident shared text lib data: the sixth field, in pages */
    char *p = buf;
    for (int field = 0; field < 5 && p; field++) {
        p = strchr(p, ' ');
        p = p ? p + 1 : NULL;
    }
    return p ? strtoul(p, NULL, 10) * (unsigned long)sysconf(_SC_PAGESIZE) : 0;
}

/* The next s1360 call may grow the data by 1 GiB (the soft limit; the
 * hard one stays as it was, so the limit can be raised for the next). */
static void cap_next_call(void)
{
#if !defined(__SANITIZE_ADDRESS__)
    struct rlimit rl;
    if (getrlimit(RLIMIT_DATA, &rl) == 0) {
        const rlim_t want = (rlim_t)data_bytes() + ((rlim_t)1 << 30);
        rl.rlim_cur = rl.rlim_max == RLIM_INFINITY || want < rl.rlim_max ? want : rl.rlim_max;
        setrlimit(RLIMIT_DATA, &rl);
    }
#endif
}

/* Past its CPU limit the server ends at once with status 3: the client
 * reads that as the CPU deadline (methods/sisl.c). */
static void cpu_limit_reached(int sig)
{
    (void)sig;
    _exit(3);
}

static double cpu_s(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The next s1360 call may use `seconds` of CPU time more (the soft limit,
 * whole seconds rounded up: the kernel then sends SIGXCPU). */
static void cpu_limit_next_call(double seconds)
{
    struct rlimit rl;
    if (getrlimit(RLIMIT_CPU, &rl) != 0)
        return;
    const rlim_t want = (rlim_t)ceil(cpu_s(CLOCK_PROCESS_CPUTIME_ID) + seconds);
    rl.rlim_cur = rl.rlim_max == RLIM_INFINITY || want < rl.rlim_max ? want : rl.rlim_max;
    setrlimit(RLIMIT_CPU, &rl);
}

/* The test hooks (docs/contributing.md "Testing"): a server that gets no
 * CPU (wall time passing without CPU time, `sleep` seconds, or until the
 * client goes away: 1), and one that burns `spin` CPU seconds (a runaway
 * s1360, stopped by its CPU limit long before that). */
static int test_hooks(int fd, double sleep, double spin)
{
    const double t0 = cpu_s(CLOCK_MONOTONIC);
    for (double left = sleep; left > 0; left = sleep - (cpu_s(CLOCK_MONOTONIC) - t0)) {
        struct pollfd pf = {fd, POLLIN, 0};
        const int pr = poll(&pf, 1, left > 86400 ? 86400000 : (int)(left * 1000) + 1);
        if (pr > 0)
            return 1;
        if (pr < 0 && errno != EINTR)
            break;
    }
    const double c0 = cpu_s(CLOCK_THREAD_CPUTIME_ID);
    volatile double x = 0.0;
    while (cpu_s(CLOCK_THREAD_CPUTIME_ID) - c0 < spin)
        for (int i = 0; i < 100000; i++)
            x += 1e-9 * i;
    return 0;
}

/* SISL's error reporter (sislP.h: void s6err(char *, int, int)), silenced
 * (methods/sisl.c "Printing"): defined here, where s1360 is called, so that
 * every program that serves links ours instead of SISL's. */
void s6err(char *routine, int status, int position);
void s6err(char *routine, int status, int position)
{
    (void)routine;
    (void)status;
    (void)position;
}

static int in_range(double v, double lo, double hi) { return v >= lo && v <= hi; }

static const char *const field_names[] = {
    "?", "length", "magic", "degree", "rational", "d", "tol", "max_step", "timeout", "test hook", "coefficient",
};

const char *ob_sisl_field_name(int field)
{
    const int n = (int)(sizeof field_names / sizeof field_names[0]);
    return field_names[field > 0 && field < n ? field : 0];
}

int ob_sisl_check_request(const sisl_request *q, size_t len)
{
    if (len != sizeof *q)
        return 1;
    if (q->magic != OB_SISL_REQ_MAGIC)
        return 2;
    if (q->n < 0 || q->n > OB_MAX_DEG)
        return 3;
    if (q->rational != 0 && q->rational != 1)
        return 4;
    if (!isfinite(q->d))
        return 5;
    if (!isfinite(q->tol))
        return 6;  /* <= 0 is SISL's to refuse (status -184): the fit reports it */
    if (!in_range(q->amax, 0.0, 1e12))
        return 7;
    if (!in_range(q->timeout, 1e-9, 3600.0))
        return 8;
    if (!in_range(q->test_sleep, 0.0, 1e6) || !in_range(q->test_spin, 0.0, 1e6))
        return 9;
    const int dim = q->rational ? 3 : 2;
    for (int i = 0; i < dim * (q->n + 1); i++)
        if (!isfinite(q->coef[i]))
            return 10;
    return 0;
}

/* s1360 on a checked request: the reply header filled, the curve (or NULL)
 * into *out, the CPU time into *spent. */
static void run_s1360(const sisl_request *q, sisl_reply_hdr *h, SISLCurve **out, double *spent)
{
    double knots[2 * (OB_MAX_DEG + 1)];
    for (int i = 0; i <= q->n; i++) {
        knots[i] = 0.0;
        knots[q->n + 1 + i] = 1.0;
    }
    double coef[3 * (OB_MAX_DEG + 1)];
    memcpy(coef, q->coef, sizeof coef);  /* newCurve copies, but takes no const */
    const double c0 = cpu_s(CLOCK_THREAD_CPUTIME_ID);
    SISLCurve *pc = newCurve(q->n + 1, q->n + 1, knots, coef, q->rational ? 2 : 1, 2, 1);
    SISLCurve *rc = NULL;
    double enorm[3] = {0.0, 0.0, 1.0};
    if (pc)
        s1360(pc, q->d, q->tol, enorm, q->amax, 2, &rc, &h->stat);
    else
        h->stat = -101;  /* SISL's "out of memory" */
    *spent = 1e9 * (cpu_s(CLOCK_THREAD_CPUTIME_ID) - c0);
    if (pc)
        freeCurve(pc);
    if (rc && rc->in > 0 && rc->ik > 0 && rc->idim > 0)
        h->ik = rc->ik, h->in = rc->in, h->idim = rc->idim, h->ikind = rc->ikind;
    *out = rc;
}

int ob_sisl_serve(const void *req, size_t len, int fd, unsigned long data0)
{
    sisl_request q;
    memset(&q, 0, sizeof q);
    memcpy(&q, req, len < sizeof q ? len : sizeof q);
    sisl_reply_hdr h = {0, 0, 0, 0, 0, 0};
    double spent = 0.0;
    SISLCurve *rc = NULL;
    const int bad = ob_sisl_check_request(&q, len);
    if (bad) {
        h.stat = OB_SISL_BAD_REQUEST - bad;
    } else {
        cap_next_call();
        cpu_limit_next_call(q.timeout);
        if (test_hooks(fd, q.test_sleep, q.test_spin))
            return -1;  /* the client went away meanwhile */
        run_s1360(&q, &h, &rc, &spent);
    }
    h.restart = data_bytes() > data0 + SERVER_RESTART_BYTES;
    int ok = ob_sisl_send_all(fd, &h, sizeof h) == 0 && ob_sisl_send_all(fd, &spent, sizeof spent) == 0;
    if (ok && h.ik)
        ok = ob_sisl_send_all(fd, rc->et, (size_t)(rc->in + rc->ik) * sizeof(double)) == 0 &&
             ob_sisl_send_all(fd, rc->ecoef, (size_t)rc->in * (size_t)rc->idim * sizeof(double)) == 0;
    if (rc)
        freeCurve(rc);
    return ok ? 0 : -1;
}

/* Answers requests until the client goes away; never returns. */
static void server_loop(int fd)
{
    signal(SIGXCPU, cpu_limit_reached);
    const unsigned long data0 = data_bytes();
    sisl_request q;
    for (;;) {
        size_t got = 0;
        while (got < sizeof q) {
            ssize_t k = read(fd, (char *)&q + got, sizeof q - got);
            if (k < 0 && errno == EINTR)
                continue;
            if (k <= 0)
                _exit(0);  /* the client went away (a partial request: likewise) */
            got += (size_t)k;
        }
        if (ob_sisl_serve(&q, got, fd, data0) != 0)
            _exit(0);
    }
}

/* 1 when fd is a stream socket made by our parent (the client's socketpair). */
static int parents_socket(int fd)
{
    struct stat st;
    struct ucred cr;
    int type = 0;
    socklen_t tl = sizeof type, cl = sizeof cr;
    return fstat(fd, &st) == 0 && S_ISSOCK(st.st_mode) &&
           getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &tl) == 0 && type == SOCK_STREAM &&
           getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cr, &cl) == 0 && cr.pid == getppid();
}

/* Runs before main (glibc passes argc, argv and envp to constructors):
 * serves when started by the client (the file's comment), else returns. */
__attribute__((constructor)) static void serve_if_server(int argc, char **argv, char **envp)
{
    (void)envp;
    if (argc < 1 || !argv || !argv[0] || strcmp(argv[0], OB_SISL_ARGV0) != 0)
        return;
    const char *secret = getenv(OB_SISL_ENV);
    int ok = secret && strlen(secret) == OB_SISL_SECRET && strspn(secret, "0123456789abcdef") == OB_SISL_SECRET &&
             parents_socket(OB_SISL_FD);
    char hello[4 + OB_SISL_SECRET];
    if (ok) {
        memcpy(hello, OB_SISL_HELLO, 4);
        memcpy(hello + 4, secret, OB_SISL_SECRET);
        unsetenv(OB_SISL_ENV);
        ok = ob_sisl_send_all(OB_SISL_FD, hello, sizeof hello) == 0;
    }
    if (!ok) {
        fputs(OB_SISL_ARGV0 ": started by the sisl method's fits (a socket and a secret from its parent), "
              "not by hand\n", stderr);
        _exit(2);
    }
    server_loop(OB_SISL_FD);
}
