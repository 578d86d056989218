#!/bin/sh
# measure --trimmed (issue 50): the trimmed offset as the reference.
# - Its arcs (--trim-dump) agree with an independent brute force
#   (tests/e2e/trim_brute.py: 200001 offset points kept by their distance
#   to the curve's polyline, k-d tree) on the parabola's swallowtail at
#   d = 1, on liu2002_ex1 at d = 1 (cut by its end circle) and d = -1 (all
#   kept), on an S cubic at d = +-0.4 (its offset crosses the opposite
#   offset), a quintic wave at d = 0.8 and atlas_trifolium (rational) at
#   d = 0.3.
# - A trimmed polyline made in Python (the trimmed offset's kept ranges,
#   ends refined there, points on the exact offset) measures within its
#   construction error (the chords' largest distance from the offset),
#   while the untrimmed measure refuses it (exit 2); at d = -1 (no loops)
#   trimmed-hausdorff equals hausdorff-whole.
# - Bad input: --trim-dump without --trimmed, --trimmed with a metric that
#   needs a parameter match: exit 2 naming the option; --metric certified
#   gives a row n/a saying why; an empty trimmed offset: exit 2, named.
# Skipped (but the option checks) when /usr/bin/python3 lacks numpy and
# scipy.
. "$(dirname "$0")/lib_e2e.sh"
PY=${TRIM_BRUTE_PYTHON:-/usr/bin/python3}
BRUTE=$(cd "$(dirname "$0")" && pwd)/trim_brute.py
PUB=$(cd "$(dirname "$0")/../.." && pwd)/datasets/published.curves
cat > "$T/p.curves" <<'CURVES'
curve parabola
  source (t, t^2) for t in [-2, 2]
  bezier 2
  point -2 4
  point 0 -4
  point 2 4
  offset 1 -1
end
curve scurve
  source an S: its offsets cross the opposite offsets
  bezier 3
  point 0 0
  point 4 3
  point -3 3
  point 1 0
  offset 0.4 -0.4
end
curve wave
  source two and a half waves: swallowtails cut by the end circles
  bezier 5
  point 0 0
  point 1 2
  point 2 -2
  point 3 2
  point 4 -2
  point 5 0
  offset 0.8
end
CURVES
# col FILE METRIC COLUMN: a column of the row of METRIC
col() { awk -F, -v m="$2" -v c="$3" 'NR == 1 {for (i = 1; i <= NF; i++) k[$i] = i; next} $1 == m {print $k[c]}' "$1"; }
# a file to measure: a LINE of no matter what
printf '0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n0\n20\n0\n11\n1\n21\n1\n0\nENDSEC\n0\nEOF\n' > "$T/line.dxf"

# the option checks (no Python)
"$OB" measure --curve liu2002_ex1 --d 1 --approx "$T/line.dxf" --trim-dump "$T/x.csv" >"$T/o" 2>"$T/e"
check '[ $? -eq 2 ] && [ ! -s "$T/o" ] && grep -q -- "--trim-dump" "$T/e"' "--trim-dump alone: exit 2 naming it: $(cat "$T/e")"
"$OB" measure --curve liu2002_ex1 --d 1 --approx "$T/line.dxf" --trimmed --metric radial >"$T/o" 2>"$T/e"
check '[ $? -eq 2 ] && [ ! -s "$T/o" ] && grep -q -- "--metric" "$T/e" && grep -q -- "--trimmed" "$T/e"' \
    "--trimmed --metric radial: exit 2 naming both: $(cat "$T/e")"
"$OB" measure --curve liu2002_ex1 --d 1 --approx "$T/line.dxf" --trimmed --metric certified >"$T/o" 2>"$T/e"
check '[ $? -eq 0 ] && [ "$(col "$T/o" certified status)" = n/a ] && grep -q "^certified,n/a,.*does not apply" "$T/o" &&
       [ "$(col "$T/o" trimmed-hausdorff status)" = ok ]' "--metric certified: a row n/a, and trimmed-hausdorff: $(cat "$T/o" "$T/e")"
"$OB" measure --curve atlas_circle --d 1.5 --approx "$T/line.dxf" --trimmed >"$T/o" 2>"$T/e"
check '[ $? -eq 2 ] && [ ! -s "$T/o" ] && grep -q "trimmed offset is empty" "$T/e"' "inward past the center: exit 2: $(cat "$T/e")"

if ! "$PY" -c 'import numpy, scipy.spatial, scipy.optimize' >/dev/null 2>&1; then
    echo "e2e_measure_trimmed: $PY does not import numpy and scipy: skipped"
    skipped=$((skipped + 12))
    e2e_done
    exit $?
fi

# brute CURVES ID D: the dump against the brute force
brute() {
    "$OB" measure --curves "$1" --curve "$2" --d "$3" --approx "$T/line.dxf" --trimmed --trim-dump "$T/dump.csv" \
        >"$T/o" 2>"$T/e" && "$PY" "$BRUTE" check "$1" "$2" "$3" "$T/dump.csv" >"$T/b.out" 2>&1
}
brute "$T/p.curves" parabola 1
check '[ $? -eq 0 ] && [ "$(grep -c ^arc, "$T/dump.csv")" -eq 2 ]' "parabola d = 1: $(cat "$T/e" "$T/b.out")"
brute "$PUB" liu2002_ex1 1
check '[ $? -eq 0 ]' "liu2002_ex1 d = 1: $(cat "$T/e" "$T/b.out")"
brute "$PUB" liu2002_ex1 -1
check '[ $? -eq 0 ] && grep -q "^arc,0,0,1," "$T/dump.csv"' "liu2002_ex1 d = -1: $(cat "$T/e" "$T/b.out")"
for d in 0.4 -0.4; do
    brute "$T/p.curves" scurve $d
    check '[ $? -eq 0 ] && grep -q "^opposite," "$T/dump.csv"' "scurve d = $d: $(cat "$T/e" "$T/b.out")"
