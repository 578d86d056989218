/*
 * driver_fixture.h - what the driver tests build their jobs from: a
 * one-segment curve with one offset, Liu & Wang's Example 1 cubic (Liu &
 * Wang 2002, J. Software 13(3), Example 1), and a job on it.
 */
#ifndef OB_DRIVER_FIXTURE_H
#define OB_DRIVER_FIXTURE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/driver/driver.h"

static const double fixture_liu_ex1[4][2] = {
    {-0.785938, 0.891849}, {-0.993306, -0.59695}, {0.3, -2.5}, {0.9, -0.2}};

/* A curve of one Bézier segment of degree deg through the control points xy,
 * with the one offset d.  Free it with ob_curve_free. */
static inline ob_curve fixture_curve(const char *id, int deg, const double (*xy)[2], double d)
{
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "%s", id);
    c.nseg = 1;
    c.seg = calloc(1, sizeof *c.seg);
    ob_bez_from_points(c.seg, deg, xy);
    c.nd = 1;
    c.d = malloc(sizeof *c.d);
    c.d[0] = d;
    return c;
}

/* A job of method m on curve c at its offset, with the outputs cleared. */
static inline void fixture_job(ob_job *j, const ob_curve *c, const ob_method *m, ob_metric metric, ob_split split,
                               double tol)
{
    memset(j, 0, sizeof *j);
    j->curve = c;
    j->d = c->d[0];
    j->method = m;
    j->metric = metric;
    j->split = split;
    j->tol = tol;
}

#endif
