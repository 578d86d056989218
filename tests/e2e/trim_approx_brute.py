"""trim_approx_brute.py - an independent brute force of `run --trimmed`'s
numbers (issue 50), for tests/e2e/e2e_run_trimmed.sh; it shares no code
with offbench (host/measure/trim_approx.c, host/run/trimmed.c).

  CURVES ID D EXPORT.curves MAX_ERR
      EXPORT.curves: one job's approximation as `run --export` writes it
      (one `curve` per piece, `hpoint` lines, its base range in the source
      line).  The pieces, in the base's order, become one dense polyline
      (4001 points a piece, evaluated here in Bernstein form).  It is cut
      where two of its chords cross (chords that share an end excepted),
      where it crosses a dense polyline of the exact opposite offset
      C - dN, and where it crosses the circles of radius |d| about C's end
      points; every arc between two cuts is removed when its middle point
      is nearer to C than |d| - margin, margin = 2 MAX_ERR + 1e-9 size (the
      rule docs/export-measure.md states).  Prints the two-sided distance
      between the kept arcs and the trimmed offset of trim_brute.py (both
      as point sets, spacing 2e-5 of the size) and the number of removed
      regions (runs of removed arcs).
The base: trim_brute.py's reader (B-splines span by span); its trimmed
offset: trim_brute.py's (corners included).  The base's corners are not
filled here: the e2e cases have none.
"""
import sys

import numpy as np
from scipy.spatial import cKDTree

from math import comb

from trim_brute import Base, densify, offset, part_points, read_curve, trimmed_parts


def bern(n, t):
    t = np.atleast_1d(np.asarray(t, dtype=float))
    return np.stack([comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)], 1)


def read_pieces(path):
    """[(key, H)] of the export, key = (segment, base start)."""
    out, H, key = [], [], None
    for line in open(path):
        w = line.split()
        if w[:1] == ["source"] and "segment" in w:
            i = w.index("segment")
            seg, a, b, t0 = int(w[i + 1]), float(w[i + 3]), float(w[i + 4]), float(w[w.index("fit") + 1])
            key = (seg, a + (b - a) * t0)
        elif w[:1] == ["hpoint"]:
            H.append([float(x) for x in w[1:4]])
        elif w[:1] == ["end"] and H:
            out.append((key, np.array(H)))
            H, key = [], None
    out.sort(key=lambda p: p[0])
    return [h for _, h in out]


def piece_points(H, n):
    X = bern(len(H) - 1, np.linspace(0, 1, n)) @ H
    return X[:, :2] / X[:, 2:3]


def cells(A0, A1, g):
    """(cell, chord) entries: every grid cell of side g that a chord's box
    meets (chords no longer than g meet at most 4)."""
    lo = np.floor(np.minimum(A0, A1) / g).astype(np.int64)
    hi = np.floor(np.maximum(A0, A1) / g).astype(np.int64)
    ent = []
    for dx in (0, 1):
        for dy in (0, 1):
            ok = (lo[:, 0] + dx <= hi[:, 0]) & (lo[:, 1] + dy <= hi[:, 1])
            key = (lo[ok, 0] + dx) * 1000003 + (lo[ok, 1] + dy)
            ent.append(np.stack([key, np.nonzero(ok)[0]], 1))
    return np.vstack(ent)


