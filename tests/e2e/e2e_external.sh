#!/bin/sh
# External methods (issue 49 item 1, docs/external-methods.md): a program
# in any language registered with --external NAME=COMMAND, one supervised
# worker per thread.
# - `list methods` shows it with its citation, output degree, continuity,
#   its command and the supervisor's parameters;
# - the Python port examples/external/tiller.py gives the built-in
#   tiller's rows exactly (every column but the timings), with 1 and 2
#   threads, every engine and the OpenCL backend where there is a device;
# - a resume with another program under the name is refused;
# - a worker that crashes, hangs, spins, runs out of memory, prints
#   garbage, a NaN, an infinity, another id, too many pieces, a wrong
#   degree or weight: a `fail` row naming the method and quoting what it
#   sent, every other row present and ok (the worker restarted), exit 0
#   as for any run with failed jobs; an answered error is the row's
#   message; the job's --job-timeout budget caps the worker's CPU time;
# - a command that does not start: exit 2, the option named;
# - the run's fingerprint holds the external command's hash.
# No timing assertion: every cap here is far from what the test waits
# (a spinning worker gets a wall-clock cap of 600 s: only its CPU cap may
# end it, however loaded the machine; a hanging one 5 s, answers take ms).
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PORT="python3 $ROOT/examples/external/tiller.py"
BAD="python3 $ROOT/tests/e2e/external_bad.py"

"$OB" --external "tiller_py=$PORT" list methods >"$T/list" 2>"$T/list.err"
check '[ $? -eq 0 ] && grep -q "^tiller_py .* n .*G0 .*Tiller & Hanson 1984, IEEE CG&A 4(9):36-46 (Python port)" "$T/list" && grep -q "external method: $PORT" "$T/list" && grep -q "tiller_py.wall_timeout=10" "$T/list"' \
    "list methods shows the external method, its degree, continuity, citation and command: $(grep tiller_py "$T/list" | head -n 2) $(cat "$T/list.err")"

# the port's rows are the built-in's (method renamed for the comparison)
C="--curve liu2002_ex1,liu2002_ex2,atlas_circle,atlas_folium,zhao2017_quintic,ph_cubic"
R="$C --backend cpu"
for th in 1 2; do
    "$OB" run $R --external "tiller_py=$PORT" --methods tiller,tiller_py --threads $th --out "$T/p$th" >/dev/null 2>"$T/p$th.err"
    check '[ $? -eq 0 ]' "run with the port, --threads $th: $(tail -n 2 "$T/p$th.err")"
    awkc 'NR==1 || $c["method"]=="tiller"' "$T/p$th/results.csv" >"$T/b$th.csv"
    awkc 'NR==1 || $c["method"]=="tiller_py"' "$T/p$th/results.csv" | sed 's/,tiller_py,/,tiller,/' >"$T/e$th.csv"
    out=$(python3 "$ROOT/scripts/same_rows.py" "$T/b$th.csv" "$T/e$th.csv")
    check '[ $? -eq 0 ] && [ "$(wc -l <"$T/b$th.csv")" -gt 20 ]' "--threads $th: the port's rows equal the built-in's: $out"
done
out=$(python3 "$ROOT/scripts/same_rows.py" "$T/p1/results.csv" "$T/p2/results.csv")
check '[ $? -eq 0 ]' "--threads 1 and 2 give the same rows: $out"
# every engine, and the OpenCL backend where there is a device: the same rows
for e in group level; do
    "$OB" run $R --external "tiller_py=$PORT" --methods tiller,tiller_py --engine $e --out "$T/g$e" >/dev/null 2>&1
    out=$(python3 "$ROOT/scripts/same_rows.py" "$T/p2/results.csv" "$T/g$e/results.csv")
    check '[ $? -eq 0 ]' "--engine $e gives the same rows: $out"
done
if "$OB" run $C --external "tiller_py=$PORT" --methods tiller,tiller_py --backend opencl --engine device --out "$T/cl" >/dev/null 2>"$T/cl.err"; then
    out=$(python3 "$ROOT/scripts/same_rows.py" "$T/p2/results.csv" "$T/cl/results.csv")
    check '[ $? -eq 0 ]' "--backend opencl --engine device gives the same rows: $out"
else
    echo "no OpenCL device: $(tail -n 1 "$T/cl.err")"
    skipped=$((skipped + 1))
fi
check 'grep -q "external.tiller_py=[0-9a-f]\{16\}" "$T/p1/results.fingerprint"' "the fingerprint names the external method's hash"
"$OB" run --external "tiller_py=$BAD crash" --resume "$T/p1" >/dev/null 2>"$T/r1.err"
check '[ $? -ne 0 ] && grep -q -- "--external tiller_py (the program: its command or hello line) differs" "$T/r1.err"' "--resume refuses another program under the name: $(cat "$T/r1.err")"
"$OB" run --external "tiller_py=$PORT" --resume "$T/p1" >/dev/null 2>"$T/r2.err"
check '[ $? -eq 0 ] && grep -q "0 to run" "$T/r2.err"' "--resume with the same program: $(cat "$T/r2.err")"

