#!/bin/sh
# e2e_cl_build.sh - the OpenCL programs (issue 40): one per metric and
# layout, built when first used, each in the binary cache under its own
# key.  A run builds only its metric's program in its layout, and meta.json's
# opencl.programs says which, in how long and what the cache did (a miss
# the first time, a hit after).
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
    skipped=$((skipped + 6))
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

e2e_done
