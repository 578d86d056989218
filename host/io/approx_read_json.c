/*
 * approx_read_json.c - the JSON of `--export` (export_json.c) back into
 * pieces.  The file is first read whole by the strict JSON reader of
 * meta.json (metajson.h: RFC 8259, errors as FILE:LINE), which keeps arrays
 * as their text; the "pieces" array is then walked element by element here.
 * Per piece: "degree", and either "homogeneous" [[w x, w y, w], ...] or
 * "points" [[x, y], ...] with optional "weights"; optionally the base link
 * "seg", "span" [a, b], "t" [t0, t1] (all three or none).  A CAD user's
 * own file needs only "pieces" with "degree" and "points".
 */
#include "host/io/approx_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/metajson.h"

/* Reads a JSON array of numbers (cols 0: [n, ...]) or of rows of cols
 * numbers ([[n, ...], ...]) from validated text s: at most max numbers into
 * v.  Returns the number of values, or -1 when the shape differs. */
static int num_array(const char *s, int cols, double *v, int max)
{
    int n = 0;
    const char *p = s;
#define WS() while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++
    WS();
    if (*p++ != '[')
        return -1;
    WS();
    if (*p == ']')
        return 0;
    for (;;) {
        WS();
        const int rows = cols > 0;
        if (rows && *p++ != '[')
            return -1;
        for (int c = 0; c < (rows ? cols : 1); c++) {
            WS();
            char *end;
            const double x = strtod(p, &end);
            if (end == p || n >= max)
                return -1;
            v[n++] = x;
            p = end;
            WS();
            if (c + 1 < (rows ? cols : 1) && *p++ != ',')
                return -1;
        }
        if (rows) {
            WS();
            if (*p++ != ']')
                return -1;
        }
        WS();
        if (*p == ']')
            return n;
        if (*p++ != ',')
            return -1;
    }
#undef WS
}

/* The number entry of key in flat f into *x; 0, 1 when absent, -1 when not a number. */
static int get_num(const ob_json_flat *f, const char *key, double *x)
{
    const ob_json_entry *e = ob_json_get(f, key);
    if (!e)
        return 1;
    if (e->type != OB_JSON_NUMBER)
        return -1;
    *x = strtod(e->value, NULL);
    return 0;
}

/* The control points of one piece object (flattened into f). */
static int piece_points(const ob_json_flat *f, ob_apiece *p, int k, const char *name, ob_err *err)
{
    ob_bez *b = &p->approx;
    const int np = b->deg + 1;
    double v[3 * (OB_MAX_DEG + 1)];
    const ob_json_entry *h = ob_json_get(f, "homogeneous"), *pt = ob_json_get(f, "points"),
                        *w = ob_json_get(f, "weights");
    if (h) {
        if (h->type != OB_JSON_ARRAY || num_array(h->value, 3, v, 3 * np) != 3 * np)
            goto bad_h;
        for (int i = 0; i < np; i++)
            for (int c = 0; c < 3; c++)
                b->h[i][c] = v[3 * i + c];
        return 0;
    }
    if (!pt || pt->type != OB_JSON_ARRAY || num_array(pt->value, 2, v, 2 * np) != 2 * np) {
        ob_fail(err, "%s:%d: piece %d: \"points\" must be %d [x, y] pairs (degree %d)", name, p->line, k,
                np, b->deg);
        return -1;
    }
    double wv[OB_MAX_DEG + 1];
    for (int i = 0; i < np; i++)
        wv[i] = 1.0;
    if (w && (w->type != OB_JSON_ARRAY || num_array(w->value, 0, wv, np) != np)) {
        ob_fail(err, "%s:%d: piece %d: \"weights\" must be %d numbers", name, w->line, k, np);
        return -1;
    }
    for (int i = 0; i < np; i++) {
        if (!(wv[i] != 0.0)) {
            ob_fail(err, "%s:%d: piece %d: weight %d is 0 (give \"homogeneous\" for a control point at "
                    "infinity)", name, w->line, k, i);
            return -1;
        }
        ob_bez_set(b, i, v[2 * i], v[2 * i + 1], wv[i]);
    }
    return 0;
bad_h:
    ob_fail(err, "%s:%d: piece %d: \"homogeneous\" must be %d [w x, w y, w] triples (degree %d)", name,
            h->line, k, np, b->deg);
    return -1;
}

