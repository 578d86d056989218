/*
 * io.c - the sisl server protocol's transfers (proto.h), both sides.
 */
#include "methods/sisl/proto.h"

#include <errno.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

int ob_sisl_send_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        ssize_t k = send(fd, p, n, MSG_NOSIGNAL);  /* a peer gone: -1, never SIGPIPE */
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

double ob_sisl_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int ob_sisl_read_deadline(int fd, void *buf, size_t n, double deadline)
{
    char *p = buf;
    while (n > 0) {
        const double left = deadline - ob_sisl_now();
        if (left <= 0)
            return 1;
        struct pollfd pf = {fd, POLLIN, 0};
        int pr = poll(&pf, 1, left > 86400 ? 86400000 : (int)(left * 1000) + 1);
        if (pr < 0 && errno == EINTR)
            continue;
        if (pr == 0)
            continue;  /* the deadline is checked above */
        ssize_t r = pr < 0 ? -1 : read(fd, p, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        p += r;
        n -= (size_t)r;
    }
    return 0;
}

