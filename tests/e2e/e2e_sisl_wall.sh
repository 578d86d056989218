#!/bin/sh
# SISL's wall-clock cap (issue 46, methods/sisl.c): s1360 runs in a server
# process with a CPU deadline (sisl.timeout); on a loaded machine that
# deadline took minutes of wall time, so a wall-clock cap stops the call as
# well (sisl.wall_timeout, default 3 x (timeout + 1) s) and the job's status
# is `timeout` (the load decided, not the input), its message naming the
# cap.  The load is the test hook OFFBENCH_TEST_SISL_SLEEP=S: the server
# sleeps S wall-clock seconds (no CPU time) before each call, as a server
# that gets no CPU would wait; S is far beyond every cap here, so which
# limit fires never depends on this machine's speed (no timed assertion).
# - the default cap (timeout 0.1 s: 3.3 s) and an explicit one (0.5 s) stop
#   the sleeping server: every row `timeout`, the message names the cap;
# - a fit that finishes is unaffected: without the hook, the rows with a
#   cap given or not are the same;
# - the parameter is recorded in meta.json and refused outside its range.
. "$(dirname "$0")/lib_e2e.sh"
R="--curve liu2002_ex1 --methods sisl --tols 1e-2 --backend cpu --threads 2"

# the default cap: 3 x (0.1 + 1) = 3.3 s
OFFBENCH_TEST_SISL_SLEEP=600 "$OB" run $R --param sisl.timeout=0.1 --out "$T/d" >/dev/null 2>"$T/d.err"
rc=$?
st=$(rcols "$T/d/results.csv" status 2>/dev/null | sort -u | tr '\n' ' ')
check '[ $rc -eq 0 ] && [ "$st" = "timeout " ]' "a server that gets no CPU, default cap: every row timeout: exit $rc, statuses '$st' $(tail -n 2 "$T/d.err")"
n=$(awkc 'NR>1 && v("message") ~ /wall-clock cap of 3\.3 s \(sisl\.wall_timeout; CPU deadline 0\.1 s\) at t in/' "$T/d/results.csv" | wc -l)
check '[ "$n" -eq 2 ]' "... the message names the cap (3.3 s) and the CPU deadline: $n of 2 rows: $(rcols "$T/d/results.csv" message | head -n 1)"

# an explicit cap
OFFBENCH_TEST_SISL_SLEEP=600 "$OB" run $R --param sisl.wall_timeout=0.5 --out "$T/e" >/dev/null 2>"$T/e.err"
rc=$?
n=$(awkc 'NR>1 && $c["status"] == "timeout" && v("message") ~ /wall-clock cap of 0\.5 s \(sisl\.wall_timeout; CPU deadline 20 s\)/' "$T/e/results.csv" | wc -l)
check '[ $rc -eq 0 ] && [ "$n" -eq 2 ]' "--param sisl.wall_timeout=0.5: both rows timeout, naming the cap: exit $rc, $n rows $(tail -n 2 "$T/e.err")"
check 'grep -q "\"sisl.wall_timeout\": 0.5" "$T/e/meta.json"' "meta.json records sisl.wall_timeout"

# a fit that finishes is unaffected by the cap
"$OB" run $R --out "$T/a" >/dev/null 2>&1
"$OB" run $R --param sisl.wall_timeout=600 --out "$T/b" >/dev/null 2>&1
check '[ "$(rcols "$T/a/results.csv" status | sort -u)" = ok ] && [ "$(body "$T/a/results.csv")" = "$(body "$T/b/results.csv")" ]' \
    "without the hook the fits finish: the same rows with and without a cap: $(rcols "$T/a/results.csv" status message | head -n 2)"

# the range
"$OB" run $R --param sisl.wall_timeout=-1 --out "$T/r" >/dev/null 2>"$T/r.err"
check '[ $? -eq 2 ] && grep -q "sisl.wall_timeout" "$T/r.err"' "sisl.wall_timeout=-1 refused: $(cat "$T/r.err")"

e2e_done
