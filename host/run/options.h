/*
 * options.h - the `run` command line (README "Command line").
 */
#ifndef OB_OPTIONS_H
#define OB_OPTIONS_H

#include <stdint.h>

#include "host/backend/select.h"
#include "methods/driver/driver.h"

/* --certify's modes (host/run/certify.h) */
enum { OB_CERTIFY_VERDICT = 1, OB_CERTIFY_TIGHT = 2 };

enum { OB_MAX_TOLS = 64, OB_MAX_PARAM_ARGS = 256, OB_RUN_MAX_FLAGS = 32 };

/* What the command line asked for: set by parsing (ob_run_opts_parse), then
 * read only.  What the run finds out goes to an ob_run_record (record.h). */
typedef struct {
    const char *curves_file;     /* --curves FILE, or NULL: every curve file under
                                    datasets/ (none with --random) */
    char **curve_ids;            /* --curve ID,... (owned), NULL: all */
    int ncurve_ids;
    long random_n;               /* --random N[:SEED]: N curves (0: none) ... */
    uint64_t random_seed;        /* ... of this seed (random.h) */
    const ob_method **methods;   /* --methods (owned array) */
    int nmethods;
    double tols[OB_MAX_TOLS];
    int ntols;
    ob_metric metric;
    ob_split split;
    ob_backend backend;
    const char *device;          /* --device NAME-SUBSTRING, or NULL */
    double *params;              /* method parameters: OB_MAX_PARAMS values per
                                    registered method, by registry index (owned) */
    int threads;                 /* 0: OpenMP's default */
    int reps;                    /* --reps N: timed repetitions after a warm-up
                                    run (samples.csv); 0: one run, no samples */
    const char *out_dir;
    const char *export_dir;      /* --export DIR: each job's approximation (host/io/export.h) */
    int certify;                 /* --certify: each job's certified error (host/run/certify.h):
                                    0 off, OB_CERTIFY_VERDICT, OB_CERTIFY_TIGHT */
    int time_fits;               /* --time-fits: each method's own time (host/run/fittime.h) */
    int trimmed;                 /* --trimmed: each job against the trimmed offset (host/run/trimmed.h) */
    int fit_rounds;              /* --fit-reps N: its rounds (default OB_FITTIME_ROUNDS) */
    double fit_min_ns;           /* --fit-min-time MS: each measurement's length, ns */
    int fit_opts_given;          /* --fit-reps or --fit-min-time given (parsing) */
    const char *resume_dir;      /* --resume DIR: finish the run in DIR (journal.h) */
    int force;                   /* --force: a fresh run over an interrupted
                                    run's journal (which it removes) */
    int out_given;               /* --out was given (parsing) */
    const char *param_seen[OB_MAX_PARAM_ARGS]; /* the --param values so far (parsing) */
    int nparam_seen;
    const char *typed[OB_RUN_MAX_FLAGS]; /* each option's value as given on the
                                    command line, by flag ("" for a flag
                                    without value); NULL: not given */
    char *curves_file_owned;     /* --curves taken from a resumed run (owned) */
    int shard_k, shard_n;        /* --shard K/N: this process runs shard K of N
                                    (shard.h); shard_n 0: the whole run */
    ob_driver_opts driver;
    int argc;                    /* the command line, for meta.json */
    char **argv;
} ob_run_opts;

#include "host/cli/cliopts.h"

/* What `run --help` prints after the command's name. */
#define OB_RUN_SYNOPSIS "[options]   (a benchmark run: every method on every curve at every tolerance)"

/* The run options, for the commands that take some of them (draw, trace,
 * tables) beside their own. */
extern const ob_flag ob_run_flags[];
extern const int ob_run_nflags;

/* Purpose: apply one run option (an ob_flag_apply for ob_run_flags; ctx: the
 *          ob_run_opts, set up by ob_run_opts_init). */
int ob_run_flag_apply(void *ctx, int id, const char *opt, const char *value);

/* Purpose: apply the run option --name value (what draw and trace turn
 *          their --method and --tol into).  Returns 0, or -1 after ob_error(). */
int ob_run_opt_set(ob_run_opts *o, const char *name, const char *value);

/* Purpose: the value of option --name as given on the command line ("" for
 *          a flag without value), or NULL when it was not given. */
const char *ob_run_opt_typed(const ob_run_opts *o, const char *name);

/* Purpose: the value of --param key=VALUE (key "METHOD.NAME") as given, or
 *          NULL when that parameter was not given. */
const char *ob_run_param_typed(const ob_run_opts *o, const char *key);

/* Purpose: the defaults, before any option (argv: recorded for meta.json).
 * Returns 0, or -1 when out of memory.  *o is then safe to free. */
int ob_run_opts_init(ob_run_opts *o, int argc, char **argv);

/* Purpose: the checks across options, once all are applied.  Returns 0, or
 *          -1 after ob_error(). */
int ob_run_opts_finish(ob_run_opts *o);

/* Purpose: parse `run` options (argv[0] is "run").
 * Returns: OB_CLI_OK; OB_CLI_HELP after printing the help (exit 0);
 *          OB_CLI_ERROR after reporting through ob_error() an unknown
 *          option, a missing or malformed value (naming the option).
 *          Always leaves *o safe to pass to ob_run_opts_free(). */
int ob_run_opts_parse(int argc, char **argv, ob_run_opts *o);

/* Always safe to call. */
void ob_run_opts_free(ob_run_opts *o);

#endif
