#!/usr/bin/python3
"""occt_table.py - OpenCASCADE's offsets beside offbench's methods, one table
(docs/cad-example.md).

Usage: scripts/occt_table.py [--out DIR] [--offbench PATH] [--occt PATH]
                             [--curves FILE] [--curve ID,...] [--tols T,...]
                             [--methods LIST] [--no-occt | --table-only]

1. occt_offset (examples/occt, `make occt-bin`) approximates each offset of
   each curve at each tolerance in the configurations of CONFIGS below:
   DIR/*.dxf and what OCCT says of each, DIR/occt.csv;
2. `offbench measure` measures every DXF file against the exact offset
   under every metric: DIR/measure.csv;
3. `offbench run` runs the methods on the same curves, offsets and
   tolerances: DIR/offbench.csv (results.csv's columns the table needs;
   not its timings, so that the files change only when a number does);
4. DIR/table.csv (one row per job and method) and DIR/table.md (one row
   per job, OCCT's configurations beside the methods).

--no-occt skips step 1: the DXF files and occt.csv already in DIR are
measured again and the methods run again (no OpenCASCADE needed: how
results/docs/occt is refreshed when offbench changes).  --table-only
rebuilds only step 4 from DIR's CSV files.  Defaults: DIR out/occt,
./offbench, build/occt_offset, datasets/published.curves, the curves
liu2002_ex1 and liu2002_ex2 at their published offsets, 1e-2,1e-3,1e-4,
tiller,ahn,bspline-lsq,sisl (the run's default metric, hausdorff).

OCCT's claim is its MaxError(); it holds when the measured error (the
hausdorff metric, as the methods' max_err) is at most that, plus
ROUNDOFF times the tolerance.  Exit 0; 2
with a message on a failing step.  Python 3 standard library only;
scripts/docs.py renders the table from the committed files with
markdown() below.
"""
import argparse
import csv
import io
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

# OCCT's configurations: (name in the table, continuity, highest degree, most
# segments).  C2 of degree <= 8 is a CAD kernel's usual smooth choice; C1
# cubic is the form of offbench's cubic methods.
CONFIGS = [("occt-c2", "C2", 8, 1000), ("occt-c1", "C1", 3, 1000)]
DEFAULT_METHODS = "tiller,ahn,bspline-lsq,sisl"
# Where OCCT is exact (the offset of a straight run is a line), its MaxError
# and the measured error are both rounding, 1e-14 against 3e-14 on a
# drawing's lines: no claim to judge.  Errors below a millionth of the
# tolerance are taken as that.
ROUNDOFF = 1e-6
OFFBENCH_COLS = ["curve", "d", "method", "metric", "split", "tol", "status", "ctrl_points", "segments",
                 "out_degree", "max_err"]
TABLE_COLS = ["curve", "d", "tol", "method", "source", "status", "ctrl_points", "degree", "max_err",
              "hausdorff_whole", "claimed", "claim_holds", "within_tol", "message"]


class Fail(Exception):
    pass


