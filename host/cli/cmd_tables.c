/*
 * cmd_tables.c - `./offbench tables [--out DIR]`: every published cell under
 * the three protocols of tables_protocol.h, run in one go, written as
 * DIR/tables.csv (long format), DIR/tables.md (the papers' layout) and
 * DIR/zhao_sweep.csv (Zhao-Zhou's quintic over a range of radii).
 *
 * Planning: each (cell, protocol) resolves to a job; equal jobs are run once.
 * Jobs are grouped by the driver options they need (inflection pre-split,
 * one piece without subdivision) and each group is one driver run, so the
 * OpenCL kernel sees whole levels of many jobs at once.
 */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "host/io/fsutil.h"
#include "host/cli/commands.h"
#include "host/io/datadir.h"
#include "host/cli/cliopts.h"
#include "host/diag.h"
#include "host/run/certify.h"
#include "host/io/export.h"
#include "host/run/progress.h"
#include "host/run/signals.h"
#include "host/tables/published.h"
#include "host/tables/tables.h"

/* The radii swept for Zhao-Zhou's quintic (its radius is not published),
 * and the points where C1 and C2 may have been cut (nor is that). */
static const double sweep_d[] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0};
enum { NSWEEP = sizeof sweep_d / sizeof sweep_d[0] };
static const double sweep_cut[] = {0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8};
enum { NCUTS = sizeof sweep_cut / sizeof sweep_cut[0] };

static int group_of(const ob_tab_spec *s) { return 2 * s->single_piece + s->inflections; }

/* A curve or a piece of one (Zhao-Zhou's halves), owned by the plan. */
static const ob_curve *find_curve(ob_tab_plan *pl, const ob_curveset *set, const ob_tab_spec *s, ob_err *err)
{
    int i = ob_curveset_find(set, s->curve);
    if (i < 0)
        return NULL;
    const ob_curve *base = &set->v[i];
    if (s->piece_a == 0.0 && s->piece_b == 1.0)
        return base;
    for (int k = 0; k < pl->npieces; k++)
        if (pl->pieces[k].seg && strncmp(pl->pieces[k].id, s->curve, strlen(s->curve)) == 0 &&
            pl->piece_ab[k][0] == s->piece_a && pl->piece_ab[k][1] == s->piece_b)
            return &pl->pieces[k];
    if (base->nseg != 1) {
        ob_fail(err, "curve '%s': pieces are only defined for one-segment curves", base->id);
        return NULL;
    }
    if (pl->npieces == OB_TAB_MAX_PIECES) {
        ob_fail(err, "more than %d curve pieces", OB_TAB_MAX_PIECES);
        return NULL;
    }
    ob_curve *c = &pl->pieces[pl->npieces];
    memset(c, 0, sizeof *c);
    c->seg = malloc(sizeof *c->seg);
    c->d = malloc(sizeof *c->d);
    if (!c->seg || !c->d) {
        free(c->seg);
        free(c->d);
        c->seg = NULL;
        c->d = NULL;
        ob_fail(err, "out of memory");
        return NULL;
    }
    snprintf(c->id, sizeof c->id, "%.40s[%.3f,%.3f]", base->id, s->piece_a, s->piece_b);
    c->source = base->source;
    c->family = base->family;
    c->nseg = 1;
    ob_bez_subsegment(&base->seg[0], s->piece_a, s->piece_b, c->seg);
    c->nd = 1;
    c->d[0] = base->nd > 0 ? base->d[0] : 1.0;
    snprintf(c->file, sizeof c->file, "%s", base->file);
    c->line = base->line;
    pl->piece_ab[pl->npieces][0] = s->piece_a;
    pl->piece_ab[pl->npieces][1] = s->piece_b;
    pl->npieces++;
    return c;
}

static int same_job(const ob_tab_slot *a, const ob_tab_slot *b)
{
    return a->job.curve == b->job.curve && a->job.d == b->job.d && a->job.method == b->job.method &&
           a->job.metric == b->job.metric && a->job.split == b->job.split && a->job.tol == b->job.tol &&
           a->group == b->group && memcmp(a->params, b->params, sizeof a->params) == 0;
}

