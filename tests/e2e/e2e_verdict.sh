#!/bin/sh
# End-to-end tests of compare's timing verdict (issue 37): timings are
# judged only against a baseline from the same machine (meta.json's
# "machine": a name, a hashed id, CPU, cores, memory, device) and a quiet
# one (load average within the cores); a method's verdict is the
# Hodges-Lehmann estimate of its per-repetition totals with that
# estimate's own interval; too few repetitions to detect anything is
# exit 3, not a pass; the Markdown report leads with the verdict and the
# per-method table, the rows that do not count come after it, collapsed.
# The runs are real (small, CPU backend); their timings are then set by
# hand (deterministic), so no assertion here depends on the machine's speed.
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
[ -x "$PY" ] && "$PY" -c 'import json' 2>/dev/null || PY=
RUN="--curve liu2002_ex1 --methods tiller,ahn --tols 1e-1,1e-2 --backend cpu"
printf '0.00 0.00 0.00 1/100 1\n' > "$T/idle"
printf '99.00 50.00 20.00 9/100 1\n' > "$T/busy"

# run_as MACHINE LOADFILE REPS DIR: a run on the named machine, its load
# average read from LOADFILE (the test hook for /proc/loadavg)
run_as() {
    OFFBENCH_MACHINE=$1 OFFBENCH_LOADAVG=$2 $OB run $RUN --reps "$3" --out "$4" 2>/dev/null
}
# mkset SRC DST EXPR: SRC's meta.json with every row's time set by hand:
# each repetition's eval_ns is EXPR (awk, with r the repetition and m the
# method), fit_ns 0; results.csv holds EXPR at r = 3 (about the median)
mkset() {
    mkdir -p "$2"
    cp "$1/meta.json" "$2/"
    awkc 'BEGIN{OFS=","} NR>1 {r=3; m=$c["method"]; $c["fit_ns"]=0; $c["eval_ns"]='"$3"'} {print}' \
        "$1/results.csv" > "$2/results.csv"
    awkc 'BEGIN{OFS=","} NR>1 {r=$c["rep"]; m=$c["method"]; $c["fit_ns"]=0; $c["eval_ns"]='"$3"'} {print}' \
        "$1/samples.csv" > "$2/samples.csv"
}
# cmp_rc WANT BASE NEW [options]: compare, stdout in $T/out, stderr in $T/err
cmp_rc() {
    want=$1; shift
    $OB compare "$@" >"$T/out" 2>"$T/err"
    rc=$?
    if [ $rc -eq "$want" ]; then ok; else bad "compare $* -> exit $rc, want $want: $(head -c 600 "$T/err") $(sed -n '3,4p' "$T/out")"; fi
}
# the time_total line of METHOD in a CSV report: base,new,ratio,p,lo,hi,note
method_total() {
    awkc '$c["kind"]=="method" && $c["field"]=="time_total" && $c["method"]==m {
            print $c["base"] "," $c["new"] "," $c["ratio"] "," $c["p_value"] "," $c["ci_lo"] "," $c["ci_hi"] "," $c["note"]}' \
        m="$2" "$1"
}

run_as box-a "$T/idle" 5 "$T/a5"; check '[ $? -eq 0 ]' "run --reps 5 on box-a"
run_as box-a "$T/idle" 5 "$T/a5b"; check '[ $? -eq 0 ]' "a second run on box-a"
run_as box-b "$T/idle" 5 "$T/b5"; check '[ $? -eq 0 ]' "run --reps 5 on box-b"
run_as box-a "$T/busy" 5 "$T/a5busy"; check '[ $? -eq 0 ]' "run --reps 5 on a busy box-a"
run_as box-a "$T/idle" 3 "$T/a3"; check '[ $? -eq 0 ]' "run --reps 3 on box-a"
$OB run $RUN --reps 2 --out "$T/host1" 2>/dev/null
$OB run $RUN --reps 2 --out "$T/host2" 2>/dev/null

# --- meta.json: the machine ---
mline() { grep '^  "machine": {' "$1/meta.json"; }
check 'mline "$T/a5" | grep -q "\"name\": \"box-a\", \"id\": \"[0-9a-f]\{16\}\", \"id_source\": \"OFFBENCH_MACHINE\""' \
    "meta.json names the machine and its id: $(mline "$T/a5")"
