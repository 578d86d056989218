/*
 * frame.c - affine maps from a file's coordinates to the base's
 * (frame.h): composing, checking, parsing, applying to pieces.
 */
#include "host/measure/frame.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/io/numfmt.h"

const ob_frame OB_FRAME_IDENTITY = {{1, 0, 0, 1, 0, 0}};

ob_frame ob_frame_mul(const ob_frame *a, const ob_frame *b)
{
    return ob_svgr_mul(a, b);
}

void ob_frame_point(const ob_frame *f, const double p[2], double q[2])
{
    const double x = p[0], y = p[1];
    q[0] = f->m[0] * x + f->m[2] * y + f->m[4];
    q[1] = f->m[1] * x + f->m[3] * y + f->m[5];
}

double ob_frame_det(const ob_frame *f)
{
    return f->m[0] * f->m[3] - f->m[1] * f->m[2];
}

const char *ob_frame_refuse(const ob_frame *f)
{
    double big = 0.0;
    for (int i = 0; i < 6; i++) {
        if (!isfinite(f->m[i]))
            return "a number that is not finite";
        if (i < 4)
            big = fmax(big, fabs(f->m[i]));
    }
    const double det = ob_frame_det(f);
    if (!isfinite(det) || !(fabs(det) > 1e-12 * big * big))
        return "a singular matrix (a d - b c is 0: it maps the plane onto a line or a point)";
    return NULL;
}

int ob_frame_parse_list(const char *s, double *v, int n)
{
    char buf[512];
    if (n < 1 || n > 6 || strlen(s) >= sizeof buf)
        return -1;
    memcpy(buf, s, strlen(s) + 1);
    int k = 0;
    for (char *tok = buf, *next; tok; tok = next) {
        next = strchr(tok, ',');
        if (next)
            *next++ = '\0';
        if (k == n || ob_parse_double(tok, &v[k]))
            return -1;
        k++;
    }
    return k == n ? 0 : -1;
}

void ob_frame_apply(const ob_frame *f, ob_approx *a)
{
    const double *m = f->m;
    for (int k = 0; k < a->n; k++) {
        ob_bez *b = &a->v[k].approx;
        for (int i = 0; i <= b->deg; i++) {
            double *h = b->h[i];
            const double wx = h[0], wy = h[1], w = h[2];
            h[0] = m[0] * wx + m[2] * wy + m[4] * w;
            h[1] = m[1] * wx + m[3] * wy + m[5] * w;
        }
    }
}

void ob_frame_text(const ob_frame *f, char *buf, size_t len)
{
    snprintf(buf, len, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", f->m[0], f->m[1], f->m[2], f->m[3], f->m[4], f->m[5]);
}
