/*
 * cmd_list.c - `./offbench list methods|metrics|curves|columns|devices`.
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/external/ext.h"
#include "methods/method.h"
#include "methods/metrics/metric.h"
#include "host/backend/clrt.h"
#include "host/cli/commands.h"
#include "host/cli/methods_file.h"
#include "host/io/curvefile.h"
#include "host/io/datadir.h"
#include "host/cli/cliopts.h"
#include "host/cli/suggest.h"
#include "host/io/columns.h"
#include "host/diag.h"
#include "host/io/numfmt.h"
#include "host/io/random.h"

/* The output degree as a formula in the input degree n (the methods' degree
 * functions are linear in n: recover a*n + b from two evaluations). */
static void degree_formula(const ob_method *m, char *buf, size_t len)
{
    const int d3 = ob_method_out_degree(m, 3, 0, NULL), a = ob_method_out_degree(m, 4, 0, NULL) - d3, b = d3 - 3 * a;
    char an[16] = "";
    if (a != 1)
        snprintf(an, sizeof an, "%d", a);
    if (a == 0)
        snprintf(buf, len, "%d", b);
    else if (b == 0)
        snprintf(buf, len, "%sn", an);
    else
        snprintf(buf, len, "%sn%+d", an, b);
}

static int list_methods(void)
{
    printf("%-12s %-10s %-8s %-9s %-8s %s\n", "method", "output", "degree", "rational", "continu.", "citation");
    for (int i = 0; ob_methods[i]; i++) {
        const ob_method *m = ob_methods[i];
        char deg[32];
        degree_formula(m, deg, sizeof deg);
        const char *out = (m->caps & OB_CAP_RATIONAL_OUT) ? "rational" : "polynomial";
        printf("%-12s %-10s %-8s %-9s %-8s %s%s\n", m->name, out, deg,
               (m->caps & OB_CAP_RATIONAL_IN) ? "input ok" : "no",
               m->continuity, m->citation, (m->caps & OB_CAP_CONVEX) ? " [convex pieces]" : "");
        const ob_ext *e = ob_ext_of(m);
        if (e)  /* registered with --external: say which program answers */
            printf("%-12s   external method: %s\n", "", e->command);
        for (int k = 0; k < m->nparams; k++) {
            char num[40], lo[40], hi[40];
            const ob_param *p = &m->params[k];
            ob_fmt_double(num, sizeof num, p->def);
            ob_fmt_double(lo, sizeof lo, p->min);
            ob_fmt_double(hi, sizeof hi, p->max);
            printf("%-12s   --param %s.%s=%s (default; %s %s..%s): %s\n", "", m->name, p->name, num,
                   p->integer ? "whole numbers" : "range", lo, hi, p->doc);
        }
    }
    for (int k = 0; ob_methods_file_unavailable(k); k++) {  /* named by --methods-file, not there */
        const ob_unavailable *u = ob_methods_file_unavailable(k);
        printf("%-12s %-10s %-8s %-9s %-8s unavailable: %s (%s)\n", u->name, "-", "-", "-", "-", u->why, u->file);
        if (u->build[0])
            printf("%-12s   build it: %s\n", "", u->build);
        if (u->needs[0])
            printf("%-12s   which needs: %s\n", "", u->needs);
    }
    return 0;
}

static void print_curve_header(const char *where)
{
    printf("# curves from %s\n", where);
    printf("%-20s %-10s %-4s %-6s %-9s %-14s %s\n", "id", "family", "segs", "degree", "rational", "offsets", "source");
}

static void print_curve(const ob_curve *c)
{
    char offs[256] = "", num[40];
    for (int k = 0; k < c->nd; k++) {
        ob_fmt_double(num, sizeof num, c->d[k]);
        if (strlen(offs) + strlen(num) + 2 < sizeof offs) {
            if (k)
                strcat(offs, " ");
            strcat(offs, num);
        }
    }
    int rat = 0;
    for (int s = 0; s < c->nseg; s++)
        rat |= c->seg[s].rational;
    printf("%-20s %-10s %-4d %-6d %-9s %-14s %s\n", c->id, c->family ? c->family : "", c->nseg,
           c->nseg ? c->seg[0].deg : 0, rat ? "yes" : "no", offs, c->source ? c->source : "");
}

typedef struct {
    const char *file;
    long rn;
    uint64_t seed;
} list_curves_args;

static const ob_flag list_curves_flags[] = {
    {"curves", "FILE", "this curve file (default: every file under datasets/)", 0, OB_FLAG_ONCE},
    {"random", "N[:SEED]", "N random test curves of seed SEED (after the file)", 1, OB_FLAG_ONCE},
};

static int apply_list_curves_flag(void *ctx, int id, const char *opt, const char *v)
{
    list_curves_args *a = ctx;
    if (id == 0) {
        a->file = v;
        return 0;
    }
    return ob_random_parse(opt, v, &a->rn, &a->seed);
}

/* list columns: the results.csv header, one column a line with what it holds. */
static int list_columns(void)
{
    printf("# results.csv, in this order: %s\n", ob_results_header());
    for (int c = 0; c < OB_NCOLS; c++)
        printf("%-16s %s\n", ob_columns[c].name, ob_columns[c].meaning);
    return fflush(stdout) == 0 ? 0 : 1;
}

