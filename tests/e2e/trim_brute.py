"""trim_brute.py - an independent brute force of the trimmed offset, for
tests/e2e/e2e_measure_trimmed.sh (issue 50); it shares no code with
offbench (host/measure/trim.c).

The base: one Bezier segment of a .curves file (`point X Y` or `hpoint WX WY
W` lines), evaluated here in Bernstein form, its hodograph by the quotient
rule.  The offset O = C + d N, N the left unit normal (-y', x') / |C'|.

  check CURVES ID D DUMP [N]
      samples O at N (default 200001) parameters and keeps those whose
      distance to C (the 8 nearest of 2001 samples of C by a k-d tree, each
      refined by Newton's method on (C(t) - P).C'(t) = 0 within a spacing
      of it, and C's end points) is >= |d| (1 - 1e-9); every
      kept sample must lie in one of DUMP's arcs (`measure --trim-dump`),
      every removed one outside them, but within 2 / N of an arc's end.
      Prints the arcs found and the largest end mismatch; exit 1 on a
      disagreement.
  polyline CURVES ID D OUT.dxf M
      the trimmed offset computed here (the brute force's kept ranges, each
      end refined by bisection on the distance to C minimised by Brent's
      method) as one DXF LWPOLYLINE per kept range, M + 1 points each, all
      on the exact offset; prints the polyline's construction error (the
      largest distance of the offset between two points from their chord,
      sampled 64 times a chord).
  distance CURVES ID D FILE.dxf
      the two-sided Hausdorff distance between the DXF's LINE entities
      and the trimmed offset computed here, both as dense point sets
      (spacing about 1e-5 of the curve's size, a k-d tree each way):
      within some 1e-5 of the size of the exact set distance.  Prints it.
"""
import sys
from math import comb

import numpy as np
from scipy.optimize import minimize_scalar
from scipy.spatial import cKDTree


def read_curve(path, cid):
    pts, on = [], False
    for line in open(path):
        w = line.split()
        if w[:2] == ["curve", cid]:
            on = True
        elif on and w and w[0] == "end":
            break
        elif on and w and w[0] == "point":
            pts.append((float(w[1]), float(w[2]), 1.0))
        elif on and w and w[0] == "hpoint":
            pts.append((float(w[1]), float(w[2]), float(w[3])))
    if not pts:
        sys.exit("trim_brute.py: no curve %s in %s" % (cid, path))
    return np.array(pts)


def bern(n, t):
    t = np.atleast_1d(np.asarray(t, dtype=float))
    return np.stack([comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)], 1)


def curve(H, t):
    """C(t) and C'(t), rows per t."""
    n = len(H) - 1
    X = bern(n, t) @ H
    dX = bern(n - 1, t) @ (n * np.diff(H, axis=0))
    w, dw = X[:, 2:3], dX[:, 2:3]
    return X[:, :2] / w, (dX[:, :2] * w - X[:, :2] * dw) / w**2


def offset(H, d, t):
    C, V = curve(H, t)
    L = np.hypot(V[:, 0], V[:, 1])
    return C + d * np.stack([-V[:, 1] / L, V[:, 0] / L], 1)


def curve2(H, t):
    """C, C', C'' at the parameters t (rows)."""
    n = len(H) - 1
    X = bern(n, t) @ H
    dX = bern(n - 1, t) @ (n * np.diff(H, axis=0))
    ddX = bern(n - 2, t) @ (n * (n - 1) * np.diff(H, 2, axis=0)) if n >= 2 else 0 * X
    w, dw, ddw = X[:, 2:3], dX[:, 2:3], ddX[:, 2:3]
    C = X[:, :2] / w
    D1 = (dX[:, :2] - C * dw) / w
    return C, D1, (ddX[:, :2] - 2 * D1 * dw - C * ddw) / w


