/*
 * compare_context.c - loading the two runs of `compare` and the
 * comparability checks (the rules are spelled out in cmd_compare.c).
 */
#include "host/compare/compare.h"
#include "host/compare/compare_subset.h"

#include "host/io/strmap.h"
#include "methods/method.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

ob_cmp_opts ob_cmp_defaults(void)
{
    ob_cmp_opts o = {.err_rtol = 1e-9, .err_atol = 1e-15, .time_threshold = 0.10, .time_floor_ns = 1e6,
                     .alpha = 0.05, .max_rows = 50, .no_timing = 0, .method_timing_only = 0,
                     .strict_timing = 0, .timing_only = 0, .methods = NULL};
    return o;
}

int ob_strlist_addf(ob_strlist *l, const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 8;
        char **nv = realloc(l->v, (size_t)cap * sizeof *nv);
        if (!nv)
            return -1;
        l->v = nv;
        l->cap = cap;
    }
    char *s = malloc(strlen(buf) + 1);
    if (!s)
        return -1;
    strcpy(s, buf);
    l->v[l->n++] = s;
    return 0;
}

void ob_strlist_free(ob_strlist *l)
{
    for (int i = 0; l && i < l->n; i++)
        free(l->v[i]);
    if (l) {
        free(l->v);
        memset(l, 0, sizeof *l);
    }
}

/* ---- loading ---- */

void ob_cmp_side_free(ob_cmp_side *s)
{
    if (!s)
        return;
    ob_res_free(&s->res);
    ob_json_free(&s->meta);
    s->has_meta = s->has_samples = 0;
}

static void drop_samples(ob_res_table *t)
{
    free(t->rep_t);
    t->rep_t = NULL;
    t->maxrep = 0;
    for (int i = 0; i < t->n; i++) {
        t->v[i].rep_t = NULL;
        t->v[i].nsamples = 0;
    }
}

int ob_cmp_load_side(const char *arg, const char *label, ob_cmp_side *s, ob_err *err)
{
    memset(s, 0, sizeof *s);
    s->label = label;
    struct stat st;
    if (stat(arg, &st) != 0) {
        ob_fail(err, "%s: cannot open: %s", arg, strerror(errno));
        return -1;
    }
    char dir[4096];
    int too_long;
    if (S_ISDIR(st.st_mode)) {
        too_long = snprintf(dir, sizeof dir, "%s", arg) >= (int)sizeof dir ||
                   snprintf(s->results_path, sizeof s->results_path, "%s/results.csv", arg) >=
                       (int)sizeof s->results_path;
    } else {
        const char *slash = strrchr(arg, '/');
        too_long = snprintf(s->results_path, sizeof s->results_path, "%s", arg) >= (int)sizeof s->results_path;
        if (!slash)
            snprintf(dir, sizeof dir, ".");
        else if (slash == arg)
            snprintf(dir, sizeof dir, "/");
        else
            snprintf(dir, sizeof dir, "%.*s", (int)(slash - arg), arg);
    }
    too_long = too_long ||
               snprintf(s->meta_path, sizeof s->meta_path, "%s/meta.json", dir) >= (int)sizeof s->meta_path ||
               snprintf(s->samples_path, sizeof s->samples_path, "%s/samples.csv", dir) >=
                   (int)sizeof s->samples_path ||
               snprintf(s->fits_path, sizeof s->fits_path, "%s/fits.csv", dir) >= (int)sizeof s->fits_path;
    if (too_long) {
        ob_fail(err, "%.200s...: path too long", arg);
        return -1;
    }
    if (ob_res_load(s->results_path, &s->res, err))
        return -1;
    if (access(s->meta_path, F_OK) == 0) {
        if (ob_json_load(s->meta_path, &s->meta, err)) {
            ob_cmp_side_free(s);
            return -1;
        }
        s->has_meta = 1;
    }
    if (access(s->samples_path, F_OK) == 0) {
        if (ob_res_load_samples(&s->res, s->samples_path, err)) {
            ob_cmp_side_free(s);
            return -1;
        }
        s->has_samples = s->res.maxrep > 0;
    }
    if (s->res.method_timed && access(s->fits_path, F_OK) == 0) {
        if (ob_res_load_fits(&s->res, s->fits_path, err)) {
            ob_cmp_side_free(s);
            return -1;
        }
        s->has_fits = s->res.maxround > 0;
    }
    /* a samples.csv left over from an earlier run into the same directory */
    const ob_json_entry *reps = s->has_samples ? ob_json_get(&s->meta, "reps") : NULL;
    if (reps && reps->type == OB_JSON_NUMBER && strtod(reps->value, NULL) != s->res.maxrep) {
        snprintf(s->samples_note, sizeof s->samples_note,
                 "%.300s: ignored, it has %d repetitions but meta.json says reps %.40s", s->samples_path, s->res.maxrep,
                 reps->value);
        drop_samples(&s->res);
        s->has_samples = 0;
    }
    return 0;
}

