/*
 * export_json.c - a job's approximation as JSON (export.h), the form
 * `measure --approx FILE.json` reads back (host/io/approx_read_json.c):
 *
 *   {"format": "offbench-approximation", "version": 1,
 *    "job": {"curve", "d", "method", "metric", "split", "tol", "samples"},
 *    "status", "max_err", "ctrl_points", "segments", "out_degree",
 *    "same_param": true when the pieces share the base's parameter,
 *    "pieces": [{"seg", "span": [a, b], "t": [t0, t1], "base_t": [ta, tb],
 *                "degree", "rational", "knots", "points": [[x, y], ...],
 *                "weights", "homogeneous": [[w x, w y, w], ...],
 *                "base_homogeneous": [[w x, w y, w], ...]}, ...]}
 *
 * Each piece is one Bézier segment over [0, 1] (its knots: degree + 1 zeros
 * and degree + 1 ones, so it is also a clamped B-spline).  "homogeneous" is
 * what offbench computed, exactly; "points" and "weights" are the Euclidean
 * reading (x = w x / w rounds once).  The piece approximates base segment
 * "seg" over base parameters "base_t", which is the span [a, b] the driver
 * accepted, cut to [t0, t1] of its fit (approx.h).  "base_homogeneous" is
 * that base segment "seg" as the run holds it (binary64, after a B-spline's
 * conversion; a random curve as generated), so that a checker outside
 * offbench (scripts/cert_brute.py) has the exact base without regenerating
 * it.
 */
#include "host/io/export.h"

#include <math.h>

#include "methods/metrics/metric.h"

static void jstr(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static void pair(FILE *f, double a, double b)
{
    fputc('[', f);
    ob_export_num(f, a, 1);
    fputs(", ", f);
    ob_export_num(f, b, 1);
    fputc(']', f);
}

static void hpoints(FILE *f, const ob_bez *b)
{
    for (int i = 0; i <= b->deg; i++) {
        fputs(i ? ", [" : "[", f);
        for (int c = 0; c < 3; c++) {
            fputs(c ? ", " : "", f);
            ob_export_num(f, b->h[i][c], 1);
        }
        fputc(']', f);
    }
}

static void piece(FILE *f, const ob_apiece *p, const ob_curve *c)
{
    const ob_bez *b = &p->approx;
    fprintf(f, "    {\"seg\": %d, \"span\": ", p->seg);
    pair(f, p->a, p->b);
    fputs(", \"t\": ", f);
    pair(f, p->t0, p->t1);
    fputs(", \"base_t\": ", f);
    pair(f, p->a + (p->b - p->a) * p->t0, p->a + (p->b - p->a) * p->t1);
    fprintf(f, ",\n     \"degree\": %d, \"rational\": %s, \"knots\": [", b->deg, b->rational ? "true" : "false");
    for (int k = 0; k < 2 * (b->deg + 1); k++)
        fprintf(f, "%s%d", k ? ", " : "", k > b->deg);
    fputs("],\n     \"points\": [", f);
    for (int i = 0; i <= b->deg; i++) {
        double q[2];
        ob_bez_ctrl(b, i, q);
        fputs(i ? ", " : "", f);
        pair(f, q[0], q[1]);
    }
    fputs("],\n     \"weights\": [", f);
    for (int i = 0; i <= b->deg; i++) {
        fputs(i ? ", " : "", f);
        ob_export_num(f, b->h[i][2], 1);
    }
    fputs("],\n     \"homogeneous\": [", f);
    hpoints(f, b);
    fputc(']', f);
    if (c && p->seg >= 0 && p->seg < c->nseg) {
        fputs(",\n     \"base_homogeneous\": [", f);
        hpoints(f, &c->seg[p->seg]);
        fputc(']', f);
    }
    fputc('}', f);
}

int ob_export_write_json(FILE *f, const ob_job *j, int samples, const ob_approx *a)
{
    fputs("{\n  \"format\": \"offbench-approximation\",\n  \"version\": 1,\n  \"job\": {\"curve\": ", f);
    jstr(f, j->curve->id);
    fputs(", \"d\": ", f);
    ob_export_num(f, j->d, 1);
    fputs(", \"method\": ", f);
    jstr(f, j->method->name);
    fprintf(f, ", \"metric\": \"%s\", \"split\": \"%s\", \"tol\": ", ob_metric_name(j->metric),
            ob_split_name(j->split));
    ob_export_num(f, j->tol, 1);
    fprintf(f, ", \"samples\": %d},\n  \"status\": \"%s\",\n  \"max_err\": ", samples, ob_status_name(j->status));
    ob_export_num(f, j->max_err, 1);
    fprintf(f, ",\n  \"ctrl_points\": %ld,\n  \"segments\": %d,\n  \"out_degree\": %d,\n  \"same_param\": %s,\n",
            j->ctrl_points, j->segments, j->out_degree, a->same_param ? "true" : "false");
    fputs("  \"pieces\": [\n", f);
    for (int i = 0; i < a->n; i++) {
        piece(f, &a->v[i], j->curve);
        fputs(i + 1 < a->n ? ",\n" : "\n", f);
    }
    fputs("  ]\n}\n", f);
    return ferror(f) ? -1 : 0;
}
