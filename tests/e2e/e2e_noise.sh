#!/bin/sh
# End-to-end tests of "noise you can see": run --reps N writes the spread
# columns time_iqr_ns and time_cv (empty without --reps), meta.json's host,
# versions and warnings (the load warning forced with $OFFBENCH_LOADAVG, a
# stand-in for /proc/loadavg), compare's intervals, rows not judged,
# --strict-timing's exit 3, and compare --format json (parsed by python3:
# those checks are skipped, and counted so, without it).  Small runs:
# seconds.
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
[ -x "$PY" ] && "$PY" -c 'import json' 2>/dev/null || PY=
RUN="--curve liu2002_ex1 --methods tiller,ahn --tols 1e-1,1e-2 --backend cpu"

# --- the spread columns ---
printf '0.00 0.00 0.00 1/100 1\n' > "$T/idle"
printf '99.00 50.00 20.00 9/100 1\n' > "$T/busy"
# every run here on an idle machine but where the busy one is named: the
# timings below are set by hand, and compare judges timings only of quiet runs
export OFFBENCH_LOADAVG="$T/idle"
OFFBENCH_LOADAVG=$T/idle $OB run $RUN --reps 4 --out "$T/r" 2>"$T/r.err"
check '[ $? -eq 0 ]' "run --reps 4"
# (by position: that they come after the joints, before the certificate's, is the contract checked)
check '[ "$(head -n 1 "$T/r/results.csv" | awk -F, "{print \$(NF-10) \",\" \$(NF-9)}")" = "time_iqr_ns,time_cv" ]' \
    "time_iqr_ns and time_cv come before the certificate's four columns: $(head -n 1 "$T/r/results.csv")"
bad_spread=$(rcols "$T/r/results.csv" time_iqr_ns time_cv | awk -F: '!($1 ~ /^[0-9]+$/ && $2 ~ /^[0-9.e+-]+$/ && $2 >= 0)')
check '[ -z "$bad_spread" ] && [ "$(rcols "$T/r/results.csv" time_cv | wc -l)" -eq 8 ]' \
    "every row of a --reps 4 run has a whole-ns IQR and a CV >= 0: $bad_spread"
# the IQR of one row, recomputed from samples.csv (type 7 quartiles of 4 totals)
want=$(awkc 'NR>1 && $c["d"]==1 && $c["method"]=="tiller" && $c["tol"]==0.1 {print $c["fit_ns"]+$c["eval_ns"]}' "$T/r/samples.csv" | sort -n |
       awk '{v[NR]=$1} END{q1=v[1]+0.75*(v[2]-v[1]); q3=v[3]+0.25*(v[4]-v[3]); printf "%.0f", q3-q1}')
got=$(rcols "$T/r/results.csv" curve d method tol time_iqr_ns | awk -F: '$2==1 && $3=="tiller" && $4==0.1 {print $5}')
check '[ -n "$got" ] && [ "$got" = "$want" ]' "time_iqr_ns is the IQR of the repetitions' totals: $got vs $want"
check '! grep -q "load average" "$T/r.err"' "idle machine: no load warning"
$OB run $RUN --out "$T/p" 2>/dev/null
check '[ -z "$(rcols "$T/p/results.csv" time_iqr_ns time_cv | grep -v "^:$")" ]' "without --reps the spread columns are empty"
$OB run $RUN --reps 1 --out "$T/p1" 2>/dev/null
check '[ -z "$(rcols "$T/p1/results.csv" time_iqr_ns time_cv | grep -v "^:$")" ]' "--reps 1: empty too"
check '[ "$(body "$T/r/results.csv")" = "$(body "$T/p/results.csv")" ]' "--reps changes no result column"
check '$OB list columns | grep -q "^time_iqr_ns " && $OB list columns | grep -q "^time_cv "' "list columns has them"

# --- the load warning ---
OFFBENCH_LOADAVG=$T/busy $OB run $RUN --reps 2 --out "$T/b" 2>"$T/b.err"
check 'grep -q "warning: load average up to 99.00 during the run, above the [0-9]* cores\{0,1\} it used" "$T/b.err"' \
    "busy machine: a warning on stderr: $(grep load "$T/b.err")"
