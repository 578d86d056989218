/*
 * ext.h - external methods: a program in any language, registered at run
 * time (--external NAME=COMMAND), that answers fit requests as JSON lines
 * (docs/external-methods.md).  Each is an ob_method appended to ob_methods
 * after the built-ins; its fit sends the piece to this thread's worker.
 */
#ifndef OB_EXT_H
#define OB_EXT_H

#include <stddef.h>
#include "methods/method.h"

enum { OB_EXT_PROTOCOL = 1 };
/* An external method's cost per job in --shard's model (method.h cost_ms):
 * unknown until measured, so the model's default for any method, 2 ms. */
#define OB_EXT_COST_MS 2.0
/* The supervisor's own parameters, after the worker's: the wall-clock and
 * CPU seconds one fit may take and the worker's address space (MiB). */
enum { OB_EXT_OWN_PARAMS = 3, OB_EXT_USER_PARAMS = OB_MAX_PARAMS - OB_EXT_OWN_PARAMS };

typedef struct {
    ob_method m;                    /* what the registry lists */
    int index;                      /* 0 .. OB_MAX_EXTERNAL - 1 */
    char name[64];
    char *command, *citation, *continuity;
    int degree;                     /* of every output piece; -1: the input's */
    int nuser;                      /* the worker's parameters: m.params[0 .. nuser) */
    ob_param params[OB_MAX_PARAMS];
    char *param_text;               /* the parameters' names and docs (owned) */
    char fp[17];                    /* FNV-1a 64 of the command and the hello line, hex */
    unsigned long long hello;       /* FNV-1a 64 of the hello line: each restarted worker's is checked */
} ob_ext;

/* Purpose: start COMMAND once, read its hello line (the method's metadata),
 *          and register it as method NAME.  Returns 0, or -1 with the reason
 *          in msg (the caller names the option or manifest). */
int ob_ext_register(const char *name, const char *command, char *msg, size_t msglen);

/* Purpose: as ob_ext_register, but 0 at once when NAME is already this
 *          command's (the library's callers register a function before
 *          every run, from any thread).  Registrations are serialized. */
int ob_ext_register_once(const char *name, const char *command, char *msg, size_t msglen);

/* FNV-1a 64 of s[0..n), continuing from h (start: OB_EXT_FNV0). */
#define OB_EXT_FNV0 0xcbf29ce484222325ull
unsigned long long ob_ext_fnv(unsigned long long h, const char *s, size_t n);

/* The external method behind m, or NULL for a built-in. */
const ob_ext *ob_ext_of(const ob_method *m);

/* The registered external method k (0 .. OB_MAX_EXTERNAL - 1), or NULL. */
const ob_ext *ob_ext_get(int k);

/* Purpose: the fit of external method e (fit.c): one request to this
 *          thread's worker, the answer checked. */
ob_fit_status ob_ext_fit(const ob_ext *e, const ob_bez *base, const ob_fit_args *a, ob_fit *out, char *msg,
                         size_t msglen);

/* Reading the hello line (hello.c): fills e's metadata from the parsed
 * line; 0, or -1 with the reason in msg. */
struct obj_node;
int ob_ext_hello(ob_ext *e, const struct obj_node *h, char *msg, size_t msglen);

/* Purpose: one piece of the protocol (an answer's piece, or a request: its
 *          "degree", "points" and "weights" are a piece's keys) into *seg:
 *          "degree" must be want, "points" want + 1 finite [x, y], "weights"
 *          (optional: all 1) want + 1 numbers > 0.
 * Returns: 0, or -1 with what is wrong in why (fit.c). */
int ob_ext_piece(const struct obj_node *p, int want, ob_bez *seg, char *why, size_t wl);

/* The protocol's name of capability bit cap (one OB_CAP_* flag), or NULL
 * (hello.c). */
const char *ob_ext_cap_name(unsigned cap);

/* A worker's line quoted for a message: at most 40 bytes (a row's message keeps
 * 100 bytes of the fit's), control bytes
 * and bytes past ASCII as '?' (the message column stays UTF-8), "..." when cut. */
void ob_ext_quote(const char *line, size_t len, char *buf, size_t buflen);

#endif
