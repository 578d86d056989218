/*
 * test_api_measure_more.c - what `offbench measure --trimmed` and
 * `--per-piece` give, through the C API (issue 50's options in liboffbench
 * 0.7): obx_measure's metric trimmed-hausdorff and obx_measure_pieces give
 * the CLI's numbers bit for bit, because they take its code
 * (ob_measure_trimmed; ob_measure_approx, then ob_approx_per_piece), which
 * this program, linked with the library's objects, calls itself on the same
 * pieces and the run's 256 samples.  trimmed-hausdorff takes pieces that do
 * not cover the untrimmed offset (no cover check); obx_measure_pieces finds
 * a planted defect at its piece, and refuses bad input by the one error
 * carrier.  (python/tests/test_measure_more.py runs the CLI itself.)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/approx.h"
#include "host/io/curvefile.h"
#include "host/measure/measure.h"
#include "host/measure/perpiece.h"
#include "host/measure/trim.h"
#include "include/offbench.h"
#include "tests/check.h"

enum { MAXP = 64, MAXPTS = 8, SAMPLES = 256 };

/* A fit's pieces as the API's arrays (polynomial: no weights). */
typedef struct {
    int n;
    int deg[MAXP];
    double xy[MAXP * 2 * MAXPTS];
} pieces;

static int get_pieces(const obx_result *r, pieces *p)
{
    p->n = obx_result_piece_count(r);
    if (p->n < 4 || p->n > MAXP)
        return -1;
    size_t at = 0;
    for (int k = 0; k < p->n; k++) {
        if ((p->deg[k] = obx_result_piece(r, k, p->xy + at, NULL, MAXPTS, NULL)) < 1)
            return -1;
        at += 2 * (size_t)(p->deg[k] + 1);
    }
    return 0;
}

/* The first n pieces of p as the CLI holds a file without links. */
static void as_approx(const pieces *p, int n, ob_approx *a)
{
    size_t at = 0;
    for (int k = 0; k < n; k++) {
        ob_apiece *ap = ob_approx_add(a);
        ap->approx.deg = p->deg[k];
        for (int i = 0; i <= p->deg[k]; i++, at += 2)
            ob_bez_set(&ap->approx, i, p->xy[at], p->xy[at + 1], 1.0);
    }
}

/* trimmed-hausdorff: the CLI's ob_measure_trimmed, bit for bit, on the
 * first n pieces (all of them, and half: no cover check). */
static void trimmed_as_cli(const obx_curveset *s, int c, const ob_curve *cv, const pieces *p, int n, const char *what)
{
    ob_approx a = {0};
    as_approx(p, n, &a);
    ob_mres want;
    char msg[200];
    ob_err oe;
    const int wrc = ob_measure_trimmed(cv, 1.0, &a, SAMPLES, NULL, &want, msg, sizeof msg, &oe);
    ob_approx_free(&a);
    obx_measurement m;
    obx_error e = {0, ""};
    const int rc = obx_measure(s, c, 1.0, n, p->deg, p->xy, NULL, "trimmed-hausdorff", &m, &e);
    CHECK(wrc == 0 && rc == 0, "%s: rc %d (%s), the CLI's %d (%s)", what, rc, e.message, wrc, wrc ? oe.msg : "");
    if (rc != 0 || wrc != 0)
        return;
    CHECK(m.max_err == want.err && m.piece == want.piece && strcmp(m.status, ob_mres_status(&want)) == 0,
          "%s: %.17g piece %d %s, the CLI's %.17g piece %d %s", what, m.max_err, m.piece, m.status, want.err,
          want.piece, ob_mres_status(&want));
    CHECK(strcmp(m.status, "ok") == 0 && m.why[0] == '\0', "%s: status %s why '%s'", what, m.status, m.why);
}

/* The CLI's --per-piece rows of p: ob_measure_approx (match, cover), then
 * ob_approx_per_piece; *a keeps the matched pieces for their base ranges. */
static int cli_rows(const ob_curve *cv, const pieces *p, ob_approx *a, ob_perpiece *pp)
{
    as_approx(p, p->n, a);
    ob_measure_ask ask = {{0}, 0, SAMPLES};
    ob_cover cover;
    ob_measure_out out;
    ob_err e;
    int rc = ob_measure_approx(cv, 1.0, a, &ask, "pieces", &cover, &out, &e);
    ob_cover_free(&cover);
    if (rc == 0)
        rc = ob_approx_per_piece(cv, 1.0, a, SAMPLES, "pieces", pp, &e);
    if (rc != 0)
        fprintf(stderr, "the CLI's path: %s\n", e.msg);
    return rc;
}