/* ---- context ---- */

static const char *shown(const ob_json_entry *e)
{
    return e ? e->value : "(absent)";
}

/* The columns whose distinct values the checks need. */
enum { COL_METHOD, COL_METRIC, COL_SPLIT, NCOLS };

static const char *column(const ob_res_row *r, int col)
{
    return col == COL_METHOD ? r->method : col == COL_METRIC ? r->metric : r->split;
}

/* The distinct values of column col of t, into the map m (value -> its
 * first row): the checks ask one map, not every row, for each value, so
 * that they stay linear in the rows and keys read.  0, or -1 no memory. */
static int distinct(const ob_res_table *t, int col, ob_strmap *m)
{
    for (int i = 0; i < t->n; i++)
        if (ob_strmap_put(m, column(t->v + i, col), i) == -2)
            return -1;
    return 0;
}

/* "a,b,c": the distinct values of column col of t, in the order of rows. */
static void value_set(const ob_res_table *t, int col, const ob_strmap *m, char *buf, size_t len)
{
    buf[0] = '\0';
    size_t used = 0;
    for (int i = 0; i < t->n && used < len; i++)
        if (ob_strmap_get(m, column(t->v + i, col)) == i)  /* the value's first row */
            used += (size_t)snprintf(buf + used, len - used, "%s%s", used ? "," : "", column(t->v + i, col));
}

/* 1 when a row of b has a value of column col that a has (in am). */
static int shares_value(const ob_strmap *am, const ob_res_table *b, int col)
{
    for (int j = 0; j < b->n; j++)
        if (ob_strmap_get(am, column(b->v + j, col)) >= 0)
            return 1;
    return 0;
}

/* 1 when e, a key method_params.M.P, names a parameter P of method M in
 * this build and holds its default: a run whose meta.json lacks the key
 * predates the parameter, and a parameter is added with a default that keeps
 * the method's output (a change of output bumps the method's version). */
static int holds_default(const ob_json_entry *e, const char *method, size_t gl)
{
    const ob_method *m = ob_method_find(method);
    const char *name = e->path + gl + 1 + strlen(method) + 1;
    const int k = m ? ob_param_find(m, name) : -1;
    if (k < 0 || e->type != OB_JSON_NUMBER)
        return 0;
    char *end;
    const double v = strtod(e->value, &end);
    return *end == '\0' && v == m->params[k].def;
}

/* method_params.* or method_versions.* (group): a key of a method both runs
 * ran must be on both sides with the same value; a method_params key on one
 * side only counts as equal when it holds the parameter's default in this
 * build (holds_default; a note says so). */
