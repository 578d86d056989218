/*
 * tables_protocol.h - how `./offbench tables` measures each published cell.
 *
 * Three protocols per cell (issue 5):
 *   paper     the paper's own error measure, split rule and counting, as far
 *             as the papers' text establishes it (the evidence is in tables_protocol.c
 *             and in the README);
 *   rigorous  the two-sided Hausdorff metric, dense, midpoint split, for every
 *             method alike;
 *   best      the rigorous metric with the greedy split: the fewest segments
 *             each method can reach.
 * Error tables (unit max_err: Zhao-Zhou Table 1 and the septic's figures from
 * its text) fit one piece without subdivision and report its error; there the
 * split rule is moot and `best` equals `rigorous`.
 */
#ifndef OB_TABLES_PROTOCOL_H
#define OB_TABLES_PROTOCOL_H

#include "methods/driver/driver.h"
#include "host/tables/published.h"
#include "methods/core/err.h"

typedef enum { OB_PROTO_PAPER = 0, OB_PROTO_RIGOROUS, OB_PROTO_BEST, OB_PROTO_COUNT } ob_proto;
const char *ob_proto_name(ob_proto p);

enum { OB_TAB_MAX_SET = 4 };

/* What to run for one published cell under one protocol. */
typedef struct {
    const ob_method *method;  /* NULL: a method offbench does not have */
    char curve[64];           /* the curve id to load (the part after '/' selects a piece) */
    double piece_a, piece_b;  /* the part of the curve's single segment to use ([0,1]: all) */
    int single_piece;         /* 1: one fit, no subdivision; report its error */
    double d_factor;          /* d run = d_factor * d (the paper's normal may point right) */
    ob_metric metric;
    ob_split split;
    double tol;               /* the job's tolerance (error tables: what drives the method) */
    int inflections;          /* split at inflections first */
    int nset;                 /* method parameters changed from their defaults */
    const char *set_name[OB_TAB_MAX_SET];
    double set_value[OB_TAB_MAX_SET];
    const char *note;         /* the reading, one line (static text) */
} ob_tab_spec;

/* Purpose: decide how cell c is measured under protocol p.
 * Output:  *s; s->method is NULL when offbench has no such method.
 * Returns: 0; -1 if the cell names a piece or a variant this module does not
 *          know (the message goes to err->msg). */
int ob_tab_resolve(const ob_pub_cell *c, ob_proto p, ob_tab_spec *s, ob_err *err);

#endif
