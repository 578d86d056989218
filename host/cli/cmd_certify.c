/*
 * cmd_certify.c - ./offbench certify RUN_DIR [options]: a finished run
 * certified after the fact, as `run --certify` would have certified it
 * (host/run/certify_after.h; docs/certified.md).
 *
 * Options: --methods LIST, --tols LIST, --curves ID,... (only those cells;
 * default all), and of run's: --threads, --backend, --device, --engine
 * (how the jobs are run again for their pieces: never a result).  The run's
 * own options come from its results.fingerprint.
 *
 * Exit status: 0; 1 a job not certified or a file not written; 2 bad input
 * or a refused directory (not a run, another build or data, a malformed
 * results.csv named FILE:LINE, an unknown method named with its option);
 * 128 + signal when stopped (what was certified is kept).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/cli/suggest.h"
#include "host/diag.h"
#include "host/io/numfmt.h"
#include "host/run/certify_after.h"
#include "host/summary/summary.h"

enum { CO_METHODS, CO_TOLS, CO_CURVES, CO_TIGHT };

static const ob_flag certify_flags[] = {
    {"methods", "LIST", "only the jobs of these methods (default: all the run's)", CO_METHODS, OB_FLAG_LIST},
    {"tols", "LIST", "only the jobs of these tolerances (default: all the run's)", CO_TOLS, OB_FLAG_LIST},
    {"curves", "ID,...", "only the jobs of these curves (default: all the run's)", CO_CURVES, OB_FLAG_LIST},
    {"tight", NULL, "the enclosure to err_upper <= err_lower (1 + 1e-3), as run --certify=tight (default: the "
     "verdict, as run --certify)", CO_TIGHT, OB_FLAG_ONCE},
};

typedef struct {
    ob_sum_list methods, tols, curves;
    double *tolv;
    int tight;
} cmd_opts;

static int apply_certify_flag(void *ctx, int id, const char *opt, const char *v)
{
    cmd_opts *c = ctx;
    ob_err err;
    if (id == CO_TIGHT) {
        c->tight = 1;
        return 0;
    }
    ob_sum_list *l = id == CO_METHODS ? &c->methods : id == CO_TOLS ? &c->tols : &c->curves;
    if (ob_sum_list_parse(opt, v, l, &err) != 0) {
        ob_error("%s", err.msg);
        return -1;
    }
    if (id == CO_METHODS) {
        for (int k = 0; k < l->n; k++)
            if (!ob_method_find(l->v[k])) {
                char note[1024];
                ob_error("%s: unknown method '%s'%s", opt, l->v[k],
                         ob_suggest_method_note(l->v[k], note, sizeof note));
                return -1;
            }
    } else if (id == CO_TOLS) {
        free(c->tolv);
        if (!(c->tolv = malloc((size_t)l->n * sizeof *c->tolv))) {
            ob_error("out of memory");
            return -1;
        }
        for (int k = 0; k < l->n; k++)
            if (ob_parse_double(l->v[k], &c->tolv[k]) != 0 || !(c->tolv[k] > 0)) {
                ob_error("%s: expected positive numbers, got '%s'", opt, l->v[k]);
                return -1;
            }
    }
    return 0;
}

int ob_cmd_certify(int argc, char **argv)
{
    cmd_opts c;
    memset(&c, 0, sizeof c);
    ob_run_opts o;
    int st = 2;
    if (ob_run_opts_init(&o, argc, argv) != 0) {
        ob_error("out of memory");
        ob_run_opts_free(&o);
        return 1;
    }
    const ob_flagset sets[] = {
        {certify_flags, (int)(sizeof certify_flags / sizeof certify_flags[0]), NULL, NULL, "options",
         apply_certify_flag, &c},
        {ob_run_flags, ob_run_nflags, "threads backend device engine ", NULL,
         "how the jobs run again for their pieces (run's options; never a result)", ob_run_flag_apply, &o},
    };
    char *pos[1];
    int npos = 0;
    const int prc = ob_cli_parse("RUN_DIR [options]   (certify a finished run after the fact: the columns of "
                                 "run --certify)",
                                 sets, 2, argc, argv, 1, pos, &npos);
    if (prc == OB_CLI_HELP) {
        st = 0;
    } else if (prc == OB_CLI_OK && npos != 1) {
        ob_error("certify: expected RUN_DIR (the directory of a finished run)");
    } else if (prc == OB_CLI_OK) {
        o.resume_dir = pos[0];
        const ob_cert_select sel = {c.methods.v, c.methods.n, c.tolv, c.tols.n, c.curves.v, c.curves.n,
                                    c.tight ? OB_CERTIFY_TIGHT : OB_CERTIFY_VERDICT};
        st = ob_certify_after(&o, &sel);
    }
    ob_sum_list_free(&c.methods);
    ob_sum_list_free(&c.tols);
    ob_sum_list_free(&c.curves);
    free(c.tolv);
    ob_run_opts_free(&o);
    return st;
}
