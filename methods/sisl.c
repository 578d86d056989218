/*
 * sisl.c - SINTEF's SISL library (Debian libsisl-dev, 4.6) as a baseline:
 * s1360 "create a curve approximating the offset of a B-spline curve within
 * a tolerance".  It is what many C users would call instead of a method from
 * the literature; offbench measures its true error with its own metrics and
 * does not trust SISL's tolerance.
 *
 * What is done, and every reading taken:
 *  - The base segment (degree n, polynomial or rational) becomes a SISL curve
 *    by newCurve(n+1 vertices, order n+1, clamped knots 0^(n+1) 1^(n+1),
 *    ikind 1 with Euclidean (x, y) or ikind 2 with homogeneous (w x, w y, w)
 *    vertices, dimension 2, icopy 1 = SISL copies the arrays).
 *  - s1360(curve, d, tol, enorm, max_step, 2, &offset, &status) with the job's
 *    tolerance (ob_fit_args.tol).  enorm only matters in 3D.
 *  - Orientation: in 2D SISL offsets a positive distance towards (-y', x'),
 *    the left normal, which is ours (checked in tests/methods/test_sisl.c), so d is
 *    passed unchanged.
 *  - The result is a polynomial cubic B-spline (order 4, ikind 1) for every
 *    input seen, rational input included: s1360 samples the exact offset
 *    (points and tangent directions at parameters of the base, SISL choosing
 *    the steps) and joins them by cubic Hermite segments: interior knots of
 *    multiplicity 3, tangent directions matched at the knots but not their
 *    lengths, so G1 (not C1) there and at the ends.  Its domain is the
 *    base's [0,1] and its knots are BASE parameters: at each knot u the
 *    result passes through C(u) + d N(u) (to round-off, tested).  So the
 *    breakpoints t[] of the pieces are exactly the knots.  Inside a span,
 *    though, SISL's tangent lengths are not those of C + d N in the base
 *    parameter (only the directions are matched), so the result is NOT
 *    parameterized like the base: at tol 1e-3 on liu2002_ex1 (d = 1),
 *    |A(t) - O(t)| reaches 0.0085 where the hausdorff error is 0.0023.
 *    Hence no OB_CAP_SAME_PARAM: bound/radial jobs are skipped by the
 *    driver; hausdorff and normal apply.
 *  - Output pieces: one Bezier cubic per non-empty knot span, extracted by
 *    blossoming (de Boor's algorithm with the span's end knots as arguments),
 *    in fixed-size local arrays.  ctrl_points = the B-spline's own number of
 *    control points (README "Output": a B-spline counts its control points).
 *    More spans than OB_SPLIT_PIECES: OB_FIT_RETRY_SMALLER (the driver splits the
 *    piece and SISL starts again on each half).
 *  - SISL's tolerance is not a bound under our metrics (tests/methods/test_sisl.c
 *    prints the measurement): on liu2002_ex1 the hausdorff error of its
 *    whole-curve result reaches 18x the tolerance at the cusps of the d = 1
 *    offset and about 3x on the smooth d = -1 offset (in the last span), so
 *    the driver's splitting, not SISL's tolerance, decides the counts.
 *  - Capabilities: OB_CAP_TOL_DRIVEN (the number of spans follows the
 *    tolerance, so a half piece gets about as large an error as the whole);
 *    OB_CAP_ORIENTED (s1360 marches from the start of the parameter, so the
 *    reversed curve gets other Hermite points and another error).
 *  - s1360's status < 0: OB_FIT_FAIL with that status in msg (e.g. -184 for a
 *    tolerance <= 0).  A result that is not a polynomial cubic B-spline on
 *    [0,1] would break the readings above: OB_FIT_FAIL saying so.
 *
 * Allocation: newCurve/s1360/freeCurve allocate inside the library (malloc);
 * the no-allocation rule is for our own code in the timed path, which here
 * uses only stack arrays.  Every SISL curve is freed with freeCurve on every
 * path.
 *
 * Thread safety: the driver calls fit() from several OpenMP threads at once.
 * The objects of libsisl.a that s1360 can reach (its call closure, found with
 * nm: construct, destruct, s1219-s1221, s1227, s1307, s1311, s1325, s1359,
 * s1360-s1362, s6*, sh1992, sh6*, tstcyclknt) have empty .data and .bss: no
 * static mutable state (the library's only statics are in s1613bez and sh1762,
 * which s1360 does not reach), and they call only malloc/free and libm.  So no
 * lock is taken around s1360.  tests/methods/test_sisl.c also compares fits made on
 * several threads at once with serial ones.
 *
 * Printing: SISL reports every error through s6err, which writes three lines
 * to stderr.  Methods never print, and the status is returned anyway, so this
 * file defines s6err as a no-op; with the static libsisl.a the linker then
 * takes ours and leaves SISL's out (SISL's error codes still reach the
 * caller through s1360's status).
 *
 * Timing: the server measures its CPU time in newCurve and s1360 and sends
 * it with the reply; the fit adds it to the calling thread's foreign time
 * (ob_fit_foreign_add), which `run --time-fits` counts as the method's own.
 *
 * Isolation: s1360 does not always return.  On some inputs (found with
 * --random 500:7: a degenerate cubic cut down to a piece 7e-7 long) it
 * loops, growing an array by realloc without end (4 GB and counting, inside
 * s1360).  A library call cannot be stopped from outside, so s1360 runs in
 * a server process, one per calling thread, started on first use: the fit
 * sends the segment and the arguments down a pipe and reads the result
 * (status, order, knots, vertices) with a deadline (sisl.timeout seconds of
 * the server's CPU time, default 20, enforced by the kernel through
 * RLIMIT_CPU in whole seconds, rounded up); past it the server ends (and
 * is started afresh by the next fit) and the fit fails with that reason.
 * A wall-clock cap as well (sisl.wall_timeout; default 0 = 3 x (timeout + 1)
 * seconds): the CPU deadline alone, on a loaded machine where the server
 * got 5 % of a CPU, kept a fit waiting for minutes (issue 46).  Why that
 * default: RLIMIT_CPU counts whole seconds rounded up, so a call may run up
 * to timeout + 1 CPU seconds, and with three times that the server reaches
 * its CPU deadline first whenever it gets at least a third of a CPU; an
 * idle or moderately loaded machine (load up to three per core) never sees
 * the cap, and no fit that finishes is affected.  Past the cap the server
 * is killed and the fit ends OB_FIT_TIMEOUT (the job's status `timeout`,
 * the message naming the cap): what the cap decides depends on the load,
 * not on the input, so it must not read as a failure of the method.
 * Outside the sanitizer builds each s1360 call may grow the server's data
 * by 1 GiB, so a runaway allocation ends at once.  Both limits are the
 * call's own, not the machine's or the server's history: CPU time, not
 * wall time (a loaded machine must not turn a fit into a failure; the wall
 * cap above turns extreme load into a timeout, never a failure), and
 * 1 GiB above what the server holds when the call starts, not 1 GiB in all
 * (a server that served a large fit before keeps its heap, and which fits
 * a server serves depends on the threads and the engine: issue 35 found 6
 * rows of --random 200:7 whose messages changed with the engine that way).  A fork per fit cost 0.6 ms of system time (a 500-curve run
 * spent 2 of its 4 minutes in fork); a round trip costs microseconds.
 * The server is this program executed afresh (fork, then exec of
 * /proc/self/exe with the pipe ends in OFFBENCH_SISL_SERVER; a constructor
 * makes that image serve before main), not a fork that goes on running:
 * the child of a threaded process inherits every lock another thread held
 * at the fork, and once a sanitizer's allocator lock left a server waiting
 * in malloc for ever (its fit failed at the deadline: one row differed, in
 * about 30 sanitizer runs of the group engine).  Between fork and exec the
 * child only closes descriptors; the server holds nothing but its two pipe
 * ends and the standard three, so each server sees EOF, and exits, when
 * the program ends.  It inherits the blocked SIGINT/SIGTERM
 * (host/run/signals.c): a terminal's Ctrl-C to the process group does not
 * end it under its parent, which ends it when it stops.
 *
 * Parameter: max_step, s1360's "maximal step length" amax; 0 (the default)
 * leaves the step to SISL (its manual: the longest side of the curve's
 * bounding box).  The installed headers carry no documentation; measured on
 * liu2002_ex1 (d 1, tol 1e-3): amax 0, 1, 3, 10 give 49 vertices, 0.5 gives
 * 43, 0.1 gives 85, 1e-4 gives 7375 (so amax <= tol is not ignored).
 */
