#!/bin/sh
# End-to-end tests of a smaller nightly against a larger committed baseline
# (issue 46, item 5: scripts/nightly.sh, compare's "selection" rules in
# host/compare/compare_subset.h), with the program under test (NIGHTLY_BIN:
# no build) and every baseline in scratch directories, the CPU backend:
# - a larger committed baseline (ahn, cobb, tiller on liu2002_ex1,
#   arc_quarter, ph_cubic; --random 3:2026), then a smaller nightly (ahn,
#   cobb on liu2002_ex1, arc_quarter; --random 2:2026) against it: exit 0,
#   the report says what was left out, compare's CSV lists those rows
#   (kind left_out) and none as missing;
# - a row of the smaller run's selection lost: a regression, exit 1;
# - another random seed: not comparable, exit 3;
# - --size small: its committed baseline (results/baseline-small) is
#   comparable with this build, OUT/size says the size, and accepting the
#   run as another size is refused.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
NS="sh $ROOT/scripts/nightly.sh"
export NIGHTLY_BIN="$OB" NIGHTLY_BASELINE="$T/committed" NIGHTLY_HISTORY=none NIGHTLY_BACKEND=cpu \
    NIGHTLY_BASELINES="$T/machines" OFFBENCH_MACHINE=e2e-subset
unset OFFBENCH_TEST_SLOW OFFBENCH_LOADAVG NIGHTLY_SIZE

# nightly OUT METHODS CURVES RANDOM: one night, exit status in $rc, stderr in OUT.err
nightly() {
    o=$1
    NIGHTLY_METHODS=$2 NIGHTLY_CURVES=$3 NIGHTLY_RANDOM=$4 $NS --out "$o" >/dev/null 2>"$o.err"
    rc=$?
}
verdict() { sed -n 3p "$1/report.md"; }

# --- the larger committed baseline ---
nightly "$T/big" ahn,cobb,tiller liu2002_ex1,arc_quarter,ph_cubic 3:2026
$NS --accept-committed --out "$T/big" >/dev/null 2>"$T/err"
check '[ -f "$T/committed/published/results.csv" ] && [ -f "$T/committed/random/results.csv" ]' \
    "the larger baseline accepted: $(cat "$T/err")"

# --- a smaller nightly: exit 0, what it left out said and listed ---
nightly "$T/small" ahn,cobb liu2002_ex1,arc_quarter 2:2026
check '[ $rc -eq 0 ] && [ "$(cat "$T/small/status")" = 0 ] && verdict "$T/small" | grep -q "^\*\*OK: no regression\*\* (exit 0)"' \
    "a subset of the baseline: exit 0: $rc $(verdict "$T/small") $(tail -n 3 "$T/small.err")"
check 'grep -q "^Left out of published (a subset chosen on purpose, not regressions): 1 curve (ph_cubic), method tiller: [0-9]* rows left out\.$" "$T/small/report.md"' \
    "the report says what of published was left out: $(grep "^Left out" "$T/small/report.md")"
check 'grep -q "^Left out of random (a subset chosen on purpose, not regressions): 1 random curve (rnd2026_000002), method tiller: [0-9]* rows left out\.$" "$T/small/report.md"' \
    "... and of random: $(grep "^Left out of random" "$T/small/report.md")"
for set in published random; do
    said=$(sed -n "s/^Left out of $set .*: \([0-9]*\) rows left out\.\$/\1/p" "$T/small/report.md")
    listed=$(grep -c "^left_out," "$T/small/compare-$set-quality.csv")
    total=$(($(wc -l < "$T/committed/$set/results.csv") - $(wc -l < "$T/small/$set/results.csv")))
    check '[ -n "$said" ] && [ "$said" = "$listed" ] && [ "$said" = "$total" ] && ! grep -q "^missing," "$T/small/compare-$set-quality.csv"' \
        "$set: every row the baseline has beyond the run is left out, none missing: said $said, listed $listed, rows $total"
done
check 'grep -q "^- selection: NEW set out to run 2 curves from files (4 offsets), no random set, 2 methods" "$T/small/compare-published-quality.md"' \
    "compare's context says what the run set out to run: $(grep "^- selection" "$T/small/compare-published-quality.md")"
check 'grep -q "size full; random set 2:2026" "$T/small/report.md"' "the report names the size and the random set"

# --- a row inside the selection lost: a regression ---
mkdir -p "$T/lost"
cp "$T/small/published/meta.json" "$T/lost/"
awkc 'NR == 1 || !($c["method"] == "ahn" && $c["curve"] == "arc_quarter" && !done++)' \
    "$T/small/published/results.csv" > "$T/lost/results.csv"
$OB compare "$T/committed/published" "$T/lost" --no-timing >"$T/lost.md" 2>/dev/null
check '[ $? -eq 1 ] && grep -q "^\*\*REGRESSION\*\* (exit 1): .*missing rows 1)" "$T/lost.md" && grep -q "^| arc_quarter | .* | ahn |" "$T/lost.md" && grep -q "^Left out: " "$T/lost.md"' \
    "a row the run should have made is missing, exit 1, the rest still left out: $(sed -n 3p "$T/lost.md")"

# --- another random seed: not comparable ---
nightly "$T/seed" ahn liu2002_ex1 2:7
check '[ $rc -eq 3 ] && grep -q "not comparable: seed 2026 vs 7" "$T/seed/report.md"' \
    "another seed: exit 3: $rc $(grep -m 1 "not comparable" "$T/seed/report.md")"

# --- --size small: the committed small baseline, OUT/size, accepting as another size refused ---
(unset NIGHTLY_BASELINE; NIGHTLY_SIZE=small nightly "$T/sz" ahn liu2002_ex1 2:2026)
check '[ "$(cat "$T/sz/size" 2>/dev/null)" = small ] && grep -q "quality against results/baseline-small/ (committed); .*size small" "$T/sz/report.md"' \
    "--size small: against results/baseline-small, OUT/size: $(cat "$T/sz/size" 2>/dev/null) $(grep "^Commit" "$T/sz/report.md")"
st=$(cat "$T/sz/status" 2>/dev/null)
check '[ "$st" = 0 ] || [ "$st" = 1 ]' "results/baseline-small comparable with this build (0 or 1, never 3): $st $(grep -m 1 "not comparable" "$T/sz/report.md")"
check 'grep -q "^Left out of published (a subset chosen on purpose, not regressions): 8 curves" "$T/sz/report.md"' \
    "one curve of the small set: the other 8 left out: $(grep "^Left out of published" "$T/sz/report.md")"
NIGHTLY_BASELINE=$T/never $NS --accept-committed --size full --out "$T/sz" >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "is a small nightly, not full" "$T/err" && [ ! -e "$T/never" ]' \
    "a small run is not accepted as the full baseline: $(cat "$T/err")"
$NS --size medium --out "$T/m" >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "full or small" "$T/err"' "--size medium: 2: $(cat "$T/err")"
$NS --help > "$T/help" 2>&1
check 'grep -q -- "--size small" "$T/help" && grep -q "left out" "$T/help" && grep -q "Files: OUT/report.md" "$T/help"' \
    "--help says what a subset does, to its last line"

e2e_done
