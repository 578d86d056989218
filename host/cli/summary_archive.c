/*
 * summary_archive.c - loading and checking the runs of --archive (see
 * summary_archive.h).  The comparability rules are compare's, called, not
 * copied: an archive beside a run is a comparison without the verdicts.
 */
#include "host/cli/summary_archive.h"

#include <dirent.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "host/diag.h"

/* The results.csv of one run below dir (dir/NAME/results.csv), or NULL. */
static int has_results(const char *dir, const char *name, char *buf, size_t len)
{
    struct stat st;
    if (name[0] == '.' || snprintf(buf, len, "%s/%s/results.csv", dir, name) >= (int)len)
        return 0;
    return stat(buf, &st) == 0 && S_ISREG(st.st_mode);
}

/* The paths one ARCHIVE argument stands for, appended to *out (owned):
 * itself, or its subdirectories' runs.  0; 1 a directory without runs;
 * -1 out of memory. */
static int expand(const char *arg, char ***out, int *n)
{
    struct stat st;
    char buf[PATH_MAX + 64];
    snprintf(buf, sizeof buf, "%s/results.csv", arg);
    if (stat(arg, &st) != 0 || !S_ISDIR(st.st_mode) || stat(buf, &st) == 0) {  /* a run, or an error to name */
        char **v = realloc(*out, (size_t)(*n + 1) * sizeof *v);
        if (!v || !(v[*n] = strdup(arg)))
            return -1;
        *out = v;
        (*n)++;
        return 0;
    }
    struct dirent **ents;
    const int ne = scandir(arg, &ents, NULL, alphasort);
    const int before = *n;
    for (int i = 0; i < ne; i++) {
        if (has_results(arg, ents[i]->d_name, buf, sizeof buf)) {
            char **v = realloc(*out, (size_t)(*n + 1) * sizeof *v);
            if (v && (v[*n] = strdup(buf)) != NULL) {
                *out = v;
                (*n)++;
            }
        }
        free(ents[i]);
    }
    free(ne >= 0 ? ents : NULL);
    return *n > before ? 0 : 1;
}

/* "a; b; c" of l into buf. */
static void reasons(const ob_strlist *l, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < l->n && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? "; " : "", l->v[i]);
}

/* compare's checks of archive a (as BASE) against the run (as NEW): 0, or
 * 2 after ob_error() naming both files and every reason. */
static int check_comparable(const ob_cmp_side *a, const ob_cmp_side *run)
{
    ob_cmp_opts o = ob_cmp_defaults();
    o.no_timing = 1;  /* the summary judges no timing */
    ob_cmp_result r;
    ob_err err;
    memset(&r, 0, sizeof r);
    int rc = 0;
    if (ob_cmp_context(a, run, &o, &r, &err)) {
        ob_error("summary: --archive: %s", err.msg);
        rc = 2;
    } else if (r.incomparable.n) {
        char why[2048];
        reasons(&r.incomparable, why, sizeof why);
        ob_error("summary: --archive: %s is not comparable with %s (compare's checks, archive vs run): %s",
                 a->results_path, run->results_path, why);
        rc = 2;
    }
    ob_cmp_result_free(&r);
    return rc;
}

/* The same results.csv given twice (under another spelling of its path
 * too: the same device and inode). */
static int seen_before(const ob_sum_archives *a, const char *path)
{
    struct stat x, y;
    if (stat(path, &x) != 0)
        return 0;
    for (int i = 0; i < a->n; i++)
        if (stat(a->v[i]->results_path, &y) == 0 && x.st_dev == y.st_dev && x.st_ino == y.st_ino)
            return 1;
    return 0;
}

/* Loads one archived run into a->v and joins it: 0, or 2 after ob_error(). */
static int join_one(ob_summary *s, const char *path, ob_sum_archives *a)
{
    ob_err err;
    ob_cmp_side *side = calloc(1, sizeof *side);
    ob_cmp_side **v = side ? realloc(a->v, (size_t)(a->n + 1) * sizeof *v) : NULL;
    if (!v) {
        free(side);
        ob_error("summary: --archive: out of memory");
        return 2;
    }
    a->v = v;
    if (ob_cmp_load_side(path, "ARCHIVE", side, &err)) {
        ob_cmp_side_free(side);
        free(side);
        ob_error("summary: --archive: %s", err.msg);
        return 2;
    }
    if (seen_before(a, side->results_path)) {
        ob_error("summary: --archive: %s is given twice", side->results_path);
        ob_cmp_side_free(side);
        free(side);
        return 2;
    }
    v[a->n++] = side;
    const int shared = ob_summary_archive_shared(s, &side->res);
    if (!shared)
        return ob_strlist_addf(&s->alines, "Not joined: %s: no job in common with RUN (%d rows).",
                                       side->results_path, side->res.n) ? 2 : 0;
    if (check_comparable(side, &a->run))
        return 2;
    if (ob_summary_archive(s, &side->res, side->results_path, &err)) {
        ob_error("summary: --archive: %s", err.msg);
        return 2;
    }
    return 0;
}

int ob_sum_archives_join(ob_summary *s, const char *run_arg, const ob_sum_list *args, ob_sum_archives *a)
{
    ob_err err;
    if (ob_cmp_load_side(run_arg, "RUN", &a->run, &err)) {
        ob_error("summary: %s", err.msg);
        return 2;
    }
    char **paths = NULL;
    int n = 0, rc = 0;
    for (int i = 0; i < args->n && !rc; i++) {
        const int e = expand(args->v[i], &paths, &n);
        if (e)
            ob_error(e > 0 ? "summary: --archive: %s: no results.csv in it nor in its subdirectories"
                           : "summary: --archive: %s: out of memory", args->v[i]);
        rc = e ? 2 : 0;
    }
    for (int i = 0; i < n && !rc; i++)
        rc = join_one(s, paths[i], a);
    for (int i = 0; i < n; i++)
        free(paths[i]);
    free(paths);
    if (!rc && ob_summary_archive_done(s)) {
        ob_error("summary: --archive: out of memory");
        rc = 2;
    }
    return rc;
}

void ob_sum_archives_free(ob_sum_archives *a)
{
    for (int i = 0; i < a->n; i++) {
        ob_cmp_side_free(a->v[i]);
        free(a->v[i]);
    }
    free(a->v);
    ob_cmp_side_free(&a->run);
    memset(a, 0, sizeof *a);
}
