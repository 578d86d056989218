/*
 * stack.c - the thread stack check.  See stack.h.
 */
#include "host/run/stack.h"

#include <ctype.h>
#include <stdlib.h>
#include <sys/resource.h>

#include "host/diag.h"

int ob_stacksize_parse(const char *s, unsigned long long *bytes)
{
    const unsigned char *p = (const unsigned char *)s;
    while (isspace(*p))
        p++;
    if (*p == '+')
        p++;
    if (!isdigit(*p))
        return -1;
    unsigned long long v = 0;
    for (; isdigit(*p); p++) {
        if (v > (~0ull - 9) / 10)
            return -1;
        v = v * 10 + (unsigned)(*p - '0');
    }
    while (isspace(*p))
        p++;
    int shift = 10; /* kilobytes unless a suffix says otherwise */
    if (*p) {
        switch (tolower(*p++)) {
        case 'b': shift = 0; break;
        case 'k': shift = 10; break;
        case 'm': shift = 20; break;
        case 'g': shift = 30; break;
        default: return -1;
        }
        while (isspace(*p))
            p++;
        if (*p)
            return -1;
    }
    if (v > (~0ull >> shift))
        return -1;
    *bytes = v << shift;
    return 0;
}

/* The variable that sizes the OpenMP workers' stacks, as libgomp picks it. */
static int check_variable(void)
{
    const char *name = "OMP_STACKSIZE", *v = getenv(name);
    if (!v) {
        name = "GOMP_STACKSIZE";
        v = getenv(name);
    }
    if (!v)
        return 0;
    unsigned long long b;
    if (ob_stacksize_parse(v, &b) != 0) {
        ob_error("%s='%.40s': not a stack size (a number with an optional B, K, M or G; K by default); "
                 "offbench needs at least %lluK",
                 name, v, OB_STACK_MIN_KIB);
        return -1;
    }
    if (b < OB_STACK_MIN) {
        ob_error("%s='%.40s' is below the %lluK of stack each offbench thread needs (its threads would crash); "
                 "set %s=%lluK or more, or unset it",
                 name, v, OB_STACK_MIN_KIB, name, OB_STACK_MIN_KIB);
        return -1;
    }
    return 0;
}

int ob_stack_check(void)
{
    if (check_variable() != 0)
        return -1;
    struct rlimit r;
    if (getrlimit(RLIMIT_STACK, &r) == 0 && r.rlim_cur != RLIM_INFINITY && r.rlim_cur < OB_STACK_MIN) {
        ob_error("the stack limit (ulimit -s) is %lluK, below the %lluK offbench needs (its threads would crash); "
                 "raise it: ulimit -s %llu",
                 (unsigned long long)r.rlim_cur / 1024, OB_STACK_MIN_KIB, OB_STACK_MIN_KIB);
        return -1;
    }
    return 0;
}
