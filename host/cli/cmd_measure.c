/*
 * cmd_measure.c - `offbench measure --curve ID --d D --approx FILE
 * [--curves FILE] [--metric M|all] [--samples S]`: the error of an
 * approximation someone else made (a .curves file, the JSON of --export, or
 * DXF SPLINE entities) against the exact d-offset of a base curve, under
 * every metric that applies or the one asked, with the run's engine
 * (host/measure/measure.h).  Writes a small CSV to standard output:
 *   metric,status,max_err,piece,seg,t,message
 * status `ok`, or `n/a` with the reason (bound and radial need pieces in
 * the base's parameter: files exported from methods that keep it).
 * A file that names the job that exported it (approx.h: have_job) and is
 * measured against another curve or d gets a warning on stderr: its error
 * is then not that job's max_err.
 * Exit status: 0; 2 bad input (an option, the file, an unknown curve), with
 * a message naming the option or FILE:LINE; 1 standard output not writable.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/run/plan.h"
#include "host/diag.h"
#include "host/io/approx_read.h"
#include "host/io/numfmt.h"
#include "host/measure/measure.h"

typedef struct {
    const char *approx;
    int have_d, all;
    double d;
    ob_metric metric;
} measure_args;

enum { MO_APPROX, MO_D, MO_METRIC };

static const ob_flag measure_flags[] = {
    {"approx", "FILE", "the approximation: a .curves file, --export's JSON, or DXF SPLINE entities", MO_APPROX,
     OB_FLAG_ONCE},
    {"d", "D", "the signed offset distance it approximates", MO_D, OB_FLAG_ONCE},
    {"metric", "M|all", "bound, radial, normal, hausdorff or all (default: all that apply)", MO_METRIC,
     OB_FLAG_ONCE},
};

static int apply_measure_flag(void *ctx, int id, const char *opt, const char *v)
{
    measure_args *a = ctx;
    switch (id) {
    case MO_APPROX:
        if (!*v) {
            ob_error("%s: empty file name", opt);
            return -1;
        }
        a->approx = v;
        return 0;
    case MO_D:
        if (ob_parse_double(v, &a->d) || a->d == 0.0) {
            ob_error("%s: '%s' is not an offset distance (a nonzero finite number)", opt, v);
            return -1;
        }
        a->have_d = 1;
        return 0;
    default:
        a->all = strcmp(v, "all") == 0;
        if (!a->all && ob_metric_parse(v, &a->metric)) {
            ob_error("%s: unknown metric '%s' (bound, radial, normal, hausdorff, all)", opt, v);
            return -1;
        }
        return 0;
    }
}

/* Parses into a and o; 0, 2 after ob_error(), or -1 after --help. */
static int parse(int argc, char **argv, measure_args *a, ob_run_opts *o)
{
    memset(a, 0, sizeof *a);
    a->all = 1;
    if (ob_run_opts_init(o, argc, argv)) {
        ob_error("measure: out of memory");
        return 2;
    }
    const ob_flagset sets[2] = {
        {measure_flags, (int)(sizeof measure_flags / sizeof measure_flags[0]), NULL, NULL, "options",
         apply_measure_flag, a},
        {ob_run_flags, ob_run_nflags, "curves curve random samples ", NULL, "run options (as for run)",
         ob_run_flag_apply, o},
    };
    const int rc = ob_cli_parse("--curve ID --d D --approx FILE [--curves FILE] [--metric M|all] [--samples S]",
                                sets, 2, argc, argv, 0, NULL, NULL);
    if (rc == OB_CLI_HELP)
        return -1;
    if (rc != OB_CLI_OK)
        return 2;
    const char *miss = o->ncurve_ids == 0 ? "--curve ID" : !a->have_d ? "--d D" : !a->approx ? "--approx FILE" : NULL;
    if (miss) {
        ob_error("measure: %s missing (measure --curve ID --d D --approx FILE)", miss);
        return 2;
    }
    if (o->ncurve_ids != 1) {
        ob_error("--curve: measure takes exactly one curve id");
        return 2;
    }
    return 0;
}

static void put_num(FILE *f, double x)
{
    char b[40];
    ob_fmt_double(b, sizeof b, x);
    fputs(b, f);
}

/* One CSV row. */
static void row(FILE *f, ob_metric m, const ob_mres *r)
{
    fprintf(f, "%s,%s,", ob_metric_name(m), ob_mres_status(r));
    if (r->applies) {
        put_num(f, r->err);
        fprintf(f, ",%d,%d,", r->piece, r->seg);
        put_num(f, r->t);
        fputc(',', f);
        if (!r->ok)
            fprintf(f, "\"%s\"", r->why);
        fputc('\n', f);
    } else {
        fprintf(f, ",,,,\"%s\"\n", r->why);
    }
}

/* Loads, matches and measures; returns the exit status. */
static int measure(const measure_args *a, ob_run_opts *o)
{
    ob_curveset set = {0};
    ob_approx ap = {0};
    char where[4096];
    ob_err err;
    int status = 2;
    if (ob_load_run_curves(o, &set, where, sizeof where) != 0)
        goto out;
    const ob_curve *c = &set.v[ob_curveset_find(&set, o->curve_ids[0])];
    if (ob_check_option_d("measure", c, a->d) != 0)
        goto out;  /* status 2: a d the curve's file would refuse (curvefile.h) */
    if (ob_approx_read(a->approx, &ap, &err) != 0 ||
        ob_approx_match(c, a->d, &ap, a->approx, &err) != 0) {
        ob_error("%s", err.msg);
        goto out;
    }
    if (ap.have_job && (strcmp(ap.job_curve, c->id) != 0 || ap.job_d != a->d))
        ob_warn("measure: %s was exported by a job on curve %s at d = %.17g, and is measured against curve %s at "
                "d = %.17g: its error is not that job's max_err", a->approx, ap.job_curve, ap.job_d, c->id, a->d);
    const int samples = ob_clamp_samples(o->driver.samples);
    ob_mres res[OB_METRIC_COUNT];
    for (int m = 0; m < OB_METRIC_COUNT; m++)
        if ((a->all || (ob_metric)m == a->metric) &&
            ob_approx_measure(c, a->d, &ap, (ob_metric)m, samples, a->approx, &res[m], &err) != 0) {
            ob_error("%s", err.msg);
            goto out;
        }
    fputs("metric,status,max_err,piece,seg,t,message\n", stdout);
    for (int m = 0; m < OB_METRIC_COUNT; m++)
        if (a->all || (ob_metric)m == a->metric)
            row(stdout, (ob_metric)m, &res[m]);
    status = fflush(stdout) != 0 || ferror(stdout) ? 1 : 0;
    if (status)
        ob_error("measure: writing standard output failed");
    else
        ob_info("measure: %d pieces of %s against %s (%s), d = %.17g, %d samples", ap.n, a->approx, c->id, where,
                a->d, samples);
out:
    ob_approx_free(&ap);
    ob_curveset_free(&set);
    return status;
}

int ob_cmd_measure(int argc, char **argv)
{
    measure_args a;
    ob_run_opts o;
    int status = parse(argc, argv, &a, &o);
    if (status == 0)
        status = measure(&a, &o);
    ob_run_opts_free(&o);
    return status < 0 ? 0 : status;
}
