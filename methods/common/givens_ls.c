/*
 * givens_ls.c - weighted linear least squares by row-wise Givens QR.  See
 * givens_ls.h.
 */
#include "methods/common/givens_ls.h"

#include <math.h>
#include <string.h>

size_t ob_gls_mem_rhs(int n, int nrhs) { return (size_t)n * (size_t)(n + nrhs) + (size_t)n; }

size_t ob_gls_mem(int n) { return ob_gls_mem_rhs(n, 1); }

void ob_gls_init_rhs(ob_gls *g, int n, int nrhs, double *mem)
{
    nrhs = nrhs < 1 ? 1 : nrhs > OB_GLS_MAX_RHS ? OB_GLS_MAX_RHS : nrhs;
    g->n = n;
    g->nrhs = nrhs;
    g->R = mem;
    g->cn2 = mem + (size_t)n * (size_t)(n + nrhs);
    g->rss = 0.0;
    g->maxcol = -1;
    memset(mem, 0, ob_gls_mem_rhs(n, nrhs) * sizeof *mem);
}

void ob_gls_init(ob_gls *g, int n, double *mem) { ob_gls_init_rhs(g, n, 1, mem); }

/* The row a (nonzero in [lo, hi]) and right-hand sides b[nrhs], weighted
 * already, rotated into R column by column: a zero entry needs no rotation,
 * and beyond maxcol both the row and R are zero. */
static void rotate_in(ob_gls *g, double *a, int lo, int hi, double *b)
{
    const int n = g->n, ld = n + g->nrhs;
    if (hi > g->maxcol)
        g->maxcol = hi;
    const int last = g->maxcol;
    for (int i = lo; i <= last; i++) {
        if (a[i] == 0.0)
            continue;
        double *r = g->R + (size_t)i * ld;
        const double h = hypot(r[i], a[i]), c = r[i] / h, s = a[i] / h;
        r[i] = h;
        a[i] = 0.0;
        for (int j = i + 1; j <= last; j++) {
            const double rj = r[j], aj = a[j];
            r[j] = c * rj + s * aj;
            a[j] = c * aj - s * rj;
        }
        for (int k = 0; k < g->nrhs; k++) {
            const double rb = r[n + k];
            r[n + k] = c * rb + s * b[k];
            b[k] = c * b[k] - s * rb;
        }
    }
    for (int k = 0; k < g->nrhs; k++)
        g->rss += b[k] * b[k];
}

void ob_gls_add(ob_gls *g, double *a, double b, double w)
{
    const int n = g->n;
    for (int j = 0; j < n; j++) {
        a[j] *= w;
        g->cn2[j] += a[j] * a[j];
    }
    b *= w;
    rotate_in(g, a, 0, n - 1, &b);
}

void ob_gls_add_band(ob_gls *g, double *a, int lo, int hi, const double *b, double w)
{
    double bw[OB_GLS_MAX_RHS];
    for (int j = lo; j <= hi; j++) {
        a[j] *= w;
        g->cn2[j] += a[j] * a[j];
    }
    for (int k = 0; k < g->nrhs; k++)
        bw[k] = b[k] * w;
    rotate_in(g, a, lo, hi, bw);
}

int ob_gls_solve_rhs(const ob_gls *g, int k, double *x, double rtol)
{
    const int n = g->n, ld = n + g->nrhs;
    for (int i = n - 1; i >= 0; i--) {
        const double *r = g->R + (size_t)i * ld;
        if (!(g->cn2[i] > 0.0) || !(fabs(r[i]) > rtol * sqrt(g->cn2[i])))
            return -1;
        double s = r[n + k];
        for (int j = i + 1; j < n; j++)
            s -= r[j] * x[j];
        x[i] = s / r[i];
    }
    return 0;
}

int ob_gls_solve(const ob_gls *g, double *x, double rtol) { return ob_gls_solve_rhs(g, 0, x, rtol); }