check 'mline "$T/a5" | grep -q "\"cpu_model\": \".*\", \"logical_cores\": [1-9][0-9]*, \"memory_mib\": [1-9][0-9]*, \"device\": \"cpu\""' \
    "meta.json records CPU, cores, memory and device with the machine"
id_of() { mline "$1" | sed 's/.*"id": "\([0-9a-f]*\)".*/\1/'; }
check '[ "$(id_of "$T/a5")" = "$(id_of "$T/a5b")" ] && [ "$(id_of "$T/a5")" != "$(id_of "$T/b5")" ]' \
    "the same name gives the same id, another name another"
check '[ -n "$(id_of "$T/host1")" ] && [ "$(id_of "$T/host1")" = "$(id_of "$T/host2")" ] && [ "$(id_of "$T/host1")" != "$(id_of "$T/a5")" ]' \
    "without OFFBENCH_MACHINE: a stable id of this machine"
check 'mline "$T/host1" | grep -q "\"name\": \"$(hostname)\""' "without OFFBENCH_MACHINE the name is the host's: $(mline "$T/host1")"
if [ -r /etc/machine-id ] && [ -s /etc/machine-id ]; then
    check '! grep -q "$(cat /etc/machine-id)" "$T/host1/meta.json" && mline "$T/host1" | grep -q "\"id_source\": \"/etc/machine-id and hostname\""' \
        "/etc/machine-id is hashed, never written as it is"
else
    skipped=$((skipped + 1)); echo "SKIP: no /etc/machine-id" >&2
fi

# --- the same build twice on the same quiet machine: no timing verdict either way ---
mkset "$T/a5" "$T/q1" '10000000 + 10000 * r'
mkset "$T/a5b" "$T/q2" '10000000 + 10000 * ((r * 3) % 5)'
cmp_rc 0 "$T/q1" "$T/q2"
check 'sed -n 4p "$T/out" | grep -q "^Timing: judged: the same machine .box-a." && ! grep -q "| slower |\|| faster |" "$T/out"' \
    "same code, same quiet machine: judged, no change: $(sed -n 4p "$T/out")"
cmp_rc 0 "$T/q1" "$T/q2" --format csv
check '[ "$(method_total "$T/out" tiller | cut -d, -f7)" = same ] && [ "$(method_total "$T/out" ahn | cut -d, -f7)" = same ]' \
    "both methods: same: $(method_total "$T/out" tiller)"

# --- a planted 3x slowdown of tiller, 5 + 5 repetitions, same machine: a regression ---
mkset "$T/a5b" "$T/slow5" '(m == "tiller" ? 3 : 1) * (10000000 + 10000 * ((r * 3) % 5))'
cmp_rc 1 "$T/q1" "$T/slow5" --method-timing-only
check 'grep -q "^\*\*REGRESSION\*\* (exit 1)" "$T/out" && grep -q "^| tiller | 4 | .* | slower | regression |" "$T/out"' \
    "5 + 5 reps, tiller 3x: slower, a regression: $(grep "^| tiller" "$T/out")"
check 'grep -q "^| ahn | 4 | .* | no change | same |" "$T/out"' "ahn unchanged: $(grep "^| ahn" "$T/out")"
cmp_rc 1 "$T/q1" "$T/slow5" --method-timing-only --format csv
t=$(method_total "$T/out" tiller)
check 'echo "$t" | awk -F, "{exit !(\$3 > 2.9 && \$3 < 3.1 && \$5 <= \$3 && \$3 <= \$6 && \$7 == \"slower\")}"' \
    "tiller's estimate (about 3) lies inside its own interval: $t"
check '[ -z "$(awkc "\$c[\"kind\"]==\"method\" && \$c[\"field\"]==\"time_total\" && \$c[\"ci_lo\"]!=\"\" && !(\$c[\"ci_lo\"] <= \$c[\"ratio\"] && \$c[\"ratio\"] <= \$c[\"ci_hi\"])" "$T/out")" ]' \
    "every method's estimate lies inside its interval"
check 'grep -q "^regression,,,tiller,,,,time_total," "$T/out"' "CSV: the method's regression line is its time_total"

