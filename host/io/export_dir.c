/*
 * export_dir.c - the export directory's names and its rule (export_dir.h).
 */
#include "host/io/export_dir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "buildinfo.h"
#include "host/diag.h"
#include "host/io/fsutil.h"
#include "host/io/numfmt.h"

const char *ob_export_build_datasets(void)
{
    return OB_DATASETS_DIR;
}

/* s[0..n) is a number as the stems spell d and tol (ob_fmt_double). */
static int is_number(const char *s, size_t n)
{
    char buf[48];
    double v;
    if (n == 0 || n >= sizeof buf || !(s[0] == '-' || s[0] == '.' || (s[0] >= '0' && s[0] <= '9')))
        return 0;
    memcpy(buf, s, n);
    buf[n] = '\0';
    return ob_parse_double(buf, &v) == 0;
}

/* Every byte of s[0..n) is in the set, and n > 0. */
static int only(const char *s, size_t n, const char *set)
{
    if (n == 0)
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!s[i] || !strchr(set, s[i]))
            return 0;
    return 1;
}

#define ALNUM "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"

/* The last occurrence of pat in s[0..n), or NULL. */
static const char *last_of(const char *s, size_t n, const char *pat)
{
    const size_t m = strlen(pat);
    for (size_t i = n >= m ? n - m + 1 : 0; i-- > 0;)
        if (memcmp(s + i, pat, m) == 0)
            return s + i;
    return NULL;
}

/* s[0..n) is CURVE__dD__METHOD__tolT. */
static int is_stem(const char *s, size_t n)
{
    const char *tol = last_of(s, n, "__tol");
    if (!tol || !is_number(tol + 5, n - (size_t)(tol + 5 - s)))
        return 0;
    const char *m = last_of(s, (size_t)(tol - s), "__");
    if (!m || !only(m + 2, (size_t)(tol - m - 2), ALNUM "-"))
        return 0;
    const char *d = last_of(s, (size_t)(m - s), "__d");
    return d && is_number(d + 3, (size_t)(m - d - 3)) && only(s, (size_t)(d - s), ALNUM "_.~-");
}

static int shard_index_name(const char *name, int *k, int *n)
{
    int kk, nn, end = 0;
    if (sscanf(name, "index.shard%d-of-%d.csv%n", &kk, &nn, &end) != 2 || name[end] || kk < 0 || kk >= nn)
        return 0;
    char canon[64];
    snprintf(canon, sizeof canon, "index.shard%d-of-%d.csv", kk, nn);
    if (strcmp(canon, name) != 0)  /* "index.shard+01-of-2.csv" is not ours */
        return 0;
    if (k)
        *k = kk;
    if (n)
        *n = nn;
    return 1;
}

ob_xname ob_export_name_kind(const char *name, char *stem, size_t len, int *k, int *n)
{
    static const char *const ext[] = {".json", ".curves", ".dxf", ".svg"};
    if (strcmp(name, "index.csv") == 0)
        return OB_XNAME_INDEX;
    if (shard_index_name(name, k, n))
        return OB_XNAME_SHARD_INDEX;
    size_t l = strlen(name);
    if (l > 4 && strcmp(name + l - 4, ".tmp") == 0)
        l -= 4;
    for (size_t e = 0; e < sizeof ext / sizeof ext[0]; e++) {
        const size_t el = strlen(ext[e]);
        if (l > el && memcmp(name + l - el, ext[e], el) == 0 && is_stem(name, l - el)) {
            if (stem && len)
                snprintf(stem, len, "%.*s", (int)(l - el), name);
            return OB_XNAME_STEM;
        }
    }
    return OB_XNAME_OTHER;
}

void ob_export_index_name(char *buf, size_t len, int shard_k, int shard_n)
{
    if (shard_n > 0)
        snprintf(buf, len, "index.shard%d-of-%d.csv", shard_k, shard_n);
    else
        snprintf(buf, len, "index.csv");
}

/* Whether rule r removes the entry called name. */
static int prunes(const ob_prune_rule *r, const char *name)
{
    char stem[512];
    int k, n;
    switch (ob_export_name_kind(name, stem, sizeof stem, &k, &n)) {
    case OB_XNAME_STEM: {
        if (r->scope && ob_strmap_get(r->scope, stem) < 0)
            return 0;
        const size_t l = strlen(name);
        return (l > 4 && strcmp(name + l - 4, ".tmp") == 0)  /* a write cut short is never a file kept */
               || !r->keep || ob_strmap_get(r->keep, stem) < 0;
    }
    case OB_XNAME_INDEX: return r->index_csv;
    case OB_XNAME_SHARD_INDEX: return r->shard_indexes == 0 || (r->shard_indexes > 0 && n != r->shard_indexes);
    case OB_XNAME_OTHER: break;
    }
    return 0;
}

int ob_export_prune(const char *dir, const ob_prune_rule *r, long *removed, ob_err *err)
{
    long count = 0;
    if (removed)
        *removed = 0;
    const int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    DIR *d = dfd >= 0 ? fdopendir(dfd) : NULL;
    if (!d) {
        if (dfd >= 0)
            close(dfd);
        return errno == ENOENT ? 0 : ob_fail(err, "%s: cannot read the directory: %s", dir, strerror(errno));
    }
    int rc = 0;
    struct dirent *de;
    errno = 0;
    while (rc == 0 && (de = readdir(d))) {
        struct stat st;
        if (!prunes(r, de->d_name) || fstatat(dfd, de->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0 ||
            !(S_ISREG(st.st_mode) || S_ISLNK(st.st_mode))) {
            errno = 0;
            continue;
        }
        if (unlinkat(dfd, de->d_name, 0) != 0 && errno != ENOENT)
            rc = ob_fail(err, "%s/%s: cannot remove an earlier export's file: %s", dir, de->d_name, strerror(errno));
        else
            count++;
        errno = 0;
    }
    if (rc == 0 && errno)
        rc = ob_fail(err, "%s: cannot read the directory: %s", dir, strerror(errno));
    closedir(d);
    if (removed)
        *removed = count;
    return rc;
}

/* dir and other are one existing directory. */
static int same_dir(const char *dir, const char *other)
{
    struct stat a, b;
    return other && *other && stat(dir, &a) == 0 && stat(other, &b) == 0 && S_ISDIR(a.st_mode) &&
           a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

int ob_export_check_dir(const char *cmd, const char *dir, const char *curves_file)
{
    const char *env = getenv("OFFBENCH_DATA");
    if (same_dir(dir, env)) {
        ob_error("%s: --export %s is the directory the default curves are loaded from ($OFFBENCH_DATA=%s): the "
                 "exported .curves files would be curves of every later default run; choose another --export",
                 cmd, dir, env);
        return -1;
    }
    if (same_dir(dir, ob_export_build_datasets())) {
        ob_error("%s: --export %s is the datasets/ directory this program was built from (%s), whose .curves "
                 "files are compiled into the next build's default curves; choose another --export (a "
                 "subdirectory is fine)",
                 cmd, dir, ob_export_build_datasets());
        return -1;
    }
    const char *const inputs[] = {curves_file};
    return ob_check_dir_not_input(cmd, "--export", dir, inputs, 1);
}
