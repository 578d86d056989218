#!/bin/sh
# The sisl method's server processes seen from the command line
# (methods/sisl/client.c, docs/reliability.md "The SISL server"):
# - an inherited OFFBENCH_SISL_SERVER does nothing: the program runs as
#   usual whatever it holds and whatever its descriptors are (it used to
#   exit 126 silently, or serve on stdin/stdout when those were pipes);
# - the server program run by hand says what it is and exits 2;
# - --job-timeout bounds a sisl job: a server that spins (the test hook
#   OFFBENCH_TEST_SISL_SPIN=S: S CPU seconds before each call) is stopped
#   at the job's remaining budget and the job's status is timeout, not a
#   failure after the method's own 20 s deadline;
# - a server killed during a fit: the row is fail, saying the server was
#   killed by signal 9, and the next job gets a fresh server (ok).
# No timed assertion: the hooks sleep or spin far beyond every limit.
. "$(dirname "$0")/lib_e2e.sh"
R="--curve liu2002_ex1 --methods sisl --backend cpu --threads 1"

"$OB" run $R --tols 1e-2 --out "$T/ref" >/dev/null 2>&1
for v in 3,4 0,1 x; do
    OFFBENCH_SISL_SERVER=$v "$OB" --help >"$T/h.out" 2>&1
    rc=$?
    check '[ $rc -eq 0 ] && grep -q "run" "$T/h.out"' "OFFBENCH_SISL_SERVER=$v offbench --help: exit $rc $(head -c 200 "$T/h.out")"
done
echo | OFFBENCH_SISL_SERVER=0,1 "$OB" list methods 2>"$T/l.err" | cat >"$T/l.out"
check 'grep -q sisl "$T/l.out"' "OFFBENCH_SISL_SERVER=0,1 with stdin and stdout pipes: offbench list methods prints the methods: $(head -c 200 "$T/l.out" "$T/l.err")"
OFFBENCH_SISL_SERVER=3,4 "$OB" run $R --tols 1e-2 --out "$T/env" >/dev/null 3<&0 4>&1 2>"$T/env.err"
rc=$?
check '[ $rc -eq 0 ] && [ "$(body "$T/env/results.csv")" = "$(body "$T/ref/results.csv")" ]' \
    "a sisl run with OFFBENCH_SISL_SERVER inherited: the same rows: exit $rc $(tail -n 2 "$T/env.err")"

SRV=$(dirname "$OB")/offbench-sisl-server
[ -x "$SRV" ] || SRV=$(dirname "$OB")/build/offbench-sisl-server
if [ -x "$SRV" ]; then
    OFFBENCH_SISL_SERVER=3 "$SRV" >"$T/s.out" 2>&1
    rc=$?
    check '[ $rc -eq 2 ] && grep -q "not by hand" "$T/s.out"' "the server program by hand: exit $rc $(cat "$T/s.out")"
fi

# --job-timeout 1 and a server that spins: status timeout, naming the job timeout
OFFBENCH_TEST_SISL_SPIN=600 "$OB" run $R --tols 1e-2 --job-timeout 1 --out "$T/jt" >/dev/null 2>"$T/jt.err"
rc=$?
st=$(rcols "$T/jt/results.csv" status 2>/dev/null | sort -u | tr '\n' ' ')
check '[ $rc -eq 0 ] && [ "$st" = "timeout " ]' "--job-timeout 1, a spinning server: every row timeout: exit $rc, '$st' $(rcols "$T/jt/results.csv" message 2>/dev/null | head -n 1) $(tail -n 2 "$T/jt.err")"

# a server killed during its fit (each server sleeps; every server is killed
# until the run ends: every row fail, saying signal 9)
OFFBENCH_TEST_SISL_SLEEP=600 "$OB" run $R --tols 1e-2 --out "$T/k" >/dev/null 2>"$T/k.err" &
run=$!
n=0
while kill -0 $run 2>/dev/null && [ $n -lt 3000 ]; do
    for p in $(ps -o pid= --ppid $run 2>/dev/null); do kill -9 "$p" 2>/dev/null; done
    n=$((n + 1))
    sleep 0.1
done
wait $run
rc=$?
st=$(rcols "$T/k/results.csv" status 2>/dev/null | sort -u | tr '\n' ' ')
m=$(rcols "$T/k/results.csv" message 2>/dev/null | head -n 1)
check '[ $rc -eq 0 ] && [ "$st" = "fail " ] && echo "$m" | grep -q "signal 9" && ! echo "$m" | grep -q "did not finish"' \
    "servers killed during their fits: every row fail, naming signal 9: exit $rc, '$st' $m"
# ... and a run after it is unaffected
"$OB" run $R --tols 1e-2 --out "$T/after" >/dev/null 2>&1
check '[ "$(body "$T/after/results.csv")" = "$(body "$T/ref/results.csv")" ]' "a run after it: the same rows"

e2e_done
