#!/usr/bin/python3
"""Helper of tests/e2e/e2e_svg2curves.sh (not a test itself): checks the
geometry of a .curves file written by scripts/svg2curves.py against the SVG
it came from, with its own reader and rational de Boor evaluation of the
.curves text (independent of the converter) and svgelements' own geometry.

Usage: svgcheck.py FILE.svg FILE.curves [--y up|down] [--units user|px] [--tol 1e-9] [--expect CURVE:SPANS,...]

For every curve and every knot span k (one SVG segment or arc piece, named
by the converter's "# span k: SVG segment N (X)" comment) and t in a grid:
  L, Q, C, Z: the B-spline point at k + t equals svgelements' point(t) of
              segment N of the element (parsed with reify=True: svgelements
              applies the transforms itself) within --tol;
  A:          the point, mapped back by the inverse of the element's
              transform, lies on the local ellipse of the arc (svgelements'
              radii and rotation, the centre by the SVG spec: spec_center)
              (p - c = a1 u + a2 v with |hypot(a1, a2) - 1| within --tol)
              and inside its sweep; the first and last arc pieces start and
              end at the arc's ends; every piece spans at most 90 degrees.
Prints one line per curve and the largest deviations; exits 1 on a failure.
"""
import math
import re
import sys

import svgelements as se


def read_curves(path):
    curves, cur = [], None
    for line in open(path, encoding="utf-8"):
        m = re.match(r"\s*# span (\d+): SVG segment (\d+) \((\w)\)", line)
        if m and cur is not None:
            cur["spans"].append((int(m.group(2)), m.group(3)))
        line = line.split("#")[0].split()
        if not line:
            continue
        kw, rest = line[0], line[1:]
        if kw == "curve":
            cur = {"id": rest[0], "spans": [], "pts": [], "knots": [], "source": ""}
        elif kw == "source":
            cur["source"] = " ".join(rest)
        elif kw in ("bezier", "bspline"):
            cur["deg"] = int(rest[0])
        elif kw == "knots":
            cur["knots"] += [float(x) for x in rest]
        elif kw == "point":
            x, y = float(rest[0]), float(rest[1])
            w = float(rest[2]) if len(rest) > 2 else 1.0
            cur["pts"].append((x * w, y * w, w))
        elif kw == "end":
            p, n = cur["deg"], len(cur["pts"])
            if not cur["knots"]:
                cur["knots"] = [0.0] * (p + 1) + [1.0] * (p + 1)
            assert len(cur["knots"]) == n + p + 1, cur["id"]
            curves.append(cur)
            cur = None
    return curves


def deboor(c, k, t):
    """Point of the rational B-spline at u = k + t (0 <= t <= 1), on span k."""
    U, p, P = c["knots"], c["deg"], c["pts"]
    i = max(j for j in range(len(U) - 1) if U[j] <= k and U[j] < U[j + 1])
    u = k + t
    d = [list(P[j + i - p]) for j in range(p + 1)]
    for r in range(1, p + 1):
        for j in range(p, r - 1, -1):
            a = (u - U[j + i - p]) / (U[j + 1 + i - r] - U[j + i - p])
            d[j] = [(1 - a) * d[j - 1][q] + a * d[j][q] for q in range(3)]
    X, Y, W = d[p]
    return X / W, Y / W


def element_segments(doc, eid, transformed):
    for e in doc.elements():
        if isinstance(e, se.Shape) and e.id == eid:
            segs = list(e.segments(transformed=transformed))
            return e, [s for s in segs if not isinstance(s, se.Move)]
    raise SystemExit(f"svgcheck: no element id={eid}")


def spec_center(a):
    """The arc's centre by the SVG 1.1 implementation notes (Appendix F.6.5,
    endpoint to centre), from svgelements' radii, rotation and sweep and the
    arc's ends; radii that just reach (lambda within 1e-12 of 1, as after the
    out-of-range scaling of F.6.6) put the centre at the chord's midpoint."""
    u = (a.prx.x - a.center.x, a.prx.y - a.center.y)
    rx, ry = math.hypot(*u), math.hypot(a.pry.x - a.center.x, a.pry.y - a.center.y)
    phi = math.atan2(u[1], u[0])
    fa, fs = abs(a.sweep) > math.pi, a.sweep > 0
    dx, dy = (a.start.x - a.end.x) / 2, (a.start.y - a.end.y) / 2
    x1 = math.cos(phi) * dx + math.sin(phi) * dy
    y1 = -math.sin(phi) * dx + math.cos(phi) * dy
    lam = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry)
    coef = 0.0
    if lam < 1 - 1e-12:
        coef = math.sqrt((rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1)
                         / (rx * rx * y1 * y1 + ry * ry * x1 * x1))
        coef = coef if fa != fs else -coef
    cx1, cy1 = coef * rx * y1 / ry, -coef * ry * x1 / rx
    return (math.cos(phi) * cx1 - math.sin(phi) * cy1 + (a.start.x + a.end.x) / 2,
            math.sin(phi) * cx1 + math.cos(phi) * cy1 + (a.start.y + a.end.y) / 2)


