"""trim_brute.py - an independent brute force of the trimmed offset, for
tests/e2e/e2e_measure_trimmed.sh and e2e_occt_trimmed.sh (issue 50); it
shares no code with offbench (host/measure/trim.c).

The base: a curve of a .curves file, `bezier DEGREE` or `bspline DEGREE`
with its `knots` (`point X Y` or `hpoint WX WY W` lines), evaluated span
by span (each non-empty knot span, offbench's segment of the same index,
on its own local parameter s in [0, 1]) by scipy's BSpline on the
homogeneous points, derivatives by the quotient rule.  The offset
O = C + d N, N the left unit normal (-y', x') / |C'|.  Where two spans
meet (the wrap of a closed base too) the set of points at distance |d|
from C may hold an arc of the circle of radius |d| about the joint (a
corner's, on its convex side): every joint's circle is sampled, and its
points on the d side of the joint (Q with (Q - P).d (N1 + N2) > 0, N1
and N2 the unit normals on either side of the joint P: the arc about
the normals' mean direction, not the one of the offset to the other
side; where the curve reverses, N1 + N2 = 0, the half circle ahead of
the tangent before the joint) kept the same way as O's, whatever the
joint.

  check CURVES ID D DUMP [N]
      samples O at N (default 200001 over the spans, 50001 a span at
      least) parameters a span and keeps those
      whose distance to C (the 8 nearest of 2001 samples a span of C by a
      k-d tree, each refined by Newton's method on (C(s) - P).C'(s) = 0
      within a spacing of it, and the spans' end points) is >= |d| (1 -
      1e-9); every kept sample must lie in one of DUMP's arcs of its span
      (`measure --trim-dump`), every removed one outside them, but within
      2 / N of an arc's end.  The circle about each joint sampled at 20000
      angles the same way against DUMP's corner arcs of that joint (but
      within 2 spacings of an arc's end or of the directions of d N on
      either side of the joint, where the circle touches O), as many kept
      ranges as corner arcs.  Prints the arcs found and the largest end
      mismatch; exit 1 on a disagreement.
  polyline CURVES ID D OUT.dxf M
      the trimmed offset computed here (the brute force's kept ranges, each
      end refined by bisection on the distance to C minimised by Brent's
      method; a corner arc's end within 2 spacings of a direction of d N
      at the joint is that direction) as one DXF LWPOLYLINE per kept range,
      M + 1 points each, all on the exact offset or circle; prints the
      polyline's construction error (the largest distance of the offset
      between two points from their chord, sampled 64 times a chord).
  distance CURVES ID D FILE.dxf
      the two-sided Hausdorff distance between the DXF's LINE entities
      and the trimmed offset computed here, both as dense point sets
      (spacing about 1e-5 of the curve's size, a k-d tree each way):
      within some 1e-5 of the size of the exact set distance.  Prints it.
"""
import sys

import numpy as np
from scipy.interpolate import BSpline
from scipy.optimize import minimize_scalar
from scipy.spatial import cKDTree


