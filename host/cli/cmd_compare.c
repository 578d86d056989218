/*
 * cmd_compare.c - ./offbench compare BASE NEW [options]: compare two runs,
 * for nightly regression checks.
 *
 * Inputs.  BASE and NEW are each a results.csv or a run directory DIR
 * (DIR/results.csv); meta.json, samples.csv and fits.csv are taken from the
 * same directory when they exist (readers: results_csv.h, metajson.h).
 *
 * Exit status: 0 no regression; 1 a regression (quality, timing, or a row of
 * BASE missing from NEW); 2 an error (unreadable or missing file, malformed
 * CSV or JSON, missing column, duplicate job, bad option: the message names
 * FILE:LINE or the option); 3 not comparable (or timings that cannot be
 * judged for too few repetitions, a method whose timing the repetitions
 * cannot decide, or with --strict-timing not judged; a regression found
 * elsewhere still exits 1).
 *
 * Comparability (exit 3; every reason is printed, on stderr and in the
 * report).  When both meta.json exist: samples_per_segment, max_depth,
 * max_segments, inflection_split and seed must be equal (absent on one side
 * counts as different), and so must every method_params.M.* and
 * method_versions.M key of each method M that has rows on both sides (a key
 * on one side only counts as different, but for a method_params key that
 * holds the parameter's default in this build: the other run predates the
 * parameter, which was added with a default that keeps the output; a note
 * says so).  Keys of methods that only one side
 * ran, or neither, are not checked (a note says how many differ); a group
 * missing from one meta.json entirely is not checked (a note says so).
 * From the rows: when both runs have rows and their sets of metrics (or of
 * splits) share no value: "metric differs: hausdorff vs radial".  Without a
 * meta.json on a side, quality and timings are compared and a note says that
 * comparability could not be checked.
 *
 * Timing context (compare_context.c): timings are judged only when both
 * runs have a meta.json, both record a machine (meta.json "machine",
 * hostinfo.h) with the same id, logical cores and memory (within 5 %),
 * compiler, cflags, backend, opencl.device, opencl.driver, omp_threads and
 * cpu_model agree.  Otherwise the report's "Timing:" line says "not
 * judged: baseline from machine 'X' (id ...), this is 'Y' (id ...)" (or
 * which key differs), stderr says it too, and timing adds nothing to the
 * exit status; quality is judged all the same.  A run whose load average
 * (host.loadavg_max) exceeded its cores (host.cores_used) is judged all
 * the same, with a note: the times are thread CPU time and the
 * repetitions' spread decides (issue 46).
 *
 * Join: rows are matched on (curve, d, method, metric, split, tol), d and tol
 * as doubles.  A row of BASE missing from NEW is a regression (a lost job),
 * unless it lies outside what NEW set out to run (NEW's meta.json
 * "selection": its curves and their offsets, random set, methods, metrics,
 * splits, tolerances): then it was left out on purpose (a smaller run), is
 * counted and listed as left out, not a regression (compare_subset.h).
 * Without NEW's meta.json or a selection in it every missing row is a
 * regression, and a note says so.  A row only in NEW is reported as new,
 * not a regression.
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
 *      an improvement);
 *   5. same max_err, both rows certified (run --certify): err_upper <= tol
 *      no longer is a regression, now an improvement (field certified:
 *      base and new each side's err_upper, in Markdown "yes (err_upper X)";
 *      ratio new/base of err_upper).  A certified run against an
 *      uncertified one, or joined rows with a certificate on one side only,
 *      are not compared: a note says so (the exit status is unchanged).
 *
 * Timing of a joined row: when both runs timed their fits (run --time-fits),
 * t = method_ns, the method's own time (its rounds in fits.csv), judged
 * when both rows have it; else t = fit_ns + eval_ns (the medians of the
 * repetitions when the run had --reps; samples.csv), judged when both
 * t >= --time-floor-ns (shorter jobs are timer noise), and a note says
 * so.  Judged only when timings are judged (above) and the statuses are
 * equal.  With at least 2 repetitions of the row on both sides the ratio new/base is the Hodges-Lehmann estimate
 * of the log times' shift and its interval is that estimate's own Moses
 * interval at level 1 - alpha (hlshift.h: the interval that inverts the
 * Mann-Whitney test of ranktest.h, whose p is reported too), and the
 * verdict (band = 1 + --time-threshold):
 *   - no bounded interval: not judged, few_reps;
 *   - estimate beyond the band (above it, or below 1 / band): slower /
 *     faster when the interval excludes 1 on that side and is no wider
 *     than the change it reports (log(hi / lo) <= |log estimate|), else
 *     noisy: repetitions that spread wider than the change cannot tell it
 *     (for a method: "cannot decide: need N more repetitions per side",
 *     exit 3, N from the interval's width, which shrinks as 1 / sqrt(n));
 *   - estimate within the band: no change when hi / lo <= band^2, else
 *     noisy.
 * Without those samples the ratio of the two times and the threshold alone
 * decide (the report counts such rows).  Slower is a regression, faster an
 * improvement.
 *
 * Too few repetitions: when both runs have repetitions and the smallest
 * two-sided p of the rank test, 2 / C(n + m, n), is not below --alpha (3 + 3
 * at 0.05: 0.1), no change could be significant: timings are not judged and
 * the comparison exits 3 with "too few repetitions to judge timing: need N
 * per side" (N the smallest count per side that can reach alpha) instead
 * of passing what it cannot see.
 *
 * Per method: geometric means over its joined rows of new/base of
 * ctrl_points (rows where both > 0), of max_err (both finite and > 0) and of
 * t (rows judged for timing; informational).  Its timing is one claim from
 * one statistic: its total, the sum of t over its rows judged for timing,
 * for each repetition that all those rows have; with at least 2 such
 * totals per side, the HL estimate of new/base with its own interval and
 * the verdict as for a row (p: the rank test on the totals); without, the
 * ratio of the summed times and the threshold.  Slower is a regression
 * (exit 1), faster an improvement.
 *
 * The harness: eval_ns (offbench's measuring) summed over every row judged,
 * per repetition, judged as a method is (its own line in every format); a
 * regression only when both runs measured on the CPU backend (thread CPU
 * time), else reported only (a batch backend's eval_ns is wall time).
 *
 * --strict-timing: timings that could not be judged make the exit status 3
 * (timings not judged for the machine or context, rows judged by the
 * threshold alone for want of repetitions, rows not judged, methods not
 * judged; with --method-timing-only only the methods), the report lists
 * each reason.
 *
 * Options: --format md|csv|json (md), --out FILE (stdout; written through
 * FILE.tmp and a rename), --err-rtol R (1e-9), --err-atol A (1e-15),
 * --time-threshold F (0.10), --time-floor-ns N (1e6), --alpha A (0.05),
 * --max-rows N (50 per Markdown table), --no-timing, --method-timing-only
 * (row-level timing changes are listed but only the per-method verdicts
 * count for the exit status: with thousands of rows, a few pass the rank
 * test by chance and a nightly would fail on noise; the per-method totals
 * do not have that multiplicity), --strict-timing (not with --no-timing),
 * --timing-only (timings alone: quality changes, missing and new rows are
 * not judged; not with --no-timing), --methods LIST (only these methods'
 * rows on both sides; a name neither run has is an error).  "--opt=value"
 * works too.
 *
 * Markdown report, the verdict first: the verdict line with the counts
 * (joined rows, regressions: quality / timing / missing rows, improvements,
 * new and missing rows, methods slower / faster), the "Timing:" line
 * (judged on the same machine, with the per-method counts, or why not),
 * when rows were left out the "Left out:" line (what, how many rows),
 * then the table that decides it, "Verdict by method" (method, joined rows,
 * geometric means of ctrl_points and max_err, row regressions and
 * improvements that count, time base and new, new/base and its interval, p,
 * timing verdict, verdict), the Regressions and Missing rows tables (what
 * counts), the context (the inputs, comparability, how timings were judged,
 * notes), and last, in a collapsed <details> section, what does not count:
 * improvements, new rows, row-level timing changes under
 * --method-timing-only, rows not judged; then, collapsed too, the rows
 * left out.  Each table is capped at
 * --max-rows, saying how many were left out.  When not comparable: the
 * verdict, the inputs and the reasons only.
 *
 * CSV report (long format, one line per change, header
 * kind,curve,d,method,metric,split,tol,field,base,new,ratio,p_value,ci_lo,
 * ci_hi,note; ci_lo, ci_hi the interval of a time ratio, "0" and "inf" when
 * unbounded, empty without; note as below):
 *   regression|improvement  a row's change: field status, ctrl_points,
 *                           max_err, certified (err_upper) or time (t in
 *                           ns); base and new values;
 *                           ratio new/base (not for status; for a time with
 *                           repetitions the HL estimate); p_value when the
 *                           rank test was run.  A method's timing verdict:
 *                           curve, d, metric, split, tol empty, field
 *                           time_total, as its method line below.
 *   missing                 a row of BASE not in NEW: field status, base its status
 *   left_out                a row of BASE outside NEW's selection (not a
 *                           regression): field status, base its status
 *   new                     a row only in NEW: field status, new its status
 *   method                  per method: fields ctrl_points_gm, max_err_gm and
 *                           time_gm with the geometric mean in ratio (empty
 *                           when there is none); where its timing was
 *                           judged, time_total: base and new its time (ns),
 *                           ratio the estimate, p_value, ci_lo and ci_hi
 *                           that estimate's interval, note the verdict
 *                           (slower, faster, same, noisy, few_reps)
 *   not_judged              a row's time not judged: field time, base and
 *                           new, ratio, p_value, interval, note noisy or
 *                           few_reps
 *   context                 field not_comparable, timing_not_compared (why
 *                           timings were not judged; note noisy for a load),
 *                           timing_not_judged (exit 3: too few repetitions,
 *                           or --strict-timing), note, timing (the
 *                           report's "Timing:" line), or left_out (the
 *                           summary of what was left out, when any); the
 *                           text in base
 * d and tol are written as in the input file; numbers in full precision.
 * When not comparable only the context lines follow the header.
 *
 * JSON report (compare_json.c): one object, keys program, status, verdict
 * (ok, regression, not_comparable, timing_not_judged), base and new (results
 * path, rows, meta, git_commit, git_dirty, timestamp, cpu_model, machine,
 * machine_id, repetitions), options, context (checked, timing_compared,
 * timing (the "Timing:" line), interval, noise_width, and the lists
 * not_comparable, timing_not_compared, timing_not_judged, notes), counts,
 * left_out (rows: how many, summary: the "Left out:" line, selection: what
 * NEW set out to run; null without), changes (the CSV's change lines as
 * objects: d and tol as numbers, base and
 * new typed, null for none) and methods (with time_base_ns, time_new_ns,
 * time_estimate, ci_lo, ci_hi, p_value and timing, the verdict); numbers
 * that are not finite are null.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/fsutil.h"
#include "host/cli/commands.h"
#include "host/compare/compare.h"
#include "host/cli/cliopts.h"
#include "host/diag.h"
#include "host/io/numfmt.h"


typedef struct {
    ob_cmp_opts c;
    const char *in[2];
    int format;  /* 0 md, 1 csv, 2 json */
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

