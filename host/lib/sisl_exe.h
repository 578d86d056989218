/*
 * sisl_exe.h - liboffbench's choice of the sisl method's server program
 * (methods/sisl_server.h).
 */
#ifndef OB_LIB_SISL_EXE_H
#define OB_LIB_SISL_EXE_H

#include <stddef.h>

/* Purpose: make sure sisl fits can start their server, once per process:
 *          $OFFBENCH_SISL_EXE when set; else, when this code is part of the
 *          running program itself (./offbench, a test linked statically),
 *          that program; else offbench-sisl-server in the directory of the
 *          shared library holding this code (dladdr: build/), else in that
 *          directory's offbench/ (LIBDIR/offbench/, where make install puts it).
 * Returns: 0; -1 with the reason in why when no such program exists.
 * Threads: safe (pthread_once). */
int ob_lib_sisl_ready(char *why, size_t len);

#endif
