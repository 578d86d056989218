#!/bin/sh
# device_check.sh - every figure of the execution engine on this machine, in
# one call (issue 35; docs/performance.md "Engines"), in at most about five minutes:
#   1. the machine: cores, memory, CPU model, OpenCL devices, GPUs
#   2. the CPU backend at 1, 2, 4, ... all threads, level and group engines:
#      wall, speed-up over 1 thread, efficiency (meta.json's engine block:
#      fit and measure thread time / (threads x wall)); every run's rows
#      checked against the first's (timings aside)
#   3. each OpenCL device: the first build (an empty binary cache) and the
#      cached one of each metric's program in each layout, the device's fp64
#      peak, each metric's samples/s, GFLOP/s and fraction of that peak in
#      both layouts (batches of at least 1e7 samples on a GPU), and the
#      work counts (samples per record, operations per sample, bytes per
#      record to and from the device) -- all from `bench --kernels` (issue
#      40); then the same jobs on all threads through each engine and
#      both kernel layouts, wall against the CPU backend's, records per
#      launch, and a row-by-row agreement check
# Prints a summary table at the end; exits 1 when any rows differ.
# Without a GPU (PoCL only) every step runs on the devices there are.
#
# Usage: scripts/device_check.sh [--quick]
# Environment:
#   OB                  the program (default ./offbench); a bundle made by
#                       scripts/device_bundle.sh DIR runs as OB=DIR/offbench
#   DEVICE_CHECK_RANDOM the jobs' curves, N:SEED (default 200:7; --quick 20:3)
#   DEVICE_CHECK_TOLS   tolerances (default 1e-1,1e-2,1e-3,1e-4,1e-5)
#   DEVICE_CHECK_OUT    where the runs go (default a temporary directory,
#                       removed at the end)
#   DEVICE_CHECK_INLINE 1: also the first build of hausdorff's program with
#                       every call inlined (-D OBC_INLINE_ALL, the kernels
#                       as they were built before issue 40 but for one
#                       metric and layout): what the out-of-line calls save;
#                       minutes on NVIDIA's compiler, so off by default
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
ksummary="$out/kernels.txt"
: > "$summary"
: > "$ksummary"
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
        # a run builds only its metric's program in its layout: the first
        # build (an empty cache, and the drivers' own caches off: PoCL's and
        # NVIDIA's JIT cache) and the cached one (from the binary cache; the
        # drivers' caches were not filled, so what a driver still compiles
        # from the cached binary at its first launch is in it)
        for pass in first cached; do
            d="$out/build_${tag}_$pass"
            cold=; [ $pass = first ] && cold="env POCL_KERNEL_CACHE=0 CUDA_CACHE_DISABLE=1"
            $cold $OB run --curve liu2002_ex1 --methods tiller --tols 1e-2 --backend opencl --device "$dev" --out "$d" >/dev/null 2>"$d.err"
            echo "run's build ($pass) on $dev: $(meta "$d/meta.json" build_seconds) s; cache: $(meta "$d/meta.json" binary_cache)" |
                tee -a "$ksummary"
        done
        # every program (the first pass from an empty cache), the peak, the
        # metrics against it and the work counts
        bq=; [ $quick -eq 1 ] && bq=--quick
        for pass in first cached; do
            d="$out/bench_${tag}_$pass"
            cold=; [ $pass = first ] && { rm -rf "$OFFBENCH_CL_CACHE"; cold="env POCL_KERNEL_CACHE=0 CUDA_CACHE_DISABLE=1"; }
            if ! $cold $OB bench --kernels $bq --device "$dev" --out "$d" > "$d.out" 2>"$d.err"; then
                echo "bench --kernels failed on $dev: $(tail -n 2 "$d.err")" | tee -a "$ksummary"
                continue
            fi
            echo "programs built by bench --kernels on $dev ($pass: $( [ $pass = first ] && echo "an empty cache" || echo "from the binary cache"))" |
                tee -a "$ksummary"
            awk -F, '$1 ~ /^cl_build\// {printf "   %-28s %8.2f s  %s\n", $1, $5, $2; n++; s += $5}
                END {printf "   %d programs, %.2f s in all\n", n, s}' "$d/bench.csv" | tee -a "$ksummary"
        done
        d="$out/bench_${tag}_cached"
        if [ -s "$d/bench.csv" ]; then
            { echo "the fp64 peak, the metrics against it, the work counts on $dev:"
              grep -E "^(OpenCL fp64 peak|OpenCL batches)" "$d.out" | sed 's/^/   /'
              awk -F, '
                $1 ~ /^samples\// && $2 ~ /^opencl-/ {split($1, a, "/"); sps[a[2] " " substr($2, 8)] = $6}
                $1 ~ /^gflops\// && $2 ~ /^opencl-/ {split($1, a, "/"); gf[a[2] " " substr($2, 8)] = $6}
                $1 ~ /^cl_peak_fraction\// && $2 ~ /^opencl-/ {split($1, a, "/"); fr[a[2] " " substr($2, 8)] = $6}
                $1 ~ /^samples_per_record\// {split($1, a, "/"); spr[a[2]] = $6}
                $1 ~ /^ops_per_sample\// && $2 == "any" {split($1, a, "/"); ops[a[2]] = $6}
                $1 ~ /^ops_per_sample\// && $2 ~ /^opencl-/ {split($1, a, "/"); own[a[2] " " substr($2, 8)] = $6}
                $1 ~ /^bytes_per_record\// {split($1, a, "/"); by[a[2]] = $6}
                $1 ~ /^bytes_back_per_record\// {split($1, a, "/"); bb[a[2]] = $6}
                END {
                    printf "   %-10s %-7s %12s %9s %9s   %s\n", "metric", "layout", "samples/s", "GFLOP/s", "of peak",
                           "samples/record, flop/sample, bytes/record to/from the device"
                    n = split("radial normal hausdorff param", ms, " ")
                    for (i = 1; i <= n; i++)
                        for (l = 1; l <= 2; l++) {
                            lay = l == 1 ? "groups" : "items"
                            k = ms[i] " " lay
                            if (!(k in sps)) continue
                            w = l == 1 ? sprintf("%d, %.0f, %.0f/%.0f", spr[ms[i]], ops[ms[i]], by[ms[i]], bb[ms[i]]) : ""
                            if (k in own) w = w sprintf("%s(this layout does %.0f flop/sample)", w == "" ? "" : " ", own[k])
                            printf "   %-10s %-7s %12.4g %9.3g %8.2f%%   %s\n", ms[i], lay, sps[k], gf[k] / 1e9, 100 * fr[k], w
                        }
                }' "$d/bench.csv"; } | tee -a "$ksummary"
        fi
        if [ "${DEVICE_CHECK_INLINE:-0}" = 1 ] && [ -f kernels/metric_core.h ]; then
            k="$out/kernels_inline_all"
            mkdir -p "$k" && { echo "#define OBC_INLINE_ALL"; cat kernels/metric_core.h; } > "$k/metric_core.h" && cp kernels/measure.cl "$k/"
            d="$out/build_${tag}_inline_all"
            OFFBENCH_KERNELS="$k" POCL_KERNEL_CACHE=0 CUDA_CACHE_DISABLE=1 $OB run --curve liu2002_ex1 --methods tiller --tols 1e-2 --backend opencl --device "$dev" --out "$d" >/dev/null 2>"$d.err"
            echo "hausdorff's program with every call inlined (-D OBC_INLINE_ALL), first build on $dev: $(meta "$d/meta.json" build_seconds) s" |
                tee -a "$ksummary"
        fi
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
if [ -s "$ksummary" ]; then
    echo "== summary of the OpenCL programs and kernels"
    cat "$ksummary"
fi
echo "== summary (speed-up: CPU rows against 1 thread of the level engine, OpenCL rows against the"
echo "   group engine on all $ncpu threads of the CPU backend, ${cpu_all_wall:-?} s)"
cat "$summary"
if grep -q "differ" "$summary" && ! grep -q " 0 differ" "$summary"; then bad=1; fi
[ $bad -eq 0 ] && echo "device_check: every run's rows agree" || echo "device_check: SOME ROWS DIFFER (see above)"
[ $bad -eq 0 ]