enum { CO_FORMAT, CO_OUT, CO_ERR_RTOL, CO_ERR_ATOL, CO_TIME_THRESHOLD, CO_TIME_FLOOR, CO_ALPHA, CO_MAX_ROWS,
       CO_NO_TIMING, CO_METHOD_TIMING, CO_STRICT_TIMING, CO_TIMING_ONLY, CO_METHODS };

static const ob_flag compare_flags[] = {
    {"format", "md|csv|json", "the report's format (default md)", CO_FORMAT, OB_FLAG_ONCE},
    {"out", "FILE", "write the report there (default: standard output)", CO_OUT, OB_FLAG_ONCE},
    {"err-rtol", "R", "max_err may grow by this factor before it is a regression", CO_ERR_RTOL, OB_FLAG_ONCE},
    {"err-atol", "A", "... or by this much", CO_ERR_ATOL, OB_FLAG_ONCE},
    {"time-threshold", "F", "a timing ratio past 1 + F is slower", CO_TIME_THRESHOLD, OB_FLAG_ONCE},
    {"time-floor-ns", "N", "timings below N ns are not judged", CO_TIME_FLOOR, OB_FLAG_ONCE},
    {"alpha", "A", "significance level of the rank test", CO_ALPHA, OB_FLAG_ONCE},
    {"max-rows", "N", "rows of each table in the report", CO_MAX_ROWS, OB_FLAG_ONCE},
    {"no-timing", NULL, "judge the results only", CO_NO_TIMING, OB_FLAG_ONCE},
    {"method-timing-only", NULL, "judge timing per method only, not per job", CO_METHOD_TIMING, OB_FLAG_ONCE},
    {"strict-timing", NULL, "exit 3 when timings could not be judged (no repetitions, too noisy)", CO_STRICT_TIMING,
     OB_FLAG_ONCE},
    {"timing-only", NULL, "judge the timings only (quality, missing and new rows not judged)", CO_TIMING_ONLY,
     OB_FLAG_ONCE},
    {"methods", "LIST", "compare only these methods' rows (comma separated)", CO_METHODS, OB_FLAG_ONCE},
};