# --- the report: the verdict, then the deciding table, the rest collapsed after it ---
cmp_rc 1 "$T/q1" "$T/slow5" --method-timing-only
first_table=$(grep -n "^## " "$T/out" | head -n 1)
check 'sed -n 3p "$T/out" | grep -q "^\*\*REGRESSION\*\*" && [ "${first_table#*:}" = "## Verdict by method" ]' \
    "the report leads with the verdict and the per-method table: line 3 $(sed -n 3p "$T/out"), first section $first_table"
check 'awk "/^<details>/{d=1} /^## Timing changes of rows, not counted/{print d}" "$T/out" | grep -qx 1' \
    "row-level timing changes that do not count are inside a collapsed section"
check '! awk "/^<details>/{exit} {print}" "$T/out" | grep -q "| time |"' "no row-level timing line before the collapsed section"
check 'grep -q "^| method | rows | ctrl_points | max_err | regressions | improvements | time base | time new | time new/base | interval | p | timing | verdict |" "$T/out"' \
    "the per-method header"

# --- the same slowdown with 3 + 3 repetitions: cannot be detected; says so, exit 3 ---
mkset "$T/a3" "$T/q3" '10000000 + 10000 * r'
mkset "$T/a3" "$T/slow3" '(m == "tiller" ? 3 : 1) * (10000000 + 10000 * ((r * 2) % 3))'
cmp_rc 3 "$T/q3" "$T/slow3" --method-timing-only
check 'grep -q "too few repetitions to judge timing: need 4 per side" "$T/out" && grep -q "too few repetitions to judge timing: need 4 per side" "$T/err"' \
    "3 + 3 reps: too few repetitions, need 4: $(cat "$T/err")"
check '! grep -q "^\*\*OK" "$T/out"' "... and not reported as OK"
cmp_rc 3 "$T/q3" "$T/q3"
check 'grep -q "need 4 per side" "$T/out"' "3 + 3 reps of the same run: exit 3 too (nothing could be detected)"
cmp_rc 0 "$T/q3" "$T/slow3" --no-timing
check '! grep -q "too few" "$T/out"' "--no-timing: timings not asked for, exit 0"

# --- another machine: timings not judged, quality still is ---
mkset "$T/b5" "$T/other" '10000000 + 10000 * r'
cmp_rc 0 "$T/other" "$T/slow5" --method-timing-only
check 'grep -q "^Timing: \*\*not judged\*\*: baseline from machine .box-b. (id [0-9a-f]*), this is .box-a. (id [0-9a-f]*)" "$T/out"' \
    "another machine: not judged: $(sed -n 4p "$T/out")"
check 'grep -q "timings not judged: baseline from machine .box-b." "$T/err" && ! grep -q "| slower |" "$T/out"' \
    "said on stderr too, and no method is slower"
awkc 'BEGIN{OFS=","} NR==3{$c["ctrl_points"]=$c["ctrl_points"]+2} {print}' "$T/slow5/results.csv" > "$T/cp.csv"
mkdir "$T/slowcp" && cp "$T/slow5/meta.json" "$T/slow5/samples.csv" "$T/slowcp/" && mv "$T/cp.csv" "$T/slowcp/results.csv"
cmp_rc 1 "$T/other" "$T/slowcp" --method-timing-only
check 'grep -q "^\*\*REGRESSION\*\* (exit 1): .* (quality 1, " "$T/out" && grep -q "baseline from machine .box-b." "$T/out"' \
    "another machine with a quality regression: 1, quality judged"
# a baseline written before machines were recorded: not judged
mkdir "$T/old" && cp "$T/q1/results.csv" "$T/q1/samples.csv" "$T/old/"
grep -v '^  "machine": {' "$T/q1/meta.json" > "$T/old/meta.json"
cmp_rc 0 "$T/old" "$T/slow5" --method-timing-only
check 'grep -q "^Timing: \*\*not judged\*\*: BASE records no machine" "$T/out"' "a baseline without a machine: $(sed -n 4p "$T/out")"
# no meta.json at all: the machine is unknown
mkdir "$T/nometa" && cp "$T/slow5/results.csv" "$T/slow5/samples.csv" "$T/nometa/"
cmp_rc 0 "$T/q1" "$T/nometa" --method-timing-only
check 'grep -q "^Timing: \*\*not judged\*\*: NEW has no meta.json" "$T/out"' "no meta.json: not judged: $(sed -n 4p "$T/out")"
# --strict-timing asks for a verdict: another machine is then exit 3
cmp_rc 3 "$T/other" "$T/slow5" --strict-timing --method-timing-only

