/*
 * test_api_batch.c - obx_run_batch's progress callback: called by the
 * calling thread, outside the driver's locks, so that it may call obx_fit
 * or obx_run_batch itself (it deadlocked inside the driver's critical
 * section); its counts rise strictly; obx_run_batch_stop's callback stops
 * the run by returning nonzero (OBX_E_STOPPED, no results); a forked
 * child runs batches of its own.  A hang guard
 * (SIGALRM, generous) turns a deadlock into a failure.
 */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "include/offbench.h"
#include "tests/check.h"

enum { N = 8, HANG_GUARD_S = 900 };

static void hung(int sig)
{
    (void)sig;
    static const char msg[] = "test_api_batch: FAIL: hung (a progress callback deadlocked)\n0 passed, 1 failed\n";
    ssize_t w = write(1, msg, sizeof msg - 1);
    (void)w;
    _exit(1);
}

typedef struct {
    const obx_curveset *s;
    int c;
    pthread_t caller;
    size_t calls, last, total;
    int rising, on_caller, nested_ok;
    int reenter;        /* 1: obx_fit inside, 2: obx_run_batch inside */
    size_t stop_at;     /* obx_run_batch_stop: stop at this call (0: never) */
} seen;

static void nested(seen *p)
{
    obx_error e = {0, ""};
    if (p->reenter == 1) {
        obx_result *r = NULL;
        p->nested_ok &= obx_fit(p->s, p->c, "tiller", 1.0, 1e-2, NULL, NULL, NULL, &r, &e) == 0;
        obx_result_free(r);
    } else if (p->reenter == 2) {
        obx_job_spec j = {p->c, "cobb", -1.0, 1e-2, NULL, NULL, NULL};
        obx_result *r = NULL;
        p->nested_ok &= obx_run_batch(p->s, &j, 1, NULL, NULL, &r, &e) == 0;
        obx_result_free(r);
    }
}

static void told(seen *p, size_t done, size_t total)
{
    p->rising &= done > p->last && done <= total;
    p->on_caller &= pthread_equal(pthread_self(), p->caller) != 0;
    p->calls++;
    p->last = done;
    p->total = total;
    nested(p);
}

static void on_progress(void *ctx, size_t done, size_t total)
{
    told(ctx, done, total);
}

static void jobs_of(int c, obx_job_spec *jobs)
{
    static const char *const methods[] = {"tiller", "cobb", "lee", "hoschek"};
    for (int i = 0; i < N; i++)
        jobs[i] = (obx_job_spec){c, methods[i % 4], i % 2 ? 1.0 : -1.0, i < 4 ? 1e-2 : 1e-3, NULL, NULL, NULL};
}

static int on_progress_stop(void *ctx, size_t done, size_t total)
{
    seen *p = ctx;
    told(p, done, total);
    return p->stop_at && p->calls >= p->stop_at;
}

/* obx_run_batch_stop: stopped at the first count (nothing told after it,
 * no result, OBX_E_STOPPED), or never (every job, as obx_run_batch). */
static void test_stop(const obx_curveset *s, int c)
{
    obx_job_spec jobs[N];
    jobs_of(c, jobs);
    obx_result *out[N];
    obx_error e = {0, ""};
    seen p = {s, c, pthread_self(), 0, 0, 0, 1, 1, 1, 0, 1};
    const int rc = obx_run_batch_stop(s, jobs, N, on_progress_stop, &p, out, &e);
    int none = 1;
    for (int i = 0; i < N; i++)
        none &= out[i] == NULL;
    CHECK(rc == -1 && e.code == OBX_E_STOPPED && strstr(e.message, "stopped by its progress callback") && none,
          "stopped: rc %d code %d '%s'", rc, e.code, e.message);
    CHECK(p.calls == 1 && p.on_caller, "nothing told after the stop: %zu calls", p.calls);
    seen q = {s, c, pthread_self(), 0, 0, 0, 1, 1, 1, 0, 0};
    CHECK(obx_run_batch_stop(s, jobs, N, on_progress_stop, &q, out, &e) == 0 && q.last == N && q.rising,
          "never stopped: every job (%s), last %zu", e.message, q.last);
    for (int i = 0; i < N; i++)
        obx_result_free(out[i]);
}

/* obx_run_batch with a callback that re-enters as asked. */
static void test_progress(const obx_curveset *s, int c, int reenter)
{
    obx_job_spec jobs[N];
    jobs_of(c, jobs);
    obx_result *out[N];
    obx_error e = {0, ""};
    seen p = {s, c, pthread_self(), 0, 0, 0, 1, 1, 1, reenter, 0};
    CHECK(obx_run_batch(s, jobs, N, on_progress, &p, out, &e) == 0, "batch (reenter %d): %s", reenter, e.message);
    CHECK(p.calls > 0 && p.rising && p.last == N && p.total == N,
          "reenter %d: counts strictly rising to %d: %zu calls, last %zu of %zu", reenter, N, p.calls, p.last, p.total);
    CHECK(p.on_caller, "reenter %d: every call on the calling thread", reenter);
    CHECK(p.nested_ok, "reenter %d: the nested call succeeded", reenter);
    for (int i = 0; i < N; i++)
        obx_result_free(out[i]);
}

/* After a fork the child's batch gets a thread of its own (the parent's
 * pooled ones are not in the child): it ends instead of waiting forever. */
static void test_fork(const obx_curveset *s, int c)
{
    const pid_t pid = fork();
    if (pid == 0) {
        alarm(HANG_GUARD_S / 2);  /* the child's own guard: it is not left behind */
        obx_job_spec jobs[N];
        jobs_of(c, jobs);
        obx_result *out[N];
        seen p = {s, c, pthread_self(), 0, 0, 0, 1, 1, 1, 0, 0};
        _exit(obx_run_batch(s, jobs, N, on_progress, &p, out, NULL) == 0 && p.last == N ? 0 : 3);
    }
    int ws = 0;
    CHECK(pid > 0 && waitpid(pid, &ws, 0) == pid && WIFEXITED(ws) && WEXITSTATUS(ws) == 0,
          "a batch in a forked child: status %#x", ws);
}

int main(void)
{
    signal(SIGALRM, hung);
    alarm(HANG_GUARD_S);
    obx_curveset *s = NULL;
    obx_error e = {0, ""};
    if (obx_curves_load_file("datasets/published.curves", &s, &e) != 0) {
        CHECK(0, "load: %s", e.message);
        return check_done();
    }
    const int c = obx_curves_find(s, "liu2002_ex1");
    test_progress(s, c, 0);
    test_progress(s, c, 1);
    test_progress(s, c, 2);
    test_stop(s, c);
    test_fork(s, c);
    obx_curves_free(s);
    return check_done();
}
