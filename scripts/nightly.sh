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
# Usage:
#   scripts/nightly.sh [--out DIR]      run and compare (default out/nightly)
#   scripts/nightly.sh --accept [--out DIR]
#                                       run, then make this run the baseline
#                                       (copies it into results/baseline/;
#                                       review `git diff --stat` and commit)
# Environment: NIGHTLY_RANDOM=N:SEED overrides the random set (a baseline
# made with another set is not comparable: compare exits 3), OFFBENCH_THREADS
# the thread count (default: OpenMP's).
set -u
cd "$(dirname "$0")/.."
out=out/nightly
accept=0
while [ $# -gt 0 ]; do
    case "$1" in
        --out) [ $# -ge 2 ] || { echo "nightly: --out needs a directory" >&2; exit 2; }; out=$2; shift 2 ;;
        --accept) accept=1; shift ;;
        -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
        *) echo "nightly: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
random=${NIGHTLY_RANDOM:-250:2026}
threads=${OFFBENCH_THREADS:+--threads $OFFBENCH_THREADS}
base=results/baseline
start=$(date +%s)

mkdir -p "$(dirname "$out")" || exit 2
make >"$out.build.log" 2>&1 || { mkdir -p "$out"; mv "$out.build.log" "$out/build.log" 2>/dev/null;
    echo "nightly: the build failed (see $out/build.log)" >&2; exit 2; }
rm -rf "$out"
mkdir -p "$out"
mv "$out.build.log" "$out/build.log"

run() {  # name, then run options
    name=$1; shift
    t0=$(date +%s)
    # shellcheck disable=SC2086
    ./offbench run --methods all --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --metric hausdorff --split mid \
        $threads "$@" --out "$out/$name" 2>"$out/$name.log"
    rc=$?
    echo "nightly: $name: exit $rc in $(($(date +%s) - t0)) s ($(tail -n 1 "$out/$name.log"))" >&2
    [ $rc -eq 0 ] || { echo "nightly: the $name run failed (see $out/$name.log)" >&2; exit 2; }
}
run published --reps 5
run random --random "$random"

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
    echo "Commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD -- 2>/dev/null || echo ' (dirty)'); random set $random."
    echo
} >"$report"
for name in published random; do
    # speed: per-method verdicts only (a few of hundreds of rows pass a rank
    # test by chance; the per-method totals do not have that multiplicity)
    opts="--method-timing-only"
    [ "$name" = random ] && opts="--no-timing"
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
exit $status
