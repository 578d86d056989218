#!/bin/sh
# `offbench worker METHOD` (host/cli/cmd_worker.c): every built-in method
# served over the external-method protocol (docs/external-methods.md) gives
# the built-in's rows: bit for bit where the pieces are polynomial, to
# rounding where a piece is rational (the protocol's Euclidean points), and
# zhao-rational's answers with a weight <= 0 are refused by the protocol
# with that message (tests/e2e/worker_rows.py says which is which).  The
# methods the protocol cannot carry are refused with the reason, exit 2:
# kim2018, ahn, lee and exact (an output degree that is neither the
# input's nor one number), sisl (a parameter named as the supervisor's
# own).  Bad arguments and bad requests: exit 2, error answers.
# Uses $OFFBENCH (set by make) or ./offbench; python3.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2

all=$("$OB" list methods | awk 'NR > 1 && $1 ~ /^[a-z]/ {print $1}')
served="" refused=""
for m in $all; do
    if "$OB" worker "$m" </dev/null >"$T/hello.$m" 2>"$T/err.$m"; then served="$served $m"; else refused="$refused $m"; fi
done
check '[ "$(echo $refused)" = "kim2018 ahn lee exact" ]' \
    "worker refuses exactly kim2018 ahn lee exact (their output degree): refused:$refused"
check 'grep -q "cannot be served: its output degree is neither the input" "$T/err.ahn"' "ahn's refusal says why: $(cat "$T/err.ahn")"
check '[ "$(echo $served | wc -w)" -ge 13 ]' "worker serves the other built-ins: $served"

# sisl's hello declares a parameter named as the supervisor's own: the
# registration refuses it, naming the parameter
"$OB" --external "s_w=$OB worker sisl" list methods >/dev/null 2>"$T/sisl.err"
check '[ $? -eq 2 ] && grep -q "the name \"wall_timeout\" is taken" "$T/sisl.err"' "sisl over the protocol: refused naming the parameter: $(cat "$T/sisl.err")"

rat_curves=$("$OB" list curves --random 8:5 | awk '$1 == "id" {for (i = 1; i <= NF; i++) if ($i == "rational") k = i} k && $k == "yes" {printf "%s,", $1}')
rat_methods=$("$OB" list methods | awk 'NR > 1 && $2 == "rational" {printf "%s,", $1}')
set -- $(echo $served | tr ' ' '\n' | grep -v '^sisl$')
batch=0
while [ $# -gt 0 ]; do  # at most 8 external methods a run: 6 a batch
    batch=$((batch + 1)) n=0 ml="" cmd='"$OB"'
    for m in "$@"; do
        [ $n -lt 6 ] || break
        n=$((n + 1)) ml="$ml,$m,${m}_w"
        cmd="$cmd --external \"${m}_w=\$OB worker $m\""  # words with spaces: built for eval
    done
    eval "$cmd run --methods \"${ml#,}\" --random 8:5 --tols 1e-2,1e-4 --backend cpu --out \"\$T/b$batch\"" \
        >/dev/null 2>"$T/b$batch.err"
    check '[ $? -eq 0 ]' "run of batch $batch (${ml#,}): exit 0: $(tail -n 3 "$T/b$batch.err")"
    out=$(python3 tests/e2e/worker_rows.py "$T/b$batch/results.csv" "$rat_curves" "$rat_methods")
    check '[ $? -eq 0 ]' "batch $batch: the worker's rows are the built-in's: $out"
    echo "$out" | sed 's/^/  /'
    shift $n
done

# bad arguments and requests
"$OB" worker nosuch </dev/null 2>"$T/e1"
check '[ $? -eq 2 ] && grep -q "not a built-in method" "$T/e1"' "worker nosuch: exit 2 naming it: $(cat "$T/e1")"
"$OB" worker </dev/null 2>"$T/e2"
check '[ $? -eq 2 ]' "worker without a method: exit 2: $(cat "$T/e2")"
printf '%s\n' 'not json' '{"id":1}' '{"id":2,"degree":1,"points":[[0,0],[1,0]],"weights":[1,0],"d":0.5,"tol":0.001,"params":{}}' \
    '{"id":3,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":0.5,"tol":0.001,"params":{"k":1}}' \
    '{"id":4,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":0.5,"tol":0.001,"params":{}}' |
    "$OB" worker tiller >"$T/hand" 2>"$T/hand.err"
check '[ $? -eq 0 ] && [ "$(grep -c "\"error\":" "$T/hand")" -eq 4 ] && tail -n 1 "$T/hand" | grep -q "^{\"id\":4,\"pieces\":\[{\"degree\":1,\"points\":\[\[0,0.5\],\[1,0.5\]\]"' \
    "4 bad requests: 4 error answers, then a good one: $(tr '\n' ' ' <"$T/hand" | cut -c 1-700)"
e2e_done
