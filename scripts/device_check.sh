#!/bin/sh
# device_check.sh - every figure of the execution engine on this machine, in
# one call (issue 35; docs/performance.md "Engines"), in at most about five minutes:
#   1. the machine: cores, memory, CPU model, OpenCL devices, GPUs
#   2. the CPU backend at 1, 2, 4, ... all threads, level and group engines:
#      wall, speed-up over 1 thread, efficiency (meta.json's engine block:
#      fit and measure thread time / (threads x wall)); every run's rows
#      checked against the first's (timings aside)
#   3. each OpenCL device: the first build (an empty binary cache) and the
#      cached one, then the same jobs on all threads through each engine and
#      both kernel layouts, wall against the CPU backend's, records per
#      launch, and a row-by-row agreement check
# Prints a summary table at the end; exits 1 when any rows differ.
#
# Usage: scripts/device_check.sh [--quick]
# Environment:
#   OB                  the program (default ./offbench); a bundle made by
#                       scripts/device_bundle.sh DIR runs as OB=DIR/offbench
#   DEVICE_CHECK_RANDOM the jobs' curves, N:SEED (default 200:7; --quick 20:3)
#   DEVICE_CHECK_TOLS   tolerances (default 1e-1,1e-2,1e-3,1e-4,1e-5)
#   DEVICE_CHECK_OUT    where the runs go (default a temporary directory,
#                       removed at the end)
# On a machine with NVIDIA's OpenCL driver under /usr/local/nvidia/lib64 and
# no ICD file for it, one is written into the output directory and
# OCL_ICD_VENDORS points at it.
set -u
cd "$(dirname "$0")/.."
OB=${OB:-./offbench}
quick=0
[ "${1:-}" = "--quick" ] && quick=1
if [ $quick -eq 1 ]; then rnd=${DEVICE_CHECK_RANDOM:-20:3}; else rnd=${DEVICE_CHECK_RANDOM:-200:7}; fi
tols=${DEVICE_CHECK_TOLS:-1e-1,1e-2,1e-3,1e-4,1e-5}
out=${DEVICE_CHECK_OUT:-$(mktemp -d)}
[ -n "${DEVICE_CHECK_OUT:-}" ] || trap 'rm -rf "$out"' EXIT
mkdir -p "$out" || exit 2
[ -x "$OB" ] || { echo "device_check: no program at $OB (make, or OB=...)" >&2; exit 2; }
py=$(command -v python3 || true)
nv=/usr/local/nvidia/lib64
if [ -z "${OCL_ICD_VENDORS:-}" ] && [ -e "$nv/libnvidia-opencl.so.1" ] && [ ! -e /etc/OpenCL/vendors/nvidia.icd ]; then
    mkdir -p "$out/icd" && echo "$nv/libnvidia-opencl.so.1" > "$out/icd/nvidia.icd"
    export OCL_ICD_VENDORS="$out/icd"
fi
export OFFBENCH_CL_CACHE="$out/clcache"
J="--random $rnd --methods all --tols $tols --metric hausdorff --split mid"

echo "== device_check: $(date -u +%Y-%m-%dT%H:%M:%SZ), $($OB --version 2>/dev/null | head -n 1)"
echo "== 1. the machine"
ncpu=$(nproc 2>/dev/null || getconf _NPROCESSORS_ONLN)
echo "cores (online): $ncpu"
grep -m 1 "model name" /proc/cpuinfo 2>/dev/null | sed 's/^/cpu: /'
grep MemTotal /proc/meminfo 2>/dev/null | sed 's/^/memory: /'
command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null | sed 's/^/gpu: /'
$OB list devices 2>&1 | sed 's/^/  /'
echo "jobs: $J"

# field NAME of meta.json's engine block, or of the top level
meta() { sed -n "s/.*\"$2\": \([^,}]*\).*/\1/p" "$1" | head -n 1 | tr -d '"'; }
same() {  # reference, candidate: "identical" or "N rows differ"
    if [ -n "$py" ]; then
        r=$("$py" scripts/same_rows.py "$1" "$2" 2>&1 | head -n 1)
        case "$r" in *" 0 differ") echo identical ;; *) echo "$r"; bad=1 ;; esac
    else
        echo "(no python3: not checked)"
    fi
}
bad=0
summary="$out/summary.txt"
: > "$summary"
row() { printf '%-34s %9s %8s %9s %10s  %s\n' "$@" | tee -a "$summary"; }