static int check_group(const ob_cmp_side *b, const ob_cmp_side *n, const ob_strmap *mb, const ob_strmap *mn,
                       const char *group, ob_cmp_result *r)
{
    const size_t gl = strlen(group);
    int on_b = 0, on_n = 0, ignored = 0;
    for (int i = 0; i < b->meta.n; i++)
        on_b += strncmp(b->meta.v[i].path, group, gl) == 0 && b->meta.v[i].path[gl] == '.';
    for (int i = 0; i < n->meta.n; i++)
        on_n += strncmp(n->meta.v[i].path, group, gl) == 0 && n->meta.v[i].path[gl] == '.';
    if (!on_b && !on_n)
        return 0;
    if (!on_b || !on_n)
        return ob_strlist_addf(&r->notes, "%s is not recorded in the meta.json of %s: not checked", group,
                               on_b ? n->label : b->label);
    for (int side = 0; side < 2; side++) {
        const ob_cmp_side *x = side ? n : b, *y = side ? b : n;
        for (int i = 0; i < x->meta.n; i++) {
            const ob_json_entry *e = &x->meta.v[i];
            if (strncmp(e->path, group, gl) != 0 || e->path[gl] != '.')
                continue;
            const ob_json_entry *o = ob_json_get(&y->meta, e->path);
            if (side == 1 && o)
                continue; /* compared in the first pass */
            if (ob_json_same(e, o))
                continue;
            char method[256];
            const char *m = e->path + gl + 1, *dot = strchr(m, '.');
            snprintf(method, sizeof method, "%.*s", (int)(dot ? (size_t)(dot - m) : strlen(m)), m);
            if (ob_strmap_get(mb, method) < 0 || ob_strmap_get(mn, method) < 0) {
                ignored++;
                continue;
            }
            if (!o && dot && strcmp(group, "method_params") == 0 && holds_default(e, method, gl)) {
                if (ob_strlist_addf(&r->notes, "%s is absent in %s: taken as its default %s", e->path, y->label,
                                    e->value))
                    return -1;
                continue;
            }
            const ob_json_entry *eb = side ? o : e, *en = side ? e : o;
            if (ob_strlist_addf(&r->incomparable, "%s %s vs %s", e->path, shown(eb), shown(en)))
                return -1;
        }
    }
    if (ignored)
        return ob_strlist_addf(&r->notes, "%d %s key(s) differ for methods not run on both sides (ignored)", ignored,
                               group);
    return 0;
}

/* The identity keys (README "What a run directory guarantees"): another
 * kernel text changes the numbers, so kernel_fnv1a must agree; data_hash
 * covers the selected curves, which two comparable runs may choose
 * differently (rows are matched by curve), so a difference is a note.  A
 * key on one side only (a run from before it existed) is a note too. */
static int check_identity(const ob_cmp_side *b, const ob_cmp_side *n, ob_cmp_result *r)
{
    static const char *const keys[] = {"kernel_fnv1a", "data_hash"};
    int rc = 0;
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        const ob_json_entry *eb = ob_json_get(&b->meta, keys[k]), *en = ob_json_get(&n->meta, keys[k]);
        if (ob_json_same(eb, en))
            continue;
        if (!eb || !en)
            rc |= ob_strlist_addf(&r->notes, "%s is not recorded in the meta.json of %s: not checked", keys[k],
                                  eb ? n->label : b->label);
        else if (k == 0)
            rc |= ob_strlist_addf(&r->incomparable, "%s %s vs %s (another kernel text: $OFFBENCH_KERNELS)",
                                  keys[k], shown(eb), shown(en));
        else
            rc |= ob_strlist_addf(&r->notes, "%s %s vs %s: the curve sets differ (another selection or content)",
                                  keys[k], shown(eb), shown(en));
    }
    return rc;
}

/* metric and split: the runs must share a value of each.  cols: the
 * distinct values of each side (distinct()). */
static int check_values(const ob_cmp_side *b, const ob_cmp_side *n, ob_strmap cols[2][NCOLS], ob_cmp_result *r)
{
    char sb[512], sn[512];
    int rc = 0;
    for (int col = COL_METRIC; b->res.n && n->res.n && col <= COL_SPLIT; col++)
        if (!shares_value(&cols[0][col], &n->res, col)) {
            value_set(&b->res, col, &cols[0][col], sb, sizeof sb);
            value_set(&n->res, col, &cols[1][col], sn, sizeof sn);
            rc |= ob_strlist_addf(&r->incomparable, "%s differs: %s vs %s", col == COL_METRIC ? "metric" : "split",
                                  sb, sn);
        }
    return rc;
}

/* A merged run's key whose shards differ (merge.h): its value, or that of
 * the object holding it ("opencl" for "opencl.device"), is "mixed".  Two
 * such runs are never the same setting: each shard's may differ. */
static int is_mixed(const ob_json_flat *meta, const char *key)
{
    char top[64];
    const ob_json_entry *e = ob_json_get(meta, key);
    if (e && e->type == OB_JSON_STRING && strcmp(e->value, "mixed") == 0)
        return 1;
    const char *dot = strchr(key, '.');
    if (!dot || (size_t)(dot - key) >= sizeof top)
        return 0;
    snprintf(top, sizeof top, "%.*s", (int)(dot - key), key);
    e = ob_json_get(meta, top);
    return e && e->type == OB_JSON_STRING && strcmp(e->value, "mixed") == 0;
}