#define _GNU_SOURCE /* pipe2 */
#include "methods/method.h"
#include "methods/sisl_server.h"

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
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* SISL's error reporter (sislP.h: void s6err(char *, int, int)), silenced. */
void s6err(char *routine, int status, int position);
void s6err(char *routine, int status, int position)
{
    (void)routine;
    (void)status;
    (void)position;
}

enum { SISL_OUT_DEG = 3 };

static const ob_param sisl_params[] = {
    {"max_step", 0.0,
     "s1360's maximal step length amax; 0 (default) = SISL's own choice, which its manual "
     "gives as the longest side of the curve's bounding box", 0, 1e12, 0},
    {"timeout", 20.0,
     "CPU seconds one s1360 call may take, counted in whole seconds rounded up (it runs in a child "
     "process, ended past this; the fit then fails): s1360 loops without end on some inputs.  Our "
     "choice; 0.1..3600", 0.1, 3600, 0},
    {"wall_timeout", 0.0,
     "wall-clock seconds one s1360 call may take; 0 (default) = 3 x (timeout + 1), which a server "
     "that gets at least a third of a CPU never reaches before its CPU deadline.  Past it the "
     "server is stopped and the job's status is timeout (the machine was too loaded), not fail.  "
     "Our choice; 0..36000", 0, 36000, 0},
};

