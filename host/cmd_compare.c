/*
 * cmd_compare.c - ./offbench compare BASE NEW [options]: compare two runs,
 * for nightly regression checks.
 *
 * Inputs.  BASE and NEW are each a results.csv or a run directory DIR
 * (DIR/results.csv); meta.json and samples.csv are taken from the same
 * directory when they exist (readers: results_csv.h, metajson.h).
 *
 * Exit status: 0 no regression; 1 a regression (quality, timing, or a row of
 * BASE missing from NEW); 2 an error (unreadable or missing file, malformed
 * CSV or JSON, missing column, duplicate job, bad option: the message names
 * FILE:LINE or the option); 3 not comparable.
 *
 * Comparability (exit 3; every reason is printed, on stderr and in the
 * report).  When both meta.json exist: samples_per_segment, max_depth,
 * max_segments, inflection_split and seed must be equal (absent on one side
 * counts as different), and so must every method_params.M.* and
 * method_versions.M key of each method M that has rows on both sides (a key
 * on one side only counts as different).  Keys of methods that only one side
 * ran, or neither, are not checked (a note says how many differ); a group
 * missing from one meta.json entirely is not checked (a note says so).
 * From the rows: when both runs have rows and their sets of metrics (or of
 * splits) share no value: "metric differs: hausdorff vs radial".  Without a
 * meta.json on a side, quality and timings are compared and a note says that
 * comparability could not be checked.
 *
 * Timing context: when compiler, cflags, backend, opencl.device,
 * opencl.driver, omp_threads or cpu_model differ, timings are not compared (the report
 * lists the differing values); quality still is.
 *
 * Join: rows are matched on (curve, d, method, metric, split, tol), d and tol
 * as doubles.  A row of BASE missing from NEW is a regression (a lost job); a
 * row only in NEW is reported as new, not a regression.
 *
 * Quality of a joined row (exact rules, first that applies):
 *   1. status changed: ok -> anything else is a regression, anything else ->
 *      ok an improvement, any other change (limit -> fail, skip -> fail,
 *      fail -> limit, ...) a regression;
 *   2. both fail or both skip: nothing to compare;
 *   3. both ok or both limit: more ctrl_points is a regression, fewer an
 *      improvement - ctrl_points decides whenever it changed, so fewer
 *      control points with a larger max_err (which still met the tolerance:
 *      the status is the same) is an improvement;
 *   4. same ctrl_points: max_err > base*(1+rtol)+atol is a regression,
 *      base > new*(1+rtol)+atol an improvement (--err-rtol, --err-atol;
 *      a max_err that becomes nan is a regression, one that stops being nan
 *      an improvement).
 *
 * Timing of a joined row: t = fit_ns + eval_ns (the medians of the
 * repetitions when the run had --reps).  Judged only when timings are
 * compared, the statuses are equal and both t >= --time-floor-ns (shorter
 * jobs are timer noise).  A regression when new/base > 1 + --time-threshold
 * and, when both sides have at least 2 repetitions of the row in
 * samples.csv, the two-sided Mann–Whitney U test (ranktest.h) of the
 * per-repetition t values gives p < --alpha; without those samples the
 * threshold alone decides (the report counts such rows).  An improvement
 * symmetrically (base/new > 1 + threshold, same test).  Note: with 3
 * repetitions per side the smallest exact two-sided p is 0.1, so at least 4
 * per side are needed to reject at 0.05; the report says so when fewer.
 *
 * Per method: geometric means over its joined rows of new/base of
 * ctrl_points (rows where both > 0), of max_err (both finite and > 0) and of
 * t (rows judged for timing).  A method is slower (a regression, exit 1) when
 * its time mean > 1 + threshold and, with repetitions on both sides, the
 * Mann–Whitney test on its per-repetition totals gives p < alpha; a total is
 * the sum of t over the method's rows judged for timing (the rows its time
 * mean covers), for each repetition that all those rows have.  Faster
 * symmetrically (reported, not a regression).
 *
 * Options: --format md|csv (md), --out FILE (stdout; written through
 * FILE.tmp and a rename), --err-rtol R (1e-9), --err-atol A (1e-15),
 * --time-threshold F (0.10), --time-floor-ns N (1e6), --alpha A (0.05),
 * --max-rows N (50 per Markdown table), --no-timing, --method-timing-only
 * (row-level timing changes are listed but only the per-method verdicts
 * count for the exit status: with thousands of rows, a few pass the rank
 * test by chance and a nightly would fail on noise; the per-method totals
 * do not have that multiplicity).  "--opt=value" works too.
 *
 * Markdown report: the two inputs, a verdict line with the counts (joined
 * rows, regressions: quality / timing / missing rows, improvements, new and
 * missing rows, methods slower / faster), the context (comparability, timing
 * context, how timings were judged, notes), then the tables Regressions,
 * Missing rows, Improvements, New rows (each capped at --max-rows, saying how
 * many were left out) and the per-method table (method, joined rows,
 * geometric means of new/base of ctrl_points, max_err and time, p of the
 * method test, row regressions, row improvements, verdict).  When not
 * comparable: the inputs and the reasons only.
 *
 * CSV report (long format, one line per change, header
 * kind,curve,d,method,metric,split,tol,field,base,new,ratio,p_value):
 *   regression|improvement  a row's change: field status, ctrl_points,
 *                           max_err or time (t in ns); base and new values;
 *                           ratio new/base (not for status); p_value when
 *                           the rank test was run.  A method's timing
 *                           verdict: curve, d, metric, split, tol empty,
 *                           field time_gm, ratio the geometric mean.
 *   missing                 a row of BASE not in NEW: field status, base its status
 *   new                     a row only in NEW: field status, new its status
 *   method                  per method: fields ctrl_points_gm, max_err_gm and
 *                           time_gm with the geometric mean in ratio (empty
 *                           when there is none) and, for time_gm, the p-value
 *   context                 field not_comparable, timing_not_compared or
 *                           note; the text in base
 * d and tol are written as in the input file; numbers in full precision.
 * When not comparable only the context lines follow the header.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "compare.h"
#include "diag.h"
#include "numfmt.h"

static const char usage[] =
    "usage: ./offbench compare BASE NEW [--format md|csv] [--out FILE] [--err-rtol R] [--err-atol A]\n"
    "                          [--time-threshold F] [--time-floor-ns N] [--alpha A] [--max-rows N]\n"
    "                          [--no-timing] [--method-timing-only]\n"
    "BASE and NEW: results.csv files or run directories.  Exit 0 no regression, 1 regression,\n"
    "2 error, 3 not comparable.\n";

typedef struct {
    ob_cmp_opts c;
    const char *in[2];
    int csv;
    const char *out;
} cmd_opts;

/* A finite number for option opt in [lo, hi] (lo excluded when open_lo);
 * `what` describes the range for the message. */
