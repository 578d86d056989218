/*
 * rules.c - the split rules: what becomes of one measured piece of a job
 * (accept, split, narrow a greedy bracket, the optimal rule's passes), in the
 * fixed order its share group decides in.
 * See driver.h (the contract) and driver_int.h (the pieces).
 */
#include "methods/driver/driver_int.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The job status that a fit status ends a job with: the one place where a
 * method's fit status becomes a job's.  OB_FIT_OK and OB_FIT_RETRY_SMALLER
 * end no job (decide accepts or splits the piece): OB_OK. */
static ob_status job_status_of(ob_fit_status st)
{
    switch (st) {
    case OB_FIT_FAIL: return OB_FAIL;
    case OB_FIT_SKIP: return OB_SKIP;
    case OB_FIT_TIMEOUT: return OB_TIMEOUT;
    case OB_FIT_OK:
    case OB_FIT_RETRY_SMALLER: break;
    }
    return OB_OK;
}

/* What drv_decide() says of a piece that asks for a smaller piece (r: its fit's
 * result) when none may be made: at the retry limit, or past the depth or
 * segment limits. */
static void retry_end_msg(const item *it, const itemres *r, int at_retry_limit, char *msg, size_t len)
{
    const char *why = r->msg[0] ? r->msg : "the method needs a smaller piece";
    if (at_retry_limit)
        snprintf(msg, len, "%.60s, still after %d halvings, at t in [%.6g, %.6g] of segment %d", why,
                 RETRY_LEVELS, it->a, it->b, it->seg);
    else
        snprintf(msg, len, "%.60s; pieces that small are past the limits, at t in [%.6g, %.6g] of segment %d",
                 why, it->a, it->b, it->seg);
}

/* The optimal rule at the end of one pass over its stretch: the next
 * level, or the final pass.  Phase 0 (at tol) gives the target count; a
 * pass of phase 1 is feasible when it covers the stretch in at most target
 * pieces.  The upper level is always one whose pass was feasible, so the
 * final pass at it (the same fits, the same decisions) takes that pass's
 * pieces; the lower one starts at 1/64 of phase 0's largest error. */
static void optimal_next_pass(item *g, int covered)
{
    if (g->phase == 0) {
        g->target = g->pieces;
        g->ehi = g->level;
        g->elo = g->pass_max / 64;
    } else if (covered && g->pieces <= g->target) {
        g->ehi = g->level;
    } else {
        g->elo = g->level;
    }
    g->rounds++;
    const int done = g->target <= 1 || g->ehi <= OPT_RATIO * g->elo || g->rounds > OPT_ROUNDS;
    g->phase = done ? 2 : 1;
    g->level = done ? g->ehi : sqrt(g->elo * g->ehi);
    g->pieces = 0;
    g->pass_max = 0.0;
    g->a = g->lo = g->start;
    g->hi = g->b = g->end;
}

/* Purpose: the optimal split rule's counting passes (phases 0 and 1): the
 *          greedy bisection on the end of the prefix [a, b] at the item's
 *          level, counting the pieces instead of accepting them.
 * Method:  a pass that needs more than target pieces, or where not even a
 *          sliver meets the level, is infeasible and ends early; phase 0
 *          where not even a sliver passes goes straight to the final pass
 *          at tol, which is greedy's (with its limit rules).  The level is
 *          bisected geometrically between an infeasible and a feasible one;
 *          the final pass (phase 2, in drv_decide) accepts the pieces at the
 *          lowest feasible level found.  Every pass fits the same pieces
 *          as a greedy run at that tolerance would.  A stretch whose first
 *          probe of phase 0 (the whole of it) passes is accepted at once:
 *          the target is then 1 and the final pass would fit and measure
 *          that same piece again. */
static int decide_optimal(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj, int pass,
                          itemvec *next)
{
    item g = *it;
    if (g.phase == 0 && pass && it->a == g.start && it->b >= g.end) {
        /* the whole stretch is one piece at tol: the final pass would fit
         * and measure this same piece again (target 1) and accept it */
        drv_accept_item(j, s, it, r, fj);
        return 0;
    }
    if (pass) {
        g.lo = it->b;
        g.pass_err = r->err;
    } else {
        g.hi = it->b;
    }
    const int reached = pass && it->b >= it->end;
    if (reached || g.hi - g.lo <= GREEDY_EPS * (g.end - g.a)) {
        if (g.lo > g.a) {  /* a piece of this pass: [a, lo] */
            g.pieces++;
            g.pass_max = fmax(g.pass_max, g.pass_err);
            g.a = g.lo;
            g.hi = g.b = g.end;
            if (g.a >= g.end || (g.phase == 1 && g.pieces > g.target))
                optimal_next_pass(&g, g.a >= g.end);
        } else if (g.phase == 0) {
            g.phase = 2;  /* not even a sliver at tol: greedy decides */
            g.level = j->tol;
            g.a = g.lo = g.start;
            g.hi = g.b = g.end;
        } else {
            optimal_next_pass(&g, 0);
        }
    } else {
        g.b = 0.5 * (g.lo + g.hi);
    }
    s->pending++;
    return drv_push(next, &g);
}

