#!/bin/sh
# e2e_signals_measure.sh - SIGTERM and SIGINT stop measure as they stop run
# (docs/reliability.md "Signals"; issue 48, item 10): its loop over files
# and pieces stops at its next step, the CSV is written whole or not at
# all, and what stderr says is true.  Which of the two a test sees depends
# on when the signal lands, so both are accepted:
#   stopped:  exit 128 + the signal, no CSV, stderr says none was written;
#   finished: the whole CSV, exit 0 or 128 + the signal with stderr saying
#             the CSV is complete;
# never the whole CSV with "rerun the command to finish", never a hang
# (the guard: timeout -s KILL, far above what measure takes here).
. "$(dirname "$0")/lib_e2e.sh"

"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-6 --backend cpu --out "$T/r" --export "$T/x" \
    >/dev/null 2>"$T/run.err"
check "[ $? = 0 ]" "run --export: $(tail -n 1 "$T/run.err")"
A=$T/x/liu2002_ex1__d-1__tiller__tol1e-06.json

# judge NAME RC SIG ROWS: the outcome of measure NAME, stopped by SIG,
# whose whole CSV has ROWS lines
judge() {
    name=$1 rc=$2 sig=$3 rows=$4
    lines=$(wc -l <"$T/$name.csv")
    check "[ $rc != 137 ]" "$name: killed by the hang guard: the signal was not taken"
    if [ "$lines" = 0 ]; then
        check "[ $rc = $((128 + sig)) ]" "$name: no CSV, exit $rc, not $((128 + sig))"
        check "grep -q 'interrupted by signal $sig' $T/$name.err && grep -q 'no CSV' $T/$name.err" \
            "$name: no CSV and stderr does not say so: $(tail -n 1 "$T/$name.err")"
    else
        check "[ $lines = $rows ]" "$name: a CSV of $lines lines, not the whole $rows"
        check "! grep -q 'rerun the command' $T/$name.err" \
            "$name: the whole CSV, and stderr says to rerun: $(tail -n 1 "$T/$name.err")"
        check "[ $rc = 0 ] || { [ $rc = $((128 + sig)) ] && grep -q 'complete' $T/$name.err; }" \
            "$name: the whole CSV, exit $rc: $(tail -n 1 "$T/$name.err")"
    fi
}

# four files: the signal once the first is measured (its line on stderr)
timeout -s KILL 600 "$OB" measure --curve liu2002_ex1 --d -1 --approx "$A" --approx "$A" --approx "$A" \
    --approx "$A" >"$T/files.csv" 2>"$T/files.err" &
pid=$!
n=0
while ! grep -q 'measure: .* pieces of' "$T/files.err" && [ $n -lt 5000 ]; do sleep 0.1; n=$((n + 1)); done
kill -TERM "$pid" 2>/dev/null
wait "$pid"
judge files $? 15 25

# one file of many samples: the signal while its pieces are measured
timeout -s KILL 600 "$OB" measure --curve liu2002_ex1 --d -1 --approx "$A" --samples 1024 \
    >"$T/pieces.csv" 2>"$T/pieces.err" &
pid=$!
sleep 1
kill -INT "$pid" 2>/dev/null
wait "$pid"
judge pieces $? 2 7

e2e_done
