/*
 * clprobe.c - why an installed OpenCL platform did not start (clprobe.h).
 */
#include "host/backend/clprobe.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

int ob_as_limit(char *buf, size_t len)
{
    struct rlimit r;
    if (getrlimit(RLIMIT_AS, &r) != 0 || r.rlim_cur == RLIM_INFINITY) {
        snprintf(buf, len, "%s", "");
        return 0;
    }
    snprintf(buf, len, " (the address space is limited to %llu MiB: ulimit -v)",
             (unsigned long long)(r.rlim_cur >> 20));
    return 1;
}

int ob_dl_oom(const char *dlerr)
{
    char lim[100];
    if (!dlerr)
        return 0;
    if (strstr(dlerr, "Cannot allocate memory") || strstr(dlerr, "cannot allocate memory"))
        return 1;
    /* glibc's words when mmap fails: ENOMEM under a limit, but also a
     * noexec mount, so memory only when the address space is limited */
    return strstr(dlerr, "failed to map segment") && ob_as_limit(lim, sizeof lim);
}

/* What the ICDs' libraries do when loaded, gathered over all of them. */
typedef struct {
    int icds, loads, oom;
    char first[1200];  /* the first failure, or the first that loads: named */
} icd_scan;

/* Load lib (from icd, for the message) as the ICD loader would, note the outcome. */
static void try_lib(icd_scan *s, const char *icd, const char *lib)
{
    s->icds++;
    void *h = dlopen(lib, RTLD_LAZY | RTLD_LOCAL);
    const char *e = h ? NULL : dlerror();
    if (h) {
        dlclose(h);
        if (!s->loads++ && !s->first[0])
            snprintf(s->first, sizeof s->first, "%.300s (%.300s) loads but gives no platform: it failed to start",
                     icd, lib);
        return;
    }
    const int oom = ob_dl_oom(e);
    if (oom && !s->oom)
        s->first[0] = '\0';  /* out of memory is the one to say */
    if (!s->first[0] || (oom && !s->oom))
        snprintf(s->first, sizeof s->first, "%.300s names %.300s, which cannot be loaded: %.400s", icd, lib,
                 e ? e : "?");
    s->oom |= oom;
}

/* The first line of an .icd file (the library it names) into lib; 0 or -1. */
static int icd_lib(const char *path, char *lib, size_t len)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    const int ok = fgets(lib, (int)len, f) != NULL;
    fclose(f);
    lib[strcspn(lib, "\r\n")] = '\0';
    return ok && lib[0] ? 0 : -1;
}

/* The .icd files of dir, each tried. */
static void scan_dir(icd_scan *s, const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d))) {
        const size_t n = strlen(e->d_name);
        char path[4200], lib[1024];
        if (n < 5 || strcmp(e->d_name + n - 4, ".icd") != 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (icd_lib(path, lib, sizeof lib) == 0)
            try_lib(s, path, lib);
    }
    if (d)
        closedir(d);
}

int ob_cl_no_platform_why(char *msg, size_t len)
{
    icd_scan s = {0, 0, 0, ""};
    const char *names = getenv("OCL_ICD_FILENAMES"), *vend = getenv("OCL_ICD_VENDORS");
    const char *dir = vend && *vend ? vend : "/etc/OpenCL/vendors";
    char lim[100];
    const int limited = ob_as_limit(lim, sizeof lim);
    if (names && *names) {  /* the ocl-icd loader takes these instead of the .icd files */
        char list[4096], *save = NULL;
        snprintf(list, sizeof list, "%s", names);
        for (char *t = strtok_r(list, ":", &save); t; t = strtok_r(NULL, ":", &save))
            try_lib(&s, "OCL_ICD_FILENAMES", t);
    } else {
        scan_dir(&s, dir);
    }
    if (s.oom)
        snprintf(msg, len, "out of memory starting the OpenCL platform: %s%s", s.first, lim);
    else if (!s.icds)
        snprintf(msg, len, "no OpenCL platform: no ICD is installed (%.300s has no .icd file); install an ICD "
                 "such as pocl-opencl-icd", names && *names ? "OCL_ICD_FILENAMES" : dir);
    else if (!s.loads)
        snprintf(msg, len, "no OpenCL platform: %s (reinstall that ICD)", s.first);
    else
        snprintf(msg, len, "%s%s: %s", limited ? "out of memory starting the OpenCL platform" : "no OpenCL platform",
                 lim, s.first);
    return s.oom || (s.loads && limited);
}

/* The child: fn's message down the pipe, its status (0, 1, 2) as exit.
 * Its stderr goes nowhere: what it would warn the run warns itself when it
 * does the same, and what made it fail comes back through the pipe. */
static void child(int (*fn)(void *, ob_err *), void *ctx, int fd)
{
    ob_err e = {""};
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0)
        dup2(null, 2);
    const int rc = fn(ctx, &e);
    if (rc != 0 && write(fd, e.msg, strlen(e.msg)) < 0)
        _exit(3);
    _exit(rc == -2 ? 2 : rc != 0);
}

int ob_cl_try_in_child(int (*fn)(void *, ob_err *), void *ctx, int *rc, ob_err *err)
{
    char lim[100];
    int fd[2];
    if (!ob_as_limit(lim, sizeof lim) || pipe(fd) != 0)
        return -1;
    fflush(NULL);  /* nothing buffered is written twice */
    const pid_t pid = fork();
    if (pid == 0) {
        close(fd[0]);
        child(fn, ctx, fd[1]);
    }
    close(fd[1]);
    size_t n = 0;
    ssize_t got = 0;
    while (pid > 0 && n + 1 < sizeof err->msg &&
           ((got = read(fd[0], err->msg + n, sizeof err->msg - 1 - n)) > 0 || (got < 0 && errno == EINTR)))
        n += got > 0 ? (size_t)got : 0;
    err->msg[n] = '\0';
    close(fd[0]);
    int st = 0;
    pid_t w = -1;
    while (pid > 0 && (w = waitpid(pid, &st, 0)) < 0 && errno == EINTR)
        ;
    if (w != pid)
        return -1;
    if (WIFSIGNALED(st))
        return WTERMSIG(st);
    const int x = WIFEXITED(st) ? WEXITSTATUS(st) : 3;
    *rc = x == 0 ? 0 : x == 2 ? -2 : -1;
    if (x == 3)
        snprintf(err->msg, sizeof err->msg, "the OpenCL trial process failed");
    return 0;
}
