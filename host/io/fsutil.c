/*
 * fsutil.c - output directories and files a reader never sees half-written
 * (fsutil.h).
 */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/io/fsutil.h"
#include "host/io/outfile.h"
#include "host/diag.h"

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
 * sees a half-written file, and a link at either name is never followed. */
int ob_write_atomically(const char *dir, const char *name, int (*writer)(FILE *, void *), void *ctx)
{
    char path[4200];
    ob_outfile o;
    ob_err err;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (ob_outfile_open(&o, path, 0, &err) != 0) {
        ob_error("%s", err.msg);
        return -1;
    }
    if (writer(o.f, ctx) != 0) {
        ob_error("%s: write failed", o.tmp);
        ob_outfile_discard(&o);
        return -1;
    }
    if (ob_outfile_commit(&o, 0, &err) != 0) {
        ob_error("%s", err.msg);
        return -1;
    }
    return 0;
}

/* The owner of a run directory: a POSIX record lock (fcntl F_SETLK) on
 * DIR/.lock, which the kernel releases when the process ends however it
 * ends; the file holds the owner's pid.  The lock is per process and would
 * be dropped if the process closed any descriptor of the file: only this
 * function opens it. */
int ob_lock_dir(const char *dir, int *fd_out, ob_err *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/.lock", dir);
    *fd_out = -1;
    const int fd = ob_open_in_place(path, O_RDWR | O_CREAT, err);  /* a link there: refused, -2 */
    if (fd < 0)
        return fd;
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
            ob_fail(err, "%s is in use by another offbench run (pid %ld holds %s): wait for it to end, or "
                    "choose another directory", dir, pid, path);
            return -2;
        }
        ob_fail(err, "%s: cannot lock: %s", path, strerror(e));
        return -1;
    }
    char buf[32];
    const int n = snprintf(buf, sizeof buf, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, buf, (size_t)n, 0) != n) {
        ob_fail(err, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        return -1;
    }
    *fd_out = fd;
    return 0;
}

int ob_take_run_dir(const char *cmd, const char *dir, int create, int *fd)
{
    ob_err err;
    *fd = -1;
    if (create && ob_mkdir_p(dir) != 0) {
        ob_error("%s: --out: cannot create '%s': %s", cmd, dir, strerror(errno));
        return 1;
    }
    const int lrc = ob_lock_dir(dir, fd, &err);
    if (lrc != 0) {
        ob_error("%s: --out: %s", cmd, err.msg);
        return lrc == -2 ? 2 : 1;
    }
    return 0;
}

static int check_not_input(const char *cmd, const char *opt, const char *out, int out_is_dir, const char *const *in,
                           size_t nin);

/* stat of path's directory and its last name (for a path that need not
 * exist); 0 or -1. */
static int parent_of(const char *path, struct stat *dst, const char **base)
{
    char dir[4200];
    const char *slash = strrchr(path, '/');
    while (slash && slash > path && !slash[1]) {  /* "a/b/": b is the name */
        const char *s = slash - 1;
        while (s > path && *s != '/')
            s--;
        slash = *s == '/' ? s : NULL;
    }
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    *base = slash ? slash + 1 : path;
    return stat(dir, dst);
}

static int same_node(const struct stat *a, const struct stat *b)
{
    return a->st_dev == b->st_dev && a->st_ino == b->st_ino;
}

/* Is the existing file or directory path, or one of the directories above
 * it, the directory d?  Walks up through "/.." by device and inode. */
