#!/bin/sh
# e2e_engines.sh - how the work is scheduled never changes a row (docs/performance.md
# "Engines"): the same run through the level and group engines, at 1, 2 and
# 7 threads, at small and default chunk sizes, on the CPU and through
# OpenCL (PoCL) in both kernel layouts with the level, group and device
# engines, gives the same results.csv, timing
# columns aside; meta.json names the engine that ran and what it did;
# --backend auto takes the CPU backend where there is no GPU (PoCL only
# when asked for); a bad --engine or --chunk is an error.
. "$(dirname "$0")/lib_e2e.sh"
R="--random 6:5 --methods all --tols 1e-2,1e-3"

$OB run $R --backend cpu --engine level --threads 1 --out "$T/ref" >/dev/null 2>&1
check '[ $? -eq 0 ]' "the reference run (level engine, 1 thread)"
body "$T/ref/results.csv" > "$T/ref.txt"
same() {  # name, then run options: the rows equal the reference's
    name=$1; shift
    $OB run $R "$@" --out "$T/$name" >/dev/null 2>"$T/$name.err"
    check '[ $? -eq 0 ] && body "$T/$name/results.csv" | cmp -s - "$T/ref.txt"' \
        "$*: the reference's rows: $(python3 scripts/same_rows.py "$T/ref/results.csv" "$T/$name/results.csv" 2>&1 | head -n 4 | tr '\n' ' ') $(cat "$T/$name.err")"
}
same g1 --backend cpu --engine group --threads 1
same g2 --backend cpu --engine group --threads 2
same g7 --backend cpu --engine group --threads 7 --chunk 3
same l2 --backend cpu --engine level --threads 2 --chunk 7
same a2 --backend cpu --threads 2
same d2 --backend cpu --engine device --threads 2
check 'grep -q "\"engine\": {\"name\": \"level\", \"asked\": \"device\"" "$T/d2/meta.json"' \
    "--engine device without an OpenCL device runs the level engine, and says so"
check 'grep -q "\"engine\": {\"name\": \"group\", \"asked\": \"auto\", \"chunk\": 512, \"threads\": 2" "$T/a2/meta.json"' \
    "meta.json: auto ran the group engine on 2 threads: $(grep -o '"engine": {[^}]*' "$T/a2/meta.json" | cut -c1-160)"
check 'grep -q "\"engine\": {\"name\": \"group\", \"asked\": \"group\", \"chunk\": 3, \"threads\": 7" "$T/g7/meta.json"' \
    "meta.json: --engine group --chunk 3 --threads 7"
check 'grep -q "\"efficiency\": 0\.[0-9]" "$T/g2/meta.json" && grep -q "\"work_seconds\": [0-9]" "$T/g2/meta.json"' \
    "meta.json: the engine's work and efficiency"

if $OB run --curve liu2002_ex1 --methods tiller --tols 1e-2 --backend opencl --out "$T/probe" >/dev/null 2>&1; then
    for lay in groups items; do
        # the group engine with a batch backend too (never auto's choice:
        # 12 records a launch): it once differed in a row when a SISL
        # server forked from a worker thread deadlocked (methods/sisl.c)
        for e in level group device; do
            OFFBENCH_CL_LAYOUT=$lay same "cl$lay$e" --backend opencl --engine $e --threads 2
        done
    done
    check 'grep -q "\"name\": \"device\", \"asked\": \"device\"" "$T/clitemsdevice/meta.json" && grep -q "\"device_seconds\": [0-9.]*[1-9]" "$T/clitemsdevice/meta.json"' \
        "meta.json: the device engine ran, with the kernels' own time: $(grep -o '"engine": {[^}]*' "$T/clitemsdevice/meta.json" | cut -c1-400)"
    check 'grep -q "\"backend_launches\": [1-9]" "$T/clgroupslevel/meta.json"' "meta.json: the OpenCL launches are counted"
    # auto: a CPU OpenCL device is not taken (it is slower than the CPU backend)
    $OB run $R --threads 2 --out "$T/auto" >/dev/null 2>&1
    if $OB list devices 2>/dev/null | grep -qi "gpu\|accelerator"; then
        skipped=$((skipped + 1))
    else
        check 'grep -q "\"backend\": \"cpu\"" "$T/auto/meta.json" && grep -q "cpu_because\": \"--backend auto: no OpenCL GPU" "$T/auto/meta.json"' \
            "--backend auto on a machine without a GPU: the CPU backend, and why: $(grep -o '"cpu_because": "[^"]*' "$T/auto/meta.json")"
    fi
else
    skipped=$((skipped + 9))
fi

$OB run $R --engine fast --out "$T/bad" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "engine" "$T/e.txt" && [ ! -e "$T/bad" ]' "--engine fast: exit 2 naming the option: $(cat "$T/e.txt")"
$OB run $R --chunk 0 --out "$T/bad" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "chunk" "$T/e.txt" && [ ! -e "$T/bad" ]' "--chunk 0: exit 2 naming the option: $(cat "$T/e.txt")"

e2e_done
