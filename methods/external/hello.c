/*
 * hello.c - an external method's metadata from its worker's first line
 * (docs/external-methods.md "Hello"): the worker says what it is, so that
 * registering it needs only its name and command.
 */
#include "methods/external/ext.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/external/json.h"

/* The supervisor's parameters (ext.h), after the worker's own. */
static const ob_param own_params[OB_EXT_OWN_PARAMS] = {
    {"wall_timeout", 10.0, "wall-clock seconds one fit may take; past it the worker is killed and the fit fails",
     0.01, 86400.0, 0},
    {"cpu_timeout", 10.0, "CPU seconds one fit may take (RLIMIT_CPU of the worker; the job's --job-timeout "
     "budget when smaller)", 0.01, 86400.0, 0},
    {"mem_mb", 4096.0, "the worker's address space in MiB (RLIMIT_AS; 0: no cap)", 0.0, 1048576.0, 1},
};

static const struct {
    const char *name;
    unsigned cap;
} cap_names[] = {
    {"poly_out", OB_CAP_POLY_OUT},         {"rational_out", OB_CAP_RATIONAL_OUT},
    {"rational_in", OB_CAP_RATIONAL_IN},   {"convex", OB_CAP_CONVEX},
    {"same_param", OB_CAP_SAME_PARAM},     {"oriented", OB_CAP_ORIENTED},
    {"tol_driven", OB_CAP_TOL_DRIVEN},     {"cusp_breaks", OB_CAP_CUSP_BREAKS},
    {"interp_ends", OB_CAP_INTERP_ENDS},   {"nonmonotone", OB_CAP_NONMONOTONE},
};

const char *ob_ext_cap_name(unsigned cap)
{
    for (size_t k = 0; k < sizeof cap_names / sizeof cap_names[0]; k++)
        if (cap_names[k].cap == cap)
            return cap_names[k].name;
    return NULL;
}

static char *dup_str(const obj_node *v, const char *def)
{
    return strdup(v && v->type == OBJ_STR ? v->str : def);
}

static int caps_of(const obj_node *v, unsigned *caps, char *msg, size_t msglen)
{
    *caps = 0;
    for (int i = 0; v && i < v->n; i++) {
        int k = 0, nk = (int)(sizeof cap_names / sizeof cap_names[0]);
        while (k < nk && !(v->kids[i]->type == OBJ_STR && strcmp(v->kids[i]->str, cap_names[k].name) == 0))
            k++;
        if (k == nk) {
            ob_method_msg(msg, msglen, "\"caps\"[%d] is not one of poly_out, rational_out, rational_in, convex, "
                          "same_param, oriented, tol_driven, cusp_breaks, interp_ends, nonmonotone", i);
            return -1;
        }
        *caps |= cap_names[k].cap;
    }
    return 0;
}

