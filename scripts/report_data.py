"""report_data.py - reads the nightly history store for scripts/report.py:
the runs (directories holding a run.json, see scripts/nightly_history.sh),
and per run set (published, random) each method's figures, from
results.csv (columns found by name in its header) and samples.csv.
Problems with a run's files are collected as warnings naming the file and
line; they leave that run set out, never the whole report.

Every file of the store is opened through open_regular(): a regular file
itself, never a symbolic link (not even one pointing into the store), a
FIFO, a device or a directory; an entry of any other kind is a warning
naming it and is otherwise left alone.  Names are whatever bytes the file
system holds: shown() makes them printable, the bytes stay in the paths."""

import csv
import errno
import hashlib
import json
import os
import stat
import statistics

NEEDED = ("curve", "d", "method", "metric", "split", "tol", "ctrl_points", "status", "fit_ns", "eval_ns")
KEY = ("curve", "d", "method", "metric", "split", "tol")
SET_ORDER = ("published", "random")


class NotRegular(OSError):
    """A store entry that is not a regular file (a link, a FIFO, ...)."""

    def __init__(self, path, what):
        super().__init__("%s: %s, not a regular file" % (path, what))


def kind_of(mode):
    """What an entry that is not a regular file is, in words."""
    for test, what in ((stat.S_ISLNK, "a symbolic link"), (stat.S_ISFIFO, "a FIFO"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISDIR, "a directory")):
        if test(mode):
            return what
    return "of an unknown kind"


