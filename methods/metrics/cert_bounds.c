/*
 * cert_bounds.c - the certified interval enclosures (see cert_bounds.h).
 */
#include "methods/metrics/cert_bounds.h"

#include <string.h>

static ob_iv pt(double x) { return ob_iv_pt(x); }

/* centre and radius: [lo, hi] within c +- r */
static double mid(ob_iv a) { return 0.5 * a.lo + 0.5 * a.hi; }
static double rad(ob_iv a) { return fmax(ob_iv_up(a.hi - mid(a)), ob_iv_up(mid(a) - a.lo)); }

static ob_iv norm(ob_iv x, ob_iv y) { return ob_iv_sqrt(ob_iv_add(ob_iv_sqr(x), ob_iv_sqr(y))); }
static ob_iv dotf(const ob_iv e[2], double ux, double uy)
{
    return ob_iv_add(ob_iv_scale(e[0], ux), ob_iv_scale(e[1], uy));
}

/* max over h in H of sqrt(N(h)^2 + T(h)^2) / |u|, N, T the components of
 * the Taylor form sum_{j <= order} e_j h^j / j! along u and its left normal
 * (each component a scalar function of h: the Lagrange remainder holds for
 * it, the last e_j the enclosure of the derivative over the interval). */
static double side_bound(const ob_iv e[][2], int order, double ux, double uy, ob_iv H)
{
    ob_iv pw[4];  /* h^j / j! over H */
    pw[0] = pt(1.0), pw[1] = H;
    pw[2] = ob_iv_scale(ob_iv_sqr(H), 0.5);
    pw[3] = ob_iv_div(ob_iv_mul(ob_iv_sqr(H), H), pt(6.0));  /* H is one-signed: exact hull of h^3 */
    ob_iv c[2];
    for (int j = 0; j < 2; j++) {
        const double ax = j ? -uy : ux, ay = j ? ux : uy;
        c[j] = dotf(e[0], ax, ay);
        for (int i = 1; i <= order; i++)
            c[j] = ob_iv_add(c[j], ob_iv_mul(dotf(e[i], ax, ay), pw[i]));
    }
    const ob_iv r = ob_iv_div(norm(c[0], c[1]), norm(pt(ux), pt(uy)));
    return r.hi == r.hi ? r.hi : INFINITY;
}

/* The bound of one Taylor form e[0..order] over [-hl, hr] in the frame
 * turned to the centre of e(m) (a tangential slip then enters squared). */
static double taylor_bound(const ob_iv e[][2], int order, ob_iv hl, ob_iv hr)
{
    double ux = mid(e[0][0]), uy = mid(e[0][1]);
    if (!(fabs(ux) + fabs(uy) > 0))
        ux = 1.0, uy = 0.0;
    const double U = fmax(side_bound(e, order, ux, uy, (ob_iv){-hl.hi, 0.0}),
                          side_bound(e, order, ux, uy, (ob_iv){0.0, hr.hi}));
    return U == U ? U : INFINITY;
}

int ob_cert_upper_prep(const ob_cv *P, double u0, double u1, int third, ob_cert_pside *ps)
{
    ps->u0 = u0, ps->u1 = u1, ps->m = 0.5 * (u0 + u1);
    ps->hl = ob_iv_sub(pt(ps->m), pt(u0)), ps->hr = ob_iv_sub(pt(u1), pt(ps->m));
    ob_iv r[2][2];
    ps->bad = ob_cv_point2(P, ps->m, ps->Pp, ps->P1, ps->P2m);
    /* the third-order form is optional: where P''' cannot be enclosed (an
     * overflow) only the second order bounds */
    ps->third = third && !ps->bad && !ob_cv_range_n(P, u0, u1, 2, 3, r);
    if (ps->third)
        memcpy(ps->P2, r[0], sizeof ps->P2), memcpy(ps->P3, r[1], sizeof ps->P3);
    else
        ps->bad = ps->bad || ob_cv_range(P, u0, u1, 2, ps->P2);
    return ps->bad ? -1 : 0;
}

