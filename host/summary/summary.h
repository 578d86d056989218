/*
 * summary.h - the paper table of one run (`./offbench summary RUN_DIR`):
 * the rows of a results.csv pivoted into methods x tolerances.
 *
 * Three tables, each optional (sections):
 *   curves    per (curve, d) and tolerance, each method's control points
 *             for an ok job, else the job's status (limit, fail, skip,
 *             timeout);
 *   families  per family and tolerance, each method's median and quartiles
 *             of the control points over its ok jobs, and the count of its
 *             other (non-ok) jobs;
 *   methods   per method, its jobs by status and the time per job
 *             (fit_ns + eval_ns), median and quartiles over the jobs not
 *             skipped; with certificates (run --certify) also the jobs
 *             certified within tol (certified yes) and not (no), and the
 *             certificate's time per job.
 * Quartiles: linear interpolation between order statistics, Q(p) at the
 * 0-based position (n - 1) p of the sorted values (R's type 7, numpy's
 * default; the same as results.csv's time_iqr_ns).
 *
 * With a baseline (a second run), every cell gets the baseline's value of
 * the same job: rows joined on (curve, d, method, tol), the baseline's own
 * metric and split (so a run under one metric can sit beside one under
 * another), and its family and method statistics over the joined rows.
 *
 * Order: methods as --methods lists them, else in order of first
 * appearance in results.csv (the registry's, for a run); tolerances
 * descending; (curve, d) pairs and families in order of first appearance.
 * The pivot (summary.c) is pure: it reads an ob_res_table and writes
 * nothing; the writers (summary_write.c) print one of three formats.
 */
#ifndef OB_SUMMARY_H
#define OB_SUMMARY_H

#include <stdio.h>

#include "host/compare/compare.h"  /* ob_strlist */
#include "host/io/results_csv.h"
#include "methods/core/err.h"

enum { OB_SUM_OK = 0, OB_SUM_LIMIT, OB_SUM_FAIL, OB_SUM_SKIP, OB_SUM_TIMEOUT, OB_SUM_NSTATUS };

/* The statuses in the order above ("ok", "limit", "fail", "skip", "timeout"). */
extern const char *const ob_sum_status_names[OB_SUM_NSTATUS];

/* The index of status in ob_sum_status_names, or -1. */
int ob_sum_status_index(const char *status);

/* Median and quartiles of n values (all NAN when n is 0). */
typedef struct {
    double median, q1, q3;
    int n;
} ob_sum_quart;

/* Purpose: quantile p (0 <= p <= 1) of sorted[0..n), n >= 1, by linear
 *          interpolation between order statistics (type 7).
 * Returns: the quantile. */
double ob_sum_quantile7(const double *sorted, int n, double p);

/* Purpose: median and quartiles of v[0..n) (n >= 0).
 * Outputs: *q; v is left sorted ascending. */
void ob_sum_quartiles(double *v, int n, ob_sum_quart *q);

/* A comma list of an option (--methods a,b): the values, owned. */
typedef struct {
    char **v;
    int n;
} ob_sum_list;

/* Purpose: split text at commas into l (l->v owned by l).
 * Errors:  returns 0; -1 with "OPT: ..." in err: an empty list, an empty
 *          value ("a,,b", a trailing comma), a value given twice, no memory. */
int ob_sum_list_parse(const char *opt, const char *text, ob_sum_list *l, ob_err *err);

/* Frees l's values; l is then empty.  Safe on a zeroed list, twice. */
void ob_sum_list_free(ob_sum_list *l);

/* Purpose: the family a row counts in: its family column when not empty;
 *          else, for a random curve id (rnd<SEED>_<i>), the random family of
 *          i; else "(none)".
 * Returns: a string that lives as long as the row (or static). */
const char *ob_sum_family(const ob_res_row *r);

/* What to keep of the rows: NULL lists (or empty ones) keep everything. */
typedef struct {
    const ob_sum_list *methods;   /* --methods: these methods, in this order */
    const ob_sum_list *curves;    /* --curves */
    const ob_sum_list *families;  /* --family */
    const char *metric;           /* --metric; NULL: the only one in the rows */
    const char *split;            /* --split; NULL: the only one in the rows */
} ob_sum_filter;

typedef struct {
    const char *curve, *d_text, *family;
    double d;
    int fam;                      /* index into ob_summary.families */
} ob_sum_pair;

/* One method at one tolerance in one family. */
typedef struct {
    ob_sum_quart q;               /* over the ok jobs' ctrl_points (q.n of them) */
    int nonok;                    /* the jobs with another status */
} ob_sum_fcell;

/* One method over every kept job. */
typedef struct {
    int jobs;
    int status[OB_SUM_NSTATUS];   /* jobs by status */
    ob_sum_quart time_ns;         /* fit_ns + eval_ns over the jobs not skipped */
    int cert_yes, cert_no;        /* run --certify: jobs certified within tol, and not */
    ob_sum_quart cert_ns;         /* their cert_ns */
} ob_sum_mstat;

/* The rows of one run in the summary's cells (the run's own, or the
 * baseline's rows joined to them). */
typedef struct {
    const char *name;             /* its results.csv, for the report */
    const char *metric, *split;
    const ob_res_row **cell;      /* [pair][method][tol]; NULL: no such job */
    ob_sum_fcell *fam;            /* [family][method][tol] */
    ob_sum_mstat *meth;           /* [method] */
    int njobs;                    /* cells that hold a row */
} ob_sum_side;

