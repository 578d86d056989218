/*
 * select.c - which backend measures a run (see select.h).
 */
#include <stdio.h>

#include "host/backend/clprobe.h"
#include "host/backend/kernsrc.h"
#include "host/backend/select.h"
#include "host/diag.h"

/* What opening the backend needs, and what it gives: for open_prepare,
 * here or in the child process that tries it first (clprobe.h). */
typedef struct {
    const char *device;
    int gpu_only;
    unsigned metrics;
    ob_cl *cl;
} open_args;

/* Open the device and build the programs of the metrics (each launched
 * once): 0, or ob_cl_open's and ob_cl_prepare's -1 or -2 (a->err). */
static int open_prepare(void *ctx, ob_err *err)
{
    open_args *a = ctx;
    int rc = ob_cl_open(a->device, a->gpu_only, &a->cl, err);
    for (int m = 0; rc == 0 && m < OB_METRIC_COUNT; m++)
        if ((a->metrics & (1u << m)) && ob_metric_batched((ob_metric)m))
            rc = ob_cl_prepare(a->cl, (ob_metric)m, ob_cl_get_layout(a->cl), err);
    return rc;
}

/* The trial process died of signal sig: said as out of memory, -2. */
static int trial_died(int sig, ob_err *err)
{
    char lim[100];
    ob_as_limit(lim, sizeof lim);
    ob_fail(err, "out of memory starting the OpenCL platform: it ended a trial process with signal %d%s", sig, lim);
    return -2;
}

/* --backend: opencl must work (exit 2 with the reason otherwise) on any
 * device with fp64, PoCL's CPU device included; auto takes the faster path:
 * a GPU or accelerator with fp64 when there is one (or the device --device
 * names), else the CPU backend, and says why in meta.json (on a CPU, PoCL
 * measures the same jobs at 0.6-0.8x the CPU backend's speed, issue 35);
 * cpu never tries.  The programs of the run's metrics are built here, once,
 * before any timed work (one per metric and layout, clrt.h). */
int ob_open_backend(ob_backend kind, const char *device, unsigned metrics, ob_backend_info *b, ob_cl **cl)
{
    b->kernel_hash = ob_embedded_kernel_hash();
    if (kind == OB_BACKEND_CPU) {
        snprintf(b->why_cpu, sizeof b->why_cpu, "--backend cpu");
        return 0;
    }
    ob_err err;
    ob_cl_layout layout;
    if (ob_cl_layout_env(&layout, &err) < 0) { /* a setting, not a missing device: auto does not hide it */
        ob_error("%s", err.msg);
        return -1;
    }
    const int gpu_only = kind == OB_BACKEND_AUTO && !device;
    /* under ulimit -v PoCL may abort (no error code) starting its threads,
     * at open or at the first launch: a child process tries first */
    open_args a = {device, gpu_only, metrics, NULL};
    int rc = 0;
    const int sig = ob_cl_try_in_child(open_prepare, &a, &rc, &err);
    if (sig > 0)
        rc = trial_died(sig, &err);
    else if (sig < 0 || rc == 0)  /* not tried, or it worked there: here */
        rc = open_prepare(&a, &err);
    *cl = a.cl;
    if (rc != 0) {
        ob_cl_close(*cl);
        *cl = NULL;
        if (kind == OB_BACKEND_OPENCL || device) {
            ob_error("--backend opencl: %s", err.msg);
            return rc == -2 ? -2 : -1;
        }
        snprintf(b->why_cpu, sizeof b->why_cpu, "--backend auto: %.400s%s", err.msg,
                 gpu_only ? " (a CPU OpenCL device is used only when asked: --backend opencl)" : "");
        return 0;
    }
    b->opencl = 1;
    snprintf(b->platform, sizeof b->platform, "%s", ob_cl_platform(*cl));
    snprintf(b->device, sizeof b->device, "%s", ob_cl_device(*cl));
    snprintf(b->driver, sizeof b->driver, "%s", ob_cl_driver(*cl));
    snprintf(b->kernels, sizeof b->kernels, "%s", ob_cl_source(*cl));
    b->kernel_hash = ob_cl_kernel_hash(*cl);
    b->build_seconds = ob_cl_build_seconds(*cl);
    snprintf(b->cache, sizeof b->cache, "%s", ob_cl_cache_status(*cl));
    b->nbuilds = ob_cl_builds(*cl, b->builds, (int)(sizeof b->builds / sizeof *b->builds));
    if (b->nbuilds > (int)(sizeof b->builds / sizeof *b->builds))
        b->nbuilds = (int)(sizeof b->builds / sizeof *b->builds);
    snprintf(b->layout, sizeof b->layout, "%s", ob_cl_layout_name(ob_cl_get_layout(*cl)));
    b->group_size = ob_cl_get_layout(*cl) == OB_CL_GROUPS ? ob_cl_group_size(*cl) : 1;
    b->gpu = ob_cl_is_gpu(*cl);
    ob_info("OpenCL %s / %s, kernels from %s: %d program%s built in %.2f s (binary cache %.4s), layout %s (%d "
            "work-item%s per record)", b->platform, b->device, b->kernels, b->nbuilds, b->nbuilds == 1 ? "" : "s",
            b->build_seconds, b->cache, b->layout, b->group_size, b->group_size == 1 ? "" : "s");
    return 0;
}

int ob_backend_exit(int rc) { return rc == -2 ? 1 : 2; }

void ob_backend_hooks(ob_cl *cl, ob_backend_info *b, ob_driver_hooks *h)
{
    if (!cl)
        return;
    h->batch = ob_cl_measure_batch;
    h->batch_submit = ob_cl_batch_submit;
    h->batch_wait = ob_cl_batch_wait;
    h->batch_overlap = b->gpu;  /* on a CPU device overlap only oversubscribes the cores */
    h->batch_ctx = cl;
    /* a GPU wants tens of thousands of records a launch; a CPU device
     * (PoCL) gains nothing from more than the CPU path's chunk */
    h->batch_chunk = b->gpu ? OB_GPU_CHUNK : 0;
    h->batch_fallbacks = &b->fallbacks;
}
