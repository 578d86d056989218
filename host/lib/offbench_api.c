/*
 * offbench_api.c - liboffbench's C API (include/offbench.h): a thin layer
 * over the code `offbench` itself runs.  Curves come from the curve-file
 * reader (arrays are written as curve-file text and read by it, so both
 * take the same checks), a fit is a one-job ob_driver_run with the run
 * command's defaults, its pieces are the accepted spans refitted
 * (ob_approx_from_job, as --export), and a measurement is `measure`'s
 * one path (ob_measure_approx: match, cover, measure), or --trimmed's
 * (ob_measure_trimmed), or --per-piece's (ob_approx_per_piece after the
 * one path).  No state besides the handles
 * (and the SISL server's path, set once: host/lib/sisl_exe.c).
 */
#define _GNU_SOURCE 1 /* open_memstream's prototype with older glibc */
#include "include/offbench.h"

#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/approx.h"
#include "host/io/columns.h"
#include "host/io/curvefile.h"
#include "host/io/datadir.h"
#include "host/io/output.h"
#include "host/lib/lib_thread.h"
#include "host/lib/sisl_exe.h"
#include "host/measure/measure.h"
#include "host/measure/perpiece.h"
#include "host/measure/trim.h"
#include "host/run/clock.h"
#include "methods/core/offdeg.h"
#include "methods/driver/driver.h"
#include "methods/external/ext.h"
#include "methods/metrics/cert_job.h"

struct obx_curveset {
    ob_curveset set;
};

struct obx_result {
    ob_job job;
    double params[OB_MAX_PARAMS];
    ob_approx pieces;
    char *row;
    int cert_tight;     /* its certificate (job.cert_done) is obx_result_certify's tight mode */
};

