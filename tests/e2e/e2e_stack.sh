#!/bin/sh
# End-to-end tests of the thread stack check (host/run/stack.c, docs/commands.md
# "Command line"): an OMP_STACKSIZE (or GOMP_STACKSIZE, or stack limit) below
# what offbench's threads need crashed them with SIGSEGV; now it is refused
# before any work, exit 2, naming the setting and the minimum, and nothing is
# written.  A size at the minimum runs every method with the deepest sampled
# metric table (--samples 512), the workload that crashed at 64K and 80K.
# Uses $OFFBENCH or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

MIN=512K
J="--random 20:3 --methods all --samples 512 --backend cpu --threads 2"

# refused VAR=VALUE TEXT: run exits 2 saying TEXT, no crash, nothing written
refused() {
    env "$1" $OB run $J --out "$T/no" >/dev/null 2>"$T/err"; rc=$? pat=$2
    check '[ $rc -eq 2 ] && grep -qF -- "$pat" "$T/err" && [ ! -e "$T/no" ]' \
        "$1: exit 2 saying '$2', nothing written (rc $rc): $(cat "$T/err")"
    rm -rf "$T/no"
}
for v in 16K 64K 64k 100 511K 524287B 0; do
    refused "OMP_STACKSIZE=$v" "OMP_STACKSIZE='$v' is below the $MIN"
done
for v in lots 1X 1KB -1 1.5M "" 99999999999999999999G; do
    refused "OMP_STACKSIZE=$v" "OMP_STACKSIZE='$v': not a stack size"
done
refused "GOMP_STACKSIZE=64K" "GOMP_STACKSIZE='64K' is below the $MIN"
# every command runs on these threads: the check is the program's, not run's
for c in "tables --out $T/no" "draw --curve x --method tiller --tol 0.1 --out $T/no.svg" "list curves" "atlas --out $T/no"; do
    # shellcheck disable=SC2086
    OMP_STACKSIZE=64K $OB $c >/dev/null 2>"$T/err"
    check '[ $? -eq 2 ] && grep -q "OMP_STACKSIZE" "$T/err" && [ ! -e "$T/no" ]' "$c with OMP_STACKSIZE=64K: exit 2"
    rm -rf "$T/no"
done

# sizes that work: the minimum, a large one, and GOMP_STACKSIZE losing to OMP_STACKSIZE
env -u OMP_STACKSIZE -u GOMP_STACKSIZE $OB run $J --out "$T/ref" 2>/dev/null
check '[ $? -eq 0 ]' "the workload runs with the default stacks"
for v in "OMP_STACKSIZE=$MIN" "OMP_STACKSIZE=16M" "OMP_STACKSIZE=1g" "OMP_STACKSIZE=8M GOMP_STACKSIZE=64K"; do
    # shellcheck disable=SC2086
    env $v $OB run $J --out "$T/ok" 2>"$T/err"
    check '[ $? -eq 0 ] && [ "$(body "$T/ok/results.csv")" = "$(body "$T/ref/results.csv")" ]' \
        "$v: runs, the same rows as the default: $(tail -n 1 "$T/err")"
    rm -rf "$T/ok"
done

# the main thread's stack (and the workers' when no variable is set): the stack limit
if (ulimit -s 64) 2>/dev/null; then
    (ulimit -s 64; env -u OMP_STACKSIZE $OB run $J --out "$T/no" >/dev/null 2>"$T/err"); rc=$?
    check '[ $rc -eq 2 ] && grep -q "stack limit (ulimit -s) is 64K" "$T/err" && [ ! -e "$T/no" ]' \
        "ulimit -s 64: exit 2 naming the stack limit (rc $rc): $(cat "$T/err")"
    rm -rf "$T/no"
    (ulimit -s 512; env -u OMP_STACKSIZE -u GOMP_STACKSIZE $OB run $J --out "$T/ok0" >/dev/null 2>"$T/err"); rc=$?
    check '[ $rc -eq 0 ]' "ulimit -s 512 (the minimum), no variable: runs (rc $rc): $(cat "$T/err")"
    (ulimit -s 100000; OMP_STACKSIZE=$MIN $OB run --random 20:3 --methods all --samples 512 --backend cpu --threads 1 --out "$T/ok1" >/dev/null 2>"$T/err"); rc=$?
    check '[ $rc -eq 0 ]' "ulimit -s 100000: runs (rc $rc): $(cat "$T/err")"
else
    skipped=$((skipped + 3))
fi

e2e_done
