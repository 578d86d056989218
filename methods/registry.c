/*
 * registry.c - the list of all methods.  Adding a method is one line here.
 */
#include "method.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

extern const ob_method ob_method_tiller, ob_method_cobb, ob_method_ahn;

const ob_method *const ob_methods[] = {
    &ob_method_tiller,
    &ob_method_cobb,
    &ob_method_ahn,
    NULL,
};

const ob_method *ob_method_find(const char *name)
{
    for (int i = 0; ob_methods[i]; i++)
        if (strcmp(ob_methods[i]->name, name) == 0)
            return ob_methods[i];
    return NULL;
}

int ob_method_count(void)
{
    int n = 0;
    while (ob_methods[n])
        n++;
    return n;
}

const char *ob_status_name(ob_status s)
{
    switch (s) {
    case OB_OK: return "ok";
    case OB_LIMIT: return "limit";
    case OB_FAIL: return "fail";
    case OB_SKIP: return "skip";
    }
    return "?";
}

int ob_degree_same(int n, int rational_in)
{
    (void)rational_in;
    return n;
}

void ob_fit_single(ob_fit *out, const ob_bez *seg)
{
    out->n = 1;
    out->t[0] = 0.0;
    out->t[1] = 1.0;
    out->seg[0] = *seg;
}

int ob_method_msg(char *msg, size_t msglen, const char *fmt, ...)
{
    if (!msg || msglen == 0)
        return 0;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(msg, msglen, fmt, ap);
    va_end(ap);
    return n;
}
