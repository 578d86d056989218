/*
 * register.c - external methods entered into the registry at run time
 * (ext.h).  A fit and an out_degree take no method argument (method.h), so
 * each of the OB_MAX_EXTERNAL slots has its own pair of small functions
 * that pass the slot on.
 */
#include "methods/external/ext.h"

#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/external/json.h"
#include "methods/external/proc.h"
#include "methods/sisl/proto.h"

static ob_ext *table[OB_MAX_EXTERNAL];

const ob_ext *ob_ext_get(int k) { return k >= 0 && k < OB_MAX_EXTERNAL ? table[k] : NULL; }

const ob_ext *ob_ext_of(const ob_method *m)
{
    for (int k = 0; k < OB_MAX_EXTERNAL; k++)
        if (table[k] && &table[k]->m == m)
            return table[k];
    return NULL;
}

#define OB_EXT_SLOT(k)                                                                                     \
    static ob_fit_status fit_##k(const ob_bez *b, const ob_fit_args *a, void *w, ob_fit *o, char *m,       \
                                 size_t ml)                                                                \
    {                                                                                                      \
        (void)w;                                                                                           \
        return ob_ext_fit(table[k], b, a, o, m, ml);                                                       \
    }                                                                                                      \
    static int degree_##k(int n, int rational_in, const double *par)                                       \
    {                                                                                                      \
        (void)rational_in, (void)par;                                                                      \
        return table[k]->degree < 0 ? n : table[k]->degree;                                                \
    }
OB_EXT_SLOT(0)
OB_EXT_SLOT(1)
OB_EXT_SLOT(2)
OB_EXT_SLOT(3)
OB_EXT_SLOT(4)
OB_EXT_SLOT(5)
OB_EXT_SLOT(6)
OB_EXT_SLOT(7)
#undef OB_EXT_SLOT

typedef ob_fit_status (*fit_fn)(const ob_bez *, const ob_fit_args *, void *, ob_fit *, char *, size_t);
typedef int (*degree_fn)(int, int, const double *);
static const fit_fn fits[OB_MAX_EXTERNAL] = {fit_0, fit_1, fit_2, fit_3, fit_4, fit_5, fit_6, fit_7};
static const degree_fn degrees[OB_MAX_EXTERNAL] = {degree_0, degree_1, degree_2, degree_3,
                                                    degree_4, degree_5, degree_6, degree_7};

unsigned long long ob_ext_fnv(unsigned long long h, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        h = (h ^ (unsigned char)s[i]) * 0x100000001b3ull;
    return h;
}

/* The worker's first line, parsed (obj_free it); NULL with the reason in msg. */
static obj_node *read_hello(const char *command, uint64_t *hash, unsigned long long *hello, char *msg,
                            size_t msglen)
{
    ob_ext_proc w = {0};
    w.fd = -1;
    if (ob_ext_proc_start(&w, command, 0, msg, msglen) != 0)
        return NULL;
    char *line;
    size_t len;
    const int rc = ob_ext_proc_line(&w, ob_sisl_now() + 30.0, &line, &len);
    obj_node *h = NULL;
    char err[160], q[160];
    if (rc == 0) {
        h = obj_parse(line, len, err, sizeof err);
        ob_ext_quote(line, len, q, sizeof q);
        if (!h || h->type != OBJ_OBJ)
            ob_method_msg(msg, msglen, "its hello line is not a JSON object (%s): '%s'", h ? "another value" : err, q);
        *hello = ob_ext_fnv(OB_EXT_FNV0, line, len);
        *hash = ob_ext_fnv(ob_ext_fnv(OB_EXT_FNV0, command, strlen(command) + 1), line, len);
    }
    int ws = -1;
    ob_ext_proc_stop(&w, SIGKILL, &ws);
    free(w.buf);
    if (rc != 0) {
        char how[80];
        ob_sisl_describe_wait(ws, how, sizeof how);
        ob_method_msg(msg, msglen, "no hello line from `%s` (%s)", command,
                      rc == 1 ? "none within 30 s" : rc == -2 ? "a line too long" : how);
    }
    if (h && h->type != OBJ_OBJ)
        obj_free(h), h = NULL;
    return h;
}

/* Registrations one at a time: the library's callers (Python threads) may
 * register at once, and two must not take one slot of the table. */
static pthread_mutex_t register_mu = PTHREAD_MUTEX_INITIALIZER;

static int register_locked(const char *name, const char *command, char *msg, size_t msglen);

int ob_ext_register(const char *name, const char *command, char *msg, size_t msglen)
{
    pthread_mutex_lock(&register_mu);
    const int rc = register_locked(name, command, msg, msglen);
    pthread_mutex_unlock(&register_mu);
    return rc;
}

int ob_ext_register_once(const char *name, const char *command, char *msg, size_t msglen)
{
    pthread_mutex_lock(&register_mu);
    const ob_method *m = ob_method_find(name);
    const ob_ext *e = m ? ob_ext_of(m) : NULL;
    const int rc = e && strcmp(e->command, command) == 0 ? 0 : register_locked(name, command, msg, msglen);
    pthread_mutex_unlock(&register_mu);
    return rc;
}

/* A method whose hello was refused, and what its reading allocated
 * (hello.c: the strings; the worker's parameters' names and docs, NULL
 * past the one refused). */
static void ext_free(ob_ext *e)
{
    if (!e)
        return;
    free(e->citation);
    free(e->continuity);
    for (int i = 0; i < e->nuser; i++) {
        free((char *)e->params[i].name);
        free((char *)e->params[i].doc);
    }
    free(e);
}

static int register_locked(const char *name, const char *command, char *msg, size_t msglen)
{
    int k = 0;
    while (k < OB_MAX_EXTERNAL && table[k])
        k++;
    if (k == OB_MAX_EXTERNAL) {
        ob_method_msg(msg, msglen, "more than %d external methods", OB_MAX_EXTERNAL);
        return -1;
    }
    /* the method contract's rule (methods/CONTRACT.md, `name`): the name goes
     * unquoted into results.csv and meta.json */
    const size_t len = strlen(name);
    if (ob_method_find(name) || len < 1 || len > 31 || strspn(name, "abcdefghijklmnopqrstuvwxyz0123456789_-") != len) {
        ob_method_msg(msg, msglen, ob_method_find(name) ? "the name '%.64s' is taken"
                      : "'%.64s' is no method name (1 to 31 lower-case letters, digits, '_' and '-')", name);
        return -1;
    }
    uint64_t hash = 0;
    unsigned long long hello = 0;
    obj_node *h = read_hello(command, &hash, &hello, msg, msglen);
    ob_ext *e = h ? calloc(1, sizeof *e) : NULL;
    if (!e || ob_ext_hello(e, h, msg, msglen) != 0) {
        obj_free(h);
        ext_free(e);  /* the library goes on after a failed registration (Python): nothing kept */
        return -1;
    }
    obj_free(h);
    snprintf(e->name, sizeof e->name, "%s", name);
    snprintf(e->fp, sizeof e->fp, "%016llx", (unsigned long long)hash);
    e->command = strdup(command);
    e->hello = hello;
    e->index = k;
    e->m.name = e->name;
    e->m.cost_ms = OB_EXT_COST_MS;
    e->m.fit = fits[k];
    e->m.out_degree = degrees[k];
    table[k] = e;
    if (ob_method_register(&e->m) != 0) {
        table[k] = NULL;
        free(e->command);
        ext_free(e);
        ob_method_msg(msg, msglen, "the method table is full");
        return -1;
    }
    return 0;
}
