/*
 * check.h - the tiny assertion layer every C test program uses.
 *
 * Each CHECK counts one pass or one failure; failures print file:line and the
 * expression.  check_done() prints "N passed, N failed[, N skipped]" and
 * returns the exit status.  tests/run_all.sh sums those lines over programs.
 */
#ifndef OB_CHECK_H
#define OB_CHECK_H

#include <math.h>
#include <stdio.h>

#include "host/san_options.h"

static int check_passed, check_failed, check_skipped;

#define CHECK(cond, ...)                                                      \
    do {                                                                      \
        if (cond) {                                                           \
            check_passed++;                                                   \
        } else {                                                              \
            check_failed++;                                                   \
            fprintf(stderr, "%s:%d: FAIL: %s: ", __FILE__, __LINE__, #cond);  \
            fprintf(stderr, __VA_ARGS__);                                     \
            fputc('\n', stderr);                                              \
        }                                                                     \
    } while (0)

/* |a - b| <= tol, with both values printed on failure. */
#define CHECK_NEAR(a, b, tol, what)                                           \
    do {                                                                      \
        double check_a_ = (a), check_b_ = (b);                                \
        CHECK(fabs(check_a_ - check_b_) <= (tol), "%s: %.17g vs %.17g (tol %g)", \
              (what), check_a_, check_b_, (double)(tol));                     \
    } while (0)

#define SKIP(why)                                                             \
    do {                                                                      \
        check_skipped++;                                                      \
        fprintf(stderr, "%s:%d: SKIP: %s\n", __FILE__, __LINE__, (why));      \
    } while (0)

static inline int check_done(void)
{
    if (check_skipped)
        printf("%d passed, %d failed, %d skipped\n", check_passed, check_failed, check_skipped);
    else
        printf("%d passed, %d failed\n", check_passed, check_failed);
    return check_failed ? 1 : 0;
}

#endif