/* Sets err (may be NULL) and returns -1. */
static int fail(obx_error *err, obx_code code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(obx_error *err, obx_code code, const char *fmt, ...)
{
    if (!err)
        return -1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    err->code = code;
    return -1;
}

const char *obx_version(void)
{
    return OBX_VERSION;
}

/* ---- curves ---------------------------------------------------------------- */

/* Fills in each curve's exact offset degree (results.csv's offset_degree,
 * offset_rational), as the run command does before it plans its jobs. */
static void offset_degrees(ob_curveset *s)
{
    for (int c = 0; c < s->n; c++) {
        ob_curve *cv = &s->v[c];
        char msg[160];
        if (ob_curve_offset_degree(cv, &cv->offset_degree, &cv->offset_rational, msg, sizeof msg) == 0)
            cv->offset_known = 1;
    }
}

/* A new handle owning *s (emptied), or -1 with OBX_E_NOMEM. */
static int wrap_set(ob_curveset *s, obx_curveset **out, obx_error *err)
{
    obx_curveset *h = malloc(sizeof *h);
    if (!h) {
        ob_curveset_free(s);
        return fail(err, OBX_E_NOMEM, "out of memory");
    }
    offset_degrees(s);
    h->set = *s;
    memset(s, 0, sizeof *s);
    *out = h;
    return 0;
}

/* The reader's message's code: unreadable files are IO, the rest PARSE. */
static obx_code load_code(const char *path, const char *msg)
{
    size_t k = strlen(path);
    return strncmp(msg, path, k) == 0 && msg[k] == ':' && msg[k + 1] == ' ' ? OBX_E_IO : OBX_E_PARSE;
}

int obx_curves_load_file(const char *path, obx_curveset **out, obx_error *err)
{
    if (!path || !out)
        return fail(err, OBX_E_INVALID, "obx_curves_load_file: NULL %s", path ? "out" : "path");
    ob_curveset s = {0};
    ob_err e;
    if (ob_curves_load_file(path, &s, &e) != 0) {
        ob_curveset_free(&s);
        return fail(err, load_code(path, e.msg), "%s", e.msg);
    }
    return wrap_set(&s, out, err);
}

int obx_curves_load_default(obx_curveset **out, obx_error *err)
{
    if (!out)
        return fail(err, OBX_E_INVALID, "obx_curves_load_default: NULL out");
    ob_curveset s = {0};
    ob_err e;
    char where[512];
    if (ob_load_default_curves(&s, where, sizeof where, &e) != 0) {
        ob_curveset_free(&s);
        return fail(err, OBX_E_PARSE, "%s", e.msg);
    }
    return wrap_set(&s, out, err);
}

/* Checks what the reader's message could not name by segment and point:
 * counts, degrees, finite numbers, weights.  Counts the points in *npts. */
static int check_arrays(const char *id, int nseg, const int *degrees, const double *xy, const double *w, size_t *npts,
                        obx_error *err)
{
    if (!id || !degrees || !xy || nseg < 1)
        return fail(err, OBX_E_INVALID, "obx_curves_from_arrays: %s",
                    !id ? "NULL id" : nseg < 1 ? "nseg must be >= 1" : "NULL degrees or xy");
    size_t k = 0;
    for (int s = 0; s < nseg; s++) {
        if (degrees[s] < 1 || degrees[s] > OB_MAX_IN_DEG)
            return fail(err, OBX_E_INVALID, "curve '%s': segment %d: degree %d (must be 1 to %d)", id, s, degrees[s],
                        OB_MAX_IN_DEG);
        for (int i = 0; i <= degrees[s]; i++, k++) {
            if (!isfinite(xy[2 * k]) || !isfinite(xy[2 * k + 1]))
                return fail(err, OBX_E_INVALID, "curve '%s': segment %d: point %d is not finite", id, s, i);
            if (w && !(isfinite(w[k]) && w[k] > 0))
                return fail(err, OBX_E_INVALID, "curve '%s': segment %d: weight %d is %g (must be > 0, finite)", id,
                            s, i, w[k]);
        }
    }
    *npts = k;
    return 0;
}

/* One segment as curve-file text, with one offset line (a placeholder the
 * caller drops: the format asks for one).  NULL when out of memory. */
static char *segment_text(const char *id, int degree, const double *xy, const double *w, size_t *len)
{
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (!f)
        return NULL;
    fprintf(f, "curve %s\n  source obx_curves_from_arrays\n  bezier %d\n", id, degree);
    double big = 1.0;
    for (int i = 0; i <= degree; i++) {
        fprintf(f, "  point %.17g %.17g %.17g\n", xy[2 * i], xy[2 * i + 1], w ? w[i] : 1.0);
        big = fmax(big, fmax(fabs(xy[2 * i]), fabs(xy[2 * i + 1])));
    }
    fprintf(f, "  offset %.17g\nend\n", fmin(big, 1e12));
    if (fclose(f) != 0) {
        free(text);
        return NULL;
    }
    return text;
}

/* Segment s read by the curve-file reader into *one (a curve file holds one
 * Bézier segment per curve, so each is read on its own); its messages are
 * named "obx_curves_from_arrays" for a one-segment curve, else
 * "obx_curves_from_arrays segment S". */
static int read_segment(const char *id, int nseg, int s, int degree, const double *xy, const double *w,
                        ob_curveset *one, obx_error *err)
{
    size_t len = 0;
    char *text = segment_text(id, degree, xy, w, &len);
    if (!text)
        return fail(err, OBX_E_NOMEM, "out of memory");
    char name[64];
    snprintf(name, sizeof name, nseg > 1 ? "obx_curves_from_arrays segment %d" : "obx_curves_from_arrays", s);
    ob_err e;
    int rc = ob_curves_parse(text, len, name, one, &e);
    free(text);
    return rc ? fail(err, OBX_E_INVALID, "%s", e.msg) : 0;
}

/* Segment 0 of `one` appended to curve c (which takes over the segment). */
static int append_segment(ob_curve *c, const ob_curve *one, obx_error *err)
{
    ob_bez *v = realloc(c->seg, (size_t)(c->nseg + 1) * sizeof *v);
    if (!v)
        return fail(err, OBX_E_NOMEM, "out of memory");
    c->seg = v;
    c->seg[c->nseg++] = one->seg[0];
    c->coord_max = fmax(c->coord_max, one->coord_max);
    return 0;
}

int obx_curves_from_arrays(const char *id, int nseg, const int *degrees, const double *xy, const double *w,
                           obx_curveset **out, obx_error *err)
{
    size_t npts = 0;
    if (!out)
        return fail(err, OBX_E_INVALID, "obx_curves_from_arrays: NULL out");
    if (check_arrays(id, nseg, degrees, xy, w, &npts, err))
        return -1;
    if (strlen(id) > 63 || strspn(id, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./") !=
                               strlen(id) || !*id)
        return fail(err, OBX_E_INVALID, "curve id '%.80s': 1 to 63 letters, digits, '_', '-', '.', '/'", id);
    ob_curveset s = {0};
    int rc = 0;
    for (int g = 0, k = 0; g < nseg && rc == 0; k += degrees[g] + 1, g++) {
        ob_curveset one = {0};
        const double *wg = w ? w + k : NULL;
        rc = read_segment(id, nseg, g, degrees[g], xy + 2 * k, wg, g ? &one : &s, err);
        if (rc == 0 && g)
            rc = append_segment(&s.v[0], &one.v[0], err);
        ob_curveset_free(&one);
    }
    if (rc) {
        ob_curveset_free(&s);
        return -1;
    }
    s.v[0].nd = 0; /* the placeholder offset */
    return wrap_set(&s, out, err);
}

void obx_curves_free(obx_curveset *set)
{
    if (!set)
        return;
    ob_curveset_free(&set->set);
    free(set);
}

int obx_curves_count(const obx_curveset *set)
{
    return set ? set->set.n : 0;
}

const char *obx_curves_id(const obx_curveset *set, int i)
{
    return set && i >= 0 && i < set->set.n ? set->set.v[i].id : NULL;
}

int obx_curves_find(const obx_curveset *set, const char *id)
{
    return set ? ob_curveset_find(&set->set, id) : -1;
}

int obx_curves_offsets(const obx_curveset *set, int i, const double **d)
{
    if (!set || i < 0 || i >= set->set.n)
        return 0;
    if (d)
        *d = set->set.v[i].d;
    return set->set.v[i].nd;
}

int obx_curves_segment_count(const obx_curveset *set, int i)
{
    return set && i >= 0 && i < set->set.n ? set->set.v[i].nseg : 0;
}

/* Bézier b's degree, and its Euclidean points and weights into the buffers
 * (either may be NULL) when they hold cap >= degree + 1 points; what names
 * b in a message is what. */
static int bez_out(const ob_bez *b, const char *what, double *xy, double *w, int cap, obx_error *err)
{
    if ((xy || w) && cap < b->deg + 1)
        return fail(err, OBX_E_INVALID, "%s has degree %d: the buffers need %d points, not %d", what, b->deg,
                    b->deg + 1, cap);
    for (int i = 0; i <= b->deg && (xy || w); i++) {
        double p[2];
        ob_bez_ctrl(b, i, p);
        if (xy) {
            xy[2 * i] = p[0];
            xy[2 * i + 1] = p[1];
        }
        if (w)
            w[i] = ob_bez_weight(b, i);
    }
    return b->deg;
}

int obx_curves_segment(const obx_curveset *set, int i, int k, double *xy, double *w, int cap, obx_error *err)
{
    if (k < 0 || k >= obx_curves_segment_count(set, i))
        return fail(err, OBX_E_INVALID, "obx_curves_segment: %s", obx_curves_segment_count(set, i)
                                                                     ? "no such segment index" : "no such curve index");
    char what[96];
    snprintf(what, sizeof what, "curve '%s' segment %d", set->set.v[i].id, k);
    return bez_out(&set->set.v[i].seg[k], what, xy, w, cap, err);
}

const char *obx_curves_family(const obx_curveset *set, int i)
{
    return set && i >= 0 && i < set->set.n ? set->set.v[i].family : NULL;
}

/* ---- methods ---------------------------------------------------------------- */

int obx_method_count(void)
{
    return ob_method_count();
}

static const ob_method *method_at(int i)
{
    return i >= 0 && i < ob_method_count() ? ob_methods[i] : NULL;
}

const char *obx_method_name(int i)
{
    const ob_method *m = method_at(i);
    return m ? m->name : NULL;
}

const char *obx_method_citation(int i)
{
    const ob_method *m = method_at(i);
    return m ? m->citation : NULL;
}

int obx_external_register(const char *name, const char *command, obx_error *err)
{
    if (!name || !command)
        return fail(err, OBX_E_INVALID, "obx_external_register: NULL %s", name ? "command" : "name");
    char msg[400];
    /* the same method again is 0 (Python registers its function before
     * every run); the check and the registration are one step, under the
     * registry's lock, so that threads registering at once cannot race */
    if (ob_ext_register_once(name, command, msg, sizeof msg) == 0)
        return 0;
    const ob_method *m = ob_method_find(name);
    const ob_ext *e = m ? ob_ext_of(m) : NULL;
    if (m && !e)
        return fail(err, OBX_E_INVALID, "obx_external_register %s: the name '%s' is a built-in method", name, name);
    if (e)
        return fail(err, OBX_E_INVALID, "obx_external_register %s: registered with another command `%s`", name,
                    e->command);
    return fail(err, OBX_E_INVALID, "obx_external_register %s: %s", name, msg);
}

int obx_method_param_count(int i)
{
    const ob_method *m = method_at(i);
    return m ? m->nparams : 0;
}

int obx_method_param(int i, int k, obx_param_info *out, obx_error *err)
{
    const ob_method *m = method_at(i);
    if (!m || !out || k < 0 || k >= m->nparams)
        return fail(err, OBX_E_INVALID, "obx_method_param: %s", !m ? "no such method index"
                                                               : !out ? "NULL out" : "no such parameter index");
    const ob_param *p = &m->params[k];
    *out = (obx_param_info){p->name, p->def, p->min, p->max, p->integer, p->doc};
    return 0;
}

/* ---- fit ------------------------------------------------------------------------ */

/* The names a message lists: every method's. */
static void method_names(char *buf, size_t len)
{
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; ob_methods[i] && k < len; i++)
        k += (size_t)snprintf(buf + k, len - k, "%s%s", i ? ", " : "", ob_methods[i]->name);
}

/* "NAME=VALUE[,...]" onto par (the defaults already there). */
static int parse_params(const ob_method *m, const char *spec, double *par, obx_error *err)
{
    char buf[512];
    if (strlen(spec) >= sizeof buf)
        return fail(err, OBX_E_INVALID, "parameters '%.40s...': too long", spec);
    strcpy(buf, spec);
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '=');
        if (!eq)
            return fail(err, OBX_E_INVALID, "parameter '%s': not NAME=VALUE", tok);
        *eq = '\0';
        int k = ob_param_find(m, tok);
        if (k < 0)
            return fail(err, OBX_E_INVALID, "method %s has no parameter '%s'", m->name, tok);
        char *end;
        double v = strtod(eq + 1, &end);
        char msg[256];
        if (end == eq + 1 || *end)
            return fail(err, OBX_E_INVALID, "parameter %s.%s: '%s' is not a number", m->name, tok, eq + 1);
        if (ob_param_check(m, &m->params[k], v, msg, sizeof msg))
            return fail(err, OBX_E_INVALID, "%s", msg);
        par[k] = v;
    }
    return 0;
}

