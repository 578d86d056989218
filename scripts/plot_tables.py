#!/usr/bin/python3
"""Plot the published tables against ours, from `./offbench tables` output.

Usage: scripts/plot_tables.py TABLES_CSV OUTDIR

Writes one PNG per (source, table) into OUTDIR and prints their paths:
  - unit ctrl_points (e.g. OUTDIR/liu2002_table1.png): control points against
    tolerance, both log scale, stricter tolerance to the right.  One colour per
    method label; our counts as lines (paper protocol solid, rigorous dashed,
    best dotted), the published counts as open circles (also for the methods
    we do not implement, which only have circles).
  - unit max_err (e.g. OUTDIR/zhao2017_table1.png): bars of the published
    error (hatched) next to ours under the paper protocol (filled), per curve
    piece and method, log scale.
Exits 2, naming the file and line, on a missing or malformed CSV.

Needs matplotlib: run it as /usr/bin/python3 (Debian's python3-matplotlib).
"""
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

import csvrows  # noqa: E402  (scripts/csvrows.py, beside this file)

HEADER = ("source,table,curve,d,tol,method,label,protocol,published,ours,ratio,"
          "status,unit,d_run,metric,split,job_status,note").split(",")
UNITS = ("ctrl_points", "max_err")
PAPERS = {"liu2002": "Liu & Wang 2002", "ahn2023": "Ahn 2023",
          "zhao2017": "Zhao & Zhou 2017", "kim2018": "Kim, Lee & Ahn 2018"}
STYLES = {"paper": "-", "rigorous": "--", "best": ":"}
DRUN_MARKERS = (".", "x", "+", "^", "s")


def die(msg):
    print(f"plot_tables: {msg}", file=sys.stderr)
    sys.exit(2)


def read_rows(path):
    """The rows of tables.csv as dicts, with tol/published/ours as floats."""
    rows = csvrows.read_csv(path, HEADER, ("tol", "published", "ours"), die=die)
    for row in rows:
        line = row["line"] = row["_line"]
        if row["unit"] not in UNITS:
            die(f"{path}:{line}: unit {row['unit']!r} is not one of {', '.join(UNITS)}")
        if not row["source"] or not row["table"] or not row["label"]:
            die(f"{path}:{line}: empty source, table or label")
    return rows


def colours(labels):
    cmap = plt.get_cmap("tab10" if len(labels) <= 10 else "tab20")
    return {lab: cmap(i % cmap.N) for i, lab in enumerate(labels)}


def unique(seq):
    return list(dict.fromkeys(seq))


def title(source, table, rows):
    curves = unique(r["curve"].split("/")[0] for r in rows)
    ds = unique(r["d"] for r in rows)
    what = ", ".join(curves) + (f", d = {ds[0]}" if len(ds) == 1 and ds[0] else "")
    head = f"Table {table}" if table != "text" else "in the text"
    return f"{PAPERS.get(source, source)}, {head} ({what})"


