/*
 * compare.h - the comparison behind `./offbench compare BASE NEW` (see
 * cmd_compare.c for the command line, the exact rules and the report).
 *
 *   ob_cmp_load_side()  a run: results.csv, and meta.json / samples.csv when present
 *   ob_cmp_context()    can the two runs be compared, and their timings?
 *   ob_cmp_rows()       join on the job key; quality, timing and per-method verdicts
 *   ob_cmp_write_md() / ob_cmp_write_csv()   the report
 */
#ifndef OB_COMPARE_H
#define OB_COMPARE_H

#include <stdio.h>

#include "host/io/metajson.h"
#include "host/io/results_csv.h"
#include "methods/core/err.h"

typedef struct {
    double err_rtol, err_atol;   /* max_err changes: beyond base*(1+rtol)+atol */
    double time_threshold;       /* timing changes: ratio beyond 1 + this */
    double time_floor_ns;        /* both times at least this to be judged */
    double alpha;                /* Mann–Whitney significance level */
    int max_rows;                /* rows per report table */
    int no_timing;               /* --no-timing */
    int method_timing_only;      /* --method-timing-only: row-level timing
                                    changes are reported but only per-method
                                    verdicts count for the exit status */
    int strict_timing;           /* --strict-timing: timings that could not be
                                    judged make the comparison exit 3 */
    int timing_only;             /* --timing-only: timings only; quality,
                                    missing and new rows are not judged */
    const char *methods;         /* --methods LIST: only these methods' rows
                                    (comma separated); NULL: every method */
} ob_cmp_opts;

/* The defaults: 1e-9, 1e-15, 0.10, 1e6 ns, 0.05, 50, timings on, not strict. */
ob_cmp_opts ob_cmp_defaults(void);

typedef struct {
    const char *label;             /* "BASE" / "NEW" */
    char results_path[4096], meta_path[4096], samples_path[4096], fits_path[4096];
    ob_res_table res;
    ob_json_flat meta;
    int has_meta, has_samples;
    int has_fits;                  /* fits.csv with rounds (run --time-fits) */
    char samples_note[512];        /* why samples.csv was ignored, or "" */
} ob_cmp_side;

/* Purpose: load one side: arg is a results.csv file or a run directory
 *          (DIR/results.csv); meta.json and samples.csv are taken from the
 *          same directory when they exist.
 * Errors:  returns 0; -1 with the reason in err->msg ("PATH: cannot open: ...",
 *          "FILE:LINE: ...").  *s is always safe for ob_cmp_side_free(). */
int ob_cmp_load_side(const char *arg, const char *label, ob_cmp_side *s, ob_err *err);

void ob_cmp_side_free(ob_cmp_side *s);

typedef struct {
    char **v;
    int n, cap;
} ob_strlist;

/* OB_CH_NOT_JUDGED: a row whose timing was due to be judged but could not
 * be (its interval is unbounded or too wide: ob_cmp_rows); OB_CH_LEFT_OUT:
 * a row of BASE outside NEW's selection, not a regression (compare_subset.h) */
typedef enum { OB_CH_REGRESSION, OB_CH_IMPROVEMENT, OB_CH_NEW, OB_CH_MISSING, OB_CH_NOT_JUDGED,
               OB_CH_LEFT_OUT } ob_ch_kind;

typedef struct {
    ob_ch_kind kind;
    const char *field;              /* status, ctrl_points, max_err, time */
    const ob_res_row *base, *nw;    /* nw NULL: missing; base NULL: new */
    double ratio;                   /* new/base (NAN when meaningless) */
    double p;                       /* Mann–Whitney p, NAN when not tested */
    double ci_lo, ci_hi;            /* time: interval of new/base (hlshift.h), NAN without */
    const char *note;               /* NOT_JUDGED: "noisy" or "few_reps"; else "" */
} ob_change;

