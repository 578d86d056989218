#!/bin/sh
# e2e_identity.sh - everything that can change a number is in the run's
# identity (docs/reliability.md "What a run directory guarantees"): a kernels/ or
# datasets/ directory in the working directory is not picked up; meta.json
# records kernel_fnv1a and data_hash; --resume, merge and compare check them.
. "$(dirname "$0")/lib_e2e.sh"
# the sources of the checkout (the program may be build-san/offbench)
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
KR="curve d method metric split tol ctrl_points segments out_degree max_err status"
metakey() { sed -n "s/.*\"$2\": \"\\([0-9a-f]*\\)\".*/\\1/p" "$1/meta.json" | head -n 1; }
# a kernel copy whose errors are doubled: it changes every max_err
mkdir -p "$T/wd"
cp -r "$ROOT/kernels" "$T/wd/kernels"
sed -i 's/err\[i\] = e;/err[i] = 2.0 * e;/' "$T/wd/kernels/measure.cl"
check 'grep -q "2.0 \* e" "$T/wd/kernels/measure.cl"' "the test's kernel copy is modified"
RUN="run --backend opencl --methods cobb --tols 1e-1"
if ! $OB $RUN --out "$T/probe" >/dev/null 2>&1; then
    echo "no OpenCL device: the kernel checks are skipped"; skipped=$((skipped + 1))
else
    # a run started beside another kernels/ uses the compiled-in kernel
    (cd "$T" && $OB $RUN --out emb >/dev/null 2>&1)
    (cd "$T/wd" && $OB $RUN --out "$T/cwd" >/dev/null 2>&1)
    check '[ $? -eq 0 ]' "a run in a directory with kernels/ runs"
    csvcols "$T/emb/results.csv" $KR > "$T/emb.cut"
    csvcols "$T/cwd/results.csv" $KR > "$T/cwd.cut"
    check '[ -s "$T/emb.cut" ] && cmp -s "$T/emb.cut" "$T/cwd.cut"' "./kernels is not picked up: the embedded kernel's results"
    ke=$(metakey "$T/emb" kernel_fnv1a); kc=$(metakey "$T/cwd" kernel_fnv1a)
    check '[ -n "$ke" ] && [ "$ke" = "$kc" ]' "meta.json kernel_fnv1a is the embedded kernel's: '$ke' '$kc'"
    check 'grep -q "\"kernels\": \"embedded" "$T/cwd/meta.json"' "meta.json names the embedded kernel"
    # $OFFBENCH_KERNELS names another kernel: another hash, recorded
    OFFBENCH_KERNELS="$T/wd/kernels" $OB $RUN --out "$T/env" >/dev/null 2>&1
    kv=$(metakey "$T/env" kernel_fnv1a)
    check '[ -n "$kv" ] && [ "$kv" != "$ke" ]' "OFFBENCH_KERNELS: another kernel_fnv1a: '$kv'"
    # --resume with another kernel is refused, naming it
    OFFBENCH_KERNELS="$T/wd/kernels" $OB $RUN --resume "$T/emb" >/dev/null 2>"$T/res.err"
    check '[ $? -eq 2 ] && grep -q "kernel_fnv1a" "$T/res.err"' "--resume with another kernel exits 2 naming it: $(cat "$T/res.err")"
    $OB $RUN --resume "$T/emb" >/dev/null 2>"$T/res2.err"
    check '[ $? -eq 0 ]' "--resume with the same kernel runs: $(cat "$T/res2.err")"
    # compare: another kernel is not comparable
    $OB compare "$T/emb" "$T/env" >"$T/cmp.out" 2>&1
    check '[ $? -eq 3 ] && grep -q "kernel_fnv1a" "$T/cmp.out"' "compare of two kernels exits 3 naming kernel_fnv1a"
    $OB compare "$T/emb" "$T/cwd" >"$T/cmp2.out" 2>&1
    check '! grep -q "kernel_fnv1a" "$T/cmp2.out"' "compare of one kernel says nothing of it"
fi
# the CPU path records the compiled-in kernel's hash too
$OB run --backend cpu --methods cobb --tols 1e-1 --out "$T/cpu" >/dev/null 2>&1
kp=$(metakey "$T/cpu" kernel_fnv1a); dh=$(metakey "$T/cpu" data_hash)
check '[ -n "$kp" ] && [ -n "$dh" ]' "the CPU run's meta.json has kernel_fnv1a '$kp' and data_hash '$dh'"
# a datasets/ in the working directory is not picked up either
cp -r "$ROOT/datasets" "$T/wd/datasets"
sed -i 's/^  point  0.3      -2.5$/  point  0.3      -2.4/' "$T/wd/datasets/published.curves"
(cd "$T/wd" && unset OFFBENCH_DATA && $OB list curves >"$T/wd.lc" 2>&1)
check 'grep -q "^# curves from embedded" "$T/wd.lc"' "./datasets is not picked up: $(head -n 1 "$T/wd.lc")"
# merge: shards computed on different curve content are refused
cp "$ROOT/datasets/published.curves" "$T/c.curves"
M="run --backend cpu --methods cobb --tols 1e-1 --curves $T/c.curves"
$OB $M --shard 0/2 --out "$T/s1" >/dev/null 2>&1
sed -i 's/^  point  0.3      -2.5$/  point  0.3      -2.4/' "$T/c.curves"
check '! cmp -s "$T/c.curves" "$ROOT/datasets/published.curves"' "the test's curve file is modified"
$OB $M --shard 1/2 --out "$T/s2" >/dev/null 2>&1
check '[ "$(metakey "$T/s1" data_hash)" != "$(metakey "$T/s2" data_hash)" ]' "the shards' data_hash differ"
$OB merge "$T/s1" "$T/s2" --out "$T/m" >/dev/null 2>"$T/m.err"
check '[ $? -eq 2 ] && grep -q "data_hash" "$T/m.err"' "merge of shards on other curve content exits 2 naming data_hash: $(cat "$T/m.err")"
# the same content merges
$OB $M --shard 0/2 --out "$T/s1b" >/dev/null 2>&1
$OB merge "$T/s1b" "$T/s2" --out "$T/mb" >/dev/null 2>"$T/mb.err"
check '[ $? -eq 0 ]' "merge of shards on one curve content runs: $(cat "$T/mb.err")"
e2e_done