/* Checks and names of a fit's or a measurement's arguments. */
static int check_curve_d(const obx_curveset *set, int curve, double d, obx_error *err)
{
    if (!set || curve < 0 || curve >= set->set.n)
        return fail(err, OBX_E_INVALID, "%s", !set ? "NULL curve set" : "curve index out of range");
    char why[200];
    if (ob_offset_check(d, set->set.v[curve].coord_max, why, sizeof why))
        return fail(err, OBX_E_INVALID, "curve '%s': %s", set->set.v[curve].id, why);
    return 0;
}

static int parse_metric(const char *name, ob_metric *m, obx_error *err)
{
    if (ob_metric_parse(name ? name : "hausdorff", m) != 0)
        return fail(err, OBX_E_INVALID, "unknown metric '%s' (bound, radial, normal, hausdorff, param, certified; obx_measure: "
                    "hausdorff-whole and trimmed-hausdorff too)", name);
    return 0;
}

/* The job's inputs from the arguments, into r->job. */
static int set_job(obx_result *r, const obx_curveset *set, int curve, const char *method, double d, double tol,
                   const char *metric, const char *split, const char *params, obx_error *err)
{
    if (check_curve_d(set, curve, d, err))
        return -1;
    const ob_method *m = method ? ob_method_find(method) : NULL;
    if (!m) {
        char names[1024];
        method_names(names, sizeof names);
        return fail(err, OBX_E_INVALID, "unknown method '%s' (%s)", method ? method : "(null)", names);
    }
    if (!(isfinite(tol) && tol > 0))
        return fail(err, OBX_E_INVALID, "tolerance %g: must be finite and > 0", tol);
    ob_job *j = &r->job;
    if (parse_metric(metric, &j->metric, err))
        return -1;
    if (ob_split_parse(split ? split : "mid", &j->split) != 0)
        return fail(err, OBX_E_INVALID, "unknown split '%s' (mid, maxerr, greedy, optimal)", split);
    ob_param_defaults(m, r->params);
    if (params && parse_params(m, params, r->params, err))
        return -1;
    j->curve = &set->set.v[curve];
    j->d = d;
    j->method = m;
    j->params = r->params;
    j->tol = tol;
    return 0;
}

