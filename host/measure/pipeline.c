/*
 * pipeline.c - `measure`'s one path (measure.h, ob_measure_approx): the
 * CLI (host/cli/cmd_measure.c) and the C API (obx_measure) both measure
 * through it, so every check one makes the other makes.
 */
#include "host/measure/measure.h"

#include <stdio.h>
#include <string.h>

#include "host/io/numfmt.h"

/* The failure of a cover with gaps, overlaps or duplicates, into err. */
static int cover_fail(const ob_curve *c, double d, const ob_approx *a, const ob_cover *cv, const char *name,
                      ob_err *err)
{
    const int *k = cv->count;
    int matched = 0;
    for (int i = 0; i < a->n; i++)
        matched |= a->v[i].matched;
    char ds[40];
    ob_fmt_double(ds, sizeof ds, d);  /* the shortest form that reads back as d, as results.csv writes it */
    return ob_fail(err, "measure: %s does not cover the d = %s offset of curve %s once (%d gaps, %d overlaps, %d "
                   "duplicates): measure takes a whole approximation, each part of the offset covered by one piece%s",
                   name, ds, c->id, k[OB_COVER_GAP], k[OB_COVER_OVERLAP], k[OB_COVER_DUPLICATE],
                   matched ? OB_MEASURE_CUSP_HINT " to the base by projection, which near an offset's cusps can "
                             "land on another branch: a file with base links, as --export writes, is matched "
                             "exactly)"
                           : "");
}

int ob_measure_approx(const ob_curve *c, double d, ob_approx *a, const ob_measure_ask *ask, const char *name,
                      ob_cover *cv, ob_measure_out *out, ob_err *err)
{
    memset(cv, 0, sizeof *cv);
    memset(out, 0, sizeof *out);
    if (ob_approx_match(c, d, a, name, err) != 0 || ob_approx_cover(c, d, a, ask->samples, name, cv, err) != 0)
        return -1;
    if (ob_cover_fails(cv))
        return cover_fail(c, d, a, cv, name, err);
    for (int m = 0; m < OB_METRIC_COUNT; m++)
        if (ask->want[m] && ob_approx_measure(c, d, a, (ob_metric)m, ask->samples, name, &out->res[m], err) != 0)
            return -1;
    if (ask->whole && ob_approx_hausdorff_whole(c, d, a, cv, ask->samples, &out->whole, err) != 0)
        return -1;
    return 0;
}
