/*
 * sisl_server.h - where the sisl method's server process comes from.
 *
 * The sisl method fits in a server process (methods/sisl/client.c): by default
 * this program executed afresh (/proc/self/exe), whose constructor serves.
 * A process that does not link the method itself (python with
 * liboffbench.so loaded: its /proc/self/exe is python) names a program that
 * does: build/offbench-sisl-server or ./offbench (host/lib/sisl_exe.c).
 */
#ifndef OB_SISL_SERVER_H
#define OB_SISL_SERVER_H

/* Purpose: the program every later server start executes (NULL: back to
 *          /proc/self/exe).  The string must stay valid.  Not thread-safe:
 *          call it once, before any fit. */
void ob_sisl_set_server_exe(const char *path);

#endif