def read_csv(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        raise Fail(f"cannot read {path}: {e.strerror}")


def write_csv(path, cols, rows):
    with open(path + ".tmp", "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, cols, lineterminator="\n", extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)


def run(cmd, cwd=None):
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise Fail(f"{' '.join(cmd)}: exit {p.returncode}: {p.stderr.strip()[-600:]}")
    return p.stdout


# ------------------------------------------------------------ the steps

def step_occt(a):
    """occt_offset in each configuration; their CSVs as one, DIR/occt.csv"""
    rows, cols = [], None
    for name, cont, deg, segs in CONFIGS:
        part = os.path.join(a.out, f".{name}.csv")
        run([a.occt, "--curves", a.curves, "--curve", a.curve, "--tols", a.tols, "--out", a.out,
             "--method", name, "--continuity", cont, "--max-degree", str(deg), "--max-segments", str(segs),
             "--csv", part])
        got = read_csv(part)
        os.unlink(part)
        cols = cols or list(got[0].keys())
        rows += got
    write_csv(os.path.join(a.out, "occt.csv"), cols, rows)


def step_measure(a, occt):
    """every DXF file against its curve and d, under every metric: one CSV,
    the files named as in DIR (measure runs there)"""
    groups = {}
    for r in occt:
        if r["file"]:
            groups.setdefault((r["curve"], r["d"]), []).append(r["file"])
    curves = os.path.abspath(a.curves)
    out = []
    for (curve, d), files in groups.items():
        cmd = [os.path.abspath(a.offbench), "measure", "--curves", curves, "--curve", curve, "--d", d,
               "--metric", "all"]
        for f in files:
            cmd += ["--approx", f]
        out += list(csv.DictReader(io.StringIO(run(cmd, cwd=a.out))))
    if not out:
        raise Fail(f"{a.out}/occt.csv: no approximation to measure")
    write_csv(os.path.join(a.out, "measure.csv"), list(out[0].keys()), out)


def step_offbench(a, occt):
    """the methods on the same curves and tolerances (each curve's own
    offsets, as occt_offset takes them)"""
    curves = ",".join(dict.fromkeys(r["curve"] for r in occt))
    tols = ",".join(dict.fromkeys(r["tol"] for r in occt))
    scratch = tempfile.mkdtemp(prefix="occt_table.")
    try:
        run([a.offbench, "run", "--curves", a.curves, "--curve", curves, "--methods", a.methods,
             "--tols", tols, "--backend", "cpu", "--out", os.path.join(scratch, "run")])
        rows = read_csv(os.path.join(scratch, "run", "results.csv"))
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    write_csv(os.path.join(a.out, "offbench.csv"), OFFBENCH_COLS, rows)


# ------------------------------------------------------------ the table

def yes(b):
    return "yes" if b else "no"


def key(r):
    """a job's key: the numbers, not their text"""
    c, d, t = (r["curve"], r["d"], r["tol"]) if isinstance(r, dict) else r
    return c, float(d), float(t)


def table_rows(occt, measure, offbench):
    """one row per job (curve, d, tol) and method: OCCT's configurations
    first, in occt.csv's order, then the methods in offbench.csv's"""
    by_file = {}
    for m in measure:
        by_file.setdefault(m["file"], {})[m["metric"]] = m
    rows = []
    jobs = list(dict.fromkeys((r["curve"], r["d"], r["tol"]) for r in occt))
    for job in jobs:
        for r in (r for r in occt if key(r) == key(job)):
            t = dict(zip(("curve", "d", "tol"), job), method=r["method"], source="occt", status=r["status"],
                     degree=r["degree"], claimed=r["max_error"], message=r["message"])
            if r["file"]:
                got = by_file.get(r["file"])
                if not got or "hausdorff" not in got:
                    raise Fail(f"measure.csv: no hausdorff row for {r['file']}")
                h = got["hausdorff"]
                t.update(ctrl_points=r["poles"], max_err=h["max_err"],
                         hausdorff_whole=got["hausdorff-whole"]["max_err"])
                if h["status"] == "ok":
                    t.update(claim_holds=yes(float(h["max_err"]) <= float(r["max_error"]) + ROUNDOFF * float(r["tol"])),
                             within_tol=yes(float(h["max_err"]) <= float(r["tol"])))
            rows.append(t)
        for r in offbench:
            if key(r) != key(job):
                continue
            t = dict(zip(("curve", "d", "tol"), job), method=r["method"], source="offbench",
                     status=r["status"], ctrl_points=r["ctrl_points"], degree=r["out_degree"],
                     max_err=r["max_err"])
            if r["max_err"]:
                t["within_tol"] = yes(float(r["max_err"]) <= float(r["tol"]))
            rows.append(t)
    return rows


def sci(x):
    """8.61e-3: three digits, the exponent without padding"""
    m, e = f"{float(x):.2e}".split("e")
    return f"{m}e{int(e)}"


def tol_text(t):
    m, e = f"{float(t):.0e}".split("e")
    return f"{m}e{int(e)}"


def d_text(d):
    x = float(d)
    return ("+" if x > 0 else "−") + d.lstrip("+-") if x == int(x) else d.replace("-", "−")


def cell(r):
    """control points · measured error, and what is wrong with it"""
    if not r.get("max_err"):
        return r["status"]
    s = f"{r['ctrl_points']} · {sci(r['max_err'])}"
    if r["status"] != "ok":
        s += f" ({r['status']})"
    elif r.get("within_tol") == "no":
        s += " (over tol)"
    return s


def claim(r):
    if not r.get("claimed"):
        return "—"
    return f"{sci(r['claimed'])} " + ("holds" if r.get("claim_holds") == "yes" else "**fails**")


def markdown(rows):
    """one row per job: each OCCT configuration (its cell and its claim),
    then each method"""
    occt = list(dict.fromkeys(r["method"] for r in rows if r["source"] == "occt"))
    meth = list(dict.fromkeys(r["method"] for r in rows if r["source"] == "offbench"))
    head = ["curve, d", "tol"]
    for m in occt:
        head += [f"`{m}`", "its MaxError"]
    head += [f"`{m}`" for m in meth]
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for job in dict.fromkeys((r["curve"], r["d"], r["tol"]) for r in rows):
        at = {r["method"]: r for r in rows if (r["curve"], r["d"], r["tol"]) == job}
        cells = [f"{job[0]}, {d_text(job[1])}", tol_text(job[2])]
        for m in occt:
            cells += [cell(at[m]), claim(at[m])] if m in at else ["", ""]
        cells += [cell(at[m]) if m in at else "" for m in meth]
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def summary(rows, occt):
    """what the table says, in a few generated lines (docs/cad-example.md
    quotes them): did OCCT's claims hold, how many control points beside
    each method"""
    oc = [r for r in rows if r["source"] == "occt"]
    have = [r for r in oc if r.get("claim_holds")]
    ratios = sorted(float(r["max_err"]) / float(r["claimed"]) for r in have if float(r["claimed"]) > 0)
    held = sum(r["claim_holds"] == "yes" for r in have)
    within = sum(r.get("within_tol") == "yes" for r in oc)
    out = [f"- OCCT's own MaxError held for {held} of the {len(oc)} approximations: the error measured "
           f"here (`hausdorff`) was at most the MaxError OCCT gave"
           + (f", at {ratios[0]:.2f} to {ratios[-1]:.2f} of it (median {statistics.median(ratios):.2f})"
              if ratios else "")
           + f"; {within} of the {len(oc)} were within the tolerance asked."]
    bad = [r for r in oc if r.get("claim_holds") != "yes"]
    if bad:
        out.append("- It did not hold, or there was none, for: " + "; ".join(
            f"`{r['method']}` on {r['curve']}, d = {r['d']}, tol {tol_text(r['tol'])} ({r['status']}"
            + (f", measured {sci(r['max_err'])} against {sci(r['claimed'])}" if r.get("max_err") else "") + ")"
            for r in bad) + ".")
    meth = list(dict.fromkeys(r["method"] for r in rows if r["source"] == "offbench"))
    cfg = {r["method"]: r for r in occt}
    by_job = {}
    for r in rows:
        by_job.setdefault(key(r), {})[r["method"]] = r
    for m in dict.fromkeys(r["method"] for r in oc):
        c = cfg[m]
        degs = sorted({int(r["degree"]) for r in oc if r["method"] == m and r["degree"] not in ("", "0")})
        parts = []
        for x in meth:
            pairs = [(int(j[m]["ctrl_points"]), int(j[x]["ctrl_points"])) for j in by_job.values()
                     if m in j and x in j and j[m]["status"] == "ok" and j[x]["status"] == "ok"]
            fewer = sum(a < b for a, b in pairs)
            same = sum(a == b for a, b in pairs)
            parts.append(f"than `{x}` in {fewer} of {len(pairs)}" + (f" (as many in {same})" if same else ""))
        out.append(f"- `{m}` ({c['continuity']}, degree at most {c['max_degree']}; its B-splines of degree "
                   f"{', '.join(map(str, degs))}) needed fewer control points " + ", ".join(parts)
                   + " jobs where both are ok.")
    return "\n".join(out)


def table_from(dirname):
    """(the table's rows, occt.csv's rows) from DIR's occt.csv, measure.csv
    and offbench.csv"""
    occt = read_csv(os.path.join(dirname, "occt.csv"))
    return table_rows(occt, read_csv(os.path.join(dirname, "measure.csv")),
                      read_csv(os.path.join(dirname, "offbench.csv"))), occt


def step_table(a):
    rows, occt = table_from(a.out)
    write_csv(os.path.join(a.out, "table.csv"), TABLE_COLS, rows)
    with open(os.path.join(a.out, "table.md.tmp"), "w", encoding="utf-8") as f:
        f.write(markdown(rows) + "\n\n" + summary(rows, occt) + "\n")
    os.replace(os.path.join(a.out, "table.md.tmp"), os.path.join(a.out, "table.md"))


# ------------------------------------------------------------ main

def main(argv):
    p = argparse.ArgumentParser(prog="occt_table.py", description="OpenCASCADE's offsets beside offbench's methods")
    p.add_argument("--out", default="out/occt")
    p.add_argument("--offbench", default="./offbench")
    p.add_argument("--occt", default="build/occt_offset")
    p.add_argument("--curves", default="datasets/published.curves")
    p.add_argument("--curve", default="liu2002_ex1,liu2002_ex2")
    p.add_argument("--tols", default="1e-2,1e-3,1e-4")
    p.add_argument("--methods", default=DEFAULT_METHODS)
    g = p.add_mutually_exclusive_group()
    g.add_argument("--no-occt", action="store_true", help="measure DIR's DXF files and run the methods again")
    g.add_argument("--table-only", action="store_true", help="only the table, from DIR's CSV files")
    a = p.parse_args(argv[1:])
    try:
        if not (a.no_occt or a.table_only):
            os.makedirs(a.out, exist_ok=True)
            # an earlier run's approximations (other curves, tolerances) would
            # stay beside this one's: remove the files occt_offset names so,
            # and no other
            ours = tuple(f"__{name}__tol" for name, *_ in CONFIGS)
            for f in os.listdir(a.out):
                if f.endswith(".dxf") and any(t in f for t in ours) and os.path.isfile(os.path.join(a.out, f)):
                    os.unlink(os.path.join(a.out, f))
            step_occt(a)
        if not a.table_only:
            occt = read_csv(os.path.join(a.out, "occt.csv"))
            step_measure(a, occt)
            step_offbench(a, occt)
        step_table(a)
    except (Fail, OSError) as e:
        print(f"occt_table.py: {e}", file=sys.stderr)
        return 2
    print(f"occt_table.py: wrote {os.path.join(a.out, 'table.md')} and table.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