/* A string of a side's meta.json, or "?". */
static const char *meta_str(const ob_cmp_side *s, const char *key)
{
    const ob_json_entry *e = ob_json_get(&s->meta, key);
    return e ? e->value : "?";
}

/* The machines (meta.json "machine", hostinfo.h): timings are judged only
 * between runs of one machine id with the same logical cores and memory
 * (within 5 %: MemTotal moves a little with the kernel); the CPU model and
 * the device are among the timing context keys.  Why not, into
 * r->timing_diffs.  0, or -1 no memory. */
static int machine_check(const ob_cmp_side *b, const ob_cmp_side *n, ob_cmp_result *r)
{
    const ob_json_entry *ib = ob_json_get(&b->meta, "machine.id"), *in = ob_json_get(&n->meta, "machine.id");
    if (!ib || !in)
        return ob_strlist_addf(&r->timing_diffs, "%s record%s no machine (a meta.json from before offbench recorded "
                               "one)", !ib && !in ? "BASE and NEW" : !ib ? b->label : n->label, !ib && !in ? "" : "s");
    if (is_mixed(&b->meta, "machine.id") || is_mixed(&n->meta, "machine.id"))
        return ob_strlist_addf(&r->timing_diffs, "%s ran on several machines (merged shards: meta.json \"shards\")",
                               is_mixed(&b->meta, "machine.id") ? b->label : n->label);
    if (!ob_json_same(ib, in))
        return ob_strlist_addf(&r->timing_diffs, "baseline from machine '%s' (id %s), this is '%s' (id %s)",
                               meta_str(b, "machine.name"), ib->value, meta_str(n, "machine.name"), in->value);
    int rc = 0;
    const ob_json_entry *cb = ob_json_get(&b->meta, "machine.logical_cores"),
                        *cn = ob_json_get(&n->meta, "machine.logical_cores");
    if (!ob_json_same(cb, cn))
        rc |= ob_strlist_addf(&r->timing_diffs, "machine '%s' changed: logical_cores %s vs %s",
                              meta_str(n, "machine.name"), shown(cb), shown(cn));
    const ob_json_entry *mb = ob_json_get(&b->meta, "machine.memory_mib"),
                        *mn = ob_json_get(&n->meta, "machine.memory_mib");
    const double xb = mb ? strtod(mb->value, NULL) : 0, xn = mn ? strtod(mn->value, NULL) : 0;
    if (!(xb > 0 && xn > 0 && fabs(xb - xn) <= 0.05 * fmax(xb, xn)) && !ob_json_same(mb, mn))
        rc |= ob_strlist_addf(&r->timing_diffs, "machine '%s' changed: memory_mib %s vs %s",
                              meta_str(n, "machine.name"), shown(mb), shown(mn));
    return rc;
}

/* A run whose 1-minute load average exceeded the cores it used shared the
 * CPUs with other work (its own threads count in the load).  That no longer
 * stops timings from being judged (issue 46: shared CI runners are the
 * normal case): the times are thread CPU time, and the repetitions' own
 * spread decides whether a change can be told (time_verdict); a note says
 * so.  0, or -1 no memory. */
static int load_note(const ob_cmp_side *s, ob_cmp_result *r)
{
    const ob_json_entry *l = ob_json_get(&s->meta, "host.loadavg_max"), *c = ob_json_get(&s->meta, "host.cores_used");
    if (!l || !c || l->type != OB_JSON_NUMBER || c->type != OB_JSON_NUMBER)
        return 0;
    const double load = strtod(l->value, NULL), cores = strtod(c->value, NULL);
    if (!(load > cores))
        return 0;
    return ob_strlist_addf(&r->notes, "%s's load average reached %.2f on its %.0f core%s: timings judged all the "
                           "same, by the spread of the repetitions of thread CPU times", s->label, load, cores,
                           cores == 1 ? "" : "s");
}

/* The backend that measured a side ("cpu", "opencl"; "" unknown). */
static const char *backend_of(const ob_cmp_side *s)
{
    const ob_json_entry *e = ob_json_get(&s->meta, "backend");
    return e && e->type == OB_JSON_STRING ? e->value : "";
}