/* The job's results.csv row, without its newline, into r->row. */
static int make_row(obx_result *r)
{
    size_t len = 0;
    FILE *f = open_memstream(&r->row, &len);
    if (!f)
        return -1;
    int rc = ob_write_result_row(f, &r->job);
    if (fclose(f) != 0 || rc != 0)
        return -1;
    if (len && r->row[len - 1] == '\n')
        r->row[len - 1] = '\0';
    return 0;
}

/* After the driver ran r's job: its pieces (from its span log) and row. */
static int finish_result(obx_result *r, const ob_span_log *log, obx_error *err)
{
    ob_err e;
    if ((r->job.status == OB_OK || r->job.status == OB_LIMIT) &&
        ob_approx_from_job(&r->job, log, &r->pieces, &e) != 0)
        return fail(err, OBX_E_NOMEM, "the job's pieces: %s", e.msg);
    if (make_row(r) != 0)
        return fail(err, OBX_E_NOMEM, "out of memory");
    return 0;
}

static int drive(ob_job *jobs, size_t n, ob_driver_hooks *hooks, obx_progress_stop_fn progress, void *ctx);

/* Runs r's job (on a library thread: drive) and keeps its pieces. */
static int run_job(obx_result *r, obx_error *err)
{
    ob_span_log log = {0};
    ob_driver_hooks hooks = {0};
    hooks.spans = &log;
    int rc = drive(&r->job, 1, &hooks, NULL, NULL) == 0 ? finish_result(r, &log, err)
                                                         : fail(err, OBX_E_NOMEM, "out of memory");
    free(log.v);
    return rc;
}

/* The method sisl needs its server program (host/lib/sisl_exe.h). */
static int sisl_ready(const ob_method *m, obx_error *err)
{
    char why[480];
    if (strcmp(m->name, "sisl") != 0 || ob_lib_sisl_ready(why, sizeof why) == 0)
        return 0;
    return fail(err, OBX_E_UNSUPPORTED, "method sisl: %s", why);
}

int obx_fit(const obx_curveset *set, int curve, const char *method, double d, double tol, const char *metric,
            const char *split, const char *params, obx_result **out, obx_error *err)
{
    if (!out)
        return fail(err, OBX_E_INVALID, "obx_fit: NULL out");
    obx_result *r = calloc(1, sizeof *r);
    if (!r)
        return fail(err, OBX_E_NOMEM, "out of memory");
    if (set_job(r, set, curve, method, d, tol, metric, split, params, err) || sisl_ready(r->job.method, err) ||
        run_job(r, err)) {
        obx_result_free(r);
        return -1;
    }
    *out = r;
    return 0;
}

