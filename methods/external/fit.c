/*
 * fit.c - an external method's fit (ext.h): the piece sent to this
 * thread's worker as one JSON line, the answer checked field by field.
 *
 * Supervision (docs/external-methods.md "Supervision"): one worker per
 * calling thread and external method, started on first use and again after
 * it ended; each fit has a wall-clock cap (NAME.wall_timeout) and a CPU cap
 * (NAME.cpu_timeout, or the job's remaining --job-timeout budget when
 * smaller: ob_fit_budget_ns); the worker's address space is capped
 * (NAME.mem_mb).  Whatever goes wrong - the worker ends, hangs, answers
 * garbage, a NaN, another request's id, too many pieces - the fit fails
 * with a message that names the method and quotes what it sent, and the
 * worker is killed and replaced for the next fit: a row, never a lost one.
 * A thread's workers are stopped when it exits; a forked child never uses
 * its parent's (proc.c only forgets a worker another process started).
 */
#include "methods/external/ext.h"

#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "methods/external/json.h"
#include "methods/external/proc.h"
#include "methods/sisl/proto.h"

typedef struct {
    ob_ext_proc w[OB_MAX_EXTERNAL];
    long next_id;
} workers;

static pthread_key_t key;
static pthread_once_t once = PTHREAD_ONCE_INIT;

static void thread_gone(void *p)
{
    workers *ws = p;
    for (int k = 0; k < OB_MAX_EXTERNAL; k++) {
        ob_ext_proc_stop(&ws->w[k], SIGKILL, NULL);
        free(ws->w[k].buf);
    }
    free(ws);
}

static void make_key(void) { pthread_key_create(&key, thread_gone); }

static workers *my_workers(void)
{
    pthread_once(&once, make_key);
    workers *ws = pthread_getspecific(key);
    if (!ws && (ws = calloc(1, sizeof *ws)) != NULL) {
        for (int k = 0; k < OB_MAX_EXTERNAL; k++)
            ws->w[k].fd = -1;
        if (pthread_setspecific(key, ws) != 0) {
            free(ws);
            ws = NULL;
        }
    }
    return ws;
}

/* Appends printf output to the request buffer (16 KiB holds the largest:
 * 33 points, 33 weights, 5 parameters at 24 characters each). */
static void put(char *buf, size_t cap, size_t *n, const char *fmt, double v)
{
    if (*n < cap)
        *n += (size_t)snprintf(buf + *n, cap - *n, fmt, v);
}

/* The request line for one fit (docs/external-methods.md "Request"). */
static size_t request(const ob_ext *e, long id, const ob_bez *b, const ob_fit_args *a, char *buf, size_t cap)
{
    size_t n = (size_t)snprintf(buf, cap, "{\"id\":%ld,\"degree\":%d,\"points\":[", id, b->deg);
    for (int i = 0; i <= b->deg; i++) {
        double p[2];
        ob_bez_ctrl(b, i, p);
        put(buf, cap, &n, i ? ",[%.17g" : "[%.17g", p[0]);
        put(buf, cap, &n, ",%.17g]", p[1]);
    }
    put(buf, cap, &n, "],\"weights\":[", 0);
    for (int i = 0; i <= b->deg; i++)
        put(buf, cap, &n, i ? ",%.17g" : "%.17g", ob_bez_weight(b, i));
    put(buf, cap, &n, "],\"d\":%.17g", a->d);
    put(buf, cap, &n, ",\"tol\":%.17g,\"params\":{", a->tol);
    for (int i = 0; i < e->nuser; i++) {
        if (n < cap)
            n += (size_t)snprintf(buf + n, cap - n, "%s\"%s\":", i ? "," : "", e->params[i].name);
        put(buf, cap, &n, "%.17g", a->par[i]);
    }
    put(buf, cap, &n, "}}\n", 0);
    return n;
}

/* 1 when v is an array of n numbers, each finite and (positive) > 0 when asked. */
static int numbers(const obj_node *v, int n, int positive)
{
    if (!v || v->type != OBJ_ARR || v->n != n)
        return 0;
    for (int i = 0; i < n; i++)
        if (v->kids[i]->type != OBJ_NUM || (positive && !(v->kids[i]->num > 0)))
            return 0;
    return 1;
}

int ob_ext_piece(const obj_node *p, int want, ob_bez *seg, char *why, size_t wl)
{
    const obj_node *dg = obj_get(p, "degree"), *pts = obj_get(p, "points"), *w = obj_get(p, "weights");
    if (!dg || dg->type != OBJ_NUM || dg->num != want) {
        snprintf(why, wl, "\"degree\" is not %d", want);
        return -1;
    }
    if (!pts || pts->type != OBJ_ARR || pts->n != want + 1) {
        snprintf(why, wl, "\"points\" is not %d points", want + 1);
        return -1;
    }
    for (int i = 0; i <= want; i++)
        if (!numbers(pts->kids[i], 2, 0)) {
            snprintf(why, wl, "\"points\"[%d] is not [x, y]", i);
            return -1;
        }
    if (w && !numbers(w, want + 1, 1)) {
        snprintf(why, wl, "\"weights\" is not %d numbers > 0", want + 1);
        return -1;
    }
    memset(seg, 0, sizeof *seg);
    seg->deg = want;
    for (int i = 0; i <= want; i++)
        ob_bez_set(seg, i, pts->kids[i]->kids[0]->num, pts->kids[i]->kids[1]->num, w ? w->kids[i]->num : 1.0);
    return 0;
}