static int num_opt(const char *opt, const char *v, double lo, double hi, int open_lo, const char *what, double *out)
{
    double x;
    if (ob_parse_double(v, &x) || x < lo || (open_lo && x == lo) || x > hi) {
        ob_error("%s: expected %s, got '%s'", opt, what, v);
        return -1;
    }
    *out = x;
    return 0;
}

static int parse_opts(int argc, char **argv, cmd_opts *o)
{
    int npos = 0, nseen = 0;
    char seen[16][64];
    o->c = ob_cmp_defaults();
    o->csv = 0;
    o->out = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strncmp(a, "--", 2) != 0) {
            if (npos == 2) {
                ob_error("compare: too many arguments ('%s'): expected BASE NEW", a);
                return -1;
            }
            o->in[npos++] = a;
            continue;
        }
        char name[64];
        const char *v = NULL, *eq = strchr(a, '=');
        snprintf(name, sizeof name, "%.*s", eq ? (int)(eq - a) : (int)strlen(a), a);
        /* each option once: a repeated one is an error, not "the last wins" */
        for (int k = 0; k < nseen; k++)
            if (strcmp(seen[k], name) == 0) {
                ob_error("%s: given twice (give each option once)", name);
                return -1;
            }
        if (nseen < (int)(sizeof seen / sizeof seen[0]))
            snprintf(seen[nseen++], sizeof seen[0], "%s", name);
        if (strcmp(name, "--no-timing") == 0 || strcmp(name, "--method-timing-only") == 0 ||
            strcmp(name, "--help") == 0) {
            if (eq) {
                ob_error("%s takes no value", name);
                return -1;
            }
            if (strcmp(name, "--help") == 0) {
                fputs(usage, stdout);
                return 1;
            }
            if (strcmp(name, "--no-timing") == 0)
                o->c.no_timing = 1;
            else
                o->c.method_timing_only = 1;
            continue;
        }
        static const char *const with_value[] = {"--format", "--out", "--err-rtol", "--err-atol",
                                                 "--time-threshold", "--time-floor-ns", "--alpha", "--max-rows"};
        int known = 0;
        for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; k++)
            known |= strcmp(name, with_value[k]) == 0;
        if (!known) {
            ob_error("compare: unknown option '%s'", name);
            return -1;
        }
        if (eq)
            v = eq + 1;
        else if (i + 1 < argc)
            v = argv[++i];
        else {
            ob_error("%s: missing value", name);
            return -1;
        }
        double x;
        int rc = 0;
        if (strcmp(name, "--format") == 0) {
            if (strcmp(v, "md") != 0 && strcmp(v, "csv") != 0) {
                ob_error("--format: expected md or csv, got '%s'", v);
                return -1;
            }
            o->csv = strcmp(v, "csv") == 0;
        } else if (strcmp(name, "--out") == 0) {
            if (!*v) {
                ob_error("--out: expected a file name");
                return -1;
            }
            o->out = v;
        } else if (strcmp(name, "--err-rtol") == 0) {
            rc = num_opt(name, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.err_rtol);
        } else if (strcmp(name, "--err-atol") == 0) {
            rc = num_opt(name, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.err_atol);
        } else if (strcmp(name, "--time-threshold") == 0) {
            rc = num_opt(name, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.time_threshold);
        } else if (strcmp(name, "--time-floor-ns") == 0) {
            rc = num_opt(name, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.time_floor_ns);
        } else if (strcmp(name, "--alpha") == 0) {
            rc = num_opt(name, v, 0, 1, 1, "a number > 0 and <= 1", &o->c.alpha);
        } else {
            rc = num_opt(name, v, 0, 1e9, 0, "a whole number >= 0", &x);
            if (rc == 0 && x != floor(x)) {
                ob_error("--max-rows: expected a whole number >= 0, got '%s'", v);
                rc = -1;
            }
            o->c.max_rows = rc ? o->c.max_rows : (int)x;
        }
        if (rc)
            return -1;
    }
    if (npos != 2) {
        ob_error("compare: expected BASE NEW (results.csv files or run directories)");
        fputs(usage, stderr);
        return -1;
    }
    return 0;
}