void obx_result_free(obx_result *r)
{
    if (!r)
        return;
    ob_approx_free(&r->pieces);
    free(r->row);
    free(r);
}

const char *obx_result_status(const obx_result *r)
{
    return ob_status_name(r->job.status);
}

double obx_result_max_err(const obx_result *r)
{
    return r->job.max_err;
}

long obx_result_ctrl_points(const obx_result *r)
{
    return r->job.ctrl_points;
}

int obx_result_segments(const obx_result *r)
{
    return r->job.segments;
}

const char *obx_result_message(const obx_result *r)
{
    return r->job.message;
}

const char *obx_result_row(const obx_result *r)
{
    return r->row;
}

const char *obx_results_header(void)
{
    return ob_results_header();
}

int obx_result_piece_count(const obx_result *r)
{
    return r->pieces.n;
}

int obx_result_piece(const obx_result *r, int k, double *xy, double *w, int cap, obx_error *err)
{
    if (!r || k < 0 || k >= r->pieces.n)
        return fail(err, OBX_E_INVALID, "obx_result_piece: no piece %d", k);
    char what[32];
    snprintf(what, sizeof what, "piece %d", k);
    return bez_out(&r->pieces.v[k].approx, what, xy, w, cap, err);
}

/* ---- certify ---------------------------------------------------------------- */

int obx_result_certify(obx_result *r, const char *mode, double *upper, double *lower, obx_error *err)
{
    if (upper)
        *upper = NAN;
    if (lower)
        *lower = NAN;
    if (!r)
        return fail(err, OBX_E_INVALID, "obx_result_certify: NULL result");
    const int tight = mode && strcmp(mode, "tight") == 0;
    if (mode && !tight && strcmp(mode, "verdict") != 0)
        return fail(err, OBX_E_INVALID, "unknown certificate mode '%s' (verdict, tight)", mode);
    ob_job *j = &r->job;
    if (!(j->status == OB_OK || j->status == OB_LIMIT) || r->pieces.n == 0)
        return 0;  /* no approximation: nothing to certify, its columns stay empty (as run --certify's) */
    if (j->cert_done == OB_CERT_DONE && r->cert_tight == tight) {  /* twice: the same certificate */
        if (upper)
            *upper = j->err_upper;
        if (lower)
            *lower = j->err_lower;
        return 0;
    }
    /* as host/run/certify.c: each piece against the exact offset of its base piece */
    const int n = r->pieces.n;
    ob_bez *base = malloc((size_t)n * sizeof *base), *apx = malloc((size_t)n * sizeof *apx);
    ob_cert_src *src = malloc((size_t)n * sizeof *src);
    if (!base || !apx || !src) {
        free(base);
        free(apx);
        free(src);
        return fail(err, OBX_E_NOMEM, "out of memory");
    }
    for (int k = 0; k < n; k++) {
        const ob_apiece *p = &r->pieces.v[k];
        apx[k] = p->approx;
        if (ob_apiece_base(j->curve, p, &base[k]) != 0) {
            free(base);
            free(apx);
            free(src);
            return fail(err, OBX_E_INVALID, "obx_result_certify: piece %d has no base piece", k);
        }
        src[k] = (ob_cert_src){&j->curve->seg[p->seg], p->a, p->b, p->t0, p->t1};  /* the segment as stored */
    }
    ob_cert_opts co;
    ob_cert_defaults(&co);
    co.decide = j->tol;  /* refined to a verdict where the enclosure straddles tol (certify.c) */
    co.verdict = !tight;  /* run --certify's default: the verdict alone; tight: to rtol */
    ob_driver_opts dopt;
    ob_driver_defaults(&dopt);  /* obx_fit's samples: the feet the certificate starts from */
    ob_cert_job cj;
    const double t0 = ob_thread_ns();
    const int crc = ob_certify_job_src(n, base, src, apx, j->d, ob_clamp_samples(dopt.samples), &co, NULL, &cj, NULL);
    const double ns = ob_thread_ns() - t0;
    free(base);
    free(apx);
    free(src);
    if (crc != 0 && cj.failed == 0)
        return fail(err, OBX_E_NOMEM, "out of memory");
    j->cert_ns = ns;
    j->err_upper = crc != 0 ? INFINITY : cj.upper;  /* a piece unbounded: the job is */
    j->err_lower = cj.lower;
    j->cert_done = OB_CERT_DONE;
    r->cert_tight = tight;
    free(r->row);
    r->row = NULL;
    if (make_row(r) != 0)
        return fail(err, OBX_E_NOMEM, "out of memory");
    if (upper)
        *upper = j->err_upper;
    if (lower)
        *lower = j->err_lower;
    return 0;
}

/* ---- batch ------------------------------------------------------------------ */

/* A batch whose driver runs on a library thread (lib_thread.h) while the
 * calling thread tells the callback: the driver's hook only records the
 * count, under mu, so the callback runs outside every lock the driver
 * holds (it may fit or run a batch itself) and on the caller's thread. */
