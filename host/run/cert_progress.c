/*
 * cert_progress.c - see cert_progress.h.
 */
#include "host/run/cert_progress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "host/run/clock.h"

double ob_cert_cost(const ob_job *j)
{
    const double per = j->status == OB_LIMIT ? OB_CERT_MS_PER_PIECE_LIMIT : OB_CERT_MS_PER_PIECE;
    return per * (j->segments > 1 ? j->segments : 1);
}

int ob_cert_kind(const ob_job *j)
{
    const int m = j->method ? ob_method_index(j->method) : -1;
    return m < 0 ? -1 : 2 * m + (j->status == OB_LIMIT);
}

int ob_cert_progress_init(ob_cert_progress *p, size_t n, int threads)
{
    memset(p, 0, sizeof *p);
    p->n = n;
    p->threads = threads > 0 ? threads : 1;
    p->g = calloc(n ? n : 1, sizeof *p->g);
    p->start = calloc(n ? n : 1, sizeof *p->start);
    ob_progress_init(&p->bar);
    p->bar.what = "certified";
    p->t0 = ob_mono_s();
    if (!p->g || !p->start) {
        ob_cert_progress_end(p);
        return -1;
    }
    return 0;
}

void ob_cert_progress_set(ob_cert_progress *p, size_t k, const ob_job *j)
{
    p->g[k] = (ob_work_group){ob_cert_cost(j), 0.0, 0.0, OB_WORK_PENDING, ob_cert_kind(j)};
}

void ob_cert_progress_start(ob_cert_progress *p, size_t k, double now)
{
    p->g[k].state = OB_WORK_RUNNING;
    p->start[k] = now;
}

void ob_cert_progress_done(ob_cert_progress *p, size_t k, double cert_ns, double now)
{
    p->g[k].state = OB_WORK_DONE;
    p->g[k].spent_ns = cert_ns;
    p->g[k].wall_ns = 1e9 * (now - p->start[k]);
    p->done++;
    p->done_ns += cert_ns;
    p->done_wall_s += now - p->start[k];
}

void ob_cert_progress_groups(const ob_cert_progress *p, double now, ob_work_group *out)
{
    /* a running job's thread time is not readable from here: its wall time
     * at the speed of the jobs done */
    const double speed = p->done_ns > 0 && p->done_wall_s > 0 ? p->done_ns / (1e9 * p->done_wall_s) : 1.0;
    for (size_t k = 0; k < p->n; k++) {
        out[k] = p->g[k];
        if (out[k].state == OB_WORK_RUNNING) {
            out[k].wall_ns = 1e9 * fmax(0.0, now - p->start[k]);
            out[k].spent_ns = speed * out[k].wall_ns;
        }
    }
}

double ob_cert_progress_now(const ob_cert_progress *p) { return ob_mono_s() - p->t0; }

/* ob_progress_info.groups: the jobs now. */
static void groups_now(const ob_progress_info *pi, ob_work_group *out)
{
    const ob_cert_progress *p = pi->run;
    ob_cert_progress_groups(p, ob_cert_progress_now(p), out);
}

void ob_cert_progress_show(ob_cert_progress *p)
{
    const ob_progress_info pi = {p->done, p->n, p->threads, 1, p->n, groups_now, p};
    ob_progress_cb(&p->bar, &pi);
}

void ob_cert_progress_clear(ob_cert_progress *p)
{
    ob_progress_end(&p->bar);  /* blanks the line; the display's buffers are made again as needed */
}

void ob_cert_progress_end(ob_cert_progress *p)
{
    ob_progress_end(&p->bar);
    free(p->g);
    free(p->start);
    p->g = NULL;
    p->start = NULL;
}
