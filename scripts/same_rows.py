#!/usr/bin/env python3
"""same_rows.py A/results.csv B/results.csv - are two runs' rows the same,
timing columns aside?  (Engines, thread counts, chunk sizes and devices must
never change a row: docs/performance.md "Engines".)

Rows are matched by their job key (curve, d, method, metric, split, tol);
every other column except the timings (fit_ns, eval_ns, time_iqr_ns,
time_cv, cert_ns, method_ns, method_iqr_ns) must be equal as text, so max_err is compared to the last bit.
Prints "N rows, M differ" and up to --show differing rows; exit 0 when none
differ and both runs have the same jobs, 1 when some do, 2 on bad input."""
import csv
import sys

TIMING = {"fit_ns", "eval_ns", "time_iqr_ns", "time_cv", "cert_ns", "method_ns", "method_iqr_ns"}
KEY = ("curve", "d", "method", "metric", "split", "tol")


def rows(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            r = csv.reader(f)
            header = next(r, None)
            if header is None or any(k not in header for k in KEY):
                sys.exit(f"same_rows.py: {path}:1: not a results.csv header")
            out = {}
            for line, rec in enumerate(r, 2):
                if len(rec) != len(header):
                    sys.exit(f"same_rows.py: {path}:{line}: {len(rec)} fields, header has {len(header)}")
                d = dict(zip(header, rec))
                out[tuple(d[k] for k in KEY)] = d
            return header, out
    except OSError as e:
        print(f"same_rows.py: cannot read {path}: {e.strerror}", file=sys.stderr)
        sys.exit(2)


def main(argv):
    show = 5
    args = [a for a in argv if not a.startswith("--show=")]
    for a in argv:
        if a.startswith("--show="):
            show = int(a.split("=", 1)[1])
    if len(args) != 2:
        print(__doc__.split("\n\n")[0], file=sys.stderr)
        return 2
    ha, a = rows(args[0])
    hb, b = rows(args[1])
    cols = [c for c in ha if c in hb and c not in TIMING and c not in KEY]
    differ = []
    for k, ra in a.items():
        rb = b.get(k)
        if rb is None:
            differ.append((k, "missing in " + args[1]))
            continue
        bad = [f"{c}: {ra[c]} vs {rb[c]}" for c in cols if ra[c] != rb[c]]
        if bad:
            differ.append((k, "; ".join(bad)))
    for k in b:
        if k not in a:
            differ.append((k, "missing in " + args[0]))
    print(f"{len(a)} rows, {len(differ)} differ")
    for k, why in differ[:show]:
        print("  " + ",".join(k) + ": " + why)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
