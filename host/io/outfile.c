/*
 * outfile.c - files written without ever following a link (outfile.h).
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/io/outfile.h"

/* A new file at path, whatever had that name removed first: O_EXCL makes
 * open fail rather than follow a link or reuse a file (a hard link) that
 * another name shares.  A descriptor, or -1 (errno). */
static int create_new(const char *path)
{
    for (int tries = 0; tries < 3; tries++) {
        const int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST)
            return fd;
        if (unlink(path) != 0 && errno != ENOENT)
            return -1;  /* a directory, a name we may not remove */
    }
    errno = EEXIST;  /* something keeps putting a file there */
    return -1;
}

int ob_outfile_open(ob_outfile *o, const char *path, int per_process, ob_err *err)
{
    memset(o, 0, sizeof *o);
    const int pl = snprintf(o->path, sizeof o->path, "%s", path);
    const int tl = per_process ? snprintf(o->tmp, sizeof o->tmp, "%s.%ld.tmp", path, (long)getpid())
                               : snprintf(o->tmp, sizeof o->tmp, "%s.tmp", path);
    if (pl < 0 || tl < 0 || pl >= (int)sizeof o->path || tl >= (int)sizeof o->tmp) {
        o->tmp[0] = '\0';
        return ob_fail(err, "%.200s...: cannot write: the path is too long", path);
    }
    /* the rename would replace a directory's or a device's name (as root,
     * /dev/null itself), or a link to one: those are refused, not written */
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        o->tmp[0] = '\0';
        return ob_fail(err, "%s: %s (offbench writes regular files only)", path,
                       S_ISDIR(st.st_mode) ? "is a directory" : "not a regular file");
    }
    const int fd = create_new(o->tmp);
    if (fd >= 0 && !(o->f = fdopen(fd, "w")))
        close(fd);
    if (!o->f) {
        ob_fail(err, "%s: cannot write: %s", o->tmp, strerror(errno));
        o->tmp[0] = '\0';  /* nothing of ours to remove */
        return -1;
    }
    return 0;
}

int ob_outfile_finish(ob_outfile *o, int sync, ob_err *err)
{
    int bad = !o->f || ferror(o->f);
    if (o->f && sync && (fflush(o->f) != 0 || fsync(fileno(o->f)) != 0))
        bad = 1;
    if (o->f && fclose(o->f) != 0)
        bad = 1;
    o->f = NULL;
    if (bad) {
        ob_fail(err, "%s: write failed", o->tmp);
        ob_outfile_discard(o);
        return -1;
    }
    return 0;
}

int ob_outfile_publish(ob_outfile *o, ob_err *err)
{
    if (rename(o->tmp, o->path) != 0) {
        ob_fail(err, "%s: cannot rename to %s: %s", o->tmp, o->path, strerror(errno));
        ob_outfile_discard(o);
        return -1;
    }
    o->tmp[0] = '\0';  /* it is path now */
    return 0;
}

int ob_outfile_commit(ob_outfile *o, int sync, ob_err *err)
{
    if (ob_outfile_finish(o, sync, err) != 0)
        return -1;
    return ob_outfile_publish(o, err);
}

void ob_outfile_discard(ob_outfile *o)
{
    if (o->f)
        fclose(o->f);
    o->f = NULL;
    if (o->tmp[0])
        unlink(o->tmp);
    o->tmp[0] = '\0';
}

int ob_open_in_place(const char *path, int flags, ob_err *err)
{
    /* O_NONBLOCK: a FIFO planted there is refused below, not waited on */
    const int fd = open(path, flags | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
    if (fd < 0 && errno == ELOOP) {
        ob_fail(err, "%s: is a symbolic link; offbench never writes through a link (it would change the "
                "file the link points to): remove it", path);
        return -2;
    }
    if (fd < 0) {
        ob_fail(err, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    struct stat st;
    int rc = 0;
    if (fstat(fd, &st) != 0)
        rc = ob_fail(err, "%s: cannot open: %s", path, strerror(errno));
    else if (!S_ISREG(st.st_mode))
        rc = ob_fail(err, "%s: not a regular file", path);
    else if (st.st_nlink > 1) {
        ob_fail(err, "%s: has %ld names (a hard link); offbench never writes through a link (it would "
                "change the file under its other names): remove it", path, (long)st.st_nlink);
        rc = -2;
    }
    int fl;
    if (rc == 0 && ((fl = fcntl(fd, F_GETFL)) < 0 || fcntl(fd, F_SETFL, fl & ~O_NONBLOCK) != 0))
        rc = ob_fail(err, "%s: cannot open: %s", path, strerror(errno));
    if (rc != 0) {
        close(fd);
        return rc;
    }
    return fd;
}
