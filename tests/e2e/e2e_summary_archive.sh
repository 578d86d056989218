#!/bin/sh
# End-to-end tests of ./offbench summary RUN --archive ARCHIVE (issue 49):
# a small run of one method beside every method of the committed archive
# (results/baseline-small) on the same curves, d and tolerances, without
# running them again.  The joined and unjoined counts are recomputed here by
# a direct join in Python, independent of the C code; a mismatched metric is
# refused naming both files; a missing or malformed archive exits 2 naming it.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
A=$ROOT/results/baseline-small/random

# tol 1e-6 is not archived: those RUN rows cannot join
$OB run --random 3:2026 --methods tiller --tols 1e-1,1e-2,1e-6 --metric hausdorff --split mid --threads 2 \
    --out "$T/r" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/r/results.csv" ]' "offbench run --random 3:2026 --methods tiller"

# the reference: a direct join on (curve, d, tol) under metric hausdorff, split mid
"$PY" - "$T/r/results.csv" "$A/results.csv" >"$T/ref.txt" <<'PYEOF'
import csv, sys
run = list(csv.DictReader(open(sys.argv[1])))
arc = list(csv.DictReader(open(sys.argv[2])))
job = lambda r: (r["curve"], float(r["d"]), float(r["tol"]))
rm = {r["method"] for r in run}
jobs = {job(r) for r in run}
arc = [r for r in arc if r["metric"] == "hausdorff" and r["split"] == "mid"]
ajobs = {job(r) for r in arc}
other = [r for r in arc if r["method"] not in rm]
print("joined", sum(job(r) in jobs for r in other))
print("methods", len({r["method"] for r in other}))
print("run_unjoined", sum(job(r) not in ajobs for r in run))
print("arc_unjoined", sum(job(r) not in jobs for r in other))
print("arc_same", len(arc) - len(other))
print("ok_cells", sum(job(r) in jobs and r["status"] == "ok" for r in other))
PYEOF
ref() { awk -v k="$1" '$1==k{print $2}' "$T/ref.txt"; }
check '[ "$(ref joined)" -gt 0 ] && [ "$(ref run_unjoined)" -gt 0 ]' "the reference join: $(tr '\n' ' ' <"$T/ref.txt")"

# --- Markdown: the archived methods beside tiller, the counts ---
$OB summary "$T/r" --archive "$A" >"$T/s.md" 2>"$T/s.err"
check '[ $? -eq 0 ]' "summary --archive exits 0: $(head -c 300 "$T/s.err")"
check 'grep -q "^| curve | d | tol | tiller | cobb (archive) | .* | sisl (archive) |$" "$T/s.md"' \
    "the archived methods are columns beside tiller: $(grep '^| curve' "$T/s.md" | head -c 300)"
check 'grep -qxF "Archive: $A/results.csv (metric hausdorff, split mid): $(ref methods) methods beside the run'"'"'s, $(ref joined) rows joined." "$T/s.md"' \
    "the joined count matches Python's: $(grep '^Archive' "$T/s.md")"
check 'grep -q "^Not joined: $(ref run_unjoined) RUN rows have no archived job (curve, d, tol)" "$T/s.md"' \
    "RUN's unjoined rows counted: $(grep '^Not joined' "$T/s.md" | head -3)"
check 'grep -q "^Not joined: $(ref arc_unjoined) archive rows are on jobs RUN did not run" "$T/s.md"' \
    "the archive's unjoined rows counted"
check 'grep -q "^Not joined: $(ref arc_same) archive rows are of methods RUN ran itself (tiller): RUN.s values shown" "$T/s.md"' \
    "the archive rows of RUN's own method: RUN's values"
check 'grep -q "^| cobb (archive) | " "$T/s.md"' "the method table marks the archived methods"
njobs=$(($(wc -l <"$T/r/results.csv") - 1))
check 'grep -q "^$njobs jobs on .*; methods tiller; tolerances" "$T/s.md"' \
    "the scope line counts and names the run's own: $(grep ' jobs on ' "$T/s.md")"

