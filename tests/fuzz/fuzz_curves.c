/*
 * fuzz_curves.c - libFuzzer target: the curve-file reader (host/io/curvefile.c)
 * on arbitrary bytes must return 0 or -1 with a FILE:LINE message, never
 * crash, overrun or leak (built with ASan + UBSan by `make fuzz`).  Each
 * parsed set is also cleared and parsed again into a non-empty set, so the
 * duplicate-id path sees the same input.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "host/io/curvefile.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ob_curveset set;
    ob_err err;
    memset(&set, 0, sizeof set);
    err.msg[0] = '\0';
    int rc = ob_curves_parse((const char *)data, size, "fuzz.curves", &set, &err);
    if (rc != 0 && strncmp(err.msg, "fuzz.curves:", 12) != 0)
        __builtin_trap();  /* every error names the file and line */
    if (rc == 0 && set.n > 0 && ob_curves_parse((const char *)data, size, "again.curves", &set, &err) == 0)
        __builtin_trap();  /* the same ids twice must be refused */
    ob_curveset_free(&set);
    return 0;
}
