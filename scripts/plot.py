#!/usr/bin/python3
"""Plot the results of `./offbench run` (results.csv) or `./offbench trace`.

Usage: scripts/plot.py RESULTS.csv [--out DIR] [--methods LIST] [--highlight M]
                       [--curve ID,...] [--per-curve] [--max-curves N] [--archive A]
                       [--format svg|pdf|png[,...]]
       scripts/plot.py --trace TRACE.csv [--out DIR] [--format ...]

From RESULTS.csv (columns read by name) it writes into DIR (default: the
directory of RESULTS.csv + /plots), each in every --format (default svg: vector
output, text kept as text; pdf embeds TrueType fonts; png for screens):
  ctrl_<curve>_d<d>      control points against tolerance, log-log, one line per
                         method, stricter tolerance to the right; `limit` points
                         hollow; fail/skip jobs are listed in a footnote.  One
                         file per (curve, d) of the curves that are not random
                         (family `published` first) up to --max-curves (default
                         12) others; random curves (ids rnd<seed>_<n>) only with
                         --per-curve; or the curves given by --curve.
  summary_families       per family of the random curves: the median control
                         points of each method against the tolerance, with the
                         interquartile range as a band.
  time_per_job           per method, the distribution of fit_ns + eval_ns per
                         job (box plot, log axis), methods sorted by median.
--methods a,b plots only those methods (in that order); --highlight M draws M
in colour over the others in grey, in every plot.  --archive A (repeatable: a
run, a results.csv or a directory of runs, e.g. results/baseline-small) draws
the archived methods the run lacks, dashed and marked "(archive)", on the
run's jobs (curve, d, tol) under its metric and split; the rows that could
not join are counted on standard error, as `offbench summary --archive`
says them (scripts/archive_join.py).
From TRACE.csv (columns curve,d,method,metric,split,tol,seg,piece,t,u,err,x,y;
default DIR: the directory of TRACE.csv + /plots):
  trace_<curve>_<method> the error against the curve parameter u, with the
                         piece boundaries and the tolerance.

Prints the paths written.  Exits 2, naming the file and line, on a missing
file, a missing column or a malformed number; a file without plottable rows
writes nothing and exits 0.

Needs matplotlib and numpy: run it as /usr/bin/python3 (Debian's
python3-matplotlib); without them it says which interpreter lacks what.
"""
import argparse
import math
import os
import re
import sys
import textwrap

import archive_join  # scripts/archive_join.py: --archive, the summary's join
import csvrows  # scripts/csvrows.py, beside this file

DEBIAN_PYTHON = "/usr/bin/python3"


def missing_module(name):
    """The message for a module this interpreter cannot import: which
    interpreter (another Python than Debian's often lacks the packages), and
    what to install."""
    exe = sys.executable or "python3"
    msg = (f"plot.py: {name} is not installed for {exe} (Python {sys.version_info[0]}."
           f"{sys.version_info[1]}); on Debian: apt-get install python3-{name} (or 'make deps')")
    if os.path.realpath(exe) != os.path.realpath(DEBIAN_PYTHON) and os.path.exists(DEBIAN_PYTHON):
        msg += f" and run it with {DEBIAN_PYTHON}, whose packages those are"
    return msg


try:
    import matplotlib
    import numpy  # noqa: F401  (matplotlib needs it; named here if it is what is missing)
except ImportError as e:
    sys.exit(missing_module(e.name if e.name in ("matplotlib", "numpy") else "matplotlib"))

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter, NullLocator  # noqa: E402

PROG = "plot"
RESULT_COLUMNS = ("curve", "d", "method", "metric", "split", "tol", "ctrl_points",
                  "segments", "out_degree", "max_err", "status", "fit_ns", "eval_ns",
                  "message", "family")
TRACE_COLUMNS = ("curve", "d", "method", "metric", "split", "tol", "seg", "piece",
                 "t", "u", "err", "x", "y")
PLOTTED = ("ok", "limit")
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">")
RANDOM_ID = re.compile(r"^rnd\d+_\d+$")

# Reproducible SVG output (no random ids, no date): nightly plots diff cleanly.
matplotlib.rcParams["svg.hashsalt"] = "offbench"
# Plots for papers: SVG text stays text (editable, searchable), PDF embeds
# TrueType fonts (journals refuse Type 3)
matplotlib.rcParams["svg.fonttype"] = "none"
matplotlib.rcParams["pdf.fonttype"] = 42
matplotlib.rcParams["axes.titlesize"] = 11
matplotlib.rcParams["legend.fontsize"] = 8


