#!/bin/sh
# End-to-end tests of scripts/plot.py --archive ARCHIVE (issue 49): the
# archived methods drawn beside a small run's on its jobs, and the rows that
# could not join said in the same lines as `offbench summary --archive`.
# The joined data (scripts/archive_join.py, what plot.py draws) is checked
# against a direct join in this script; the drawing needs /usr/bin/python3
# with matplotlib, without it those checks count as skipped.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PLOT=$ROOT/scripts/plot.py
JOIN=$ROOT/scripts/archive_join.py
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
A=$ROOT/results/baseline-small

$OB run --random 3:2026 --methods tiller --tols 1e-1,1e-2,1e-6 --metric hausdorff --split mid --threads 2 \
    --out "$T/r" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/r/results.csv" ]' "offbench run --random 3:2026 --methods tiller"

# --- the joined data against a direct join here ---
OFFBENCH=$OB "$PY" "$JOIN" "$T/r/results.csv" "$A" >"$T/j.csv" 2>"$T/j.err"
check '[ $? -eq 0 ]' "archive_join.py RUN ARCHIVE exits 0: $(head -c 300 "$T/j.err")"
"$PY" - "$T/r/results.csv" "$A/random/results.csv" "$T/j.csv" <<'PYEOF' >"$T/ref.txt" 2>&1
import csv, sys
run = list(csv.DictReader(open(sys.argv[1])))
arc = list(csv.DictReader(open(sys.argv[2])))
got = list(csv.DictReader(open(sys.argv[3])))
job = lambda r: (r["curve"], float(r["d"]), float(r["tol"]))
jobs, own = {job(r) for r in run}, {r["method"] for r in run}
want = sorted((job(r) + (r["method"] + " (archive)", r["status"], r["ctrl_points"])) for r in arc
              if r["metric"] == "hausdorff" and r["split"] == "mid" and r["method"] not in own and job(r) in jobs)
have = sorted((job(r) + (r["method"], r["status"], r["ctrl_points"])) for r in got)
print("same" if want == have and want else f"differ: {len(want)} wanted, {len(have)} joined")
PYEOF
check 'grep -qx same "$T/ref.txt"' "the joined rows are the direct join's: $(cat "$T/ref.txt")"
$OB summary "$T/r" --archive "$A" --sections methods | grep -E "^(Archive|Not joined|The archived)" >"$T/sum.txt"
check '[ -s "$T/sum.txt" ] && cmp -s "$T/sum.txt" "$T/j.err"' \
    "plot's join says what the summary says: $(diff "$T/sum.txt" "$T/j.err" | head -5)"

# --- refusals, before any drawing ---
mkdir -p "$T/m"
sed 's/,hausdorff,mid,/,normal,mid,/' "$A/random/results.csv" >"$T/m/results.csv"
"$PY" "$JOIN" "$T/r/results.csv" "$T/m" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "not comparable" "$T/e.txt" && grep -qF "$T/m/results.csv" "$T/e.txt" && grep -qF "$T/r/results.csv" "$T/e.txt"' \
    "another metric: refused naming both files: $(cat "$T/e.txt")"
mkdir -p "$T/s"
cp "$A/random/results.csv" "$T/s/"
sed 's/"samples_per_segment": 256/"samples_per_segment": 128/' "$A/random/meta.json" >"$T/s/meta.json"
OFFBENCH=$OB "$PY" "$JOIN" "$T/r/results.csv" "$T/s" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "samples_per_segment 128 vs 256" "$T/e.txt" && grep -qF "$T/s/results.csv" "$T/e.txt"' \
    "compare's other checks, by the program itself: refused: $(cat "$T/e.txt")"
"$PY" "$JOIN" "$T/r/results.csv" "$T/nosuch" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--archive: .*nosuch" "$T/e.txt"' "a missing archive: exit 2, named: $(cat "$T/e.txt")"

# --- the drawing ---
if ! "$PY" -c 'import matplotlib' >/dev/null 2>&1; then
    echo "e2e_plot_archive: $PY cannot import matplotlib: the drawing is skipped"
    skipped=$((skipped + 3))
    e2e_done
    exit $?
fi
OFFBENCH=$OB "$PY" "$PLOT" "$T/r/results.csv" --archive "$A" --out "$T/p" >"$T/p.out" 2>"$T/p.err"
check '[ $? -eq 0 ] && grep -q "summary_families.svg" "$T/p.out"' "plot.py --archive exits 0: $(head -c 300 "$T/p.err")"
check 'grep -q ">cobb (archive)<" "$T/p/summary_families.svg" && grep -q ">tiller<" "$T/p/summary_families.svg"' \
    "the archived methods are in the legend beside the run's"
check 'grep -qF "plot: $(grep "RUN rows have no archived job" "$T/sum.txt")" "$T/p.err"' "plot.py says what could not join"
e2e_done
