/*
 * clrt.h - the OpenCL runtime: device choice, the measure kernel built once
 * per run, and batches of records measured in one launch.
 *
 * libOpenCL is loaded at run time (dlopen), so the program runs, on the CPU
 * path, where no OpenCL loader or platform exists; it is compiled in when the
 * OpenCL headers were present at build time (the deps step installs them).
 */
#ifndef OB_CLRT_H
#define OB_CLRT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "methods/driver/driver.h"
#include "methods/core/err.h"

typedef struct ob_cl ob_cl;

/* 1 if this build has the OpenCL backend compiled in. */
int ob_cl_compiled(void);

/* Whether the backend can be used at all: compiled in and the OpenCL loader
 * found (dlopen; no platform or device is opened).  0, or -1; msg says which. */
int ob_cl_loader_status(char *msg, size_t len);

/* Purpose: open the first OpenCL device that supports double precision and
 *          whose "PLATFORM DEVICE" name contains device_substr (NULL: any),
 *          a GPU or an accelerator only when gpu_only is nonzero, and
 *          load kernels/measure.cl with kernels/metric_core.h prepended (the
 *          copy compiled in, or $OFFBENCH_KERNELS: kernsrc.h).  No program
 *          is built yet: each metric's, in each layout, is built when first
 *          used (ob_cl_prepare; a batch prepares its records' metrics).
 * Errors:  returns 0; -1 with the reason in err->msg: no loader, no platform, no
 *          matching device, no fp64, a failing call (named), or kernel
 *          sources that cannot be read; -2 when it is out of memory (an
 *          installed platform that cannot be loaded or started, a call that
 *          says so: clprobe.h). */
int ob_cl_open(const char *device_substr, int gpu_only, ob_cl **out, ob_err *err);

/* Always safe to call (NULL included). */
void ob_cl_close(ob_cl *cl);

/* Descriptions for meta.json and messages. */
const char *ob_cl_platform(const ob_cl *cl);
const char *ob_cl_device(const ob_cl *cl);
const char *ob_cl_driver(const ob_cl *cl);
const char *ob_cl_source(const ob_cl *cl);   /* where the kernel text came from */
uint64_t ob_cl_kernel_hash(const ob_cl *cl); /* FNV-1a of that text (kernsrc.h) */
/* The seconds of every program build so far (ob_cl_builds), summed. */
double ob_cl_build_seconds(const ob_cl *cl);
/* What the program binary cache did (clcache.h): for one program built,
 * "hit: FILE", "miss: WHY; built and stored" (or why it was not stored), or
 * "off (WHY)"; for several, "METRIC/LAYOUT: that; ..." in the order built;
 * "" before any. */
const char *ob_cl_cache_status(const ob_cl *cl);
/* 1 when the device is a GPU or an accelerator (CL_DEVICE_TYPE). */
int ob_cl_is_gpu(const ob_cl *cl);

/* Purpose: print one line per OpenCL device (platform, device, type, compute
 * units, fp64, driver).  Returns the number of devices, -1 if there is no
 * loader or the backend is not compiled in (a line says so). */
int ob_cl_list_devices(FILE *f);

/* How a launch maps records to the device.  Both give the CPU reference's
 * bits (tests/unit/test_opencl.c checks it):
 *   OB_CL_GROUPS  a work-group per record, its work-items over the record's
 *                 samples: the sample tables of hausdorff and the samples of
 *                 the other metrics, then the scan;
 *   OB_CL_ITEMS   a work-item per record, the whole measurement serial.
 * ob_cl_open takes the layout from $OFFBENCH_CL_LAYOUT (ob_cl_layout_env),
 * else by the device: items on a CPU device (where a group's work-items are
 * a loop on one core and the barriers cost 10-20 %), groups on the others. */
typedef enum { OB_CL_GROUPS, OB_CL_ITEMS } ob_cl_layout;
/* The layout $OFFBENCH_CL_LAYOUT names, groups or items, into *layout.
 * Returns 1; 0 when it is unset or empty (*layout unchanged); -1 with the
 * variable and its value in err->msg when it is anything else. */
int ob_cl_layout_env(ob_cl_layout *layout, ob_err *err);
void ob_cl_set_layout(ob_cl *cl, ob_cl_layout layout);
ob_cl_layout ob_cl_get_layout(const ob_cl *cl);
const char *ob_cl_layout_name(ob_cl_layout layout); /* "groups", "items" */
/* Work-items per group in the group layout (the device's limit for the
 * kernel, at most 64; the least over the group-layout programs built so
 * far, 0 before any). */
int ob_cl_group_size(const ob_cl *cl);