/* A method's timing is one claim from one statistic: the estimate t_est of
 * new/base of its time and the interval [ci_lo, ci_hi] of that same
 * estimate.  With repetitions on both sides: the Hodges-Lehmann shift of
 * the log per-repetition totals and its Moses interval (hlshift.h), t_base
 * and t_new the medians of the totals; without: the ratio of the summed
 * times, no interval.  timing, the verdict (compare.c, time_verdict):
 * "slower", "faster", "same", "noisy" (the interval is too wide for the
 * change it would report), "few_reps" (no bounded interval); NULL when
 * timings were not judged or the method has no row to judge. */
typedef struct {
    const char *method;
    int rows;                       /* joined rows */
    int n_cp, n_err, n_t;           /* rows in each geometric mean */
    double gm_cp, gm_err, gm_t;     /* NAN when no row (gm_t: informational) */
    double p;                       /* of the per-repetition totals; NAN: not tested */
    int reps_base, reps_new;        /* totals tested */
    int regressions, improvements;  /* row-level changes of this method that count */
    int verdict;                    /* timing: 1 regression, -1 improvement, 0 neither */
    double ci_lo, ci_hi;            /* interval of t_est; NAN: not tested */
    double t_base, t_new, t_est;    /* the method's time (ns) and new/base; NAN: none */
    const char *timing;             /* the timing verdict (above), or NULL */
    const char *not_judged;         /* why the method's timing was not judged, or NULL */
    int need_reps;                  /* "noisy": repetitions per side that would make
                                       its interval narrow enough to decide (the
                                       width shrinks as 1 / sqrt(n)); 0 otherwise */
} ob_method_sum;

/* A method's verdict as report.md's per-method table and the JSON's
 * "method_verdict" give it: "regression" (a row regression or slower),
 * "improvement" (a row improvement or faster), else "same". */
const char *ob_method_verdict(const ob_method_sum *m);

/* Whether timings were judged, and if not, why (the report's "Timing:"
 * line): OFF --no-timing; MACHINE another or an unknown machine, or another
 * timing context (compiler, flags, device, threads: r->timing_diffs says
 * which); NOISY a side's load average above its cores; FEW_REPS too few
 * repetitions for any change to be significant (exit 3). */
typedef enum { OB_TIMING_JUDGED, OB_TIMING_OFF, OB_TIMING_MACHINE, OB_TIMING_NOISY, OB_TIMING_FEW_REPS } ob_timing_state;

typedef struct {
    ob_strlist incomparable;        /* reasons: exit 3 */
    ob_strlist timing_diffs;        /* why timings were not judged: another
                                       machine, "compiler: A vs B", a load above
                                       the cores (tstate says which kind) */
    ob_timing_state tstate;
    int need_reps;                  /* FEW_REPS: repetitions needed per side */
    ob_strlist notes;               /* everything else the reader should know */
    int checked;                    /* both meta.json present */
    int timing;                     /* timings compared */
    ob_change *ch;
    int nch, capch;
    ob_method_sum *ms;
    int nms;
    int joined, n_new, n_missing;
    int q_reg, q_imp, t_reg, t_imp; /* row-level changes */
    int t_rows_count;               /* row-level timing regressions count for
                                       the exit status (not --method-timing-only) */
    int m_reg, m_imp;               /* method-level timing verdicts */
    int t_judged, t_tested, t_threshold_only;
    int t_noisy, t_few_reps;        /* tested rows not judged: interval too wide / unbounded */
    ob_strlist strict;              /* --strict-timing: what could not be judged (exit 3) */
    /* What is timed: 1 the methods' own time (both runs --time-fits:
     * method_ns and the rounds of fits.csv), 0 fit_ns + eval_ns (a run
     * without it, e.g. an older baseline; r->notes says so). */
    int method_time;
    /* The harness's own line: the measuring (eval_ns) over every row judged
     * for timing, per repetition (samples.csv), judged like a method
     * (method "harness"; NULL timing when not judged). */
    ob_method_sum harness;
    int harness_counts;             /* 1: a slower harness is a regression (both
                                       runs measured on the CPU: thread CPU time);
                                       0: reported only (a batch backend's eval_ns
                                       is wall time, which load inflates) */
    int undecided;                  /* methods whose timing cannot be decided
                                       (noisy): exit 3 */
    int n_left_out;                 /* rows of BASE outside NEW's selection (compare_subset.h) */
    struct ob_cmp_subset *subset;   /* NEW's selection and what it left out (owned) */
} ob_cmp_result;