static int apply_compare_flag(void *ctx, int id, const char *opt, const char *v)
{
    cmd_opts *o = ctx;
    double x;
    switch (id) {
    case CO_FORMAT:
        if (strcmp(v, "md") != 0 && strcmp(v, "csv") != 0 && strcmp(v, "json") != 0) {
            ob_error("--format: expected md, csv or json, got '%s'", v);
            return -1;
        }
        o->format = strcmp(v, "csv") == 0 ? 1 : strcmp(v, "json") == 0 ? 2 : 0;
        return 0;
    case CO_OUT:
        if (!*v) {
            ob_error("--out: expected a file name");
            return -1;
        }
        o->out = v;
        return 0;
    case CO_ERR_RTOL: return num_opt(opt, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.err_rtol);
    case CO_ERR_ATOL: return num_opt(opt, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.err_atol);
    case CO_TIME_THRESHOLD: return num_opt(opt, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.time_threshold);
    case CO_TIME_FLOOR: return num_opt(opt, v, 0, HUGE_VAL, 0, "a number >= 0", &o->c.time_floor_ns);
    case CO_ALPHA: return num_opt(opt, v, 0, 1, 1, "a number > 0 and <= 1", &o->c.alpha);
    case CO_MAX_ROWS:
        if (num_opt(opt, v, 0, 1e9, 0, "a whole number >= 0", &x) || x != floor(x)) {
            ob_error("--max-rows: expected a whole number >= 0, got '%s'", v);
            return -1;
        }
        o->c.max_rows = (int)x;
        return 0;
    case CO_NO_TIMING: o->c.no_timing = 1; return 0;
    case CO_STRICT_TIMING: o->c.strict_timing = 1; return 0;
    case CO_TIMING_ONLY: o->c.timing_only = 1; return 0;
    case CO_METHODS:
        if (!*v || strspn(v, ",") || strstr(v, ",,") || v[strlen(v) - 1] == ',') {
            ob_error("--methods: expected method names separated by commas, got '%s'", v);
            return -1;
        }
        o->c.methods = v;
        return 0;
    default: o->c.method_timing_only = 1; return 0;
    }
}