class Span:
    """One non-empty knot span [a, b] of a (rational) B-spline: the local
    B-spline of its p + 1 coefficients, evaluated at s in [0, 1]."""

    def __init__(self, knots, H, p, i):
        self.a, self.b = knots[i], knots[i + 1]
        self.f = BSpline(np.array(knots[i - p:i + p + 2]), np.array(H[i - p:i + 1]), p, extrapolate=True)
        self.df = [self.f.derivative(k) if k <= p else None for k in (1, 2)]

    def eval(self, s, nder=1):
        """C and its derivatives in s up to nder (<= 2), rows per s."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        u, L = self.a + (self.b - self.a) * s, self.b - self.a
        X = self.f(u)
        dX = self.df[0](u) * L if self.df[0] is not None else 0 * X
        ddX = self.df[1](u) * L * L if self.df[1] is not None else 0 * X
        w, dw, ddw = X[:, 2:3], dX[:, 2:3], ddX[:, 2:3]
        C = X[:, :2] / w
        D1 = (dX[:, :2] - C * dw) / w
        if nder == 1:
            return C, D1
        return C, D1, (ddX[:, :2] - 2 * D1 * dw - C * ddw) / w


def read_curve(path, cid):
    """The spans of curve cid of a .curves file, in order."""
    pts, on, deg, knots, kind = [], False, None, None, None
    for line in open(path):
        w = line.split("#")[0].split()
        if w[:2] == ["curve", cid]:
            on = True
        elif on and w and w[0] == "end":
            break
        elif on and w and w[0] in ("bezier", "bspline"):
            kind, deg = w[0], int(w[1])
        elif on and w and w[0] == "knots":
            knots = [float(x) for x in w[1:]]
        elif on and w and w[0] == "point":
            pts.append((float(w[1]), float(w[2]), 1.0))
        elif on and w and w[0] == "hpoint":
            pts.append((float(w[1]), float(w[2]), float(w[3])))
    if not pts or deg is None:
        sys.exit("trim_brute.py: no curve %s in %s" % (cid, path))
    if kind == "bezier":
        knots = [0.0] * len(pts) + [1.0] * len(pts)
    n = len(pts)
    return [Span(knots, pts, deg, i) for i in range(deg, n) if knots[i] < knots[i + 1]]


def unit_normal(V):
    L = np.hypot(V[:, 0], V[:, 1])
    return np.stack([-V[:, 1] / L, V[:, 0] / L], 1)


def offset(sp, d, s):
    C, V = sp.eval(s)
    return C + d * unit_normal(V)


class Base:
    """The spans, their ends, the joints (between spans, and the wrap
    when the curve is closed: each the index of the span it starts)."""

    def __init__(self, spans):
        self.spans = spans
        self.start = np.array([sp.eval(0.0)[0][0] for sp in spans])
        self.end = np.array([sp.eval(1.0)[0][0] for sp in spans])
        size = np.ptp(np.vstack([self.start, self.end]), axis=0).max()
        closed = np.hypot(*(self.end[-1] - self.start[0])) <= 1e-12 * max(size, 1e-300)
        self.joints = ([0] if closed and len(spans) > 1 else []) + list(range(1, len(spans)))
        if closed and len(spans) == 1:
            self.joints = [0]

    def joint_normals(self, j, d):
        """d N at the end of the span before joint j and at the start of span j."""
        a = self.spans[j - 1 if j > 0 else len(self.spans) - 1]
        return unit_normal(a.eval(1.0)[1])[0] * d, unit_normal(self.spans[j].eval(0.0)[1])[0] * d

    def joint_dirs(self, j, d):
        """The angles of d N on either side of joint j."""
        na, nb = self.joint_normals(j, d)
        return np.arctan2(na[1], na[0]), np.arctan2(nb[1], nb[0])


class Dist:
    """Distance to the base: the k nearest of NC samples a span of C (a
    k-d tree), each refined by Newton's method on (C(s) - P).C'(s) = 0
    within a sample spacing of it; the spans' end points too."""

    def __init__(self, base, NC=2001):
        self.base, self.tc = base, np.linspace(0, 1, NC)
        self.Cc = np.vstack([sp.eval(self.tc)[0] for sp in base.spans])
        self.sid = np.repeat(np.arange(len(base.spans)), NC)
        self.ts = np.tile(self.tc, len(base.spans))
        self.ends = np.vstack([base.start, base.end])
        self.tree = cKDTree(self.Cc)

    def poly(self, P, k=8):
        _, idx = self.tree.query(P, k=k)
        h = self.tc[1] - self.tc[0]
        best = np.full(len(P), np.inf)
        for E in self.ends:
            best = np.minimum(best, np.hypot(*(P - E).T))
        for j in range(k):
            sid, t0 = self.sid[idx[:, j]], self.ts[idx[:, j]]
            for m, sp in enumerate(self.base.spans):
                on = sid == m
                if not on.any():
                    continue
                Q, t = P[on], t0[on].copy()
                lo, hi = np.maximum(t - h, 0), np.minimum(t + h, 1)
                for _ in range(12):
                    C, D1, D2 = sp.eval(t, 2)
                    R = C - Q
                    g, dg = (R * D1).sum(1), (D1 * D1).sum(1) + (R * D2).sum(1)
                    t = np.clip(t - g / np.where(dg > 0, dg, np.inf), lo, hi)
                best[on] = np.minimum(best[on], np.hypot(*(Q - sp.eval(t)[0]).T))
        return best

    def exact(self, p):
        _, idx = self.tree.query(p, k=16)
        h = self.tc[1] - self.tc[0]
        best = min(np.hypot(*(p - E)) for E in self.ends)
        for i in idx:
            sp = self.base.spans[self.sid[i]]
            lo, hi = max(self.ts[i] - h, 0.0), min(self.ts[i] + h, 1.0)
            r = minimize_scalar(lambda u: np.hypot(*(p - sp.eval(u)[0][0])), bounds=(lo, hi),
                                method="bounded", options={"xatol": 1e-15})
            best = min(best, r.fun)
        return best