def die(msg):
    print(f"{PROG}: {msg}", file=sys.stderr)
    sys.exit(2)


def note(msg):
    print(f"{PROG}: {msg}", file=sys.stderr)


def unique(seq):
    return list(dict.fromkeys(seq))


# ---------------------------------------------------------------- reading

def read_csv(path, columns, numeric, integer=()):
    return csvrows.read_csv(path, columns, numeric, integer, die=die)


def require(path, rows, fields, test, what):
    for r in rows:
        for c in fields:
            if r[c] is None or not test(r[c]):
                die(f"{path}:{r['_line']}: {c} must be {what}: {r[c]!r}")


def read_results(path):
    rows = read_csv(path, RESULT_COLUMNS,
                    ("d", "tol", "ctrl_points", "segments", "out_degree", "max_err",
                     "fit_ns", "eval_ns"),
                    integer=("ctrl_points", "segments", "out_degree"))
    require(path, rows, ("d",), math.isfinite, "a finite number")
    require(path, rows, ("tol",), lambda v: math.isfinite(v) and v > 0, "a positive number")
    require(path, rows, ("fit_ns", "eval_ns"), lambda v: v >= 0, "a number >= 0")
    return rows


def read_trace(path):
    rows = read_csv(path, TRACE_COLUMNS, ("d", "tol", "seg", "piece", "t", "u", "err"),
                    integer=("seg", "piece"))
    require(path, rows, ("d", "u", "t"), math.isfinite, "a finite number")
    require(path, rows, ("tol",), lambda v: math.isfinite(v) and v > 0, "a positive number")
    require(path, rows, ("piece", "err"), lambda v: True, "given")
    return rows


# ---------------------------------------------------------------- styling

# tab10, then darker hues that stay apart from it (drawn dashed as well)
PALETTE = tuple(plt.get_cmap("tab10").colors) + (
    "#393b79", "#637939", "#843c39", "#7b4173", "#8c6d31", "#000000", "#1b9e77",
    "#e7298a", "#5254a3", "#b5cf6b")


GREY = "#a6a6a6"           # the methods not highlighted
HIGHLIGHT = PALETTE[0]     # the one highlighted


class Style:
    """How one method is drawn: colour, marker, line style, line width, marker
    size and z-order (the highlighted method over the grey ones)."""

    def __init__(self, colour, marker, dash, width=1.4, msize=6.5, z=2):
        self.colour, self.marker, self.dash = colour, marker, dash
        self.width, self.msize, self.z = width, msize, z


