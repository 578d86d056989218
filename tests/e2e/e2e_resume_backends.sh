#!/bin/sh
# e2e_resume_backends.sh - meta.json "backends" lists every backend and
# device that computed rows of a run, in the order they first did, across
# --resume (issue 48, class 12): a run interrupted on one backend (the
# OFFBENCH_TEST_OOM_AFTER hook stops it after a set number of jobs: no
# timing) and resumed with another lists both; a resume that computes no
# row adds nothing; a fresh run in the same directory starts the list anew;
# an uninterrupted run (and one with --reps) lists its own backend alone;
# merged shards list every shard's.
# "backend" and "opencl" keep what they said: the last backend.
# The OpenCL cases are skipped without an OpenCL device.
. "$(dirname "$0")/lib_e2e.sh"
. "$(dirname "$0")/lib_cl.sh"
R="--random 12:5 --methods tiller,cobb,ahn,zhao,interp --threads 2"
export OFFBENCH_CL_CACHE="$T/cache"
# the backends of a meta.json, "backend:device" joined by spaces
bk() {
    python3 -c 'import json,sys
m = json.load(open(sys.argv[1]))
print(" ".join(b["backend"] + ":" + (b.get("device") or "") for b in m["backends"]))' "$1" 2>&1
}

$OB run $R --backend cpu --out "$T/p" >/dev/null 2>&1
check '[ "$(bk "$T/p/meta.json")" = "cpu:" ]' "an uninterrupted run: its backend alone: $(bk "$T/p/meta.json")"
$OB run $R --backend cpu --reps 1 --out "$T/reps" >/dev/null 2>&1
check '[ "$(bk "$T/reps/meta.json")" = "cpu:" ]' "a --reps run: its backend alone: $(bk "$T/reps/meta.json")"
body "$T/p/results.csv" > "$T/ref.txt"

# cpu, interrupted, then resumed on cpu: one entry; then a resume of the
# finished run on another backend computes no row: still one
OFFBENCH_TEST_OOM_AFTER=20 $OB run $R --backend cpu --out "$T/c" >/dev/null 2>&1
check '[ $? -eq 1 ] && [ -s "$T/c/results.journal.csv" ]' "the hook stops the run with rows journaled"
$OB run $R --backend cpu --resume "$T/c" >/dev/null 2>&1
check '[ "$(bk "$T/c/meta.json")" = "cpu:" ]' "cpu, resumed on cpu: one entry: $(bk "$T/c/meta.json")"

cl_device_or_skip 6
dev=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["opencl"]["device"])' "$T/cl_probe/meta.json")
$OB run $R --backend opencl --resume "$T/c" >/dev/null 2>&1
check '[ $? -eq 0 ] && [ "$(bk "$T/c/meta.json")" = "cpu:" ]' \
    "a resume that computes no row adds nothing: $(bk "$T/c/meta.json")"

# opencl, interrupted, resumed on cpu: both, in order; the rows as one run's
OFFBENCH_TEST_OOM_AFTER=20 $OB run $R --backend opencl --out "$T/o" >/dev/null 2>&1
check '[ $? -eq 1 ] && [ -s "$T/o/results.journal.csv" ]' "opencl stopped with rows journaled"
$OB run $R --backend cpu --resume "$T/o" >/dev/null 2>"$T/o.err"
check '[ $? -eq 0 ] && [ "$(bk "$T/o/meta.json")" = "opencl:$dev cpu:" ]' \
    "opencl then cpu: both listed: $(bk "$T/o/meta.json"); $(tail -n 1 "$T/o.err")"
check 'body "$T/o/results.csv" | cmp -s - "$T/ref.txt" && grep -q "\"backend\": \"cpu\"" "$T/o/meta.json"' \
    "the rows as an uninterrupted run's; \"backend\" the last, as before"
# a fresh run in the same directory starts anew
$OB run $R --backend opencl --force --out "$T/o" >/dev/null 2>&1
check '[ "$(bk "$T/o/meta.json")" = "opencl:$dev" ]' "a fresh run in the directory: its own alone: $(bk "$T/o/meta.json")"
# merged shards, one on each backend: the merged run lists both
$OB run $R --backend cpu --shard 0/2 --out "$T/s0" >/dev/null 2>&1
$OB run $R --backend opencl --shard 1/2 --out "$T/s1" >/dev/null 2>&1
$OB merge "$T/s0" "$T/s1" --out "$T/sm" >/dev/null 2>"$T/sm.err"
check '[ "$(bk "$T/sm/meta.json")" = "cpu: opencl:$dev" ]' \
    "merge of a cpu and an opencl shard: both: $(bk "$T/sm/meta.json"); $(tail -n 1 "$T/sm.err")"
e2e_done
