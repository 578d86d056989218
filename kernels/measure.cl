/*
 * measure.cl - one launch measures a whole batch of (base piece, approximating
 * piece, d, metric) records: one work-item per record, running the same
 * sample-and-refine code as the CPU reference.
 *
 * The host builds this file with kernels/metric_core.h prepended (it holds the
 * formulas, shared with methods/metrics/metric_sampled.c).
 *
 * Buffers (structure of arrays, sized once per run and grown when needed):
 *   metric[i], d[i]          the record's sampled metric code and offset
 *   bdeg[i], boff[i]         degree of the base piece, offset of its
 *   adeg[i], aoff[i]         homogeneous control points in ctrl (doubles)
 *   soff[i]                  offset of its scratch (2 OBC_TABLE_SIZE(S) doubles) in scratch,
 *                            used by hausdorff only
 *   err[i], tpar[i]          the error and the base parameter of its maximum
 *   work[i]                  the work it took (flops, counted as OBC_OPS_* say),
 *                            by which the host shares the launch's time
 */
__kernel void ob_measure_batch(const int nrec, const int S, __global const int *metric,
                               __global const double *d, __global const int *bdeg,
                               __global const int *boff, __global const int *adeg,
                               __global const int *aoff, __global const double *ctrl,
                               __global const int *soff, __global double *scratch,
                               __global double *err, __global double *tpar, __global double *work)
{
    const int i = get_global_id(0);
    if (i >= nrec)
        return;
    double e, t;
    long ops = 0;
    obc_measure(metric[i], ctrl + boff[i], bdeg[i], ctrl + aoff[i], adeg[i], d[i], S, scratch + soff[i], &e, &t,
                &ops);
    err[i] = e;
    tpar[i] = t;
    work[i] = (double)ops;
}