typedef struct {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    size_t done, total;             /* the latest count the driver told */
    int finished, rc;               /* the driver returned rc */
    volatile sig_atomic_t stop;     /* the callback asked to stop (hooks.stop) */
    ob_job *jobs;
    size_t n;
    ob_driver_hooks *hooks;
} batch_run;

static void progress_hook(void *ctx, const ob_progress_info *pi)
{
    batch_run *b = ctx;
    pthread_mutex_lock(&b->mu);
    if (pi->done > b->done) {  /* ticks without a new job are not told: counts rise strictly */
        b->done = pi->done;
        b->total = pi->total;
        pthread_cond_signal(&b->cv);
    }
    pthread_mutex_unlock(&b->mu);
}

static void batch_work(void *arg)
{
    batch_run *b = arg;
    ob_driver_opts o;
    ob_driver_defaults(&o);
    b->rc = ob_driver_run(b->jobs, b->n, &o, b->hooks);
}

static void batch_done(void *arg)
{
    batch_run *b = arg;
    pthread_mutex_lock(&b->mu);
    b->finished = 1;
    pthread_cond_signal(&b->cv);
    pthread_mutex_unlock(&b->mu);
}

/* The calling thread's part: each new count to progress (unlocked) until
 * the driver returns; a nonzero answer stops it at its next batch, and
 * nothing more is told.  The driver's return code. */
static int tell_until_done(batch_run *b, obx_progress_stop_fn progress, void *ctx)
{
    size_t told = 0;
    pthread_mutex_lock(&b->mu);
    for (;;) {
        if (progress && b->done > told && !b->stop) {
            const size_t done = b->done, total = b->total;
            pthread_mutex_unlock(&b->mu);
            if (progress(ctx, done, total) != 0)
                b->stop = 1;
            told = done;
            pthread_mutex_lock(&b->mu);
        } else if (b->finished) {
            break;
        } else {
            pthread_cond_wait(&b->cv, &b->mu);
        }
    }
    pthread_mutex_unlock(&b->mu);
    return b->rc;
}

/* ob_driver_run of the jobs on a library thread, with progress (if any)
 * told as above.  Always on a library thread, also without progress: the
 * driver's OpenMP regions then never run on the caller's thread, whose
 * libgomp thread pool a forked child (Python's multiprocessing) would
 * inherit without its threads and wait on for ever; a child's library
 * thread is new (lib_thread.c forgets the parent's at the fork) and starts
 * a pool of its own.  0, 1 (stopped), -1 (memory, or no thread). */
static int drive(ob_job *jobs, size_t n, ob_driver_hooks *hooks, obx_progress_stop_fn progress, void *ctx)
{
    batch_run b = {PTHREAD_MUTEX_INITIALIZER, PTHREAD_COND_INITIALIZER, 0, n, 0, 0, 0, jobs, n, hooks};
    if (progress) {
        hooks->progress = progress_hook;
        hooks->progress_ctx = &b;
        hooks->stop = &b.stop;
    }
    if (ob_lib_thread_run(batch_work, batch_done, &b) != 0)
        return -1;
    const int rc = tell_until_done(&b, progress, ctx);
    return b.stop ? 1 : rc;  /* asked to stop: stopped, also when the last batch had run */
}

/* Results for the n specs, their jobs checked; NULL entries on failure
 * (the caller frees what was made). */
static int make_results(const obx_curveset *set, const obx_job_spec *jobs, size_t n, obx_result **out,
                        obx_error *err)
{
    for (size_t i = 0; i < n; i++) {
        const obx_job_spec *j = &jobs[i];
        if (!(out[i] = calloc(1, sizeof *out[i])))
            return fail(err, OBX_E_NOMEM, "out of memory");
        obx_error e = {0, ""};
        if (set_job(out[i], set, j->curve, j->method, j->d, j->tol, j->metric, j->split, j->params, &e) ||
            sisl_ready(out[i]->job.method, &e))
            return fail(err, (obx_code)e.code, "job %zu: %.480s", i, e.message);
    }
    return 0;
}

/* The driver over the results' jobs (copied into one array), then each
 * result's pieces and row. */
static int run_batch(obx_result **res, size_t n, obx_progress_stop_fn progress, void *ctx, obx_error *err)
{
    ob_job *jobs = malloc(n * sizeof *jobs);
    ob_span_log *logs = calloc(n, sizeof *logs);
    int rc = jobs && logs ? 0 : fail(err, OBX_E_NOMEM, "out of memory");
    for (size_t i = 0; i < n && rc == 0; i++)
        jobs[i] = res[i]->job;
    ob_driver_hooks hooks = {0};
    hooks.spans = logs;
    const int drc = rc == 0 ? drive(jobs, n, &hooks, progress, ctx) : 0;
    if (drc == 1)
        rc = fail(err, OBX_E_STOPPED, "obx_run_batch: stopped by its progress callback");
    else if (drc != 0)
        rc = fail(err, OBX_E_NOMEM, "out of memory");
    for (size_t i = 0; i < n && rc == 0; i++) {
        res[i]->job = jobs[i];
        res[i]->job.params = res[i]->params;
        rc = finish_result(res[i], &logs[i], err);
    }
    for (size_t i = 0; logs && i < n; i++)
        free(logs[i].v);
    free(logs);
    free(jobs);
    return rc;
}

