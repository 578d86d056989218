/*
 * test_sisl_procs.c - the sisl method's server processes (methods/sisl/client.c)
 * seen from the fitting process: who owns a server, and what is left behind.
 *
 * What is checked (each check can fail, none depends on timing):
 *  - fork: a child forked after the parent's fits starts a server of its
 *    own (it never writes to its parent's), and parent and children fitting
 *    at the same time all get the parent's serial results;
 *  - threads: 60 threads that each make a fit and exit leave no server
 *    process and no descriptor behind; under RLIMIT_NOFILE 64, 60 such
 *    threads one after another all fit;
 *  - a server killed during a fit: the fit fails saying it was killed by
 *    signal 9 (not "did not finish"), and the next fit starts a fresh one.
 */
#include <dirent.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "methods/method.h"
#include "tests/check.h"
#include "tests/testlib.h"

extern const ob_method ob_method_sisl;

enum { MSGLEN = 160, NCASE = 6 };

static const double LIU[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};

static ob_fit_status fit_case(int i, ob_fit *f, char *msg)
{
    ob_bez C;
    memset(&C, 0, sizeof C);
    C.deg = 3;
    for (int k = 0; k < 4; k++)
        C.h[k][0] = LIU[k][0], C.h[k][1] = LIU[k][1], C.h[k][2] = 1.0;
    double par[OB_MAX_PARAMS] = {0.0, 20.0, 0.0};
    const ob_fit_args a = {(i % 2 ? -1.0 : 1.0) * (0.3 + 0.2 * i), i < 3 ? 1e-2 : 3e-3, par};
    memset(f, 0, sizeof *f);
    msg[0] = '\0';
    return ob_method_sisl.fit(&C, &a, NULL, f, msg, MSGLEN);
}

/* The children of this process (their pids into out, at most n). */
static int children(pid_t *out, int n)
{
    DIR *d = opendir("/proc");
    int k = 0;
    struct dirent *e;
    while (d && (e = readdir(d))) {
        char path[64], buf[512];
        snprintf(path, sizeof path, "/proc/%.20s/stat", e->d_name);
        FILE *f = fopen(path, "r");
        if (!f)
            continue;
        size_t got = fread(buf, 1, sizeof buf - 1, f);
        fclose(f);
        buf[got] = '\0';
        const char *rp = strrchr(buf, ')');
        int ppid = 0;
        char state;
        if (rp && sscanf(rp + 1, " %c %d", &state, &ppid) == 2 && ppid == getpid() && k < n)
            out[k++] = atoi(e->d_name);
    }
    if (d)
        closedir(d);
    return k;
}

static int open_fds(void)
{
    DIR *d = opendir("/proc/self/fd");
    int n = 0;
    while (d && readdir(d))
        n++;
    if (d)
        closedir(d);
    return n;
}

static ob_fit ref[NCASE];
static long ref_ctrl[NCASE];

/* All cases, 8 times: 0, or 1 + the first case that differed from ref. */
static int fits_match(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    for (int round = 0; round < 8; round++)
        for (int i = 0; i < NCASE; i++)
            if (fit_case(i, &f, msg) != OB_FIT_OK || f.ctrl_points != ref_ctrl[i] ||
                memcmp(f.seg, ref[i].seg, sizeof f.seg[0] * (size_t)f.n) != 0) {
                fprintf(stderr, "  pid %d case %d: %ld control points, parent's %ld (%s)\n", (int)getpid(), i,
                        f.ctrl_points, ref_ctrl[i], msg);
                return 1 + i;
            }
    return 0;
}

/* A forked child: the parent's results, from a server of its own (its one
 * child process).  Exit 0, 1 + a case that differed, or 100. */
static int forked_fits(void)
{
    const int rc = fits_match();
    pid_t kids[8];
    const int nk = children(kids, 8);
    if (nk != 1)
        fprintf(stderr, "  forked child: %d server processes of its own, not 1\n", nk);
    return rc ? rc : nk == 1 ? 0 : 100;
}