class Dist:
    """Distance to the base: the k nearest of NC samples of C (a k-d tree),
    each refined by Newton's method on (C(t) - P).C'(t) = 0 within a sample
    spacing of it; the end points too."""

    def __init__(self, H, N, NC=2001):
        self.H, self.t = H, np.linspace(0, 1, N)
        self.tc = np.linspace(0, 1, NC)
        self.Cc, _ = curve(H, self.tc)
        self.tree = cKDTree(self.Cc)

    def poly(self, P, k=8):
        _, idx = self.tree.query(P, k=k)
        h = self.tc[1] - self.tc[0]
        best = np.minimum(np.hypot(*(P - self.Cc[0]).T), np.hypot(*(P - self.Cc[-1]).T))
        for j in range(k):
            t0 = self.tc[idx[:, j]]
            lo, hi, t = np.maximum(t0 - h, 0), np.minimum(t0 + h, 1), t0.copy()
            for _ in range(12):
                C, D1, D2 = curve2(self.H, t)
                R = C - P
                g, dg = (R * D1).sum(1), (D1 * D1).sum(1) + (R * D2).sum(1)
                t = np.clip(t - g / np.where(dg > 0, dg, np.inf), lo, hi)
            best = np.minimum(best, np.hypot(*(P - curve(self.H, t)[0]).T))
        return best

    def exact(self, p):
        _, idx = self.tree.query(p, k=16)
        h = self.tc[1] - self.tc[0]
        best = min(np.hypot(*(p - self.Cc[0])), np.hypot(*(p - self.Cc[-1])))
        for i in idx:
            lo, hi = max(self.tc[i] - h, 0.0), min(self.tc[i] + h, 1.0)
            r = minimize_scalar(lambda u: np.hypot(*(p - curve(self.H, u)[0][0])), bounds=(lo, hi),
                                method="bounded", options={"xatol": 1e-15})
            best = min(best, r.fun)
        return best


def kept_ranges(H, d, N):
    D = Dist(H, N)
    t = D.t
    kept = D.poly(offset(H, d, t)) >= abs(d) * (1 - 1e-9)
    edges = np.nonzero(np.diff(kept.astype(int)))[0]
    starts = ([0] if kept[0] else []) + [i + 1 for i in edges if not kept[i]]
    ends = [i for i in edges if kept[i]] + ([N - 1] if kept[-1] else [])
    return D, t, kept, list(zip(starts, ends))


def check(path, cid, d, dump, N=200001):
    H = read_curve(path, cid)
    _, t, kept, ranges = kept_ranges(H, d, N)
    arcs = [tuple(map(float, l.split(",")[2:4])) for l in open(dump) if l.startswith("arc,")]
    print("brute force kept:", [(t[a], t[b]) for a, b in ranges], "offbench:", arcs)
    inside = np.zeros(N, bool)
    for t0, t1 in arcs:
        inside |= (t >= t0) & (t <= t1)
    h = 2.0 / (N - 1)
    near_end = np.zeros(N, bool)
    for t0, t1 in arcs:
        near_end |= (np.abs(t - t0) <= h) | (np.abs(t - t1) <= h)
    bad = (kept != inside) & ~near_end
    worst = 0.0
    if len(arcs) == len(ranges):
        for (a, b), (t0, t1) in zip(ranges, arcs):
            worst = max(worst, abs(t[a] - t0), abs(t[b] - t1))
    print("disagreeing samples: %d; arcs %d vs %d; largest end mismatch %.3g (spacing %.3g)"
          % (bad.sum(), len(arcs), len(ranges), worst, t[1] - t[0]))
    return 0 if bad.sum() == 0 and len(arcs) == len(ranges) and worst <= h else 1


def refine(D, H, d, a, b):
    """The end of a kept range between parameters a (kept) and b (removed)."""
    for _ in range(60):
        m = 0.5 * (a + b)
        if D.exact(offset(H, d, m)[0]) >= abs(d) - 1e-13:
            a = m
        else:
            b = m
    return a