/* Every field of out[k] is the CLI's row k, bit for bit. */
static void rows_as_cli(const ob_curve *cv, const pieces *p, const obx_piece_error *out, const char *what)
{
    ob_approx a = {0};
    ob_perpiece pp = {0};
    CHECK(cli_rows(cv, p, &a, &pp) == 0 && pp.n == p->n, "%s: the CLI's rows: %d of %d", what, pp.n, p->n);
    for (int k = 0; k < pp.n && k < p->n; k++) {
        const ob_pp_row *r = &pp.v[k];
        const ob_apiece *p0 = &a.v[r->first], *p1 = &a.v[r->last];
        const obx_piece_error *o = &out[k];
        CHECK(o->max_err == r->err && o->seg == r->seg && o->t == r->t && o->x == r->x && o->y == r->y &&
                  o->x_off == r->xo && o->y_off == r->yo,
              "%s: piece %d: %.17g at %d %.17g (%.17g, %.17g) / (%.17g, %.17g), the CLI's %.17g at %d %.17g", what, k,
              o->max_err, o->seg, o->t, o->x, o->y, o->x_off, o->y_off, r->err, r->seg, r->t);
        CHECK(o->seg0 == p0->seg && o->t0 == ob_apiece_base_t(p0, 0.0) && o->seg1 == p1->seg &&
                  o->t1 == ob_apiece_base_t(p1, 1.0),
              "%s: piece %d: base %d %.17g .. %d %.17g", what, k, o->seg0, o->t0, o->seg1, o->t1);
        CHECK(strcmp(o->status, "ok") == 0 && o->why[0] == '\0', "%s: piece %d: %s '%s'", what, k, o->status, o->why);
    }
    ob_perpiece_free(&pp);
    ob_approx_free(&a);
}

/* The largest of the rows is obx_measure's hausdorff max_err (perpiece.h),
 * and the worst point's distance is the piece's error. */
static int worst_row(const obx_piece_error *out, int n)
{
    int w = 0;
    for (int k = 1; k < n; k++)
        if (out[k].max_err > out[w].max_err)
            w = k;
    return w;
}

static void per_piece(const obx_curveset *s, int c, const ob_curve *cv, pieces *p)
{
    obx_piece_error out[MAXP];
    obx_error e = {0, ""};
    CHECK(obx_measure_pieces(s, c, 1.0, p->n, p->deg, p->xy, NULL, out, &e) == 0, "per piece: %s", e.message);
    rows_as_cli(cv, p, out, "the fit");
    obx_measurement m;
    CHECK(obx_measure(s, c, 1.0, p->n, p->deg, p->xy, NULL, NULL, &m, &e) == 0 &&
              out[worst_row(out, p->n)].max_err == m.max_err && worst_row(out, p->n) == m.piece,
          "largest row %.17g at %d, hausdorff %.17g at %d", out[worst_row(out, p->n)].max_err, worst_row(out, p->n),
          m.max_err, m.piece);
    /* a local defect planted in piece k: its inner points moved 0.02 up */
    const int k = p->n / 3;
    size_t at = 0;
    for (int i = 0; i < k; i++)
        at += 2 * (size_t)(p->deg[i] + 1);
    for (int i = 1; i < p->deg[k]; i++)
        p->xy[at + 2 * i + 1] += 0.02;
    CHECK(obx_measure_pieces(s, c, 1.0, p->n, p->deg, p->xy, NULL, out, &e) == 0, "planted: %s", e.message);
    const obx_piece_error *w = &out[worst_row(out, p->n)];
    CHECK(worst_row(out, p->n) == k && w->max_err > 5e-3, "planted in piece %d: the worst is piece %d (%g)", k,
          worst_row(out, p->n), w->max_err);
    /* x, y is max_err from x_off, y_off (perpiece.h), also here, where the
     * worst is on the piece's side, the bulge's top, whose nearest offset
     * point within the base range is the range's end: x, y is the top, not
     * the piece's point nearest to that end */
    CHECK(fabs(hypot(w->x - w->x_off, w->y - w->y_off) - w->max_err) <= 1e-9 * w->max_err,
          "the worst point's distance %.17g, the error %.17g", hypot(w->x - w->x_off, w->y - w->y_off), w->max_err);
    int others_small = 1;
    for (int i = 0; i < p->n; i++)
        others_small &= i == k || out[i].max_err < 1e-3;
    CHECK(others_small, "the other pieces keep their errors (within the fit's tol)");
    rows_as_cli(cv, p, out, "planted");
}

