/*
 * jobview.c - one job of draw / trace, its refitted pieces and its pointwise
 * error.  See jobview.h.
 */
#include "host/view/jobview.h"
#include "host/run/plan.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "kernels/metric_core.h"
#include "host/cli/commands.h"
#include "host/diag.h"
#include "host/io/numfmt.h"

int ob_jobview_open(ob_jobview *v, const char *cmd, int have_d, double d)
{
    v->cmd = cmd;
    if (v->o.ncurve_ids != 1) {
        ob_error("--curve: %s needs exactly one curve id", cmd);
        return 2;
    }
    if (v->o.nmethods != 1 || v->o.ntols != 1) {
        ob_error("%s: exactly one --method and one --tol", cmd);
        return 2;
    }
    char where[4096];
    if (ob_load_run_curves(&v->o, &v->set, where, sizeof where) != 0)
        return 2;
    const int c = ob_curveset_find(&v->set, v->o.curve_ids[0]);
    if (c < 0) { /* ob_load_run_curves has checked it; kept for safety */
        ob_error("--curve: no curve '%s'", v->o.curve_ids[0]);
        return 2;
    }
    v->curve = &v->set.v[c];
    if (!have_d) {
        if (v->curve->nd < 1) {
            ob_error("--d: curve '%s' has no offsets of its own; give one", v->curve->id);
            return 2;
        }
        d = v->curve->d[0];
    } else if (ob_check_option_d(cmd, v->curve, d) != 0) {
        return 2;  /* a d the curve's file would refuse (curvefile.h) */
    }
    ob_job *j = &v->job;
    j->curve = v->curve;
    j->d = d;
    j->method = v->o.methods[0];
    j->params = v->o.params + ob_method_index(j->method) * OB_MAX_PARAMS;
    j->metric = v->o.metric;
    j->split = v->o.split;
    j->tol = v->o.tols[0];
    v->samples = ob_clamp_samples(v->o.driver.samples);
    return 0;
}

int ob_jobview_has_approx(const ob_jobview *v)
{
    return v->job.status == OB_OK || v->job.status == OB_LIMIT;
}

/* Refits span i and appends its pieces; adds its segments and control points
 * (counted as the driver counts them) to *segs and *ctrl.  0, or -1 after
 * ob_error(). */
static int refit_span(ob_jobview *v, const ob_span *sp, void *work, int *cap, int *segs, long *ctrl)
{
    const ob_job *j = &v->job;
    ob_bez sub;
    ob_fit fit;
    char msg[160] = "";
    ob_bez_subsegment(&v->curve->seg[sp->seg], sp->a, sp->b, &sub);
    const ob_fit_args args = {j->d, j->tol, j->params};
    const ob_fit_status st = j->method->fit(&sub, &args, work, &fit, msg, sizeof msg);
    if (st != OB_FIT_OK || fit.n < 1 || fit.n > OB_MAX_PIECES) {
        ob_error("%s: refitting the accepted piece [%.6g, %.6g] of segment %d failed (%s): the method did not "
                 "repeat the run's fit",
                 v->cmd, sp->a, sp->b, sp->seg, msg[0] ? msg : ob_fit_status_name(st));
        return -1;
    }
    if (v->npieces + fit.n > *cap) {
        const int nc = 2 * *cap + fit.n + 16;
        ob_jv_piece *np = realloc(v->pieces, (size_t)nc * sizeof *np);
        if (!np) {
            ob_error("%s: out of memory", v->cmd);
            return -1;
        }
        v->pieces = np;
        *cap = nc;
    }
    long add = 0;  /* control points beyond the shared start, as the driver counts them */
    for (int p = 0; p < fit.n; p++) {
        ob_jv_piece *q = &v->pieces[v->npieces++];
        q->seg = sp->seg;
        /* the span's own ends where the pieces meet them, so base parameters
         * join exactly from one span to the next */
        q->ta = p == 0 ? sp->a : sp->a + (sp->b - sp->a) * fit.t[p];
        q->tb = p == fit.n - 1 ? sp->b : sp->a + (sp->b - sp->a) * fit.t[p + 1];
        ob_bez_subsegment(&sub, fit.t[p], fit.t[p + 1], &q->base);  /* as the driver measures */
        q->approx = fit.seg[p];
        q->fit_first = p == 0;
        q->own_count = fit.ctrl_points > 0;
        add += fit.seg[p].deg;
    }
    if (fit.ctrl_points > 0)  /* the method's own representation, e.g. a B-spline */
        add = fit.ctrl_points - 1;
    *ctrl += add;
    *segs += fit.n;
    return 0;
}