# --- a busy machine (load above the cores): judged all the same (issue 46:
# shared runners are the normal case; the repetitions' spread decides), the
# load said in a note ---
mkset "$T/a5busy" "$T/busyslow" '(m == "tiller" ? 3 : 1) * (10000000 + 10000 * r)'
cmp_rc 1 "$T/q1" "$T/busyslow" --method-timing-only
check 'grep -q "^Timing: judged" "$T/out" && grep -q "note: NEW.s load average reached 99.00 on its [0-9]* core" "$T/out" && grep -q "^| tiller | .* | slower | regression |" "$T/out"' \
    "load above the cores: judged, tiller 3x slower found, the load noted: $(sed -n 4p "$T/out")"
cmp_rc 0 "$T/busyslow" "$T/busyslow" --method-timing-only
check 'grep -q "BASE.s load average reached 99.00" "$T/out" && grep -q "^| ahn | .* | no change | same |" "$T/out"' \
    "a busy run against itself: no change, noted"

# --- repetitions spread wider than the change they would report: the data
# cannot decide: exit 3 with the repetitions needed, never a pass ---
mkset "$T/a5b" "$T/spread" '(m == "tiller" && r % 2 ? 13000000 : 10000000) + 10000 * r'
cmp_rc 3 "$T/q1" "$T/spread" --method-timing-only --format csv
t=$(method_total "$T/out" tiller)
check '[ "${t##*,}" = noisy ]' "tiller 1.3x on 3 of 5 repetitions: noisy, not slower: $t"
check 'grep -q "^method,,,tiller,,,,need_reps,[0-9]*,[1-9][0-9]*," "$T/out"' "the CSV says how many repetitions it needs: $(grep need_reps "$T/out")"
cmp_rc 3 "$T/q1" "$T/spread"
check 'grep -q "^| tiller | 4 | .* | cannot decide: need [1-9][0-9]* more repetitions per side | same |" "$T/out" && grep -q "TIMINGS NOT JUDGED" "$T/out"' "the table says it cannot decide: $(grep "^| tiller" "$T/out")"

# --- --timing-only: quality not judged; --methods: only those methods ---
cmp_rc 2 "$T/q1" "$T/slowcp" --timing-only --no-timing
cmp_rc 1 "$T/q1" "$T/slowcp" --timing-only --method-timing-only
check 'grep -q "quality: not judged (--timing-only)" "$T/out" && grep -q "(quality 0, " "$T/out"' "--timing-only: the ctrl_points change is not judged"
cmp_rc 0 "$T/q1" "$T/slowcp" --methods ahn
check 'grep -q "^\*\*OK: no regression\*\* (exit 0): 4 joined rows" "$T/out" && ! grep -q "^| tiller" "$T/out"' \
    "--methods ahn: tiller's rows left out: $(sed -n 3p "$T/out")"
cmp_rc 2 "$T/q1" "$T/slowcp" --methods nosuch
check 'grep -q -- "--methods" "$T/err"' "--methods with a method neither run has: $(cat "$T/err")"

# --- the methods' own fit time (run --time-fits, issue 46) ---
# mkfits SRC DST EXPR [EVAL]: SRC (a run with --time-fits) with every round's
# method_ns set to EXPR (awk, r the round, m the method) in fits.csv and at
# r = 3 in results.csv; eval_ns of every repetition EVAL (default 10 ms)
mkfits() {
    mkdir -p "$2"
    cp "$1/meta.json" "$2/"
    ev=${4:-10000000}
    awkc 'BEGIN{OFS=","} NR>1 && $c["fit_calls"] != "" {r=3; m=$c["method"]; $c["method_ns"]='"$3"'} NR>1 {$c["eval_ns"]='"$ev"'} {print}' \
        "$1/results.csv" > "$2/results.csv"
    awkc 'BEGIN{OFS=","} NR>1 {r=$c["round"]; m=$c["method"]; $c["method_ns"]='"$3"'} {print}' "$1/fits.csv" > "$2/fits.csv"
    awkc 'BEGIN{OFS=","} NR>1 {r=$c["rep"]; m=$c["method"]; $c["eval_ns"]='"$ev"'} {print}' "$1/samples.csv" > "$2/samples.csv"
}
OFFBENCH_MACHINE=box-a OFFBENCH_LOADAVG=$T/idle $OB run $RUN --reps 5 --time-fits --fit-reps 5 --fit-min-time 0.1 \
    --out "$T/f5" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/f5/fits.csv" ]' "run --reps 5 --time-fits on box-a"
