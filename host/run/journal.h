/*
 * journal.h - rows saved as jobs finish, and resuming an interrupted run.
 *
 * While `run` works, DIR/results.journal.csv holds every finished job's row
 * in the order jobs finish: a first line "#offbench-journal 1 FINGERPRINT"
 * (the options that decide the results), the results.csv header, then whole
 * rows, each flushed as it is written and synced to disk at least once a
 * second.  A kill at any moment leaves at most one partial last line, which a
 * resume cuts off.  When the run ends, results.csv is written in job order
 * (through a temporary file and a rename) and the journal removed.
 *
 * `run --resume DIR` takes the finished rows from DIR's journal (or, when the
 * run had finished, from DIR/results.csv, checked against the fingerprint
 * the run left in DIR/results.fingerprint), runs only the other jobs, and
 * writes the same results.csv an uninterrupted run writes (timing columns
 * aside: a restored row keeps its own timings).
 */
#ifndef OB_JOURNAL_H
#define OB_JOURNAL_H

#include <stdio.h>

#include "methods/driver/driver.h"
#include "host/run/options.h"
#include "host/run/record.h"
#include "host/io/results_csv.h"
#include "methods/core/err.h"

typedef struct {
    FILE *f;
    char path[4200];
    double last_sync;   /* monotonic seconds of the last fsync */
    int from_results;   /* resumed from results.csv: the restored rows are
                           not in the journal yet (the caller adds them) */
} ob_journal;

/* Purpose: the options that decide a run's results, as one line of text
 *          (samples, limits, inflections, job timeout, every method
 *          parameter, the data source and its content hash); malloc'd, NULL
 *          without memory. */
char *ob_run_fingerprint(const ob_run_opts *o, const char *where, uint64_t data_hash);

/* Purpose: everything that decides a resumed run's results and job set, as
 *          one line of " key=value" tokens (values %-escaped): the options
 *          of ob_run_fingerprint, the selected curves' content hash
 *          (rec->data_hash), --curve, --methods, --tols, --metric, --split,
 *          --shard, the build (git commit, dirty flag, compiler flags) and
 *          the versions of the run's methods.  Kept in the journal's first
 *          line and, once the run has finished, in DIR/results.fingerprint.
 *          malloc'd; NULL without memory. */
char *ob_resume_fingerprint(const ob_run_opts *o, const ob_run_record *rec, const char *where);

/* Purpose: 0 when fingerprints was and now agree; else 1 with the first
 *          difference in out, named as the user knows it ("--samples differs
 *          (the run's 8, now 256)"), its values as written ("random 250:2026",
 *          not %-escaped). */
int ob_fingerprint_diff(const char *was, const char *now, char *out, size_t len);

/* Purpose: the value of key in fingerprint fp as the user wrote it (the
 *          %-escapes undone), malloc'd; NULL when fp has no such key (or
 *          without memory). */
char *ob_fp_get(const char *fp, const char *key);

/* Purpose: the fingerprint that the run in dir left, for `run --resume DIR`
 *          to take the run's own options from: its journal's first line (an
 *          interrupted run) or results.fingerprint (a finished one), as
 *          written (%-escaped); malloc'd, the file it came from in path.
 *          NULL when dir holds neither, or a journal without a whole first
 *          line (*journal_there says whether a journal is there). */
char *ob_stored_fingerprint(const char *dir, char *path, size_t plen, int *journal_there);

/* Purpose: start the journal of a run in dir.  Fresh (resume 0): create it
 *          (replacing an old one).  resume 1: read dir's journal (its
 *          fingerprint must equal fp) or, without one, dir/results.csv
 *          (dir/results.fingerprint, written by the finished run, must equal
 *          fp: a finished run without it is refused);
 *          their rows go to *restored (empty when there is nothing); then
 *          continue the journal (a partial last line cut off) or start one
 *          holding the restored rows' text.
 * Errors:  returns 0; -1 with the reason in err->msg (naming the file and line):
 *          unreadable or malformed files, another fingerprint (err names
 *          the first difference, ob_fingerprint_diff), a journal with other columns or a
 *          results.csv without the joint columns (another build), no
 *          previous run to resume, cannot write.
 *          *j and *restored are always safe to pass to the free functions. */
int ob_journal_open(ob_journal *j, const char *dir, const char *fp, int resume, ob_res_table *restored, ob_err *err);

/* Purpose: append a finished job's row (flushed; synced when a second has
 *          passed since the last sync).  Returns 0 or -1 (write error). */
int ob_journal_add(ob_journal *j, const ob_job *job);

/* Purpose: sync and close; remove the file too when `remove_it`.  Always safe. */
void ob_journal_close(ob_journal *j, int remove_it);

/* Purpose: give job the results of row (status, counts, error, timings,
 *          message, joints).  Returns 0, or -1 when the row's status is unknown. */
int ob_job_from_row(ob_job *job, const ob_res_row *row);

#endif
