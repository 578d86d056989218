/*
 * test_grow.c - ob_grow (methods/core/grow.c): a growable array keeps its
 * elements as it doubles, grows only when full, and refuses a size that
 * would overflow without touching the array.
 */
#include <stdint.h>
#include <stdlib.h>

#include "methods/core/grow.h"
#include "tests/check.h"

static void test_push(void)
{
    double *v = NULL;
    size_t cap = 0, n = 0;
    int ok = 1;
    for (int i = 0; i < 1000 && ok; i++) {
        ok = ob_grow(&v, &cap, n, sizeof *v, 4) == 0;
        if (ok)
            v[n++] = 0.5 * i;
    }
    CHECK(ok && n == 1000, "1000 pushes (%zu)", n);
    CHECK(cap == 1024, "capacity doubles from 4: %zu", cap);
    int same = 1;
    for (size_t i = 0; i < n; i++)
        same &= v[i] == 0.5 * (double)i;
    CHECK(same, "the elements survive each realloc");
    const size_t before = cap;
    CHECK(ob_grow(&v, &cap, 10, sizeof *v, 4) == 0 && cap == before, "no growth while there is room");
    free(v);
}

static void test_overflow(void)
{
    char *v = malloc(8);
    char *const keep = v;
    size_t cap = 8;
    CHECK(ob_grow(&v, &cap, 8, SIZE_MAX / 8, 1) == -1, "a size past SIZE_MAX is refused");
    CHECK(v == keep && cap == 8, "and the array is left as it was");
    free(v);
}

int main(void)
{
    test_push();
    test_overflow();
    return check_done();
}
