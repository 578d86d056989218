/*
 * meta_selection.c - meta.json's "selection" (see meta_selection.h).
 */
#include "host/io/meta_selection.h"

#include <inttypes.h>
#include <string.h>

#include "host/io/numfmt.h"
#include "host/io/output.h"
#include "host/run/plan.h"

/* random.c names every curve it makes so (ob_random_curve) */
static int is_random(const ob_curve *c)
{
    return strcmp(c->file, "--random") == 0;
}

static void put_num(FILE *f, double x)
{
    char b[40];
    ob_fmt_double(b, sizeof b, x);
    fputs(b, f);
}

/* "curves": the planned curves from files, each with its offsets. */
static void put_curves(FILE *f, const ob_run_opts *o, const ob_curveset *set)
{
    int first = 1;
    fputs("\"curves\": {", f);
    for (int c = 0; c < set->n; c++) {
        const ob_curve *cv = &set->v[c];
        if (is_random(cv) || !ob_run_selects(o, cv->id))
            continue;
        fputs(first ? "" : ", ", f);
        ob_json_string(f, cv->id);
        fputs(": [", f);
        for (int k = 0; k < cv->nd; k++) {
            fputs(k ? ", " : "", f);
            put_num(f, cv->d[k]);
        }
        fputc(']', f);
        first = 0;
    }
    fputs("}", f);
}

/* "random": the rule of --random, with the ids --curve kept of it. */
static void put_random(FILE *f, const ob_run_opts *o, const ob_curveset *set)
{
    fputs(", \"random\": ", f);
    if (o->random_n <= 0) {
        fputs("null", f);
        return;
    }
    fprintf(f, "{\"n\": %ld, \"seed\": %" PRIu64 ", \"only\": ", o->random_n, o->random_seed);
    if (!o->curve_ids) {
        fputs("null}", f);
        return;
    }
    int first = 1;
    fputc('[', f);
    for (int c = 0; c < set->n; c++)
        if (is_random(&set->v[c])) {  /* (with --curve only the listed ones are generated) */
            fputs(first ? "" : ", ", f);
            ob_json_string(f, set->v[c].id);
            first = 0;
        }
    fputs("]}", f);
}

void ob_meta_write_selection(FILE *f, const ob_run_opts *o, const ob_curveset *set)
{
    fputs("  \"selection\": ", f);
    if (!set) {
        fputs("null,\n", f);
        return;
    }
    fputc('{', f);
    put_curves(f, o, set);
    put_random(f, o, set);
    fputs(", \"methods\": [", f);
    for (int m = 0; m < o->nmethods; m++) {
        fputs(m ? ", " : "", f);
        ob_json_string(f, o->methods[m]->name);
    }
    fprintf(f, "], \"metrics\": [\"%s\"], \"splits\": [\"%s\"], \"tols\": [", ob_metric_name(o->metric),
            ob_split_name(o->split));
    for (int t = 0; t < o->ntols; t++) {
        fputs(t ? ", " : "", f);
        put_num(f, o->tols[t]);
    }
    fputs("], \"doc\": \"what the run set out to run: the curves from files with their offsets d, the random "
          "curves 0..n-1 of seed (or only those listed: --curve), methods, metrics, splits, tols; compare: a row "
          "of BASE outside NEW's selection was left out on purpose, one inside it that NEW lacks is missing "
          "(docs/nightly.md)\"},\n", f);
}
