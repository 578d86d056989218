/*
 * test_atlas_curves.c - every curve of datasets/atlas.curves lies on the
 * implicit curve its source line names (the Offset Atlas of San Segundo,
 * Sendra & Sendra, ICM 2006 poster): F(X(u), Y(u), W(u)) = 0 identically, F homogenized with W, in
 * exact integer polynomial arithmetic (FLINT) on the file's integer
 * homogeneous control points.  Each equation's degree and number of terms
 * are checked against the atlas' columns (results/published/offset_atlas.csv),
 * so a reading of a row (e.g. the Ramphoid's) is pinned to the atlas.
 */
#include <flint/fmpz_poly.h>
#include <math.h>
#include <string.h>

#include "host/io/curvefile.h"
#include "tests/check.h"

typedef struct {
    int c, i, j;  /* c x^i y^j */
} mono;

enum { MAX_TERMS = 8 };

typedef struct {
    const char *id;
    int degree, terms;  /* the atlas' degree and terms columns */
    mono m[MAX_TERMS];
} implicit;

/* The implicit equations, expanded; degree and terms as the atlas lists. */
static const implicit eqs[] = {
    {"atlas_circle", 2, 3, {{1, 2, 0}, {1, 0, 2}, {-1, 0, 0}}},
    {"atlas_ellipse", 2, 3, {{1, 2, 0}, {4, 0, 2}, {-4, 0, 0}}},
    {"atlas_hyperbola", 2, 3, {{1, 2, 0}, {-1, 0, 2}, {-1, 0, 0}}},
    {"atlas_parabola", 2, 2, {{1, 0, 1}, {-1, 2, 0}}},
    {"atlas_conchoid", 3, 3, {{1, 0, 2}, {-1, 1, 2}, {-1, 3, 0}}},
    {"atlas_cuspidal_cubic", 3, 2, {{1, 0, 2}, {-1, 3, 0}}},
    {"atlas_trisectrix", 3, 4, {{1, 0, 2}, {1, 1, 2}, {-3, 2, 0}, {1, 3, 0}}},
    {"atlas_folium", 3, 3, {{1, 3, 0}, {1, 0, 3}, {-3, 1, 1}}},
    {"atlas_epitrochoid", 4, 7, {{1, 4, 0}, {2, 2, 2}, {1, 0, 4}, {-2, 3, 0}, {-2, 1, 2}, {-3, 2, 0}, {-4, 0, 2}}},
    {"atlas_lemniscate", 4, 5, {{1, 4, 0}, {2, 2, 2}, {1, 0, 4}, {-1, 2, 0}, {1, 0, 2}}},
    {"atlas_cardioid", 4, 6, {{1, 4, 0}, {2, 2, 2}, {1, 0, 4}, {-2, 3, 0}, {-2, 1, 2}, {-1, 0, 2}}},
    {"atlas_trifolium", 4, 5, {{1, 4, 0}, {2, 2, 2}, {1, 0, 4}, {-1, 3, 0}, {3, 1, 2}}},
    {"atlas_ramphoid", 4, 5, {{1, 4, 0}, {1, 2, 2}, {-2, 2, 1}, {-1, 1, 2}, {1, 0, 2}}},
};

static unsigned long binomial(int n, int k)
{
    unsigned long r = 1;
    for (int j = 1; j <= k; j++)
        r = r * (unsigned long)(n - k + j) / (unsigned long)j;
    return r;
}

/* One homogeneous coordinate (k = 0, 1, 2: w x, w y, w) of a Bézier segment
 * in the power basis: sum_i h_i C(n, i) u^i (1 - u)^(n - i).  Returns -1
 * when a control coordinate is not an integer (the file promises integers). */
static int coord_poly(fmpz_poly_t out, const ob_bez *b, int k)
{
    fmpz_poly_t term, one_minus;
    fmpz_poly_init(term);
    fmpz_poly_init(one_minus);
    fmpz_poly_set_coeff_si(one_minus, 0, 1);
    fmpz_poly_set_coeff_si(one_minus, 1, -1);
    fmpz_poly_zero(out);
    int rc = 0;
    for (int i = 0; i <= b->deg; i++) {
        const double h = b->h[i][k];
        if (h != floor(h) || fabs(h) > 1e15)
            rc = -1;
        fmpz_poly_pow(term, one_minus, (unsigned long)(b->deg - i));
        fmpz_poly_shift_left(term, term, i);
        fmpz_poly_scalar_mul_si(term, term, (long)h);
        fmpz_poly_scalar_mul_ui(term, term, binomial(b->deg, i));
        fmpz_poly_add(out, out, term);
    }
    fmpz_poly_clear(term);
    fmpz_poly_clear(one_minus);
    return rc;
}

