#!/usr/bin/python3
"""fit_svg.py - three of offbench's methods on your own drawing, plotted
(docs/cad-example.md).

Usage: examples/fit_svg.py DRAWING.svg --d D [--tol T] [--methods A,B,C]
                           [--curve ID,...] [--out FILE] [--offbench PATH]
                           [--keep DIR]

1. scripts/svg2curves.py turns the drawing's paths into a .curves file, one
   curve per subpath, each with the offset D (d > 0 on the left of the
   direction the path is drawn in);
2. `offbench run --curves FILE --methods A,B,C --tols T --export DIR` fits
   every method to every curve's offset and exports the approximations;
3. one panel per method: the drawing's curves (grey) and the method's
   offsets (the pieces in alternating colours, their ends as dots), titled
   with the control points and the largest error measured (hausdorff).

It drives the command line only, so it needs no Python binding of the
library.  Writes FILE (default fit_svg.png; .svg and .pdf too, by the
extension) with matplotlib's Agg backend, prints one line per method and
exits 0; 2 with a message when a step fails.  Defaults: --tol 1e-2,
--methods tiller,bspline-lsq,sisl (all three take rational curves, the
arcs of a drawing, which some methods skip: ahn does), every curve,
./offbench of this checkout.  --keep DIR keeps the .curves file, the run
and the export there.
Needs /usr/bin/python3 with matplotlib and numpy (Debian:
python3-matplotlib); svg2curves.py needs only the standard library.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROG = "fit_svg.py"


def die(msg):
    print(f"{PROG}: {msg}", file=sys.stderr)
    sys.exit(2)


try:
    import matplotlib
    import numpy as np
except ImportError as e:
    die(f"{e.name} is not installed for {sys.executable}: on Debian, apt-get install "
        f"python3-matplotlib and run this with /usr/bin/python3")
matplotlib.use("Agg")   # files only, no window: works without a display
import matplotlib.pyplot as plt  # noqa: E402

matplotlib.rcParams["svg.hashsalt"] = "offbench"   # the same drawing gives the same SVG
matplotlib.rcParams["svg.fonttype"] = "none"


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        die(f"{os.path.basename(cmd[1] if cmd[0].endswith('python3') else cmd[0])}: exit {p.returncode}: "
            f"{p.stderr.strip()[-800:]}")
    return p


# ------------------------------------------------------------ curves

def read_curves(path):
    """{id: (degree, knots or None, homogeneous control points)} of a
    .curves file as svg2curves.py writes it (docs/curves.md)"""
    out, cur = {}, None
    with open(path, encoding="utf-8") as f:
        for line in f:
            w = line.split("#")[0].split()
            if not w:
                continue
            if w[0] == "curve":
                cur = out[w[1]] = {"deg": 0, "knots": None, "h": []}
            elif w[0] in ("bezier", "bspline"):
                cur["deg"] = int(w[1])
            elif w[0] == "knots":
                cur["knots"] = (cur["knots"] or []) + [float(x) for x in w[1:]]
            elif w[0] in ("point", "hpoint"):
                x, y, wt = (float(v) for v in (w[1:] + ["1"])[:3])
                cur["h"].append((x, y, wt) if w[0] == "hpoint" else (x * wt, y * wt, wt))
    return out


def bspline_points(c, n=400):
    """points of a curve (a Bézier curve is the B-spline of its clamped
    knots) by de Boor's algorithm on the homogeneous control points"""
    p, h = c["deg"], np.array(c["h"])
    U = c["knots"] or [0.0] * (p + 1) + [1.0] * (p + 1)
    pts = []
    for t in np.linspace(U[p], U[len(h)], n):
        k = next(i for i in range(len(h) - 1, p - 1, -1) if U[i] <= t)   # the span of t
        d = [h[j].copy() for j in range(k - p, k + 1)]
        for r in range(1, p + 1):
            for j in range(p, r - 1, -1):
                i = j + k - p
                a = (t - U[i]) / (U[i + p + 1 - r] - U[i])
                d[j] = (1 - a) * d[j - 1] + a * d[j]
        pts.append(d[p][:2] / d[p][2])
    return np.array(pts)


