/*
 * givens_ls.c - weighted linear least squares by row-wise Givens QR.  See
 * givens_ls.h.
 */
#include "methods/common/givens_ls.h"

#include <math.h>
#include <string.h>

size_t ob_gls_mem(int n) { return (size_t)n * (size_t)(n + 1) + (size_t)n; }

void ob_gls_init(ob_gls *g, int n, double *mem)
{
    g->n = n;
    g->R = mem;
    g->cn2 = mem + (size_t)n * (size_t)(n + 1);
    g->rss = 0.0;
    memset(mem, 0, ob_gls_mem(n) * sizeof *mem);
}

void ob_gls_add(ob_gls *g, double *a, double b, double w)
{
    const int n = g->n, ld = n + 1;
    for (int j = 0; j < n; j++) {
        a[j] *= w;
        g->cn2[j] += a[j] * a[j];
    }
    b *= w;
    for (int i = 0; i < n; i++) {
        if (a[i] == 0.0)
            continue;
        double *r = g->R + (size_t)i * ld;
        const double h = hypot(r[i], a[i]), c = r[i] / h, s = a[i] / h;
        r[i] = h;
        a[i] = 0.0;
        for (int j = i + 1; j < n; j++) {
            const double rj = r[j], aj = a[j];
            r[j] = c * rj + s * aj;
            a[j] = c * aj - s * rj;
        }
        const double rb = r[n];
        r[n] = c * rb + s * b;
        b = c * b - s * rb;
    }
    g->rss += b * b;
}

int ob_gls_solve(const ob_gls *g, double *x, double rtol)
{
    const int n = g->n, ld = n + 1;
    for (int i = n - 1; i >= 0; i--) {
        const double *r = g->R + (size_t)i * ld;
        if (!(g->cn2[i] > 0.0) || !(fabs(r[i]) > rtol * sqrt(g->cn2[i])))
            return -1;
        double s = r[n];
        for (int j = i + 1; j < n; j++)
            s -= r[j] * x[j];
        x[i] = s / r[i];
    }
    return 0;
}