# broken workers: liu2002_ex1 d=-1 misbehaves; its d=1 row and ph_cubic's
# (after it, one thread) are answered by a restarted worker
B="--curve liu2002_ex1,ph_cubic --tols 1e-2 --backend cpu --threads 1 --methods bad"
WANT="1:ok -1:fail 0.2:ok "
msg_of() {  # FILE: the d=-1 row's message, unquoted
    awkc 'NR>1 && $c["d"]=="-1" {print v("message")}' "$1" 2>/dev/null | sed 's/^"//; s/"$//; s/""/"/g'
}
bad_case() {  # MODE STATUS PATTERN [OPTIONS...]: the d=-1 row has STATUS, PATTERN in its message
    mode=$1 want=$2 pat=$3; shift 3
    "$OB" run $B --external "bad=$BAD $mode" "$@" --out "$T/$mode-$want" >/dev/null 2>"$T/$mode.err"
    rc=$?
    f="$T/$mode-$want/results.csv"
    st=$(rcols "$f" d status 2>/dev/null | tr '\n' ' ')
    msg=$(msg_of "$f")
    check '[ $rc -eq 0 ] && [ "$st" = "1:ok -1:$want 0.2:ok " ] && printf "%s" "$msg" | grep -q "$pat"' \
        "$mode: exit $rc (want 0), statuses '$st' (want 1:ok -1:$want 0.2:ok), message '$msg' (want /$pat/) $(tail -n 2 "$T/$mode.err")"
}
bad_case crash fail "^bad died (exit status 1) after sending ''; restarted"
bad_case hang fail "^bad hung (no answer in bad.wall_timeout 5 s), sent ''" --param bad.wall_timeout=5
bad_case spin fail "^bad died (killed by signal 24" --param bad.cpu_timeout=1 --param bad.wall_timeout=600
bad_case mem fail "^bad died (exit status 1)" --param bad.mem_mb=300
check 'grep -q MemoryError "$T/mem.err"' "the memory cap: python's MemoryError on stderr: $(tail -n 3 "$T/mem.err")"
bad_case garbage fail "^bad sent 'hello, this is not JSON': not a JSON value at byte 0; restarted"
bad_case nan fail "^bad sent '{\"id\": [0-9]*, \"pieces\": \[{\"degree\": 3, \"poin\.\.\.': not a JSON value at byte"
bad_case inf fail "^bad sent .*: a number out of the double range at byte"
bad_case wrongid fail "^bad sent '{\"id\": [0-9]*, .*\"id\" is not [0-9]*; restarted"
bad_case huge fail "^bad sent .*: no \"error\", no \"pieces\" (1 to 64); restarted"
bad_case baddeg fail "^bad sent .*: \"degree\" is not 3; restarted"
bad_case badweight fail "^bad sent .*: \"weights\" is not 4 numbers > 0; restarted"
bad_case error fail "^no offset for d = -1 here at t in"
bad_case skip skip "^d = -1 does not apply at t in"
bad_case params fail '^params {"scale": 2} at t in' --param bad.scale=2
# the job's --job-timeout budget caps the worker's CPU time: a timeout row
B="$B --job-timeout 1"
bad_case spin timeout "^job timeout (the worker of external method bad reached" --param bad.wall_timeout=600

# a plain Python function, no protocol code: offbench/worker.py FILE:FUNCTION
cat >"$T/mine.py" <<'PY'
METHOD = {"citation": "a polygon moved up by d", "degree": "same", "continuity": "G0", "caps": ["poly_out"]}


def shift(piece, d, tol):
    return [[(x, y + d) for x, y in piece.points]]
PY
"$OB" --external "mine=python3 $ROOT/python/offbench/worker.py $T/mine.py:shift" list methods >"$T/mine.list" 2>&1
check 'grep -q "^mine .*G0 .*a polygon moved up by d" "$T/mine.list"' "worker.py FILE:FUNCTION lists the METHOD dict: $(grep mine "$T/mine.list")"
"$OB" run --external "mine=python3 $ROOT/python/offbench/worker.py $T/mine.py:shift" --methods mine --curve liu2002_ex1 --tols 1e-2 --backend cpu --out "$T/mine" >/dev/null 2>"$T/mine.err"
check '[ $? -eq 0 ] && [ "$(rcols "$T/mine/results.csv" method status | sort -u)" = "mine:limit" ]' \
    "worker.py FILE:FUNCTION runs (a poor method: limit rows): $(rcols "$T/mine/results.csv" method status message) $(tail -n 2 "$T/mine.err")"

# a command that does not start, a malformed option
"$OB" run --external "nope=$T/no-such-program" --out "$T/n" >/dev/null 2>"$T/n.err"
check '[ $? -eq 2 ] && grep -q "^offbench: --external nope=.*no-such-program: no hello line from .* (exit status 127)" "$T/n.err"' \
    "a missing command: exit 2 naming the option: $(cat "$T/n.err")"
"$OB" list methods --external "tiller" >/dev/null 2>"$T/m.err"
check '[ $? -eq 2 ] && grep -q "^offbench: --external .tiller.: expected NAME=COMMAND" "$T/m.err"' "--external without '=': $(cat "$T/m.err")"
"$OB" list methods --external "tiller=$PORT" >/dev/null 2>"$T/t.err"
check '[ $? -eq 2 ] && grep -q "the name .tiller. is taken" "$T/t.err"' "a built-in's name refused: $(cat "$T/t.err")"

e2e_done
