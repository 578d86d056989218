/*
 * sisl_exe.c - the sisl server's program for liboffbench (sisl_exe.h).
 */
#define _GNU_SOURCE 1 /* dladdr */
#include "host/lib/sisl_exe.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "methods/sisl_server.h"

static pthread_once_t once = PTHREAD_ONCE_INIT;
static char exe[PATH_MAX + 64];
static char problem[PATH_MAX + 512];

/* 1 when the object holding this function is the running program. */
static int in_main_program(const char *obj)
{
    char a[PATH_MAX], b[PATH_MAX];
    return realpath(obj, a) && realpath("/proc/self/exe", b) && strcmp(a, b) == 0;
}

static void choose(void)
{
    const char *env = getenv("OFFBENCH_SISL_EXE");
    Dl_info info;
    if (env && *env) {
        snprintf(exe, sizeof exe, "%s", env);
    } else if (!dladdr((void *)choose, &info) || !info.dli_fname || in_main_program(info.dli_fname)) {
        return; /* /proc/self/exe links the method and serves */
    } else {
        /* beside the library (build/), else in its directory's offbench/
         * (make install: LIBDIR/offbench/, the package's private programs) */
        const char *slash = strrchr(info.dli_fname, '/');
        int dir = slash ? (int)(slash - info.dli_fname) : 1;
        const char *d = slash ? info.dli_fname : ".";
        snprintf(exe, sizeof exe, "%.*s/offbench-sisl-server", dir, d);
        if (access(exe, X_OK) != 0)
            snprintf(exe, sizeof exe, "%.*s/offbench/offbench-sisl-server", dir, d);
    }
    if (access(exe, X_OK) != 0) {
        snprintf(problem, sizeof problem,
                 "its fits run in a server process, and %s is not an executable program (%s; set "
                 "OFFBENCH_SISL_EXE to build/offbench-sisl-server or ./offbench)",
                 exe, env && *env ? "OFFBENCH_SISL_EXE" : "nor is offbench-sisl-server beside the library");
        return;
    }
    ob_sisl_set_server_exe(exe);
}

int ob_lib_sisl_ready(char *why, size_t len)
{
    pthread_once(&once, choose);
    if (!problem[0])
        return 0;
    snprintf(why, len, "%s", problem);
    return -1;
}