/* Shift the correspondence t = tm + k h + c h^2 (h = u - m) into Q's
 * domain [0, 1] over the interval (by round-off at an end), or hold t
 * constant where it cannot be: sets *tm, *k, *c and the hull [*tlo, *thi]
 * of t (|t - tm| <= |k| r + |c| r^2, r the larger half-width). */
static void fit_line(const ob_cert_pside *ps, double *tm, double *k, double *c, double *tlo, double *thi)
{
    *tm = fmin(fmax(*tm, 0.0), 1.0);
    const double r = fmax(ps->hl.hi, ps->hr.hi);
    const double w = ob_iv_up(ob_iv_up(fabs(*k) * r) + ob_iv_up(ob_iv_up(fabs(*c) * r) * r));
    *tlo = ob_iv_dn(*tm - w), *thi = ob_iv_up(*tm + w);
    if (*tlo < 0.0 || *thi > 1.0) {
        *tm = *tlo < 0.0 ? *tm - 2.0 * *tlo + 0x1p-1070 : *tm - 2.0 * (*thi - 1.0);
        *tlo = ob_iv_dn(*tm - w), *thi = ob_iv_up(*tm + w);
    }
    if (!(*tlo >= 0.0 && *thi <= 1.0))  /* it still leaves it: hold t */
        *k = *c = 0.0, *tm = fmin(fmax(*tm, 0.0), 1.0), *tlo = *thi = *tm;
}

/* Q's derivatives over [tlo, thi] into Qr[0..2] (Q', Q'', Q'''): Q'' always,
 * Q' for a quadratic correspondence (c != 0), Q''' for the third-order
 * form (third); none where t is held (k = c = 0: every term with Q's
 * derivatives has a factor t' or t'' = 0).
 * Returns whether Q''' is enclosed, or -1 where Q' or Q'' cannot be (the
 * bound is +inf). */
static int q_range(const ob_cv *Q, double tlo, double thi, double c, int third, int held, ob_iv Qr[3][2])
{
    memset(Qr, 0, 3 * sizeof Qr[0]);
    if (held)
        return 1;
    const int k1 = c != 0.0 ? 1 : 2;
    if (third && !ob_cv_range_n(Q, tlo, thi, k1, 3, Qr + (k1 - 1)))
        return 1;
    return ob_cv_range_n(Q, tlo, thi, k1, 2, Qr + (k1 - 1)) ? -1 : 0;
}

double ob_cert_upper_quad(const ob_cert_pside *ps, const ob_cv *Q, double tm, double k, double c)
{
    double tlo, thi;
    fit_line(ps, &tm, &k, &c, &tlo, &thi);
    ob_iv Qp[2], Q1[2], Q2m[2] = {{0, 0}, {0, 0}}, Qr[3][2];
    if (ps->bad || (ps->third ? ob_cv_point2(Q, tm, Qp, Q1, Q2m) : ob_cv_point(Q, tm, Qp, Q1)))
        return INFINITY;
    const int qr = q_range(Q, tlo, thi, c, ps->third, k == 0.0 && c == 0.0, Qr);
    if (qr < 0)
        return INFINITY;
    const int third = ps->third && qr;
    /* e = P(u) - Q(t(u)), t = tm + k h + c h^2: e' = P' - t' Q',
     * e'' = P'' - t'^2 Q'' - 2 c Q', e''' = P''' - t'^3 Q''' - 6 c t' Q'',
     * t' = k + 2 c h: k at the midpoint, T1 over the interval */
    const ob_iv K = pt(k), K2 = ob_iv_sqr(K), C2 = pt(2.0 * c), C6 = ob_iv_scale(pt(c), 6.0);
    const ob_iv T1 = c == 0.0 ? K : ob_iv_add(K, ob_iv_mul(C2, ob_iv_make(-ps->hl.hi, ps->hr.hi)));
    const ob_iv T2 = ob_iv_sqr(T1), T3 = ob_iv_mul(T2, T1);
    ob_iv e2[3][2], e3[4][2];
    for (int j = 0; j < 2; j++) {
        e2[0][j] = e3[0][j] = ob_iv_sub(ps->Pp[j], Qp[j]);
        e2[1][j] = e3[1][j] = ob_iv_sub(ps->P1[j], ob_iv_mul(K, Q1[j]));
        e2[2][j] = ob_iv_sub(ob_iv_sub(ps->P2[j], ob_iv_mul(T2, Qr[1][j])), ob_iv_mul(C2, Qr[0][j]));
        e3[2][j] = ob_iv_sub(ob_iv_sub(ps->P2m[j], ob_iv_mul(K2, Q2m[j])), ob_iv_mul(C2, Q1[j]));
        e3[3][j] = ob_iv_sub(ob_iv_sub(ps->P3[j], ob_iv_mul(T3, Qr[2][j])), ob_iv_mul(ob_iv_mul(C6, T1), Qr[1][j]));
    }
    const double U2 = taylor_bound((const ob_iv (*)[2])e2, 2, ps->hl, ps->hr);
    return third ? fmin(U2, taylor_bound((const ob_iv (*)[2])e3, 3, ps->hl, ps->hr)) : U2;
}