def open_regular(path, mode="r", **kw):
    """PATH opened for reading (open()'s MODE and keywords) when it is a
    regular file itself.  A symbolic link (wherever it points), a FIFO, a
    device, a socket or a directory raises NotRegular naming PATH: it is
    never followed, and opening never blocks."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as e:
        if e.errno == errno.ELOOP:
            raise NotRegular(path, "a symbolic link") from None
        raise
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise NotRegular(path, kind_of(st.st_mode))
        os.set_blocking(fd, True)
        return os.fdopen(fd, mode, **kw)
    except BaseException:
        os.close(fd)
        raise


def load_json(path):
    """The JSON text of the regular file PATH (OSError, ValueError or
    RecursionError when it cannot be read or parsed)."""
    with open_regular(path, encoding="utf-8") as f:
        return json.load(f)


def shown(text):
    """TEXT printable as UTF-8: a name in bytes that are not UTF-8
    (surrogate escapes) or a lone surrogate from JSON becomes U+FFFD."""
    try:
        raw = text.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:
        raw = text.encode("utf-8", "replace")
    return raw.decode("utf-8", "replace")


class Run:
    """One run of the store: run.json's facts and its sets' figures."""

    def __init__(self, dirname, path, meta):
        self.dirname = dirname  # the directory's name as the file system has it
        self.name = shown(dirname)
        self.path = path
        self.meta = meta
        self.date = shown(str(meta.get("date", "")))
        self.commit = shown(str(meta.get("commit", "unknown")))
        self.short = shown(str(meta.get("commit_short", self.commit[:7])))
        self.dirty = meta.get("dirty", False) is True
        self.host = shown(str(meta.get("host", "")))
        self.status = meta.get("status")
        self.status_text = shown(str(meta.get("status_text", "")))
        self.stage = shown(str(meta.get("stage", "")))
        self.seconds = meta.get("seconds")
        self.sets = {}      # set name -> {method: figures dict}
        self.machine = {}   # set name -> machine key of its timings
        self.problems = []  # warnings about this run's files
        self.files = []     # its regular files, relative to path (scan_files)

    def flag(self, text, warn):
        """A problem of this run: on the page and a warning."""
        self.problems.append(shown(text))
        warn(text)


def load_store(store, warn):
    """The runs of STORE in run order (date, then name); warn(text) is
    called for every problem."""
    runs = []
    for name in sorted(os.listdir(store)):
        path = os.path.join(store, name)
        if name.startswith("."):
            continue
        try:
            st = os.lstat(path)
        except OSError as e:
            warn("%s (left out)" % e)
            continue
        if stat.S_ISLNK(st.st_mode):
            warn("%s: a symbolic link, not a run (the report follows no link; left out)" % path)
            continue
        mfile = os.path.join(path, "run.json")
        if not stat.S_ISDIR(st.st_mode) or not os.path.lexists(mfile):
            continue  # not a run (the report's site, say)
        try:
            meta = load_json(mfile)
            if not isinstance(meta, dict):
                raise ValueError("not a JSON object")
        except (OSError, ValueError, RecursionError) as e:
            warn("%s (run left out)" % (e if isinstance(e, OSError) else "%s: %s" % (mfile, e)))
            continue
        run = Run(name, path, meta)
        scan_files(run, warn)
        for s in set_names(run):
            load_set(run, s, warn)
        runs.append(run)
    runs.sort(key=lambda r: (r.date, r.name))
    return runs


def scan_files(run, warn):
    """Fills run.files with the run directory's regular files (paths
    relative to it, sorted), through its subdirectories.  Every other entry
    (a symbolic link, a FIFO, a device, a socket) and every directory that
    cannot be read is flagged and left alone: never followed, never read."""
    todo = [""]
    while todo:
        rel = todo.pop()
        d = os.path.join(run.path, rel) if rel else run.path
        try:
            with os.scandir(d) as it:
                entries = sorted(it, key=lambda e: e.name)
        except OSError as e:
            run.flag("%s (its files left out)" % e, warn)
            continue
        for e in entries:
            r = os.path.join(rel, e.name) if rel else e.name
            try:
                mode = e.stat(follow_symlinks=False).st_mode
            except OSError as ex:
                run.flag("%s (skipped)" % ex, warn)
                continue
            if stat.S_ISDIR(mode):
                todo.append(r)
            elif stat.S_ISREG(mode):
                run.files.append(r)
            else:
                run.flag("%s (skipped)" % NotRegular(e.path, kind_of(mode)), warn)
    run.files.sort()


def set_names(run):
    """The run sets of a run: subdirectories with a results.csv (a regular
    file), published and random first."""
    names = [os.path.dirname(f) for f in run.files
             if os.path.basename(f) == "results.csv" and os.path.dirname(f)
             and os.path.dirname(os.path.dirname(f)) == ""]
    return sorted(names, key=lambda n: (SET_ORDER.index(n) if n in SET_ORDER else len(SET_ORDER), n))


def load_set(run, s, warn):
    """Reads run/s/results.csv (and samples.csv or fits.csv, meta.json) into
    run.sets[s].  A method's time is its own fit time (method_ns: run
    --time-fits, its rounds in fits.csv) where the run has it, else
    fit_ns + eval_ns (its repetitions in samples.csv); the "harness" line
    is eval_ns over every row (offbench's measuring), per repetition.  What
    is timed enters the jobs hash: a switch is a "jobs" mark, not a step."""
    d = os.path.join(run.path, s)
    try:
        methods = read_results(os.path.join(d, "results.csv"))
        timed = any(m["method_ns"] for m in methods.values())
        if timed:
            for m in methods.values():
                m["time_ns"] = m["method_ns"]
            if os.path.join(s, "fits.csv") in run.files:
                read_fits(os.path.join(d, "fits.csv"), methods)
        if os.path.join(s, "samples.csv") in run.files:
            read_samples(os.path.join(d, "samples.csv"), methods, timed)
    except (OSError, ValueError, csv.Error) as e:
        run.flag("%s (run set left out)" % e, warn)
        return
    for name, m in methods.items():
        what = "harness" if name == HARNESS else "method_ns" if timed else "fit_ns+eval_ns"
        m["jobs"] = hashlib.sha1("\n".join(sorted(m["jobs"]) + [what]).encode()).hexdigest()[:12]
        tot = sorted(m.pop("reps").values())
        m["rep_totals"] = tot
        m["iqr_ns"] = iqr(tot) if len(tot) >= 2 else None
    run.sets[s] = methods
    run.machine[s] = machine_key(run, s, warn)


def read_results(path):
    """Per method: rows, ctrl (summed ctrl_points), ok/limit/fail/timeout/
    skip counts, time_ns (fit_ns + eval_ns summed), jobs (a hash of the
    job keys).  Raises ValueError naming FILE:LINE on bad content."""
    methods = {}
    for row, col, line in csv_rows(path, NEEDED, True):
        m = methods.setdefault(row[col["method"]], new_method())
        add_row(m, row, col, path, line)
        h = methods.setdefault(HARNESS, new_method())
        h["rows"] += 1
        h["time_ns"] += number(row[col["eval_ns"]], "eval_ns", path, line, int)
        h["jobs"].append("|".join(row[col[k]] for k in KEY))
    return methods


def csv_rows(path, needed, whole_list, empty_is_error=True):
    """The non-empty rows of the CSV file PATH as (row, col, line), col
    mapping each header name to its index.  ValueError naming FILE:LINE for
    an empty file (when EMPTY_IS_ERROR), a header without the NEEDED names
    (all of them listed when WHOLE_LIST, else the first), or a row with
    another field count than the header."""
    with open_regular(path, newline="", encoding="utf-8") as f:
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


# The harness's line among the methods: eval_ns, offbench's own measuring.
HARNESS = "(harness)"


def new_method():
    return {"rows": 0, "ctrl": 0, "ok": 0, "limit": 0, "fail": 0, "timeout": 0, "skip": 0,
            "time_ns": 0, "method_ns": 0, "jobs": [], "reps": {}}


def add_row(m, row, col, path, line):
    """Adds one results.csv row to its method's figures."""
    m["rows"] += 1
    st = row[col["status"]]
    if st in ("ok", "limit", "fail", "timeout", "skip"):
        m[st] += 1
    m["ctrl"] += number(row[col["ctrl_points"]], "ctrl_points", path, line, int)
    m["time_ns"] += (number(row[col["fit_ns"]], "fit_ns", path, line, int)
                     + number(row[col["eval_ns"]], "eval_ns", path, line, int))
    if "method_ns" in col:  # run --time-fits: the method's own fit time
        m["method_ns"] += number(row[col["method_ns"]], "method_ns", path, line, float)
    m["jobs"].append("|".join(row[col[k]] for k in KEY if k != "method"))


def number(text, name, path, line, kind):
    """TEXT as a number (empty: 0); ValueError naming FILE:LINE otherwise."""
    if text == "":
        return 0
    try:
        return kind(text)
    except ValueError:
        raise ValueError("%s:%d: %s is '%s', not a number" % (path, line, name, text)) from None


def read_samples(path, methods, timed=False):
    """Adds each repetition's method total (fit_ns + eval_ns over the
    method's rows; not where TIMED: fits.csv has those) and the harness's
    (eval_ns over every row) from samples.csv."""
    for row, col, line in csv_rows(path, ("method", "rep", "fit_ns", "eval_ns"), False, False):
        rep = row[col["rep"]]
        ev = number(row[col["eval_ns"]], "eval_ns", path, line, int)
        h = methods.get(HARNESS)
        if h is not None:
            h["reps"][rep] = h["reps"].get(rep, 0) + ev
        m = methods.get(row[col["method"]])
        if m is None or timed:
            continue
        m["reps"][rep] = m["reps"].get(rep, 0) + number(row[col["fit_ns"]], "fit_ns", path, line, int) + ev


def read_fits(path, methods):
    """Adds each round's method total (method_ns over the method's timed
    rows) from fits.csv (run --time-fits)."""
    for row, col, line in csv_rows(path, ("method", "round", "method_ns"), False, False):
        m = methods.get(row[col["method"]])
        if m is not None:
            r = row[col["round"]]
            m["reps"][r] = m["reps"].get(r, 0) + number(row[col["method_ns"]], "method_ns", path, line, float)


def iqr(values):
    """The interquartile range of VALUES (quartiles by linear interpolation,
    statistics.quantiles' inclusive method)."""
    if len(values) < 2:
        return 0
    q = statistics.quantiles(values, n=4, method="inclusive")
    return q[2] - q[0]


def machine_key(run, s, warn):
    """What must match for two runs' timings to be compared: the host, and
    the CPU model, thread count and backend of set S's meta.json (when it
    is a regular file; one that cannot be read or parsed is flagged)."""
    meta = {}
    if os.path.join(s, "meta.json") in run.files:
        path = os.path.join(run.path, s, "meta.json")
        try:
            meta = load_json(path)
            if not isinstance(meta, dict):
                raise ValueError("not a JSON object")
        except (OSError, ValueError, RecursionError) as e:
            run.flag("%s: %s (its machine unknown: timings compared with no other run)" % (path, e), warn)
            return "%s|unreadable %s" % (run.host, path)
    return "%s|%s|%s|%s" % (run.host, meta.get("cpu_model", ""), meta.get("omp_threads", ""),
                            meta.get("backend", ""))
