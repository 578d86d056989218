#!/bin/sh
# A nightly that dies still reports (issue 46, scripts/nightly.sh): killed
# by SIGTERM (`timeout`, a CI job's time limit) inside a run stage, it
# writes OUT/status = 2, records the night in the history store with the
# stage it reached ("run published (killed by SIGTERM)"), rebuilds the site
# and exits 2; the offbench processes it started are stopped, and a second
# signal during the recording does not cut it short or leave half a run in
# the store.
# Deterministic: the nightly runs only sisl, whose server sleeps (the test
# hook OFFBENCH_TEST_SISL_SLEEP: no CPU time, far longer than the test
# waits), so the published run is still running when the test, having
# seen its log appear, sends the signal itself.  Two ways in:
# - kill -TERM to nightly.sh alone: its trap must stop its child;
# - kill -TERM to a `timeout` around it, again and again: timeout passes
#   each to the nightly and its whole process group, as at a time limit.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
export NIGHTLY_BIN="$OB" NIGHTLY_BASELINE="$T/committed" NIGHTLY_BASELINES="$T/machines" NIGHTLY_RANDOM=2:2026 \
    NIGHTLY_METHODS=sisl NIGHTLY_CURVES=liu2002_ex1 NIGHTLY_BACKEND=cpu OFFBENCH_MACHINE=e2e-box \
    OFFBENCH_TEST_SISL_SLEEP=3000 E2E_NIGHTLY_MARK="$T"
unset OFFBENCH_TEST_SLOW OFFBENCH_LOADAVG NIGHTLY_SITE NIGHTLY_KEEP NIGHTLY_KEEP_DAYS

# until_file FILE PID: waits for FILE to appear while PID runs (at most 2 min)
until_file() {
    i=0
    while [ ! -e "$1" ] && kill -0 "$2" 2>/dev/null && [ $i -lt 1200 ]; do sleep 0.1; i=$((i + 1)); done
    [ -e "$1" ]
}
# the processes of this test's nights still there (the marker in their environment)
leftovers() {
    for p in /proc/[0-9]*; do
        [ "${p#/proc/}" = $$ ] && continue
        tr '\0' '\n' 2>/dev/null < "$p/environ" | grep -qxF "E2E_NIGHTLY_MARK=$T" && \
            printf '%s ' "${p#/proc/}:$(tr '\0' ' ' < "$p/cmdline" 2>/dev/null | cut -c1-60)"
    done
}
# no_leftovers: none of them within 20 s (a killed server ends when it sees its pipe close)
no_leftovers() {
    i=0
    while [ -n "$(leftovers)" ] && [ $i -lt 200 ]; do sleep 0.1; i=$((i + 1)); done
    [ -z "$(leftovers)" ]
}
# the checks on one killed night: OUT HISTORY EXIT-STATUS WHAT
killed_checks() {
    o=$1 h=$2 rc=$3 what=$4
    check '[ "$rc" -eq 2 ] && [ "$(cat "$o/status" 2>/dev/null)" = 2 ]' \
        "$what: exit 2 and OUT/status 2: exit $rc, status '$(cat "$o/status" 2>/dev/null)': $(tail -n 3 "$o.err")"
    runs=$(ls "$h" 2>/dev/null | grep -v '^site$')
    rj="$h/$runs/run.json"
    check '[ "$(echo "$runs" | grep -c .)" -eq 1 ] && grep -q "\"status\": 2," "$rj" && grep -q "\"stage\": \"run published (killed by SIGTERM)\"" "$rj" && grep -qF "\"baseline\": \"$T/committed\"" "$rj"' \
        "$what: one run in the store, run.json status 2 at the stage reached, NIGHTLY_BASELINE recorded: $runs $(cat "$rj" 2>/dev/null | tr '\n' ' ')"
    check '[ -f "$h/$runs/published.log" ] && [ -z "$(ls -A "$h" | grep "^\.")" ]' \
        "$what: the stage's log kept, no half-copied run: $(ls -A "$h" "$h/$runs" 2>/dev/null | tr '\n' ' ')"
    check 'grep -q "^run published (killed by SIGTERM),[0-9.]*$" "$o/timings.csv" 2>/dev/null' \
        "$what: OUT/timings.csv has the stage's seconds: $(cat "$o/timings.csv" 2>/dev/null | tr '\n' ' ')"
    if [ -x /usr/bin/python3 ]; then
        check '[ -f "$h/site/index.html" ] && grep "class=\"stage\"" "$h/site/index.html" | grep "killed by SIGTERM" | grep -q "published.log"' \
            "$what: the site rebuilt, showing the stage and linking its log: $(grep "class=\"stage\"" "$h/site/index.html" 2>/dev/null)"
    else
        echo "skipped: no /usr/bin/python3, so no site to check"; skipped=$((skipped + 1))
    fi
    check 'no_leftovers' "$what: no process of the night left: $(leftovers)"
    if [ -x /usr/bin/python3 ]; then
        /usr/bin/python3 "$ROOT/scripts/nightly_wall.py" "$o" --out "$T/wall.txt" >/dev/null 2>"$T/err"
        check '[ $? -eq 2 ] && [ ! -e "$T/wall.txt" ] && grep -q "failed" "$T/err"' \
            "$what: nightly_wall.py refuses a killed night (its stages are not a night's): $(cat "$T/err")"
    fi
}

# --- SIGTERM to nightly.sh alone, inside the published run ---
sh "$ROOT/scripts/nightly.sh" --out "$T/a" --history "$T/ha" >/dev/null 2>"$T/a.err" &
pid=$!
until_file "$T/a/published.log" $pid
check '[ $? -eq 0 ]' "the published run starts: $(tail -n 3 "$T/a.err")"
kill -TERM $pid
wait $pid
killed_checks "$T/a" "$T/ha" $? "SIGTERM to nightly.sh"

# --- SIGTERM through timeout, to the whole process group, again and again ---
timeout -s TERM 600 sh "$ROOT/scripts/nightly.sh" --out "$T/b" --history "$T/hb" >/dev/null 2>"$T/b.err" &
pid=$!
until_file "$T/b/published.log" $pid
k=0
while kill -TERM $pid 2>/dev/null && [ $k -lt 300 ]; do k=$((k + 1)); sleep 0.05; done
wait $pid
killed_checks "$T/b" "$T/hb" $? "SIGTERM through timeout, $k times"

e2e_done
