/*
 * progress.h - a progress bar on stderr while a run works: jobs done, rate,
 * ETA.  Drawn only when stderr is a terminal, so logs and pipes stay clean.
 */
#ifndef OB_PROGRESS_H
#define OB_PROGRESS_H

#include <stddef.h>

typedef struct {
    int tty;          /* stderr is a terminal */
    int drawn;        /* something is on the line */
    double t0, last;  /* start, last redraw (s) */
} ob_progress;

void ob_progress_init(ob_progress *p);
/* The driver's progress callback (ctx: an ob_progress*); redraws at most
 * ten times a second. */
void ob_progress_cb(void *ctx, size_t done, size_t total);
/* Clears the bar's line. */
void ob_progress_end(ob_progress *p);

#endif
