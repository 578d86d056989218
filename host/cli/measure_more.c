/*
 * measure_more.c - measure's frame and verdict options (measure_more.h).
 */
#include "host/cli/measure_more.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "host/diag.h"
#include "host/io/numfmt.h"

enum { MM_TRANSFORM, MM_TRANSLATE, MM_SCALE, MM_FLIP_Y, MM_SVG_UNITS, MM_TOL };

static const ob_flag more_flags[] = {
    {"transform", "a,b,c,d,e,f", "map the file's coordinates to the base's: x' = a x + c y + e, y' = b x + d y + f "
     "(SVG matrix order), before matching", MM_TRANSFORM, OB_FLAG_ONCE},
    {"translate", "X,Y", "then move them: x' = x + X, y' = y + Y", MM_TRANSLATE, OB_FLAG_ONCE},
    {"scale", "S|SX,SY", "then scale them: x' = SX x, y' = SY y (S: both)", MM_SCALE, OB_FLAG_ONCE},
    {"flip-y", NULL, "then y' = -y (a CAD or SVG drawing with y the other way)", MM_FLIP_Y, OB_FLAG_ONCE},
    {"svg-units", "user|px", "an SVG file's coordinates: its root's user units (default) or CSS px, its root viewBox "
     "mapped onto its width and height (as svg2curves.py --units px)", MM_SVG_UNITS, OB_FLAG_ONCE},
    {"tol", "T", "the verdict: exit 1 when a file's error (hausdorff-whole, or the one --metric names) is over T "
     "(> 0), 0 when every file is within", MM_TOL, OB_FLAG_ONCE},
};

/* --transform's value into x; 0 or -1 after ob_error(). */
static int set_transform(ob_measure_more *x, const char *opt, const char *v)
{
    if (ob_frame_parse_list(v, x->transform.m, 6)) {
        ob_error("%s: '%s' is not six finite numbers a,b,c,d,e,f", opt, v);
        return -1;
    }
    const char *why = ob_frame_refuse(&x->transform);
    if (why) {
        ob_error("%s: '%s' is %s", opt, v, why);
        return -1;
    }
    return 0;
}

/* --scale's value: S or SX,SY, each finite and nonzero; 0 or -1. */
static int set_scale(ob_measure_more *x, const char *opt, const char *v)
{
    const int two = strchr(v, ',') != NULL;
    if (ob_frame_parse_list(v, x->scale, two ? 2 : 1) || x->scale[0] == 0.0 || (two && x->scale[1] == 0.0)) {
        ob_error("%s: '%s' is not a scale S or SX,SY (finite, nonzero)", opt, v);
        return -1;
    }
    if (!two)
        x->scale[1] = x->scale[0];
    return 0;
}

static int apply_more(void *ctx, int id, const char *opt, const char *v)
{
    ob_measure_more *x = ctx;
    x->have_frame |= id != MM_TOL && id != MM_SVG_UNITS;
    switch (id) {
    case MM_TRANSFORM:
        return set_transform(x, opt, v);
    case MM_TRANSLATE:
        if (ob_frame_parse_list(v, x->translate, 2)) {
            ob_error("%s: '%s' is not two finite numbers X,Y", opt, v);
            return -1;
        }
        return 0;
    case MM_SCALE:
        return set_scale(x, opt, v);
    case MM_FLIP_Y:
        x->flip_y = 1;
        return 0;
    case MM_SVG_UNITS:
        if (strcmp(v, "user") != 0 && strcmp(v, "px") != 0) {
            ob_error("%s: '%s' is not user or px", opt, v);
            return -1;
        }
        x->svg_px = !strcmp(v, "px");
        return 0;
    default:
        if (ob_parse_double(v, &x->tol) || !(x->tol > 0.0)) {
            ob_error("%s: '%s' is not a tolerance (a finite number > 0)", opt, v);
            return -1;
        }
        x->have_tol = 1;
        return 0;
    }
}

ob_flagset ob_measure_more_flags(ob_measure_more *x)
{
    memset(x, 0, sizeof *x);
    x->transform = OB_FRAME_IDENTITY;
    x->scale[0] = x->scale[1] = 1.0;
    return (ob_flagset){more_flags, (int)(sizeof more_flags / sizeof more_flags[0]), NULL, NULL,
                        "frame and verdict options", apply_more, x};
}

ob_frame ob_measure_more_frame(const ob_measure_more *x)
{
    const ob_frame t = {{1, 0, 0, 1, x->translate[0], x->translate[1]}};
    const ob_frame s = {{x->scale[0], 0, 0, x->scale[1], 0, 0}};
    const ob_frame f = {{1, 0, 0, x->flip_y ? -1 : 1, 0, 0}};
    const ob_frame tm = ob_frame_mul(&t, &x->transform), stm = ob_frame_mul(&s, &tm);
    return ob_frame_mul(&f, &stm);
}

int ob_measure_decider(const char *named)
{
    ob_metric m;
    if (!named || !strcmp(named, "all") || !strcmp(named, "hausdorff-whole") || ob_metric_parse(named, &m))
        return OB_METRIC_COUNT;
    return (int)m;
}

const ob_mres *ob_measure_decided(const ob_measure_out *out, int dm, const char **name)
{
    *name = dm == OB_METRIC_COUNT ? "hausdorff-whole" : ob_metric_name((ob_metric)dm);
    return dm == OB_METRIC_COUNT ? &out->whole : &out->res[dm];
}

int ob_measure_verdict_check(const ob_measure_more *x, int dm, const ob_measure_out *out, const char *name)
{
    const char *metric;
    const ob_mres *r = ob_measure_decided(out, dm, &metric);
    if (!x->have_tol || r->applies)
        return 0;
    ob_error("--tol: %s: its %s row is n/a (%s), so it has no error to hold against the tolerance: pick another "
             "--metric (hausdorff-whole applies to every file)", name, metric, r->why);
    return 2;
}

int ob_measure_verdict(const ob_measure_more *x, int dm, const ob_measure_out *out, const char *name)
{
    const char *metric;
    const ob_mres *r = ob_measure_decided(out, dm, &metric);
    return ob_measure_verdict_row(x, r, metric, name);
}

int ob_measure_verdict_row(const ob_measure_more *x, const ob_mres *r, const char *metric, const char *name)
{
    const int over = !(r->err <= x->tol);
    char ts[40], es[40];
    ob_fmt_double(ts, sizeof ts, x->tol);
    ob_fmt_double(es, sizeof es, r->err);
    ob_info("measure: %s: %s tolerance %s: %s = %s", name, over ? "over" : "within", ts, metric, es);
    return over;
}

void ob_measure_say_hidden(const int *want, const ob_measure_out *out, const char *name)
{
    char buf[2048] = "";
    size_t n = 0;
    const char *last_why = NULL;
    for (int m = 0; m < OB_METRIC_COUNT && n < sizeof buf; m++) {
        const ob_mres *r = &out->res[m];
        if (!want[m] || r->applies)
            continue;
        const int same = last_why && !strcmp(last_why, r->why);
        if (last_why && !same)
            n += (size_t)snprintf(buf + n, sizeof buf - n, " (n/a: %s);", last_why);
        if (n < sizeof buf)
            n += (size_t)snprintf(buf + n, sizeof buf - n, "%s %s", same ? "," : "", ob_metric_name((ob_metric)m));
        last_why = r->why;
    }
    if (!last_why)
        return;
    if (n < sizeof buf)
        snprintf(buf + n, sizeof buf - n, " (n/a: %s)", last_why);
    ob_info("measure: %s: not shown (--metric all shows every row):%s", name, buf);
}
