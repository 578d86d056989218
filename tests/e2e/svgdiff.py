#!/usr/bin/python3
"""Helper of tests/e2e/e2e_svg_xml.sh (not a test itself): compares the
pieces measure's SVG reader makes of a file (test_svg_read --dump: one line
per piece, "DEG x y w x y w ...") with the curves scripts/svg2curves.py
writes of it (one .curves block per subpath, its segments degree-elevated
to one degree; elevated here the same way, exactly).

Usage: svgdiff.py DUMP FILE.curves [--rel 1e-12]

The pieces must come in the same order and agree to --rel times the
largest coordinate (weights to --rel).  Prints what differs; exits 1.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from svg2curves import elevate  # noqa: E402


def read_dump(path):
    out = []
    with open(path) as f:
        for line in f:
            v = line.split()
            deg = int(v[0])
            out.append([tuple(float(x) for x in v[1 + 3 * i:4 + 3 * i]) for i in range(deg + 1)])
    return out


def read_curves(path):
    """[(id, degree, [segment points])] of a .curves file as svg2curves writes it."""
    curves, cur = [], None
    with open(path) as f:
        for line in f:
            v = line.split()
            if not v or v[0].startswith("#"):
                continue
            if v[0] == "curve":
                cur = {"id": v[1], "pts": []}
            elif v[0] in ("bezier", "bspline"):
                cur["deg"] = int(v[1])
            elif v[0] == "point":
                cur["pts"].append((float(v[1]), float(v[2]), float(v[3]) if len(v) > 3 else 1.0))
            elif v[0] == "end":
                d, p = cur["deg"], cur["pts"]
                segs = [p[k:k + d + 1] for k in range(0, len(p) - 1, d)]
                curves.append((cur["id"], d, segs))
    return curves


def main(argv):
    rel = float(argv[argv.index("--rel") + 1]) if "--rel" in argv else 1e-12
    c_pieces, curves = read_dump(argv[0]), read_curves(argv[1])
    py = [(cid, k, d, s) for cid, d, segs in curves for k, s in enumerate(segs)]
    scale = max([abs(v) for p in c_pieces for q in p for v in q[:2]] + [1.0])
    bad = []
    if len(py) != len(c_pieces):
        bad.append(f"{len(c_pieces)} pieces from the C reader, {len(py)} segments from svg2curves.py")
    for i, (cid, k, d, s) in enumerate(py[:len(c_pieces)]):
        c = elevate(c_pieces[i], d) if len(c_pieces[i]) - 1 <= d else None
        if c is None or len(c) != len(s):
            bad.append(f"piece {i} ({cid} segment {k}): degree {len(c_pieces[i]) - 1} in C, {d} in svg2curves")
            continue
        dev = max(max(abs(a[q] - b[q]) for q in (0, 1)) / scale + abs(a[2] - b[2]) for a, b in zip(c, s))
        if not dev <= rel:
            bad.append(f"piece {i} ({cid} segment {k}): differs by {dev:.3g} (relative): C {c}, svg2curves {s}")
    for b in bad[:8]:
        print(b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
