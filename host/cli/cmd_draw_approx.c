/*
 * cmd_draw_approx.c - `./offbench draw --approx FILE [--approx FILE]...
 * --curve ID --d D --out FILE.svg [--curves FILE] [--samples S]`: the
 * picture of a file's approximation against the exact d-offset of a
 * built-in base curve (host/view/draw_approx.h), the same figure as
 * `measure ... --draw FILE.svg` draws: every file matched and checked as
 * measure checks it (ob_measure_approx), each piece coloured by its own
 * hausdorff error (host/measure/perpiece.h).  ob_cmd_draw hands a command
 * line with --approx here.  Exit status: 0; 2 bad input (an option, a file,
 * pieces that do not cover the offset once), naming the option or
 * FILE:LINE; 1 the SVG not writable.
 */
#include <stdlib.h>
#include <string.h>

#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/cli/where_out.h"
#include "host/diag.h"
#include "host/io/approx_read.h"
#include "host/io/numfmt.h"
#include "host/measure/measure.h"
#include "host/run/plan.h"

typedef struct {
    const char **approx;
    int napprox;
    int have_d;
    double d;
    const char *out;
} dargs;

enum { DA_APPROX, DA_D, DA_OUT };

static const ob_flag da_flags[] = {
    {"approx", "FILE", "the approximation (as measure reads it); repeat it to draw several", DA_APPROX,
     OB_FLAG_REPEAT},
    {"d", "D", "the signed offset distance it approximates", DA_D, OB_FLAG_ONCE},
    {"out", "FILE.svg", "the SVG file", DA_OUT, OB_FLAG_ONCE},
};

static int apply(void *ctx, int id, const char *opt, const char *v)
{
    dargs *a = ctx;
    if (id != DA_D && !*v) {
        ob_error("%s: empty file name", opt);
        return -1;
    }
    if (id == DA_OUT) {
        a->out = v;
    } else if (id == DA_D) {
        if (ob_parse_double(v, &a->d) || a->d == 0.0) {
            ob_error("%s: '%s' is not an offset distance (a nonzero finite number)", opt, v);
            return -1;
        }
        a->have_d = 1;
    } else {
        const char **nv = realloc(a->approx, (size_t)(a->napprox + 1) * sizeof *nv);
        if (!nv) {
            ob_error("%s: out of memory", opt);
            return -1;
        }
        a->approx = nv;
        a->approx[a->napprox++] = v;
    }
    return 0;
}

/* 0, 2 after ob_error(), -1 after --help. */
static int parse(int argc, char **argv, dargs *a, ob_run_opts *o)
{
    if (ob_run_opts_init(o, argc, argv)) {
        ob_error("draw: out of memory");
        return 2;
    }
    const ob_flagset sets[2] = {
        {da_flags, (int)(sizeof da_flags / sizeof da_flags[0]), NULL, NULL, "options", apply, a},
        {ob_run_flags, ob_run_nflags, "curves curve random samples ", NULL, "run options (as for run)",
         ob_run_flag_apply, o},
    };
    const int rc = ob_cli_parse("--approx FILE [--approx FILE]... --curve ID --d D --out FILE.svg [--curves FILE] "
                                "[--samples S]", sets, 2, argc, argv, 0, NULL, NULL);
    if (rc == OB_CLI_HELP)
        return -1;
    if (rc != OB_CLI_OK)
        return 2;
    const char *miss = o->ncurve_ids != 1 ? "--curve ID (one)" : !a->have_d ? "--d D" : !a->out ? "--out FILE.svg" : NULL;
    if (miss) {
        ob_error("draw --approx: %s missing (draw --approx FILE --curve ID --d D --out FILE.svg)", miss);
        return 2;
    }
    return 0;
}

/* File name read, matched, checked and its pieces' errors found; 0, or 2
 * after ob_error(). */
static int one_file(const ob_curve *c, double d, int samples, const char *name, ob_approx *ap, ob_perpiece *pp)
{
    ob_err err;
    ob_cover cv = {0};
    ob_measure_out mo;
    ob_measure_ask ask = {{0}, 0, samples};
    ask.want[OB_METRIC_HAUSDORFF] = 1;
    int rc = 2;
    if (ob_approx_read(name, ap, &err) == 0 && ob_measure_approx(c, d, ap, &ask, name, &cv, &mo, &err) == 0 &&
        ob_approx_per_piece(c, d, ap, samples, name, pp, &err) == 0)
        rc = 0;
    if (rc != 0) {
        char buf[1024];
        for (int i = 0; i < cv.nfail; i++) {
            ob_cover_text(&cv.fail[i], ap, name, buf, sizeof buf);
            ob_error("%s", buf);
        }
        ob_error("%s", err.msg);
    }
    ob_cover_free(&cv);
    return rc;
}

/* Loads the curve, reads every file, writes the SVG; the exit status. */
static int draw(const dargs *a, ob_run_opts *o)
{
    ob_curveset set = {0};
    char where[4096];
    const int n = a->napprox;
    ob_approx *aps = calloc((size_t)n, sizeof *aps);
    ob_perpiece *pps = calloc((size_t)n, sizeof *pps);
    ob_pp_file *files = calloc((size_t)n, sizeof *files);
    const char **in = calloc((size_t)n + 1, sizeof *in);
    int status = 2;
    if (!aps || !pps || !files || !in) {
        ob_error("draw: out of memory");
        goto out;
    }
    memcpy(in, a->approx, (size_t)n * sizeof *in);
    in[n] = o->curves_file;
    const ob_where_out wo = {NULL, a->out, "--out"};
    if (ob_where_check("draw", &wo, in, n + 1) != 0 || ob_load_run_curves(o, &set, where, sizeof where) != 0)
        goto out;
    const ob_curve *c = &set.v[ob_curveset_find(&set, o->curve_ids[0])];
    if (ob_check_option_d("draw", c, a->d) != 0)
        goto out;
    const int samples = ob_clamp_samples(o->driver.samples);
    for (int k = 0; k < n; k++) {
        if (one_file(c, a->d, samples, a->approx[k], &aps[k], &pps[k]) != 0)
            goto out;
        files[k] = (ob_pp_file){a->approx[k], &aps[k], &pps[k]};
    }
    status = ob_where_write(&wo, c, a->d, files, n);
out:
    for (int k = 0; aps && pps && k < n; k++) {
        ob_approx_free(&aps[k]);
        ob_perpiece_free(&pps[k]);
    }
    free(aps);
    free(pps);
    free(files);
    free(in);
    ob_curveset_free(&set);
    return status;
}

int ob_cmd_draw_approx(int argc, char **argv)
{
    dargs a = {0};
    ob_run_opts o;
    int status = parse(argc, argv, &a, &o);
    if (status == 0)
        status = draw(&a, &o);
    free(a.approx);
    ob_run_opts_free(&o);
    return status < 0 ? 0 : status;
}