/* Purpose: the comparability checks (meta.json keys, method parameters and
 *          versions, metric and split sets) and the timing context; fills
 *          r->incomparable, r->timing_diffs, r->notes, r->checked, r->timing.
 * Errors:  returns 0, or -1 with "out of memory" in err->msg. */
int ob_cmp_context(const ob_cmp_side *base, const ob_cmp_side *nw, const ob_cmp_opts *o, ob_cmp_result *r,
                   ob_err *err);

/* Purpose: join the rows and judge them (after ob_cmp_context); fills the
 *          changes (regressions and improvements in BASE order, then new
 *          rows in NEW order), the counts and the per-method summary.
 * Errors:  returns 0, or -1 with "out of memory" in err->msg. */
int ob_cmp_rows(const ob_cmp_side *base, const ob_cmp_side *nw, const ob_cmp_opts *o, ob_cmp_result *r,
                ob_err *err);

/* Exit status of a finished comparison: 3 not comparable (or timings that
 * could not be judged: too few repetitions for any change to be
 * significant, or, with --strict-timing, anything not judged: r->strict),
 * 1 a regression (quality, timing of a row or a method, a missing row),
 * else 0.  Timings not judged for another machine or a busy one add
 * nothing (r->tstate says why). */
int ob_cmp_status(const ob_cmp_result *r);

void ob_cmp_result_free(ob_cmp_result *r);

/* Purpose: write the Markdown / CSV report (formats: cmd_compare.c).
 * Errors:  returns 0, or -1 when the stream reports an error. */
int ob_cmp_write_md(FILE *f, const ob_cmp_side *base, const ob_cmp_side *nw, const ob_cmp_opts *o,
                    const ob_cmp_result *r);
int ob_cmp_write_csv(FILE *f, const ob_cmp_side *base, const ob_cmp_side *nw, const ob_cmp_opts *o,
                     const ob_cmp_result *r);
/* The same content as one JSON document (compare_json.c). */
int ob_cmp_write_json(FILE *f, const ob_cmp_side *base, const ob_cmp_side *nw, const ob_cmp_opts *o,
                      const ob_cmp_result *r);

/* The timing interval's width limit: an estimate within the threshold is
 * "same" only when its interval's hi / lo is at most (1 + time_threshold)^2
 * (no wider than the band of ratios that count as unchanged); wider, it is
 * too noisy to judge. */
double ob_cmp_noise_width(const ob_cmp_opts *o);

/* Purpose: the report's timing line (without "Timing: "), e.g. "judged:
 *          the same machine 'vm' (id ...); per method 1 slower, ..." or
 *          "not judged: baseline from machine 'a' (id ...), this is 'b' (id
 *          ...)"; md: with Markdown emphasis on what was not judged.
 * Outputs: the text in buf (cut to len). */
void ob_cmp_timing_text(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, const ob_cmp_result *r,
                        int md, char *buf, size_t len);

/* A method's (or the harness's) timing verdict in words: "slower",
 * "no change", "cannot decide: need N more repetitions per side", ...
 * ("(threshold only)" added where there were no repetitions); "-" none.
 * Points to static or per-call storage: use before the next call. */
const char *ob_cmp_timing_word(const ob_method_sum *m);

/* 1 when --methods selects method (or there is no --methods). */
int ob_cmp_method_selected(const ob_cmp_opts *o, const char *method);

/* Purpose: check --methods against the runs: every method named must have
 *          rows on a side.
 * Errors:  returns 0; -1 with "--methods: no rows of method 'M' in either
 *          run" in err->msg. */
int ob_cmp_check_methods(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, ob_err *err);

/* Adds a formatted string to l; 0 or -1 (no memory). */
int ob_strlist_addf(ob_strlist *l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void ob_strlist_free(ob_strlist *l);

#endif
