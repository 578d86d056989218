/*
 * progress.c - see progress.h.
 */
#include "host/run/progress.h"

#include "host/diag.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* The model's unit (ob_job_cost): 1 ms of thread time on the development
 * machine. */
static const double MODEL_NS_PER_MS = 1e6;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* What the groups say so far: their predicted cost, the work measured (of
 * the groups finished with work: a group that ended before any work, a
 * method not applicable, says nothing of the model's unit), the wall time
 * the groups ran. */
typedef struct {
    double cost;        /* all groups' predicted cost */
    double done_cost;   /* of the finished groups with work */
    double done_ns;     /* their work */
    double work_ns;     /* all work measured */
    double wall_ns;     /* the groups' wall time (whole_groups) */
} tally;

static void tally_add(tally *t, const ob_work_group *g)
{
    t->cost += g->cost;
    t->work_ns += g->spent_ns;
    t->wall_ns += g->wall_ns;
    if (g->state == OB_WORK_DONE && g->spent_ns > 0) {
        t->done_cost += g->cost;
        t->done_ns += g->spent_ns;
    }
}

/* Thread ns per ms of predicted cost: the finished groups' ratio, with
 * prior_k weighing the share `prior` of the cost, so the first groups to
 * finish do not swing it. */
static double ns_per_cost(const tally *t, double prior, double prior_k)
{
    const double c0 = prior * t->cost;
    if (t->done_cost + c0 <= 0)
        return prior_k;
    return (t->done_ns + prior_k * c0) / (t->done_cost + c0);
}

/* A group's method as a calibration slot: -1 (the run's) for none, or for
 * one past OB_PROGRESS_MAX_KINDS (not a registry index). */
static int kind_of(const ob_work_group *g)
{
    return g->kind >= 0 && g->kind < OB_PROGRESS_MAX_KINDS ? g->kind : -1;
}

/* The calibration: k[0] the run's thread ns per ms of predicted cost (the
 * model's own unit before any group finished), k[1 + kind] each method's,
 * its own groups' ratio shrunk to the run's.  NULL without memory. */
static double *calibrate(const ob_work_group *g, size_t n)
{
    int kinds = 0;
    for (size_t i = 0; i < n; i++)
        if (kind_of(&g[i]) >= kinds)
            kinds = kind_of(&g[i]) + 1;
    tally *tk = calloc((size_t)kinds + 1, sizeof *tk);
    double *k = malloc(((size_t)kinds + 1) * sizeof *k);
    if (!tk || !k) {
        free(tk);
        free(k);
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        tally_add(&tk[0], &g[i]);
        if (kind_of(&g[i]) >= 0)
            tally_add(&tk[1 + kind_of(&g[i])], &g[i]);
    }
    k[0] = ns_per_cost(&tk[0], OB_PROGRESS_PRIOR_SHARE, MODEL_NS_PER_MS);
    for (int m = 0; m < kinds; m++)
        k[1 + m] = ns_per_cost(&tk[1 + m], OB_PROGRESS_KIND_PRIOR, k[0]);
    free(tk);
    return k;
}

/* The predicted thread time a group still needs: its predicted cost (at
 * its method's calibration) less what it has used.  Near or past its
 * prediction, OB_PROGRESS_OVERRUN x (used / predicted) of what it has used,
 * at most as much again: still running, it is not done (never "ETA 0 s"),
 * and the further past its prediction, the longer it is likely to run. */
static double group_left(const ob_work_group *g, const double *k)
{
    if (g->state == OB_WORK_DONE)
        return 0.0;
    const double ns = k[1 + kind_of(g)] * g->cost, m = g->spent_ns;
    const double over = ns > 0 ? fmin(m, OB_PROGRESS_OVERRUN * m * m / ns) : m;
    return fmax(ns - m, over);
}

/* The makespan of the unfinished groups' left work (thread ns) on `threads`
 * threads: each group, in schedule order (the running ones come first: the
 * engine took them in that order), on the earliest free thread, as the
 * group engine takes them.  -1 without memory. */
static double list_schedule(const ob_work_group *g, size_t n, int threads, const double *k)
{
    double *h = calloc((size_t)threads, sizeof *h);
    if (!h)
        return -1.0;
    double end = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (g[i].state == OB_WORK_DONE)
            continue;
        h[0] += group_left(&g[i], k);
        end = fmax(end, h[0]);
        ob_sched_heap_down(h, (size_t)threads, 0);
    }
    free(h);
    return end;
}