/* The slot of a job like j (added if new); -1 on no memory. */
static long add_slot(ob_tab_plan *pl, const ob_tab_slot *j)
{
    for (long i = 0; i < pl->nslots; i++)
        if (same_job(&pl->slots[i], j))
            return i;
    if (pl->nslots == pl->cap_slots) {
        long cap = pl->cap_slots ? 2 * pl->cap_slots : 256;
        ob_tab_slot *nv = realloc(pl->slots, (size_t)cap * sizeof *nv);
        if (!nv)
            return -1;
        pl->slots = nv;
        pl->cap_slots = cap;
    }
    pl->slots[pl->nslots] = *j;
    return pl->nslots++;
}

static long slot_for(ob_tab_plan *pl, const ob_curve *curve, double d, const ob_tab_spec *s)
{
    ob_tab_slot j;
    memset(&j, 0, sizeof j);
    j.job.curve = curve;
    j.job.d = d;
    j.job.method = s->method;
    j.job.metric = s->metric;
    j.job.split = s->split;
    j.job.tol = s->tol;
    j.group = group_of(s);
    ob_param_defaults(s->method, j.params);
    for (int i = 0; i < s->nset; i++) {
        int k = ob_param_find(s->method, s->set_name[i]);
        if (k >= 0)
            j.params[k] = s->set_value[i];
    }
    return add_slot(pl, &j);
}

/* --table SOURCE:TABLE,...: is the cell's table selected (all when none)? */
/* Every name of --table (SOURCE:TABLE,...) is a published table; a typo is
 * refused with the list of valid names.  0, or -1 after ob_error(). */
static int check_table_names(const char *only, const ob_pub_set *pub)
{
    for (const char *p = only; p && *p;) {
        const char *e = strchr(p, ',');
        const int len = e ? (int)(e - p) : (int)strlen(p);
        int found = 0;
        for (int i = 0; i < pub->n && !found; i++) {
            char key[80];
            snprintf(key, sizeof key, "%s:%s", pub->v[i].source, pub->v[i].table);
            found = (int)strlen(key) == len && strncmp(p, key, (size_t)len) == 0;
        }
        if (!found) {
            char names[2048] = "";
            size_t k = 0;
            for (int i = 0; i < pub->n; i++) {
                char key[80];
                snprintf(key, sizeof key, "%s:%s", pub->v[i].source, pub->v[i].table);
                if (!strstr(names, key) && k + strlen(key) + 3 < sizeof names)
                    k += (size_t)snprintf(names + k, sizeof names - k, "%s%s", k ? ", " : "", key);
            }
            ob_error("--table: no table '%.*s' in %s; the tables are: %s", len, p, pub->where, names);
            return -1;
        }
        p = e ? e + 1 : p + len;
    }
    return 0;
}

static int selected(const char *only, const char *source, const char *table)
{
    if (!only)
        return 1;
    char key[80];
    snprintf(key, sizeof key, "%s:%s", source, table);
    const size_t n = strlen(key);
    for (const char *p = only; *p;) {
        const char *e = strchr(p, ',');
        const size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && strncmp(p, key, n) == 0)
            return 1;
        if (!e)
            break;
        p = e + 1;
    }
    return 0;
}

/* Plans the row of published cell c under protocol p: its run's slot, or
 * why it has none (r->fixed); 0, or -1 after ob_error(). */
static int plan_cell(ob_tab_plan *pl, const ob_pub_set *pub, const ob_pub_cell *c, ob_proto p,
                     const ob_curveset *set)
{
    ob_err err;
    ob_tab_row *r = &pl->rows[pl->nrows++];
    r->cell = c;
    r->proto = p;
    r->slot = -1;
    err.msg[0] = '\0'; /* find_curve's NULL without a message: no such curve */
    if (ob_tab_resolve(c, p, &r->spec, &err)) {
        ob_error("%s:%d: %s", pub->where, c->line, err.msg);
        return -1;
    }
    if (!r->spec.method) {
        r->fixed = "no-method";
        return 0;
    }
    const ob_curve *curve = find_curve(pl, set, &r->spec, &err);
    if (!curve && err.msg[0]) {
        ob_error("%s:%d: %s", pub->where, c->line, err.msg);
        return -1;
    }
    if (!curve || (isnan(c->d) && curve->nd == 0)) {
        r->fixed = "no-data";
        return 0;
    }
    r->d_run = r->spec.d_factor * (isnan(c->d) ? curve->d[0] : c->d);
    if ((r->slot = slot_for(pl, curve, r->d_run, &r->spec)) < 0) {
        ob_error("out of memory planning the tables");
        return -1;
    }
    return 0;
}

