/*
 * select.h - which backend measures a run's sampled metrics: the OpenCL
 * kernel (clrt.h) when one is asked for or found, otherwise the CPU
 * reference path; what was chosen and why, for meta.json.
 */
#ifndef OB_SELECT_H
#define OB_SELECT_H

#include "host/backend/clrt.h"
#include "methods/driver/driver.h"

typedef enum { OB_BACKEND_AUTO = 0, OB_BACKEND_OPENCL, OB_BACKEND_CPU } ob_backend;

/* What measured the run, for meta.json (filled by ob_open_backend). */
typedef struct {
    int opencl;                  /* 0: the CPU reference path */
    char platform[256], device[256], driver[128], kernels[512];
    uint64_t kernel_hash;        /* of the kernel text: the one built, or the
                                    compiled-in one on the CPU (kernsrc.h) */
    char layout[16];             /* the kernel's layout: groups or items (clrt.h) */
    int group_size;              /* work-items per record in the group layout */
    int gpu;                     /* the device is a GPU or an accelerator */
    double build_seconds;        /* every program built at open, summed */
    char cache[600];             /* the program binary cache (ob_cl_cache_status) */
    ob_cl_build builds[8];       /* the programs built at open: the run's metrics in its layout */
    int nbuilds;
    long fallbacks;              /* batches the OpenCL backend gave back to the CPU */
    char why_cpu[512];           /* with auto: why OpenCL was not used */
} ob_backend_info;

/* Purpose: open the backend a run asks for (--backend kind, --device
 *          substring or NULL) and build the programs of the metrics it
 *          measures (metrics: a set of 1u << ob_metric; only the sampled
 *          ones have one) in the layout it runs, here, once, before any
 *          timed work: a run builds only what it uses (clrt.h).
 * Outputs: *cl, or NULL when the CPU measures; *b: what and why.
 * Returns: 0; -1 after ob_error() when OpenCL was required (kind opencl, or
 *          a device named) and cannot start or build, or $OFFBENCH_CL_LAYOUT
 *          is not a layout (unless kind is cpu); -2 after ob_error() when
 *          it was required and could not start for want of memory (the
 *          command exits 1, not 2: ob_backend_exit).  auto falls back to
 *          the CPU and says why in b->why_cpu. */
int ob_open_backend(ob_backend kind, const char *device, unsigned metrics, ob_backend_info *b, ob_cl **cl);

/* The exit status of a command whose ob_open_backend returned rc (not 0):
 * 1 out of memory, 2 otherwise. */
int ob_backend_exit(int rc);

/* Purpose: plug an opened OpenCL backend into a driver run's hooks (the
 *          batch measurer; batches given back counted in b->fallbacks).
 *          cl NULL: the CPU measures, h unchanged. */
void ob_backend_hooks(ob_cl *cl, ob_backend_info *b, ob_driver_hooks *h);

/* Pieces per batch on a GPU or accelerator (ob_driver_hooks.batch_chunk):
 * about 20,000 records a launch at the level engine's 2-3 pieces a fit. */
enum { OB_GPU_CHUNK = 8192 };

#endif