echo "== 2. the CPU backend, 1 .. $ncpu threads"
row "run" "wall s" "speedup" "effic." "rec/launch" "rows vs level@1"
t=1
ref=
base_wall=
while :; do
    for e in level group; do
        d="$out/cpu_${e}_$t"
        $OB run $J --backend cpu --engine $e --threads $t --out "$d" >/dev/null 2>"$d.err" || { echo "run failed: $(tail -n 2 "$d.err")"; bad=1; continue; }
        w=$(meta "$d/meta.json" wall_seconds)
        eff=$(meta "$d/meta.json" efficiency)
        if [ -z "$ref" ]; then ref="$d/results.csv"; base_wall=$w; agree="(reference)"; else agree=$(same "$ref" "$d/results.csv"); fi
        row "cpu $e $t threads" "$w" "$(awk -v a="$base_wall" -v b="$w" 'BEGIN{printf "x%.2f", a/b}')" "$eff" "-" "$agree"
    done
    [ $t -ge "$ncpu" ] && break
    t=$((t * 2)); [ $t -gt "$ncpu" ] && t=$ncpu
done
cpu_all_wall=$(meta "$out/cpu_group_$ncpu/meta.json" wall_seconds)

echo "== 3. OpenCL devices"
$OB list devices 2>/dev/null | awk 'NR > 1 && $0 !~ /^#/ && /yes/' > "$out/devices.txt"
if [ ! -s "$out/devices.txt" ]; then
    echo "no OpenCL device with fp64"
else
    # each device by its name (the columns before the type)
    awk '{n=""; for (i=1;i<=NF;i++){ if ($i=="cpu"||$i=="gpu"||$i=="accelerator"||$i=="other") break; n=n (n?" ":"") $i}; print n}' "$out/devices.txt" |
    while read -r dev; do
        tag=$(printf '%s' "$dev" | tr -c 'A-Za-z0-9' '_' | cut -c1-24)
        for pass in first cached; do
            d="$out/build_${tag}_$pass"
            $OB run --curve liu2002_ex1 --methods tiller --tols 1e-2 --backend opencl --device "$dev" --out "$d" >/dev/null 2>"$d.err"
            echo "build ($pass) on $dev: $(meta "$d/meta.json" build_seconds) s; cache: $(meta "$d/meta.json" binary_cache)"
        done
        for lay in groups items; do
            for e in level group; do
                d="$out/cl_${tag}_${lay}_$e"
                OFFBENCH_CL_LAYOUT=$lay $OB run $J --backend opencl --device "$dev" --engine $e --out "$d" >/dev/null 2>"$d.err" ||
                    { echo "run failed: $(tail -n 2 "$d.err")"; continue; }
                w=$(meta "$d/meta.json" wall_seconds)
                l=$(meta "$d/meta.json" backend_launches)
                r=$(meta "$d/meta.json" backend_records)
                row "$(printf '%.14s' "$dev") $lay $e" "$w" "$(awk -v a="$cpu_all_wall" -v b="$w" 'BEGIN{printf "x%.2f", a/b}')" \
                    "-" "$(awk -v l="$l" -v r="$r" 'BEGIN{printf "%.0f", (l > 0 ? r / l : 0)}')" "$(same "$ref" "$d/results.csv")"
            done
        done
    done
fi
echo "== summary (speed-up: CPU rows against 1 thread of the level engine, OpenCL rows against the"
echo "   group engine on all $ncpu threads of the CPU backend, ${cpu_all_wall:-?} s)"
cat "$summary"
if grep -q "differ" "$summary" && ! grep -q " 0 differ" "$summary"; then bad=1; fi
[ $bad -eq 0 ] && echo "device_check: every run's rows agree" || echo "device_check: SOME ROWS DIFFER (see above)"
[ $bad -eq 0 ]