/* The pieces of Zhao-Zhou's quintic the sweep runs: the whole, and C1 and
 * C2 cut at each of sweep_cut; their names stay valid for the plan. */
static int sweep_pieces(const char *(*names)[1 + 2 * NCUTS])
{
    static char pieces[1 + 2 * NCUTS][64]; /* room for any int and %g: no truncation warning */
    int npieces = 0;
    snprintf(pieces[npieces++], sizeof pieces[0], "zhao2017_quintic/C");
    for (int k = 0; k < NCUTS; k++)
        for (int h = 1; h <= 2; h++) {
            if (sweep_cut[k] == 0.5)
                snprintf(pieces[npieces++], sizeof pieces[0], "zhao2017_quintic/C%d", h);
            else
                snprintf(pieces[npieces++], sizeof pieces[0], "zhao2017_quintic/C%d@%g", h, sweep_cut[k]);
        }
    for (int k = 0; k < npieces; k++)
        (*names)[k] = pieces[k];
    return npieces;
}

/* Plans one point of the sweep: piece at sweep_d[i] by methods[m] in
 * variant v (below); 0 (planned, or nothing to run), or -1 after
 * ob_error(). */
static int plan_sweep_point(ob_tab_plan *pl, const ob_curveset *set, ob_pub_cell *cell, const char *piece,
                            const char *method, ob_proto p, int v, int i)
{
    ob_err err;
    snprintf(cell->curve, sizeof cell->curve, "%.39s", piece);
    snprintf(cell->method, sizeof cell->method, "%s", method);
    ob_tab_spec s;
    if (ob_tab_resolve(cell, p, &s, &err) || !s.method)
        return 0;
    if (v == 1)
        s.metric = OB_METRIC_NORMAL;
    if (v == 3 && s.nset < OB_TAB_MAX_SET) {
        s.set_name[s.nset] = "weighted";
        s.set_value[s.nset++] = 0.0;
    }
    const ob_curve *curve = find_curve(pl, set, &s, &err);
    if (!curve)
        return 0;
    if (pl->nsweep == OB_TAB_MAX_SWEEP) {
        ob_error("more than %d points in the quintic's sweep", OB_TAB_MAX_SWEEP);
        return -1;
    }
    ob_tab_sweep *w = &pl->sweep[pl->nsweep++];
    w->piece = piece + strlen("zhao2017_quintic/");
    w->method = method;
    w->proto = p;
    w->metric = s.metric;
    w->variant = v == 3 ? "zhao-rational.weighted=0" : "";
    w->d = sweep_d[i];
    if ((w->slot = slot_for(pl, curve, sweep_d[i], &s)) < 0) {
        ob_error("out of memory planning the tables");
        return -1;
    }
    return 0;
}

/* Zhao-Zhou's quintic: its radius is not published, so sweep it; nor
 * where it was cut into C1 and C2: t = 1/2 (tables.md) and others.  0, or
 * -1 after ob_error(). */
static int plan_sweep(ob_tab_plan *pl, const ob_curveset *set, unsigned protos)
{
    const char *pieces[1 + 2 * NCUTS];
    const int npieces = sweep_pieces(&pieces);
    static const char *methods[] = {"lee", "zhao-rational"};
    ob_pub_cell cell;
    memset(&cell, 0, sizeof cell);
    snprintf(cell.source, sizeof cell.source, "zhao2017");
    snprintf(cell.table, sizeof cell.table, "1");
    snprintf(cell.unit, sizeof cell.unit, "max_err");
    /* paper (its metric), paper's former reading (normal), rigorous, and
     * paper with zhao-rational unweighted (the paper's steps as written) */
    for (int k = 0; k < npieces; k++)
        for (int m = 0; m < 2; m++)
            for (int v = 0; v < 4; v++)
                for (int i = 0; i < NSWEEP; i++) {
                    const ob_proto p = v == 2 ? OB_PROTO_RIGOROUS : OB_PROTO_PAPER;
                    if (!(protos & (1u << p)) || (v == 3 && m == 0))
                        continue;
                    if (plan_sweep_point(pl, set, &cell, pieces[k], methods[m], p, v, i) != 0)
                        return -1;
                }
    return 0;
}