/* Returns 0, 1 after printing the help (--help), or -1 after ob_error(). */
static int parse_opts(int argc, char **argv, cmd_opts *o)
{
    o->c = ob_cmp_defaults();
    o->format = 0;
    o->out = NULL;
    const ob_flagset flags = {compare_flags, (int)(sizeof compare_flags / sizeof compare_flags[0]), NULL, NULL,
                              "options", apply_compare_flag, o};
    char *pos[2];
    int npos = 0;
    const int rc = ob_cli_parse("BASE NEW [options]   (results.csv files or run directories; exit 0 no regression, "
                                "1 regression, 2 error, 3 not comparable)",
                                &flags, 1, argc, argv, 2, pos, &npos);
    if (rc != OB_CLI_OK)
        return rc == OB_CLI_HELP ? 1 : -1;
    if (npos != 2) {
        ob_error("compare: expected BASE NEW (results.csv files or run directories)");
        return -1;
    }
    if (o->c.strict_timing && o->c.no_timing) {
        ob_error("compare: --strict-timing asks for timings to be judged, --no-timing for them not to be: pick one");
        return -1;
    }
    if (o->c.timing_only && o->c.no_timing) {
        ob_error("compare: --timing-only judges the timings alone, --no-timing no timings: pick one");
        return -1;
    }
    o->in[0] = pos[0];
    o->in[1] = pos[1];
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
    if (c->o->format == 2)
        return ob_cmp_write_json(f, c->b, c->n, &c->o->c, c->r);
    return c->o->format ? ob_cmp_write_csv(f, c->b, c->n, &c->o->c, c->r) : ob_cmp_write_md(f, c->b, c->n, &c->o->c, c->r);
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
    ob_err err;
    int status = 2;
    if (ob_cmp_load_side(o.in[0], "BASE", &b, &err) || ob_cmp_load_side(o.in[1], "NEW", &n, &err) ||
        ob_cmp_check_methods(&b, &n, &o.c, &err) || ob_cmp_context(&b, &n, &o.c, &r, &err) ||
        (r.incomparable.n == 0 && ob_cmp_rows(&b, &n, &o.c, &r, &err))) {
        ob_error("compare: %s", err.msg);
        goto done;
    }
    for (int i = 0; i < r.incomparable.n; i++)
        ob_error("not comparable: %s", r.incomparable.v[i]);
    for (int i = 0; i < r.strict.n; i++)
        ob_error("timing not judged%s: %s", o.c.strict_timing ? " (--strict-timing)" : "", r.strict.v[i]);
    if (!r.incomparable.n && (r.tstate == OB_TIMING_MACHINE || r.tstate == OB_TIMING_NOISY)) {
        char timing[2048];  /* what the report's "Timing:" line says, for the log */
        ob_cmp_timing_text(&b, &n, &o.c, &r, 0, timing, sizeof timing);
        ob_warn("timings %s", timing);
    }
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