int ob_jobview_run(ob_jobview *v)
{
    const int brc = ob_open_backend(v->o.backend, v->o.device, 1u << v->o.metric, &v->binfo, &v->cl);
    if (brc != 0)
        return ob_backend_exit(brc);
    if (v->o.threads > 0)
        omp_set_num_threads(v->o.threads);
    ob_driver_hooks h = {.spans = &v->spans};
    ob_backend_hooks(v->cl, &v->binfo, &h);
    if (ob_driver_run(&v->job, 1, &v->o.driver, &h) != 0 || v->spans.oom) {
        ob_error("%s: out of memory running the job", v->cmd);
        return 1;
    }
    if (!ob_jobview_has_approx(v))
        return 0;
    void *work = malloc(v->job.method->work_size ? v->job.method->work_size : 1);
    if (!work) {
        ob_error("%s: out of memory", v->cmd);
        return 1;
    }
    int cap = 0, segs = 0;
    long ctrl = 1;
    int rc = 0;
    for (int i = 0; i < v->spans.n && rc == 0; i++)
        rc = refit_span(v, &v->spans.v[i], work, &cap, &segs, &ctrl);
    free(work);
    if (rc != 0)
        return 1;
    /* the joints, as the driver counts them (methods/driver/joints.h): an open one
     * inside a fit (unless the fit counts its own representation) or between
     * fits is two points */
    const double gtol = ob_joint_gap_tol(v->curve, v->job.d);
    ob_joint_stats st;
    memset(&st, 0, sizeof st);
    long open = 0;
    for (int p = 1; p < v->npieces; p++) {
        const ob_jv_piece *a = &v->pieces[p - 1], *b = &v->pieces[p];
        ob_end l, r;
        ob_bez_end(&a->approx, 1, &l);
        ob_bez_end(&b->approx, 0, &r);
        if (!b->fit_first) {
            const int o = ob_joint_measure(&st, &l, &r, gtol);
            open += b->own_count ? 0 : o;
        } else {
            open += ob_joint_between(&st, v->curve, gtol, a->seg, &l, b->seg, &r);
        }
    }
    ctrl += open;
    if (segs != v->job.segments || ctrl != v->job.ctrl_points) {
        ob_error("%s: refitting the accepted pieces gave %d segments and %ld control points (%ld open joints), the "
                 "run %d and %ld",
                 v->cmd, segs, ctrl, open, v->job.segments, v->job.ctrl_points);
        return 1;
    }
    return 0;
}

void ob_jobview_close(ob_jobview *v)
{
    ob_cl_close(v->cl);
    v->cl = NULL;
    free(v->spans.v);
    free(v->pieces);
    v->spans.v = NULL;
    v->pieces = NULL;
    v->npieces = 0;
    ob_curveset_free(&v->set);
    ob_run_opts_free(&v->o);
}

void ob_jobview_describe(const ob_jobview *v, char *buf, size_t len)
{
    char d[40], tol[40];
    ob_fmt_double(d, sizeof d, v->job.d);
    ob_fmt_double(tol, sizeof tol, v->job.tol);
    snprintf(buf, len, "%s: %s, d = %s, tol = %s, metric %s, split %s", v->curve->id, v->job.method->name, d, tol,
             ob_metric_name(v->job.metric), ob_split_name(v->job.split));
}

void ob_jobview_summary(const ob_jobview *v, char *buf, size_t len)
{
    char err[40] = "-", gap[40] = "-";
    if (!isnan(v->job.max_err))
        ob_fmt_double(err, sizeof err, v->job.max_err);
    if (!isnan(v->job.max_gap))
        ob_fmt_double(gap, sizeof gap, v->job.max_gap);
    const char *cont = ob_cont_name(v->job.continuity);
    snprintf(buf, len, "status %s, ctrl_points = %ld, segments = %d, max_err = %s, max_gap = %s, continuity = %s",
             ob_status_name(v->job.status), v->job.ctrl_points, v->job.segments, err, gap, cont[0] ? cont : "-");
}

/* ---- pointwise error: the metric core's obc_err_at ------------------------ */

static int err_kind(ob_metric m)
{
    switch (m) {
    case OB_METRIC_NORMAL: return OBC_K_NORMAL;
    case OB_METRIC_HAUSDORFF:
    case OB_METRIC_CERTIFIED: return OBC_K_H_OFFSET; /* the certificate has no pointwise form: hausdorff's */
    default: return OBC_K_RADIAL; /* radial; bound has no pointwise form */
    }
}

int ob_jobview_point_is_approx(const ob_jobview *v) { return err_kind(v->job.metric) == OBC_K_RADIAL; }

size_t ob_jobview_scratch(const ob_jobview *v) { return (size_t)OBC_TABLE_SIZE(v->samples); }

void ob_jobview_prepare(const ob_jobview *v, const ob_jv_piece *p, double *scratch)
{
    if (err_kind(v->job.metric) != OBC_K_H_OFFSET)
        return;
    /* the approximation's sample table, as obc_measure builds it: the
     * offset-to-approximation side starts from its nearest sample */
    long ops = 0;
    obc_fill_table(&p->approx.h[0][0], p->approx.deg, 0.0, v->samples, scratch, &ops);
}

double ob_jobview_err_at(const ob_jobview *v, const ob_jv_piece *p, const double *scratch, double s, double xy[2])
{
    const int kind = err_kind(v->job.metric);
    const double d = v->job.d;
    if (kind == OBC_K_RADIAL)
        ob_bez_point(&p->approx, s, xy);
    else
        ob_bez_offset_point(&p->base, s, d, xy);
    /* a negative cut asks for the exact distance */
    int hint = -1;
    long ops = 0;
    return obc_err_at(kind, &p->base.h[0][0], p->base.deg, &p->approx.h[0][0], p->approx.deg, d, v->samples,
                      scratch, NULL, &ops, s, -1, -1.0, &hint);
}
