#!/usr/bin/env python3
"""worker_rows.py RESULTS.csv RATIONAL_CURVES RATIONAL_METHODS: each method
M of a run beside M_w (`offbench worker M` registered as an external
method, tests/e2e/e2e_worker.sh): the same rows.

Exact, every column but the timings, where the protocol carries the
arithmetic exactly: polynomial pieces both ways (Euclidean points with 17
digits read back to the same doubles, weights 1).  Where a piece is
rational (a rational curve sent, a rational method's answer) the protocol's
Euclidean points are x = X/w, rebuilt as x*w: the rows agree to rounding
(relative 1e-7, absolute 1e-12), not bit for bit: the ulps of the
round trip, which an iterative fit (hoschek's) amplifies to some 1e-9.  A row the protocol
refuses (a weight <= 0 in an answer) must say so in its message.
Prints one line per method and exits 1 on any other difference."""
import csv
import sys

TIMING = {"fit_ns", "eval_ns", "time_iqr_ns", "time_cv", "cert_ns", "method_ns", "method_iqr_ns"}


def close(a, b):
    try:
        x, y = float(a), float(b)
    except ValueError:
        return a == b
    return abs(x - y) <= 1e-7 * max(abs(x), abs(y)) + 1e-12


def main():
    rows = list(csv.DictReader(open(sys.argv[1], newline="")))
    rat_curves = set(filter(None, sys.argv[2].split(",")))
    rat_methods = set(filter(None, sys.argv[3].split(",")))
    key = {(r["method"], r["curve"], r["d"], r["tol"]): r for r in rows}
    methods = sorted({r["method"] for r in rows if not r["method"].endswith("_w")})
    bad = 0
    for m in methods:
        n = exact = near = refused = 0
        for (mm, c, d, t), r in key.items():
            if mm != m:
                continue
            n += 1
            w = key.get((m + "_w", c, d, t))
            cols = [k for k in r if k not in TIMING and k != "method"]
            if w is None:
                print(f"FAIL {m} {c} {d} {t}: no row of {m}_w")
                bad += 1
            elif all(r[k] == w[k] for k in cols):
                exact += 1
            elif (c in rat_curves or m in rat_methods) and all(close(r[k], w[k]) for k in cols if k != "message"):
                near += 1
            elif w["status"] == "fail" and '"weights" is not' in w["message"]:
                refused += 1
            else:
                diff = [(k, r[k], w[k]) for k in cols if r[k] != w[k]][:4]
                print(f"FAIL {m} {c} {d} {t}: {diff}")
                bad += 1
        print(f"{m}: {n} rows, {exact} the same, {near} the same to rounding (rational), "
              f"{refused} refused by the protocol (a weight <= 0)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