/* Plans one row per (published cell, protocol), then the sweep. */
static int plan(ob_tab_plan *pl, const ob_pub_set *pub, const ob_curveset *set, const char *only,
                unsigned protos)
{
    pl->rows = calloc((size_t)pub->n * OB_PROTO_COUNT, sizeof *pl->rows);
    if (!pl->rows) {
        ob_error("out of memory planning the tables");
        return -1;
    }
    for (int i = 0; i < pub->n; i++)
        for (int p = 0; p < OB_PROTO_COUNT && selected(only, pub->v[i].source, pub->v[i].table); p++)
            if ((protos & (1u << p)) && plan_cell(pl, pub, &pub->v[i], (ob_proto)p, set) != 0)
                return -1;
    if (!selected(only, "zhao2017", "1"))
        return 0;
    return plan_sweep(pl, set, protos);
}

/* Runs every slot, one driver run per group of driver options. */
static int run_slots(ob_tab_plan *pl, const ob_run_opts *o, const ob_driver_hooks *base)
{
    ob_job *jobs = malloc((size_t)(pl->nslots ? pl->nslots : 1) * sizeof *jobs);
    long *idx = malloc((size_t)(pl->nslots ? pl->nslots : 1) * sizeof *idx);
    int rc = 0;
    if (!jobs || !idx) {
        ob_error("out of memory");
        rc = -1;
        goto done;
    }
    for (int g = 0; g < 4; g++) {
        size_t n = 0;
        for (long i = 0; i < pl->nslots; i++)
            if (pl->slots[i].group == g) {
                idx[n] = i;
                jobs[n] = pl->slots[i].job;
                jobs[n].params = pl->slots[i].params;
                n++;
            }
        if (n == 0)
            continue;
        ob_driver_opts d = o->driver;
        d.inflections = g & 1;
        if (g >= 2)
            d.max_depth = 0;
        ob_progress bar;
        ob_progress_init(&bar);
        ob_driver_hooks h = *base;
        h.progress = ob_progress_cb;
        h.progress_ctx = &bar;
        ob_span_log *logs = o->certify ? ob_span_logs_new(n) : NULL;  /* --certify: the pieces */
        if (o->certify && !logs) {
            ob_error("out of memory");
            rc = -1;
            break;
        }
        h.spans = logs;
        int drc = ob_driver_run(jobs, n, &d, &h);
        ob_progress_end(&bar);
        double secs = 0.0;
        if (drc == 0 && logs &&
            ob_certify_run(o->driver.samples, o->certify, o->driver.job_timeout_ns, jobs, n, logs, NULL, &secs) < 0)
            rc = -1;  /* a job not certified: said; its columns empty */
        ob_export_free(logs);
        for (size_t k = 0; k < n; k++) {
            const double *keep = pl->slots[idx[k]].job.params;
            pl->slots[idx[k]].job = jobs[k];
            pl->slots[idx[k]].job.params = keep;
        }
        if (drc == 1)
            break;  /* a signal: the caller says so */
        if (drc != 0) {
            ob_error("ran out of memory; unfinished jobs are marked fail");
            rc = -1;
        }
    }
done:
    free(jobs);
    free(idx);
    return rc;
}

static void plan_free(ob_tab_plan *pl)
{
    for (int k = 0; k < pl->npieces; k++) {
        free(pl->pieces[k].seg);
        free(pl->pieces[k].d);
    }
    free(pl->slots);
    free(pl->rows);
    memset(pl, 0, sizeof *pl);
}

