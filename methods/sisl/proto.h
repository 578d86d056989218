/*
 * proto.h - the sisl method's server protocol (methods/sisl.c fits, the
 * server in methods/sisl/server.c, the client in methods/sisl/client.c).
 *
 * One AF_UNIX stream socket per server, the server's end at descriptor
 * OB_SISL_FD.  Start: the client executes the server program with argv[0]
 * OB_SISL_ARGV0 and a fresh random secret in OB_SISL_ENV; the server checks
 * that descriptor (a socket made by its parent) and writes the handshake
 * (OB_SISL_HELLO and the secret), which the client compares.  Then
 * requests (sisl_request) and replies (sisl_reply_hdr, the fit's CPU time,
 * then in + ik knots and in * idim coefficients when ik > 0).
 */
#ifndef OB_SISL_PROTO_H
#define OB_SISL_PROTO_H

#include <stddef.h>
#include <stdint.h>

#include "methods/core/curve.h"

#define OB_SISL_ENV "OFFBENCH_SISL_SERVER"
#define OB_SISL_ARGV0 "offbench-sisl-server"
#define OB_SISL_HELLO "OBSS"
#define OB_SISL_EXECFAIL "EXEC"
enum { OB_SISL_FD = 3, OB_SISL_SECRET = 32 /* hex digits */ };
enum { OB_SISL_REQ_MAGIC = 0x5153424f /* "OBSQ" */ };

/* The largest reply the client accepts (s1360's cubic: order 4, dimension
 * 2; a bound on the vertices keeps a broken reply from a huge allocation). */
enum { OB_SISL_MAX_ORDER = 16, OB_SISL_MAX_DIM = 4, OB_SISL_MAX_VERTICES = 1 << 22 };

/* A request: the base segment as SISL wants it, and s1360's arguments. */
typedef struct {
    uint32_t magic;     /* OB_SISL_REQ_MAGIC */
    int n, rational;    /* degree 0..OB_MAX_DEG; 0 or 1 */
    double d, tol, amax;
    double timeout;     /* CPU seconds the call may take (RLIMIT_CPU in the server) */
    double test_sleep;  /* test hooks: wall seconds the server sleeps, CPU seconds it */
    double test_spin;   /* spins, before the call (docs/contributing.md "Testing") */
    double coef[3 * (OB_MAX_DEG + 1)];
} sisl_request;

/* The reply's header: s1360's status, the curve's order, vertices,
 * dimension and kind (ik 0: no curve), and 1 when the server asks to be
 * started afresh (it has grown). */
typedef struct {
    int stat, ik, in, idim, ikind, restart;
} sisl_reply_hdr;

/* The status of a request the server refused (never s1360's: its statuses
 * are small): OB_SISL_BAD_REQUEST - the field's number (ob_sisl_field_name). */
enum { OB_SISL_BAD_REQUEST = -10000 };

/* Purpose: whether every field of a request of len bytes is in range.
 * Returns: 0, or the number (>= 1) of the first bad field. */
int ob_sisl_check_request(const sisl_request *q, size_t len);
const char *ob_sisl_field_name(int field);

/* Purpose: answer one request of len bytes on fd (the reply above; a bad
 *          request gets a header with OB_SISL_BAD_REQUEST - field and no
 *          curve).  data0: the server's data size at its start.
 * Returns: 0, or -1 when the reply could not be written or the client went
 *          away during the test hook's sleep (the server then ends). */
int ob_sisl_serve(const void *req, size_t len, int fd, unsigned long data0);

/* s1360's result as plain arrays (ik order, in vertices, idim, ikind). */
typedef struct {
    int stat, ik, in, idim, ikind;
    double *et, *ecoef;     /* in + ik knots, idim * in coefficients (malloc) */
} sisl_result;

/* How a call ended (ob_sisl_call). */
typedef enum {
    OB_SISL_OK = 0,     /* *r filled */
    OB_SISL_WALL,       /* past the wall-clock cap: the server was killed */
    OB_SISL_DIED,       /* the server ended during the call: *wstatus says how */
    OB_SISL_ERROR       /* no server, or a broken reply: why in msg */
} ob_sisl_outcome;

/* Purpose: s1360 on this thread's server (started on first use, in this
 *          process: a forked child never uses its parent's), the reply read
 *          within `wall` seconds.  *wstatus: the server's wait status when
 *          OB_SISL_DIED (-1: unknown). */
ob_sisl_outcome ob_sisl_call(const sisl_request *q, double wall, sisl_result *r, int *wstatus, char *msg,
                             size_t msglen);

/* A wait status in words: "killed by signal 9 (Killed)", "exit status 3"
 * ("status unknown" for -1). */
void ob_sisl_describe_wait(int ws, char *buf, size_t len);

/* Writes exactly n bytes to the socket fd: 0, or -1 when the peer is gone
 * (no SIGPIPE) or on an error (io.c). */
int ob_sisl_send_all(int fd, const void *buf, size_t n);
/* Reads n bytes from fd before the monotonic deadline (s): 0, 1 timed out,
 * -1 EOF or an error (io.c). */
int ob_sisl_read_deadline(int fd, void *buf, size_t n, double deadline);
double ob_sisl_now(void);

#endif
