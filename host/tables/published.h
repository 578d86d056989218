/*
 * published.h - the published comparison figures (results/published/
 * published_tables.csv, copied from ../shared/ with its sources), the one
 * place `./offbench tables` reads them from.
 *
 * File format: CSV with a header naming at least the columns
 * source,table,curve,d,tol,method,label,value,unit (any order); fields may be
 * quoted ("a, b" with "" for a quote); d and tol may be empty.
 */
#ifndef OB_PUBLISHED_H
#define OB_PUBLISHED_H

#include <stddef.h>
#include "methods/core/err.h"

typedef struct {
    char source[32], table[32], curve[64], method[48], label[64], unit[16];
    char d_text[32], tol_text[32], value_text[32];  /* as published */
    double d, tol, value;                            /* NAN where empty */
    int line;                                        /* in the file */
} ob_pub_cell;

typedef struct {
    ob_pub_cell *v;
    int n;
    char where[512];   /* the file read, or "embedded copy of ..." */
} ob_pub_set;

/* Purpose: parse the text of a published-table file named `name`.
 * Errors:  returns 0; -1 with "NAME:LINE: message" in err->msg for a missing
 *          column, a wrong field count, an unterminated quote, a field too
 *          long, a number that does not parse or is not finite (value, and d
 *          and tol when given), a unit other than ctrl_points / max_err, or
 *          no memory.  *s is left safe to pass to ob_pub_free(). */
int ob_pub_parse(const char *text, size_t len, const char *name, ob_pub_set *s, ob_err *err);

/* Purpose: load the published figures: $OFFBENCH_PUBLISHED (a file), else
 * ./results/published/published_tables.csv, else the same path beside the
 * executable, else the copy compiled into the program.  Errors as above,
 * plus an unreadable file. */
int ob_pub_load(ob_pub_set *s, ob_err *err);

/* Always safe to call (also on a zeroed set). */
void ob_pub_free(ob_pub_set *s);

#endif