OFFBENCH_LOADAVG=$T/busy $OB run $RUN --out "$T/b0" 2>"$T/b0.err"
check '! grep -q "load average" "$T/b0.err"' "without --reps: no load warning"

# --- meta.json: host, versions, warnings ---
if [ -n "$PY" ]; then
    meta_check() {  # DIR WARNINGS
        "$PY" - "$1/meta.json" "$2" <<'PYEOF'
import json, sys
m = json.load(open(sys.argv[1]))
h, v, w = m["host"], m["versions"], m["warnings"]
assert all(isinstance(h[k], str) and h[k] for k in ("hostname", "os", "kernel")), h
assert isinstance(h["cores_used"], int) and h["cores_used"] >= 1, h
for k in ("loadavg_start", "loadavg_end", "loadavg_max"):
    assert h[k] is None or h[k] >= 0, (k, h)
assert all(k in v for k in ("sisl", "flint", "flint_header", "opencl_loader")), v
assert isinstance(v["flint"], str) and v["flint"], v
assert isinstance(w, list) and len(w) == int(sys.argv[2]), w
assert m["cpu_model"] and m["reps"] >= 1 and "git_commit" in m  # the old keys are kept
PYEOF
    }
    check 'meta_check "$T/r" 0' "meta.json (idle, --reps 4): host, versions, no warning"
    check 'meta_check "$T/b" 1 && grep -q "\"loadavg_max\": 99.00" "$T/b/meta.json"' "meta.json (busy): one warning, loadavg_max 99"
    check 'meta_check "$T/b0" 0' "meta.json without --reps: no warning"
else
    skipped=$((skipped + 3))
    echo "SKIP: no python3 with json: meta.json not parsed" >&2
fi

# --- compare: intervals, not judged, --strict-timing ---
# samples made by hand (deterministic): every row 10 ms in results.csv;
# tight: repetitions 10.00 .. 10.03 ms; noisy: 10, 20, 10, 20 ms
mkset() {  # DIR AWK-EXPRESSION-FOR-eval_ns(rep)
    mkdir -p "$1"
    cp "$T/r/meta.json" "$1/"
    awkc 'BEGIN{OFS=","} NR>1 {$c["fit_ns"]=0; $c["eval_ns"]=10000000} {print}' "$T/r/results.csv" > "$1/results.csv"
    awkc 'BEGIN{OFS=","} NR>1 {r=$c["rep"]; $c["fit_ns"]=0; $c["eval_ns"]='"$2"'} {print}' "$T/r/samples.csv" > "$1/samples.csv"
}
mkset "$T/tight" '10000000 + 10000 * r'
mkset "$T/noisy" '(r % 2 ? 10000000 : 20000000)'
$OB compare "$T/tight" "$T/tight" --strict-timing >"$T/out" 2>"$T/err"
check '[ $? -eq 0 ] && grep -q "^- intervals: 95% confidence intervals" "$T/out" && grep -q "0 too noisy, 0 too few" "$T/out"' \
    "tight repetitions: judged, --strict-timing passes: $(head -c 300 "$T/err")"
$OB compare "$T/tight" "$T/noisy" >"$T/out" 2>"$T/err"
# (the method's timing cannot be decided either: exit 3, never a pass)
check '[ $? -eq 3 ] && grep -q "8 too noisy" "$T/out" && grep -q "| time: noisy | 10 ms | 10 ms | 1.411 | 1 | \[0.996, 1.998\] |" "$T/out"' \
    "noisy rows are listed as not judged, with their interval: $(grep "time: noisy" "$T/out" | head -n 1)"
$OB compare "$T/tight" "$T/noisy" --strict-timing >"$T/out" 2>"$T/err"
check '[ $? -eq 3 ] && grep -q "TIMINGS NOT JUDGED" "$T/out" && grep -q "8 row(s) too noisy to judge" "$T/err"' \
    "--strict-timing: noisy rows exit 3: $(head -c 300 "$T/err")"