/* One entry of "params": {"name", "default", "min", "max", "integer"?, "doc"?}. */
static int param_of(const obj_node *v, ob_param *p, int i, char *msg, size_t msglen)
{
    const obj_node *nm = obj_get(v, "name"), *def = obj_get(v, "default"), *lo = obj_get(v, "min"),
                   *hi = obj_get(v, "max"), *in = obj_get(v, "integer"), *doc = obj_get(v, "doc");
    static const char word[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_";
    /* a name of letters, digits and '_': --param NAME.X=V splits at '.' and '=', and the
     * request writes it into JSON unescaped */
    if (!nm || nm->type != OBJ_STR || !nm->str[0] || nm->str[strspn(nm->str, word)] || strlen(nm->str) > 40 || !def ||
        def->type != OBJ_NUM || !lo || lo->type != OBJ_NUM || !hi || hi->type != OBJ_NUM || lo->num > def->num ||
        def->num > hi->num || (in && in->type != OBJ_BOOL)) {
        ob_method_msg(msg, msglen, "\"params\"[%d] needs a \"name\" (letters, digits, '_') and numbers \"min\" <= "
                      "\"default\" <= \"max\" (\"integer\": true/false, \"doc\": a string)", i);
        return -1;
    }
    p->name = strdup(nm->str);
    p->doc = dup_str(doc, "");
    p->def = def->num, p->min = lo->num, p->max = hi->num;
    p->integer = in && in->num != 0;
    return 0;
}

static int params_of(ob_ext *e, const obj_node *v, char *msg, size_t msglen)
{
    if (v && (v->type != OBJ_ARR || v->n > OB_EXT_USER_PARAMS)) {
        ob_method_msg(msg, msglen, "\"params\" must be an array of at most %d entries", OB_EXT_USER_PARAMS);
        return -1;
    }
    e->nuser = v ? v->n : 0;
    for (int i = 0; i < e->nuser; i++) {
        if (param_of(v->kids[i], &e->params[i], i, msg, msglen) != 0)
            return -1;
        for (int k = 0; k < i + OB_EXT_OWN_PARAMS; k++)
            if (strcmp(e->params[i].name, k < i ? e->params[k].name : own_params[k - i].name) == 0) {
                ob_method_msg(msg, msglen, "\"params\"[%d]: the name \"%s\" is taken", i, e->params[i].name);
                return -1;
            }
    }
    for (int k = 0; k < OB_EXT_OWN_PARAMS; k++)
        e->params[e->nuser + k] = own_params[k];
    e->m.params = e->params;
    e->m.nparams = e->nuser + OB_EXT_OWN_PARAMS;
    return 0;
}

/* "degree": "same" (the input's) or a whole number 1 .. OB_MAX_DEG. */
static int degree_of(ob_ext *e, const obj_node *v, char *msg, size_t msglen)
{
    if (v && v->type == OBJ_STR && strcmp(v->str, "same") == 0) {
        e->degree = -1;
        return 0;
    }
    if (v && v->type == OBJ_NUM && v->num == floor(v->num) && v->num >= 1 && v->num <= OB_MAX_DEG) {
        e->degree = (int)v->num;
        return 0;
    }
    ob_method_msg(msg, msglen, "\"degree\" must be \"same\" or a whole number from 1 to %d", OB_MAX_DEG);
    return -1;
}

int ob_ext_hello(ob_ext *e, const obj_node *h, char *msg, size_t msglen)
{
    const obj_node *pv = obj_get(h, "protocol"), *ver = obj_get(h, "version"), *mt = obj_get(h, "max_turn"),
                   *ut = obj_get(h, "uses_tol");
    if (!pv || pv->type != OBJ_NUM || pv->num != OB_EXT_PROTOCOL) {
        ob_method_msg(msg, msglen, "the hello line has no \"protocol\": %d", OB_EXT_PROTOCOL);
        return -1;
    }
    if (degree_of(e, obj_get(h, "degree"), msg, msglen) != 0 ||
        caps_of(obj_get(h, "caps"), &e->m.caps, msg, msglen) != 0 ||
        params_of(e, obj_get(h, "params"), msg, msglen) != 0)
        return -1;
    if ((ver && (ver->type != OBJ_NUM || ver->num != floor(ver->num) || fabs(ver->num) > 1e9)) ||
        (mt && (mt->type != OBJ_NUM || mt->num < 0)) || (ut && ut->type != OBJ_BOOL)) {
        ob_method_msg(msg, msglen, "\"version\" must be a whole number, \"max_turn\" a number >= 0, "
                      "\"uses_tol\" true or false");
        return -1;
    }
    e->citation = dup_str(obj_get(h, "citation"), "(no citation given)");
    e->continuity = dup_str(obj_get(h, "continuity"), "none");
    e->m.citation = e->citation;
    e->m.continuity = e->continuity;
    e->m.version = ver ? (int)ver->num : 1;
    e->m.max_turn = mt ? mt->num : 0.0;
    e->m.fit_uses_tol = ut && ut->num != 0 ? ob_fit_uses_tol_always : NULL;
    return 0;
}

void ob_ext_quote(const char *line, size_t len, char *buf, size_t buflen)
{
    size_t k = 0;
    const size_t cut = len > 40 ? 40 : len;
    for (size_t i = 0; i < cut && k + 4 < buflen; i++) {
        const unsigned char c = (unsigned char)line[i];
        buf[k++] = c < 0x20 || c >= 0x7f ? '?' : (char)c;
    }
    if (cut < len && k + 4 < buflen)
        buf[k++] = '.', buf[k++] = '.', buf[k++] = '.';
    if (buflen)
        buf[k < buflen ? k : buflen - 1] = '\0';
}
