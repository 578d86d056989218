#!/usr/bin/python3
"""archive_join.py - the archive beside a run, for scripts/plot.py --archive
(the same join as `./offbench summary RUN --archive ARCHIVE`, docs/output.md
"Compare against the archive").

An ARCHIVE is a run directory, a results.csv, or a directory of run
directories (results/baseline-small).  The rows of an archived run join the
run's on the job (curve, d, tol) under the run's one metric and split, for
the methods the run did not run itself; every row that cannot join is
counted by reason, in the summary's own words.  An archive that shares jobs
with the run but none of its metric and split is refused (exit 2, naming
both files): its numbers would not mean the same.  The full comparability
checks (samples per segment, seed, method versions, kernel text: compare's)
are not repeated here: the program's own summary makes them
(offbench_checks: $OFFBENCH, else ./offbench at the repository's root), and
without a program a note says only metric and split were checked.

Usage: archive_join.py RUN ARCHIVE...   prints the joined archive rows as
CSV (curve,d,tol,method,source,status,ctrl_points) and the report's lines on
standard error: the data plot.py --archive draws, for checking.
"""
import csv
import os
import subprocess
import sys

import csvrows  # scripts/csvrows.py, beside this file

COLUMNS = ("curve", "d", "method", "metric", "split", "tol", "ctrl_points", "status")
TAG = " (archive)"


def die(msg):
    print(f"archive_join: {msg}", file=sys.stderr)
    sys.exit(2)


def expand(arg, die=die):
    """The results.csv files ARCHIVE stands for: itself, DIR/results.csv, or
    the runs in DIR's subdirectories (name order)."""
    if not os.path.isdir(arg) or os.path.isfile(os.path.join(arg, "results.csv")):
        path = os.path.join(arg, "results.csv") if os.path.isdir(arg) else arg
        if not os.path.isfile(path):
            die(f"--archive: {arg}: no such run directory or results.csv")
        return [path]
    runs = [os.path.join(arg, n, "results.csv") for n in sorted(os.listdir(arg))
            if not n.startswith(".") and os.path.isfile(os.path.join(arg, n, "results.csv"))]
    if not runs:
        die(f"--archive: {arg}: no results.csv in it nor in its subdirectories")
    return runs


def job(r):
    return (r["curve"], float(r["d"]), float(r["tol"]))


class Join:
    """The run's jobs and what the archives gave them so far."""

    def __init__(self, run_rows, run_path):
        combos = sorted({(r["metric"], r["split"]) for r in run_rows})
        if len(combos) != 1:
            die(f"--archive: {run_path} holds several metrics or splits "
                f"({'; '.join(', '.join(c) for c in combos)}): the archive joins one")
        (self.metric, self.split), self.run_path = combos[0], run_path
        self.jobs = {job(r) for r in run_rows}
        self.own = {r["method"] for r in run_rows}
        self.run_rows = run_rows
        self.taken, self.hit, self.columns = set(), set(), set()
        self.rows, self.lines = [], []

    def row(self, r, c):
        """One archive row into the drawn rows, or into a count of why not."""
        if (r["metric"], r["split"]) != (self.metric, self.split):
            c["other"] += 1
            return
        j = job(r)
        if j in self.jobs:
            self.hit.add(j)
        if r["method"] in self.own:
            c["own"] += 1
            c["own_names"] = c["own_names"] or []
            if r["method"] not in c["own_names"]:
                c["own_names"].append(r["method"])
        elif j not in self.jobs:
            c["not_run"] += 1
        elif (r["method"], j) in self.taken:
            c["dup"] += 1
        else:
            self.taken.add((r["method"], j))
            c["added"] += r["method"] not in self.columns
            self.columns.add(r["method"])
            self.rows.append(dict(r, method=r["method"] + TAG, source=c["path"]))
            c["joined"] += 1

    def archive(self, path, read):
        """Joins one archived run (its rows by read(path)); refuses one that
        shares jobs but not the run's metric and split."""
        rows = read(path)
        if not any(job(r) in self.jobs for r in rows):
            self.lines.append(f"Not joined: {path}: no job in common with RUN ({len(rows)} rows).")
            return
        if not any((r["metric"], r["split"]) == (self.metric, self.split) for r in rows):
            theirs = sorted({f"{r['metric']}, {r['split']}" for r in rows})
            die(f"--archive: {path} is not comparable with {self.run_path}: metric and split "
                f"{'; '.join(theirs)} vs {self.metric}, {self.split}")
        c = dict(path=path, joined=0, added=0, other=0, own=0, own_names=None, not_run=0, dup=0)
        for r in rows:
            self.row(r, c)
        self.lines += report(c, self.metric, self.split)

    def done(self):
        """The run's rows no archive has a job of, and the timing caveat."""
        if not self.columns and not self.hit:
            return
        self.lines.append("The archived methods' time/job is the archive's own (its machine and backend, in "
                          "its meta.json): ./offbench compare says whether times compare.")
        lost = [r for r in self.run_rows if job(r) not in self.hit]
        if lost:
            tols = sorted({r["tol"] for r in lost}, reverse=True)
            self.lines.append(f"Not joined: {len(lost)} RUN rows have no archived job (curve, d, tol); at "
                              f"tolerances {', '.join(f'{t:g}' for t in tols)}.")


