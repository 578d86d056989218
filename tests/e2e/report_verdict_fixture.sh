#!/bin/sh
# report_verdict_fixture.sh OFFBENCH STORE SCRATCH STATUS [STAGE] [--json] -
# a first night's history store for tests/e2e/e2e_report.sh (not a test
# itself): one run, recorded through scripts/nightly_history.sh, whose
# nightly ended with exit STATUS at STAGE (default compare).  The run sets
# published (liu2002_ex1, tiller and cobb at 1e-2 and 1e-3) and random
# (--random 2:7 at 1e-2) are real runs of OFFBENCH, made once into
# SCRATCH/base and compared by OFFBENCH the way scripts/nightly.sh does
# (report.md: a section per set with compare's markdown report, its
# messages in compare-SET.err), with a new run edited so that compare itself
# gives STATUS:
#   0  the new run is the baseline's copy
#   1  published: cobb's first row +2 ctrl_points (a quality regression)
#   2  published: a results.csv with a broken header (compare: error)
#   3  random: another seed in meta.json (not comparable)
# The run is recorded with its baseline's path, SCRATCH/base, as nightly.sh
# records NIGHTLY_BASELINE.
# STAGE other than compare (build, "run random") records what nightly.sh
# would then have: build.log only (build), or the logs and the run sets
# without any compare output.  --json also writes compare-SET.json
# (compare --format json) beside report.md.
set -eu
OB=$1 H=$2 S=$3 ST=$4
STAGE=${5:-compare}
JSON=${6:-}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PY=/usr/bin/python3
B=$S/base
if [ ! -f "$B/random/results.csv" ]; then
    rm -rf "$B"
    mkdir -p "$B"
    "$OB" run --curve liu2002_ex1 --methods tiller,cobb --tols 1e-2,1e-3 --backend cpu \
        --out "$B/published" 2>"$B/published.log"
    "$OB" run --random 2:7 --methods tiller,cobb --tols 1e-2 --backend cpu --out "$B/random" 2>"$B/random.log"
fi
N=$S/night-$ST
rm -rf "$N"
mkdir -p "$N"
cp -R "$B/published" "$B/random" "$B/published.log" "$B/random.log" "$N/"
echo "make: nothing to do" > "$N/build.log"

case "$ST" in
    1)  "$PY" - "$N/published/results.csv" <<'EOF'
import csv, sys
path = sys.argv[1]
with open(path, newline="") as f:
    rows = list(csv.reader(f))
col = {n: i for i, n in enumerate(rows[0])}
for r in rows[1:]:
    if r[col["method"]] == "cobb":
        r[col["ctrl_points"]] = str(int(r[col["ctrl_points"]]) + 2)
        break
with open(path, "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows(rows)
EOF
        ;;
    2)  printf 'curve,d\n' > "$N/published/results.csv" ;;
    3)  sed 's/"seed": [^,]*,/"seed": 99,/' "$B/random/meta.json" > "$N/random/meta.json" ;;
esac

if [ "$STAGE" = compare ]; then
    worst=0
    {
        echo "# offbench nightly, 2026-11-18T11:06:40Z"
        echo
        echo "Commit 0123456; random set 2:7; baseline base/ (CPU 'test')."
        echo
    } > "$N/report.md"
    for s in published random; do
        printf '## %s\n\n' "$s" >> "$N/report.md"
        rc=0
        "$OB" compare "$B/$s" "$N/$s" --no-timing --format md >>"$N/report.md" 2>"$N/compare-$s.err" || rc=$?
        cat "$N/compare-$s.err" >> "$N/report.md"
        echo >> "$N/report.md"
        if [ "$JSON" = --json ]; then
            "$OB" compare "$B/$s" "$N/$s" --no-timing --format json --out "$N/compare-$s.json" 2>/dev/null || true
        fi
        case "$rc:$worst" in 2:*|*:2) worst=2 ;; 3:*|*:3) worst=3 ;; 1:*|*:1) worst=1 ;; esac
    done
    echo "Exit status $worst (0 no regression, 1 regression, 2 error, 3 not comparable)." >> "$N/report.md"
    [ "$worst" = "$ST" ] || { echo "report_verdict_fixture: compare gave $worst, not $ST" >&2; exit 1; }
fi
sh "$ROOT/scripts/nightly_history.sh" record --out "$N" --history "$H" --status "$ST" --stage "$STAGE" \
    --commit 0123456789abcdef0123456789abcdef01234567 --time 1795000000 --random 2:7 --baseline "$B" >/dev/null
