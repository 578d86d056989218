"""report_data.py - reads the nightly history store for scripts/report.py:
the runs (directories holding a run.json, see scripts/nightly_history.sh),
and per run set (published, random) each method's figures, from
results.csv (columns found by name in its header) and samples.csv.
Problems with a run's files are collected as warnings naming the file and
line; they leave that run set out, never the whole report."""

import csv
import hashlib
import json
import os
import statistics

NEEDED = ("curve", "d", "method", "metric", "split", "tol", "ctrl_points", "status", "fit_ns", "eval_ns")
KEY = ("curve", "d", "method", "metric", "split", "tol")
SET_ORDER = ("published", "random")


class Run:
    """One run of the store: run.json's facts and its sets' figures."""

    def __init__(self, name, path, meta):
        self.name = name
        self.path = path
        self.meta = meta
        self.date = str(meta.get("date", ""))
        self.commit = str(meta.get("commit", "unknown"))
        self.short = str(meta.get("commit_short", self.commit[:7]))
        self.dirty = bool(meta.get("dirty", False))
        self.host = str(meta.get("host", ""))
        self.status = meta.get("status")
        self.status_text = str(meta.get("status_text", ""))
        self.stage = str(meta.get("stage", ""))
        self.seconds = meta.get("seconds")
        self.sets = {}      # set name -> {method: figures dict}
        self.machine = {}   # set name -> machine key of its timings
        self.problems = []  # warnings about this run's files


def load_store(store, warn):
    """The runs of STORE in run order (date, then name); warn(text) is
    called for every problem."""
    runs = []
    for name in sorted(os.listdir(store)):
        path = os.path.join(store, name)
        mfile = os.path.join(path, "run.json")
        if name.startswith(".") or not os.path.isfile(mfile):
            continue
        try:
            with open(mfile, encoding="utf-8") as f:
                meta = json.load(f)
            if not isinstance(meta, dict):
                raise ValueError("not a JSON object")
        except (OSError, ValueError) as e:
            warn("%s: %s (run left out)" % (mfile, e))
            continue
        run = Run(name, path, meta)
        for s in set_names(path):
            load_set(run, s, warn)
        runs.append(run)
    runs.sort(key=lambda r: (r.date, r.name))
    return runs


def set_names(path):
    """The run sets of a run directory: subdirectories with a results.csv,
    published and random first."""
    names = [n for n in os.listdir(path)
             if os.path.isfile(os.path.join(path, n, "results.csv"))]
    return sorted(names, key=lambda n: (SET_ORDER.index(n) if n in SET_ORDER else len(SET_ORDER), n))


def load_set(run, s, warn):
    """Reads run/s/results.csv (and samples.csv, meta.json) into run.sets[s]."""
    d = os.path.join(run.path, s)
    try:
        methods = read_results(os.path.join(d, "results.csv"))
        read_samples(os.path.join(d, "samples.csv"), methods)
    except (OSError, ValueError, csv.Error) as e:
        text = "%s" % e
        run.problems.append(text)
        warn(text + " (run set left out)")
        return
    for m in methods.values():
        m["jobs"] = hashlib.sha1("\n".join(sorted(m["jobs"])).encode()).hexdigest()[:12]
        tot = sorted(m.pop("reps").values())
        m["rep_totals"] = tot
        m["iqr_ns"] = iqr(tot) if len(tot) >= 2 else None
    run.sets[s] = methods
    run.machine[s] = machine_key(run, os.path.join(d, "meta.json"))


def read_results(path):
    """Per method: rows, ctrl (summed ctrl_points), ok/limit/fail/timeout/
    skip counts, time_ns (fit_ns + eval_ns summed), jobs (a hash of the
    job keys).  Raises ValueError naming FILE:LINE on bad content."""
    methods = {}
    for row, col, line in csv_rows(path, NEEDED, True):
        m = methods.setdefault(row[col["method"]], new_method())
        add_row(m, row, col, path, line)
    return methods


def csv_rows(path, needed, whole_list, empty_is_error=True):
    """The non-empty rows of the CSV file PATH as (row, col, line), col
    mapping each header name to its index.  ValueError naming FILE:LINE for
    an empty file (when EMPTY_IS_ERROR), a header without the NEEDED names
    (all of them listed when WHOLE_LIST, else the first), or a row with
    another field count than the header."""
    with open(path, newline="", encoding="utf-8") as f:
        rd = csv.reader(f)
        header = next(rd, None)
        if header is None and empty_is_error:
            raise ValueError("%s: empty file" % path)
        header = header or []
        col = {n: i for i, n in enumerate(header)}
        missing = [n for n in needed if n not in col]
        if missing:
            raise ValueError("%s:1: no column %s in the header" % (path, ", ".join(missing if whole_list else missing[:1])))
        for row in rd:
            if not row:
                continue
            line = rd.line_num
            if len(row) != len(header):
                raise ValueError("%s:%d: %d fields, the header has %d" % (path, line, len(row), len(header)))
            yield row, col, line


def new_method():
    return {"rows": 0, "ctrl": 0, "ok": 0, "limit": 0, "fail": 0, "timeout": 0, "skip": 0,
            "time_ns": 0, "jobs": [], "reps": {}}


def add_row(m, row, col, path, line):
    """Adds one results.csv row to its method's figures."""
    m["rows"] += 1
    st = row[col["status"]]
    if st in ("ok", "limit", "fail", "timeout", "skip"):
        m[st] += 1
    m["ctrl"] += number(row[col["ctrl_points"]], "ctrl_points", path, line, int)
    m["time_ns"] += (number(row[col["fit_ns"]], "fit_ns", path, line, int)
                     + number(row[col["eval_ns"]], "eval_ns", path, line, int))
    m["jobs"].append("|".join(row[col[k]] for k in KEY if k != "method"))


def number(text, name, path, line, kind):
    """TEXT as a number (empty: 0); ValueError naming FILE:LINE otherwise."""
    if text == "":
        return 0
    try:
        return kind(text)
    except ValueError:
        raise ValueError("%s:%d: %s is '%s', not a number" % (path, line, name, text)) from None


def read_samples(path, methods):
    """Adds each repetition's method total (fit_ns + eval_ns over the
    method's rows) from samples.csv, where there is one."""
    if not os.path.isfile(path):
        return
    for row, col, line in csv_rows(path, ("method", "rep", "fit_ns", "eval_ns"), False, False):
        m = methods.get(row[col["method"]])
        if m is None:
            continue
        rep = row[col["rep"]]
        m["reps"][rep] = (m["reps"].get(rep, 0) + number(row[col["fit_ns"]], "fit_ns", path, line, int)
                          + number(row[col["eval_ns"]], "eval_ns", path, line, int))


def iqr(values):
    """The interquartile range of VALUES (quartiles by linear interpolation,
    statistics.quantiles' inclusive method)."""
    if len(values) < 2:
        return 0
    q = statistics.quantiles(values, n=4, method="inclusive")
    return q[2] - q[0]


def machine_key(run, meta_path):
    """What must match for two runs' timings to be compared: the host, and
    meta.json's CPU model, thread count and backend."""
    try:
        with open(meta_path, encoding="utf-8") as f:
            meta = json.load(f)
    except (OSError, ValueError):
        meta = {}
    if not isinstance(meta, dict):
        meta = {}
    return "%s|%s|%s|%s" % (run.host, meta.get("cpu_model", ""), meta.get("omp_threads", ""),
                            meta.get("backend", ""))