mkfits "$T/f5" "$T/fq" '100000 + 1000 * r'
# tiller's fits 1.5x as long, its fit_ns + eval_ns (eval 10 ms) unchanged:
# the method time sees it, the old sum could not
mkfits "$T/f5" "$T/fslow" '(m == "tiller" ? 1.5 : 1) * (100000 + 1000 * r)'
cmp_rc 1 "$T/fq" "$T/fslow" --timing-only --method-timing-only
check 'grep -q "^Timing: judged: .*the methods. own fit time (--time-fits); per method 1 slower, 0 faster, 1 no change" "$T/out" && grep -q "^| tiller | .* | 1.5 | .* | slower | regression |" "$T/out"' \
    "a method whose fits take 1.5x as long is slower: $(grep "^| tiller" "$T/out")"
check 'grep -q "^| \*harness\* (eval_ns) | .* | no change | same |" "$T/out"' "the harness's own line: $(grep harness "$T/out")"
cmp_rc 0 "$T/fq" "$T/fq" --timing-only --method-timing-only
check 'grep -q "per method 0 slower, 0 faster, 2 no change" "$T/out"' "unchanged fits: no change: $(grep "^Timing" "$T/out")"
# the harness twice as slow: a regression on the CPU backend (thread CPU time) ...
mkfits "$T/f5" "$T/fharn" '100000 + 1000 * r' '20000000 + 10000 * r'
cmp_rc 1 "$T/fq" "$T/fharn" --timing-only --method-timing-only
check 'grep -q "^| \*harness\* (eval_ns) | .* | slower | regression |" "$T/out" && grep -q "harness (eval_ns) slower" "$T/out"' \
    "the harness 2x slower: a regression on the CPU backend: $(grep harness "$T/out" | head -n 1)"
check '$OB compare "$T/fq" "$T/fharn" --timing-only --method-timing-only --format csv 2>/dev/null | grep -q "^harness,,,harness,,,,time_total,.*,slower$"' \
    "CSV: the harness line"
# ... reported only where a batch backend measured (its eval_ns is wall time)
for d in fq fharn; do sed -i 's/"backend": "cpu"/"backend": "opencl"/' "$T/$d/meta.json"; done
cmp_rc 0 "$T/fq" "$T/fharn" --timing-only --method-timing-only
check 'grep -q "^| \*harness\* (eval_ns) | .* | slower | reported only |" "$T/out"' \
    "the harness of a batch backend: reported, not counted: $(grep harness "$T/out" | head -n 1)"
# one side without --time-fits: fit_ns + eval_ns, said
cmp_rc 0 "$T/q1" "$T/fslow" --timing-only --method-timing-only
check 'grep -q "BASE has no method time (run --time-fits)" "$T/out" && grep -q "fit_ns + eval_ns;" "$T/out"' \
    "a run without --time-fits: the old sum (which cannot see the 1.5x fits), and a note: $(grep "no method time" "$T/out")"

# --- JSON: the machine of each side, the per-method estimate ---
if [ -n "$PY" ]; then
    $OB compare "$T/q1" "$T/slow5" --format json --method-timing-only >"$T/j.json" 2>/dev/null
    check '"$PY" -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert d[\"base\"][\"machine\"] == \"box-a\" and len(d[\"new\"][\"machine_id\"]) == 16, d[\"base\"]
t = [m for m in d[\"methods\"] if m[\"method\"] == \"tiller\"][0]
assert t[\"timing\"] == \"slower\" and t[\"ci_lo\"] <= t[\"time_estimate\"] <= t[\"ci_hi\"], t
assert d[\"context\"][\"timing\"].startswith(\"judged\"), d[\"context\"]
" "$T/j.json"' "JSON: machines, the estimate inside its interval, the timing line"
else
    skipped=$((skipped + 1)); echo "SKIP: no python3 with json" >&2
fi

e2e_done