int obx_run_batch_stop(const obx_curveset *set, const obx_job_spec *jobs, size_t n, obx_progress_stop_fn progress,
                       void *ctx, obx_result **out, obx_error *err)
{
    if (!jobs || !out || n == 0)
        return fail(err, OBX_E_INVALID, "obx_run_batch: %s", n == 0 ? "no jobs" : "NULL jobs or out");
    memset(out, 0, n * sizeof *out);
    if (make_results(set, jobs, n, out, err) == 0 && run_batch(out, n, progress, ctx, err) == 0)
        return 0;
    for (size_t i = 0; i < n; i++) {
        obx_result_free(out[i]);
        out[i] = NULL;
    }
    return -1;
}

/* obx_run_batch's callback, told through obx_run_batch_stop's: it never stops. */
typedef struct {
    obx_progress_fn fn;
    void *ctx;
} plain_progress;

static int plain_told(void *ctx, size_t done, size_t total)
{
    const plain_progress *p = ctx;
    p->fn(p->ctx, done, total);
    return 0;
}

int obx_run_batch(const obx_curveset *set, const obx_job_spec *jobs, size_t n, obx_progress_fn progress, void *ctx,
                  obx_result **out, obx_error *err)
{
    plain_progress p = {progress, ctx};
    return obx_run_batch_stop(set, jobs, n, progress ? plain_told : NULL, &p, out, err);
}

/* ---- measure ------------------------------------------------------------------ */

/* The pieces as an approximation without links; fn names the call in a
 * message about the arrays themselves. */
static int pieces_approx(const char *fn, int npieces, const int *degrees, const double *xy, const double *w,
                         ob_approx *a, obx_error *err)
{
    if (npieces < 1 || !degrees || !xy)
        return fail(err, OBX_E_INVALID, "%s: %s", fn, npieces < 1 ? "no pieces" : "NULL degrees or xy");
    size_t k = 0;
    for (int p = 0; p < npieces; p++) {
        if (degrees[p] < 1 || degrees[p] > OB_MAX_DEG)
            return fail(err, OBX_E_INVALID, "piece %d: degree %d (must be 1 to %d)", p, degrees[p], OB_MAX_DEG);
        ob_apiece *ap = ob_approx_add(a);
        if (!ap)
            return fail(err, OBX_E_NOMEM, "out of memory");
        ap->approx.deg = degrees[p];
        for (int i = 0; i <= degrees[p]; i++, k++) {
            const double wk = w ? w[k] : 1.0;
            if (!isfinite(xy[2 * k]) || !isfinite(xy[2 * k + 1]) || !(isfinite(wk) && wk > 0))
                return fail(err, OBX_E_INVALID, "piece %d: point %d is not finite or its weight not > 0", p, i);
            ob_bez_set(&ap->approx, i, xy[2 * k], xy[2 * k + 1], wk);
        }
    }
    return 0;
}

/* A reader's message without the "pieces:0: " it puts before a piece
 * that has no file and no line. */
static const char *without_file(const char *msg)
{
    return strncmp(msg, "pieces:0: ", 10) == 0 ? msg + 10 : msg;
}

/* `measure`'s one path (ob_measure_approx): the pieces are matched and
 * must cover the offset once, whatever is asked, as the CLI checks a file;
 * *out the rows asked.  The message names the first problem. */
static int measure_path(const ob_curve *c, double d, ob_approx *a, const ob_measure_ask *ask, ob_measure_out *out,
                        obx_error *err)
{
    ob_cover cv;
    ob_err e;
    int rc = ob_measure_approx(c, d, a, ask, "pieces", &cv, out, &e);
    if (rc != 0 && cv.nfail > 0) {  /* the summary's head, then where: the first problem */
        char first[300];
        ob_cover_text(&cv.fail[0], a, "pieces", first, sizeof first);
        const char *head = strstr(e.msg, " once ("), *end = head ? strchr(head, ')') : NULL;
        const int len = end ? (int)(end + 1 - e.msg) : 200;
        rc = fail(err, OBX_E_MEASURE, "%.*s; the first: %s", len < 200 ? len : 200, e.msg, without_file(first));
    } else if (rc != 0) {
        rc = fail(err, OBX_E_MEASURE, "%.500s", e.msg);
    }
    ob_cover_free(&cv);
    return rc;
}

/* One row of the one path: metric met, or hausdorff-whole. */
static int measure_row(const ob_curve *c, double d, ob_approx *a, ob_metric met, int whole, ob_mres *r,
                       obx_error *err)
{
    ob_measure_ask ask = {{0}, whole, OB_DEFAULT_SAMPLES};
    ask.want[met] = !whole;
    ob_measure_out out;
    const int rc = measure_path(c, d, a, &ask, &out, err);
    *r = whole ? out.whole : out.res[met];
    return rc;
}

