/*
 * test_sisl_request.c - the sisl server's request handler (methods/sisl/
 * server.c, ob_sisl_serve) given crafted requests directly: each bad field
 * (a degree past the fixed arrays, negative counts, NaN and infinite values,
 * a wrong magic, a truncated or overlong request) must be answered with
 * OB_SISL_BAD_REQUEST naming that field, no curve, and no crash (the
 * sanitizer build runs this too: a degree of 1000 overflowed a stack array
 * before).  A good request gets s1360's curve.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "methods/sisl/proto.h"
#include "tests/check.h"

static const double LIU[4][2] = {{-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};

static sisl_request good(void)
{
    sisl_request q;
    memset(&q, 0, sizeof q);
    q.magic = OB_SISL_REQ_MAGIC;
    q.n = 3;
    q.d = 1.0;
    q.tol = 1e-2;
    q.timeout = 20.0;
    for (int i = 0; i < 4; i++)
        q.coef[2 * i] = LIU[i][0], q.coef[2 * i + 1] = LIU[i][1];
    return q;
}

/* The handler's answer to len bytes of q: its header (stat 1 when none
 * came), and the rest of the reply read away. */
static sisl_reply_hdr ask(const sisl_request *q, size_t len)
{
    sisl_reply_hdr h = {1, 0, 0, 0, 0, 0};
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM, 0, sv) != 0)
        return h;
    const int rc = ob_sisl_serve(q, len, sv[1], 0);
    close(sv[1]);
    double spent;
    if (rc != 0 || read(sv[0], &h, sizeof h) != (ssize_t)sizeof h || read(sv[0], &spent, sizeof spent) != sizeof spent)
        h.stat = 1;
    char sink[4096];
    while (read(sv[0], sink, sizeof sink) > 0)
        ;
    close(sv[0]);
    return h;
}

static void refused(const sisl_request *q, size_t len, const char *field, const char *what)
{
    const sisl_reply_hdr h = ask(q, len);
    const int f = OB_SISL_BAD_REQUEST - h.stat;
    CHECK(h.stat <= OB_SISL_BAD_REQUEST && h.ik == 0 && strcmp(ob_sisl_field_name(f), field) == 0,
          "%s: status %d (field '%s'), order %d: want refused, field '%s'", what, h.stat,
          h.stat <= OB_SISL_BAD_REQUEST ? ob_sisl_field_name(f) : "-", h.ik, field);
}

int main(void)
{
    sisl_request q = good();
    sisl_reply_hdr h = ask(&q, sizeof q);
    CHECK(h.stat >= 0 && h.ik == 4 && h.in > 4 && h.idim == 2, "a good request: status %d, order %d, %d vertices",
          h.stat, h.ik, h.in);

    static const int degrees[] = {-1, -2147483647 - 1, OB_MAX_DEG + 1, 1000, 2147483647};
    for (size_t k = 0; k < sizeof degrees / sizeof degrees[0]; k++) {
        q = good(), q.n = degrees[k];
        char what[64];
        snprintf(what, sizeof what, "degree %d", degrees[k]);
        refused(&q, sizeof q, "degree", what);
    }
    q = good(), q.rational = 2;
    refused(&q, sizeof q, "rational", "rational 2");
    q = good(), q.rational = -1;
    refused(&q, sizeof q, "rational", "rational -1");
    q = good(), q.magic = 0;
    refused(&q, sizeof q, "magic", "magic 0");
    q = good(), q.d = NAN;
    refused(&q, sizeof q, "d", "d NaN");
    q = good(), q.tol = INFINITY;
    refused(&q, sizeof q, "tol", "tol inf");
    q = good(), q.amax = -1.0;
    refused(&q, sizeof q, "max_step", "max_step -1");
    q = good(), q.amax = NAN;
    refused(&q, sizeof q, "max_step", "max_step NaN");
    q = good(), q.timeout = 0.0;
    refused(&q, sizeof q, "timeout", "timeout 0");
    q = good(), q.timeout = NAN;
    refused(&q, sizeof q, "timeout", "timeout NaN");
    q = good(), q.timeout = 1e300;
    refused(&q, sizeof q, "timeout", "timeout 1e300");
    q = good(), q.test_sleep = -1.0;
    refused(&q, sizeof q, "test hook", "test_sleep -1");
    q = good(), q.test_spin = NAN;
    refused(&q, sizeof q, "test hook", "test_spin NaN");
    q = good(), q.coef[5] = NAN;
    refused(&q, sizeof q, "coefficient", "a NaN coefficient");
    q = good(), q.rational = 1, q.coef[11] = INFINITY;
    refused(&q, sizeof q, "coefficient", "an infinite weight");
    q = good();
    refused(&q, sizeof q - 1, "length", "a request one byte short");
    refused(&q, 3, "length", "3 bytes");
    refused(&q, 0, "length", "no bytes");
    struct {
        sisl_request q;
        char extra[8];
    } big;
    memset(&big, 0, sizeof big);
    big.q = good();
    refused(&big.q, sizeof big, "length", "a request 8 bytes long");

    /* unused coefficients past the degree are not read: NaN there is fine */
    q = good(), q.coef[3 * OB_MAX_DEG] = NAN;
    h = ask(&q, sizeof q);
    CHECK(h.stat >= 0 && h.ik == 4, "NaN past the degree's coefficients: status %d", h.stat);
    /* SISL refuses a tolerance <= 0 itself (status -184), the fit reports it */
    q = good(), q.tol = -1.0;
    h = ask(&q, sizeof q);
    CHECK(h.stat < 0 && h.stat > OB_SISL_BAD_REQUEST, "tol -1 reaches s1360: status %d", h.stat);
    return check_done();
}