def ranges_of(kept):
    """The runs of True in kept, as (first, last) index pairs."""
    edges = np.nonzero(np.diff(kept.astype(int)))[0]
    starts = ([0] if kept[0] else []) + [i + 1 for i in edges if not kept[i]]
    ends = [i for i in edges if kept[i]] + ([len(kept) - 1] if kept[-1] else [])
    return list(zip(starts, ends))


def kept_ranges(base, d, N):
    """Per span: the parameters, the kept mask and its runs."""
    D = Dist(base)
    t = np.linspace(0, 1, N)
    out = []
    for sp in base.spans:
        kept = D.poly(offset(sp, d, t)) >= abs(d) * (1 - 1e-9)
        out.append((kept, ranges_of(kept)))
    return D, t, out


def circle_kept(base, D, d, j, NA):
    """The circle of radius |d| about joint j at NA angles from -pi: the
    angles, the kept mask, and its cyclic runs as (a0, a1) angle pairs
    (a1 >= a0, a1 - a0 < 2 pi)."""
    P = base.start[j]
    A = -np.pi + 2 * np.pi * np.arange(NA) / NA
    U = np.stack([np.cos(A), np.sin(A)], 1)
    na, nb = base.joint_normals(j, d)
    v = na + nb
    if np.hypot(*v) <= 1e-6 * abs(d):  # a reversal: the half circle round the front, along T before the joint
        v = np.array([na[1], -na[0]]) * np.sign(d)
    side = U @ v > 0
    kept = side & (D.poly(P + abs(d) * U) >= abs(d) * (1 - 1e-9))
    if kept.all():
        return A, kept, [(-np.pi, np.pi)]
    r0 = int(np.argmin(kept))  # a removed sample: the runs start after it
    order = np.roll(np.arange(NA), -r0)
    runs = [(A[order[a]], A[order[a]] + (b - a) * 2 * np.pi / NA) for a, b in ranges_of(kept[order])]
    return A, kept, runs


def angle_in(x, a0, a1, tol=0.0):
    """1 where angle x lies in the arc from a0 to a1 (either way round), to tol."""
    lo, hi = min(a0, a1), max(a0, a1)
    return np.mod(x - lo + tol, 2 * np.pi) <= hi - lo + 2 * tol


def angle_gap(x, y):
    return abs(np.mod(x - y + np.pi, 2 * np.pi) - np.pi)