/* The ETA (s) of the work left: the list schedule at a group's speed on
 * its thread (whole_groups), else at the run's rate of work; the window's
 * speed where work was measured in it (a window without any, one long fit,
 * says nothing of the speed: the run's then).  -1: no rate yet; -2: no
 * memory. */
static double eta_of(const ob_progress_in *in, const tally *t, double left_ns, const double *k)
{
    const int win = in->win_work_ns > 0;
    if (!in->whole_groups) {
        const double work = win && in->win_s > 0 ? in->win_work_ns : t->work_ns;
        const double wall = win && in->win_s > 0 ? in->win_s : in->elapsed_s;
        return work > 0 && wall > 0 ? left_ns * wall / work : -1.0;
    }
    /* thread time per wall time of the groups' threads: below 1 on a shared
     * machine, above where threads without a group helped */
    const double work = win && in->win_wall_ns > 0 ? in->win_work_ns : t->work_ns;
    const double wall = win && in->win_wall_ns > 0 ? in->win_wall_ns : t->wall_ns;
    if (work <= 0 || wall <= 0)
        return -1.0;
    const double span = list_schedule(in->g, in->n, in->threads > 0 ? in->threads : 1, k);
    return span < 0 ? -2.0 : 1e-9 * span * wall / work;
}

int ob_progress_estimate(const ob_progress_in *in, ob_progress_est *e)
{
    memset(e, 0, sizeof *e);
    e->eta_s = -1.0;
    double *k = calibrate(in->g, in->n);
    if (!k)
        return -1;
    tally t = {0, 0, 0, 0, 0};
    for (size_t i = 0; i < in->n; i++) {
        tally_add(&t, &in->g[i]);
        e->left_ns += group_left(&in->g[i], k);
    }
    e->done_ns = t.work_ns;
    e->fraction = t.work_ns > 0 ? t.work_ns / (t.work_ns + e->left_ns) : 0.0;
    const double eta = t.work_ns > 0 && in->elapsed_s > 0 ? eta_of(in, &t, e->left_ns, k) : -1.0;
    free(k);
    e->eta_s = eta >= 0 ? eta : -1.0;
    return eta == -2.0 ? -1 : 0;
}

static void fmt_eta(char *buf, size_t len, double eta)
{
    if (eta < 0)
        snprintf(buf, len, "ETA ?");
    else
        snprintf(buf, len, "ETA %.0f s", eta);
}

void ob_progress_format(char *buf, size_t len, size_t done, size_t total, const ob_progress_est *e, double elapsed_s,
                        int tty)
{
    char eta[32];
    fmt_eta(eta, sizeof eta, e->eta_s);
    /* floor: "work 100 %" only when nothing is left */
    const double work = floor(100.0 * e->fraction);
    if (tty)
        snprintf(buf, len, "%zu/%zu jobs, work %.0f %%, %.0f s, %s", done, total, work, elapsed_s, eta);
    else
        snprintf(buf, len, "%zu/%zu jobs (%.0f %%), work %.0f %%, %.0f s elapsed, %s", done, total,
                 total ? 100.0 * (double)done / (double)total : 0.0, work, elapsed_s, eta);
}

void ob_progress_format_pass(char *buf, size_t len, const char *what, size_t done, size_t total,
                             const ob_progress_est *e, double elapsed_s, int tty)
{
    char eta[32];
    fmt_eta(eta, sizeof eta, e->eta_s);
    snprintf(buf, len, "%s %zu/%zu jobs, %.0f s%s, %s", what, done, total, elapsed_s, tty ? "" : " elapsed", eta);
}

/* The line p shows (without the bar). */
static void format_line(const ob_progress *p, char *buf, size_t len, const ob_progress_info *pi,
                        const ob_progress_est *e, double el, int tty)
{
    if (p->what)
        ob_progress_format_pass(buf, len, p->what, pi->done, pi->total, e, el, tty);
    else
        ob_progress_format(buf, len, pi->done, pi->total, e, el, tty);
}

void ob_progress_init(ob_progress *p)
{
    memset(p, 0, sizeof *p);
    p->tty = isatty(2);
    p->t0 = p->last = now_s();
}

/* The groups now into p->buf: 0, or -1 without memory. */
static int snapshot(ob_progress *p, const ob_progress_info *pi)
{
    if (pi->ngroups > p->cap) {
        ob_work_group *b = realloc(p->buf, pi->ngroups * sizeof *b);
        if (!b)
            return -1;
        p->buf = b;
        p->cap = pi->ngroups;
    }
    pi->groups(pi, p->buf);
    return 0;
}

/* The window's speed for in: the work and the groups' wall time since the
 * newest sample at least OB_PROGRESS_WINDOW_SECONDS old (none yet: the
 * whole run's), then this one kept as a sample. */