/* The pieces' base parameters "t" (or equal steps): 0, or -1. */
static int breaks(const obj_node *t, ob_fit *out, char *why, size_t wl)
{
    for (int i = 0; i <= out->n; i++)
        out->t[i] = t ? t->kids[i]->num : (double)i / out->n;
    out->t[out->n] = 1.0;
    int okv = !t || (numbers(t, out->n + 1, 0) && t->kids[0]->num == 0.0 && t->kids[out->n]->num == 1.0);
    for (int i = 0; okv && i < out->n; i++)
        okv = out->t[i] < out->t[i + 1];
    if (!okv)
        snprintf(why, wl, "\"t\" is not %d increasing numbers from 0 to 1", out->n + 1);
    return okv ? 0 : -1;
}

/* The answer's pieces into out: 0, or -1 with what is wrong in why. */
static int pieces(const obj_node *r, int want, ob_fit *out, char *why, size_t wl)
{
    const obj_node *ps = obj_get(r, "pieces"), *t = obj_get(r, "t"), *cp = obj_get(r, "ctrl_points");
    if (!ps || ps->type != OBJ_ARR || ps->n < 1 || ps->n > OB_MAX_PIECES) {
        snprintf(why, wl, "no \"error\", no \"pieces\" (1 to %d)", OB_MAX_PIECES);
        return -1;
    }
    out->n = ps->n;
    for (int i = 0; i < ps->n; i++)
        if (ob_ext_piece(ps->kids[i], want, &out->seg[i], why, wl) != 0)
            return -1;
    if (cp && (cp->type != OBJ_NUM || cp->num < 0 || cp->num != floor(cp->num) || cp->num > 1e9)) {
        snprintf(why, wl, "\"ctrl_points\" is not a whole number >= 0");
        return -1;
    }
    out->ctrl_points = cp ? (long)cp->num : 0;
    return breaks(t, out, why, wl);
}

/* An answer "error": the worker's own reason, the worker kept. */
static ob_fit_status answered_error(const ob_ext *e, const obj_node *r, char *msg, size_t msglen)
{
    const obj_node *er = obj_get(r, "error"), *st = obj_get(r, "status");
    const char *s = st && st->type == OBJ_STR ? st->str : "fail";
    char q[160];
    ob_ext_quote(er->str, strlen(er->str), q, sizeof q);
    ob_method_msg(msg, msglen, "%s", q);
    (void)e;
    return strcmp(s, "skip") == 0 ? OB_FIT_SKIP : strcmp(s, "retry_smaller") == 0 ? OB_FIT_RETRY_SMALLER
                                                                                  : OB_FIT_FAIL;
}

/* Checks the answer line to request id: OB_FIT_OK with out filled, an
 * answered error, or -1 with what is wrong in why (the worker is then
 * replaced). */
static int answer(const ob_ext *e, long id, int want, const char *line, size_t len, ob_fit *out, char *msg,
                  size_t msglen, char *why, size_t wl)
{
    obj_node *r = obj_parse(line, len, why, wl);
    int rc = -1;
    const obj_node *idv = obj_get(r, "id"), *er = obj_get(r, "error");
    if (!r)
        ;
    else if (r->type != OBJ_OBJ)
        snprintf(why, wl, "not a JSON object");
    else if (!idv || idv->type != OBJ_NUM || idv->num != (double)id)
        snprintf(why, wl, "\"id\" is not %ld", id);
    else if (er && er->type == OBJ_STR)
        rc = (int)answered_error(e, r, msg, msglen);
    else if (pieces(r, want, out, why, wl) == 0)
        rc = OB_FIT_OK;
    obj_free(r);
    return rc;
}

/* The worker ended during a fit (EOF): how, into msg.  A CPU cap that was
 * the job's budget ends the job as the driver would (timeout). */
static ob_fit_status ended(const ob_ext *e, ob_ext_proc *w, int by_budget, char *msg, size_t msglen)
{
    char q[160], how[80];
    ob_ext_quote(w->buf ? w->buf : "", w->have, q, sizeof q);
    int ws = -1;
    ob_ext_proc_stop(w, 0, &ws);
    if (by_budget && ws != -1 && WIFSIGNALED(ws) && (WTERMSIG(ws) == SIGXCPU || WTERMSIG(ws) == SIGKILL)) {
        ob_method_msg(msg, msglen, "job timeout (the worker of external method %s reached the job's "
                      "--job-timeout budget)", e->name);
        return OB_FIT_TIMEOUT;
    }
    ob_sisl_describe_wait(ws, how, sizeof how);
    ob_method_msg(msg, msglen, "%s died (%s) after sending '%s'; restarted", e->name, how, q);
    return OB_FIT_FAIL;
}

