#!/bin/sh
# e2e_cl_build.sh - the OpenCL programs (issue 40): one per metric and
# layout, built when first used, each in the binary cache under its own
# key.  A run builds only its metric's program in its layout, and meta.json's
# opencl.programs says which, in how long and what the cache did (a miss
# the first time, a hit after); `bench --quick --kernels` gives a cl_build
# row per program, the device's fp64 peak (cl_fma_peak, by device name),
# each metric's fraction of it, and the work counts (samples per record,
# operations per sample, bytes per record to and from the device);
# bench --device naming no device is an error, as run's is.
# No timed assertion: only that the figures are there and are numbers.
# Skipped without an OpenCL device.
. "$(dirname "$0")/lib_e2e.sh"
C="--curve liu2002_ex1 --methods tiller --tols 1e-2 --backend opencl"
export OFFBENCH_CL_CACHE="$T/cache"
unset OFFBENCH_CL_LAYOUT
# the programs of a run's meta.json: "metric layout cache-word" per line
progs() {
    python3 -c 'import json,sys
m = json.load(open(sys.argv[1]))
for p in m["opencl"]["programs"]:
    assert p["build_seconds"] >= 0
    print(p["metric"], p["layout"], p["binary_cache"].split(":")[0].split(" ")[0])' "$1" 2>&1
}
nbin() { ls "$T/cache"/*.bin 2>/dev/null | wc -l | tr -d ' '; }

if ! $OB run $C --metric radial --out "$T/r1" >/dev/null 2>"$T/r1.err"; then
    echo "no OpenCL device: $(tail -n 1 "$T/r1.err")"
    skipped=$((skipped + 27))
    e2e_done
    exit $?
fi
lay=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["opencl"]["layout"])' "$T/r1/meta.json")
check '[ "$(progs "$T/r1/meta.json")" = "radial $lay miss" ] && [ "$(nbin)" = 1 ]' \
    "a radial run builds the radial program alone: $(progs "$T/r1/meta.json"); $(nbin) cache files"
check 'grep -q "\"binary_cache\": \"miss: [^\"]*built and stored" "$T/r1/meta.json"' \
    "meta.json's binary_cache as before for one program: $(grep -o '"binary_cache": "[^"]*' "$T/r1/meta.json" | head -n 1)"
$OB run $C --metric radial --out "$T/r2" >/dev/null 2>&1
check '[ "$(progs "$T/r2/meta.json")" = "radial $lay hit" ] && [ "$(nbin)" = 1 ]' \
    "again: from the cache: $(progs "$T/r2/meta.json")"
$OB run $C --metric hausdorff --out "$T/h1" >/dev/null 2>&1
check '[ "$(progs "$T/h1/meta.json")" = "hausdorff $lay miss" ] && [ "$(nbin)" = 2 ]' \
    "a hausdorff run: its own program and cache file: $(progs "$T/h1/meta.json"); $(nbin) files"
other=groups; [ "$lay" = groups ] && other=items
OFFBENCH_CL_LAYOUT=$other $OB run $C --metric hausdorff --out "$T/h2" >/dev/null 2>&1
check '[ "$(progs "$T/h2/meta.json")" = "hausdorff $other miss" ] && [ "$(nbin)" = 3 ]' \
    "the other layout: another program: $(progs "$T/h2/meta.json"); $(nbin) files"
body "$T/h1/results.csv" > "$T/h1.txt"
check 'body "$T/h2/results.csv" | cmp -s - "$T/h1.txt"' "both layouts' programs give the same rows"

# bench: the kernel figures alone
$OB bench --quick --kernels --out "$T/b" >"$T/b.out" 2>"$T/b.err"
check '[ $? -eq 0 ] && [ -s "$T/b/bench.csv" ]' "bench --quick --kernels: $(tail -n 3 "$T/b.err")"
B="$T/b/bench.csv"
# rows WHAT: present, 7 fields, a number in seconds and rate
rowok() { awk -F, -v w="$1" '$1 == w && NF == 7 && $5 + 0 == $5 && $6 + 0 == $6 {n++} END {exit !(n >= 1)}' "$B"; }
for m in radial normal hausdorff param; do
    for l in groups items; do
        check 'rowok "cl_build/$m/$l" && grep -q "^cl_build/$m/$l,cache-\(hit\|miss\|off\)," "$B"' \
            "bench: a cl_build row for $m/$l with its cache outcome: $(grep "^cl_build/$m/$l," "$B")"
    done
done
check 'awk -F, "\$1 == \"cl_fma_peak\" && \$2 != \"\" && \$2 != \"opencl\" && \$6 > 0 && \$7 == \"flop/s\"" "$B" | grep -q .' \
    "bench: cl_fma_peak, the device by name, flop/s: $(grep '^cl_fma_peak' "$B")"
for m in radial normal hausdorff param; do
    check 'rowok "samples/$m" && rowok "gflops/$m" && awk -F, "\$1 == \"cl_peak_fraction/$m\" && \$6 > 0 && \$6 < 1 && \$7 == \"of_peak\"" "$B" | grep -q .' \
        "bench: $m: samples/s, flop/s and the fraction of the device's peak: $(grep "^cl_peak_fraction/$m," "$B" | head -n 1)"
    check 'awk -F, "\$1 == \"samples_per_record/$m\" && \$6 == 256" "$B" | grep -q . && awk -F, "\$1 == \"ops_per_sample/$m\" && \$6 > 1" "$B" | grep -q . && awk -F, "\$1 == \"bytes_per_record/$m\" && \$6 > 100" "$B" | grep -q . && awk -F, "\$1 == \"bytes_back_per_record/$m\" && \$6 == 24" "$B" | grep -q .' \
        "bench: $m: the work counts: $(grep "_per_\(record\|sample\)/$m," "$B" | tr '\n' ' ')"
done
check '! grep -q "^\(run\|random_run\|engines\)" "$B"' "bench --kernels: no whole runs"
$OB bench --quick --kernels --device no-such-device --out "$T/bx" >/dev/null 2>"$T/bx.err"
check '[ $? -eq 2 ] && grep -q "bench --device no-such-device" "$T/bx.err" && [ ! -e "$T/bx/bench.csv" ]' \
    "bench --device naming no device: exit 2, nothing written: $(cat "$T/bx.err")"
check 'grep -q "fp64 peak" "$T/b.out" && grep -q "of the device.s fp64 peak" "$T/b.out"' \
    "bench prints the device's peak and each metric's share of it: $(grep -i peak "$T/b.out" | head -n 3)"

e2e_done
