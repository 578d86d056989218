/*
 * slurp.c - see slurp.h.
 */
#include "host/io/slurp.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int ob_slurp_max(const char *path, size_t max, char **text, size_t *len, ob_err *err)
{
    *text = NULL;
    *len = 0;
    if (max > OB_SLURP_LIMIT)
        max = OB_SLURP_LIMIT;
    /* O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        ob_fail(err, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        ob_fail(err, "%s: cannot stat: %s", path, strerror(errno));
        close(fd);
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        ob_fail(err, "%s: %s", path, S_ISDIR(st.st_mode) ? "is a directory" : "not a regular file");
        close(fd);
        return -1;
    }
    if ((unsigned long long)st.st_size > max) {
        ob_fail(err, "%s: file too large (%lld bytes; the limit is %zu MiB)", path, (long long)st.st_size,
                max >> 20);
        close(fd);
        return -1;
    }
    int fl = fcntl(fd, F_GETFL);
    if (fl != -1)
        (void)fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    /* read to the end, not st_size bytes (the file may grow), and never past
     * max: the buffer holds at most max + 1 bytes, and filling it means too large */
    size_t cap = (size_t)st.st_size + 2 < 65536 ? 65536 : (size_t)st.st_size + 2, n = 0;
    if (cap > max + 2)
        cap = max + 2;
    char *buf = malloc(cap);
    int rd = 0, toobig = 0;
    while (buf) {
        ssize_t got = read(fd, buf + n, cap - 1 - n);
        if (got < 0) {
            if (errno == EINTR)
                continue;
            rd = errno;
            break;
        }
        if (got == 0)
            break;
        n += (size_t)got;
        if (n > max) {
            toobig = 1;
            break;
        }
        if (n == cap - 1) {
            size_t nc = cap * 2 > max + 2 ? max + 2 : cap * 2;
            char *nb = realloc(buf, nc);
            if (!nb) {
                free(buf);
                buf = NULL;
            } else {
                buf = nb;
                cap = nc;
            }
        }
    }
    close(fd);
    if (!buf || rd || toobig) {
        if (toobig)
            ob_fail(err, "%s: file too large (the limit is %zu MiB)", path, max >> 20);
        else if (rd)
            ob_fail(err, "%s: read error: %s", path, strerror(rd));
        else
            ob_fail(err, "%s: out of memory", path);
        free(buf);
        return -1;
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return 0;
}

int ob_slurp(const char *path, char **text, size_t *len, ob_err *err)
{
    return ob_slurp_max(path, OB_SLURP_LIMIT, text, len, err);
}