/* `measure --trimmed`'s row (ob_measure_trimmed): the pieces as a point set
 * against the trimmed offset, not matched, so no cover check (a trimmed
 * file does not cover the untrimmed offset); msg holds r's note. */
static int trimmed_row(const ob_curve *c, double d, const ob_approx *a, ob_mres *r, char *msg, size_t len,
                       obx_error *err)
{
    ob_err e;
    if (ob_measure_trimmed(c, d, a, OB_DEFAULT_SAMPLES, NULL, r, msg, len, &e) != 0)
        return fail(err, strstr(e.msg, "out of memory") ? OBX_E_NOMEM : OBX_E_MEASURE, "%.500s", e.msg);
    return 0;
}

/* The extra metrics obx_measure takes beyond ob_metric_parse's names. */
typedef enum { ROW_METRIC = 0, ROW_WHOLE, ROW_TRIMMED } row_kind;

static row_kind row_of(const char *metric)
{
    if (metric && strcmp(metric, "hausdorff-whole") == 0)
        return ROW_WHOLE;
    if (metric && strcmp(metric, "trimmed-hausdorff") == 0)
        return ROW_TRIMMED;
    return ROW_METRIC;
}

int obx_measure(const obx_curveset *set, int curve, double d, int npieces, const int *degrees, const double *xy,
                const double *w, const char *metric, obx_measurement *m, obx_error *err)
{
    ob_metric met = OB_METRIC_HAUSDORFF;
    if (!m)
        return fail(err, OBX_E_INVALID, "obx_measure: NULL out");
    const row_kind kind = row_of(metric);
    if (check_curve_d(set, curve, d, err) || (kind == ROW_METRIC && parse_metric(metric, &met, err)))
        return -1;
    ob_approx a = {0};
    ob_mres r;
    char note[200];
    const ob_curve *c = &set->set.v[curve];
    int rc = pieces_approx("obx_measure", npieces, degrees, xy, w, &a, err);
    if (rc == 0)
        rc = kind == ROW_TRIMMED ? trimmed_row(c, d, &a, &r, note, sizeof note, err)
                                 : measure_row(c, d, &a, met, kind == ROW_WHOLE, &r, err);
    ob_approx_free(&a);
    if (rc)
        return -1;
    memset(m, 0, sizeof *m);
    m->max_err = r.applies ? r.err : NAN;
    m->piece = r.piece;
    snprintf(m->status, sizeof m->status, "%s", ob_mres_status(&r));
    snprintf(m->why, sizeof m->why, "%s", r.ok ? "" : r.why ? r.why : "");
    return 0;
}

/* Row r of the per-piece rows as the API's struct: the numbers
 * `measure --per-piece` writes (perpiece_csv.c), the base range from the
 * first part's start to the last part's end. */
static void piece_error_of(const ob_approx *a, const ob_pp_row *r, obx_piece_error *o)
{
    const ob_apiece *p0 = &a->v[r->first], *p1 = &a->v[r->last];
    memset(o, 0, sizeof *o);
    o->max_err = r->err;
    o->seg0 = p0->seg;
    o->t0 = ob_apiece_base_t(p0, 0.0);
    o->seg1 = p1->seg;
    o->t1 = ob_apiece_base_t(p1, 1.0);
    o->seg = r->seg;
    o->t = r->t;
    o->x = r->x, o->y = r->y, o->x_off = r->xo, o->y_off = r->yo;
    const int ok = ob_err_can_pass(r->err);
    snprintf(o->status, sizeof o->status, "%s", ok ? "ok" : "fail");
    snprintf(o->why, sizeof o->why, "%s", ok ? "" : "the error is not finite: a piece that cannot be evaluated (a "
                                                    "pole or a weight <= 0 of a rational piece?)");
}

int obx_measure_pieces(const obx_curveset *set, int curve, double d, int npieces, const int *degrees,
                       const double *xy, const double *w, obx_piece_error *out, obx_error *err)
{
    if (!out)
        return fail(err, OBX_E_INVALID, "obx_measure_pieces: NULL out");
    if (check_curve_d(set, curve, d, err))
        return -1;
    const ob_curve *c = &set->set.v[curve];
    ob_approx a = {0};
    ob_measure_ask ask = {{0}, 0, OB_DEFAULT_SAMPLES};  /* no row: the match and the cover check */
    ob_measure_out rows;
    ob_perpiece pp = {0};
    ob_err e;
    int rc = pieces_approx("obx_measure_pieces", npieces, degrees, xy, w, &a, err);
    if (rc == 0)
        rc = measure_path(c, d, &a, &ask, &rows, err);
    if (rc == 0 && ob_approx_per_piece(c, d, &a, OB_DEFAULT_SAMPLES, "pieces", &pp, &e) != 0)
        rc = fail(err, strstr(e.msg, "out of memory") ? OBX_E_NOMEM : OBX_E_MEASURE, "%.500s", without_file(e.msg));
    for (int k = 0; rc == 0 && k < pp.n; k++)
        piece_error_of(&a, &pp.v[k], &out[k]);
    ob_perpiece_free(&pp);
    ob_approx_free(&a);
    return rc;
}
