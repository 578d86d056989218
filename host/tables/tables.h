/*
 * tables.h - the plan of `./offbench tables` and its writers (cmd_tables.c
 * plans and runs, tables_write.c writes).
 */
#ifndef OB_TABLES_H
#define OB_TABLES_H

#include <stdio.h>

#include "host/io/curvefile.h"
#include "host/run/options.h"
#include "host/tables/published.h"
#include "host/tables/tables_protocol.h"

enum { OB_TAB_MAX_PIECES = 32, OB_TAB_MAX_SWEEP = 4096 };

/* One distinct job (cells that need the same run share it). */
typedef struct {
    ob_job job;
    double params[OB_MAX_PARAMS];
    int group;              /* driver options: 2 * single_piece + inflections */
} ob_tab_slot;

/* One published cell under one protocol. */
typedef struct {
    const ob_pub_cell *cell;
    ob_proto proto;
    ob_tab_spec spec;
    double d_run;
    long slot;              /* -1: not run */
    const char *fixed;      /* "no-method" / "no-data" when not run */
} ob_tab_row;

/* One point of the Zhao-Zhou quintic sweep. */
typedef struct {
    const char *piece;      /* C, C1, C2 (cut at 1/2), C1@X, C2@X (cut at X) */
    const char *method;
    ob_proto proto;
    ob_metric metric;
    const char *variant;    /* "" for the protocol's reading, else the parameter set (zhao-rational.weighted=0) */
    double d;
    long slot;
} ob_tab_sweep;

typedef struct {
    ob_tab_slot *slots;
    long nslots, cap_slots;
    ob_tab_row *rows;
    int nrows;
    ob_curve pieces[OB_TAB_MAX_PIECES];   /* seg and d owned */
    double piece_ab[OB_TAB_MAX_PIECES][2];
    int npieces;
    ob_tab_sweep sweep[OB_TAB_MAX_SWEEP];
    int nsweep;
} ob_tab_plan;

/* What the writers need. */
typedef struct {
    const ob_tab_plan *pl;
    const ob_pub_set *pub;
    const char *curves_from;
    const ob_run_opts *o;
    double wall;
} ob_tab_out;

/* Row statuses, in this order. */
enum { OB_TAB_MATCH = 0, OB_TAB_CLOSE, OB_TAB_DIFFERS, OB_TAB_NO_METHOD, OB_TAB_NO_DATA, OB_TAB_NSTATUS };
extern const char *const ob_tab_status_names[OB_TAB_NSTATUS];

/* Purpose: the status of a row and our figure for it.
 * Rules:   counts: equal = match, within 10 % = close, else differs, and a
 *          job that did not end ok (limit, fail, skip) differs; errors:
 *          equal to the published figure at its printed digits = match, within
 *          10 % = close, else differs (a one-piece job may end `limit`: its
 *          error is still the figure); no job: no-method / no-data.
 * Output:  *ours (NAN when there is none), if ours is not NULL. */
int ob_tab_row_status(const ob_tab_plan *pl, const ob_tab_row *r, double *ours);

/* Writers for ob_write_atomically (ctx: ob_tab_out*); 0 or -1. */
int ob_tab_write_csv(FILE *f, void *ctx);
int ob_tab_write_md(FILE *f, void *ctx);
int ob_tab_write_sweep(FILE *f, void *ctx);

#endif