def main(argv):
    svg, curves_file = argv[0], argv[1]
    opts = dict(zip(argv[2::2], argv[3::2]))
    flip = -1.0 if opts.get("--y", "up") == "up" else 1.0
    tol = float(opts.get("--tol", "1e-9"))
    expect = dict(x.split(":") for x in opts["--expect"].split(",")) if "--expect" in opts else {}
    reified = se.SVG.parse(svg)                # transforms applied by svgelements
    local = se.SVG.parse(svg, reify=False)     # local segments + element transforms
    # --units user: svgelements' px mapped back by the root viewBox transform V
    V = se.Matrix(local.viewbox_transform) if opts.get("--units", "user") == "user" \
        and local.viewbox_transform else se.Matrix()
    Vinv = ~V
    user = lambda q: se.Point(q) * Vinv
    worst_pt = worst_ell = worst_c = 0.0
    failures = 0
    grid = [j / 16 for j in range(17)]
    for c in read_curves(curves_file):
        m = re.search(r'id="([^"]*)"', c["source"])
        eid = m.group(1)
        _, rsegs = element_segments(reified, eid, True)
        le, lsegs = element_segments(local, eid, False)
        inv = ~le.transform
        bad = []
        got = "".join(x for _, x in c["spans"])
        if c["id"] in expect and expect.pop(c["id"]) != got:
            bad.append(f"spans {got}, expected otherwise (--expect)")
        arc_first = {}
        for k, (num, letter) in enumerate(c["spans"]):
            if letter != "A":
                s = rsegs[num - 1]
                for t in grid:
                    q = user(s.point(t))
                    x, y = deboor(c, k, t)
                    e = math.hypot(x - q.x, y - flip * q.y)
                    worst_pt = max(worst_pt, e)
                    if not e <= tol:
                        bad.append(f"span {k} t={t}: {e:.3g} from svgelements' point(t)")
                continue
            a = lsegs[num - 1]
            cx, cy = spec_center(a)
            worst_c = max(worst_c, math.hypot(cx - a.center.x, cy - a.center.y) / math.hypot(
                a.prx.x - a.center.x, a.prx.y - a.center.y))
            u = (a.prx.x - a.center.x, a.prx.y - a.center.y)  # the axes
            v = (a.pry.x - a.center.x, a.pry.y - a.center.y)
            det = u[0] * v[1] - u[1] * v[0]
            ang = []
            for t in grid:
                x, y = deboor(c, k, t)
                p = se.Point(x, flip * y) * V * inv
                # p - c = u a1 + v a2; on the ellipse when a1^2 + a2^2 = 1
                a1 = ((p.x - cx) * v[1] - (p.y - cy) * v[0]) / det
                a2 = (u[0] * (p.y - cy) - u[1] * (p.x - cx)) / det
                e = abs(math.hypot(a1, a2) - 1)
                worst_ell = max(worst_ell, e)
                if not e <= tol:
                    bad.append(f"span {k} (arc) t={t}: off the ellipse by {e:.3g}")
                ang.append(math.atan2(a2, a1))
            # the piece's sweep, unwrapped: monotone, at most 90 degrees, same sign as the arc's
            steps = [math.remainder(b - a0, 2 * math.pi) for a0, b in zip(ang, ang[1:])]
            total = sum(steps)
            if not (all(s * a.sweep > 0 for s in steps) and abs(total) <= math.pi / 2 + 1e-12):
                bad.append(f"span {k} (arc): sweeps {total:.6g} rad, not monotone within 90 degrees")
            arc_first.setdefault(num, []).append((k, total))
        for num, pieces in arc_first.items():
            a = rsegs[num - 1]
            sweep = sum(t for _, t in pieces)
            if not abs(abs(sweep) - abs(lsegs[num - 1].sweep)) <= 1e-9:
                bad.append(f"SVG segment {num}: arc pieces sweep {sweep:.12g}, the arc {lsegs[num - 1].sweep:.12g}")
            for (k, t), end in ((pieces[0], a.start), (pieces[-1], a.end)):
                x, y = deboor(c, k, 0.0 if end is a.start else 1.0)
                q = user(end)
                e = math.hypot(x - q.x, y - flip * q.y)
                worst_pt = max(worst_pt, e)
                if not e <= tol:
                    bad.append(f"SVG segment {num}: arc end off by {e:.3g}")
        print(f"svgcheck: {c['id']}: {len(c['spans'])} spans " + ("ok" if not bad else "FAIL: " + "; ".join(bad[:5])))
        failures += bool(bad)
    print(f"svgcheck: largest distance from svgelements' point(t) {worst_pt:.3g}, "
          f"largest relative distance from the ellipse {worst_ell:.3g} (its centre by the SVG "
          f"spec, {worst_c:.3g} of the radius from svgelements' centre)")
    if expect:
        print(f"svgcheck: FAIL: no curve {', '.join(expect)} (--expect)")
    return 1 if failures or expect else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