typedef struct {
    const char **methods;         /* column order (strings of the table or the filter) */
    int nm;
    double *tols;                 /* descending */
    const char **tol_text;        /* as the file spells each (its first row) */
    int nt;
    ob_sum_pair *pairs;
    int np;
    const char **families;
    int *fam_pairs;               /* (curve, d) pairs per family */
    int nf;
    int ncurves;
    ob_sum_side run, base;
    int has_base;
    int has_cert;                 /* some job of the run has a certificate (run --certify) */
    /* --archive (summary_archive.c); all zero without one */
    int has_archive;
    int nm_run;                   /* the run's own methods: columns 0 .. nm_run-1 */
    const char **msrc;            /* [method]: the archive's results.csv of the column; NULL: the run's */
    char **mlabel;                /* [method]: "m (archive)", owned; NULL: the run's method */
    char *arch_hit;               /* [pair * nt + tol]: an archive has a row of that job */
    ob_strlist alines;            /* the "Archive:" and "Not joined:" lines, owned */
} ob_summary;

/* The index of cell (pair p, method m, tolerance k) in the side arrays. */
static inline int ob_sum_at(const ob_summary *s, int p, int m, int k) { return (p * s->nm + m) * s->nt + k; }

/* The index of family cell (family f, method m, tolerance k). */
static inline int ob_sum_fat(const ob_summary *s, int f, int m, int k) { return (f * s->nm + m) * s->nt + k; }

/* Purpose: pivot the rows of t (read from `name`) that pass f.
 * Outputs: *s (free with ob_summary_free), pointing into t and f's lists:
 *          both must outlive it.
 * Errors:  returns 0; -1 with a message in err (the caller exits 2):
 *          a value of --methods, --curves or --family no row has ("--methods:
 *          unknown method 'x'" when it is no method of this build, else "no
 *          rows of method 'x' in NAME"), or whose rows the other filters
 *          all leave out, a --metric or --split no row has,
 *          rows of several metrics (or splits) and no --metric (--split) to
 *          choose one, no row left, no memory. */
int ob_summary_build(const ob_res_table *t, const char *name, const ob_sum_filter *f, ob_summary *s, ob_err *err);

/* Purpose: join a baseline run b (read from `name`) to s: s->base gets,
 *          for every cell of s->run, b's row of the same curve, d, method
 *          and tol under b's metric and split (f->metric and f->split when
 *          given, else b's only ones), and the statistics of those rows.
 * Errors:  returns 0; -1 with a message in err: b has no row of that metric
 *          or split, or several and no option to choose, no memory. */
int ob_summary_join(ob_summary *s, const ob_res_table *b, const char *name, const ob_sum_filter *f, ob_err *err);

/* Purpose: put the methods of an archived run a (read from `name`; its
 *          comparability checked by the caller: host/cli/summary_archive.c)
 *          beside the run's, on the run's jobs: a rows of the run's metric
 *          and split and of a method the run lacks fill a new column, marked
 *          "m (archive)", when the run has that (curve, d, tol).  The rows
 *          that cannot join are counted into s->alines by reason (another
 *          metric or split, a job the run did not run, a method the run ran
 *          itself: its values are shown, a job an earlier archive gave).
 *          Call ob_summary_archive_done after the last archive.
 * Errors:  returns 0; -1 with a message in err (no memory, over 64 columns). */
int ob_summary_archive(ob_summary *s, const ob_res_table *a, const char *name, ob_err *err);

/* Purpose: the rows of a on some (curve, d, tol) of the run, whatever their
 *          method, metric or split: 0 means a shares no job with the run. */
int ob_summary_archive_shared(const ob_summary *s, const ob_res_table *a);

/* Purpose: after the last archive: the run's rows no archive has a job of,
 *          counted into s->alines.  Returns 0, -1 when out of memory. */
int ob_summary_archive_done(ob_summary *s);

/* A method column's label: "m (archive)" for an archived one, else m. */
const char *ob_sum_label(const ob_summary *s, int m);

/* Always safe (also twice, or on a zeroed summary). */
void ob_summary_free(ob_summary *s);

/* The tables to write (or'ed). */
enum { OB_SUM_CURVES = 1, OB_SUM_FAMILIES = 2, OB_SUM_METHODS = 4, OB_SUM_ALL = 7 };

/* Purpose: parse --sections' list (curves, families, methods, all).
 * Errors:  returns the bits; -1 with "--sections: ..." in err. */
int ob_sum_sections_parse(const char *text, ob_err *err);

/* Purpose: write the chosen sections of s to f as Markdown (a title,
 *          then each table under a heading with a line saying what its
 *          cells are), as CSV (one long table, header
 *          section,family,curve,d,method,tol,status,value,q1,q3,n,n_nonok,
 *          base_status,base_value,base_q1,base_q3,base_n,ratio; see
 *          README "summary"), or as LaTeX (booktabs tabulars, % comments
 *          for the rest, text escaped).
 * Returns: 0; -1 when a write failed or memory ran out (nothing said). */
int ob_summary_write_md(FILE *f, const ob_summary *s, int sections);
int ob_summary_write_csv(FILE *f, const ob_summary *s, int sections);
int ob_summary_write_latex(FILE *f, const ob_summary *s, int sections);

#endif
