/*
 * results_csv.h - reading a run's results.csv (and its samples.csv) back,
 * for `compare`.
 *
 * results.csv: a header naming the columns, then one row per job.  Columns
 * are found by name (any order, extra columns ignored); required:
 * curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,
 * status,fit_ns,eval_ns,message.  Optional: family (written by run; a file
 * without it reads family "" on every row, has_family 0).
 * Optional: max_gap, max_kink, continuity (the joints; files written before
 * they existed have none, and are read all the same: has_joints 0).
 * Optional: err_upper, err_lower, certified, cert_ns (run --certify; all four
 * or none in the header, and on a row all empty or all set, or cert_ns alone:
 * a certificate stopped by --job-timeout).
 * Fields may be quoted ("a, b" with "" for a quote, newlines inside quotes),
 * lines end in LF or CRLF, blank lines are skipped.  A job is identified by
 * its key (curve, d, method, metric, split, tol), d and tol compared as
 * doubles (1e-05 == 0.00001); a key given twice is an error.
 *
 * Optional: fit_calls, method_ns, method_iqr_ns (run --time-fits; all three
 * or none in the header).
 *
 * samples.csv (run --reps N): curve,d,method,metric,split,tol,rep,fit_ns,
 * eval_ns, one row per job and repetition rep = 1..N; every key must be a
 * row of results.csv and every (key, rep) appear once.  fits.csv (run
 * --time-fits) likewise with round,fit_calls,method_ns.
 */
#ifndef OB_RESULTS_CSV_H
#define OB_RESULTS_CSV_H

#include <stddef.h>
#include "methods/core/err.h"

typedef struct {
    /* text fields point into the table's buffer */
    const char *curve, *method, *metric, *split, *status, *message;
    const char *d_text, *tol_text, *max_err_text;
    double d, tol;
    long ctrl_points;
    long segments, out_degree;
    double max_err;          /* NAN when empty or "nan" */
    double fit_ns, eval_ns;
    double max_gap, max_kink;  /* NAN when empty or the column is absent */
    const char *continuity;  /* "" when empty or absent */
    const char *family;      /* "" when empty or the column is absent */
    int cert_done;           /* as ob_job.cert_done: 1 (OB_CERT_DONE), the certificate's
                                columns are set (run --certify); 2 (OB_CERT_TIMEOUT),
                                only cert_ns: stopped by --job-timeout, no verdict */
    double err_upper, err_lower, cert_ns; /* NAN when empty or absent */
    const char *certified;   /* "yes", "no"; "" when empty or absent */
    long fit_calls;          /* run --time-fits: 0 when empty or absent */
    double method_ns, method_iqr_ns; /* NAN when empty or absent */
    int line;                /* first line of the row in the file */
    const double *rep_t;     /* samples.csv: fit_ns + eval_ns of repetition r
                                at rep_t[r - 1], NAN where absent; NULL without */
    int nsamples;            /* repetitions present for this row */
    const double *rep_e;     /* samples.csv: eval_ns of repetition r (the
                                harness's share), as rep_t; NULL without */
    const double *round_m;   /* fits.csv: method_ns of round r at
                                round_m[r - 1], NAN where absent; NULL without */
} ob_res_row;

typedef struct {
    char *text;              /* the file, split in place (owned) */
    ob_res_row *v;           /* rows in file order */
    int n;
    ob_res_row **sorted;     /* the rows ordered by key, for lookups */
    double *rep_t;           /* n x maxrep sample times (owned), or NULL */
    int maxrep;              /* largest rep in samples.csv; 0 without */
    int has_joints;          /* the header has max_gap, max_kink and continuity */
    int has_family;          /* the header has family */
    int has_cert;            /* the header has err_upper, err_lower, certified and cert_ns */
    int has_method_time;     /* the header has fit_calls, method_ns and method_iqr_ns */
    int method_timed;        /* rows with a method time (fit_calls > 0) */
    double *rep_e;           /* n x maxrep eval_ns of samples.csv (owned), or NULL */
    double *round_m;         /* n x maxround method_ns of fits.csv (owned), or NULL */
    int maxround;            /* largest round in fits.csv; 0 without */
} ob_res_table;

/* Purpose: parse the text of a results.csv named `name` (copied: the caller
 *          keeps text).
 * Errors:  returns 0; -1 with "NAME:LINE: reason" in err->msg: no header, a
 *          missing or repeated column, a wrong field count, an unterminated
 *          quote or text after a closing quote, an empty key field, d or tol
 *          not a finite number, ctrl_points not a whole number >= 0, max_err
 *          not a number (empty and nan are accepted) or negative, max_gap or
 *          max_kink likewise, continuity other than empty / open / G0 / G1,
 *          only some of the three joint columns, segments or
 *          out_degree not whole numbers >= 0, fit_ns or
 *          eval_ns not a finite number >= 0, a status other than ok / limit /
 *          fail / skip / timeout, the certificate's columns
 *          not all present or a row's not all set or empty, inconsistent
 *          (err_lower > err_upper, certified not yes exactly when
 *          err_upper <= tol, a certificate on a fail / skip / timeout
 *          row), a duplicate key (naming both lines), no memory.  *t is
 *          always left safe for ob_res_free() (empty after an error). */
int ob_res_parse(const char *text, size_t len, const char *name, ob_res_table *t, ob_err *err);
/* As ob_res_parse, for text that starts on line first_line of the file name
 * (the journal's header is its line 2): messages say NAME:LINE of the file. */
int ob_res_parse_at(const char *text, size_t len, const char *name, int first_line, ob_res_table *t, ob_err *err);

/* Purpose: read and parse the results.csv at path.
 * Errors:  as ob_res_parse, plus "PATH: cannot open: reason". */
int ob_res_load(const char *path, ob_res_table *t, ob_err *err);

/* Purpose: attach the repetitions of a samples.csv (text, named `name`) to
 *          the rows of t: fills t->rep_t, t->maxrep, and each row's rep_t and
 *          nsamples.
 * Errors:  returns 0; -1 with "NAME:LINE: reason" in err->msg (missing column,
 *          malformed field, rep not a whole number in 1..100000, a key that
 *          is not a row of results.csv, a (key, rep) twice, no memory); t then
 *          has no samples, its rows are unchanged. */
int ob_res_attach_samples(ob_res_table *t, const char *text, size_t len, const char *name, ob_err *err);

/* Purpose: as ob_res_attach_samples, reading the file at path. */
int ob_res_load_samples(ob_res_table *t, const char *path, ob_err *err);

/* Purpose: attach the rounds of a fits.csv (run --time-fits) at path:
 *          curve,d,method,metric,split,tol,round,fit_calls,method_ns; fills
 *          t->round_m, t->maxround and each row's round_m.
 * Errors:  as ob_res_attach_samples (round for rep), plus a fit_calls that
 *          is not the row's in results.csv. */
int ob_res_load_fits(ob_res_table *t, const char *path, ob_err *err);

/* Orders two rows by key: curve, d, method, metric, split, tol. */
int ob_res_key_cmp(const ob_res_row *a, const ob_res_row *b);

/* The row of t with the key of `key` (only its key fields are read), or NULL. */
const ob_res_row *ob_res_find(const ob_res_table *t, const ob_res_row *key);

/* Always safe to call (also twice, or on a zeroed table). */
void ob_res_free(ob_res_table *t);

#endif
