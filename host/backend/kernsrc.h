/*
 * kernsrc.h - the OpenCL kernel text a run uses and its hash.
 *
 * The copy compiled into the program is the default: a kernels/ directory in
 * the working directory or beside the program is not read, because a run
 * started beside another checkout would silently measure with another kernel
 * (issue 36).  $OFFBENCH_KERNELS names another directory on purpose; the
 * hash of the text used (kernel_fnv1a in meta.json and the resume
 * fingerprint) then tells the runs apart.
 */
#ifndef OB_KERNSRC_H
#define OB_KERNSRC_H

#include <stddef.h>
#include <stdint.h>

/* Purpose: metric_core.h then measure.cl, from the directory in
 *          $OFFBENCH_KERNELS when set, else the copies compiled in.
 *          *where gets "DIR" or "embedded copy of kernels/".
 * Returns: malloc'd text, or NULL (a file of $OFFBENCH_KERNELS unreadable,
 *          no memory): a named directory never falls back silently. */
char *ob_kernel_source(char *where, size_t wlen);

/* FNV-1a of a kernel text (kernel_fnv1a). */
uint64_t ob_kernel_hash(const char *src);

/* The hash of the compiled-in kernel text: the CPU path compiles the same
 * metric core (methods/metrics), so its runs record this one. */
uint64_t ob_embedded_kernel_hash(void);

#endif
