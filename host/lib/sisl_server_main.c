/*
 * sisl_server_main.c - build/offbench-sisl-server: the sisl method's server
 * for processes that do not link the method (liboffbench loaded by python;
 * host/lib/sisl_exe.h).  The method's constructor (methods/sisl.c) serves
 * before main when the process was started as a server; run otherwise, it
 * only says what it is.
 */
#include <stdio.h>

int main(void)
{
    fputs("offbench-sisl-server: started by liboffbench's sisl fits (OFFBENCH_SISL_SERVER), not by hand\n", stderr);
    return 2;
}