done
brute "$T/p.curves" wave 0.8
check '[ $? -eq 0 ] && grep -q "^end," "$T/dump.csv" && grep -q "^self," "$T/dump.csv"' "wave d = 0.8: $(cat "$T/e" "$T/b.out")"
brute "$(dirname "$PUB")/atlas.curves" atlas_trifolium 0.3
check '[ $? -eq 0 ]' "atlas_trifolium d = 0.3: $(cat "$T/e" "$T/b.out")"

# within FILE E: trimmed-hausdorff of FILE's row in (0.9 E, E (1 + 1e-4) + 1e-13] (E is sampled
# 65 times a chord: a little low)
within() {
    awk -v a="$(col "$1" trimmed-hausdorff max_err)" -v e="$2" 'BEGIN{exit !(a != "" && a > 0.9 * e && a <= e * (1 + 1e-4) + 1e-13)}'
}
for cd in "$T/p.curves parabola 1 300" "$PUB liu2002_ex1 1 200"; do
    set -- $cd
    E=$("$PY" "$BRUTE" polyline "$1" "$2" "$3" "$T/poly.dxf" "$4" 2>"$T/pe")
    "$OB" measure --curves "$1" --curve "$2" --d "$3" --approx "$T/poly.dxf" --trimmed >"$T/t.csv" 2>"$T/e"
    check '[ $? -eq 0 ] && within "$T/t.csv" "$E"' \
        "$2 d = $3: trimmed-hausdorff $(col "$T/t.csv" trimmed-hausdorff max_err) vs construction error $E: $(cat "$T/pe" "$T/e")"
    "$OB" measure --curves "$1" --curve "$2" --d "$3" --approx "$T/poly.dxf" >"$T/u.csv" 2>"$T/e"
    check '[ $? -eq 2 ] && [ ! -s "$T/u.csv" ]' "$2 d = $3: the untrimmed measure refuses it: $(cat "$T/u.csv" "$T/e")"
done
# d = -1: nothing trimmed, the two distances agree
E=$("$PY" "$BRUTE" polyline "$PUB" liu2002_ex1 -1 "$T/poly.dxf" 200 2>"$T/pe")
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$T/poly.dxf" --trimmed >"$T/t.csv" 2>"$T/e"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$T/poly.dxf" --metric hausdorff-whole >"$T/u.csv" 2>>"$T/e"
a=$(col "$T/t.csv" trimmed-hausdorff max_err) b=$(col "$T/u.csv" hausdorff-whole max_err)
check 'awk -v a="$a" -v b="$b" -v e="$E" "BEGIN{d = a - b; if (d < 0) d = -d; exit !(a != \"\" && b != \"\" && d <= 1e-12 && a <= e * (1 + 1e-6))}"' \
    "d = -1: trimmed-hausdorff $a, hausdorff-whole $b, construction error $E: $(cat "$T/e")"
# with the other options of measure: --tol decides on trimmed-hausdorff,
# the frame options apply before it, --per-piece and --draw are refused
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$T/poly.dxf" --trimmed --tol 1 >/dev/null 2>"$T/e1"
r1=$?
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$T/poly.dxf" --trimmed --tol 1e-15 >/dev/null 2>"$T/e2"
r2=$?
check '[ $r1 -eq 0 ] && [ $r2 -eq 1 ] && grep -q "within tolerance 1: trimmed-hausdorff = " "$T/e1" && grep -q "over tolerance 1e-15: trimmed-hausdorff = " "$T/e2"' \
    "--trimmed --tol: exit 0 within, 1 over, on trimmed-hausdorff: $r1 $r2 $(cat "$T/e1" "$T/e2" | grep tolerance)"
awk '{ if (prev == "10" || prev == "20") printf "%.17g\n", $1 * 2; else print; prev = $0 }' "$T/poly.dxf" >"$T/poly2.dxf"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$T/poly2.dxf" --trimmed --scale 0.5 >"$T/s.csv" 2>"$T/e3"
check '[ $? -eq 0 ] && [ "$(col "$T/s.csv" trimmed-hausdorff max_err)" = "$a" ]' \
    "--scale applies before --trimmed: a file drawn twice as large measures the same, $(col "$T/s.csv" trimmed-hausdorff max_err) and $a: $(cat "$T/e3")"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$T/poly.dxf" --trimmed --per-piece "$T/pp.csv" >/dev/null 2>"$T/e4"
check '[ $? -eq 2 ] && grep -q "^offbench: --per-piece: not with --trimmed" "$T/e4" && [ ! -e "$T/pp.csv" ]' \
    "--trimmed with --per-piece: exit 2 naming it: $(cat "$T/e4")"
e2e_done