def plot_counts(source, table, rows, path):
    """Control points against tolerance, one panel per (curve, d)."""
    panels = unique((r["curve"], r["d"]) for r in rows)
    labels = unique(r["label"] for r in rows)
    colour = colours(labels)
    fig, axes = plt.subplots(len(panels), 1, squeeze=False, layout="constrained",
                             figsize=(9, 4.5 * len(panels)))
    drun_all = []
    for ax, (curve, d) in zip(axes[:, 0], panels):
        prow = [r for r in rows if (r["curve"], r["d"]) == (curve, d) and r["tol"]]
        druns = unique(r["d_run"] for r in prow if r["ours"] is not None)
        marker = {dr: (DRUN_MARKERS[i % len(DRUN_MARKERS)] if len(druns) > 1 else ".")
                  for i, dr in enumerate(druns)}
        if len(druns) > 1:
            drun_all += [dr for dr in druns if dr not in drun_all]
        for lab in labels:
            mine = [r for r in prow if r["label"] == lab]
            pub = sorted({(r["tol"], r["published"]) for r in mine
                          if r["published"] and r["published"] > 0})
            if pub:
                ax.plot(*zip(*pub), linestyle="none", marker="o", markersize=8,
                        markerfacecolor="none", markeredgecolor=colour[lab])
            for key in unique((r["protocol"], r["d_run"]) for r in mine
                              if r["ours"] is not None and r["ours"] > 0):
                pts = sorted((r["tol"], r["ours"]) for r in mine
                             if (r["protocol"], r["d_run"]) == key
                             and r["ours"] is not None and r["ours"] > 0)
                ax.plot(*zip(*pts), color=colour[lab], marker=marker[key[1]],
                        linestyle=STYLES.get(key[0], "-."))
        ax.set_xscale("log")
        ax.set_yscale("log")
        if not ax.xaxis_inverted():
            ax.invert_xaxis()
        ax.set_xlabel("tolerance (stricter to the right)")
        ax.set_ylabel("control points")
        ax.grid(True, which="major", alpha=0.3)
        if len(panels) > 1:
            ax.set_title(f"{curve}" + (f", d = {d}" if d else ""), fontsize=10)

    handles = []
    for lab in labels:
        mine = [r for r in rows if r["label"] == lab]
        methods = "/".join(unique(r["method"] for r in mine))
        ran = any(r["ours"] is not None for r in mine)
        handles.append(Line2D([], [], color=colour[lab], marker="o", markerfacecolor="none",
                              label=f"{lab} ({methods})" + ("" if ran else ": published only")))
    handles.append(Line2D([], [], color="none", label=""))
    handles.append(Line2D([], [], linestyle="none", marker="o", markerfacecolor="none",
                          color="black", label="published"))
    for proto in unique(r["protocol"] for r in rows if r["ours"] is not None):
        handles.append(Line2D([], [], color="black", linestyle=STYLES.get(proto, "-."),
                              label=f"ours, {proto} protocol"))
    for i, dr in enumerate(drun_all):
        handles.append(Line2D([], [], color="black", linestyle="none",
                              marker=DRUN_MARKERS[i % len(DRUN_MARKERS)], label=f"ours, d = {dr}"))
    axes[0, 0].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1),
                      fontsize=8, frameon=False)
    fig.suptitle(title(source, table, rows))
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_errors(source, table, rows, path):
    """Grouped bars: published (hatched) and ours, paper protocol (filled)."""
    curves = unique(r["curve"] for r in rows)
    labels = unique(r["label"] for r in rows)
    colour = colours(labels)
    width = 0.8 / (2 * len(labels))
    drawn = []
    fig, ax = plt.subplots(figsize=(max(6.0, 1.8 * len(curves) * len(labels) / 2), 4.5))
    for ci, curve in enumerate(curves):
        for li, lab in enumerate(labels):
            cell = [r for r in rows if r["curve"] == curve and r["label"] == lab]
            pub = next((r["published"] for r in cell if r["published"]), None)
            ours = next((r["ours"] for r in cell
                         if r["protocol"] == "paper" and r["ours"]), None)
            x = ci - 0.4 + (2 * li + 0.5) * width
            for value, dx, filled in ((pub, 0, False), (ours, width, True)):
                if value and value > 0:
                    drawn.append(value)
                    ax.bar(x + dx, value, width, color=colour[lab] if filled else "none",
                           edgecolor=colour[lab], hatch=None if filled else "///")
    ax.set_yscale("log")
    if drawn:  # bars start a decade below the smallest, not at an arbitrary clip
        ax.set_ylim(10 ** math.floor(math.log10(min(drawn)) - 0.5), 1.5 * max(drawn))
    ax.set_xticks(range(len(curves)))
    ax.set_xticklabels([c.split("/", 1)[-1] for c in curves])
    ax.set_xlabel("curve" + (" piece" if any("/" in c for c in curves) else ""))
    ax.set_ylabel("maximum error")
    ax.grid(True, axis="y", which="major", alpha=0.3)
    handles = []
    for lab in labels:
        mine = [r for r in rows if r["label"] == lab]
        methods = "/".join(unique(r["method"] for r in mine))
        ran = any(r["ours"] is not None and r["protocol"] == "paper" for r in mine)
        handles.append(Patch(color=colour[lab],
                             label=f"{lab} ({methods})" + ("" if ran else ": published only")))
    handles.append(Patch(facecolor="none", edgecolor="black", hatch="///", label="published"))
    handles.append(Patch(color="black", label="ours, paper protocol"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1),
              fontsize=8, frameon=False)
    ax.set_title(title(source, table, rows))
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().split("\n\n")[1], file=sys.stderr)
        sys.exit(2)
    rows = read_rows(argv[1])
    outdir = argv[2]
    try:
        os.makedirs(outdir, exist_ok=True)
    except OSError as e:
        die(f"cannot create {outdir}: {e.strerror}")
    tables = unique((r["source"], r["table"], r["unit"]) for r in rows)
    both = {(s, t) for s, t, u in tables if u == "max_err" and (s, t, "ctrl_points") in tables}
    written = []
    for source, table, unit in tables:
        group = [r for r in rows if (r["source"], r["table"], r["unit"]) == (source, table, unit)]
        name = re.sub(r"[^A-Za-z0-9._-]", "_", f"{source}_table{table}")
        if (source, table) in both and unit == "max_err":
            name += "_err"
        path = os.path.join(outdir, name + ".png")
        if unit == "ctrl_points":
            notol = [str(r["line"]) for r in group if not r["tol"]]
            if notol:
                print(f"plot_tables: {argv[1]}: no tol, not plotted: line(s) {', '.join(notol)}",
                      file=sys.stderr)
            if len(notol) == len(group):
                continue
            plot_counts(source, table, group, path)
        else:
            plot_errors(source, table, group, path)
        written.append(path)
    for path in written:
        print(path)
    if not written:
        print(f"plot_tables: {argv[1]}: no rows to plot", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv)
