/*
 * fsutil.c - output directories and files a reader never sees half-written
 * (declared in commands.h).
 */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "commands.h"
#include "diag.h"

int ob_mkdir_p(const char *dir)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST)
            return -1;
        *p = '/';
    }
    if (mkdir(buf, 0777) != 0 && errno != EEXIST)
        return -1;
    struct stat st;
    if (stat(buf, &st) != 0)
        return -1;
    if (!S_ISDIR(st.st_mode)) {  /* EEXIST from a file of that name */
        errno = ENOTDIR;
        return -1;
    }
    return 0;
}

/* Writes DIR/NAME through a temporary file and a rename, so a reader never
 * sees a half-written file. */
int ob_write_atomically(const char *dir, const char *name, int (*writer)(FILE *, void *), void *ctx)
{
    char path[4200], tmp[4210];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        ob_error("%s: cannot write: %s", tmp, strerror(errno));
        return -1;
    }
    int rc = writer(f, ctx);
    if (fclose(f) != 0 || rc != 0) {
        ob_error("%s: write failed", tmp);
        remove(tmp);
        return -1;
    }
    if (rename(tmp, path) != 0) {
        ob_error("%s: cannot rename to %s: %s", tmp, path, strerror(errno));
        remove(tmp);
        return -1;
    }
    return 0;
}


/* The owner of a run directory: a POSIX record lock (fcntl F_SETLK) on
 * DIR/.lock, which the kernel releases when the process ends however it
 * ends; the file holds the owner's pid.  The lock is per process and would
 * be dropped if the process closed any descriptor of the file: only this
 * function opens it. */
int ob_lock_dir(const char *dir, int *fd_out, char *err, size_t errlen)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/.lock", dir);
    *fd_out = -1;
    const int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot create the lock file: %s", path, strerror(errno));
        return -1;
    }
    struct flock fl;
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    if (fcntl(fd, F_SETLK, &fl) != 0) {
        const int e = errno;
        long pid = -1;
        struct flock q;
        memset(&q, 0, sizeof q);
        q.l_type = F_WRLCK;
        q.l_whence = SEEK_SET;
        if (fcntl(fd, F_GETLK, &q) == 0 && q.l_type != F_UNLCK)
            pid = (long)q.l_pid;
        if (pid <= 0) {  /* the pid the holder wrote */
            char buf[32] = "";
            ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
            if (n > 0) {
                buf[n] = '\0';
                pid = strtol(buf, NULL, 10);
            }
        }
        close(fd);
        if (e == EACCES || e == EAGAIN) {
            snprintf(err, errlen, "%s is in use by another offbench run (pid %ld holds %s): wait for it to end, or "
                     "choose another directory", dir, pid, path);
            return -2;
        }
        snprintf(err, errlen, "%s: cannot lock: %s", path, strerror(e));
        return -1;
    }
    char buf[32];
    const int n = snprintf(buf, sizeof buf, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, buf, (size_t)n, 0) != n) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        return -1;
    }
    *fd_out = fd;
    return 0;
}
