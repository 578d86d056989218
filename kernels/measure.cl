/*
 * measure.cl - one launch measures a whole batch of (base piece, approximating
 * piece, d, metric) records, in one of two layouts (host/backend/clrt.h):
 *
 *   ob_measure_groups  a work-group per record, its work-items over the
 *                      record's samples (on GPUs and accelerators);
 *   ob_measure_batch   a work-item per record running obc_measure whole (on
 *                      CPU devices, where a group's items are a loop).
 *
 * Both give the CPU reference's bits: they run the same functions of
 * kernels/metric_core.h on the same operands, and only reorder work whose
 * results do not depend on order.  The host builds this file with
 * kernels/metric_core.h prepended.
 *
 * A launch measures records i0 .. nrec - 1 of the buffers (the host stages
 * a batch metric by metric and launches each metric's program over its
 * records).
 *
 * Buffers (structure of arrays, sized once per run and grown when needed):
 *   metric[i], d[i]          the record's sampled metric code and offset
 *   stop[i]                  > 0: the measurement may end above it (obc_measure);
 *                            else the full measurement
 *   bdeg[i], boff[i]         degree of the base piece, offset of its
 *   adeg[i], aoff[i]         homogeneous control points in ctrl (doubles)
 *   soff[i]                  offset of its scratch in scratch: 2 OBC_TABLE_SIZE(S)
 *                            doubles for hausdorff (and 2 S more in the group
 *                            layout: both sides' sample errors); in the group
 *                            layout 2 S for the other metrics (rec_scratch)
 *   err[i], tpar[i]          the error and the base parameter of its maximum
 *   work[i]                  the work it took (flops, counted as OBC_OPS_* say),
 *                            by which the host shares the launch's time
 */
/* The arguments of both kernels, in the order the host sets them. */
#define OBK_ARGS                                                                                         \
    const int i0, const int nrec, const int S, __global const int *metric, __global const double *d,     \
        __global const double *stop,                                                                     \
        __global const int *bdeg, __global const int *boff, __global const int *adeg,                      \
        __global const int *aoff, __global const double *ctrl, __global const int *soff,                   \
        __global double *scratch, __global double *err, __global double *tpar, __global double *work

/* The layouts a build holds: both, or the one -D OBC_ONLY_GROUPS or
 * -D OBC_ONLY_ITEMS names (the host builds one program per metric and
 * layout it uses, each with one kernel). */
#ifndef OBC_ONLY_GROUPS
__kernel void ob_measure_batch(OBK_ARGS)
{
    const int i = i0 + (int)get_global_id(0);
    if (i >= nrec)
        return;
    double e, t;
    long ops = 0;
    obc_measure(metric[i], ctrl + boff[i], bdeg[i], ctrl + aoff[i], adeg[i], d[i], S, stop[i], scratch + soff[i], &e,
                &t, &ops);
    err[i] = e;
    tpar[i] = t;
    work[i] = (double)ops;
}
#endif

#ifndef OBC_ONLY_ITEMS
/* ---- a work-group per record ------------------------------------------ */

#define OBG_MAX 256 /* largest work-group the host launches (ob_cl_open caps it) */

/* The tasks 0 .. n-1 shared out over the work-items of the group. */
#define OBG_EACH(v, n) for (int v = (int)get_local_id(0); v < (n); v += (int)get_local_size(0))

/* The work of the group: each item's count in lops, summed by item 0 (whole
 * numbers: the order of the sum does not matter). */
long obg_sum_ops(__local long *lops, long mine)
{
    lops[get_local_id(0)] = mine;
    barrier(CLK_LOCAL_MEM_FENCE);
    long s = 0;
    if (get_local_id(0) == 0)
        for (int q = 0; q < (int)get_local_size(0); q++)
            s += lops[q];
    return s;
}