/* The options `tables` shares with `run` are run's own (its flag table and
 * parser: the same defaults and messages). */
/* --protocols LIST: a bit per protocol; 0 on an unknown name. */
static unsigned parse_protocols(const char *list)
{
    unsigned bits = 0;
    for (const char *p = list; *p;) {
        const char *e = strchr(p, ',');
        const size_t len = e ? (size_t)(e - p) : strlen(p);
        int k = 0;
        while (k < OB_PROTO_COUNT &&
               !(strlen(ob_proto_name((ob_proto)k)) == len && strncmp(p, ob_proto_name((ob_proto)k), len) == 0))
            k++;
        if (k == OB_PROTO_COUNT)
            return 0;
        bits |= 1u << k;
        if (!e)
            break;
        p = e + 1;
    }
    return bits;
}

/* What tables' own options set. */
typedef struct {
    const char *out, *only;
    unsigned protos;
} tables_args;

enum { TO_OUT, TO_TABLE, TO_PROTOCOLS };

static const ob_flag tables_flags[] = {
    {"out", "DIR", "output directory (default out/tables)", TO_OUT, OB_FLAG_ONCE},
    {"table", "SOURCE:TABLE,...", "only these tables", TO_TABLE, OB_FLAG_ONCE},
    {"protocols", "LIST", "paper, rigorous, best (default all three)", TO_PROTOCOLS, OB_FLAG_ONCE},
};

static int apply_tables_flag(void *ctx, int id, const char *opt, const char *v)
{
    tables_args *t = ctx;
    if (id == TO_OUT)
        t->out = v;
    else if (id == TO_TABLE)
        t->only = v;
    else if (!(t->protos = parse_protocols(v))) {
        ob_error("%s: '%s': give one or more of paper, rigorous, best, separated by commas", opt, v);
        return -1;
    }
    return 0;
}

/* Returns 0, 1 after printing the help (--help), or -1 after ob_error(). */
static int parse_opts(int argc, char **argv, ob_run_opts *o, const char **only, unsigned *protos)
{
    tables_args t = {"out/tables", NULL, *protos};
    if (ob_run_opts_init(o, argc, argv))
        return -1;
    const ob_flagset sets[2] = {
        {tables_flags, (int)(sizeof tables_flags / sizeof tables_flags[0]), NULL, NULL, "options",
         apply_tables_flag, &t},
        {ob_run_flags, ob_run_nflags, "backend device threads certify ", NULL, "run options (as for run)",
         ob_run_flag_apply, o},
    };
    const int rc = ob_cli_parse("[--out DIR] [--table SOURCE:TABLE,...] [--protocols LIST] [run options]", sets, 2,
                                argc, argv, 0, NULL, NULL);
    if (rc != OB_CLI_OK)
        return rc == OB_CLI_HELP ? 1 : -1;
    if (ob_run_opt_set(o, "out", t.out))
        return -1;
    *only = t.only;
    *protos = t.protos;
    return ob_run_opts_finish(o) ? -1 : 0;
}

/* Writes tables.csv, tables.md and, with the sweep, zhao_sweep.csv into
 * dir, each whole; without the sweep an earlier run's is removed.  0, or
 * -1 when a write failed (said). */
static int write_tables(ob_tab_out *out, const char *dir)
{
    const ob_tab_plan *pl = out->pl;
    int rc = 0;
    if (ob_write_atomically(dir, "tables.csv", ob_tab_write_csv, out) != 0 ||
        ob_write_atomically(dir, "tables.md", ob_tab_write_md, out) != 0 ||
        (pl->nsweep > 0 && ob_write_atomically(dir, "zhao_sweep.csv", ob_tab_write_sweep, out) != 0))
        rc = -1;
    if (pl->nsweep == 0) {  /* --table without Zhao-Zhou's Table 1: no sweep, and none of an earlier run */
        char sp[4200];
        snprintf(sp, sizeof sp, "%s/zhao_sweep.csv", dir);
        remove(sp);
    }
    return rc;
}

/* The closing line: the rows by status and, with --certify, those whose
 * job's certified error is within tol. */
