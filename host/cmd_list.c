/*
 * cmd_list.c - `./offbench list methods|curves|devices`.
 */
#include <stdio.h>
#include <string.h>

#include "../methods/method.h"
#include "commands.h"
#include "curvefile.h"
#include "datadir.h"
#include "diag.h"
#include "numfmt.h"

/* The output degree as a formula in the input degree n (the methods' degree
 * functions are linear in n: recover a*n + b from two evaluations). */
static void degree_formula(const ob_method *m, char *buf, size_t len)
{
    int a = m->out_degree(4, 0) - m->out_degree(3, 0), b = m->out_degree(3, 0) - 3 * a;
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
        for (int k = 0; k < m->nparams; k++) {
            char num[40];
            ob_fmt_double(num, sizeof num, m->params[k].def);
            printf("%-12s   --param %s.%s=%s (default): %s\n", "", m->name, m->params[k].name, num,
                   m->params[k].doc);
        }
    }
    return 0;
}

static int list_curves(int argc, char **argv)
{
    ob_curveset set = {0};
    char err[1024], where[4096];
    int rc;
    if (argc >= 4 && strcmp(argv[2], "--curves") == 0) {
        snprintf(where, sizeof where, "%s", argv[3]);
        rc = ob_curves_load_file(argv[3], &set, err, sizeof err);
    } else if (argc > 2) {
        ob_error("list curves: unknown option '%s' (use --curves FILE)", argv[2]);
        return 2;
    } else {
        rc = ob_load_default_curves(&set, where, sizeof where, err, sizeof err);
    }
    if (rc != 0) {
        ob_error("%s", err);
        ob_curveset_free(&set);
        return 2;
    }
    printf("# curves from %s\n", where);
    printf("%-20s %-10s %-4s %-6s %-9s %-14s %s\n", "id", "family", "segs", "degree", "rational", "offsets", "source");
    for (int i = 0; i < set.n; i++) {
        const ob_curve *c = &set.v[i];
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
    ob_curveset_free(&set);
    return 0;
}

int ob_cmd_list(int argc, char **argv)
{
    if (argc < 2) {
        ob_error("list: what? methods, curves or devices");
        return 2;
    }
    if (strcmp(argv[1], "methods") == 0)
        return list_methods();
    if (strcmp(argv[1], "curves") == 0)
        return list_curves(argc, argv);
    if (strcmp(argv[1], "devices") == 0) {
        printf("# this build measures on the CPU only; the OpenCL backend is not built in yet\n");
        printf("cpu\tOpenMP, %s\n", "host C reference");
        return 0;
    }
    ob_error("list: unknown subject '%s' (methods, curves, devices)", argv[1]);
    return 2;
}
