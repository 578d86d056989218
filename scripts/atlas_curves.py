#!/usr/bin/python3
"""atlas_curves.py - writes datasets/atlas.curves: the rational curves of San
Segundo, Sendra & Sendra's Offset Atlas ("Algorithms for offset curves and
surfaces", ICM 2006 poster) as exact Bézier segments.

Each curve is given here by a rational parameterization (X(t), Y(t), W(t))
with integer coefficients (its derivation in `derivation`), restricted to a
parameter interval [t0, t1] away from singular points (t = t0 + (t1 - t0) u,
u in [0, 1]), converted exactly to Bernstein form and written as homogeneous
integer control points (`hpoint WX WY W`), so the file holds the curve
exactly: offbench's exact offset degree is that of the atlas curve.

Run: /usr/bin/python3 scripts/atlas_curves.py > datasets/atlas.curves
"""
from fractions import Fraction as F
from math import comb, lcm

# name (as in the atlas), id, (X, Y, W) power coefficients (t^0 first),
# interval, derivation
CURVES = [
    ("Circle", "atlas_circle", ([1, 0, -1], [0, 2], [1, 0, 1]), (0, 1),
     "x^2 + y^2 = 1: x = (1 - t^2)/(1 + t^2), y = 2t/(1 + t^2) (t = tan(theta/2))"),
    ("Ellipse", "atlas_ellipse", ([2, 0, -2], [0, 2], [1, 0, 1]), (0, 1),
     "x^2/4 + y^2 = 1: the circle's parameterization with x scaled by 2"),
    ("Hyperbola", "atlas_hyperbola", ([1, 0, 1], [0, 2], [1, 0, -1]), (0, F(1, 2)),
     "x^2 - y^2 = 1: x = (1 + t^2)/(1 - t^2), y = 2t/(1 - t^2); t in [0, 1/2] keeps W > 0"),
    ("Parabola", "atlas_parabola", ([0, 1], [0, 0, 1], [1]), (0, 1), "y = x^2: (t, t^2)"),
    ("Conchoid", "atlas_conchoid", ([0, 0, 1], [0, 0, 0, 1], [1, 0, 1]), (F(1, 2), F(3, 2)),
     "conchoid of de Sluze (x - 1)(x^2 + y^2) = a x^2 with a = -1, i.e. y^2 (1 - x) = x^3 (3 terms, as the "
     "atlas counts): x = t^2/(1 + t^2), y = t^3/(1 + t^2); t in [1/2, 3/2] avoids the cusp at t = 0. The atlas "
     "does not say which conchoid it means: this reading is ours"),
    ("Cuspidal Cubic", "atlas_cuspidal_cubic", ([0, 0, 1], [0, 0, 0, 1], [1]), (F(1, 2), F(3, 2)),
     "y^2 = x^3: (t^2, t^3); t in [1/2, 3/2] avoids the cusp at t = 0"),
    ("Trisectrix", "atlas_trisectrix", ([3, 0, -1], [0, 3, 0, -1], [1, 0, 1]), (0, 1),
     "trisectrix of Maclaurin y^2 (1 + x) = x^2 (3 - x): with y = m x, x = (3 - m^2)/(1 + m^2), "
     "y = m (3 - m^2)/(1 + m^2)"),
    ("Folium", "atlas_folium", ([0, 3], [0, 0, 3], [1, 0, 0, 1]), (0, 1),
     "folium of Descartes x^3 + y^3 = 3xy: x = 3t/(1 + t^3), y = 3t^2/(1 + t^3)"),
    ("Epitrochoid", "atlas_epitrochoid", ([3, 0, -2, 0, -1], [0, 6, 0, 2], [1, 0, 2, 0, 1]), (0, 1),
     "the epitrochoid limacon of Pascal r = 2 + cos(theta), (x^2 + y^2 - x)^2 = 4 (x^2 + y^2) (7 terms): "
     "x = (3 + t^2)(1 - t^2)/(1 + t^2)^2, y = 2t (3 + t^2)/(1 + t^2)^2 (t = tan(theta/2)); the atlas does not "
     "say which epitrochoid: this reading is ours"),
    ("Ramphoid", "atlas_ramphoid", ([1, -1, 1], [1], [1, -1, 2, -1, 1]), (0, 1),
     "ramphoid quartic x^4 + x^2 y^2 - 2 x^2 y - x y^2 + y^2 (degree 4, 5 terms, as the atlas lists; the atlas "
     "gives no equation: this reading is ours): a ramphoid cusp at the origin and an acnode at infinity, so "
     "genus 0; x = 1/(1 + t^2), y = 1/((1 + t^2)(t^2 - t + 1)), the cusp at t = infinity"),
    ("Lemniscate", "atlas_lemniscate", ([0, 1, 0, 1], [0, 1, 0, -1], [1, 0, 0, 0, 1]), (0, 1),
     "lemniscate of Bernoulli (x^2 + y^2)^2 = x^2 - y^2: x = (t + t^3)/(1 + t^4), y = (t - t^3)/(1 + t^4)"),
    ("Cardioid", "atlas_cardioid", ([2, 0, -2], [0, 4], [1, 0, 2, 0, 1]), (0, 1),
     "cardioid r = 1 + cos(theta), (x^2 + y^2 - x)^2 = x^2 + y^2: x = 2(1 - t^2)/(1 + t^2)^2, "
     "y = 4t/(1 + t^2)^2 (t = tan(theta/2)); the cusp is at t = infinity"),
    ("Trifolium", "atlas_trifolium", ([1, 0, -3], [0, 1, 0, -3], [1, 0, 2, 0, 1]), (0, 1),
     "trifolium r = cos(3 theta), (x^2 + y^2)^2 = x^3 - 3 x y^2: with u = tan(theta), x = (1 - 3u^2)/(1 + u^2)^2, "
     "y = u (1 - 3u^2)/(1 + u^2)^2 (proper: theta in [0, pi) traces it once)"),
]