/* What the timings are (r->method_time): the methods' own time when both
 * runs timed their fits, else fit_ns + eval_ns, said in a note; and whether
 * the harness's verdict counts (both measured on the CPU).  0, or -1. */
static int what_is_timed(const ob_cmp_side *b, const ob_cmp_side *n, ob_cmp_result *r)
{
    int rc = 0;
    r->method_time = b->res.method_timed > 0 && n->res.method_timed > 0;
    if (!r->method_time && (b->res.method_timed || n->res.method_timed))
        rc |= ob_strlist_addf(&r->notes, "%s has no method time (run --time-fits): the methods are timed by fit_ns + "
                              "eval_ns, which is mostly offbench's own measuring", b->res.method_timed ? n->label
                                                                                                      : b->label);
    r->harness_counts = strcmp(backend_of(b), "cpu") == 0 && strcmp(backend_of(n), "cpu") == 0;
    return rc;
}

/* Whether timings can be judged (after the comparability checks): both
 * meta.json present, one machine, one timing context (timing keys), then
 * both runs quiet.  Sets r->timing and r->tstate; 0, or -1 no memory. */
static int timing_context(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, ob_cmp_result *r)
{
    static const char *const timing[] = {"compiler", "cflags", "backend", "opencl.device", "opencl.driver",
                                         "omp_threads", "cpu_model"};
    int rc = 0;
    r->timing = !o->no_timing;
    r->tstate = o->no_timing ? OB_TIMING_OFF : OB_TIMING_JUDGED;
    if (o->no_timing)
        return 0;
    if (!b->has_meta || !n->has_meta)
        rc |= ob_strlist_addf(&r->timing_diffs, "%s ha%s no meta.json: the machine is unknown",
                              !b->has_meta && !n->has_meta ? "BASE and NEW" : !b->has_meta ? b->label : n->label,
                              !b->has_meta && !n->has_meta ? "ve" : "s");
    else {
        rc |= machine_check(b, n, r);
        for (size_t k = 0; k < sizeof timing / sizeof timing[0]; k++) {
            const ob_json_entry *eb = ob_json_get(&b->meta, timing[k]), *en = ob_json_get(&n->meta, timing[k]);
            const int mixed = is_mixed(&b->meta, timing[k]) || is_mixed(&n->meta, timing[k]);
            if (!ob_json_same(eb, en) || mixed)
                rc |= ob_strlist_addf(&r->timing_diffs, "%s: %s vs %s%s", timing[k],
                                      is_mixed(&b->meta, timing[k]) ? "mixed" : shown(eb),
                                      is_mixed(&n->meta, timing[k]) ? "mixed" : shown(en),
                                      mixed ? " (merged shards that differ: meta.json \"shards\")" : "");
        }
    }
    if (r->timing_diffs.n) {
        r->timing = 0;
        r->tstate = OB_TIMING_MACHINE;
        return rc;
    }
    rc |= load_note(b, r) | load_note(n, r);
    return rc | what_is_timed(b, n, r);
}

/* "a; b; c": the list l joined, into buf at used (cut to len). */
static size_t join_list(char *buf, size_t len, size_t used, const ob_strlist *l)
{
    for (int i = 0; i < l->n && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? "; " : "", l->v[i]);
    return used;
}

