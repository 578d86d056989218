/*
 * registry.c - the list of all methods (read from registry.def: adding a
 * method is one line there) and the helpers every method file shares.
 */
#include "methods/method.h"

#include <stdarg.h>
#include <stdio.h>
#include <math.h>
#include <string.h>

/* The methods of registry.def: first their declarations, then the list. */
#define OB_METHOD(id) extern const ob_method ob_method_##id;
#include "methods/registry.def"
#undef OB_METHOD

/* Room after the built-ins for the methods registered at run time
 * (ob_method_register: external methods, docs/external-methods.md); they
 * come after every built-in, so no built-in's position (the order of jobs
 * and rows) moves. */
enum {
    OB_NBUILTIN = 0
#define OB_METHOD(id) + 1
#include "methods/registry.def"
#undef OB_METHOD
};
const ob_method *ob_methods[OB_NBUILTIN + OB_MAX_EXTERNAL + 1] = {
#define OB_METHOD(id) &ob_method_##id,
#include "methods/registry.def"
#undef OB_METHOD
    NULL,
};

int ob_method_register(const ob_method *m)
{
    const int n = ob_method_count();
    if (n >= OB_NBUILTIN + OB_MAX_EXTERNAL || ob_method_find(m->name))
        return -1;
    /* the terminator first, then the entry, published with release order: a
     * thread walking the list meanwhile (a run of the library) sees the old
     * list or the new one, never a half-written entry */
    ob_methods[n + 1] = NULL;
    __atomic_store_n(&ob_methods[n], m, __ATOMIC_RELEASE);
    return 0;
}

const ob_method *ob_method_find(const char *name)
{
    for (int i = 0; ob_methods[i]; i++)
        if (strcmp(ob_methods[i]->name, name) == 0)
            return ob_methods[i];
    return NULL;
}

int ob_method_index(const ob_method *m)
{
    for (int i = 0; ob_methods[i]; i++)
        if (ob_methods[i] == m)
            return i;
    return -1;
}

int ob_param_find(const ob_method *m, const char *name)
{
    for (int i = 0; i < m->nparams; i++)
        if (strcmp(m->params[i].name, name) == 0)
            return i;
    return -1;
}

int ob_param_check(const ob_method *m, const ob_param *p, double v, char *msg, size_t msglen)
{
    if (isfinite(v) && v >= p->min && v <= p->max && (!p->integer || v == floor(v)))
        return 0;
    if (p->integer)
        ob_method_msg(msg, msglen, "%s.%s = %g is out of range: a whole number from %.17g to %.17g", m->name,
                      p->name, v, p->min, p->max);
    else
        ob_method_msg(msg, msglen, "%s.%s = %g is out of range: a number from %.17g to %.17g", m->name, p->name,
                      v, p->min, p->max);
    return -1;
}

void ob_param_defaults(const ob_method *m, double *par)
{
    for (int i = 0; i < OB_MAX_PARAMS; i++)
        par[i] = i < m->nparams ? m->params[i].def : 0.0;
}

int ob_method_count(void)
{
    int n = 0;
    while (ob_methods[n])
        n++;
    return n;
}

const char *ob_fit_status_name(ob_fit_status s)
{
    switch (s) {
    case OB_FIT_OK: return "ok";
    case OB_FIT_FAIL: return "fail";
    case OB_FIT_SKIP: return "skip";
    case OB_FIT_RETRY_SMALLER: return "retry-smaller";
    case OB_FIT_TIMEOUT: return "timeout";
    }
    return "?";
}

int ob_fit_uses_tol_always(const double *par)
{
    (void)par;
    return 1;
}

int ob_method_fit_uses_tol(const ob_method *m, const double *par)
{
    if (!m->fit_uses_tol)
        return 0;
    double defaults[OB_MAX_PARAMS];
    if (!par) {
        ob_param_defaults(m, defaults);
        par = defaults;
    }
    return m->fit_uses_tol(par) != 0;
}

int ob_degree_same(int n, int rational_in, const double *par)
{
    (void)rational_in;
    (void)par;
    return n;
}

int ob_degree_three(int n, int rational_in, const double *par)
{
    (void)n;
    (void)rational_in;
    (void)par;
    return 3;
}

int ob_degree_or_param(int n, double pd)
{
    return pd >= 0.5 ? (int)lround(pd) : n;
}

int ob_method_out_degree(const ob_method *m, int n, int rational_in, const double *par)
{
    double defaults[OB_MAX_PARAMS];
    if (!par) {
        ob_param_defaults(m, defaults);
        par = defaults;
    }
    return m->out_degree(n, rational_in, par);
}

void ob_fit_single(ob_fit *out, const ob_bez *seg)
{
    out->n = 1;
    out->ctrl_points = 0;
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

/* The calling thread's CPU time spent outside it by its fits (method.h). */
static _Thread_local double foreign_ns;

void ob_fit_foreign_add(double ns) { foreign_ns += ns; }

double ob_fit_foreign_ns(void) { return foreign_ns; }

/* The job's --job-timeout budget for the calling thread's fits (method.h). */
static _Thread_local double budget_ns;

void ob_fit_budget_set(double ns) { budget_ns = ns; }

double ob_fit_budget_ns(void) { return budget_ns; }