/* s1360's result as plain arrays (ik order, in vertices, idim 2, ikind 1). */
typedef struct {
    int stat, ik, in, idim, ikind;
    double *et, *ecoef;     /* in + ik knots, idim * in coefficients (malloc) */
} sisl_result;

/* Moves exactly n bytes to (writing) or from fd, retrying short transfers
 * and interruptions; -1 at EOF or on an error.  No deadline: the server side,
 * and the fit's request (a pipe with room for it). */
static int xfer_all(int fd, void *buf, size_t n, int writing)
{
    char *p = buf;
    while (n > 0) {
        ssize_t k = writing ? write(fd, p, n) : read(fd, p, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

/* A request: the base segment as SISL wants it, and s1360's arguments. */
typedef struct {
    int n, rational;
    double d, tol, amax;
    double timeout;     /* CPU seconds the call may take (RLIMIT_CPU in the server) */
    double test_sleep;  /* test hook: wall seconds the server sleeps first (below) */
    double coef[3 * (OB_MAX_DEG + 1)];
} sisl_request;

#if !defined(__SANITIZE_ADDRESS__)
#define SERVER_MEMORY_NOTE "1 GiB of data, without crashing"
#else
#define SERVER_MEMORY_NOTE "its memory, without crashing"
#endif

/* A server holding this much more data than when it started is started
 * afresh. */
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

/* Past its CPU limit the server ends at once: the parent sees the pipe
 * close and the fit fails "did not finish". */
static void cpu_limit_reached(int sig)
{
    (void)sig;
    _exit(3);
}

/* The next s1360 call may use `seconds` of CPU time more (the soft limit,
 * whole seconds rounded up: the kernel then sends SIGXCPU). */
static void cpu_limit_next_call(double seconds)
{
    struct rusage ru;
    struct rlimit rl;
    if (getrusage(RUSAGE_SELF, &ru) != 0 || getrlimit(RLIMIT_CPU, &rl) != 0)
        return;
    const double used = ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
    const rlim_t want = (rlim_t)ceil(used + seconds);
    rl.rlim_cur = rl.rlim_max == RLIM_INFINITY || want < rl.rlim_max ? want : rl.rlim_max;
    setrlimit(RLIMIT_CPU, &rl);
}

/* The server's CPU time (it has one thread), ns. */
static double cpu_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
}

/* The test hook's sleep (test_sleep_hook below): a server that gets no CPU,
 * wall time passing without CPU time, for `seconds` or until the parent goes
 * away (its end of the request pipe closes: 1), so that a server of a
 * killed run does not sleep on. */
static int test_sleep(int in, double seconds)
{
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (;;) {
        clock_gettime(CLOCK_MONOTONIC, &t);
        const double left = seconds - (double)(t.tv_sec - t0.tv_sec) - 1e-9 * (double)(t.tv_nsec - t0.tv_nsec);
        if (left <= 0)
            return 0;
        struct pollfd pf = {in, POLLIN, 0};
        const int pr = poll(&pf, 1, left > 86400 ? 86400000 : (int)(left * 1000) + 1);
        if (pr > 0)
            return 1;
        if (pr < 0 && errno != EINTR)
            return 0;
    }
}

/* The server: answer requests until the parent goes away; never returns.
 * The reply's sixth word asks the parent to start a fresh server: this one
 * has grown SERVER_RESTART_BYTES past what it started with. */
static void server_loop(int in, int out)
{
    signal(SIGXCPU, cpu_limit_reached);
    const unsigned long data0 = data_bytes();
    sisl_request q;
    while (xfer_all(in, &q, sizeof q, 0) == 0) {
        cap_next_call();
        cpu_limit_next_call(q.timeout);
        if (q.test_sleep > 0 && test_sleep(in, q.test_sleep))
            break;  /* the parent went away meanwhile */
        double knots[2 * (OB_MAX_DEG + 1)];
        for (int i = 0; i <= q.n; i++) {
            knots[i] = 0.0;
            knots[q.n + 1 + i] = 1.0;
        }
        int hdr[6] = {0, 0, 0, 0, 0, 0};
        const double cpu0 = cpu_ns();
        SISLCurve *pc = newCurve(q.n + 1, q.n + 1, knots, q.coef, q.rational ? 2 : 1, 2, 1);
        SISLCurve *rc = NULL;
        double enorm[3] = {0.0, 0.0, 1.0};
        if (pc)
            s1360(pc, q.d, q.tol, enorm, q.amax, 2, &rc, &hdr[0]);
        else
            hdr[0] = -101;  /* SISL's "out of memory" */
        const double spent = cpu_ns() - cpu0;  /* the fit's own CPU time, sent after the header */
        if (rc && rc->in > 0 && rc->ik > 0 && rc->idim > 0) {
            hdr[1] = rc->ik, hdr[2] = rc->in, hdr[3] = rc->idim, hdr[4] = rc->ikind;
        }
        hdr[5] = data_bytes() > data0 + SERVER_RESTART_BYTES;
        int ok = xfer_all(out, hdr, sizeof hdr, 1) == 0 && xfer_all(out, (void *)&spent, sizeof spent, 1) == 0;
        if (ok && hdr[1])
            ok = xfer_all(out, rc->et, (size_t)(rc->in + rc->ik) * sizeof(double), 1) == 0 &&
                 xfer_all(out, rc->ecoef, (size_t)rc->in * (size_t)rc->idim * sizeof(double), 1) == 0;
        if (pc)
            freeCurve(pc);
        if (rc)
            freeCurve(rc);
        if (!ok)
            break;
    }
    _exit(0);
}

/* One server process per calling thread, started on first use and again
 * after it was killed. */
typedef struct {
    pid_t pid;
    int to, from;
} sisl_server;
static _Thread_local sisl_server srv = {0, -1, -1};

static void server_stop(int sig)
{
    if (srv.pid > 0) {
        if (sig)
            kill(srv.pid, sig);
        close(srv.to);
        close(srv.from);
        int ws;
        while (waitpid(srv.pid, &ws, 0) < 0 && errno == EINTR)
            ;
    }
    srv.pid = 0;
    srv.to = srv.from = -1;
}

/* The environment variable that makes a process the server: "IN,OUT", the
 * two pipe ends it inherited (set only in the environment of the image the
 * fit starts). */
#define SERVER_ENV "OFFBENCH_SISL_SERVER"
#define SERVER_ARGV0 "offbench-sisl-server"

/* The program the server is executed from: this one unless a library user
 * (liboffbench, whose process may be python) names another that links this
 * method (methods/sisl_server.h).  Set once, before any fit. */
static const char *server_exe = "/proc/self/exe";

void ob_sisl_set_server_exe(const char *path)
{
    server_exe = path ? path : "/proc/self/exe";
}

/* Runs before main in every program that links this method (offbench and
 * the tests): the image started by server_start() serves and never
 * returns; any other process goes on.  Both ends must be pipes. */
__attribute__((constructor)) static void serve_if_server(void)
{
    const char *v = getenv(SERVER_ENV);
    int in = -1, out = -1;
    char tail = 0;
    if (!v || sscanf(v, "%d,%d%c", &in, &out, &tail) != 2)
        return;
    struct stat si, so;
    if (fstat(in, &si) != 0 || fstat(out, &so) != 0 || !S_ISFIFO(si.st_mode) || !S_ISFIFO(so.st_mode))
        _exit(126);
    server_loop(in, out);
}

/* The environment of the server: ours and SERVER_ENV (made before the
 * fork: the child may only exec).  NULL when out of memory. */
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
        if (strncmp(environ[i], SERVER_ENV "=", sizeof SERVER_ENV) != 0)
            env[k++] = environ[i];
    env[k++] = (char *)var;
    env[k] = NULL;
    return env;
}

/* Between fork and exec the child of a threaded process may only make
 * async-signal-safe calls (every lock another thread held at the fork
 * stays held in the child: a sanitizer's allocator lock once left a
 * server waiting in malloc for ever): close what is not its own, exec
 * this program afresh, or report exec's errno on `status` and end. */
static void exec_server(const char *exe, int keep_in, int keep_out, int status, int maxfd,
                        char *const envp[])
{
    for (int fd = 3; fd < maxfd; fd++)
        if (fd != keep_in && fd != keep_out && fd != status)
            close(fd);
    char *const argv[] = {(char *)SERVER_ARGV0, NULL};
    execve(exe, argv, envp);
    const int e = errno;
    ssize_t w = write(status, &e, sizeof e);
    (void)w;
    _exit(127);
}

/* The request, reply and exec-status pipes, close-on-exec; 0, or -1 with
 * errno (none left open). */
static int open_pipes(int req[2], int rep[2], int st[2])
{
    if (pipe2(req, O_CLOEXEC) != 0)
        return -1;
    if (pipe2(rep, O_CLOEXEC) == 0) {
        if (pipe2(st, O_CLOEXEC) == 0)
            return 0;
        const int e = errno;
        close(rep[0]), close(rep[1]);
        errno = e;
    }
    const int e = errno;
    close(req[0]), close(req[1]);
    errno = e;
    return -1;
}

/* The file to execute as the server, into buf: server_exe, where that is
 * /proc/self/exe the path it links to.  Why: under valgrind (and other
 * tools that load the program themselves) /proc/self/exe is the tool's own
 * image, which refuses to run as the server, while readlink is answered
 * with the program's path.  A program replaced since it started (a rebuild
 * during a run) reads "PATH (deleted)": then /proc/self/exe itself, which
 * is still the image that runs. */
static const char *server_program(char *buf, size_t len)
{
    if (strcmp(server_exe, "/proc/self/exe") != 0)
        return server_exe;
    const ssize_t n = readlink(server_exe, buf, len - 1);
    static const char deleted[] = " (deleted)";
    const size_t dl = sizeof deleted - 1;
    if (n <= 0 || (size_t)n >= len - 1 || buf[0] != '/'
        || ((size_t)n >= dl && memcmp(buf + n - dl, deleted, dl) == 0))
        return server_exe;
    buf[n] = '\0';
    return buf;
}

/* Purpose: start this thread's server: this program executed afresh (the
 *          constructor above makes it serve), its two pipe ends named in
 *          its environment.  Returns 0, or -1 with the reason in msg. */
static int server_start(char *msg, size_t msglen)
{
    int req[2], rep[2], st[2];
    if (open_pipes(req, rep, st) != 0) {
        ob_method_msg(msg, msglen, "cannot start the SISL process: pipe: %s", strerror(errno));
        return -1;
    }
    /* the server's ends stay open across exec, the rest close */
    fcntl(req[0], F_SETFD, 0);
    fcntl(rep[1], F_SETFD, 0);
    char var[64];
    snprintf(var, sizeof var, SERVER_ENV "=%d,%d", req[0], rep[1]);
    char **envp = server_environ(var);
    const long om = sysconf(_SC_OPEN_MAX);
    const int maxfd = om > 0 && om < 65536 ? (int)om : 1024;
    char path[4096];
    const char *exe = server_program(path, sizeof path);
    pid_t pid = envp ? fork() : -1;
    if (pid == 0)
        exec_server(exe, req[0], rep[1], st[1], maxfd, envp);
    int why = !envp ? ENOMEM : pid < 0 ? errno : 0;
    free(envp);
    close(req[0]);
    close(rep[1]);
    close(st[1]);
    ssize_t got = -1;
    if (pid > 0)
        while ((got = read(st[0], &why, sizeof why)) < 0 && errno == EINTR)
            ;
    close(st[0]);
    if (pid > 0 && got == 0) {  /* EOF: the exec closed it, the server runs */
        srv.pid = pid;
        srv.to = req[1];
        srv.from = rep[0];
        return 0;
    }
    close(req[1]);
    close(rep[0]);
    if (pid > 0)
        while (waitpid(pid, NULL, 0) < 0 && errno == EINTR)
            ;
    ob_method_msg(msg, msglen, "cannot start the SISL process: %s%s: %s", pid > 0 ? "exec " : "",
                  pid > 0 ? exe : "fork", strerror(got > 0 ? why : pid > 0 ? EIO : why));
    return -1;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Reads n bytes from the server before the deadline: 0, 1 timed out, -1 the
 * server died (or ended itself past its CPU limit). */
static int read_deadline(int fd, void *buf, size_t n, double deadline)
{
    char *p = buf;
    while (n > 0) {
        const double left = deadline - now_s();
        if (left <= 0)
            return 1;
        struct pollfd pf = {fd, POLLIN, 0};
        int pr = poll(&pf, 1, (int)(left * 1000) + 1);
        if (pr < 0 && errno == EINTR)
            continue;
        if (pr == 0)
            return 1;
        if (pr < 0)
            return -1;
        ssize_t r = read(fd, p, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        p += r;
        n -= (size_t)r;
    }
    return 0;
}

/* The test hook OFFBENCH_TEST_SISL_SLEEP=S (docs/contributing.md
 * "Testing"): the server sleeps S wall-clock seconds before each s1360 call,
 * as a server that gets no CPU on a loaded machine would wait; 0 without it. */
static double test_sleep_hook(void)
{
    const char *v = getenv("OFFBENCH_TEST_SISL_SLEEP");
    char *end;
    const double s = v && *v ? strtod(v, &end) : 0.0;
    return v && *v && !*end && s > 0 && s <= 1e6 ? s : 0.0;
}

/* Purpose: s1360 in this thread's server process, with its CPU deadline
 *          (timeout, in the server) and a wall-clock cap (wall seconds).
 * Returns: 0 with *r filled (free r->et, r->ecoef; NULL when s1360 gave no
 *          curve); -1 with the reason in msg (past its CPU deadline or
 *          memory cap and ended, the server crashed or could not start);
 *          1 past the wall-clock cap (killed), the reason in msg. */
static int guarded_s1360(const sisl_request *q, double timeout, double wall, sisl_result *r, char *msg,
                         size_t msglen)
{
    memset(r, 0, sizeof *r);
    if (srv.pid <= 0 && server_start(msg, msglen) != 0)
        return -1;
    /* a write to a dead server must not raise SIGPIPE */
    struct sigaction ign, old;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &ign, &old);
    sisl_request copy = *q;
    copy.timeout = timeout;
    copy.test_sleep = test_sleep_hook();
    /* the server's CPU time decides (RLIMIT_CPU there) unless the machine
     * is so loaded that the wall-clock cap comes first (the file's comment) */
    const double deadline = now_s() + wall;
    int wrc = xfer_all(srv.to, &copy, sizeof copy, 1);
    sigaction(SIGPIPE, &old, NULL);
    int hdr[6];
    double spent = 0;
    int rc = wrc ? -1 : read_deadline(srv.from, hdr, sizeof hdr, deadline);
    if (rc == 0)
        rc = read_deadline(srv.from, &spent, sizeof spent, deadline);
    if (rc == 0) {
        ob_fit_foreign_add(spent);  /* the fit's time in the server: the method's own (method.h) */
        r->stat = hdr[0], r->ik = hdr[1], r->in = hdr[2], r->idim = hdr[3], r->ikind = hdr[4];
        if (r->ik > 0) {
            const size_t nk = (size_t)(r->in + r->ik), nc = (size_t)r->in * (size_t)r->idim;
            r->et = malloc(nk * sizeof(double));
            r->ecoef = malloc(nc * sizeof(double));
            if (!r->et || !r->ecoef) {
                free(r->et), free(r->ecoef);
                r->et = r->ecoef = NULL;
                server_stop(SIGKILL);  /* its reply is not read: start afresh */
                ob_method_msg(msg, msglen, "out of memory reading SISL's result");
                return -1;
            }
            rc = read_deadline(srv.from, r->et, nk * sizeof(double), deadline);
            if (rc == 0)
                rc = read_deadline(srv.from, r->ecoef, nc * sizeof(double), deadline);
        }
    }
    if (rc == 0) {
        /* a server grown large (SISL does not free everything on every
         * path) is started afresh: each call's limits are its own anyway */
        if (hdr[5])
            server_stop(SIGKILL);
        return 0;
    }
    free(r->et), free(r->ecoef);
    r->et = r->ecoef = NULL;
    server_stop(SIGKILL);
    if (rc == 1) {  /* the load decided, not the input: a timeout, said as such */
        /* short: the driver keeps 100 characters of it before the piece's place */
        ob_method_msg(msg, msglen, "SISL s1360 stopped at its wall-clock cap of %g s (sisl.wall_timeout; CPU "
                      "deadline %g s)", wall, timeout);
        return 1;
    }
    /* One message for the deadline, the memory cap and a crash: a runaway
     * s1360 meets whichever limit first depends on the machine's load, and
     * results.csv must not depend on it (same rows for any thread count). */
    ob_method_msg(msg, msglen, "SISL s1360 did not finish in %g s within %s (stopped; it loops on some inputs)",
                  timeout, SERVER_MEMORY_NOTE);
    return -1;
}

/* Bezier segment of span [et[j], et[j+1]] of a non-rational B-spline of degree
 * p (coefficients ecoef, 2 per vertex): control point k is the blossom with
 * p-k arguments a = et[j] and k arguments b = et[j+1] (de Boor). */
static void span_bezier(const double *et, const double *ecoef, int p, int j, ob_bez *out)
{
    const double a = et[j], b = et[j + 1];
    out->deg = p;
    out->rational = 0;
    for (int k = 0; k <= p; k++) {
        double q[OB_MAX_DEG + 1][2];
        for (int i = 0; i <= p; i++) {
            q[i][0] = ecoef[2 * (j - p + i)];
            q[i][1] = ecoef[2 * (j - p + i) + 1];
        }
        for (int r = 1; r <= p; r++) {
            const double x = r <= p - k ? a : b;
            for (int i = p; i >= r; i--) {
                const int idx = j - p + i;
                const double alpha = (x - et[idx]) / (et[idx + p + 1 - r] - et[idx]);
                q[i][0] = (1.0 - alpha) * q[i - 1][0] + alpha * q[i][0];
                q[i][1] = (1.0 - alpha) * q[i - 1][1] + alpha * q[i][1];
            }
        }
        out->h[k][0] = q[p][0];
        out->h[k][1] = q[p][1];
        out->h[k][2] = 1.0;
    }
}

static ob_fit_status sisl_fit(const ob_bez *base, const ob_fit_args *a, void *work, ob_fit *out,
                              char *msg, size_t msglen)
{
    (void)work;
    sisl_request q;
    memset(&q, 0, sizeof q);
    q.n = base->deg;
    q.rational = base->rational;
    q.d = a->d;
    q.tol = a->tol;
    q.amax = a->par[0];
    const int dim = base->rational ? 3 : 2;
    for (int i = 0; i <= q.n; i++)
        for (int c = 0; c < dim; c++)
            q.coef[dim * i + c] = base->h[i][c];  /* polynomial: w = 1, h = (x, y) */
    sisl_result res;
    const double timeout = a->par[1], wall_par = a->par[2];
    if (!(timeout >= 0.1 && timeout <= 3600) || !(q.amax >= 0.0 && q.amax <= 1e12) ||
        !(wall_par >= 0.0 && wall_par <= 36000)) {
        /* --param refuses these; a caller that bypasses it gets no silent substitute */
        ob_method_msg(msg, msglen, "timeout %g (0.1..3600), max_step %g (0..1e12) or wall_timeout %g (0..36000) "
                      "out of range", timeout, q.amax, wall_par);
        return OB_FIT_FAIL;
    }
    const double wall = wall_par > 0.0 ? wall_par : 3.0 * (timeout + 1.0);  /* why: the file's comment */
    const int grc = guarded_s1360(&q, timeout, wall, &res, msg, msglen);
    if (grc != 0)
        return grc > 0 ? OB_FIT_TIMEOUT : OB_FIT_FAIL;
    const sisl_result *rc = &res;
    if (res.stat < 0 || !res.et) {
        ob_method_msg(msg, msglen, "SISL s1360 failed with status %d", res.stat);
        free(res.et);
        free(res.ecoef);
        return OB_FIT_FAIL;
    }

    ob_fit_status st = OB_FIT_OK;
    const int p = rc->ik - 1, nv = rc->in;
    const double *et = rc->et;
    if (p != SISL_OUT_DEG || rc->idim != 2 || rc->ikind != 1 || nv < rc->ik) {
        ob_method_msg(msg, msglen, "SISL s1360 returned order %d, kind %d, dimension %d, %d "
                      "vertices: not a polynomial cubic B-spline", rc->ik, rc->ikind, rc->idim, nv);
        st = OB_FIT_FAIL;
        goto done;
    }
    const double lo = et[p], hi = et[nv];
    if (!(fabs(lo) <= 1e-12 && fabs(hi - 1.0) <= 1e-12)) {
        ob_method_msg(msg, msglen, "SISL s1360 returned the domain [%.17g, %.17g], not the "
                      "base's [0, 1]", lo, hi);
        st = OB_FIT_FAIL;
        goto done;
    }
    int spans = 0;
    for (int j = p; j < nv; j++)
        spans += et[j] < et[j + 1];
    if (spans > OB_SPLIT_PIECES) {
        ob_method_msg(msg, msglen, "SISL's offset has %d spans, more than %d pieces", spans,
                      OB_SPLIT_PIECES);
        st = OB_FIT_RETRY_SMALLER;
        goto done;
    }
    out->n = 0;
    out->ctrl_points = nv;
    out->t[0] = 0.0;
    for (int j = p; j < nv; j++) {
        if (!(et[j] < et[j + 1]))
            continue;
        span_bezier(et, rc->ecoef, p, j, &out->seg[out->n]);
        out->n++;
        out->t[out->n] = out->n == spans ? 1.0 : et[j + 1];
    }

done:
    free(res.et);
    free(res.ecoef);
    return st;
}

const ob_method ob_method_sisl = {
    .name = "sisl",
    .version = 1,
    .citation = "SINTEF SISL 4.6, s1360 (offset of a B-spline curve within a tolerance)",
    .continuity = "G1",
    .caps = OB_CAP_POLY_OUT | OB_CAP_RATIONAL_IN | OB_CAP_ORIENTED | OB_CAP_TOL_DRIVEN,
    .max_turn = 0.0,
    .out_degree = ob_degree_three, /* SISL_OUT_DEG */
    .cost_ms = 4.48,
    .work_size = 0,
    .params = sisl_params,
    .nparams = 3,
    .fit_uses_tol = ob_fit_uses_tol_always, /* s1360 offsets to tol */
    .fit = sisl_fit,
};
