/*
 * progress.c - see progress.h.  (stub: the estimator to come)
 */
#include "host/run/progress.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int ob_progress_estimate(const ob_progress_in *in, ob_progress_est *e)
{
    (void)in;
    memset(e, 0, sizeof *e);
    e->eta_s = -1.0;
    return 0;
}

void ob_progress_format(char *buf, size_t len, size_t done, size_t total, const ob_progress_est *e, double elapsed_s,
                        int tty)
{
    (void)tty;
    (void)e;
    snprintf(buf, len, "%zu/%zu jobs, %.0f s", done, total, elapsed_s);
}

void ob_progress_init(ob_progress *p) { memset(p, 0, sizeof *p); }
void ob_progress_cb(void *ctx, const ob_progress_info *pi)
{
    (void)ctx;
    (void)pi;
}
void ob_progress_end(ob_progress *p) { free(p->buf); }