/* What drv_decide() found of one measured item: it asks for a smaller piece
 * (msg then says why none may be made), it meets its error level, the job
 * is at its segment limit; msg: the message of the job's end, if it ends. */
typedef struct {
    int retry, pass, full;
    char msg[160];
} verdict;

/* mid / maxerr: the two halves of a piece that is to be split (cut at the
 * middle, or at the largest error kept MAXERR_MARGIN from the ends), or, for
 * a chain of requests for a smaller piece down to the limit, its leftmost
 * half alone. */
static int split_children(jstate *s, const item *it, const itemres *r, int split, int retry, int stall,
                          itemvec *next)
{
    double cut = 0.5 * (it->a + it->b);
    if (split == OB_SPLIT_MAXERR && !retry) {
        double w = it->b - it->a;
        cut = fmin(it->b - MAXERR_MARGIN * w, fmax(it->a + MAXERR_MARGIN * w, r->t));
    }
    item l = *it, rr = *it;
    l.b = cut;
    rr.a = cut;
    l.depth = rr.depth = it->depth + 1;
    l.parent_err = rr.parent_err = retry ? INFINITY : r->err;
    l.stall = rr.stall = stall;
    l.end = l.hi = l.b;
    l.lo = l.a;
    rr.end = rr.hi = rr.b;
    rr.lo = rr.a;
    l.chain_to = retry ? (it->chain_to > 0 ? it->chain_to : r->chain_to) : 0;
    if (l.chain_to > 0) {  /* a chain of requests down to the limit: its leftmost piece alone */
        s->pending += 1;
        return drv_push(next, &l);
    }
    s->pending += 2;
    return drv_push(next, &l) || drv_push(next, &rr) ? -1 : 0;
}

/* The mid and maxerr rules: accept a piece that passes; else end the job at
 * the retry limit, keep the piece where the job has hit an error floor or
 * the error stalls, or at the depth or segment limit; else split it. */
static int decide_split(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj,
                        const ob_driver_opts *o, verdict *v, itemvec *next)
{
    const int retry = v->retry, full = v->full;
    if (v->pass) {
        drv_accept_item(j, s, it, r, fj);
        return 0;
    }
    const int stall = !retry && r->err >= STALL_RATIO * it->parent_err ? it->stall + 1 : 0;
    if (retry && it->depth >= RETRY_LEVELS) {
        retry_end_msg(it, r, 1, v->msg, sizeof v->msg);
        drv_job_end(j, s, OB_FAIL, v->msg);
        return 0;
    }
    if (!retry && s->floored) {  /* the job cannot reach tol: no more splitting */
        drv_accept_item(j, s, it, r, fj);
        return 0;
    }
    if (stall >= STALL_LEVELS && !(it->depth >= o->max_depth || full)) {
        drv_accept_item(j, s, it, r, fj);
        snprintf(v->msg, sizeof v->msg, "error stalls at %.3g > tol under subdivision at t in [%.6g, %.6g] "
                 "of segment %d (%d splits without a 10%% drop); the rest kept as it was", r->err, it->a,
                 it->b, it->seg, STALL_LEVELS);
        drv_job_end(j, s, OB_LIMIT, v->msg);
        s->floored = 1;
        return 0;
    }
    if (it->depth >= o->max_depth || full) {
        if (retry) {
            drv_job_end(j, s, OB_FAIL, v->msg);
            return 0;
        }
        drv_accept_item(j, s, it, r, fj);
        if (full)
            snprintf(v->msg, sizeof v->msg, "segment limit %d reached (error %.3g > tol)", o->max_segments,
                     r->err);
        else
            snprintf(v->msg, sizeof v->msg, "depth limit %d reached at t in [%.6g, %.6g] of segment %d "
                     "(error %.3g)", o->max_depth, it->a, it->b, it->seg, r->err);
        drv_job_end(j, s, OB_LIMIT, v->msg);
        return 0;
    }
    return split_children(s, it, r, j->split, retry, stall, next);
}

/* The greedy rule (and the optimal rule's final pass): bisection on the end
 * of the prefix [a, b]; the longest passing prefix is accepted once the
 * bracket [lo, hi] is within GREEDY_EPS, and the rest of the stretch starts
 * over. */
