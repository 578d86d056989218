/*
 * similarity.c - the least-squares similarity between two point lists
 * (frame.h, ob_similarity_fit): Procrustes in the plane.
 */
#include "host/measure/frame.h"

#include <math.h>

/* The centroid of n points. */
static void centroid(const double (*p)[2], int n, double c[2])
{
    c[0] = c[1] = 0.0;
    for (int i = 0; i < n; i++) {
        c[0] += p[i][0];
        c[1] += p[i][1];
    }
    c[0] /= n;
    c[1] /= n;
}

int ob_similarity_fit(const double (*p)[2], const double (*q)[2], int n, int reflect, ob_frame *f)
{
    if (n < 2)
        return -1;
    const double sy = reflect ? -1.0 : 1.0;  /* p reflected first: (x, y) -> (x, -y) */
    double cp[2], cq[2];
    centroid(p, n, cp);
    centroid(q, n, cq);
    cp[1] *= sy;
    double sa = 0.0, sb = 0.0, spp = 0.0;
    for (int i = 0; i < n; i++) {
        const double px = p[i][0] - cp[0], py = sy * p[i][1] - cp[1];
        const double qx = q[i][0] - cq[0], qy = q[i][1] - cq[1];
        sa += px * qx + py * qy;  /* the rotation's cos part, times s */
        sb += px * qy - py * qx;  /* its sin part */
        spp += px * px + py * py;
    }
    if (!(spp > 0.0))
        return -1;
    const double a = sa / spp, b = sb / spp;  /* s cos(theta), s sin(theta): the least-squares optimum */
    /* q = [a -b; b a] (R p) + t, R = diag(1, sy) */
    f->m[0] = a;
    f->m[1] = b;
    f->m[2] = -b * sy;
    f->m[3] = a * sy;
    f->m[4] = cq[0] - (a * cp[0] - b * cp[1]);
    f->m[5] = cq[1] - (b * cp[0] + a * cp[1]);
    return 0;
}