/* One refused call: rc -1, code, and words in the message. */
static void refused(int rc, const obx_error *e, int code, const char *words, const char *what)
{
    CHECK(rc == -1 && e->code == code && strstr(e->message, words), "%s: rc %d code %d '%s'", what, rc, e->code,
          e->message);
}

/* Bad input: OBX_E_INVALID naming it, or OBX_E_MEASURE for pieces that
 * do not cover the offset once (as the CLI's --per-piece refuses them). */
static void bad_input(const obx_curveset *s, int c, const pieces *p)
{
    obx_piece_error out[MAXP];
    obx_error e = {0, ""};
    double xy[MAXP * 2 * MAXPTS];
    memcpy(xy, p->xy, sizeof xy);
    xy[3] = NAN;
    refused(obx_measure_pieces(NULL, c, 1, p->n, p->deg, p->xy, NULL, out, &e), &e, OBX_E_INVALID, "NULL curve set",
            "NULL set");
    refused(obx_measure_pieces(s, c, 1, p->n, p->deg, p->xy, NULL, NULL, &e), &e, OBX_E_INVALID, "NULL out",
            "NULL out");
    refused(obx_measure_pieces(s, c, 1, p->n, NULL, p->xy, NULL, out, &e), &e, OBX_E_INVALID, "NULL degrees or xy",
            "NULL degrees");
    refused(obx_measure_pieces(s, c, 1, 0, p->deg, p->xy, NULL, out, &e), &e, OBX_E_INVALID, "no pieces",
            "npieces 0");
    refused(obx_measure_pieces(s, c, NAN, p->n, p->deg, p->xy, NULL, out, &e), &e, OBX_E_INVALID, "finite", "NaN d");
    refused(obx_measure_pieces(s, c, 1, p->n, p->deg, xy, NULL, out, &e), &e, OBX_E_INVALID,
            "piece 0: point 1 is not finite", "NaN point");
    refused(obx_measure_pieces(s, 99, 1, p->n, p->deg, p->xy, NULL, out, &e), &e, OBX_E_INVALID,
            "curve index out of range", "curve 99");
    refused(obx_measure_pieces(s, c, 1, p->n / 2, p->deg, p->xy, NULL, out, &e), &e, OBX_E_MEASURE,
            "does not cover the d = 1 offset of curve liu2002_ex1 once (1 gaps", "half the pieces");
    CHECK(obx_measure_pieces(s, c, 1, p->n, p->deg, p->xy, NULL, out, NULL) == 0, "err may be NULL");
    obx_measurement m;
    refused(obx_measure(s, c, NAN, p->n, p->deg, p->xy, NULL, "trimmed-hausdorff", &m, &e), &e, OBX_E_INVALID,
            "finite", "trimmed-hausdorff, NaN d");
    refused(obx_measure(s, c, 1, 0, p->deg, p->xy, NULL, "trimmed-hausdorff", &m, &e), &e, OBX_E_INVALID,
            "no pieces", "trimmed-hausdorff, npieces 0");
    refused(obx_measure(s, c, 1, p->n, p->deg, xy, NULL, "trimmed-hausdorff", &m, &e), &e, OBX_E_INVALID,
            "piece 0: point 1 is not finite", "trimmed-hausdorff, NaN point");
}

int main(void)
{
    obx_curveset *s = NULL;
    obx_error e = {0, ""};
    obx_result *r = NULL;
    ob_curveset cs = {0};
    ob_err oe;
    pieces p;
    if (obx_curves_load_file("datasets/published.curves", &s, &e) != 0 ||
        obx_fit(s, obx_curves_find(s, "liu2002_ex1"), "tiller", 1.0, 1e-3, NULL, NULL, NULL, &r, &e) != 0 ||
        get_pieces(r, &p) != 0 || ob_curves_load_file("datasets/published.curves", &cs, &oe) != 0) {
        CHECK(0, "setup: %s", e.message);
        return check_done();
    }
    const int c = obx_curves_find(s, "liu2002_ex1");
    const ob_curve *cv = &cs.v[ob_curveset_find(&cs, "liu2002_ex1")];
    trimmed_as_cli(s, c, cv, &p, p.n, "the fit");
    trimmed_as_cli(s, c, cv, &p, p.n / 2, "half the fit (no cover check)");
    bad_input(s, c, &p);
    per_piece(s, c, cv, &p);
    obx_result_free(r);
    obx_curves_free(s);
    ob_curveset_free(&cs);
    return check_done();
}