/* One element of "pieces" (object text elem, starting at line). */
static int read_piece(const char *elem, size_t len, int line, int k, const char *name, ob_approx *out, ob_err *err)
{
    ob_json_flat f = {0};
    ob_err e2;
    if (ob_json_flatten(elem, len, "", &f, &e2) != 0) {
        const char *reason = strchr(e2.msg + 1, ':');
        ob_fail(err, "%s:%d: piece %d: %s", name, line + atoi(e2.msg + 1) - 1, k, reason ? reason + 2 : e2.msg);
        return -1;
    }
    ob_apiece *p = ob_approx_add(out);
    int rc = p ? 0 : -1;
    double deg = 0, seg = 0, ab[2], tt[2];
    if (!p)
        ob_fail(err, "%s: out of memory", name);
    else {
        p->line = line;
        p->fit_first = 1;
        if (get_num(&f, "degree", &deg) != 0 || !(fabs(deg) < 1e6) || deg != (int)deg) {
            ob_fail(err, "%s:%d: piece %d: \"degree\" missing or not a whole number", name, line, k);
            rc = -1;
        } else {
            p->approx.deg = (int)deg;
            rc = deg < 1 || deg > OB_MAX_DEG ? ob_approx_check_piece(p, k, name, err)
                                             : piece_points(&f, p, k, name, err);
        }
    }
    if (rc == 0) {
        const ob_json_entry *sp = ob_json_get(&f, "span"), *t = ob_json_get(&f, "t");
        const int has = get_num(&f, "seg", &seg) == 0;
        if (has || sp || t) {
            if (!has || !sp || !t || num_array(sp->value, 0, ab, 2) != 2 || num_array(t->value, 0, tt, 2) != 2 ||
                !(seg >= 0 && seg < 1e9) || seg != (int)seg) {
                ob_fail(err, "%s:%d: piece %d: the base link needs \"seg\" (a whole number), \"span\" "
                        "[a, b] and \"t\" [t0, t1] together", name, line, k);
                rc = -1;
            } else {
                *p = (ob_apiece){1, (int)seg, ab[0], ab[1], tt[0], tt[1], 1, line, p->approx, 0, 0, "", "", ""};
            }
        }
    }
    if (rc == 0)
        rc = ob_approx_check_piece(p, k, name, err);
    ob_json_free(&f);
    return rc;
}

/* Walks the validated array text arr (at line) element by element. */
static int read_pieces(const char *arr, int line, const char *name, ob_approx *out, ob_err *err)
{
    const char *p = arr + 1;
    int k = 0;
    while (*p) {
        while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == ',')
            line += *p++ == '\n';
        if (*p == ']' || !*p)
            break;
        if (*p != '{') {
            ob_fail(err, "%s:%d: piece %d: not an object", name, line, k);
            return -1;
        }
        const char *s = p;
        int depth = 0, instr = 0, l0 = line;
        for (; *p; p++) {
            line += *p == '\n';
            if (instr) {
                if (*p == '\\' && p[1])
                    p++;
                else if (*p == '"')
                    instr = 0;
            } else if (*p == '"')
                instr = 1;
            else if (*p == '{' || *p == '[')
                depth++;
            else if ((*p == '}' || *p == ']') && --depth == 0) {
                p++;
                break;
            }
        }
        if (read_piece(s, (size_t)(p - s), l0, k++, name, out, err) != 0)
            return -1;
    }
    return 0;
}

/* The exporting job's curve and d ("job": {"curve", "d", ...}), when both are there. */
static void job_of(const ob_json_flat *f, ob_approx *out)
{
    const ob_json_entry *c = ob_json_get(f, "job.curve");
    double d;
    if (c && c->type == OB_JSON_STRING && strlen(c->value) < sizeof out->job_curve && get_num(f, "job.d", &d) == 0) {
        snprintf(out->job_curve, sizeof out->job_curve, "%s", c->value);
        out->job_d = d;
        out->have_job = 1;
    }
}

int ob_approx_read_json(const char *text, size_t len, const char *name, ob_approx *out, ob_err *err)
{
    ob_json_flat f = {0};
    if (ob_json_flatten(text, len, name, &f, err) != 0)
        return -1;
    int rc = 0;
    const ob_json_entry *fmt = ob_json_get(&f, "format"), *pc = ob_json_get(&f, "pieces"),
                        *sp = ob_json_get(&f, "same_param");
    if (fmt && (fmt->type != OB_JSON_STRING || strcmp(fmt->value, "offbench-approximation") != 0)) {
        ob_fail(err, "%s:%d: \"format\" is \"%.60s\", not \"offbench-approximation\"", name, fmt->line,
                fmt->value);
        rc = -1;
    } else if (!pc || pc->type != OB_JSON_ARRAY) {
        ob_fail(err, "%s:%d: no \"pieces\" array (a list of {\"degree\": N, \"points\": [[x, y], ...]})",
                name, pc ? pc->line : 1);
        rc = -1;
    } else {
        rc = read_pieces(pc->value, pc->line, name, out, err);
        out->same_param = rc == 0 && sp && sp->type == OB_JSON_BOOL && strcmp(sp->value, "true") == 0;
        job_of(&f, out);
    }
    ob_json_free(&f);
    return rc;
}
