/*
 * approx.c - a job's approximation as pieces (approx.h).
 *
 * Why refit the logged spans rather than keep the driver's fits: the driver
 * keeps, per accepted fit, only its span (seg, a, b) and its two ends
 * (driver.h), so that a run of millions of pieces never holds them all and
 * its timed path is untouched; fits are deterministic (the method contract
 * test checks it, and draw relies on it: host/view/jobview.c), so refitting
 * the span gives the very pieces the run measured.  The refit runs after the
 * results are final and outside every timing.
 */
#include "host/io/approx.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ob_approx_free(ob_approx *a)
{
    if (!a)
        return;
    free(a->v);
    memset(a, 0, sizeof *a);
}

ob_apiece *ob_approx_add(ob_approx *a)
{
    if (a->n == a->cap) {
        const int cap = a->cap ? 2 * a->cap : 16;
        ob_apiece *v = a->cap < (1 << 28) ? realloc(a->v, (size_t)cap * sizeof *v) : NULL;
        if (!v)
            return NULL;
        a->v = v;
        a->cap = cap;
    }
    ob_apiece *p = &a->v[a->n++];
    memset(p, 0, sizeof *p);
    return p;
}

int ob_approx_file_piece(const ob_approx *a, int k)
{
    int n = -1;
    for (int i = 0; i <= k; i++)
        n += a->v[i].part == 0;
    return n;
}

int ob_approx_file_pieces(const ob_approx *a)
{
    return a->n ? ob_approx_file_piece(a, a->n - 1) + 1 : 0;
}

void ob_approx_note_skip(ob_approx *a, const char *type, int line)
{
    ob_approx_note_skip_why(a, type, NULL, line);
}

void ob_approx_note_skip_why(ob_approx *a, const char *type, const char *why, int line)
{
    if (a->nskipped < OB_APPROX_NOTES) {
        ob_anote *o = &a->notes[a->nskipped];
        snprintf(o->type, sizeof o->type, "%s", type);
        snprintf(o->why, sizeof o->why, "%s", why ? why : "not a curve measure reads");
        o->line = line;
    }
    a->nskipped++;
    for (int i = 0; i < a->nskipped_types; i++)
        if (strncmp(a->skipped[i].type, type, sizeof a->skipped[i].type - 1) == 0) {
            a->skipped[i].count++;
            return;
        }
    if (a->nskipped_types < OB_APPROX_SKIP_TYPES) {
        ob_askip *k = &a->skipped[a->nskipped_types];
        snprintf(k->type, sizeof k->type, "%s", type);
        k->count = 1;
        k->line = line;
        a->nskipped_types++;
    }
}

/* x + (y - x) u, exactly x at u = 0 and y at u = 1. */
static double lerp_ends(double x, double y, double u)
{
    return u == 0.0 ? x : u == 1.0 ? y : x + (y - x) * u;
}

double ob_apiece_base_t(const ob_apiece *p, double s)
{
    return lerp_ends(p->a, p->b, lerp_ends(p->t0, p->t1, s));
}

int ob_apiece_base(const ob_curve *c, const ob_apiece *p, ob_bez *base)
{
    if (!p->has_base || p->seg < 0 || p->seg >= c->nseg)
        return -1;
    if (!(0.0 <= p->a && p->a < p->b && p->b <= 1.0 && 0.0 <= p->t0 && p->t0 < p->t1 && p->t1 <= 1.0))
        return -1;
    ob_bez sub;
    ob_bez_subsegment(&c->seg[p->seg], p->a, p->b, &sub);
    ob_bez_subsegment(&sub, p->t0, p->t1, base);
    return 0;
}

/* Refits span sp of job j and appends its pieces; adds them to *segs.
 * Returns 0 or -1 (reason in err). */
static int refit_span(const ob_job *j, const ob_span *sp, void *work, ob_approx *out, int *segs, ob_err *err)
{
    ob_bez sub;
    ob_fit fit;
    char msg[160] = "";
    ob_bez_subsegment(&j->curve->seg[sp->seg], sp->a, sp->b, &sub);
    const ob_fit_args args = {j->d, j->tol, j->params};
    const ob_fit_status st = j->method->fit(&sub, &args, work, &fit, msg, sizeof msg);
    if (st != OB_FIT_OK || fit.n < 1 || fit.n > OB_MAX_PIECES) {
        ob_fail(err, "refitting the accepted piece [%.17g, %.17g] of segment %d failed (%s)", sp->a, sp->b,
                sp->seg, msg[0] ? msg : ob_fit_status_name(st));
        return -1;
    }
    for (int k = 0; k < fit.n; k++) {
        ob_apiece *p = ob_approx_add(out);
        if (!p) {
            ob_fail(err, "out of memory");
            return -1;
        }
        *p = (ob_apiece){1, sp->seg, sp->a, sp->b, fit.t[k], fit.t[k + 1], k == 0, 0, fit.seg[k], 0, 0,
                         "", "", ""};
    }
    *segs += fit.n;
    return 0;
}

int ob_approx_from_job(const ob_job *j, const ob_span_log *log, ob_approx *out, ob_err *err)
{
    if (log->oom) {
        ob_fail(err, "the run could not log the job's pieces (out of memory)");
        return -1;
    }
    void *work = malloc(j->method->work_size ? j->method->work_size : 1);
    if (!work) {
        ob_fail(err, "out of memory");
        return -1;
    }
    out->same_param = (j->method->caps & OB_CAP_SAME_PARAM) != 0;
    int segs = 0, rc = 0;
    for (int i = 0; i < log->n && rc == 0; i++)
        rc = refit_span(j, &log->v[i], work, out, &segs, err);
    free(work);
    if (rc == 0 && segs != j->segments) {
        ob_fail(err, "refitting the accepted pieces gave %d segments, the run %d", segs, j->segments);
        rc = -1;
    }
    return rc;
}

void ob_apiece_names(ob_apiece *dst, const ob_apiece *src)
{
    memcpy(dst->entity, src->entity, sizeof dst->entity);
    memcpy(dst->handle, src->handle, sizeof dst->handle);
    memcpy(dst->id, src->id, sizeof dst->id);
}
