/*
 * external_opt.c - the --external option of every command (external_opt.h).
 */
#include "host/cli/external_opt.h"

#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "methods/external/ext.h"

/* One NAME=COMMAND: 0, or -1 after the error. */
static int take_external(const char *spec)
{
    const char *eq = strchr(spec, '=');
    if (!eq || eq == spec || !eq[1]) {
        ob_error("--external '%s': expected NAME=COMMAND (a program that speaks docs/external-methods.md)", spec);
        return -1;
    }
    char name[64], msg[512];
    const size_t n = (size_t)(eq - spec) < sizeof name ? (size_t)(eq - spec) : sizeof name - 1;
    memcpy(name, spec, n);
    name[n] = '\0';
    if (ob_ext_register(name, eq + 1, msg, sizeof msg) != 0) {
        ob_error("--external %s: %s", spec, msg);
        return -1;
    }
    return 0;
}

int ob_take_global_option(int *argc, char **argv, const char *opt, const char *what, int (*take)(const char *))
{
    const size_t n = strlen(opt);
    int k = 1;
    for (int i = 1; i < *argc; i++) {
        const char *v = NULL;
        if (strcmp(argv[i], opt) == 0) {
            if (i + 1 >= *argc) {
                ob_error("%s: expected %s after it", opt, what);
                return -1;
            }
            v = argv[++i];
        } else if (strncmp(argv[i], opt, n) == 0 && argv[i][n] == '=') {
            v = argv[i] + n + 1;
        } else {
            argv[k++] = argv[i];
            continue;
        }
        if (take(v) != 0)
            return -1;
    }
    argv[k] = NULL;
    *argc = k;
    return 0;
}

int ob_external_args(int *argc, char **argv)
{
    return ob_take_global_option(argc, argv, "--external", "NAME=COMMAND", take_external);
}