$OB compare "$T/tight" "$T/noisy" --strict-timing --method-timing-only >/dev/null 2>"$T/err"
check '[ $? -eq 3 ] && ! grep -q "row(s)" "$T/err" && grep -q "method tiller: too noisy" "$T/err"' \
    "--strict-timing --method-timing-only: the methods only: $(head -c 300 "$T/err")"
$OB compare "$T/p" "$T/p" --strict-timing --time-floor-ns 0 >/dev/null 2>"$T/err"
check '[ $? -eq 3 ] && grep -q "without at least 2 repetitions" "$T/err"' "--strict-timing without samples.csv: exit 3"
$OB compare "$T/p" "$T/p" --time-floor-ns 0 >/dev/null 2>&1
check '[ $? -eq 0 ]' "... and 0 without --strict-timing"
$OB compare "$T/p" "$T/p" --strict-timing --no-timing >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "strict-timing" "$T/err"' "--strict-timing with --no-timing: a usage error"
$OB compare "$T/tight" "$T/noisy" --format csv >"$T/out" 2>/dev/null
check '[ "$(head -n 1 "$T/out")" = "kind,curve,d,method,metric,split,tol,field,base,new,ratio,p_value,ci_lo,ci_hi,note" ] &&
       [ "$(grep -c "^not_judged,.*,time,10000000,10000000,1\.41[0-9]*,.*,noisy$" "$T/out")" -eq 8 ]' "CSV: not_judged lines with their interval"

$OB compare "$T/b" "$T/r" >"$T/out" 2>/dev/null
check 'grep -q "^- note: BASE.s run warned (meta.json warnings): \[\"load average up to 99.00" "$T/out"' \
    "compare notes a run's load warning: $(grep warned "$T/out")"

# --- compare --format json ---
if [ -n "$PY" ]; then
    $OB compare "$T/tight" "$T/noisy" --format json --strict-timing >"$T/j.json" 2>/dev/null
    check '[ $? -eq 3 ] && "$PY" -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert d[\"status\"] == 3 and d[\"verdict\"] == \"timing_not_judged\", d[\"status\"]
nj = [c for c in d[\"changes\"] if c[\"kind\"] == \"not_judged\"]
assert len(nj) == 8 and all(c[\"note\"] == \"noisy\" and c[\"ci_lo\"] <= 1 <= c[\"ci_hi\"] for c in nj), nj
assert d[\"counts\"][\"timing_noisy\"] == 8 and len(d[\"methods\"]) == 2
assert d[\"context\"][\"timing_not_judged\"] and d[\"base\"][\"repetitions\"] == 4
" "$T/j.json"' "compare --format json parses, with the not-judged rows and their intervals"
    # a regression and a not-comparable pair, with a quote in a curve id's message
    $OB compare "$T/tight" "$T/tight" --format json --alpha 0.2 >"$T/j2.json" 2>/dev/null
    check '[ $? -eq 0 ] && "$PY" -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert d[\"status\"] == 0 and d[\"changes\"] == [] and d[\"options\"][\"alpha\"] == 0.2
assert all(m[\"ci_lo\"] is not None and m[\"ci_lo\"] <= 1 <= m[\"ci_hi\"] for m in d[\"methods\"])
" "$T/j2.json"' "compare --format json of identical runs: no change, method intervals hold 1"
    mkdir "$T/other" && cp "$T/p/results.csv" "$T/other/" && sed 's/"samples_per_segment": [0-9]*/"samples_per_segment": 3/' "$T/p/meta.json" > "$T/other/meta.json"
    $OB compare "$T/p" "$T/other" --format json >"$T/j3.json" 2>/dev/null
    check '[ $? -eq 3 ] && "$PY" -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert d[\"verdict\"] == \"not_comparable\" and d[\"context\"][\"not_comparable\"] and d[\"changes\"] == []
" "$T/j3.json"' "compare --format json when not comparable"
else
    skipped=$((skipped + 3))
    echo "SKIP: no python3 with json: compare --format json not parsed" >&2
fi

e2e_done
