#!/bin/sh
# e2e_signals.sh - SIGTERM and SIGINT end every long phase at its next step
# (a hang guard, not a timing: well under the 60 s kill), with exit status
# 128 + the signal, a line on stderr saying
# what was left behind, and no *.tmp file (issue 36, class 7).
. "$(dirname "$0")/lib_e2e.sh"

# stopped NAME SIG WAITFOR CMD...: start CMD in the background, once the
# path WAITFOR exists (a glob; the phase under test has begun) send SIG,
# and keep its exit status in $T/NAME.rc, its stderr in $T/NAME.err and
# the seconds from the signal to its end in $T/NAME.s
stopped() {
    name=$1 sig=$2 waitfor=$3; shift 3
    timeout -s KILL 60 "$@" >/dev/null 2>"$T/$name.err" &
    pid=$!
    n=0
    while [ -z "$(ls -d $waitfor 2>/dev/null | head -n 1)" ] && [ $n -lt 400 ]; do sleep 0.05; n=$((n + 1)); done
    kill -"$sig" "$pid"
    t0=$(date +%s)
    wait "$pid"
    echo $? >"$T/$name.rc"
    echo $(($(date +%s) - t0)) >"$T/$name.s"
}
expect() {
    name=$1 rc=$2 said=$3 dir=$4
    check "[ \"\$(cat $T/$name.rc)\" = $rc ]" "$name: exit status $(cat "$T/$name.rc"), not $rc"
    check "[ \"\$(cat $T/$name.s)\" -le 50 ]" "$name: ended $(cat "$T/$name.s") s after the signal"
    check "grep -q 'interrupted by signal' $T/$name.err && grep -q \"$said\" $T/$name.err" \
        "$name: stderr does not say what was left: $(cat "$T/$name.err" | tail -n 2)"
    check "[ -z \"\$(find $dir -name '*.tmp' 2>/dev/null)\" ]" "$name: a *.tmp file was left in $dir"
}

# run --export: the signal once the first exported file is there
RUN="run --random 40:3 --methods tiller,cobb"
stopped export TERM "$T/x1/*.json" "$OB" $RUN --out "$T/r1" --export "$T/x1"
expect export 143 "export interrupted after" "$T"
check "[ ! -e $T/x1/index.csv ]" "export: index.csv written by a stopped export"
stopped export_int INT "$T/x2/*.json" "$OB" $RUN --out "$T/r2" --export "$T/x2"
expect export_int 130 "export interrupted after" "$T"

# tables: the signal during its jobs; nothing written
stopped tables TERM "$T/t" "$OB" tables --out "$T/t"
mkdir -p "$T/t"
expect tables 143 "nothing written" "$T/t"
check "[ ! -e $T/t/tables.csv ]" "tables: tables.csv written by stopped tables"

# run without --export: the driver stops, the journal is kept (a run long
# enough, several seconds, that the signal comes while the driver works)
LONG="run --random 200:3 --methods tiller,cobb,ahn --tols 1e-3,1e-4,1e-5"
stopped run INT "$T/r3/results.journal.csv" "$OB" $LONG --out "$T/r3"
expect run 130 "resume" "$T/r3"
check "[ -e $T/r3/results.journal.csv ]" "run: the journal is gone"

e2e_done