static int decide_greedy(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj,
                         const ob_driver_opts *o, verdict *v, itemvec *next)
{
    item g = *it;
    if (it->final) {
        if (v->retry) {
            drv_job_end(j, s, OB_FAIL, v->msg);
            return 0;
        }
        drv_accept_item(j, s, it, r, fj);
        if (!v->pass) {
            snprintf(v->msg, sizeof v->msg, "segment limit %d reached (error %.3g > tol)", o->max_segments,
                     r->err);
            drv_job_end(j, s, OB_LIMIT, v->msg);
        }
        return 0;
    }
    if (v->pass) {
        if (it->b >= it->end) {
            drv_accept_item(j, s, it, r, fj);
            return 0;
        }
        g.lo = it->b;
        g.pass_err = r->err;
        g.pass_ctrl_add = r->ctrl_add;
        g.pass_maxdeg = r->maxdeg;
        g.pass_n = r->n;
        g.pass_fj = *fj;
    } else {
        g.hi = it->b;
    }
    if (g.hi - g.lo <= GREEDY_EPS * (g.end - g.a)) {
        if (g.lo > g.a) {
            drv_accept(j, s, it->seg, it->a, g.lo, g.pass_n, g.pass_ctrl_add, g.pass_maxdeg, g.pass_err, &g.pass_fj);
            g.a = g.lo;
        } else if (v->retry) {
            drv_job_end(j, s, OB_FAIL, v->msg);
            return 0;
        } else {
            /* not even a sliver passes: an error floor subdivision cannot get
             * under; keep the sliver, fit the rest of the stretch once and keep
             * it too, and end the job with status limit */
            drv_accept_item(j, s, it, r, fj);
            snprintf(v->msg, sizeof v->msg, "no prefix longer than %.3g passes at t = %.6g of segment %d "
                     "(error %.3g)", it->b - it->a, it->a, it->seg, r->err);
            drv_job_end(j, s, OB_LIMIT, v->msg);
            g.a = it->b;
            g.final = 1;
        }
        if (g.a >= g.end)
            return 0;
        g.lo = g.a;
        g.hi = g.b = g.end;
        /* out of segments: the rest is fitted once and kept whatever its error */
        g.final = g.final || j->segments + 1 >= o->max_segments;
    } else {
        g.b = 0.5 * (g.lo + g.hi);
    }
    s->pending++;
    return drv_push(next, &g);
}

/* Decide what becomes of one measured item (fj: the joints of its fit);
 * children go to `next`. */
int drv_decide(ob_job *jobs, jstate *js, const item *it, const itemres *r, const fitjoints *fj,
                  const ob_driver_opts *o, itemvec *next)
{
    ob_job *j = &jobs[it->job];
    jstate *s = &js[it->job];
    verdict v;
    s->pending--;
    if (s->dead)
        return 0;
    if (r->st != OB_FIT_OK && r->st != OB_FIT_RETRY_SMALLER) {
        snprintf(v.msg, sizeof v.msg, "%.100s at t in [%.6g, %.6g] of segment %d",
                 r->msg[0] ? r->msg : "fit failed", it->a, it->b, it->seg);
        drv_job_end(j, s, job_status_of(r->st), v.msg);
        return 0;
    }
    /* a method that asks for a smaller piece is treated as too large an error;
     * if no smaller piece may be made, there is nothing to accept */
    v.retry = r->st == OB_FIT_RETRY_SMALLER;
    if (v.retry)
        retry_end_msg(it, r, 0, v.msg, sizeof v.msg);
    /* the optimal rule's passes are greedy at their own error level */
    v.pass = !v.retry && ob_err_can_pass(r->err) && r->err <= (j->split == OB_SPLIT_OPTIMAL ? it->level : j->tol);
    v.full = j->segments + s->pending + 1 >= o->max_segments;

    if (j->split == OB_SPLIT_OPTIMAL && it->phase < 2)
        return decide_optimal(j, s, it, r, fj, v.pass, next);
    if (j->split == OB_SPLIT_MID || j->split == OB_SPLIT_MAXERR)
        return decide_split(j, s, it, r, fj, o, &v, next);
    return decide_greedy(j, s, it, r, fj, o, &v, next);
}

/* Purpose: the stop of one item's measurement (ob_measure_rec.stop).
 * Returns: its error level where only whether the error exceeds it
 *          matters: a greedy or optimal probe that fails only narrows the
 *          bracket on its end (decide_greedy, decide_optimal), unless it
 *          would end the search with not even a sliver passing (its error
 *          is then reported); else 0, the full measurement: for mid and
 *          maxerr (a failing piece's error drives the stall rule and the
 *          split point), final pieces and that sliver. */
double drv_item_stop(const ob_job *j, const item *it, int full_probes)
{
    if (full_probes || it->final || (j->split != OB_SPLIT_GREEDY && j->split != OB_SPLIT_OPTIMAL))
        return 0.0;
    if (j->split == OB_SPLIT_OPTIMAL && it->phase < 2)
        return it->level;
    /* decide_greedy's test of the bracket after a failing probe */
    const int sliver = !(it->lo > it->a) && it->b - it->lo <= GREEDY_EPS * (it->end - it->a);
    return sliver ? 0.0 : j->split == OB_SPLIT_OPTIMAL ? it->level : j->tol;
}
