/*
 * sisl_server_main.c - build/offbench-sisl-server: the sisl method's server
 * for processes that do not link the method (liboffbench loaded by python;
 * host/lib/sisl_exe.h).  The method's constructor (methods/sisl/server.c)
 * serves before main when the process was started as a server (argv[0],
 * a socket from its parent and the handshake's secret); run otherwise, it
 * only says what it is.
 */
#include <stdio.h>

int main(void)
{
    fputs("offbench-sisl-server: started by the sisl method's fits (a socket and a secret from its parent), "
          "not by hand\n", stderr);
    return 2;
}
