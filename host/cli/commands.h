/*
 * commands.h - the subcommands of ./offbench.  Each takes the arguments after
 * the program name (argv[0] is the subcommand) and returns the exit status:
 * 0 success, 1 a run-time failure (e.g. output not writable), 2 bad input.
 */
#ifndef OB_COMMANDS_H
#define OB_COMMANDS_H

#include <stdio.h>

#include "host/backend/clrt.h"
#include "host/io/curvefile.h"
#include "host/run/options.h"

int ob_cmd_run(int argc, char **argv, int full_argc, char **full_argv);
int ob_cmd_list(int argc, char **argv);
int ob_cmd_bench(int argc, char **argv);
/* `worker METHOD`: a built-in method served over the external-method
 * protocol on stdin/stdout (cmd_worker.c). */
int ob_cmd_worker(int argc, char **argv);

/* compare BASE NEW: 0 no regression, 1 regression, 2 error, 3 not comparable. */
int ob_cmd_compare(int argc, char **argv);
/* draw: an SVG of one job's approximation; trace: its error along the
 * parameter as CSV.  0, 1 (output not writable) or 2 (bad input). */
int ob_cmd_draw(int argc, char **argv);
int ob_cmd_trace(int argc, char **argv);
/* draw --approx FILE --curve ID --d D --out FILE.svg: a file's pieces
 * coloured by their error (cmd_draw_approx.c; ob_cmd_draw hands it a
 * command line with --approx).  0, 1 or 2 as draw. */
int ob_cmd_draw_approx(int argc, char **argv);

/* measure --curve ID --d D --approx FILE...: an approximation's error (0; 2
 * bad input; 1 output not writable). */
int ob_cmd_measure(int argc, char **argv);

/* merge DIR... --out DIR: shards of one run into its results.csv (0; 2 a
 * refused set or bad input; 1 output not writable). */
int ob_cmd_merge(int argc, char **argv);

/* summary RUN_DIR [options]: the paper table of a run (0; 2 bad input; 1
 * output not writable). */
int ob_cmd_summary(int argc, char **argv);

/* certify RUN_DIR [options]: a finished run certified after the fact
 * (host/run/certify_after.h): 0; 1 a job not certified or a file not
 * written; 2 bad input or a refused directory; 128 + signal when stopped. */
int ob_cmd_certify(int argc, char **argv);

/* atlas [--out DIR]: the Offset Atlas against the exact offset degrees. */
int ob_cmd_atlas(int argc, char **argv);

int ob_cmd_tables(int argc, char **argv, int full_argc, char **full_argv);

#endif
