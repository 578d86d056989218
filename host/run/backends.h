/*
 * backends.h - every backend and device that computed rows of a run, across
 * --resume (issue 48): a run interrupted on one backend and resumed on
 * another has rows of both, and meta.json's "backends" lists them in the
 * order they first computed one ("backend" and "opencl" say the last).
 * Kept in DIR/results.backends, one line a backend ("KIND\tPLATFORM\tDEVICE\t
 * DRIVER"), written whole (temporary file and rename) when a backend
 * computes its first row of the run; a fresh run starts it anew.
 */
#ifndef OB_BACKENDS_H
#define OB_BACKENDS_H

#include <stddef.h>
#include <stdio.h>

#include "host/backend/select.h"

enum { OB_MAX_BACKENDS = 16 };

typedef struct {
    int n;
    char line[OB_MAX_BACKENDS][700];  /* as in the file, without the newline */
} ob_backend_list;

/* Purpose: the run's list so far into l: DIR's file when resuming (absent:
 *          empty), else empty with the file removed (a fresh run).
 * Returns: 0; -1 (the file unreadable: l empty) with the reason in why. */
int ob_backends_load(const char *dir, int resume, ob_backend_list *l, char *why, size_t wlen);

/* Purpose: b computed a row: added to l and the file rewritten, unless l
 *          has it already.  Returns: 0, or -1 with the reason in why. */
int ob_backends_note(const char *dir, const ob_backend_info *b, ob_backend_list *l, char *why, size_t wlen);

/* Purpose: meta.json's value of "backends": l's entries, or cur alone
 *          when l is empty (a run not journaled computed every row). */
void ob_backends_json(FILE *f, const ob_backend_list *l, const ob_backend_info *cur);

#endif
