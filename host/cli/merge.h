/*
 * merge.h - the pieces of `./offbench merge` (cmd_merge.c): one shard
 * directory as read, the merged meta.json (merge_meta.c) and the export
 * index of shards that exported into one directory (merge_export.c).
 */
#ifndef OB_MERGE_H
#define OB_MERGE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "host/io/metajson.h"

/* One shard directory, read and checked (cmd_merge.c load_shard). */
typedef struct {
    const char *dir;
    ob_json_flat meta;
    char *meta_text, *res_text, *idx_text, *smp_text;
    size_t meta_len, res_len, idx_len, smp_len;
    char **lines;        /* data lines of results.csv (into res_text) */
    size_t nlines;
    char **slines;       /* data lines of samples.csv, or NULL */
    size_t nslines;
    size_t *idx;         /* job index of each line */
    uint64_t *key;       /* the hash of its job's key (shard.csv "key") */
    int k, n, reps;
} ob_shard_in;

/* Purpose: split text into lines in place (LF or CRLF).
 * Outputs: *hdr the first line, *v (malloc'ed) the others, blank lines
 *          dropped, *n their count.
 * Returns: 0, or -1 out of memory (*v may then need freeing). */
int ob_merge_split_lines(char *text, size_t len, char **hdr, char ***v, size_t *n);

/* Purpose: the merged run's meta.json.  Every top-level key of shard 0's
 *          meta.json, in its order, with: "shard" null, then
 *          "merged_shards" (the count) and "shards" (one object per shard
 *          in K order: "shard", "dir" and its own value of every
 *          per-process key (backend, opencl, cpu_because, cpu_model,
 *          omp_threads, host, engine, warnings, rep_mismatches, jobs,
 *          wall_seconds, export_dir, argv, timestamp) and of every other
 *          key whose value differs between shards); "jobs" the whole run's;
 *          "wall_seconds" the slowest shard's; "rep_mismatches" the sum;
 *          "warnings" every shard's, in K order; any other key whose
 *          value differs between shards is "mixed" (its values: "shards").
 * Inputs:  sh[0..nsh) the shards (any order), total jobs, wall seconds.
 * Returns: 0, or -1 when writing failed or shard 0's meta.json lacks the
 *          keys merge rewrites. */
int ob_merge_write_meta(FILE *f, const ob_shard_in *sh, int nsh, size_t total, double wall);

/* The export index of a merged run (shards that ran with --export). */
typedef struct {
    int active;          /* 1: every shard exported into dir */
    char dir[4200];
    int nshards;
    char **texts;        /* each shard's index file (owned) */
    int ntexts;
    char **rows;         /* the index rows in job order (into texts) */
    size_t nrows;
} ob_merge_export;

/* Purpose: find and check the shards' export indexes: when every shard's
 *          meta.json names one export directory (by device and inode), read
 *          each shard's index.shardK-of-N.csv there and check it row for
 *          row against the shard's results.csv (curve, d, method, tol,
 *          status: an index of another run, or of an earlier export, is
 *          refused); its rows then go into x->rows in job order (who[j]:
 *          the shard of job j, row[j]: its line there).  Shards that did
 *          not export, or exported into different or missing directories,
 *          get a warning and no combined index (x->active 0).
 * Returns: 0; -1 after ob_error() naming the file and line (exit 2). */
int ob_merge_export_load(const ob_shard_in *sh, int nsh, const int *who, const size_t *row, size_t total,
                         ob_merge_export *x);

/* Purpose: write x->dir/index.csv from the checked rows, then remove the
 *          export's names there that it does not list (export_dir.h: files
 *          of earlier runs and of jobs without an approximation; shard
 *          indexes of another shard count).  Nothing without x->active.
 * Returns: 0, or -1 after ob_error() (exit 1). */
int ob_merge_export_write(const ob_merge_export *x);

/* Frees what ob_merge_export_load kept (safe on a zeroed x). */
void ob_merge_export_free(ob_merge_export *x);

#endif