static int lies_in(const char *path, const struct stat *d)
{
    char buf[4200];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return 0;
    struct stat st, prev;
    if (stat(buf, &st) != 0)
        return 0;
    if (!S_ISDIR(st.st_mode)) {  /* a file: is it the directory? then its directory on up */
        const char *base;
        if (same_node(&st, d) || parent_of(path, &st, &base) != 0)
            return same_node(&st, d);
        const char *slash = strrchr(path, '/');
        if (!slash)
            snprintf(buf, sizeof buf, ".");
        else
            snprintf(buf, sizeof buf, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    }
    for (int depth = 0; depth < 256; depth++) {
        if (same_node(&st, d))
            return 1;
        prev = st;
        const size_t len = strlen(buf);
        if (len + 4 >= sizeof buf || snprintf(buf + len, sizeof buf - len, "/..") < 0 || stat(buf, &st) != 0)
            return 0;
        if (same_node(&st, &prev))  /* the root is its own parent */
            return 0;
    }
    return 0;
}

int ob_check_out_not_input(const char *cmd, const char *out, int out_is_dir, const char *const *in, size_t nin)
{
    return check_not_input(cmd, "--out", out, out_is_dir, in, nin);
}

int ob_check_dir_not_input(const char *cmd, const char *opt, const char *dir, const char *const *in, size_t nin)
{
    return check_not_input(cmd, opt, dir, 1, in, nin);
}

int ob_check_file_not_input(const char *cmd, const char *opt, const char *out, const char *const *in, size_t nin)
{
    return check_not_input(cmd, opt, out, 0, in, nin);
}

static int check_not_input(const char *cmd, const char *opt, const char *out, int out_is_dir, const char *const *in,
                           size_t nin)
{
    struct stat os, ps;
    const char *obase = NULL;
    const int exists = stat(out, &os) == 0;
    const int parent_ok = !exists && parent_of(out, &ps, &obase) == 0;
    for (size_t i = 0; i < nin; i++) {
        if (!in[i])
            continue;
        int clash = 0;
        struct stat is;
        if (exists && (out_is_dir || S_ISDIR(os.st_mode)))
            clash = lies_in(in[i], &os);  /* the directory is, or holds, the input */
        else if (exists)
            clash = stat(in[i], &is) == 0 && same_node(&is, &os);
        else if (parent_ok) {  /* not there yet: the same directory and name */
            struct stat ips;
            const char *ibase = NULL;
            clash = parent_of(in[i], &ips, &ibase) == 0 && same_node(&ips, &ps) && strcmp(ibase, obase) == 0;
        }
        if (clash) {
            ob_error("%s: %s %s %s the input %s: it would be overwritten; choose another %s", cmd, opt, out,
                     exists && (out_is_dir || S_ISDIR(os.st_mode)) && !(stat(in[i], &is) == 0 && same_node(&is, &os))
                         ? "holds" : "is",
                     in[i], opt);
            return -1;
        }
    }
    return 0;
}

/* Every file of the set to NAME.tmp (flushed and fsync'ed), and only when all
 * of them are complete the renames, in the caller's order.  A failed write
 * (disk full, a size limit) therefore changes none of the files; the
 * temporaries go.  A link at any name is replaced, never followed (outfile.h). */
int ob_write_set_atomically(const char *dir, const ob_out_file *files, size_t n)
{
    ob_outfile *o = calloc(n ? n : 1, sizeof *o);
    if (!o) {
        ob_error("%s: out of memory", dir);
        return -1;
    }
    char path[4200];
    ob_err err;
    int ok = 1;
    for (size_t i = 0; i < n && ok; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i].name);
        if (ob_outfile_open(&o[i], path, 0, &err) != 0)
            ok = 0;
        else if (files[i].writer(o[i].f, files[i].ctx) != 0) {
            ob_fail(&err, "%s: write failed", o[i].tmp);
            ok = 0;
        } else {
            ok = ob_outfile_finish(&o[i], 1, &err) == 0;
        }
    }
    for (size_t i = 0; i < n && ok; i++)  /* results.csv is the caller's last */
        ok = ob_outfile_publish(&o[i], &err) == 0;
    if (!ok) {
        ob_error("%s", err.msg);
        for (size_t i = 0; i < n; i++)
            ob_outfile_discard(&o[i]);
        free(o);
        return -1;
    }
    free(o);
    const int dfd = open(dir, O_RDONLY);  /* the renames themselves to disk */
    if (dfd >= 0) {
        (void)fsync(dfd);
        close(dfd);
    }
    return 0;
}

int ob_abs_path(const char *path, char *buf, size_t len)
{
    char cwd[4096];
    if (path[0] == '/')
        return snprintf(buf, len, "%s", path) < (int)len ? 0 : -1;
    if (!getcwd(cwd, sizeof cwd)) {
        snprintf(buf, len, "%s", path);
        return -1;
    }
    const int slash = cwd[0] && cwd[strlen(cwd) - 1] != '/';
    return snprintf(buf, len, "%s%s%s", cwd, slash ? "/" : "", path) < (int)len ? 0 : -1;
}
