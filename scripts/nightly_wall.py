#!/usr/bin/python3
"""nightly_wall.py - how long a nightly took, per stage, from a finished
night's output directory (docs/nightly.md "How long a night takes and how to
size it", whose figures `make docs` quotes from the file this writes).

Usage: scripts/nightly_wall.py OUT [--out FILE]     (make nightly-wall NIGHTLY_OUT=OUT)

Reads OUT/timings.csv (scripts/nightly.sh: each stage's wall seconds, then
the total), OUT/status and the runs' meta.json (OUT/published, OUT/random:
the machine, the backend, the jobs, the configuration from the runs' own
command lines), and writes FILE (default results/baseline/nightly_wall.txt)
as `key: value` lines:

  configuration   full (the nightly's defaults: every curve under datasets/,
                  every method, --random 250:2026) or small
  config          the options that made it (--curve, --methods, --random)
  measured, commit, machine, backend, threads, load_max
  published_jobs, published_runs (the warm-up and the --reps runs),
  random_jobs, random_set
  seconds_build   the build (absent: not built, NIGHTLY_BIN)
  seconds_run_published, seconds_run_random, seconds_compare (every
  compare), seconds_reruns (the re-runs of noisy methods and their
  compares), seconds_report, seconds_total (up to the history store)

A night that failed (status 2, or killed) is refused: its stages are not
those of a night.  Exit 0 written, 2 refused or unreadable (said on stderr).
Python 3 standard library only.
"""
import csv
import json
import os
import sys

FULL = {"curves": "all", "methods": "all", "random": "250:2026"}


def die(msg):
    print("nightly_wall: " + msg, file=sys.stderr)
    sys.exit(2)


def read_meta(out, name):
    path = os.path.join(out, name, "meta.json")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        die("%s: %s" % (path, e))


def arg_of(meta, flag, default):
    """the value of FLAG on the run's own command line (meta.json argv)"""
    argv = meta.get("argv") or []
    for i, a in enumerate(argv[:-1]):
        if a == flag:
            return argv[i + 1]
    return default


def stage_seconds(out):
    """the stages of OUT/timings.csv summed into the file's groups"""
    path = os.path.join(out, "timings.csv")
    try:
        with open(path, encoding="utf-8", newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        die("%s: %s (a night of a nightly.sh that records its stages is needed)" % (path, e.strerror))
    sums = {}
    for r in rows:
        stage, secs = r.get("stage") or "", float(r.get("seconds") or 0)
        if "(killed by " in stage:
            die("%s: the night was killed (%s): not a whole night" % (path, stage))
        rerun = "reruns/" in stage or "timing-rerun" in stage
        key = ("reruns" if rerun else "run_" + stage[4:] if stage.startswith("run ") else
               "compare" if stage.startswith("compare ") else stage.replace(" ", "_"))
        sums[key] = sums.get(key, 0.0) + secs
    for need in ("run_published", "run_random", "total"):
        if need not in sums:
            die("%s: no '%s' line: not a whole night" % (path, need.replace("_", " ", 1)))
    return sums


def describe(out):
    """the configuration and the machine of the night in OUT"""
    pub, rnd = read_meta(out, "published"), read_meta(out, "random")
    conf = {"curves": arg_of(pub, "--curve", "all"), "methods": arg_of(pub, "--methods", "all"),
            "random": arg_of(rnd, "--random", "?")}
    m = pub.get("machine") or {}
    host = pub.get("host") or {}
    device = (pub.get("opencl") or {}).get("device")
    commit = str(pub.get("git_commit", "unknown"))[:12] + (" (dirty)" if pub.get("git_dirty") else "")
    return [
        ("configuration", "full" if conf == FULL else "small"),
        ("config", "--curve %s, --methods %s, --random %s" % (conf["curves"], conf["methods"], conf["random"])),
        ("measured", pub.get("timestamp", "unknown")),
        ("commit", commit),
        ("machine", "%s, %s logical cores, %s MiB" % (m.get("cpu_model", pub.get("cpu_model", "?")),
                                                      m.get("logical_cores", "?"), m.get("memory_mib", "?"))),
        ("backend", pub.get("backend", "?") + (" (%s)" % device if device else "")),
        ("threads", pub.get("omp_threads", "?")),
        ("load_max", host.get("loadavg_max", "?")),
        ("published_jobs", pub.get("jobs", "?")),
        ("published_runs", (pub.get("reps") or 1) + (1 if pub.get("warmup") else 0)),
        ("random_jobs", rnd.get("jobs", "?")),
        ("random_set", conf["random"]),
    ]


def main(argv):
    args, dest = [], os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "results", "baseline",
                                  "nightly_wall.txt")
    i = 0
    while i < len(argv):
        if argv[i] == "--out" and i + 1 < len(argv):
            dest, i = argv[i + 1], i + 2
        elif argv[i] in ("-h", "--help"):
            print(__doc__)
            return 0
        else:
            args, i = args + [argv[i]], i + 1
    if len(args) != 1:
        die("usage: nightly_wall.py OUT [--out FILE] (see --help)")
    out = args[0]
    try:
        status = open(os.path.join(out, "status"), encoding="utf-8").read().strip()
    except OSError:
        die("%s/status: no finished nightly in %s" % (out, out))
    if status not in ("0", "1", "3"):
        die("%s: the night failed (status %s): not a whole night" % (out, status))
    lines = describe(out) + [("seconds_" + k, "%.1f" % v) for k, v in sorted(stage_seconds(out).items())]
    text = ("# The wall time of one nightly (scripts/nightly.sh) per stage, in seconds, written by\n"
            "# scripts/nightly_wall.py from its output directory (make nightly-wall NIGHTLY_OUT=DIR);\n"
            "# make docs quotes it in docs/nightly.md.  Regenerate it from a full night.\n"
            + "".join("%s: %s\n" % kv for kv in lines))
    tmp = dest + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, dest)
    print("nightly_wall: wrote %s (%s configuration)" % (dest, dict(lines)["configuration"]), file=sys.stderr)
    return 0


sys.exit(main(sys.argv[1:]))