def report(c, metric, split):
    """The summary's lines for one archive (host/summary/summary_archive.c)."""
    p = c["path"]
    out = [f"Archive: {p} (metric {metric}, split {split}): {c['added']} methods beside the run's, "
           f"{c['joined']} rows joined."]
    if c["not_run"]:
        out.append(f"Not joined: {c['not_run']} archive rows are on jobs RUN did not run (curve, d, tol) in {p}.")
    if c["own"]:
        out.append(f"Not joined: {c['own']} archive rows are of methods RUN ran itself "
                   f"({','.join(c['own_names'])}): RUN's values shown ({p}).")
    if c["other"]:
        out.append(f"Not joined: {c['other']} archive rows are of another metric or split than RUN's "
                   f"({metric}, {split}): not comparable ({p}).")
    if c["dup"]:
        out.append(f"Not joined: {c['dup']} archive rows repeat a job an earlier archive gave: the first kept ({p}).")
    return out


def offbench_checks(run_path, archive_args, note):
    """compare's comparability checks, by `offbench summary --archive`
    itself: exits 2 with its message where it refuses."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    exe = os.environ.get("OFFBENCH") or os.path.join(root, "offbench")
    if not os.access(exe, os.X_OK):
        note(f"--archive: no offbench program ({exe}): only the metric and split were checked, "
             "not compare's other checks")
        return
    cmd = [exe, "summary", run_path, "--sections", "methods", "--format", "csv"]
    for a in archive_args:
        cmd += ["--archive", a]
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        die(p.stderr.strip().splitlines()[-1] if p.stderr.strip() else f"{exe} summary exited {p.returncode}")


def read_rows(path):
    """The columns the join needs (plot.py passes its own reader: all it draws)."""
    return csvrows.read_csv(path, COLUMNS, ("d", "tol", "ctrl_points"), integer=("ctrl_points",), die=die)


def join(run_rows, run_path, archive_args, read=read_rows):
    """The archived rows to draw beside run_rows (method "m (archive)",
    source: its results.csv) and the report's lines."""
    j = Join(run_rows, run_path)
    paths = [path for arg in archive_args for path in expand(arg)]
    offbench_checks(run_path, archive_args, lambda m: print(f"archive_join: {m}", file=sys.stderr))
    for path in paths:
        j.archive(path, read)
    j.done()
    return j.rows, j.lines


def main(argv):
    if len(argv) < 3:
        die("usage: archive_join.py RUN ARCHIVE...")
    run = expand(argv[1])[0]
    rows, lines = join(read_rows(run), run, argv[2:])
    for line in lines:
        print(line, file=sys.stderr)
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(("curve", "d", "tol", "method", "source", "status", "ctrl_points"))
    for r in rows:
        w.writerow((r["curve"], repr(r["d"]), repr(r["tol"]), r["method"], r["source"], r["status"],
                    "" if r["ctrl_points"] is None else r["ctrl_points"]))


if __name__ == "__main__":
    main(sys.argv)