static void test_fork(void)
{
    char msg[MSGLEN];
    for (int i = 0; i < NCASE; i++) {
        CHECK(fit_case(i, &ref[i], msg) == OB_FIT_OK, "case %d: %s", i, msg);
        ref_ctrl[i] = ref[i].ctrl_points;
    }
    /* 4 children and the parent fit at the same time */
    fflush(stdout), fflush(stderr);
    pid_t kid[4];
    for (int k = 0; k < 4; k++)
        if ((kid[k] = fork()) == 0)
            _exit(forked_fits());
    const int parent_rc = fits_match();
    for (int k = 0; k < 4; k++) {
        int st = -1;
        CHECK(kid[k] > 0 && waitpid(kid[k], &st, 0) == kid[k] && WIFEXITED(st) && WEXITSTATUS(st) == 0,
              "forked child %d: status %d (1 + case: results differ from the parent's; 100: no server of its own)",
              k, WIFEXITED(st) ? WEXITSTATUS(st) : -1);
    }
    CHECK(parent_rc == 0 && fits_match() == 0, "the parent's fits, during and after its children's: %d", parent_rc);
}

static void *one_fit(void *arg)
{
    static ob_fit f[64];
    char msg[MSGLEN];
    const long i = (long)arg;
    return fit_case((int)(i % NCASE), &f[i % 64], msg) == OB_FIT_OK ? NULL : (void *)1;
}

/* n threads, `together` at a time, each one fit; the number that failed. */
static int thread_fits(int n, int together)
{
    int failed = 0;
    for (int i = 0; i < n; i += together) {
        pthread_t t[16];
        int started = 0;
        for (int k = 0; k < together && i + k < n; k++)
            started += pthread_create(&t[started], NULL, one_fit, (void *)(long)(i + k)) == 0;
        failed += (together < n - i ? together : n - i) - started;
        for (int k = 0; k < started; k++) {
            void *r = NULL;
            pthread_join(t[k], &r);
            failed += r != NULL;
        }
    }
    return failed;
}

static void test_threads_leave_nothing(void)
{
    pid_t kids[128];
    const int p0 = children(kids, 128), f0 = open_fds();
    const int failed = thread_fits(60, 6);
    const int p1 = children(kids, 128), f1 = open_fds();
    CHECK(failed == 0, "%d of 60 threads' fits failed", failed);
    CHECK(p1 == p0, "60 threads, each one fit, then gone: %d server processes before, %d after", p0, p1);
    CHECK(f1 == f0, "60 threads, each one fit, then gone: %d descriptors before, %d after", f0, f1);
}

static int few_descriptors(void)
{
    struct rlimit rl = {64, 64};
    if (setrlimit(RLIMIT_NOFILE, &rl) != 0)
        return 2;
    return thread_fits(60, 1) == 0 ? 0 : 1;
}

static void test_few_descriptors(void)
{
    const int rc = in_child(few_descriptors);
    CHECK(rc == 0, "under RLIMIT_NOFILE 64, 60 threads one after another, each one fit: exit %d "
          "(1: some fit failed)", rc);
}

/* Kills every child of this process (the sleeping servers) until told to stop. */
static volatile int killing;
static void *killer(void *arg)
{
    (void)arg;
    while (killing) {
        pid_t kids[16];
        const int n = children(kids, 16);
        for (int k = 0; k < n; k++)
            kill(kids[k], SIGKILL);
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
    return NULL;
}

static void test_killed_server(void)
{
    static ob_fit f;
    char msg[MSGLEN];
    setenv("OFFBENCH_TEST_SISL_SLEEP", "600", 1);  /* each server sleeps: killed in mid-fit */
    killing = 1;
    pthread_t t;
    const int started = pthread_create(&t, NULL, killer, NULL) == 0;
    const ob_fit_status st = started ? fit_case(0, &f, msg) : OB_FIT_OK;
    killing = 0;
    if (started)
        pthread_join(t, NULL);
    unsetenv("OFFBENCH_TEST_SISL_SLEEP");
    CHECK(started && st == OB_FIT_FAIL && strstr(msg, "signal 9") && !strstr(msg, "did not finish"),
          "a server killed during the fit: %s (%s)", ob_fit_status_name(st), msg);
    CHECK(fit_case(0, &f, msg) == OB_FIT_OK && f.ctrl_points == ref_ctrl[0],
          "the next fit, on a fresh server: %s, %ld control points (%s)", ob_fit_status_name(OB_FIT_OK),
          f.ctrl_points, msg);
}

int main(void)
{
    test_fork();
    test_threads_leave_nothing();
    test_few_descriptors();
    test_killed_server();
    return check_done();
}
