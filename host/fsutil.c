/*
 * fsutil.c - output directories and files a reader never sees half-written
 * (declared in commands.h).
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

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

