/*
 * test_clprobe.c - why an installed OpenCL platform did not start
 * (host/backend/clprobe.h, issue 48): no ICD, an ICD naming a library that
 * is missing, one whose library loads but gives no platform, the
 * OCL_ICD_FILENAMES list; a failed mapping is memory only under an
 * address-space limit; the trial child reports its failure, its signal, or
 * is not tried without a limit.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "host/backend/clprobe.h"
#include "tests/check.h"

static char dir[256];

/* An .icd file in sub naming lib; sub's path into out. */
static void icd(const char *sub, const char *lib, char *out, size_t len)
{
    char path[600];
    snprintf(out, len, "%s/%s", dir, sub);
    snprintf(path, sizeof path, "mkdir -p %s", out);
    if (system(path) != 0)
        return;
    snprintf(path, sizeof path, "%s/x.icd", out);
    FILE *f = fopen(path, "w");
    if (f) {
        fprintf(f, "%s\n", lib);
        fclose(f);
    }
}

static void test_why(void)
{
    char d[400], msg[2000];
    unsetenv("OCL_ICD_FILENAMES");
    snprintf(d, sizeof d, "%s/none", dir);
    snprintf(msg, sizeof msg, "mkdir -p %s", d);
    CHECK(system(msg) == 0, "mkdir");
    setenv("OCL_ICD_VENDORS", d, 1);
    CHECK(ob_cl_no_platform_why(msg, sizeof msg) == 0 && strstr(msg, "no ICD is installed") &&
              strstr(msg, "install an ICD") && strstr(msg, d),
          "no ICD: %s", msg);
    icd("missing", "/nonexistent/libnothere.so", d, sizeof d);
    setenv("OCL_ICD_VENDORS", d, 1);
    CHECK(ob_cl_no_platform_why(msg, sizeof msg) == 0 && strstr(msg, "x.icd") && strstr(msg, "libnothere.so") &&
              strstr(msg, "cannot be loaded") && !strstr(msg, "memory"),
          "a missing library: %s", msg);
    icd("loads", "libm.so.6", d, sizeof d);
    setenv("OCL_ICD_VENDORS", d, 1);
    CHECK(ob_cl_no_platform_why(msg, sizeof msg) == 0 && strstr(msg, "loads but gives no platform"),
          "a library that loads: %s", msg);
    setenv("OCL_ICD_FILENAMES", "/nonexistent/liba.so:/nonexistent/libb.so", 1);
    CHECK(ob_cl_no_platform_why(msg, sizeof msg) == 0 && strstr(msg, "OCL_ICD_FILENAMES") && strstr(msg, "liba.so"),
          "OCL_ICD_FILENAMES: %s", msg);
    unsetenv("OCL_ICD_FILENAMES");
    unsetenv("OCL_ICD_VENDORS");
}

static int ok_fn(void *ctx, ob_err *e) { (void)ctx, (void)e; return 0; }
static int oom_fn(void *ctx, ob_err *e) { (void)ctx; return ob_fail(e, "child says out of memory") - 1; }
static int abort_fn(void *ctx, ob_err *e) { (void)ctx, (void)e; raise(SIGABRT); return 0; }

/* Without a limit nothing is tried; under one the child's outcome comes back. */
static void test_child(void)
{
    char lim[100];
    ob_err e = {""};
    int rc = 7;
    struct rlimit r;
    CHECK(getrlimit(RLIMIT_AS, &r) == 0, "getrlimit");
    if (r.rlim_cur == RLIM_INFINITY) {
        CHECK(ob_as_limit(lim, sizeof lim) == 0 && lim[0] == '\0', "no limit: %s", lim);
        CHECK(ob_cl_try_in_child(ok_fn, NULL, &rc, &e) == -1 && rc == 7, "no limit: not tried");
        CHECK(ob_dl_oom("libx.so: failed to map segment from shared object") == 0,
              "a failed mapping without a limit: not memory");
    }
    CHECK(ob_dl_oom("libx.so: Cannot allocate memory") == 1 && ob_dl_oom(NULL) == 0, "said memory: memory");
    /* a limit that never binds (ASan's shadow maps terabytes) */
    const struct rlimit big = {RLIM_INFINITY - 1, r.rlim_max};
    if (r.rlim_cur == RLIM_INFINITY && setrlimit(RLIMIT_AS, &big) != 0) {
        SKIP("cannot set RLIMIT_AS");
        return;
    }
    CHECK(ob_as_limit(lim, sizeof lim) == 1 && strstr(lim, "ulimit -v"), "limited: %s", lim);
    CHECK(ob_dl_oom("libx.so: failed to map segment from shared object") == 1, "a failed mapping under a limit");
    CHECK(ob_cl_try_in_child(ok_fn, NULL, &rc, &e) == 0 && rc == 0, "a child that works: 0, rc 0");
    CHECK(ob_cl_try_in_child(oom_fn, NULL, &rc, &e) == 0 && rc == -2 && strcmp(e.msg, "child says out of memory") == 0,
          "a child that fails: its rc %d and message '%s'", rc, e.msg);
    CHECK(ob_cl_try_in_child(abort_fn, NULL, &rc, &e) == SIGABRT, "a child that aborts: its signal");
    setrlimit(RLIMIT_AS, &r);
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/ob_clprobe_XXXXXX");
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp");
        return check_done();
    }
    test_why();
    test_child();
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
    return check_done();
}
