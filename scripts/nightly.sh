#!/bin/sh
# nightly.sh - the nightly regression run: build, run the nightly
# configuration, compare it with the committed baseline (results/baseline/),
# write a markdown report, and exit with compare's status:
#   0 no regression, 1 regression, 2 error, 3 not comparable.
#
# The nightly configuration (two runs, both every method and the tolerances
# 1e-1 ... 1e-5, hausdorff metric, mid split):
#   published  the curves under datasets/ (the papers' examples and the
#              reference shapes), --reps 5: quality and speed (5 timed runs
#              after a warm-up feed compare's rank test; a method is slower
#              when its total time is >10 % up and significant, p < 0.05)
#   random     --random $NIGHTLY_RANDOM (default 250:2026), one run: quality
#              only (compare --no-timing): one run per row cannot tell a
#              speed change from noise, the published run's repetitions can
#
# History: every run, failed or not, is then copied into a store that the
# next night does not overwrite (scripts/nightly_history.sh), one directory
# per run, DIR/STAMP_COMMIT_HOST/ (published/ and random/ with results.csv,
# samples.csv and meta.json; report.md, compare-*.err, logs, run.json with
# the exit status), old runs are pruned (never the newest), and when python3
# is there scripts/report.py rebuilds the HTML report of the store in
# SITE/index.html (a failed report is said on stderr and leaves the exit
# status alone).
#
# Usage:
#   scripts/nightly.sh [--out DIR]      run and compare (default out/nightly)
#   scripts/nightly.sh --accept [--out DIR]
#                                       run, then make this run the baseline
#                                       (copies it into results/baseline/;
#                                       review `git diff --stat` and commit)
# History options (each also an environment variable):
#   --history DIR   NIGHTLY_HISTORY    the store (default out/history;
#                                      'none': no store, no report)
#   --keep N        NIGHTLY_KEEP       keep the N newest runs (default 0: all)
#   --keep-days D   NIGHTLY_KEEP_DAYS  drop runs older than D days (0: never)
#   --site DIR      NIGHTLY_SITE       the report (default HISTORY/site)
# Environment: NIGHTLY_RANDOM=N:SEED overrides the random set (a baseline
# made with another set is not comparable: compare exits 3), OFFBENCH_THREADS
# the thread count (default: OpenMP's), NIGHTLY_BACKEND the backend (default
# opencl: the kernel through PoCL on a machine without a GPU).
set -u
cd "$(dirname "$0")/.."
out=out/nightly
accept=0
history=${NIGHTLY_HISTORY:-out/history}
keep=${NIGHTLY_KEEP:-0}
keep_days=${NIGHTLY_KEEP_DAYS:-0}
site=${NIGHTLY_SITE:-}
while [ $# -gt 0 ]; do
    case "$1" in
        --out|--history|--keep|--keep-days|--site)
            [ $# -ge 2 ] || { echo "nightly: $1 needs a value" >&2; exit 2; }
            case "$1" in
                --out) out=$2 ;; --history) history=$2 ;; --keep) keep=$2 ;;
                --keep-days) keep_days=$2 ;; --site) site=$2 ;;
            esac
            shift 2 ;;
        --accept) accept=1; shift ;;
        -h|--help) sed -n '2,40p' "$0"; exit 0 ;;
        *) echo "nightly: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
for v in "$keep" "$keep_days"; do
    case "$v" in ''|*[!0-9]*) echo "nightly: --keep and --keep-days need a whole number, not '$v'" >&2; exit 2 ;; esac
done
# the store must outlive the next night's rm -rf of the output directory
case "${history%/}/" in "${out%/}/"*)
    echo "nightly: the history store $history lies inside the output directory $out, which each run removes" >&2; exit 2 ;;
esac
random=${NIGHTLY_RANDOM:-250:2026}
threads=${OFFBENCH_THREADS:+--threads $OFFBENCH_THREADS}
# The nightly measures through OpenCL on the machine's CPU (PoCL) by name:
# --backend auto now takes the CPU backend where there is no GPU, and the
# kernel path is what the nightly guards (NIGHTLY_BACKEND=cpu to skip it).
backend=${NIGHTLY_BACKEND:-opencl}
base=results/baseline
start=$(date +%s)
# the commit the run is built from, kept for the history (HEAD may move
# while the run goes on)
commit=$(git rev-parse HEAD 2>/dev/null || echo unknown)
dirty=false
[ "$commit" != unknown ] && ! git diff --quiet HEAD -- 2>/dev/null && dirty=true