def compose(p, t0, t1):
    """p(t0 + (t1 - t0) u) as power coefficients in u (exact)."""
    a, b = F(t0), F(t1) - F(t0)
    out = [F(0)] * len(p)
    for k, c in enumerate(p):  # c (a + b u)^k
        for j in range(k + 1):
            out[j] += F(c) * comb(k, j) * a ** (k - j) * b ** j
    return out


def bernstein(p, n):
    p = list(p) + [F(0)] * (n + 1 - len(p))
    return [sum(F(comb(i, j), comb(n, j)) * p[j] for j in range(i + 1)) for i in range(n + 1)]


def main():
    print("# The rational curves of San Segundo & Sendra's Offset Atlas (poster, ICM 2006; its table: results/published/offset_atlas.csv)")
    print("# as exact Bezier segments: written by scripts/atlas_curves.py (see there for each derivation).")
    print("# hpoint WX WY W: homogeneous integer control points, so each curve is exact, not rounded.")
    print("# Not here: x^4 + y^4 - y^2 (genus 1: a quartic with one tacnode; not rational), the quadrics")
    print("# (surfaces).")
    for name, cid, (X, Y, W), (t0, t1), how in CURVES:
        n = max(len(X), len(Y), len(W)) - 1
        cols = [bernstein(compose(p, t0, t1), n) for p in (X, Y, W)]
        den = lcm(*[c.denominator for col in cols for c in col])
        pts = [[int(c * den) for c in col] for col in cols]
        if any(w <= 0 for w in pts[2]):
            raise SystemExit(f"{cid}: a weight is not positive on [{t0}, {t1}]")
        print()
        print(f"curve {cid}")
        print(f"  source Offset Atlas: {name}; {how}; t in [{t0}, {t1}]")
        print("  family atlas")
        print(f"  bezier {n}")
        for i in range(n + 1):
            print(f"  hpoint {pts[0][i]} {pts[1][i]} {pts[2][i]}")
        print("  offset 0.125")
        print("end")


if __name__ == "__main__":
    main()