#if OBC_WANT_HAUSDORFF
/* Hausdorff, data-parallel (kernels/metric_core.h, "one side's scan,
 * data-parallel"): the four tables' parts (rows of O and A, OBC_LANES
 * samples per task; then the margins; then the block circles) over the
 * work-items, a barrier between the parts that read the earlier ones; then
 * both sides' coarse samples over the work-items, exact; item 0 (A's side)
 * and item `second` (O's; 0 in a group of one) replay the serial scan over them; then both
 * sides' other samples over the work-items, each asked only above its
 * side's coarse maximum; the two items replay the rest and finish their
 * side (the refinement, A's foot).  Item 0 returns the result: the serial
 * code's bits.  Its work is what the group did, which is more than the
 * serial scan's (every coarse sample exact, O's side even where A's ends
 * above stop). hs: 8 local doubles. */
void obg_hausdorff(const __global double *hb, int nb, const __global double *ha, int na, double d, int S,
                   double stop, __global double *O, __global double *A, __global double *E, __local long *lops,
                   __local double *hs, double *err, double *t, long *total)
{
    const int lid = get_local_id(0), second = (int)get_local_size(0) / 2;
    /* O's side on the first item of the group's second half: in another
     * warp (wavefront) than A's, so that the two serial refinements run side
     * by side instead of in turn */
    const int G = (S + OBC_LANES - 1) / OBC_LANES, pb = obc_table_poly(hb, nb), pa = obc_table_poly(ha, na);
    long ops = 0;
    OBG_EACH(g, 2 * G) {
        if (g < G)
            obc_table_lanes(hb, nb, pb, d, S, OBC_LANES * g, O, &ops);
        else
            obc_table_lanes(ha, na, pa, 0.0, S, OBC_LANES * (g - G), A, &ops);
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
    OBG_EACH(j, 2 * (S - 1)) obc_table_margin(S, j < S - 1 ? O : A, j < S - 1 ? j : j - (S - 1));
    barrier(CLK_GLOBAL_MEM_FENCE);
    const int NB = OBC_NBLK(S);
    OBG_EACH(b, 2 * NB) obc_table_block(S, b < NB ? O : A, b < NB ? b : b - NB);
    barrier(CLK_GLOBAL_MEM_FENCE);
    /* side 0: A's samples to O (E[0 .. S-1]); side 1: O's to A (E[S ..]) */
    const int NC = obc_scan_ncoarse(S), NR = S - NC;
    OBG_EACH(q, 2 * NC) {
        const int s = q >= NC, k = OBC_COARSE * (s ? q - NC : q);
        E[s * S + k] = s ? obc_side_query(OBC_K_H_OFFSET, hb, nb, ha, na, d, S, A, O, &ops, k, -1.0)
                         : obc_side_query(OBC_K_H_APPROX, hb, nb, ha, na, d, S, O, A, &ops, k, -1.0);
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
    double best[2] = {-1.0, -1.0};
    int kb[2] = {0, 0}, end[2] = {0, 0};
    for (int s = 0; s < 2; s++)
        if (lid == (s ? second : 0)) {
            end[s] = obc_scan_replay(E + s * S, S, 0, NC, stop, &best[s], &kb[s]);
            hs[2 * s] = end[s] ? OBC_INF : best[s]; /* +inf: the side needs no more samples */
        }
    barrier(CLK_LOCAL_MEM_FENCE);
    OBG_EACH(q, 2 * NR) {
        const int s = q >= NR, k = obc_scan_at(NC + (s ? q - NR : q), S);
        const double cut = hs[2 * s];
        if (cut != OBC_INF)
            E[s * S + k] = s ? obc_side_query(OBC_K_H_OFFSET, hb, nb, ha, na, d, S, A, O, &ops, k, cut)
                             : obc_side_query(OBC_K_H_APPROX, hb, nb, ha, na, d, S, O, A, &ops, k, cut);
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
    for (int s = 0; s < 2; s++)
        if (lid == (s ? second : 0)) {
            if (!end[s])
                obc_scan_replay(E + s * S, S, NC, S, stop, &best[s], &kb[s]);
            double e, te;
            if (s == 0) {
                obc_scan_finish(OBC_K_H_APPROX, hb, nb, ha, na, d, S, O, A, &ops, stop, best[s], kb[s], &e, &te);
                if (!(isnan(e) || isinf(e)))
                    te = obc_h_foot(hb, nb, ha, na, d, S, O, A, &ops, te);
            } else {
                obc_scan_finish(OBC_K_H_OFFSET, hb, nb, ha, na, d, S, A, O, &ops, stop, best[s], kb[s], &e, &te);
            }
            hs[4 + 2 * s] = e, hs[5 + 2 * s] = te;
        }
    *total = obg_sum_ops(lops, ops); /* its barrier also publishes hs[] */
    if (lid == 0)
        obc_h_pick(hs[4], hs[5], hs[6], hs[7], stop, err, t);
}

#endif

#if OBC_WANT_SCAN
/* Radial, normal, param: the samples' errors over the work-items (E, their
 * work W in global scratch), then the scan's result as obc_sample_refine
 * finds it in order: the first NaN or inf sample, or the first above stop,
 * ends the scan (its work and that of the samples before it counted, none
 * after); else the first of equal maxima; item 0 refines it (not a sample
 * above stop: that is the result). */
void obg_scan(int kind, const __global double *hb, int nb, const __global double *ha, int na, double d, int S,
              double stop, __global double *E, __global double *W, __local long *lops, __local int *lk,
              __local double *lbest, double *err, double *t, long *total)
{
    const int lid = get_local_id(0), L = get_local_size(0);
    int hint = OBC_NO_HINT;
    OBG_EACH(k, S) {
        long o = 0;
        E[k] = obc_err_at(kind, hb, nb, ha, na, d, S, E, E, &o, obc_sample_t(k, S), k, -1.0, &hint);
        W[k] = (double)o;
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
    int bad = S;
    OBG_EACH(k, S) if (isnan(E[k]) || isinf(E[k]) || E[k] > stop) {
        bad = k;
        break;
    }
    lk[lid] = bad;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int q = 0; q < L; q++)
        bad = min(bad, lk[q]);
    barrier(CLK_LOCAL_MEM_FENCE); /* lk is reused below */
    double best = -1.0;
    int kb = 0;
    long ops = 0;
    OBG_EACH(k, S) {
        if (k > bad)
            break;
        ops += (long)W[k];
        obc_scan_take(E[k], k, &best, &kb);
    }
    lbest[lid] = best, lk[lid] = kb;
    *total = obg_sum_ops(lops, ops);
    if (lid != 0)
        return;
    if (bad < S && !(isnan(E[bad]) || isinf(E[bad]))) { /* above stop: the result */
        *err = E[bad];
        *t = obc_sample_t(bad, S);
        return;
    }
    if (bad < S) { /* the scan ends there, as the worst */
        best = E[bad];
        kb = bad;
    } else {
        best = -1.0, kb = 0;
        for (int q = 0; q < L; q++) /* the first of equal maxima */
            if (lbest[q] > best || (lbest[q] == best && lk[q] < kb)) {
                best = lbest[q];
                kb = lk[q];
            }
    }
    obc_scan_refine(kind, hb, nb, ha, na, d, S, E, E, total, best, kb, &hint, err, t);
}

#endif

__kernel void ob_measure_groups(OBK_ARGS)
{
    __local long lops[OBG_MAX];
    __local int lk[OBG_MAX];
    __local double lbest[OBG_MAX];
    __local double hs[8];
    const int i = i0 + (int)get_group_id(0); /* the same for the whole group: it returns as one */
    if (i >= nrec)
        return;
    const int m = metric[i], kind = obc_scan_kind(m);
    const __global double *hb = ctrl + boff[i], *ha = ctrl + aoff[i];
    __global double *scr = scratch + soff[i];
    double e = OBC_INF, t = 0.0;
    long ops = 0;
    const double st = obc_stop_of(stop[i]);
#if OBC_WANT_HAUSDORFF
    if (m == OBC_HAUSDORFF)
        obg_hausdorff(hb, bdeg[i], ha, adeg[i], d[i], S, st, scr, scr + OBC_TABLE_SIZE(S),
                      scr + 2 * OBC_TABLE_SIZE(S), lops, hs, &e, &t, &ops);
#endif
#if OBC_WANT_SCAN
    if (kind >= 0)
        obg_scan(kind, hb, bdeg[i], ha, adeg[i], d[i], S, st, scr, scr + S, lops, lk, lbest, &e, &t, &ops);
#endif
    if (get_local_id(0) == 0) {
        err[i] = e;
        tpar[i] = t;
        work[i] = (double)ops;
    }
}
#endif
