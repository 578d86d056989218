#!/bin/sh
# report_fixture.sh OFFBENCH STORE SCRATCH - a small synthetic nightly
# history for tests/e2e/e2e_report.sh and scripts/report_screenshot.sh (not a
# test itself).  Two real runs of OFFBENCH (published: liu2002_ex1, tiller
# and cobb at 1e-2 and 1e-3 with --reps 3; random: --random 3:7 at 1e-2),
# recorded through scripts/nightly_history.sh as five nights a day apart
# with made-up commits, then edited so that the history holds known steps:
#   1 aaaaaaa  status 0
#   2 bbbbbbb  status 0
#   3 ccccccc  status 2, stage "run random": the random set missing
#   4 ddddddd  status 1: published cobb's first row +5 ctrl_points (quality step)
#   5 eeeeeee  status 0: published tiller's fit_ns and eval_ns x3 in every
#              row and repetition (time step); cobb as in run 4 (no new step)
# Every other figure is the same in every run, so no other step may show.
# Each night's report.md holds real compares with --no-timing (as
# scripts/nightly.sh lays them out) against a baseline: night 1's runs, with
# cobb's raised control points accepted after night 4, so that each
# report.md agrees with its run.json (night 3 ended before compare: none).
set -eu
OB=$1 H=$2 S=$3
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PY=/usr/bin/python3
mkdir -p "$S/n"
"$OB" run --curve liu2002_ex1 --methods tiller,cobb --tols 1e-2,1e-3 --reps 3 --backend cpu \
    --out "$S/n/published" 2>"$S/n/published.log"
"$OB" run --random 3:7 --methods tiller,cobb --tols 1e-2 --backend cpu --out "$S/n/random" 2>"$S/n/random.log"
cp -R "$S/n" "$S/base"

# report: report.md as nightly.sh writes it, compare against $S/base
report() {
    printf '# offbench nightly (synthetic)\n\n' > "$S/n/report.md"
    for s in published random; do
        printf '## %s\n\n' "$s" >> "$S/n/report.md"
        "$OB" compare "$S/base/$s" "$S/n/$s" --no-timing >> "$S/n/report.md" 2>"$S/n/compare-$s.err" || true
        echo >> "$S/n/report.md"
    done
}

# edit FILE METHOD COLUMN FACTOR ADD [FIRST]: scale and shift a column of
# METHOD's rows (only the first such row with FIRST=1), found by name
edit() {
    "$PY" - "$@" <<'EOF'
import csv, sys
path, method, column, factor, add = sys.argv[1:6]
first = len(sys.argv) > 6 and sys.argv[6] == "1"
with open(path, newline="") as f:
    rows = list(csv.reader(f))
col = {n: i for i, n in enumerate(rows[0])}
done = False
for r in rows[1:]:
    if r[col["method"]] != method or (first and done):
        continue
    r[col[column]] = str(int(int(r[col[column]]) * float(factor) + int(add)))
    done = True
with open(path, "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows(rows)
EOF
}

t0=1795000000
rec() {  # NIGHT COMMIT STATUS STAGE
    sh "$ROOT/scripts/nightly_history.sh" record --out "$S/n" --history "$H" --status "$3" --stage "$4" \
        --commit "$2" --time $((t0 + $1 * 86400)) --random 3:7 >/dev/null
}
report
rec 1 aaaaaaa1111 0 compare
rec 2 bbbbbbb2222 0 compare
mv "$S/n/random" "$S/random.away"
mkdir "$S/away"
mv "$S/n/report.md" "$S/n"/compare-*.err "$S/away/"
rec 3 ccccccc3333 2 "run random"
mv "$S/random.away" "$S/n/random"
edit "$S/n/published/results.csv" cobb ctrl_points 1 5 1
report
rec 4 ddddddd4444 1 compare
for f in results samples; do
    for c in fit_ns eval_ns; do edit "$S/n/published/$f.csv" tiller $c 3 0; done
done
cp "$S/n/published/results.csv" "$S/base/published/results.csv"   # cobb's change accepted
report
rec 5 eeeeeee5555 0 compare