def crossings(P, Q, same):
    """Chord crossings of polylines P and Q, found through a grid: the
    fractional vertex indices (into P, and into Q) where they cross; same:
    Q is P (chords that share an end, and each pair twice, excepted)."""
    A0, A1, B0, B1 = P[:-1], P[1:], Q[:-1], Q[1:]
    g = 1.01 * max(np.hypot(*(A1 - A0).T).max(), np.hypot(*(B1 - B0).T).max())
    ea, eb = cells(A0, A1, g), cells(B0, B1, g)
    nb = len(A0)
    E = np.vstack([ea, eb + [0, nb]]) if not same else ea
    E = E[np.lexsort((E[:, 1], E[:, 0]))]
    pairs = []
    for k in range(1, len(E)):
        m = E[k:, 0] == E[:-k, 0]
        if not m.any():
            break
        pairs.append(np.stack([E[:-k, 1][m], E[k:, 1][m]], 1))
    if not pairs:
        return [], []
    I = np.unique(np.vstack(pairs), axis=0)
    if same:
        I = I[I[:, 1] > I[:, 0] + 1]
    else:
        I = I[(I[:, 0] < nb) & (I[:, 1] >= nb)]
        I[:, 1] -= nb
    i, j = I[:, 0], I[:, 1]
    r, s_, q = A1[i] - A0[i], B1[j] - B0[j], B0[j] - A0[i]
    den = r[:, 0] * s_[:, 1] - r[:, 1] * s_[:, 0]
    ok = den != 0
    dd = np.where(ok, den, 1)
    al = (q[:, 0] * s_[:, 1] - q[:, 1] * s_[:, 0]) / dd
    be = (q[:, 0] * r[:, 1] - q[:, 1] * r[:, 0]) / dd
    hit = ok & (al >= 0) & (al <= 1) & (be >= 0) & (be <= 1)
    return list(i[hit] + al[hit]), list(j[hit] + be[hit])


def main(path, cid, d, export, max_err):
    base = Base(read_curve(path, cid))
    pieces = read_pieces(export)
    P = np.vstack([piece_points(h, 4001)[(1 if k else 0):] for k, h in enumerate(pieces)])
    u = np.linspace(0, 1, 20001)
    C = np.vstack([sp.eval(u)[0] for sp in base.spans])
    size = np.hypot(*np.ptp(C, axis=0)) + abs(d)
    margin = 2 * max_err + 1e-9 * size
    # the cuts
    cuts = []
    a, b = crossings(P, P, True)
    cuts += a + b
    O = np.vstack([offset(sp, -d, u) for sp in base.spans])
    cuts += crossings(P, O, False)[0]
    for E in (C[0], C[-1]):  # an open base's ends (the e2e cases are open)
        f = np.hypot(*(P - E).T) ** 2 - d * d
        s = np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)[0]
        cuts += list(s + f[s] / (f[s] - f[s + 1]))
    cuts = sorted(set([0.0] + cuts + [float(len(P) - 1)]))
    tree = cKDTree(C)

    def at(x):
        i = min(int(x), len(P) - 2)
        return P[i] + (x - i) * (P[i + 1] - P[i])

    def base_dist(p):
        # nearest dense sample, then the exact foot on its two chords
        _, i = tree.query(p)
        best = np.inf
        for j in (i - 1, i):
            if 0 <= j < len(C) - 1:
                a, b = C[j], C[j + 1]
                u = np.clip(np.dot(p - a, b - a) / np.dot(b - a, b - a), 0, 1)
                best = min(best, np.hypot(*(p - a - u * (b - a))))
        return best

    kept, removed, last_removed = [], 0, False
    for x0, x1 in zip(cuts[:-1], cuts[1:]):
        if x1 <= x0:
            continue
        gone = base_dist(at(0.5 * (x0 + x1))) < abs(d) - margin
        if gone and not last_removed:
            removed += 1
        last_removed = gone
        if not gone:
            i0, i1 = int(np.ceil(x0)), int(np.floor(x1))
            seg = [at(x0)] + [P[i] for i in range(i0, i1 + 1)] + [at(x1)]
            kept.append(np.array(seg))
    h = 2e-5 * size
    _, parts = trimmed_parts(base, d)
    arcs = []
    for part in parts:
        Q = part_points(base, d, part, np.linspace(0, 1, 20001))
        arcs.append(densify(Q[:-1], Q[1:], h))
    T = np.vstack(arcs)
    F = np.vstack([densify(k[:-1], k[1:], h) for k in kept if len(k) > 1])
    there = cKDTree(T).query(F)[0].max()
    back = cKDTree(F).query(T)[0].max()
    print("%.17g %d" % (max(there, back), removed))
    return 0


if __name__ == "__main__":
    a = sys.argv[1:]
    if len(a) != 5:
        sys.exit("usage: trim_approx_brute.py CURVES ID D EXPORT.curves MAX_ERR")
    sys.exit(main(a[0], a[1], float(a[2]), a[3], float(a[4])))