/* ---- the programs: one per metric and layout, built when first used ----
 *
 * A program holds one sampled metric's code in one layout's kernel
 * (kernels/measure.cl built with -D OBC_ONLY_<METRIC> -D OBC_ONLY_<LAYOUT>):
 * the whole kernel with every metric in both layouts took NVIDIA's compiler
 * about three minutes (issue 40; kernels/README.md "Build time").  Each is
 * kept in the binary cache under its own key (the options are in it). */

/* Purpose: the build options of the program of sampled metric m in layout
 *          l into buf: "-cl-std=CL1.2 -D OBC_ONLY_<METRIC> -D OBC_ONLY_<LAYOUT>".
 * Returns: 0; -1 when m is no sampled metric (bound). */
int ob_cl_program_options(ob_metric m, ob_cl_layout l, char *buf, size_t len);

/* Purpose: the binary cache's key (clcache.h) of a program: the platform,
 *          device, driver and device version, the build options and the
 *          source (its length and FNV-1a hash), one "name=value" a line.
 * Returns: a malloc'ed text, NULL without memory. */
char *ob_cl_program_key(const char *platform, const char *device, const char *driver, const char *device_version,
                        const char *options, const char *src);

/* Purpose: build the program of sampled metric m in layout l, from the
 *          binary cache when it holds it, and launch it once (a driver that
 *          compiles at the first launch, as PoCL does, does it here); nothing
 *          when it is built already.  A run prepares its metric before any
 *          timed work (select.h); a batch prepares its records' metrics.
 * Returns: 0; -1 with the reason in err->msg (the build log of a failed
 *          build, which is not tried again; m no sampled metric); -2 when
 *          a call failed for want of memory. */
int ob_cl_prepare(ob_cl *cl, ob_metric m, ob_cl_layout l, ob_err *err);

/* One program's build, for the build report (meta.json, bench). */
typedef struct {
    ob_metric metric;
    ob_cl_layout layout;
    double seconds;      /* the build, or the load from the cache, and its first launch */
    char cache[600];     /* what the binary cache did, as ob_cl_cache_status says it */
} ob_cl_build;

/* Purpose: the programs built so far, in the order built, into out[0 ..
 *          max - 1].  Returns their number (all of them, even beyond max). */
int ob_cl_builds(const ob_cl *cl, ob_cl_build *out, int max);

/* Purpose: the bytes a record of base degree nb and approximation degree
 *          na moves: to the device (its control points, degrees, offsets,
 *          d, stop and metric) into *to, back from it (error, parameter,
 *          work) into *back; scratch stays on the device. */
void ob_cl_record_bytes(int nb, int na, size_t *to, size_t *back);

/* Purpose: the device's double-precision peak: kernels of their own (their
 *          own program, cached), many work-items each running 8 independent
 *          chains of multiply-adds (mad), counted as 2 flops each, on
 *          doubles and on double8 (a CPU device's vectors), the faster
 *          counting; each launched once untimed (the first launch), then
 *          sized to run about target_s seconds, timed by its profiling event.
 * Outputs: *flops counted, *seconds the kernel's own time.
 * Returns: 0; -1 with the reason in err->msg. */
int ob_cl_fma_peak(ob_cl *cl, double target_s, double *flops, double *seconds, ob_err *err);

/* The driver's batch backend (ob_batch_fn): ctx is an ob_cl*.  Submits in
 * slot 0 and waits. */
int ob_cl_measure_batch(void *ctx, const ob_measure_rec *recs, int n, int samples, ob_errval *out);

/* Batches in flight at once: one measured on the device while the host
 * prepares the next (the overlap engine, driver.h). */
enum { OB_CL_SLOTS = 2 };

/* Purpose: start measuring n records in slot 0 or 1 and return at once: the
 *          records' data is copied (recs may change after), the commands
 *          flushed to the device.
 * Returns: 0; -1 (a failing call, named by ob_info; the slot busy or out of
 *          range): nothing is in flight in the slot, measure on the CPU. */
int ob_cl_submit(ob_cl *cl, int slot, const ob_measure_rec *recs, int n, int samples);

/* Purpose: wait for the slot's batch: out[0..n-1] as ob_measure_until
 *          gives them; *device_ns the kernel's own time from its profiling
 *          event (0 when the driver gives none).
 * Returns: 0; -1 when nothing was in flight or a call failed (measure the
 *          batch on the CPU). */
int ob_cl_wait(ob_cl *cl, int slot, ob_errval *out, double *device_ns);

/* The same as the driver's asynchronous backend (ob_driver_hooks): ctx is
 * an ob_cl*. */
int ob_cl_batch_submit(void *ctx, int slot, const ob_measure_rec *recs, int n, int samples);
int ob_cl_batch_wait(void *ctx, int slot, ob_errval *out, double *device_ns);

#endif