def bezier_points(hom, n=64):
    """points of one exported Bézier piece (homogeneous control points)"""
    h = np.array(hom, dtype=float)
    t = np.linspace(0.0, 1.0, n)[:, None]
    b = [h[None, i] for i in range(len(h))]
    while len(b) > 1:   # de Casteljau, all parameters at once
        b = [(1 - t) * b[i] + t * b[i + 1] for i in range(len(b) - 1)]
    return b[0][:, :2] / b[0][:, 2:]


# ------------------------------------------------------------ main

def main(argv):
    ap = argparse.ArgumentParser(prog=PROG, description="three offbench methods on an SVG drawing, plotted")
    ap.add_argument("svg")
    ap.add_argument("--d", required=True, help="the offset distance (d > 0: left of the drawing direction)")
    ap.add_argument("--tol", default="1e-2")
    ap.add_argument("--methods", default="tiller,bspline-lsq,sisl")
    ap.add_argument("--curve", help="only these curve ids (as svg2curves.py names them)")
    ap.add_argument("--out", default="fit_svg.png")
    ap.add_argument("--offbench", default=os.path.join(ROOT, "offbench"))
    ap.add_argument("--keep", help="keep the .curves file, the run and the export in this directory")
    a = ap.parse_args(argv[1:])
    methods = [m for m in a.methods.split(",") if m]
    if not os.access(a.offbench, os.X_OK):
        die(f"{a.offbench}: no program (build it: make)")
    work = a.keep or tempfile.mkdtemp(prefix="fit_svg.")
    os.makedirs(work, exist_ok=True)
    try:
        curves = os.path.join(work, "drawing.curves")
        py = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
        conv = run([py, os.path.join(ROOT, "scripts", "svg2curves.py"), a.svg, "--d", a.d, "--out", curves])
        for line in conv.stderr.splitlines():   # what the drawing lost on the way: the user's to know
            print(line, file=sys.stderr)
        cmd = [a.offbench, "run", "--curves", curves, "--methods", ",".join(methods), "--tols", a.tol,
               "--out", os.path.join(work, "run"), "--export", os.path.join(work, "export"), "--force"]
        if a.curve:
            cmd += ["--curve", a.curve]
        run(cmd)
        base = read_curves(curves)
        with open(os.path.join(work, "export", "index.csv"), newline="", encoding="utf-8") as f:
            index = list(csv.DictReader(f))
        fig, axes = plt.subplots(1, len(methods), figsize=(4.2 * len(methods), 4.4), squeeze=False)
        for ax, m in zip(axes[0], methods):
            jobs = [r for r in index if r["method"] == m]
            for cid in dict.fromkeys(r["curve"] for r in jobs):
                xy = bspline_points(base[cid])
                ax.plot(xy[:, 0], xy[:, 1], color="0.6", lw=1.0)
            ctrl, err, bad = 0, 0.0, []
            for r in jobs:
                if not r["stem"]:   # fail, skip, timeout: no approximation
                    bad.append(f"{r['curve']}: {r['status']}")
                    continue
                with open(os.path.join(work, "export", r["stem"] + ".json"), encoding="utf-8") as f:
                    job = json.load(f)
                ctrl += job["ctrl_points"]
                err = max(err, job["max_err"])
                if r["status"] != "ok":
                    bad.append(f"{r['curve']}: {r['status']}")
                for k, piece in enumerate(job["pieces"]):
                    xy = bezier_points(piece["homogeneous"])
                    ax.plot(xy[:, 0], xy[:, 1], color=("C0", "C1")[k % 2], lw=1.4)
                    ax.plot(xy[[0, -1], 0], xy[[0, -1], 1], ".", color="k", ms=3)
            ax.set_title(f"{m}: {ctrl} control points\nmax error {err:.2g} (tol {a.tol})", fontsize=10)
            if bad:
                ax.text(0.02, 0.02, "; ".join(bad), transform=ax.transAxes, fontsize=7, color="C3")
            ax.set_aspect("equal", adjustable="datalim")
            ax.tick_params(labelsize=7)
            print(f"{PROG}: {m}: {len(jobs)} curves, {ctrl} control points, max error {err:.3g}"
                  + (f" ({'; '.join(bad)})" if bad else ""))
        fig.suptitle(f"{os.path.basename(a.svg)}: offsets at d = {a.d}", fontsize=11)
        fig.tight_layout()
        fig.savefig(a.out)
        print(f"{PROG}: wrote {a.out}")
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
