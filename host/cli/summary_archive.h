/*
 * summary_archive.h - `summary RUN --archive ARCHIVE`: finding, loading
 * and checking the archived runs before the summary joins them
 * (host/summary/summary.h, ob_summary_archive).
 *
 * ARCHIVE: a run directory, a results.csv, or a directory of run
 * directories (results/baseline-small: each subdirectory holding a
 * results.csv, in name order).  An archived run that shares a job (curve,
 * d, tol) with RUN must be comparable with it by compare's own checks
 * (ob_cmp_context: metric, samples per segment, depth, seed, the method
 * parameters and versions both ran, the kernel text): otherwise the numbers
 * would not mean the same and the summary refuses, naming both files.  One
 * that shares no job is named in the report and left out.
 */
#ifndef OB_SUMMARY_ARCHIVE_CLI_H
#define OB_SUMMARY_ARCHIVE_CLI_H

#include "host/compare/compare.h"
#include "host/summary/summary.h"

/* The loaded runs: their rows back the summary's archived columns, so they
 * outlive it (free them after ob_summary_free). */
typedef struct {
    ob_cmp_side run;
    ob_cmp_side **v;
    int n;
} ob_sum_archives;

/* Purpose: join every ARCHIVE of args to s (built from run_arg's rows).
 * Errors:  returns 0; 2 after ob_error() naming the archive (and the run
 *          for a refusal): a path that is missing, malformed (FILE:LINE), a
 *          directory without runs, given twice, or not comparable. */
int ob_sum_archives_join(ob_summary *s, const char *run_arg, const ob_sum_list *args, ob_sum_archives *a);

/* Always safe (also on a zeroed set). */
void ob_sum_archives_free(ob_sum_archives *a);

#endif
