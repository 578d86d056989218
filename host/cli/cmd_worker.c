/*
 * cmd_worker.c - `offbench worker METHOD`: a built-in method served over the
 * external-method protocol (docs/external-methods.md) on standard input and
 * output, so that
 *
 *     ./offbench run --external tiller_w="./offbench worker tiller" --methods tiller,tiller_w
 *
 * runs one arithmetic two ways: in process and through a worker.  Its rows
 * are the built-in's (tests/e2e/e2e_worker.sh checks every method), and the
 * difference in time per fit is the protocol's own cost (`bench`'s
 * protocol/ rows).  The hello declares what the registry holds: citation,
 * caps, continuity, version, max_turn, the parameters, whether the fit
 * reads the tolerance, and the output degree, all at the parameters'
 * defaults.  A method whose output degree the hello cannot declare (not the
 * input's and not one number at the defaults), or with more parameters
 * than a worker may declare, is refused (exit 2).
 * Exit status: 0 at the end of input; 2 bad arguments.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/diag.h"
#include "host/io/output.h"
#include "methods/external/ext.h"
#include "methods/external/json.h"

enum { LINE_MAX_BYTES = 4 << 20 };

/* The degree the hello declares: -1 "same" (the input's, polynomial and
 * rational), k (every input gives k), or -2 neither. */
static int declared_degree(const ob_method *m)
{
    double def[OB_MAX_PARAMS];
    ob_param_defaults(m, def);
    int same = 1, k = ob_method_out_degree(m, 1, 0, def), fixed = 1;
    for (int n = 1; n <= OB_MAX_DEG; n++)
        for (int r = 0; r < 2; r++) {
            if (r && !(m->caps & OB_CAP_RATIONAL_IN))
                continue;
            const int out = ob_method_out_degree(m, n, r, def);
            same &= out == n;
            fixed &= out == k;
        }
    return same ? -1 : fixed ? k : -2;
}

static void put_num(FILE *f, double x) { fprintf(f, "%.17g", x); }

static void hello(FILE *f, const ob_method *m, int degree)
{
    char cit[600];
    snprintf(cit, sizeof cit, "%s (built in, served by offbench worker)", m->citation);
    fputs("{\"protocol\":1,\"citation\":", f);
    ob_json_string(f, cit);
    if (degree < 0)
        fputs(",\"degree\":\"same\"", f);
    else
        fprintf(f, ",\"degree\":%d", degree);
    fputs(",\"continuity\":", f);
    ob_json_string(f, m->continuity);
    fputs(",\"caps\":[", f);
    int first = 1;
    for (unsigned bit = 1; bit; bit <<= 1)
        if ((m->caps & bit) && ob_ext_cap_name(bit)) {
            fprintf(f, "%s\"%s\"", first ? "" : ",", ob_ext_cap_name(bit));
            first = 0;
        }
    double def[OB_MAX_PARAMS];
    ob_param_defaults(m, def);
    fprintf(f, "],\"uses_tol\":%s,\"version\":%d,\"max_turn\":", m->fit_uses_tol && m->fit_uses_tol(def) ? "true" : "false",
            m->version);
    put_num(f, m->max_turn);
    fputs(",\"params\":[", f);
    for (int i = 0; i < m->nparams; i++) {
        const ob_param *p = &m->params[i];
        fprintf(f, "%s{\"name\":\"%s\",\"default\":", i ? "," : "", p->name);
        put_num(f, p->def);
        fputs(",\"min\":", f);
        put_num(f, p->min);
        fputs(",\"max\":", f);
        put_num(f, p->max);
        fprintf(f, ",\"integer\":%s,\"doc\":", p->integer ? "true" : "false");
        ob_json_string(f, p->doc);
        fputc('}', f);
    }
    fputs("]}\n", f);
}

static void error_answer(FILE *f, long id, const char *status, const char *why)
{
    if (id >= 0)
        fprintf(f, "{\"id\":%ld,\"error\":", id);
    else
        fputs("{\"id\":null,\"error\":", f);
    ob_json_string(f, why);
    fprintf(f, ",\"status\":\"%s\"}\n", status);
}

static void pieces_answer(FILE *f, long id, const ob_fit *out)
{
    fprintf(f, "{\"id\":%ld,\"pieces\":[", id);
    for (int i = 0; i < out->n; i++) {
        const ob_bez *b = &out->seg[i];
        fprintf(f, "%s{\"degree\":%d,\"points\":[", i ? "," : "", b->deg);
        for (int k = 0; k <= b->deg; k++) {
            double p[2];
            ob_bez_ctrl(b, k, p);
            fputs(k ? ",[" : "[", f);
            put_num(f, p[0]);
            fputc(',', f);
            put_num(f, p[1]);
            fputc(']', f);
        }
        fputs("],\"weights\":[", f);
        for (int k = 0; k <= b->deg; k++) {
            if (k)
                fputc(',', f);
            put_num(f, ob_bez_weight(b, k));
        }
        fputs("]}", f);
    }
    fputs("],\"t\":[", f);
    for (int i = 0; i <= out->n; i++) {
        if (i)
            fputc(',', f);
        put_num(f, out->t[i]);
    }
    fprintf(f, "],\"ctrl_points\":%ld}\n", out->ctrl_points);
}

