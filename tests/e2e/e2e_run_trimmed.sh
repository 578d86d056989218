#!/bin/sh
# End-to-end test of `run --trimmed` (issue 50, host/run/trimmed.h): each
# job's approximation, trimmed by its own crossings as a CAD kernel trims
# it, measured against the exact trimmed offset.
# - the columns trimmed_err and trimmed_cut: set exactly for the jobs with
#   an approximation, empty without --trimmed; no other column moves
#   (timing aside), and the rows are the same with 1 and 2 threads;
# - the parabola y = x^2 at d = 1 and 0.75 (a swallowtail): one region cut
#   from every approximation; at d = -1 (no loop) none, and trimmed_err is
#   at most max_err (the set distance needs no parameter match);
# - an independent brute force (tests/e2e/trim_approx_brute.py: dense
#   polylines, chord crossings through a grid, k-d trees, no code shared
#   with offbench) finds the same trimmed_err within its resolution and
#   the same number of regions cut, on exported approximations;
# - meta.json's "trimmed"; --resume with --trimmed refused.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PY=${TRIM_BRUTE_PYTHON:-/usr/bin/python3}
BRUTE=$(cd "$(dirname "$0")" && pwd)/trim_approx_brute.py

cat >"$T/p.curves" <<'EOF'
curve parabola
  source y = x^2 on [-1, 1]
  bezier 2
  point -1 1
  point 0 -1
  point 1 1
  offset 1 -1 0.75
end
EOF
J="--curves $T/p.curves --methods tiller,cobb,elber,cubic-opt,lee,exact --tols 1e-2,1e-3 --backend cpu"
"$OB" run $J --trimmed --export "$T/x" --out "$T/a" 2>"$T/a.err"
check '[ $? -eq 0 ]' "run --trimmed: exit 0: $(tail -n 2 "$T/a.err")"
check 'grep -q "trimmed [1-9][0-9]*, [1-9][0-9]* with arcs cut (" "$T/a.err"' "the closing line counts them: $(tail -n 1 "$T/a.err")"
check '[ "$(head -n 1 "$T/a/results.csv" | awk -F, "{print \$(NF-1) \",\" \$NF}")" = "trimmed_err,trimmed_cut" ]' \
    "the header ends in trimmed_err,trimmed_cut"
bad=$(awkc 'NR>1 { has = $c["trimmed_err"] != "" && $c["trimmed_cut"] != "";
                   want = $c["status"] == "ok" || $c["status"] == "limit";
                   if (has != want) print $c["method"], $c["d"], $c["tol"], $c["status"] }' "$T/a/results.csv")
check '[ -z "$bad" ]' "trimmed_err is set exactly for jobs with an approximation: $bad"
check 'awkc "NR>1 && \$c[\"status\"]==\"skip\"" "$T/a/results.csv" | grep -q .' "the fixture has skipped jobs (exact on a parabola)"
bad=$(awkc 'NR>1 && $c["trimmed_cut"] != "" && ($c["d"] == -1) != ($c["trimmed_cut"] == 0) {print $c["method"], $c["d"], $c["tol"], $c["trimmed_cut"]}' "$T/a/results.csv")
check '[ -z "$bad" ]' "one region cut at d = 1 and 0.75 (the loop), none at d = -1: $bad"
bad=$(awkc 'NR>1 && $c["d"] == -1 && $c["trimmed_err"] != "" && $c["trimmed_err"] + 0 > $c["max_err"] * (1 + 1e-9) {print $c["method"], $c["tol"], $c["max_err"], $c["trimmed_err"]}' "$T/a/results.csv")
check '[ -z "$bad" ]' "d = -1 (nothing trimmed): trimmed_err <= max_err: $bad"
bad=$(awkc 'NR>1 && $c["d"] == 1 && $c["trimmed_err"] != "" && $c["trimmed_err"] + 0 > 0.05 {print $c["method"], $c["tol"], $c["trimmed_err"]}' "$T/a/results.csv")
check '[ -z "$bad" ]' "d = 1: every trimmed approximation within 0.05 of the trimmed offset (the loop, 0.13 deep, is gone): $bad"

# no other column moves; 1 and 2 threads give the same rows
"$OB" run $J --out "$T/b" 2>/dev/null
"$OB" run $J --trimmed --threads 1 --out "$T/c" 2>/dev/null
notrim() { body "$1" | awk -F, 'NR==1{n=NF} {s=$1; for(i=2;i<=n-2;i++) s=s "," $i; print s}'; }
check '[ "$(notrim "$T/a/results.csv")" = "$(notrim "$T/b/results.csv")" ]' "every other column as without --trimmed"
check '[ "$(body "$T/a/results.csv")" = "$(body "$T/c/results.csv")" ]' "1 thread and 2 give the same rows, trimmed columns included"
bad=$(awkc 'NR>1 && ($c["trimmed_err"] != "" || $c["trimmed_cut"] != "")' "$T/b/results.csv")
check '[ -z "$bad" ]' "without --trimmed the columns are empty"
check 'grep -q "\"trimmed\": {\"wall_seconds\"" "$T/a/meta.json" && grep -q "\"trimmed\": null" "$T/b/meta.json"' "meta.json's trimmed"
"$OB" run --resume "$T/a" --trimmed 2>"$T/r.err"
check '[ $? -eq 2 ] && grep -q "not with --trimmed" "$T/r.err"' "--resume with --trimmed refused: $(cat "$T/r.err")"

# the independent brute force
if ! "$PY" -c 'import numpy, scipy.spatial, scipy.optimize' >/dev/null 2>&1; then
    echo "e2e_run_trimmed: $PY does not import numpy and scipy: the brute force skipped"
    skipped=$((skipped + 4))
else
    for job in "1 tiller 0.01" "1 cobb 0.001" "0.75 elber 0.001" "-1 lee 0.01"; do
        set -- $job
        row=$(awkc 'NR>1 && $c["d"] == d && $c["method"] == m && $c["tol"] == t {print $c["max_err"], $c["trimmed_err"], $c["trimmed_cut"]}' d="$1" m="$2" t="$3" "$T/a/results.csv")
        set -- $job $row
        (cd "$(dirname "$BRUTE")" && "$PY" "$BRUTE" "$T/p.curves" parabola "$1" "$T/x/parabola__d$1__$2__tol$3.curves" "$4") >"$T/b.out" 2>&1
        ours=$5 cut=$6
        # its point sets' spacing is 2e-5 of the size (3.83 here): the distance within 8e-5
        check 'awk -v ours="$ours" -v cut="$cut" "{d = \$1 - ours; if (d < 0) d = -d; exit !(d <= 8e-5 && \$2 == cut)}" "$T/b.out"' \
            "d = $1 $2 tol $3: offbench $5 ($6 cut), the brute force $(cat "$T/b.out")"
    done
fi
e2e_done
