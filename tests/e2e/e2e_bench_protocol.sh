#!/bin/sh
# `bench --protocol` (host/cli/bench_protocol.c): the external-method
# protocol's figures, taken in one run.  Checks what they are, never how
# fast (the machine is shared): the rows per fit call of tiller in process,
# through `offbench worker tiller` and through the Python port, each with
# its interquartile range, the overhead rows, the Python method's and the
# built-in's runs on 1 and all threads with the same rows; --protocol with
# --kernels refused.
# Uses $OFFBENCH (set by make) or ./offbench; python3 for the Python rows.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2

"$OB" bench --protocol --quick --out "$T/b" >"$T/out" 2>"$T/err"
check '[ $? -eq 0 ] && [ -f "$T/b/bench.csv" ]' "bench --protocol --quick: exit 0 and bench.csv: $(tail -n 3 "$T/err")"
C=$T/b/bench.csv
has() { grep -q "^$1," "$C"; }
check 'has protocol/fit_call/tiller/builtin && has protocol/fit_call/tiller/worker && has protocol/fit_call_iqr/tiller/worker && has protocol/overhead/tiller/worker' \
    "per fit call: built-in, worker, its IQR and the overhead: $(cut -d, -f1 "$C" | tr '\n' ' ')"
check '[ -z "$(awk -F, "NR > 1 && !(\$6 + 0 > 0) && \$1 !~ /overhead|iqr/" "$C")" ]' \
    "every figure but the differences is positive: $(awk -F, 'NR > 1 && !($6 + 0 > 0)' "$C" | tr '\n' ' ')"
check 'has "protocol/random10_7/tiller" && [ "$(grep -c "^protocol/random10_7/tiller," "$C")" -eq 2 ]' \
    "the built-in's run on 1 and all threads: $(grep "^protocol/random10_7" "$C" | tr '\n' ' ')"
if command -v python3 >/dev/null 2>&1; then
    check 'has protocol/fit_call/tiller/python && [ "$(grep -c "^protocol/random10_7/tiller_py," "$C")" -eq 2 ] && [ "$(grep -c "the same rows" "$T/out")" -eq 2 ]' \
        "the Python method per call and on 1 and all threads, the same rows: $(cat "$T/out")"
else
    echo "e2e_bench_protocol: no python3: the Python figures' check skipped"
    skipped=$((skipped + 1))
fi
"$OB" bench --protocol --kernels --out "$T/k" 2>"$T/k.err"
check '[ $? -eq 2 ] && [ ! -e "$T/k/bench.csv" ]' "--protocol with --kernels: exit 2: $(cat "$T/k.err")"
e2e_done
