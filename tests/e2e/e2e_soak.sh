#!/bin/sh
# Soak: one run SIGKILLed at SOAK_KILLS random moments (default 20), each
# kill followed by `--resume DIR` (itself killed by the next one: a kill may
# land in the start, the journal, a resume's replay or the final writes),
# then a last --resume left to finish, must end in the uninterrupted run's
# results.csv (timing columns aside), with the journal gone.  The moments are
# uniform over the uninterrupted run's duration (as measured here, so a
# slower build, e.g. `make SAN=1 test`, gets longer ones), seeded by
# SOAK_SEED (default the clock; printed on a failure).  SOAK_RUN: the run's
# options (default a small one: `make test` stays well under a minute);
# `make soak` runs a longer variant (docs/contributing.md "Testing").
. "$(dirname "$0")/lib_e2e.sh"
now() { date +%s.%N; }

KILLS=${SOAK_KILLS:-20}
R=${SOAK_RUN:-"--random 6:5 --methods tiller,cobb,ahn --tols 1e-2,1e-3 --backend cpu"}
seed=${SOAK_SEED:-$(date +%s)}

t0=$(now)
$OB run $R --out "$T/ref" >/dev/null 2>&1
check '[ $? -eq 0 ]' "reference run"
dur=$(echo "$(now) $t0" | awk '{print $1 - $2}')
body "$T/ref/results.csv" > "$T/ref.txt"

awk -v d="$dur" -v s="$seed" -v n="$KILLS" 'BEGIN{srand(s); for (i = 0; i < n; i++) printf "%.3f\n", d * rand()}' > "$T/at"
D="$T/k"
log="" done_runs=0
k=1
while [ $k -le "$KILLS" ]; do
    at=$(sed -n "${k}p" "$T/at")
    # nothing there yet (killed before the journal was made): a plain run
    if [ -e "$D/results.journal.csv" ] || [ -e "$D/results.csv" ]; then
        $OB run $R --resume "$D" >/dev/null 2>"$T/err" &
    else
        $OB run $R --out "$D" >/dev/null 2>"$T/err" &
    fi
    pid=$!
    sleep "$at"
    kill -9 $pid 2>/dev/null
    wait $pid 2>/dev/null
    rc=$?
    log="$log $at:$rc"
    # 137: killed; 0: it finished first; anything else is a refusal or a crash
    if [ $rc -ne 137 ] && [ $rc -ne 0 ]; then
        bad "kill $k (seed $seed) after ${at} s: the run ended with exit $rc: $(tail -n 3 "$T/err")"
        break
    fi
    # it finished before the kill: the result must be the reference one, and
    # the next kill goes to a fresh run
    if [ $rc -eq 0 ]; then
        body "$D/results.csv" > "$T/k.txt" 2>/dev/null
        check 'cmp -s "$T/k.txt" "$T/ref.txt" && [ ! -e "$D/results.journal.csv" ]' \
            "kill $k (seed $seed): the run finished first, with other results: moment:exit$log"
        rm -rf "$D"
        done_runs=$((done_runs + 1))
    fi
    k=$((k + 1))
done
ok
[ -n "$SOAK_VERBOSE" ] && echo "run ${dur} s; $done_runs finished between kills; moment:exit$log"
if [ -e "$D/results.journal.csv" ] || [ -e "$D/results.csv" ]; then
    $OB run $R --resume "$D" >/dev/null 2>"$T/err"
else
    $OB run $R --out "$D" >/dev/null 2>"$T/err"
fi
rc=$?
body "$D/results.csv" > "$T/k.txt" 2>/dev/null
check '[ $rc -eq 0 ] && cmp -s "$T/k.txt" "$T/ref.txt" && [ ! -e "$D/results.journal.csv" ]' \
    "$KILLS kills (seed $seed, run ${dur} s; moment:exit$log), then --resume: exit $rc, $(grep -c . "$T/k.txt" 2>/dev/null) of $(grep -c . "$T/ref.txt") lines; $(tail -n 2 "$T/err")"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