void ob_cmp_timing_text(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, const ob_cmp_result *r,
                        int md, char *buf, size_t len)
{
    const char *em = md ? "**" : "";
    size_t used = 0;
    (void)o;
    switch (r->tstate) {
    case OB_TIMING_OFF:
        snprintf(buf, len, "not compared (--no-timing)");
        return;
    case OB_TIMING_MACHINE:
    case OB_TIMING_NOISY:
        used = (size_t)snprintf(buf, len, "%snot judged%s%s: ", em, r->tstate == OB_TIMING_NOISY ? ": noisy" : "", em);
        join_list(buf, len, used < len ? used : len, &r->timing_diffs);
        return;
    case OB_TIMING_FEW_REPS:
        snprintf(buf, len, "%stoo few repetitions to judge timing: need %d per side%s (BASE has %d, NEW %d: no "
                 "change could be significant at alpha %g)", em, r->need_reps, em,
                 r->method_time ? b->res.maxround : b->res.maxrep, r->method_time ? n->res.maxround : n->res.maxrep,
                 o->alpha);
        return;
    case OB_TIMING_JUDGED:
        break;
    }
    int c[6] = {0, 0, 0, 0, 0, 0}; /* slower, faster, same, noisy, few_reps, by the threshold alone */
    for (int i = 0; i < r->nms; i++) {
        const char *t = r->ms[i].timing;
        if (!t)
            continue;
        c[5] += r->ms[i].reps_base < 2 || r->ms[i].reps_new < 2;
        c[strcmp(t, "slower") == 0 ? 0 : strcmp(t, "faster") == 0 ? 1 : strcmp(t, "same") == 0 ? 2
          : strcmp(t, "noisy") == 0 ? 3 : 4]++;
    }
    used = (size_t)snprintf(buf, len, "judged: the same machine '%s' (id %s), %s; per method %d slower, %d faster, "
                            "%d no change, %d not judged (cannot decide: need more repetitions %d, too few complete "
                            "repetitions %d)", meta_str(n, "machine.name"), meta_str(n, "machine.id"),
                            r->method_time ? "the methods' own fit time (--time-fits)" : "fit_ns + eval_ns",
                            c[0], c[1], c[2], c[3] + c[4], c[3], c[4]);
    if (c[5] && used < len)
        used += (size_t)snprintf(buf + used, len - used, "; %d method(s) by the threshold alone (no repetitions on both "
                                 "sides: one measurement a side, noise not accounted for)", c[5]);
    if (r->harness.timing && used < len)
        snprintf(buf + used, len - used, "; harness (eval_ns) %s%s", ob_cmp_timing_word(&r->harness),
                 r->harness_counts ? "" : " (reported only: a batch backend's eval_ns is wall time)");
}

int ob_cmp_context(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, ob_cmp_result *r, ob_err *err)
{
    static const char *const same[] = {"samples_per_segment", "max_depth", "max_segments", "inflection_split",
                                       "seed"};
    ob_strmap cols[2][NCOLS];
    memset(cols, 0, sizeof cols);
    int rc = 0;
    for (int side = 0; side < 2; side++)
        for (int col = 0; col < NCOLS && !rc; col++)
            rc = distinct(side ? &n->res : &b->res, col, &cols[side][col]);
    r->checked = !rc && b->has_meta && n->has_meta;
    if (r->checked) {
        for (size_t k = 0; k < sizeof same / sizeof same[0]; k++) {
            const ob_json_entry *eb = ob_json_get(&b->meta, same[k]), *en = ob_json_get(&n->meta, same[k]);
            if (!ob_json_same(eb, en))
                rc |= ob_strlist_addf(&r->incomparable, "%s %s vs %s", same[k], shown(eb), shown(en));
        }
        rc |= check_group(b, n, &cols[0][COL_METHOD], &cols[1][COL_METHOD], "method_params", r);
        rc |= check_group(b, n, &cols[0][COL_METHOD], &cols[1][COL_METHOD], "method_versions", r);
        rc |= check_identity(b, n, r);
    } else {
        rc |= ob_strlist_addf(&r->notes, "no meta.json beside %s%s%s: comparability could not be checked",
                              b->has_meta ? "" : b->label, !b->has_meta && !n->has_meta ? " and " : "",
                              n->has_meta ? "" : n->label);
    }
    for (int side = 0; side < 2; side++) {
        const ob_cmp_side *sd = side ? n : b;
        if (sd->samples_note[0])
            rc |= ob_strlist_addf(&r->notes, "%s", sd->samples_note);
        /* the run's own warnings (a load above its cores: README "Noise"), as written */
        const ob_json_entry *w = ob_json_get(&sd->meta, "warnings");
        if (w && w->type == OB_JSON_ARRAY && strcmp(w->value, "[]") != 0)
            rc |= ob_strlist_addf(&r->notes, "%s's run warned (meta.json warnings): %.700s", sd->label, w->value);
    }
    if (!rc)
        rc = check_values(b, n, cols, r) || timing_context(b, n, o, r) || ob_cmp_subset_load(b, n, r);
    for (int side = 0; side < 2; side++)
        for (int col = 0; col < NCOLS; col++)
            ob_strmap_free(&cols[side][col]);
    if (rc) {
        ob_fail(err, "out of memory");
        return -1;
    }
    return 0;
}