def polyline(path, cid, d, out, M):
    H = read_curve(path, cid)
    D, t, _, ranges = kept_ranges(H, d, 20001)
    ents, err = [], 0.0
    for a, b in ranges:
        t0 = 0.0 if a == 0 else refine(D, H, d, t[a], t[a - 1])
        t1 = 1.0 if b == len(t) - 1 else refine(D, H, d, t[b], t[b + 1])
        u = np.linspace(t0, t1, M + 1)
        P = offset(H, d, u)
        for i in range(M):
            Q = offset(H, d, np.linspace(u[i], u[i + 1], 65))
            A, AB = P[i], P[i + 1] - P[i]
            s = np.clip(((Q - A) @ AB) / (AB @ AB), 0, 1)
            err = max(err, np.hypot(*(Q - A - s[:, None] * AB).T).max())
        body = "".join("10\n%.17g\n20\n%.17g\n" % (x, y) for x, y in P)
        ents.append("0\nLWPOLYLINE\n8\n0\n90\n%d\n70\n0\n%s" % (M + 1, body))
    with open(out, "w") as f:
        f.write("0\nSECTION\n2\nENTITIES\n%s0\nENDSEC\n0\nEOF\n" % "".join(ents))
    print("%.17g" % err)
    return 0


def dxf_lines(path):
    """The LINE entities of a DXF (group codes 10, 20, 11, 21) as an (n, 4) array."""
    w = [x.strip() for x in open(path)]
    out, i = [], 0
    while i + 1 < len(w):
        if w[i] == "0" and w[i + 1] == "LINE":
            g, i = {}, i + 2
            while i + 1 < len(w) and w[i] != "0":
                g[w[i]] = w[i + 1]
                i += 2
            out.append([float(g["10"]), float(g["20"]), float(g["11"]), float(g["21"])])
        else:
            i += 2
    return np.array(out)


def densify(A, B, h):
    """Points along each segment A[i] -> B[i], at most h apart."""
    pts = []
    for a, b in zip(A, B):
        n = max(1, int(np.ceil(np.hypot(*(b - a)) / h)))
        s = np.linspace(0, 1, n + 1)[:, None]
        pts.append(a + s * (b - a))
    return np.vstack(pts)


def distance(path, cid, d, dxf):
    H = read_curve(path, cid)
    D, t, _, ranges = kept_ranges(H, d, 20001)
    L = dxf_lines(dxf)
    size = np.ptp(np.vstack([L[:, :2], L[:, 2:]]), axis=0).max() + abs(d)
    h = 1e-5 * size
    arcs = []
    for a, b in ranges:
        t0 = 0.0 if a == 0 else refine(D, H, d, t[a], t[a - 1])
        t1 = 1.0 if b == len(t) - 1 else refine(D, H, d, t[b], t[b + 1])
        P = offset(H, d, np.linspace(t0, t1, 20001))
        arcs.append(densify(P[:-1], P[1:], h))
    T = np.vstack(arcs)
    F = densify(L[:, :2], L[:, 2:], h)
    there = cKDTree(T).query(F)[0].max()
    back = cKDTree(F).query(T)[0].max()
    print("%.17g" % max(there, back))
    return 0


if __name__ == "__main__":
    a = sys.argv[1:]
    if a and a[0] == "check" and len(a) in (5, 6):
        sys.exit(check(a[1], a[2], float(a[3]), a[4], *(int(x) for x in a[5:])))
    if a and a[0] == "distance" and len(a) == 5:
        sys.exit(distance(a[1], a[2], float(a[3]), a[4]))
    if a and a[0] == "polyline" and len(a) == 6:
        sys.exit(polyline(a[1], a[2], float(a[3]), a[4], int(a[5])))
    sys.exit("usage: trim_brute.py check CURVES ID D DUMP [N] | polyline CURVES ID D OUT.dxf M | "
             "distance CURVES ID D FILE.dxf")