/* A fresh worker, its hello line read within `wall` seconds (30 at least) and the same
 * as at registration (another program behind the command would give
 * other rows under the run's fingerprint): 0, or -1 with why. */
static int start(const ob_ext *e, ob_ext_proc *w, double mem, double wall, char *why, size_t wl)
{
    if (ob_ext_proc_start(w, e->command, mem, why, wl) != 0)
        return -1;
    char *line, how[80];
    size_t len;
    /* a start may take long on a loaded machine (an interpreter's imports):
     * at least the 30 s that registration allows */
    const int rc = ob_ext_proc_line(w, ob_sisl_now() + (wall > 30.0 ? wall : 30.0), &line, &len);
    if (rc == 0 && ob_ext_fnv(OB_EXT_FNV0, line, len) == e->hello)
        return 0;
    int ws = -1;
    ob_ext_proc_stop(w, SIGKILL, &ws);
    ob_sisl_describe_wait(ws, how, sizeof how);
    snprintf(why, wl, "%s", rc == 0 ? "a restarted worker's hello differs" : rc == 1 ? "no hello line in 30 s" : how);
    return -1;
}

/* The request sent to a running worker, started (again) when it is not:
 * a worker that ended while idle had not seen the request.  0, or -1 with
 * the reason in msg. */
static int send_request(const ob_ext *e, ob_ext_proc *w, double mem, double wall, const char *req, size_t n,
                        char *msg, size_t msglen)
{
    char why[200] = "";
    if (w->pid > 0 && w->owner != getpid())
        ob_ext_proc_stop(w, 0, NULL);  /* a forked child's copy: the parent's worker */
    for (int attempt = 0; attempt < 2; attempt++) {
        if (w->pid <= 0 && start(e, w, mem, wall, why, sizeof why) != 0)
            break;
        if (ob_ext_proc_send(w, req, n) == 0)
            return 0;
        ob_ext_proc_stop(w, SIGKILL, NULL);
        snprintf(why, sizeof why, "the worker ended before it read the request");
    }
    ob_method_msg(msg, msglen, "external method %s: %s (command `%s`)", e->name, why, e->command);
    return -1;
}

ob_fit_status ob_ext_fit(const ob_ext *e, const ob_bez *base, const ob_fit_args *a, ob_fit *out, char *msg,
                         size_t msglen)
{
    workers *ws = my_workers();
    if (!ws) {
        ob_method_msg(msg, msglen, "external method %s: out of memory", e->name);
        return OB_FIT_FAIL;
    }
    ob_ext_proc *w = &ws->w[e->index];
    const double wall = a->par[e->nuser], cpu = a->par[e->nuser + 1], mem = a->par[e->nuser + 2];
    const double budget = ob_fit_budget_ns() > 0.0 ? 1e-9 * ob_fit_budget_ns() : INFINITY;
    const long id = ++ws->next_id;
    char req[16384];
    const size_t n = request(e, id, base, a, req, sizeof req);
    if (n >= sizeof req) {
        ob_method_msg(msg, msglen, "external method %s: the request is longer than %zu bytes", e->name, sizeof req);
        return OB_FIT_FAIL;
    }
    if (send_request(e, w, mem, wall, req, n, msg, msglen) != 0)
        return OB_FIT_FAIL;
    ob_ext_proc_cpu_cap(w, budget < cpu ? budget : cpu);
    const double cpu0 = ob_ext_proc_cpu_ns(w);
    char *line;
    size_t len;
    const int rc = ob_ext_proc_line(w, ob_sisl_now() + wall, &line, &len);
    const double cpu1 = ob_ext_proc_cpu_ns(w);
    if (cpu0 >= 0 && cpu1 > cpu0)
        ob_fit_foreign_add(cpu1 - cpu0);  /* the worker's time is the method's own (method.h) */
    if (rc == -1)
        return ended(e, w, budget < cpu, msg, msglen);
    char why[200] = "", q[160];
    ob_ext_quote(rc == 1 ? (w->buf ? w->buf : "") : line, rc == 1 ? w->have : len, q, sizeof q);
    const int want = e->degree < 0 ? base->deg : e->degree;
    const int st = rc == 0 ? answer(e, id, want, line, len, out, msg, msglen, why, sizeof why) : -1;
    if (st >= 0)
        return (ob_fit_status)st;
    ob_ext_proc_stop(w, SIGKILL, NULL);
    if (rc == 1)
        ob_method_msg(msg, msglen, "%s hung (no answer in %s.wall_timeout %g s), sent '%s'; "
                      "restarted", e->name, e->name, wall, q);
    else
        ob_method_msg(msg, msglen, "%s sent '%s': %s; restarted", e->name, q,
                      rc == -2 ? "a line over 4 MiB" : why);
    return OB_FIT_FAIL;
}