static void say_tables(const ob_tab_plan *pl, const ob_pub_set *pub, const ob_run_opts *o, double wall)
{
    int cnt[OB_TAB_NSTATUS] = {0};
    for (int i = 0; i < pl->nrows; i++)
        cnt[ob_tab_row_status(pl, &pl->rows[i], NULL)]++;
    char cert[80] = "";
    if (o->certify) {
        int yes = 0, done = 0;
        for (int i = 0; i < pl->nrows; i++)
            if (pl->rows[i].slot >= 0 && pl->slots[pl->rows[i].slot].job.cert_done) {
                const ob_job *j = &pl->slots[pl->rows[i].slot].job;
                done++;
                yes += ob_job_certified(j);
            }
        snprintf(cert, sizeof cert, "; certified within tol %d of %d", yes, done);
    }
    ob_info("%d rows (of %d published cells x %d protocols; %ld jobs, %.1f s): match %d, close %d, "
            "differs %d, no-method %d, no-data %d%s; wrote %s/tables.csv and tables.md",
            pl->nrows, pub->n, (int)OB_PROTO_COUNT, pl->nslots, wall, cnt[0], cnt[1], cnt[2], cnt[3], cnt[4], cert,
            o->out_dir);
}

int ob_cmd_tables(int argc, char **argv, int full_argc, char **full_argv)
{
    ob_run_opts o;
    ob_curveset set = {0};
    ob_pub_set pub = {0};
    ob_tab_plan pl;
    ob_cl *cl = NULL;
    int status = 2;
    char where[4096];
    ob_err err;
    memset(&pl, 0, sizeof pl);
    memset(&o, 0, sizeof o);
    const char *only = NULL;
    unsigned protos = (1u << OB_PROTO_COUNT) - 1;
    int prc = parse_opts(argc, argv, &o, &only, &protos);
    if (prc != 0) {
        status = prc > 0 ? 0 : 2;
        goto done;
    }
    o.argc = full_argc;
    o.argv = full_argv;
    if (ob_pub_load(&pub, &err) != 0) {
        ob_error("%s", err.msg);
        goto done;
    }
    if (check_table_names(only, &pub) != 0)
        goto done;
    if (ob_load_default_curves(&set, where, sizeof where, &err) != 0) {
        ob_error("%s", err.msg);
        goto done;
    }
    if (o.threads > 0)
        omp_set_num_threads(o.threads);
    if (plan(&pl, &pub, &set, only, protos) != 0)
        goto done;
    if (pl.nrows == 0) {
        ob_error("--table %s: no such table in %s (tables are SOURCE:TABLE, e.g. liu2002:1)", only, pub.where);
        goto done;
    }
    ob_backend_info binfo = {0};
    unsigned metrics = 0;  /* the programs the tables' jobs use */
    for (long i = 0; i < pl.nslots; i++)
        metrics |= 1u << pl.slots[i].job.metric;
    const int brc = ob_open_backend(o.backend, o.device, metrics, &binfo, &cl);
    if (brc != 0) {  /* before --out: a run that cannot start creates nothing */
        status = ob_backend_exit(brc);
        goto done;
    }
    if (ob_mkdir_p(o.out_dir) != 0) {
        ob_error("--out: cannot create '%s': %s", o.out_dir, strerror(errno));
        status = 1;
        goto done;
    }
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    ob_driver_hooks hooks = {0};
    ob_backend_hooks(cl, &binfo, &hooks);
    hooks.stop = ob_stop_flag();
    int rrc = run_slots(&pl, &o, &hooks);
    if (ob_stop_signal()) {  /* half the jobs are no table: none is written */
        status = ob_stop_exit("nothing written to %s (a tables.csv or tables.md there is an earlier run's); "
                              "run the command again", o.out_dir);
        goto done;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double wall = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
    ob_tab_out out = {&pl, &pub, where, &o, wall};
    status = write_tables(&out, o.out_dir) != 0 ? 1 : rrc ? 1 : 0;
    say_tables(&pl, &pub, &o, wall);
done:
    ob_cl_close(cl);
    plan_free(&pl);
    ob_pub_free(&pub);
    ob_curveset_free(&set);
    ob_run_opts_free(&o);
    return status;
}