typedef struct {
    const cmd_opts *o;
    const ob_cmp_side *b, *n;
    const ob_cmp_result *r;
} report_ctx;

static int write_report(FILE *f, void *ctx)
{
    const report_ctx *c = ctx;
    return c->o->csv ? ob_cmp_write_csv(f, c->b, c->n, &c->o->c, c->r) : ob_cmp_write_md(f, c->b, c->n, &c->o->c, c->r);
}

/* To stdout, or to --out FILE through FILE.tmp and a rename. */
static int emit(const cmd_opts *o, report_ctx *ctx)
{
    if (!o->out) {
        int rc = write_report(stdout, ctx);
        if (fflush(stdout) != 0 || rc != 0) {
            ob_error("compare: cannot write the report to stdout");
            return -1;
        }
        return 0;
    }
    const char *slash = strrchr(o->out, '/');
    if (slash && !slash[1]) {
        ob_error("--out: '%s' is a directory name, expected a file", o->out);
        return -1;
    }
    char dir[4096];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == o->out ? 1 : (int)(slash - o->out), o->out);
    return ob_write_atomically(dir, slash ? slash + 1 : o->out, write_report, ctx);
}

int ob_cmd_compare(int argc, char **argv)
{
    cmd_opts o;
    int prc = parse_opts(argc, argv, &o);
    if (prc)
        return prc > 0 ? 0 : 2;
    ob_cmp_side b, n;
    ob_cmp_result r;
    memset(&b, 0, sizeof b);
    memset(&n, 0, sizeof n);
    memset(&r, 0, sizeof r);
    char err[1024];
    int status = 2;
    if (ob_cmp_load_side(o.in[0], "BASE", &b, err, sizeof err) ||
        ob_cmp_load_side(o.in[1], "NEW", &n, err, sizeof err) || ob_cmp_context(&b, &n, &o.c, &r, err, sizeof err) ||
        (r.incomparable.n == 0 && ob_cmp_rows(&b, &n, &o.c, &r, err, sizeof err))) {
        ob_error("compare: %s", err);
        goto done;
    }
    for (int i = 0; i < r.incomparable.n; i++)
        ob_error("not comparable: %s", r.incomparable.v[i]);
    const char *const inputs[] = {o.in[0], o.in[1], b.results_path, b.meta_path, b.samples_path,
                                  n.results_path, n.meta_path, n.samples_path};
    if (o.out && ob_check_out_not_input("compare", o.out, 0, inputs, sizeof inputs / sizeof inputs[0]) != 0)
        goto done;  /* status 2 */
    report_ctx ctx = {&o, &b, &n, &r};
    if (emit(&o, &ctx) == 0)
        status = ob_cmp_status(&r);
done:
    ob_cmp_side_free(&b);
    ob_cmp_side_free(&n);
    ob_cmp_result_free(&r);
    return status;
}