/* The request's parameters over the defaults into par: 0, or -1 with why. */
static int params_of(const ob_method *m, const obj_node *v, double *par, char *why, size_t wl)
{
    ob_param_defaults(m, par);
    if (!v || v->type != OBJ_OBJ) {
        snprintf(why, wl, "bad request: \"params\" is not an object");
        return -1;
    }
    for (int k = 0; k < v->n; k++) {
        int i = 0;
        while (i < m->nparams && strcmp(m->params[i].name, v->kids[k]->key) != 0)
            i++;
        if (i == m->nparams || v->kids[k]->type != OBJ_NUM) {
            snprintf(why, wl, "bad request: \"params\": \"%.40s\" is not a parameter of %s with a number",
                     v->kids[k]->key, m->name);
            return -1;
        }
        if (ob_param_check(m, &m->params[i], v->kids[k]->num, why, wl) != 0)
            return -1;
        par[i] = v->kids[k]->num;
    }
    return 0;
}

/* One request line answered on f. */
static void serve_line(FILE *f, const ob_method *m, int degree, void *work, const char *line, size_t len)
{
    char why[512] = "";
    obj_node *r = obj_parse(line, len, why, sizeof why);
    const obj_node *id = r ? obj_get(r, "id") : NULL, *dg = r ? obj_get(r, "degree") : NULL;
    const long rid = id && id->type == OBJ_NUM && id->num >= 0 && id->num <= 1e15 ? (long)id->num : -1;
    double par[OB_MAX_PARAMS];
    ob_bez base;
    const obj_node *d = r ? obj_get(r, "d") : NULL, *tol = r ? obj_get(r, "tol") : NULL;
    if (!r) {
        char msg[600];
        snprintf(msg, sizeof msg, "bad request: %s", why);
        error_answer(f, -1, "fail", msg);
        return;
    }
    if (rid < 0 || !dg || dg->type != OBJ_NUM || dg->num < 1 || dg->num > OB_MAX_DEG || dg->num != (int)dg->num ||
        !d || d->type != OBJ_NUM || !tol || tol->type != OBJ_NUM || !(tol->num > 0)) {
        error_answer(f, rid, "fail", "bad request: it needs \"id\", \"degree\" (1 .. 32), \"d\" and \"tol\" > 0");
    } else if (ob_ext_piece(r, (int)dg->num, &base, why, sizeof why) != 0 ||
               params_of(m, obj_get(r, "params"), par, why, sizeof why) != 0) {
        error_answer(f, rid, "fail", why);
    } else if (degree >= 0 && ob_method_out_degree(m, base.deg, 0, par) != degree) {
        error_answer(f, rid, "fail", "these parameters change the output degree the hello declared");
    } else {
        const ob_fit_args a = {d->num, tol->num, par};
        ob_fit out;
        memset(&out, 0, sizeof out);
        const ob_fit_status s = m->fit(&base, &a, work, &out, why, sizeof why);
        if (s == OB_FIT_OK)
            pieces_answer(f, rid, &out);
        else
            error_answer(f, rid, s == OB_FIT_SKIP ? "skip" : s == OB_FIT_RETRY_SMALLER ? "retry_smaller" : "fail", why);
    }
    obj_free(r);
}

int ob_cmd_worker(int argc, char **argv)
{
    char *pos[1];
    int npos = 0;
    const int prc = ob_cli_parse("METHOD   (a built-in method served over the protocol of docs/external-methods.md "
                                 "on stdin and stdout)", NULL, 0, argc, argv, 1, pos, &npos);
    if (prc != OB_CLI_OK)
        return prc == OB_CLI_HELP ? 0 : 2;
    if (npos != 1) {
        ob_error("worker: expected one METHOD (worker METHOD)");
        return 2;
    }
    const ob_method *m = ob_method_find(pos[0]);
    if (!m || ob_ext_of(m)) {
        ob_error("worker: '%s' is not a built-in method (./offbench list methods)", pos[0]);
        return 2;
    }
    const int degree = declared_degree(m);
    if (degree == -2 || m->nparams > OB_EXT_USER_PARAMS) {
        ob_error("worker: %s cannot be served: %s", m->name,
                 degree == -2 ? "its output degree is neither the input's nor one number, which a hello must declare"
                              : "it has more parameters than a worker may declare (5)");
        return 2;
    }
    void *work = m->work_size ? calloc(1, m->work_size) : NULL;
    char *line = NULL;
    size_t cap = 0;
    if (m->work_size && !work) {
        ob_error("worker: out of memory");
        return 1;
    }
    hello(stdout, m, degree);
    fflush(stdout);
    for (ssize_t n; (n = getline(&line, &cap, stdin)) > 0;) {
        if (line[n - 1] == '\n')
            line[--n] = '\0';
        if ((size_t)n > LINE_MAX_BYTES)
            error_answer(stdout, -1, "fail", "bad request: longer than 4 MiB");
        else
            serve_line(stdout, m, degree, work, line, (size_t)n);
        if (fflush(stdout) != 0)
            break;
    }
    free(line);
    free(work);
    return 0;
}