def method_styles(methods, highlight=None):
    """A Style per method, distinct for many methods and the same in every plot
    of one results file; with highlight, that method in colour and the others
    grey, thinner and underneath."""
    n = len(PALETTE)
    out = {}
    for i, m in enumerate(methods):
        marker = MARKERS[(i + i // n) % len(MARKERS)]
        if highlight is None:
            out[m] = Style(PALETTE[i % n], marker, "-" if i % (2 * n) < 10 else (0, (4, 1.5)))
        elif m == highlight:
            out[m] = Style(HIGHLIGHT, marker, "-", width=2.2, msize=7, z=4)
        else:
            out[m] = Style(GREY, marker, "-", width=1.0, msize=4.5, z=1)
    return out


def archive_styles(style):
    """Archived methods (--archive) dashed, thinner and underneath: beside
    the run's, not confused with them."""
    for m, st in style.items():
        if m.endswith(archive_join.TAG):
            st.dash, st.width, st.msize, st.z = (0, (3, 2)), min(st.width, 1.0), min(st.msize, 5), 1
    return style


def with_archive(path, rows, order, archives):
    """rows and the method order with the archived methods' rows after the
    run's; what could not join said on standard error."""
    if not archives:
        return rows, order
    extra, lines = archive_join.join(rows, path, archives, read=read_results)
    for line in lines:
        note(line)
    return rows + extra, order + unique(r["method"] for r in extra)


def legend_handles(keys, method_of, style, highlight, handle):
    """The legend's entries: handle(key) for every key, or with highlight the
    highlighted method's keys and one grey entry naming the others."""
    if highlight is None:
        return [handle(k) for k in keys]
    mine = [handle(k) for k in keys if method_of[k] == highlight]
    others = [k for k in keys if method_of[k] != highlight]
    if others:
        text = textwrap.fill("other methods (grey): " + ", ".join(others), 44)
        mine.append(Line2D([], [], color=GREY, linewidth=1.0, label=text))
    return mine


def fmt_num(v):
    return f"{v:g}"


def exact_num(v):
    """The shortest text that reads back as v ("1", "-0.2158", "1e-05")."""
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def short_num(text):
    """A number for a file name: 6 significant digits, not the 17 of an exact
    offset (two offsets that print alike are told apart by Writer.name)."""
    try:
        return f"{float(text):.6g}"
    except ValueError:
        return text


def sanitize(text):
    return re.sub(r"[^A-Za-z0-9._-]", "_", text)


def tol_axis(ax, tols):
    """Log x axis of tolerances, stricter (smaller) to the right."""
    ax.set_xscale("log")
    if not ax.xaxis_inverted():
        ax.invert_xaxis()
    tols = sorted(set(tols))
    if 0 < len(tols) <= 12:
        ax.set_xticks(tols)
        ax.set_xticklabels([fmt_num(t) for t in tols])
        ax.xaxis.set_minor_locator(NullLocator())
    if len(tols) == 1:
        ax.set_xlim(tols[0] * 3, tols[0] / 3)


def count_axis(ax):
    """Log y axis of counts; call after plotting (the ticks follow the range)."""
    ax.set_yscale("log")
    lo, hi = ax.get_ylim()
    if lo > 0 and hi / lo < 300:  # under ~2.5 decades: label 1, 2, 5 of each
        ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.grid(True, which="major", alpha=0.35)
    ax.grid(True, which="minor", axis="y", alpha=0.12)


def legend(ax_or_fig, handles, n_methods, **kw):
    """Inside the axes for a few methods, outside to the right for many."""
    if n_methods <= 5 and not kw:
        return ax_or_fig.legend(handles=handles, loc="best", framealpha=0.85)
    kw.setdefault("loc", "upper left")
    kw.setdefault("bbox_to_anchor", (1.02, 1))
    return ax_or_fig.legend(handles=handles, frameon=False, **kw)


class Writer:
    def __init__(self, outdir, formats):
        self.outdir = outdir
        self.formats = formats
        self.written = []
        self.names = set()

    def name(self, base):
        base = sanitize(base)
        name, k = base, 2
        while name in self.names:
            name, k = f"{base}_{k}", k + 1
        self.names.add(name)
        return name

    def save(self, fig, base, tight=True):
        name = self.name(base)
        try:
            os.makedirs(self.outdir, exist_ok=True)
        except OSError as e:
            die(f"cannot create {self.outdir}: {e.strerror}")
        for ext in self.formats:
            path = os.path.join(self.outdir, f"{name}.{ext}")
            meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(ext, {})
            try:
                fig.savefig(path, dpi=110, bbox_inches="tight" if tight else None,
                            metadata=meta)
            except OSError as e:
                die(f"cannot write {path}: {e.strerror}")
            self.written.append(path)
        plt.close(fig)


def footnote(fig, lines, width=110):
    if not lines:
        return
    text = "\n".join(textwrap.fill(s, width, subsequent_indent="    ") for s in lines)
    fig.text(0.01, -0.01, text, ha="left", va="top", fontsize=7.5, color="0.25",
             wrap=False)


# ---------------------------------------------------------------- 1. ctrl vs tol

def series_key(rows):
    """Label a line by method, plus metric/split when the file mixes them."""
    combos = unique((r["metric"], r["split"]) for r in rows)
    if len(combos) <= 1:
        return lambda r: r["method"]
    return lambda r: f"{r['method']} [{r['metric']}, {r['split']}]"


def short_message(msg, n=70):
    msg = " ".join(msg.split())
    return msg if len(msg) <= n else msg[: n - 1] + "…"


def tol_list(tols, all_tols):
    if set(tols) == set(all_tols):
        return "every tol"
    return "tol " + ", ".join(fmt_num(t) for t in sorted(set(tols), reverse=True))


def plot_ctrl(curve, d, rows, style, keyof, meta_line, writer, highlight=None):
    keys = unique(keyof(r) for r in rows)
    all_tols = unique(r["tol"] for r in rows)
    fig, ax = plt.subplots(figsize=(8.2, 5.0))
    drawn, dropped, labels = [], [], {}
    method_of = {keyof(r): r["method"] for r in rows}
    for key in keys:
        mine = [r for r in rows if keyof(r) == key]
        method = mine[0]["method"]
        st = style[method]
        pts = sorted((r["tol"], r["ctrl_points"], r["status"]) for r in mine
                     if r["status"] in PLOTTED and r["ctrl_points"] and r["ctrl_points"] > 0)
        nocount = [r for r in mine if r["status"] in PLOTTED and not (r["ctrl_points"] or 0) > 0]
        other = [r for r in mine if r["status"] not in PLOTTED]
        for status in unique(r["status"] for r in other):
            rs = [r for r in other if r["status"] == status]
            msgs = unique(short_message(r["message"]) for r in rs if r["message"])
            dropped.append(f"{key}: {status} at {tol_list([r['tol'] for r in rs], all_tols)}"
                           + (f" ({'; '.join(msgs[:2])}{'; …' if len(msgs) > 2 else ''})"
                              if msgs else ""))
        if nocount:
            dropped.append(f"{key}: no control point count at "
                           f"{tol_list([r['tol'] for r in nocount], all_tols)}")
        degs = unique(r["out_degree"] for r in mine if r["status"] in PLOTTED and r["out_degree"])
        labels[key] = key + (f" (deg {degs[0]})" if len(degs) == 1 else "")
        if not pts:
            continue
        x = [p[0] for p in pts]
        y = [p[1] for p in pts]
        ax.plot(x, y, color=st.colour, linestyle=st.dash, linewidth=st.width, alpha=0.9, zorder=st.z)
        for want, face in (("ok", st.colour), ("limit", "white")):
            sel = [(a, b) for a, b, s in pts if s == want]
            if sel:
                ax.plot(*zip(*sel), linestyle="none", marker=st.marker, markersize=st.msize,
                        markerfacecolor=face, markeredgecolor=st.colour, markeredgewidth=1.3,
                        zorder=st.z + 0.5)
        drawn.append(key)
    if not drawn:
        plt.close(fig)
        return False

    def handle(k):
        s = style[method_of[k]]
        return Line2D([], [], color=s.colour, linestyle=s.dash, marker=s.marker,
                      markersize=s.msize, label=labels[k])
    handles = legend_handles(drawn, method_of, style, highlight, handle)
    tol_axis(ax, all_tols)
    count_axis(ax)
    ax.set_xlabel("tolerance (maximum error, curve units, log scale; stricter →)")
    ax.set_ylabel("control points (count, log scale)")
    fam = rows[0]["family"]
    ax.set_title(f"{curve}" + (f" ({fam})" if fam else "") + f", d = {d}: "
                 "control points vs tolerance" + meta_line)
    if any(r["status"] == "limit" for r in rows):
        handles.append(Line2D([], [], color="none", label=""))
        handles.append(Line2D([], [], linestyle="none", marker="o", color="0.3", label="ok"))
        handles.append(Line2D([], [], linestyle="none", marker="o", color="0.3",
                              markerfacecolor="white", label="limit (gave up)"))
    legend(ax, handles, len(keys))
    if dropped:
        footnote(fig, ["Not plotted: " + dropped[0]] + ["  " + s for s in dropped[1:]])
    writer.save(fig, f"ctrl_{curve}_d{short_num(d)}")
    return True


def choose_curves(path, rows, wanted, max_curves, per_curve=False):
    curves = unique(r["curve"] for r in rows)
    if wanted is not None:
        unknown = [c for c in wanted if c not in curves]
        if unknown:
            die(f"{path}: no rows for curve{'s' if len(unknown) > 1 else ''} "
                f"{', '.join(unknown)} (--curve)")
        return wanted
    family = {}
    for r in rows:
        family.setdefault(r["curve"], r["family"])
    published = [c for c in curves if family[c] == "published"]
    random = [c for c in curves if family[c] != "published" and RANDOM_ID.match(c)]
    if random and not per_curve:
        note(f"{path}: {len(random)} random curves are summarized per family (summary_families), "
             "not plotted one by one (--per-curve for that)")
    others = [c for c in curves if family[c] != "published" and (per_curve or not RANDOM_ID.match(c))]
    if len(others) > max_curves:
        note(f"{path}: {len(others) - max_curves} of {len(others)} other curves not plotted "
             f"one by one (--max-curves {max_curves})")
    return published + others[:max_curves]


def meta_suffix(rows):
    combos = unique((r["metric"], r["split"]) for r in rows)
    if len(combos) == 1:
        return f"\n(metric {combos[0][0]}, split {combos[0][1]})"
    return ""


# ---------------------------------------------------------------- 2. families

def plot_families(rows, style, keyof, writer, path, highlight=None):
    rnd = [r for r in rows if RANDOM_ID.match(r["curve"])]
    if not rnd:
        note(f"{path}: no random curves (ids rnd<seed>_<n>): summary_families not written")
        return
    families = sorted(unique(r["family"] or "(none)" for r in rnd))
    keys = unique(keyof(r) for r in rnd)
    method_of = {keyof(r): r["method"] for r in rnd}
    all_tols = unique(r["tol"] for r in rnd)
    nf = len(families)
    ncols = 1 if nf == 1 else 2 if nf <= 4 else 3 if nf <= 9 else 4
    nrows = math.ceil(nf / ncols)
    # the axes are not shared (matplotlib is slow at that): common limits instead
    # fixed margins, no bbox_inches="tight" (slow with many axes): the legend
    # goes in a column of its own on the right
    texts = [h.get_label() for h in legend_handles(keys, method_of, style, highlight, lambda k: Line2D([], [], label=k))]
    reserve = 0.8 + 0.07 * max(len(line) for t in texts + ["interquartile range"] for line in t.split("\n"))
    width = 4.3 * ncols + 0.3 + reserve
    fig, axes = plt.subplots(nrows, ncols, squeeze=False,
                             figsize=(width, 3.3 * nrows + 0.9))
    drawn = set()
    ylo, yhi = math.inf, 0.0
    groups = {}  # (family, key) -> its rows
    for r in rnd:
        groups.setdefault((r["family"] or "(none)", keyof(r)), []).append(r)
    for i, fam in enumerate(families):
        ax = axes[i // ncols][i % ncols]
        ncurves = len(unique((r["curve"], r["d"]) for k in keys for r in groups.get((fam, k), ())))
        absent = []
        for key in keys:
            mine = [r for r in groups.get((fam, key), ()) if r["status"] in PLOTTED
                    and r["ctrl_points"] and r["ctrl_points"] > 0]
            if not mine:
                if (fam, key) in groups:
                    absent.append(key)
                continue
            st = style[mine[0]["method"]]
            tols = sorted(unique(r["tol"] for r in mine))
            med, lo, hi = [], [], []
            for t in tols:
                v = np.array([r["ctrl_points"] for r in mine if r["tol"] == t], dtype=float)
                q1, q2, q3 = np.percentile(v, [25, 50, 75])
                lo.append(q1)
                med.append(q2)
                hi.append(q3)
            ax.fill_between(tols, lo, hi, color=st.colour, alpha=0.13, linewidth=0,
                            zorder=st.z - 0.5)
            ax.plot(tols, med, color=st.colour, linestyle=st.dash, marker=st.marker,
                    markersize=st.msize * 0.7, linewidth=st.width * 0.95, zorder=st.z)
            drawn.add(key)
            ylo, yhi = min(ylo, min(lo)), max(yhi, max(hi))
        ax.set_title(f"{fam}: {ncurves} (curve, d) pair{'s' if ncurves != 1 else ''}",
                     fontsize=10)
        if absent:
            ax.text(0.02, 0.98, "no ok/limit jobs:\n" + textwrap.fill(", ".join(absent), 34),
                    transform=ax.transAxes, ha="left", va="top", fontsize=6.5, color="0.35")
    for j in range(nf, nrows * ncols):
        axes[j // ncols][j % ncols].set_visible(False)
    if yhi <= 0:
        ylo, yhi = 1.0, 10.0
    for i in range(nf):
        ax = axes[i // ncols][i % ncols]
        ax.set_yscale("log")
        ax.set_ylim(ylo / 1.3, yhi * 1.3)
        count_axis(ax)
        tol_axis(ax, all_tols)
        if i % ncols:
            ax.tick_params(labelleft=False)
        else:
            ax.set_ylabel("control points (count, log scale)")
        if i + ncols >= nf:  # lowest in its column
            ax.set_xlabel("tolerance (curve units, log scale; stricter →)")

    def handle(k):
        s = style[method_of[k]]
        return Line2D([], [], color=s.colour, marker=s.marker, linestyle=s.dash, label=k)
    handles = legend_handles([k for k in keys if k in drawn], method_of, style, highlight, handle)
    handles.append(Patch(color="0.5", alpha=0.3, label="interquartile range"))
    fig.suptitle("Median control points per random family (ok and limit jobs; "
                 "band: 25th–75th percentile)" + meta_suffix(rnd).replace("\n", " "),
                 fontsize=11)
    right = 1 - reserve / width
    fig.subplots_adjust(left=0.75 / width, right=right, bottom=0.7 / fig.get_figheight(),
                        top=1 - 0.75 / fig.get_figheight(), wspace=0.06, hspace=0.32)
    legend(fig, handles, len(handles), loc="upper left",
           bbox_to_anchor=(right + 0.01, 1 - 0.75 / fig.get_figheight()), borderaxespad=0.0)
    writer.save(fig, "summary_families", tight=False)


# ---------------------------------------------------------------- 3. time

def fmt_seconds(v, _=None, digits=6):
    if v <= 0:
        return "0"
    for scale, unit in ((1, "s"), (1e-3, "ms"), (1e-6, "µs"), (1e-9, "ns")):
        if v >= scale * 0.999:
            return f"{v / scale:.{digits}g} {unit}"
    return f"{v:.{digits}g} s"


def plot_time(rows, style, keyof, writer, path):
    timed = [r for r in rows if r["status"] != "skip"]
    zero = [r for r in timed if r["fit_ns"] + r["eval_ns"] <= 0]
    timed = [r for r in timed if r["fit_ns"] + r["eval_ns"] > 0]
    if not timed:
        note(f"{path}: no timed jobs: time_per_job not written")
        return
    keys = unique(keyof(r) for r in timed)
    method_of = {keyof(r): r["method"] for r in timed}
    data = {k: np.array([(r["fit_ns"] + r["eval_ns"]) * 1e-9 for r in timed if keyof(r) == k])
            for k in keys}
    keys.sort(key=lambda k: (np.median(data[k]), k))
    fig, ax = plt.subplots(figsize=(8.5, 1.2 + 0.36 * len(keys)))
    pos = list(range(len(keys), 0, -1))  # fastest on top
    bp = ax.boxplot([data[k] for k in keys], positions=pos, vert=False, widths=0.6,
                    patch_artist=True, showfliers=True,
                    medianprops={"color": "black", "linewidth": 1.4},
                    flierprops={"marker": ".", "markersize": 3, "alpha": 0.5})
    for k, box, fl in zip(keys, bp["boxes"], bp["fliers"]):
        colour = style[method_of[k]].colour
        box.set_facecolor(colour)
        box.set_alpha(0.75)
        fl.set_markeredgecolor(colour)
    ax.set_yticks(pos)
    ax.set_yticklabels([f"{k} (n={len(data[k])}, median {fmt_seconds(np.median(data[k]), digits=3)})"
                        for k in keys], fontsize=8.5)
    ax.set_xscale("log")
    lo = min(v.min() for v in data.values())
    hi = max(v.max() for v in data.values())
    ax.set_xlim(10 ** math.floor(math.log10(lo)), 10 ** math.ceil(math.log10(hi)))
    ax.xaxis.set_major_formatter(FuncFormatter(fmt_seconds))
    ax.grid(True, axis="x", which="major", alpha=0.35)
    ax.set_xlabel("time per job: fit + evaluation (fit_ns + eval_ns; seconds, log scale)")
    ncurves = len(unique((r["curve"], r["d"]) for r in timed))
    ax.set_title(f"Time per job by method, fastest median on top\n"
                 f"{len(timed)} jobs on {ncurves} (curve, d) pairs; skipped jobs omitted"
                 + meta_suffix(timed))
    if zero:
        footnote(fig, [f"{len(zero)} job(s) with zero time not shown."])
    writer.save(fig, "time_per_job")


# ---------------------------------------------------------------- 4. trace

def plot_trace(path, outdir, formats):
    rows = read_trace(path)
    writer = Writer(outdir, formats)
    jobs = unique((r["curve"], r["d"], r["method"], r["metric"], r["split"], r["tol"])
                  for r in rows)
    if not rows:
        note(f"{path}: no samples: nothing written")
        return writer
    curves_methods = [(j[0], j[2]) for j in jobs]
    for job in jobs:
        curve, d, method, metric, split, tol = job
        jr = [r for r in rows if (r["curve"], r["d"], r["method"], r["metric"], r["split"],
                                  r["tol"]) == job]
        jr = [r for r in jr if r["err"] is not None and not math.isnan(r["err"])]
        if not jr:
            note(f"{path}: {curve} {method}: no finite err: not plotted")
            continue
        errs = [r["err"] for r in jr]
        logy = all(e > 0 for e in errs)
        fig, ax = plt.subplots(figsize=(9, 4.6))
        # one line per piece (no line across a boundary), alternating colours
        pieces = []
        for r in jr:
            if not pieces or pieces[-1][0] != r["piece"]:
                pieces.append((r["piece"], []))
            pieces[-1][1].append(r)
        colours = ("tab:blue", "tab:orange")
        for k, (_, pr) in enumerate(pieces):
            ax.plot([r["u"] for r in pr], [r["err"] for r in pr], color=colours[k % 2],
                    linewidth=1.1, marker="." if len(pr) < 40 else None, markersize=3)
        for (_, a), (_, b) in zip(pieces, pieces[1:]):
            ax.axvline((a[-1]["u"] + b[0]["u"]) / 2, color="0.45", linewidth=0.8,
                       linestyle=(0, (3, 2)), zorder=0)
        ax.axhline(tol, color="tab:red", linestyle="--", linewidth=1.2)
        worst = max(jr, key=lambda r: r["err"])
        ax.plot([worst["u"]], [worst["err"]], marker="o", markersize=7, markerfacecolor="none",
                markeredgecolor="black")
        if logy:
            ax.set_yscale("log")
            # errors that vanish at interpolated piece ends would stretch the
            # axis over many decades: show four below the larger of max, tol
            floor = 1e-4 * max(max(errs), tol)
            if min(errs) < floor:
                ax.set_ylim(bottom=floor, top=max(max(errs), tol) * 2)
                ax.text(0.005, 0.01, f"values below {floor:.2g} run off the bottom",
                        transform=ax.transAxes, fontsize=7, color="0.4", va="bottom")
        ax.grid(True, which="major", alpha=0.3)
        ax.set_xlabel("curve parameter u")
        ax.set_ylabel(f"error ({metric}, curve units)" + (", log scale" if logy else ""))
        ax.set_xlim(min(r["u"] for r in jr), max(r["u"] for r in jr))
        if not logy:
            ax.set_ylim(bottom=min(0.0, min(errs)), top=max(max(errs), tol) * 1.12)
        ax.set_title(f"{curve}, {method}: error along the curve\n"
                     f"d = {exact_num(d)}, tol = {exact_num(tol)}, metric {metric}, split {split}; "
                     f"{len(pieces)} piece{'s' if len(pieces) != 1 else ''}, "
                     f"{len(jr)} samples")
        handles = [Line2D([], [], color=colours[0], label="error (pieces alternate colour)"),
                   Line2D([], [], color="0.45", linestyle=(0, (3, 2)), linewidth=0.8,
                          label="piece boundary"),
                   Line2D([], [], color="tab:red", linestyle="--", label=f"tol = {fmt_num(tol)}"),
                   Line2D([], [], linestyle="none", marker="o", markerfacecolor="none",
                          color="black", label=f"max error {worst['err']:.3g} at u = "
                                               f"{worst['u']:.4g}")]
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1), frameon=False)
        base = f"trace_{curve}_{method}"
        if curves_methods.count((curve, method)) > 1:
            base += f"_d{exact_num(d)}_tol{exact_num(tol)}_{metric}_{split}"
        writer.save(fig, base)
    return writer


# ---------------------------------------------------------------- main

def select_methods(path, rows, methods, highlight):
    """The rows of the --methods (in that order), and the method order; exits
    2 naming a listed or highlighted method without rows."""
    present = unique(r["method"] for r in rows)
    if methods is not None:
        unknown = [m for m in methods if m not in present]
        if unknown:
            die(f"{path}: --methods: no rows for method{'s' if len(unknown) > 1 else ''} "
                f"{', '.join(unknown)} (the file has {', '.join(present)})")
        rows = [r for r in rows if r["method"] in methods]
        present = methods
    if highlight is not None and highlight not in present:
        die(f"{path}: --highlight {highlight}: no rows for that method"
            + (" among --methods" if methods is not None else "")
            + f" (methods: {', '.join(present)})")
    return rows, present


def plot_results(path, outdir, formats, wanted, max_curves, methods=None, highlight=None,
                 per_curve=False, archives=None):
    rows = read_results(path)
    rows, order = select_methods(path, rows, methods, highlight)
    rows, order = with_archive(path, rows, order, archives)
    writer = Writer(outdir, formats)
    plottable = [r for r in rows if r["status"] in PLOTTED
                 and r["ctrl_points"] and r["ctrl_points"] > 0]
    if not plottable:
        note(f"{path}: no plottable rows (status ok or limit with control points): "
             "nothing written")
        return writer
    style = archive_styles(method_styles(order, highlight))
    keyof = series_key(rows)
    for curve in choose_curves(path, rows, wanted, max_curves, per_curve):
        crows = [r for r in rows if r["curve"] == curve]
        for d in unique(r["d"] for r in crows):
            drows = [r for r in crows if r["d"] == d]
            dtext = exact_num(d)
            if not plot_ctrl(curve, dtext, drows, style, keyof, meta_suffix(drows), writer,
                             highlight):
                note(f"{path}: {curve}, d = {dtext}: no ok/limit rows: not plotted")
    plot_families(rows, style, keyof, writer, path, highlight)
    plot_time(rows, style, keyof, writer, path)
    return writer


def comma_list(ap, opt, text):
    """The values of a comma list option (None when not given); an empty list
    or a value given twice is a usage error (exit 2)."""
    if text is None:
        return None
    values = [c.strip() for c in text.split(",") if c.strip()]
    if not values:
        ap.error(f"{opt}: empty list")
    twice = [v for v in unique(values) if values.count(v) > 1]
    if twice:
        ap.error(f"{opt}: {', '.join(twice)} given twice")
    return values


def main(argv):
    ap = argparse.ArgumentParser(
        prog="plot.py", description="Plot offbench results.csv or trace CSV files.",
        usage="%(prog)s RESULTS.csv [--out DIR] [--methods LIST] [--highlight M] "
              "[--curve ID,...] [--per-curve] [--max-curves N] [--format svg|pdf|png[,...]]\n"
              "       %(prog)s --trace TRACE.csv [--out DIR] [--format ...]")
    ap.add_argument("results", nargs="?", help="results.csv written by ./offbench run")
    ap.add_argument("--trace", metavar="TRACE.csv", help="CSV written by ./offbench trace")
    ap.add_argument("--out", metavar="DIR", help="output directory (default: beside the input, "
                    "in plots/)")
    ap.add_argument("--methods", metavar="LIST", help="only these methods, in this order")
    ap.add_argument("--highlight", metavar="M", help="draw method M in colour, the others in grey")
    ap.add_argument("--curve", metavar="ID,...", help="plot only these curves one by one")
    ap.add_argument("--per-curve", action="store_true",
                    help="plot random curves one by one too (default: their family summary only)")
    ap.add_argument("--max-curves", metavar="N", type=int, default=12,
                    help="at most N curves not of family 'published' (default 12)")
    ap.add_argument("--archive", metavar="ARCHIVE", action="append",
                    help="archived runs (a run, results.csv or directory of runs; repeatable): their "
                    "other methods drawn dashed beside the run's on its jobs")
    ap.add_argument("--format", "--formats", dest="formats", metavar="LIST", default="svg",
                    help="comma-separated file formats: svg (default), pdf, png, ...")
    a = ap.parse_args(argv[1:])
    if (a.results is None) == (a.trace is None):
        ap.error("give either RESULTS.csv or --trace TRACE.csv")
    if a.max_curves < 0:
        ap.error("--max-curves must be >= 0")
    formats = unique(f.strip().lower().lstrip(".") for f in a.formats.split(",") if f.strip())
    supported = plt.figure().canvas.get_supported_filetypes()
    plt.close("all")
    bad = [f for f in formats if f not in supported]
    if not formats or bad:
        ap.error(f"--format: unsupported {', '.join(bad) or '(empty)'}; "
                 f"choose from {', '.join(sorted(supported))}")
    src = a.trace if a.trace is not None else a.results
    outdir = a.out or os.path.join(os.path.dirname(os.path.abspath(src)), "plots")
    if a.trace is not None:
        for opt, given in (("--curve", a.curve is not None), ("--methods", a.methods is not None),
                           ("--archive", a.archive is not None),
                           ("--highlight", a.highlight is not None), ("--per-curve", a.per_curve)):
            if given:
                ap.error(f"{opt} applies to RESULTS.csv, not to --trace")
        writer = plot_trace(a.trace, outdir, formats)
    else:
        wanted = comma_list(ap, "--curve", a.curve)
        methods = comma_list(ap, "--methods", a.methods)
        writer = plot_results(a.results, outdir, formats, wanted, a.max_curves, methods,
                              a.highlight, a.per_curve, a.archive)
    for p in writer.written:
        print(p)


if __name__ == "__main__":
    main(sys.argv)
