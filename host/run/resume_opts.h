/*
 * resume_opts.h - `run --resume DIR` with no other option: the run's own
 * options, taken from the fingerprint it left in DIR (journal.h).
 */
#ifndef OB_RESUME_OPTS_H
#define OB_RESUME_OPTS_H

#include "host/run/options.h"

/* Purpose: for `run --resume DIR` (o->resume_dir set, options parsed):
 *          every option that decides the run's results and was not given
 *          on the command line is taken from the run in DIR (its journal's
 *          first line, or results.fingerprint once it finished): the data
 *          source (--curves, --random), --curve, --methods, --tols,
 *          --metric, --split, --samples, --max-depth, --max-segments,
 *          --inflections, --job-timeout, --certify, --shard and every
 *          --param.  An option that was given must be the run's own: one
 *          that differs is refused, naming it with its value as given and
 *          the run's.  How the run goes (--backend, --device, --threads,
 *          --engine, --chunk, --export) is not the run's identity and is
 *          not taken.  DIR without a fingerprint is left to the resume
 *          itself to refuse (nothing to resume, no results.fingerprint),
 *          but for a journal stopped before its first line was whole, with
 *          no option given: its run cannot be known.
 * Returns: 0, or -1 after ob_error() (exit 2). */
int ob_resume_take_options(ob_run_opts *o);

#endif