double ob_cert_upper_line(const ob_cert_pside *ps, const ob_cv *Q, double tm, double k)
{
    return ob_cert_upper_quad(ps, Q, tm, k, 0.0);
}

double ob_cert_upper(const ob_cv *P, const ob_cv *Q, double u0, double u1, double tm, double k)
{
    ob_cert_pside ps;
    ob_cert_upper_prep(P, u0, u1, 1, &ps);
    return ob_cert_upper_line(&ps, Q, tm, k);
}

/* A lower bound of |x|, x an interval. */
static double mag_lo(ob_iv x) { return x.lo > 0 ? x.lo : x.hi < 0 ? -x.hi : 0.0; }

/* A lower bound of min over tau in H of |v - D tau| (v, D float vectors). */
static double seg_dist_lo(const double v[2], const double D[2], ob_iv H)
{
    const ob_iv dd = norm(pt(D[0]), pt(D[1]));
    if (!(dd.lo > 0))
        return norm(pt(v[0]), pt(v[1])).lo;
    const ob_iv proj = ob_iv_div(ob_iv_add(ob_iv_mul(pt(v[0]), pt(D[0])), ob_iv_mul(pt(v[1]), pt(D[1]))),
                                 ob_iv_sqr(dd));
    if (proj.lo >= H.hi || proj.hi <= H.lo) {  /* the nearest point is an end */
        const ob_iv h = pt(proj.lo >= H.hi ? H.hi : H.lo);
        return norm(ob_iv_sub(pt(v[0]), ob_iv_mul(pt(D[0]), h)), ob_iv_sub(pt(v[1]), ob_iv_mul(pt(D[1]), h))).lo;
    }
    const ob_iv crs = ob_iv_sub(ob_iv_mul(pt(v[0]), pt(D[1])), ob_iv_mul(pt(v[1]), pt(D[0])));
    return ob_iv_dn(mag_lo(crs) / dd.hi);
}

double ob_cert_lower(const ob_cv *Q, const ob_iv a[2], double t0, double t1)
{
    const double m = 0.5 * (t0 + t1);
    ob_iv Qp[2], Q1[2], D[2];
    if (ob_cv_point(Q, m, Qp, Q1) || ob_cv_range(Q, t0, t1, 1, D))
        return 0.0;
    const ob_iv H = ob_iv_make(ob_iv_dn(t0 - m), ob_iv_up(t1 - m));
    double vc[2], vr[2], Dc[2], Dr[2];
    for (int c = 0; c < 2; c++) {
        const ob_iv v = ob_iv_sub(a[c], Qp[c]);
        vc[c] = mid(v), vr[c] = rad(v), Dc[c] = mid(D[c]), Dr[c] = rad(D[c]);
    }
    const ob_iv slack = ob_iv_add(norm(pt(vr[0]), pt(vr[1])),
                                  ob_iv_scale(norm(pt(Dr[0]), pt(Dr[1])), fmax(-H.lo, H.hi)));
    const double L = ob_iv_dn(seg_dist_lo(vc, Dc, H) - slack.hi);
    return L > 0 ? L : 0.0;
}
