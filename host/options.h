/*
 * options.h - the `run` command line (DESIGN.md "Command line").
 */
#ifndef OB_OPTIONS_H
#define OB_OPTIONS_H

#include "../methods/driver.h"

enum { OB_MAX_TOLS = 64 };

typedef enum { OB_BACKEND_AUTO = 0, OB_BACKEND_OPENCL, OB_BACKEND_CPU } ob_backend;

typedef struct {
    const char *curves_file;     /* --curves FILE, or NULL: every curve file under datasets/ */
    char **curve_ids;            /* --curve ID,... (owned), NULL: all */
    int ncurve_ids;
    const ob_method **methods;   /* --methods (owned array) */
    int nmethods;
    double tols[OB_MAX_TOLS];
    int ntols;
    ob_metric metric;
    ob_split split;
    ob_backend backend;
    double *params;              /* method parameters: OB_MAX_PARAMS values per
                                    registered method, by registry index (owned) */
    int threads;                 /* 0: OpenMP's default */
    const char *out_dir;
    ob_driver_opts driver;
    int argc;                    /* for meta.json */
    char **argv;
} ob_run_opts;

/* Purpose: parse `run` options (argv[0] is "run").
 * Errors:  returns 0; -1 after reporting through ob_error() an unknown option,
 *          a missing or malformed value (naming the option).  Always leaves
 *          *o safe to pass to ob_run_opts_free(). */
int ob_run_opts_parse(int argc, char **argv, ob_run_opts *o);

/* Always safe to call. */
void ob_run_opts_free(ob_run_opts *o);

#endif
