#!/bin/sh
# cert_cost.sh - what `run --certify` costs and how tight it is (issue 47),
# ratios taken in one session on one machine, written as markdown for
# docs/certified.md (make docs quotes results/certify/cert_cost.md).
#
#   scripts/cert_cost.sh [OUT.md]     (default results/certify/cert_cost.md)
#
# Measures, each run alternating with its reference so that a change of
# load hits both (REPS rounds, medians; 2 threads, the CPU backend):
#   1. the default job (`make run`'s 2,070 jobs, 1e-1 .. 1e-5): without
#      --certify, with it (the verdict), and, when OLD_BIN names an older
#      build (e.g. the main before issue 47), that build with its --certify;
#   2. a tenth of the nightly's random set (--random 25:2026, all methods,
#      1e-1 .. 1e-5): without and with --certify;
#   3. --certify=tight on --random 200:7 --methods all --tols 1e-3 (once):
#      err_upper / err_lower on the ok jobs, and its cost.
# Environment: OFFBENCH (default ./offbench), REPS (default 3), OLD_BIN,
# THREADS (default 2), SKIP_TIGHT=1 (leave 3 out).
# Timings on a shared machine move with its load: the load average is
# printed beside them, and only ratios taken in the same rounds are quoted.
set -eu
OB=${OFFBENCH:-./offbench}
REPS=${REPS:-3}
THREADS=${THREADS:-2}
OUT=${1:-results/certify/cert_cost.md}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
PY=$(command -v python3)

# wall seconds of one run (its arguments), its stderr kept in $T/last.err
wall() {
    s=$(date +%s.%N)
    "$@" >/dev/null 2>"$T/last.err" || { cat "$T/last.err" >&2; exit 1; }
    e=$(date +%s.%N)
    awk -v a="$s" -v b="$e" 'BEGIN { printf "%.2f", b - a }'
}
median() { tr ' ' '\n' | grep . | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# pair NAME ARGS...: REPS rounds of (without, with --certify), medians
pair() {
    name=$1; shift
    plain= cert= old=
    for r in $(seq "$REPS"); do
        plain="$plain $(wall "$OB" run "$@" --threads "$THREADS" --backend cpu --out "$T/p" --force)"
        cert="$cert $(wall "$OB" run "$@" --threads "$THREADS" --backend cpu --out "$T/c" --force --certify)"
        if [ -n "${OLD_BIN:-}" ]; then
            old="$old $(wall "$OLD_BIN" run "$@" --threads "$THREADS" --backend cpu --out "$T/o" --force --certify)"
        fi
    done
    mp=$(echo "$plain" | median) mc=$(echo "$cert" | median)
    line="| $name | $mp s | $mc s | $(awk -v a="$mc" -v b="$mp" 'BEGIN { printf "%.2f", a / b }') x |"
    if [ -n "${OLD_BIN:-}" ]; then
        mo=$(echo "$old" | median)
        line="$line $mo s | $(awk -v a="$mo" -v b="$mp" 'BEGIN { printf "%.1f", a / b }') x |"
    fi
    echo "$line"
    # the verdicts: every job with an approximation decided
    "$PY" - "$T/c/results.csv" <<'EOF' >>"$T/verdicts.txt"
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["err_upper"] != ""]
yes = sum(r["certified"] == "yes" for r in rows)
over = sum(float(r["err_lower"]) > float(r["tol"]) for r in rows)
und = len(rows) - yes - over
ok = [r for r in rows if r["status"] == "ok"]
oky = sum(r["certified"] == "yes" for r in ok)
print(f"{len(rows)} jobs certified: {yes} within tol (err_upper <= tol), {over} over it (err_lower > tol), "
      f"{und} undecided; of the {len(ok)} ok jobs, {oky} certified within tol")
EOF
}

load() { awk '{ print $1 }' /proc/loadavg 2>/dev/null || echo "?"; }
commit=$(git rev-parse --short HEAD 2>/dev/null || echo "?")
{
    echo "Measured by \`scripts/cert_cost.sh\` at commit $commit on $(nproc) CPUs ($THREADS threads, CPU backend),"
    echo "$REPS rounds alternating, medians; load average $(load) at the start."
    echo
    if [ -n "${OLD_BIN:-}" ]; then
        echo "| run | without --certify | --certify | ratio | old build's --certify | ratio |"
        echo "|---|---:|---:|---:|---:|---:|"
    else
        echo "| run | without --certify | --certify | ratio |"
        echo "|---|---:|---:|---:|"
    fi
} >"$T/out.md"
pair "default job (2,070 jobs)" >>"$T/out.md"
pair "random 25:2026, all methods, 1e-1 .. 1e-5" --random 25:2026 --methods all \
    --tols 1e-1,1e-2,1e-3,1e-4,1e-5 >>"$T/out.md"
{
    echo
    echo "Load average $(load) at the end.  Verdicts (the last --certify of each row):"
    echo
    sed 's/^/- /' "$T/verdicts.txt"
} >>"$T/out.md"

if [ "${SKIP_TIGHT:-0}" != 1 ]; then
    tp=$(wall "$OB" run --random 200:7 --methods all --tols 1e-3 --threads "$THREADS" --backend cpu --out "$T/tp" --force)
    tc=$(wall "$OB" run --random 200:7 --methods all --tols 1e-3 --threads "$THREADS" --backend cpu --out "$T/tc" --force --certify=tight)
    vc=$(wall "$OB" run --random 200:7 --methods all --tols 1e-3 --threads "$THREADS" --backend cpu --out "$T/vc" --force --certify)
    "$PY" - "$T/tc/results.csv" "$tp" "$tc" "$vc" <<'EOF' >>"$T/out.md"
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["err_upper"] != ""]
ok = [r for r in rows if r["status"] == "ok"]
def ratio(r):
    u, l = float(r["err_upper"]), float(r["err_lower"])
    if u <= 1e-9:
        return 1.0  # round-off: exact and near-exact results count as tight
    return u / l if l > 0 else float("inf")
rs = sorted(ratio(r) for r in ok)
n = len(rs)
w101 = sum(x <= 1.01 for x in rs)
w11 = sum(x <= 1.1 for x in rs)
cert = sorted(float(r["cert_ns"]) for r in ok)
lim = sorted(float(r["cert_ns"]) for r in rows if r["status"] == "limit")
med = lambda v: v[len(v) // 2] if v else float("nan")
tp, tc, vc = map(float, sys.argv[2:5])
print()
print("`--certify=tight` on `--random 200:7 --methods all --tols 1e-3`:")
print()
print(f"| ok jobs | err_upper / err_lower <= 1.01 | <= 1.1 | largest | median cert_ns, ok | median cert_ns, limit |")
print(f"|---:|---:|---:|---:|---:|---:|")
print(f"| {n} | {w101} ({100.0 * w101 / n:.2f} %) | {w11} ({100.0 * w11 / n:.2f} %) | {rs[-1]:.4g} | "
      f"{med(cert) / 1e6:.1f} ms | {med(lim) / 1e6:.1f} ms |")
print()
print(f"Wall: without --certify {tp:.1f} s, --certify {vc:.1f} s ({vc / tp:.2f} x), --certify=tight {tc:.1f} s "
      f"({tc / tp:.1f} x).  Round-off results (err_upper <= 1e-9) count as tight.")
EOF
fi
mkdir -p "$(dirname "$OUT")"
cp "$T/out.md" "$OUT"
cat "$OUT"