# finish STATUS STAGE: records the run in the history store, prunes it,
# rebuilds the report, and exits with STATUS (the store and the report
# never change it: their failures are said on stderr)
finish() {
    if [ "$history" != none ]; then
        run_dir=$(sh scripts/nightly_history.sh record --out "$out" --history "$history" --status "$1" \
                  --stage "$2" --started "$start" --random "$random" --commit "$commit" --dirty $dirty) \
            && echo "nightly: recorded in $run_dir" >&2 \
            || echo "nightly: could not record this run in $history (see above)" >&2
        sh scripts/nightly_history.sh prune --history "$history" --keep "$keep" --keep-days "$keep_days" \
            || echo "nightly: pruning $history failed (see above)" >&2
        if [ -x /usr/bin/python3 ]; then
            /usr/bin/python3 scripts/report.py "$history" --out "${site:-$history/site}" \
                && echo "nightly: report in ${site:-$history/site}/index.html" >&2 \
                || echo "nightly: scripts/report.py failed (see above); the exit status is the run's" >&2
        else
            echo "nightly: no /usr/bin/python3: no HTML report" >&2
        fi
    fi
    exit "$1"
}

mkdir -p "$(dirname "$out")" || exit 2
make >"$out.build.log" 2>&1 || { mkdir -p "$out"; mv "$out.build.log" "$out/build.log" 2>/dev/null;
    echo "nightly: the build failed (see $out/build.log)" >&2; finish 2 build; }
rm -rf "$out"
mkdir -p "$out"
mv "$out.build.log" "$out/build.log"

run() {  # name, then run options
    name=$1; shift
    t0=$(date +%s)
    # shellcheck disable=SC2086
    ./offbench run --methods all --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --metric hausdorff --split mid \
        $threads --backend "$backend" "$@" --out "$out/$name" 2>"$out/$name.log"
    rc=$?
    echo "nightly: $name: exit $rc in $(($(date +%s) - t0)) s ($(tail -n 1 "$out/$name.log"))" >&2
    [ $rc -eq 0 ] || { echo "nightly: the $name run failed (see $out/$name.log)" >&2; finish 2 "run $name"; }
}
run published --reps 5
run random --random "$random"

# Per-machine baselines (README "Nightly"): timings are judged only against
# a baseline recorded on this CPU model (meta.json's cpu_model).  The
# default baseline, results/baseline/{published,random}, is the one of the
# CPU in its meta.json; another CPU's is results/baseline/cpu/KEY/ (KEY: the
# model, each character outside [A-Za-z0-9._-] as '_').  Without either,
# quality is compared with the default and the report says why timings were
# not judged.  --accept writes the default when it is this CPU's (or there
# is none), else this CPU's directory.
cpu_of() { sed -n 's/^  "cpu_model": "\(.*\)",$/\1/p' "$1" 2>/dev/null | head -n 1; }
cpu=$(cpu_of "$out/published/meta.json")
base_cpu=$(cpu_of "$base/published/meta.json")
cpu_dir=$base/cpu/$(printf '%s' "${cpu:-unknown}" | tr -c 'A-Za-z0-9._-' '_')
timing_note=
if [ -f "$base/published/results.csv" ] && [ "$base_cpu" != "$cpu" ]; then
    if [ -f "$cpu_dir/published/results.csv" ] || [ $accept -eq 1 ]; then
        base=$cpu_dir
    else
        timing_note="timings not judged: baseline recorded on CPU '${base_cpu:-unknown}', this machine is '${cpu:-unknown}' (no $cpu_dir/: scripts/nightly.sh --accept on this machine records one)"
    fi
fi
if [ $accept -eq 1 ]; then
    for name in published random; do
        rm -rf "$base/$name"
        mkdir -p "$base/$name"
        cp "$out/$name/results.csv" "$out/$name/meta.json" "$base/$name/"
        [ -f "$out/$name/samples.csv" ] && cp "$out/$name/samples.csv" "$base/$name/"
    done
    echo "nightly: accepted this run as the baseline in $base/ (review and commit it)" >&2
fi

status=0
worst() {  # keeps the most severe compare status: 2 > 3 > 1 > 0
    case "$1:$status" in
        2:*|*:2) status=2 ;;
        3:*|*:3) status=3 ;;
        1:*|*:1) status=1 ;;
    esac
}
report="$out/report.md"
{
    echo "# offbench nightly, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo
    echo "Commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD -- 2>/dev/null || echo ' (dirty)'); random set $random; baseline $base/ (CPU '${cpu:-unknown}')."
    echo
    [ -z "$timing_note" ] || { echo "**$timing_note**"; echo; }
} >"$report"
[ -z "$timing_note" ] || echo "nightly: $timing_note" >&2
for name in published random; do
    # speed: per-method verdicts only (a few of hundreds of rows pass a rank
    # test by chance; the per-method totals do not have that multiplicity)
    opts="--method-timing-only"
    [ "$name" = random ] || [ -n "$timing_note" ] && opts="--no-timing"
    {
        echo "## $name"
        echo
    } >>"$report"
    # shellcheck disable=SC2086
    ./offbench compare "$base/$name" "$out/$name" $opts --format md >>"$report" 2>"$out/compare-$name.err"
    rc=$?
    cat "$out/compare-$name.err" >>"$report"
    echo >>"$report"
    echo "nightly: compare $name: exit $rc" >&2
    worst $rc
done
echo "Exit status $status (0 no regression, 1 regression, 2 error, 3 not comparable); $(($(date +%s) - start)) s in all." >>"$report"
echo "nightly: report in $report; exit $status" >&2
finish $status compare