/* F(X, Y, W) with F homogenized to its degree: sum c X^i Y^j W^(d - i - j). */
static void eval_implicit(fmpz_poly_t out, const implicit *e, fmpz_poly_t xyw[3])
{
    fmpz_poly_t t, p;
    fmpz_poly_init(t);
    fmpz_poly_init(p);
    fmpz_poly_zero(out);
    for (int k = 0; k < e->terms; k++) {
        const mono *m = &e->m[k];
        fmpz_poly_set_si(t, m->c);
        fmpz_poly_pow(p, xyw[0], (unsigned long)m->i);
        fmpz_poly_mul(t, t, p);
        fmpz_poly_pow(p, xyw[1], (unsigned long)m->j);
        fmpz_poly_mul(t, t, p);
        fmpz_poly_pow(p, xyw[2], (unsigned long)(e->degree - m->i - m->j));
        fmpz_poly_mul(t, t, p);
        fmpz_poly_add(out, out, t);
    }
    fmpz_poly_clear(t);
    fmpz_poly_clear(p);
}

static void test_equation(const ob_curveset *set, const implicit *e)
{
    int nterms = 0, deg = 0;
    for (int k = 0; k < MAX_TERMS; k++)
        if (e->m[k].c) {
            nterms++;
            if (e->m[k].i + e->m[k].j > deg)
                deg = e->m[k].i + e->m[k].j;
        }
    CHECK(nterms == e->terms && deg == e->degree, "%s: the equation has %d terms, degree %d (the atlas: %d, %d)",
          e->id, nterms, deg, e->terms, e->degree);
    const int i = ob_curveset_find(set, e->id);
    CHECK(i >= 0, "%s: not in datasets/atlas.curves", e->id);
    if (i < 0)
        return;
    const ob_curve *c = &set->v[i];
    CHECK(c->nseg == 1, "%s: %d segments (want one exact Bezier segment)", e->id, c->nseg);
    fmpz_poly_t xyw[3], f;
    int ints = 0;
    for (int k = 0; k < 3; k++) {
        fmpz_poly_init(xyw[k]);
        ints |= coord_poly(xyw[k], &c->seg[0], k);
    }
    CHECK(ints == 0, "%s: a control coordinate is not an integer", e->id);
    fmpz_poly_init(f);
    eval_implicit(f, e, xyw);
    CHECK(fmpz_poly_is_zero(f), "%s: F(X(u), Y(u), W(u)) is not zero (degree %ld)", e->id, fmpz_poly_degree(f));
    fmpz_poly_clear(f);
    for (int k = 0; k < 3; k++)
        fmpz_poly_clear(xyw[k]);
}

/* A wrong equation is caught: the circle does not lie on the ellipse. */
static void test_detects_wrong(const ob_curveset *set)
{
    implicit wrong = eqs[1];
    wrong.id = "atlas_circle";
    const int i = ob_curveset_find(set, wrong.id);
    if (i < 0)
        return;
    fmpz_poly_t xyw[3], f;
    for (int k = 0; k < 3; k++) {
        fmpz_poly_init(xyw[k]);
        coord_poly(xyw[k], &set->v[i].seg[0], k);
    }
    fmpz_poly_init(f);
    eval_implicit(f, &wrong, xyw);
    CHECK(!fmpz_poly_is_zero(f), "the circle satisfies the ellipse's equation: the check proves nothing");
    fmpz_poly_clear(f);
    for (int k = 0; k < 3; k++)
        fmpz_poly_clear(xyw[k]);
}

int main(void)
{
    ob_curveset set = {0};
    ob_err err = {""};
    CHECK(ob_curves_load_file("datasets/atlas.curves", &set, &err) == 0, "atlas.curves: %s", err.msg);
    for (size_t k = 0; k < sizeof eqs / sizeof eqs[0]; k++)
        test_equation(&set, &eqs[k]);
    test_detects_wrong(&set);
    ob_curveset_free(&set);
    return check_done();
}
