/*
 * clprobe.h - why an installed OpenCL platform did not start, for the
 * backend's messages and exit status (issue 48): out of memory is not a
 * missing ICD.
 *
 * Under an address-space limit (ulimit -v) PoCL fails three ways (PoCL
 * 3.1): the ICD loader cannot map libpocl and says CL_PLATFORM_NOT_FOUND_KHR,
 * as it does when no ICD is installed; clGetDeviceIDs says
 * CL_OUT_OF_HOST_MEMORY; or PoCL aborts (no error code) when it cannot
 * start its threads.  The first is told apart here by loading the ICDs'
 * libraries again; the last by trying the platform in a child process first
 * whenever the address space is limited.
 */
#ifndef OB_CLPROBE_H
#define OB_CLPROBE_H

#include <stddef.h>

#include "methods/core/err.h"

/* Purpose: " (the address space is limited to N MiB: ulimit -v)" into buf,
 *          or "" when it is not limited.
 * Returns: 1 when it is limited, else 0. */
int ob_as_limit(char *buf, size_t len);

/* Purpose: whether a dlopen failure (its dlerror text) is for want of
 *          memory: said so, or a segment that could not be mapped while
 *          the address space is limited.  1 or 0. */
int ob_dl_oom(const char *dlerr);

/* Purpose: why the ICD loader found no OpenCL platform, into msg: no ICD
 *          installed ($OCL_ICD_FILENAMES, else the .icd files of
 *          $OCL_ICD_VENDORS or /etc/OpenCL/vendors), an ICD's library that
 *          cannot be loaded (both named), out of memory, or libraries that
 *          load but give no platform.
 * Returns: 1 when it is out of memory (the run exits 1), else 0. */
int ob_cl_no_platform_why(char *msg, size_t len);

/* Purpose: when the address space is limited, run fn(ctx, err) in a child
 *          process first (fork), so that a platform that aborts on
 *          starting ends the child, not the run.  fn returns 0, -1 or -2.
 * Outputs: when the child ended normally, *rc what fn returned there and,
 *          when that is not 0, err its message: the caller takes the
 *          child's failure rather than risk the abort itself.
 * Returns: 0 (the child ended normally), -1 (not tried: no limit, no
 *          fork: do it here), or the signal that ended the child. */
int ob_cl_try_in_child(int (*fn)(void *, ob_err *), void *ctx, int *rc, ob_err *err);

#endif
