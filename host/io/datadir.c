/*
 * datadir.c - see datadir.h.
 */
#include "host/io/datadir.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct ob_embedded_file {
    const char *name;
    const char *text;
};
extern const struct ob_embedded_file ob_embedded_files[];

int ob_load_default_curves(ob_curveset *set, char *where, size_t wlen, ob_err *err)
{
    /* no ./datasets, no datasets/ beside the program: a run started beside
     * another checkout would silently use other curves (issue 36) */
    const char *env = getenv("OFFBENCH_DATA");
    if (env && *env) {
        snprintf(where, wlen, "%s", env);
        return ob_curves_load_dir(env, set, err);
    }
    snprintf(where, wlen, "embedded copy of datasets/");
    for (int i = 0; ob_embedded_files[i].name; i++) {
        const char *t = ob_embedded_files[i].text;
        if (ob_curves_parse(t, strlen(t), ob_embedded_files[i].name, set, err))
            return -1;
    }
    return 0;
}

int ob_find_tree_file(const char *rel, const char *env, char *path, size_t len)
{
    const char *e = env ? getenv(env) : NULL;
    if (e && *e) {
        snprintf(path, len, "%s", e);
        return 0;
    }
    if (access(rel, R_OK) == 0) {
        snprintf(path, len, "%s", rel);
        return 0;
    }
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return -1;
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash)
        return -1;
    slash[1] = '\0';
    if ((size_t)snprintf(path, len, "%s%s", exe, rel) >= len || access(path, R_OK) != 0)
        return -1;
    return 0;
}
