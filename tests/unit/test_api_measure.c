/*
 * test_api_measure.c - obx_measure takes `offbench measure`'s one path
 * (host/measure/measure.h, ob_measure_approx): pieces that do not cover the
 * offset once are refused under every metric, as the CLI refuses the file
 * (tests/e2e/e2e_measure_cover.sh): one piece of N, copies of one piece,
 * half the pieces, certified and hausdorff-whole alike; pieces out of order
 * or each reversed are measured, as the CLI measures them (it notes them).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "include/offbench.h"
#include "tests/check.h"

enum { MAXP = 64, MAXPTS = 8 };

/* A fit's pieces as obx_measure's arrays. */
typedef struct {
    int n;
    int deg[MAXP];
    double xy[MAXP][2 * MAXPTS];
} pieces;

static int get_pieces(const obx_result *r, pieces *p)
{
    p->n = obx_result_piece_count(r);
    if (p->n < 4 || p->n > MAXP)
        return -1;
    for (int k = 0; k < p->n; k++)
        if ((p->deg[k] = obx_result_piece(r, k, p->xy[k], NULL, MAXPTS, NULL)) < 1)
            return -1;
    return 0;
}

/* obx_measure of pieces idx[0..n) of p (each reversed when rev), under metric. */
static int measure_some(const obx_curveset *s, int c, const pieces *p, const int *idx, int n, int rev,
                        const char *metric, obx_measurement *m, obx_error *e)
{
    int deg[4 * MAXP];
    double xy[4 * MAXP * 2 * MAXPTS];
    size_t at = 0;
    for (int i = 0; i < n; i++) {
        const int k = idx[i];
        deg[i] = p->deg[k];
        for (int j = 0; j <= p->deg[k]; j++) {
            const int src = rev ? p->deg[k] - j : j;
            xy[at++] = p->xy[k][2 * src];
            xy[at++] = p->xy[k][2 * src + 1];
        }
    }
    *e = (obx_error){0, ""};
    return obx_measure(s, c, 1.0, n, deg, xy, NULL, metric, m, e);
}

/* Refused, with the CLI's message: does not cover ... once (... KIND). */
static void refused(const obx_curveset *s, int c, const pieces *p, const int *idx, int n, const char *metric,
                    const char *kind, const char *what)
{
    obx_measurement m;
    obx_error e;
    const int rc = measure_some(s, c, p, idx, n, 0, metric, &m, &e);
    CHECK(rc == -1 && e.code == OBX_E_MEASURE && strstr(e.message, "does not cover the d = 1 offset of curve "
          "liu2002_ex1 once") && strstr(e.message, kind),
          "%s (%s): rc %d status %s max_err %g, message '%s'", what, metric ? metric : "hausdorff", rc,
          rc == 0 ? m.status : "-", rc == 0 ? m.max_err : NAN, e.message);
}

int main(void)
{
    obx_curveset *s = NULL;
    obx_error e = {0, ""};
    obx_result *r = NULL;
    pieces p;
    if (obx_curves_load_file("datasets/published.curves", &s, &e) != 0 ||
        obx_fit(s, obx_curves_find(s, "liu2002_ex1"), "tiller", 1.0, 1e-3, NULL, NULL, NULL, &r, &e) != 0 ||
        get_pieces(r, &p) != 0) {
        CHECK(0, "setup: %s", e.message);
        return check_done();
    }
    const int c = obx_curves_find(s, "liu2002_ex1"), n = p.n;
    int all[MAXP], copies[50], shuffled[MAXP], backwards[MAXP];
    for (int k = 0; k < n; k++) {
        all[k] = k;
        shuffled[k] = k < (n + 1) / 2 ? 2 * k : 2 * (k - (n + 1) / 2) + 1;  /* evens, then odds */
        backwards[k] = n - 1 - k;
    }
    for (int k = 0; k < 50; k++)
        copies[k] = 0;
    const char *metrics[] = {NULL, "normal", "certified", "hausdorff-whole", "bound"};
    for (size_t i = 0; i < sizeof metrics / sizeof *metrics; i++) {
        refused(s, c, &p, all, 1, metrics[i], "gaps", "one piece of N");
        refused(s, c, &p, copies, 50, metrics[i], "49 duplicates", "50 copies of one piece");
        refused(s, c, &p, all, n / 2, metrics[i], "1 gaps", "half the pieces");
        refused(s, c, &p, all + 1, n - 1, metrics[i], "1 gaps", "all but the first");
    }
    obx_measurement ref, m;
    CHECK(measure_some(s, c, &p, all, n, 0, NULL, &ref, &e) == 0 && strcmp(ref.status, "ok") == 0,
          "the whole fit: %s", e.message);
    CHECK(measure_some(s, c, &p, shuffled, n, 0, NULL, &m, &e) == 0 && strcmp(m.status, "ok") == 0 &&
              m.max_err == ref.max_err, "shuffled: %s %g vs %g (%s)", m.status, m.max_err, ref.max_err, e.message);
    CHECK(measure_some(s, c, &p, backwards, n, 0, NULL, &m, &e) == 0 && m.max_err == ref.max_err,
          "last to first: %g vs %g (%s)", m.max_err, ref.max_err, e.message);
    CHECK(measure_some(s, c, &p, all, n, 1, NULL, &m, &e) == 0 && fabs(m.max_err - ref.max_err) <= 1e-9 * ref.max_err,
          "each piece reversed: %g vs %g (%s)", m.max_err, ref.max_err, e.message);
    obx_result_free(r);
    obx_curves_free(s);
    return check_done();
}