# --- CSV: a source column; the archived ok cells as Python counts them ---
$OB summary "$T/r" --archive "$A" --format csv >"$T/s.csv" 2>/dev/null
check '[ $? -eq 0 ] && head -1 "$T/s.csv" | grep -q ",source$"' "--format csv has a source column: $(head -1 "$T/s.csv")"
n=$(awk -F, -v a="$A/results.csv" '$1=="curve" && $NF==a && $7=="ok"' "$T/s.csv" | wc -l)
check '[ "$n" -eq "$(ref ok_cells)" ]' "CSV: $n archived ok cells, Python $(ref ok_cells)"
check 'awk -F, -v r="$T/r/results.csv" "\$1==\"curve\" && \$5==\"tiller\" && \$NF!=r{exit 1}" "$T/s.csv"' \
    "CSV: tiller's rows are the run's"

# --- a directory of run directories: the published run shares no job ---
$OB summary "$T/r" --archive "$ROOT/results/baseline-small" >"$T/d.md" 2>"$T/d.err"
check '[ $? -eq 0 ] && grep -qxF "Archive: $A/results.csv (metric hausdorff, split mid): $(ref methods) methods beside the run'"'"'s, $(ref joined) rows joined." "$T/d.md"' \
    "a directory of runs: the random run joined: $(head -c 300 "$T/d.err")"
check 'grep -q "^Not joined: $ROOT/results/baseline-small/published/results.csv: no job in common with RUN" "$T/d.md"' \
    "a directory of runs: the published run named as not joined"
$OB summary "$T/r" --archive "$A" --archive "$A/results.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--archive: .*given twice" "$T/e.txt"' "the same archive twice: exit 2: $(cat "$T/e.txt")"

# --- refusals ---
mkdir -p "$T/m"
sed 's/,hausdorff,mid,/,normal,mid,/' "$A/results.csv" >"$T/m/results.csv"
sed 's/"metrics": \["hausdorff"\]/"metrics": ["normal"]/' "$A/meta.json" >"$T/m/meta.json"
$OB summary "$T/r" --archive "$T/m" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "not comparable" "$T/e.txt" && grep -q "metric" "$T/e.txt" && grep -qF "$T/m/results.csv" "$T/e.txt" && grep -qF "$T/r/results.csv" "$T/e.txt"' \
    "another metric: refused naming both files: $(head -c 400 "$T/e.txt")"
mkdir -p "$T/s"
cp "$A/results.csv" "$T/s/"
sed 's/"samples_per_segment": 256/"samples_per_segment": 128/' "$A/meta.json" >"$T/s/meta.json"
$OB summary "$T/r" --archive "$T/s" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "samples_per_segment 128 vs 256" "$T/e.txt"' \
    "another sample count: refused by compare's checks: $(head -c 400 "$T/e.txt")"
$OB summary "$T/r" --archive "$T/nosuch" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--archive: .*nosuch" "$T/e.txt"' "a missing archive: exit 2, named: $(cat "$T/e.txt")"
mkdir -p "$T/bad"
cp "$A/meta.json" "$T/bad/"
awk 'NR==3{sub(/,ok,/, ",okay,")} {print}' "$A/results.csv" >"$T/bad/results.csv"
$OB summary "$T/r" --archive "$T/bad" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "bad/results.csv:3" "$T/e.txt"' "a malformed archive: exit 2, FILE:LINE: $(cat "$T/e.txt")"
mkdir -p "$T/empty"
$OB summary "$T/r" --archive "$T/empty" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "empty" "$T/e.txt"' "a directory without runs: exit 2, named: $(cat "$T/e.txt")"
$OB summary "$T/r" --archive "$A" --baseline "$A" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--archive" "$T/e.txt"' "--archive with --baseline: exit 2: $(cat "$T/e.txt")"
e2e_done
