/*
 * cert_bounds.c - the certified interval enclosures (see cert_bounds.h).
 */
#include "methods/metrics/cert_bounds.h"

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
 * e0 + e1 h + e2 h^2 / 2 along u and its left normal. */
static double side_bound(const ob_iv e[3][2], double ux, double uy, ob_iv H)
{
    const ob_iv h2 = ob_iv_scale(ob_iv_sqr(H), 0.5);
    ob_iv c[2];
    for (int j = 0; j < 2; j++) {
        const double ax = j ? -uy : ux, ay = j ? ux : uy;
        c[j] = ob_iv_add(ob_iv_add(dotf(e[0], ax, ay), ob_iv_mul(dotf(e[1], ax, ay), H)),
                         ob_iv_mul(dotf(e[2], ax, ay), h2));
    }
    const ob_iv r = ob_iv_div(norm(c[0], c[1]), norm(pt(ux), pt(uy)));
    return r.hi == r.hi ? r.hi : INFINITY;
}

int ob_cert_upper_prep(const ob_cv *P, double u0, double u1, ob_cert_pside *ps)
{
    ps->u0 = u0, ps->u1 = u1, ps->m = 0.5 * (u0 + u1);
    ps->hl = ob_iv_sub(pt(ps->m), pt(u0)), ps->hr = ob_iv_sub(pt(u1), pt(ps->m));
    ps->bad = ob_cv_point(P, ps->m, ps->Pp, ps->P1) || ob_cv_range(P, u0, u1, 2, ps->P2);
    return ps->bad ? -1 : 0;
}

double ob_cert_upper_line(const ob_cert_pside *ps, const ob_cv *Q, double tm, double k)
{
    const ob_iv hl = ps->hl, hr = ps->hr;
    tm = fmin(fmax(tm, 0.0), 1.0);
    const double w = ob_iv_up(fabs(k) * fmax(hl.hi, hr.hi));
    double tlo = ob_iv_dn(tm - w), thi = ob_iv_up(tm + w);
    if (tlo < 0.0 || thi > 1.0) {  /* shift the line into Q's domain (by round-off at an end) */
        tm = tlo < 0.0 ? tm - 2.0 * tlo + 0x1p-1070 : tm - 2.0 * (thi - 1.0);
        tlo = ob_iv_dn(tm - w), thi = ob_iv_up(tm + w);
    }
    if (!(tlo >= 0.0 && thi <= 1.0))  /* the line still leaves it: hold t */
        k = 0.0, tm = fmin(fmax(tm, 0.0), 1.0), tlo = thi = tm;
    ob_iv Qp[2], Q1[2], Q2[2] = {{0, 0}, {0, 0}};
    if (ps->bad || ob_cv_point(Q, tm, Qp, Q1))
        return INFINITY;
    if (k != 0.0 && ob_cv_range(Q, tlo, thi, 2, Q2))
        return INFINITY;
    const ob_iv K = pt(k), K2 = ob_iv_sqr(K);
    ob_iv e[3][2];
    for (int c = 0; c < 2; c++) {
        e[0][c] = ob_iv_sub(ps->Pp[c], Qp[c]);
        e[1][c] = ob_iv_sub(ps->P1[c], ob_iv_mul(K, Q1[c]));
        e[2][c] = ob_iv_sub(ps->P2[c], ob_iv_mul(K2, Q2[c]));
    }
    double ux = mid(e[0][0]), uy = mid(e[0][1]);
    if (!(fabs(ux) + fabs(uy) > 0))
        ux = 1.0, uy = 0.0;
    const double U = fmax(side_bound(e, ux, uy, (ob_iv){-hl.hi, 0.0}), side_bound(e, ux, uy, (ob_iv){0.0, hr.hi}));
    return U == U ? U : INFINITY;
}

double ob_cert_upper(const ob_cv *P, const ob_cv *Q, double u0, double u1, double tm, double k)
{
    ob_cert_pside ps;
    ob_cert_upper_prep(P, u0, u1, &ps);
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