static void window(ob_progress *p, double el, ob_progress_in *in)
{
    double work = 0.0, wall = 0.0;
    for (size_t k = 0; k < in->n; k++) {
        work += in->g[k].spent_ns;
        wall += in->g[k].wall_ns;
    }
    for (int i = p->nsamp - 1; i >= 0; i--)
        if (p->samp[i].t <= el - OB_PROGRESS_WINDOW_SECONDS) {
            in->win_work_ns = work - p->samp[i].work_ns;
            in->win_wall_ns = wall - p->samp[i].wall_ns;
            in->win_s = el - p->samp[i].t;
            break;
        }
    if (p->nsamp > 0 && el - p->samp[p->nsamp - 1].t < 1.0)
        return;  /* one sample a second: the ring spans the window */
    enum { CAP = (int)(sizeof p->samp / sizeof *p->samp) };
    if (p->nsamp == CAP) {
        memmove(p->samp, p->samp + 1, (CAP - 1) * sizeof *p->samp);
        p->nsamp--;
    }
    p->samp[p->nsamp].t = el;
    p->samp[p->nsamp].work_ns = work;
    p->samp[p->nsamp++].wall_ns = wall;
}

/* The estimate now; nothing known where memory ran out.  The work done as
 * shown never goes back (a group past its prediction adds work to come:
 * the ETA says so; a bar moving back would read as a fault). */
static ob_progress_est estimate_now(ob_progress *p, const ob_progress_info *pi, double el)
{
    ob_progress_est e = {0, 0, 0, -1.0};
    if (snapshot(p, pi) != 0)
        return e;
    ob_progress_in in = {p->buf, pi->ngroups, pi->threads, pi->whole_groups, el, 0, 0, 0};
    window(p, el, &in);
    if (ob_progress_estimate(&in, &e) != 0)
        e.eta_s = -1.0;
    e.fraction = fmax(e.fraction, p->shown);
    p->shown = e.fraction;
    return e;
}

/* The bar on a terminal, redrawn in place. */
static void draw_bar(ob_progress *p, const ob_progress_info *pi, const ob_progress_est *e, double el)
{
    enum { W = 20 };
    char bar[W + 1], line[160];
    const int fill = (int)(W * e->fraction);
    for (int i = 0; i < W; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[W] = '\0';
    format_line(p, line, sizeof line, pi, e, el, 1);
    /* raw, not through the funnel: a bar redrawn in place ("\r", no newline,
     * no "offbench: " prefix), drawn only on a terminal; blanks cover what
     * is left of a longer line drawn before */
    const int n = fprintf(stderr, "\r[%s] %s", bar, line);
    fprintf(stderr, "%*s", p->width > n ? p->width - n : 0, "");
    fflush(stderr);
    if (n > p->width)
        p->width = n;
    p->drawn = 1;
}

void ob_progress_cb(void *ctx, const ob_progress_info *pi)
{
    ob_progress *p = ctx;
    if (pi->total == 0)
        return;
    const double t = now_s(), el = t - p->t0;
    /* a log: one line now and then, none at the end (the run's summary
     * says it); a terminal: ten redraws a second at most */
    const int show = p->tty ? t - p->last >= 0.1 || pi->done >= pi->total
                            : t - p->last >= OB_PROGRESS_LOG_SECONDS && pi->done < pi->total;
    /* the estimate (O(groups), under the engine's lock) once a second, and
     * at the end: it also samples the speed's window */
    const int refresh = !p->estimated || el - p->est_at >= 1.0 || pi->done >= pi->total;
    if (!show && !refresh)
        return;
    if (refresh) {
        p->est = estimate_now(p, pi, el);
        p->est_at = el;
        p->estimated = 1;
    }
    if (!show)
        return;
    p->last = t;
    ob_progress_est e = p->est;
    if (e.eta_s >= 0)  /* between estimates it counts down */
        e.eta_s = fmax(0.0, e.eta_s - (el - p->est_at));
    if (p->tty) {
        draw_bar(p, pi, &e, el);
    } else {
        char line[160];
        format_line(p, line, sizeof line, pi, &e, el, 0);
        ob_info("%s", line);
    }
}

void ob_progress_end(ob_progress *p)
{
    if (p->tty && p->drawn) {
        /* raw: blanks the bar in place before the next line */
        fprintf(stderr, "\r%*s\r", p->width, "");
        fflush(stderr);
    }
    p->drawn = 0;
    free(p->buf);
    p->buf = NULL;
    p->cap = 0;
}
