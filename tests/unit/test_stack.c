/*
 * test_stack.c - host/run/stack.c: OMP_STACKSIZE read as libgomp reads it
 * (a number, optional blanks, an optional B/K/M/G suffix in either case, K
 * by default), anything else refused; and the check refuses a size below
 * OB_STACK_MIN, a malformed one, and takes GOMP_STACKSIZE when
 * OMP_STACKSIZE is unset.
 */
#include <stdlib.h>
#include <string.h>

#include "host/diag.h"
#include "host/run/stack.h"
#include "tests/check.h"

static char said[512];
static void capture(const char *m) { snprintf(said, sizeof said, "%s", m); }

static void test_parse(void)
{
    static const struct {
        const char *text;
        unsigned long long bytes;
    } good[] = {
        {"64K", 64ull << 10}, {"64k", 64ull << 10}, {"64", 64ull << 10},     {"100B", 100},
        {"2M", 2ull << 20},   {"1g", 1ull << 30},   {" 512 K ", 512ull << 10}, {"0", 0},
        {"16 M", 16ull << 20},
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        unsigned long long b = 1;
        CHECK(ob_stacksize_parse(good[i].text, &b) == 0 && b == good[i].bytes, "'%s': %llu", good[i].text, b);
    }
    static const char *const bad[] = {"",    "K",  "abc", "1X",   "1KB", "-1",  "+-1", "1.5M",
                                      "1 2", "0x10", "99999999999999999999", "17179869184G", "1e3"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        unsigned long long b = 7;
        CHECK(ob_stacksize_parse(bad[i], &b) == -1, "'%s' refused (got %llu)", bad[i], b);
    }
}

/* ob_stack_check with OMP_STACKSIZE and GOMP_STACKSIZE as given (NULL:
 * unset); returns its status, the message in said. */
static int check_with(const char *omp, const char *gomp)
{
    said[0] = 0;
    if (omp)
        setenv("OMP_STACKSIZE", omp, 1);
    else
        unsetenv("OMP_STACKSIZE");
    if (gomp)
        setenv("GOMP_STACKSIZE", gomp, 1);
    else
        unsetenv("GOMP_STACKSIZE");
    return ob_stack_check();
}

static void test_check(void)
{
    ob_set_error_handler(capture);
    CHECK(check_with(NULL, NULL) == 0, "unset: fine (%s)", said);
    CHECK(check_with("64K", NULL) == -1 && strstr(said, "OMP_STACKSIZE") && strstr(said, "512K"),
          "64K: refused, naming the variable and the minimum: %s", said);
    CHECK(check_with("16k", NULL) == -1 && strstr(said, "16k"), "16k refused, the value quoted: %s", said);
    CHECK(check_with("511K", NULL) == -1, "just below the minimum: %s", said);
    CHECK(check_with("512K", NULL) == 0, "the minimum itself: %s", said);
    CHECK(check_with("524288B", NULL) == 0, "the minimum in bytes: %s", said);
    CHECK(check_with("1G", NULL) == 0, "a large size: %s", said);
    CHECK(check_with("lots", NULL) == -1 && strstr(said, "OMP_STACKSIZE") && strstr(said, "'lots'"),
          "a malformed size: %s", said);
    CHECK(check_with("", NULL) == -1 && strstr(said, "OMP_STACKSIZE"), "an empty size: %s", said);
    CHECK(check_with(NULL, "64K") == -1 && strstr(said, "GOMP_STACKSIZE"), "GOMP_STACKSIZE when OMP's is unset: %s",
          said);
    CHECK(check_with("8M", "64K") == 0, "OMP_STACKSIZE wins over GOMP_STACKSIZE (as in libgomp): %s", said);
    CHECK(check_with(NULL, "4M") == 0, "GOMP_STACKSIZE large enough: %s", said);
    ob_set_error_handler(NULL);
    unsetenv("OMP_STACKSIZE");
    unsetenv("GOMP_STACKSIZE");
}

int main(void)
{
    test_parse();
    test_check();
    return check_done();
}