/* list metrics: every --metric name with its definition (metric.h). */
static int list_metrics(void)
{
    for (int m = 0; m < OB_METRIC_COUNT; m++)
        printf("%-10s %s\n", ob_metric_name((ob_metric)m), ob_metric_doc((ob_metric)m));
    return fflush(stdout) == 0 ? 0 : 1;
}

/* list curves [--curves FILE] [--random N[:SEED]]: as `run` loads them (the
 * file first); the random curves are generated one at a time, not stored. */
static int list_curves(int argc, char **argv)
{
    ob_curveset set = {0};
    char where[4096] = "";
    ob_err err;
    const char *file = NULL;
    long rn = 0;
    uint64_t seed = 1;
    int rc = 0;
    list_curves_args a = {NULL, 0, 1};
    const ob_flagset flags = {list_curves_flags, 2, NULL, NULL, "options", apply_list_curves_flag, &a};
    const int prc = ob_cli_parse("[--curves FILE] [--random N[:SEED]]", &flags, 1, argc - 1, argv + 1, 0, NULL, NULL);
    if (prc != OB_CLI_OK)
        return prc == OB_CLI_HELP ? 0 : 2;
    file = a.file;
    rn = a.rn;
    seed = a.seed;
    if (file) {
        snprintf(where, sizeof where, "%s", file);
        rc = ob_curves_load_file(file, &set, &err);
    } else if (rn == 0) {
        rc = ob_load_default_curves(&set, where, sizeof where, &err);
    }
    if (rc != 0) {
        ob_error("%s", err.msg);
        ob_curveset_free(&set);
        return 2;
    }
    if (rn > 0) {
        size_t k = strlen(where);
        snprintf(where + k, sizeof where - k, "%srandom %ld:%" PRIu64, k ? " + " : "", rn, seed);
        /* a random id must not repeat one from the file */
        char id[64];
        for (int i = 0; i < set.n; i++) {
            const char *p = set.v[i].id;
            char pre[32];
            int plen = snprintf(pre, sizeof pre, "rnd%" PRIu64 "_", seed);
            if (strncmp(p, pre, (size_t)plen) != 0)
                continue;
            long idx = strtol(p + plen, NULL, 10);
            ob_random_id(seed, idx, id, sizeof id);
            if (idx >= 0 && idx < rn && strcmp(id, p) == 0) {
                ob_error("--random: curve id '%s' is also defined at %s:%d", p, set.v[i].file, set.v[i].line);
                ob_curveset_free(&set);
                return 2;
            }
        }
    }
    print_curve_header(where);
    for (int i = 0; i < set.n; i++)
        print_curve(&set.v[i]);
    ob_curveset_free(&set);
    for (long i = 0; i < rn; i++) {
        ob_curve c;
        if (ob_random_curve(seed, i, &c) != 0) {
            ob_error("--random: out of memory");
            return 1;
        }
        print_curve(&c);
        ob_curve_free(&c);
    }
    return fflush(stdout) == 0 ? 0 : 1;
}

/* list SUBJECT [its options]: the subject is list's operand, so "list --
 * SUBJECT ..." is "list SUBJECT -- ...": what follows is all operands, which
 * the subject's parser refuses (a subject takes none). */
int ob_cmd_list(int argc, char **argv)
{
    if (argc > 2 && strcmp(argv[1], "--") == 0) {
        argv[1] = argv[2];
        argv[2] = (char *)"--";
    }
    if (argc < 2 || strcmp(argv[1], "--") == 0) {
        ob_error("list: what? methods, metrics, curves, columns or devices");
        return 2;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        puts("usage: ./offbench list methods|metrics|curves|columns|devices\n"
             "  methods   every method: citation, claimed continuity, parameters with defaults and ranges\n"
             "  metrics   every error metric (--metric) with its definition\n"
             "  curves    the curves a run loads (list curves --help for its options)\n"
             "  columns   the columns of results.csv, in order, with what each holds\n"
             "  devices   the OpenCL devices found");
        return 0;
    }
    /* the parser's messages and help name the command as "list SUBJECT" */
    static const char *const named[][2] = {{"curves", "list curves"},   {"methods", "list methods"},
                                           {"metrics", "list metrics"}, {"columns", "list columns"},
                                           {"devices", "list devices"}};
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
        if (strcmp(argv[1], named[i][0]) == 0)
            argv[1] = (char *)named[i][1];
    if (strcmp(argv[1], "list curves") == 0)
        return list_curves(argc, argv);
    if (strncmp(argv[1], "list ", 5) == 0) {
        const int prc = ob_cli_no_options("(no options)", argc - 1, argv + 1);
        if (prc != OB_CLI_OK)
            return prc == OB_CLI_HELP ? 0 : 2;
        argv[1] += 5;
    }
    if (strcmp(argv[1], "methods") == 0)
        return list_methods();
    if (strcmp(argv[1], "metrics") == 0)
        return list_metrics();
    if (strcmp(argv[1], "columns") == 0)
        return list_columns();
    if (strcmp(argv[1], "devices") == 0) {
        ob_cl_list_devices(stdout);
        printf("# --backend cpu: the C reference path with OpenMP (always available)\n");
        return 0;
    }
    static const char *const subjects[] = {"methods", "metrics", "curves", "columns", "devices"};
    char note[64];
    ob_error("list: unknown subject '%s' (methods, metrics, curves, columns, devices)%s", argv[1],
             ob_suggest_note(argv[1], subjects, (int)(sizeof subjects / sizeof subjects[0]), note, sizeof note));
    return 2;
}