def check(path, cid, d, dump, N=None):
    base = Base(read_curve(path, cid))
    N = N or max(50001, 200000 // len(base.spans) + 1)
    D, t, per = kept_ranges(base, d, N)
    rows = [l.split(",") for l in open(dump)]
    arcs = [(int(r[1]), float(r[2]), float(r[3])) for r in rows if r[0] == "arc"]
    corners = [(int(r[1]), float(r[2]), float(r[3])) for r in rows if r[0] == "corner"]
    h = 2.0 / (N - 1)
    bad, worst, nb, no = 0, 0.0, 0, 0
    for m, (kept, ranges) in enumerate(per):
        mine = [(t0, t1) for sg, t0, t1 in arcs if sg == m]
        inside, near_end = np.zeros(N, bool), np.zeros(N, bool)
        for t0, t1 in mine:
            inside |= (t >= t0) & (t <= t1)
            near_end |= (np.abs(t - t0) <= h) | (np.abs(t - t1) <= h)
        bad += ((kept != inside) & ~near_end).sum()
        nb, no = nb + len(ranges), no + len(mine)
        if len(mine) == len(ranges):
            for (a, b), (t0, t1) in zip(ranges, mine):
                worst = max(worst, abs(t[a] - t0), abs(t[b] - t1))
        print("span %d: brute force kept:" % m, [(t[a], t[b]) for a, b in ranges], "offbench:", mine)
    NA, cbad, cworst = 20000, 0, 0.0
    ha = 2 * 2 * np.pi / NA
    for j in base.joints:
        A, kept, runs = circle_kept(base, D, d, j, NA)
        dirs = base.joint_dirs(j, d)
        runs = [(a0, a1) for a0, a1 in runs if not (a1 - a0 <= ha and min(angle_gap(a0, x) for x in dirs) <= ha)]
        mine = [(a0, a1) for sg, a0, a1 in corners if sg == j]
        inside, near = np.zeros(NA, bool), np.zeros(NA, bool)
        for a0, a1 in mine:
            inside |= angle_in(A, a0, a1)
            near |= (angle_gap(A, a0) <= ha) | (angle_gap(A, a1) <= ha)
        for x in dirs:
            near |= angle_gap(A, x) <= ha
        cbad += ((kept != inside) & ~near).sum()
        nb, no = nb + len(runs), no + len(mine)
        if len(runs) == len(mine):
            for a0, a1 in mine:  # each corner arc's ends: the nearest run ends
                e0 = min(angle_gap(min(a0, a1), r0) for r0, _ in runs)
                e1 = min(angle_gap(max(a0, a1), r1) for _, r1 in runs)
                cworst = max(cworst, e0, e1)
        print("joint %d: brute force kept angles:" % j, runs, "offbench corners:", mine)
    print("disagreeing samples: %d on O, %d on the joints' circles; arcs %d vs %d; largest end mismatch %.3g "
          "(spacing %.3g), of a corner arc %.3g rad (spacing %.3g)"
          % (bad, cbad, no, nb, worst, t[1] - t[0], cworst, 2 * np.pi / NA))
    return 0 if bad == 0 and cbad == 0 and no == nb and worst <= h and cworst <= ha else 1


def refine(f, a, b):
    """Between a (kept: f(a) true) and b (removed), the last kept point."""
    for _ in range(60):
        m = 0.5 * (a + b)
        if f(m):
            a = m
        else:
            b = m
    return a


def trimmed_parts(base, d, N=20001, NA=20000):
    """The trimmed offset computed here: (kind, span or joint, start,
    end), kind "arc" (span parameters) or "corner" (angles, start to end
    counter-clockwise), each end refined."""
    D, t, per = kept_ranges(base, d, N)
    parts = []
    for m, (kept, ranges) in enumerate(per):
        sp = base.spans[m]
        on = lambda s: D.exact(offset(sp, d, s)[0]) >= abs(d) - 1e-13
        for a, b in ranges:
            t0 = 0.0 if a == 0 else refine(on, t[a], t[a - 1])
            t1 = 1.0 if b == len(t) - 1 else refine(on, t[b], t[b + 1])
            parts.append(("arc", m, t0, t1))
    ha = 2 * 2 * np.pi / NA
    for j in base.joints:
        P, r = base.start[j], abs(d)
        on = lambda a: D.exact(P + r * np.array([np.cos(a), np.sin(a)])) >= r - 1e-13
        _, _, runs = circle_kept(base, D, d, j, NA)
        dirs = base.joint_dirs(j, d)
        for a0, a1 in runs:
            if a1 - a0 <= ha:
                continue  # a touch where O meets the circle (a smooth joint)
            ends = []
            for a, out in ((a0, a0 - 2 * np.pi / NA), (a1, a1 + 2 * np.pi / NA)):
                x = [x for x in dirs if angle_gap(a, x) <= ha]
                ends.append(a + np.mod(x[0] - a + np.pi, 2 * np.pi) - np.pi if x else refine(on, a, out))
            parts.append(("corner", j, ends[0], ends[1]))
    return D, parts


def part_points(base, d, part, u):
    kind, m, a, b = part
    if kind == "arc":
        return offset(base.spans[m], d, a + (b - a) * u)
    x = a + (b - a) * u
    return base.start[m] + abs(d) * np.stack([np.cos(x), np.sin(x)], 1)


def polyline(path, cid, d, out, M):
    base = Base(read_curve(path, cid))
    _, parts = trimmed_parts(base, d)
    ents, err = [], 0.0
    for part in parts:
        u = np.linspace(0, 1, M + 1)
        P = part_points(base, d, part, u)
        for i in range(M):
            Q = part_points(base, d, part, np.linspace(u[i], u[i + 1], 65))
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
    base = Base(read_curve(path, cid))
    _, parts = trimmed_parts(base, d)
    L = dxf_lines(dxf)
    size = np.ptp(np.vstack([L[:, :2], L[:, 2:]]), axis=0).max() + abs(d)
    h = 1e-5 * size
    T = []
    for part in parts:
        P = part_points(base, d, part, np.linspace(0, 1, 20001))
        T.append(densify(P[:-1], P[1:], h))
    T = np.vstack(T)
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
