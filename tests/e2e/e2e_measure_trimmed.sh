#!/bin/sh
# measure --trimmed (issue 50): the trimmed offset as the reference.
# - Its arcs (--trim-dump) agree with an independent brute force
#   (tests/e2e/trim_brute.py: 200001 offset points kept by their distance
#   to the curve's polyline, k-d tree) on the parabola's swallowtail at
#   d = 1, on liu2002_ex1 at d = 1 (cut by its end circle) and d = -1 (all
#   kept), on an S cubic at d = +-0.4 (its offset crosses the opposite
#   offset), a quintic wave at d = 0.8 and atlas_trifolium (rational) at
#   d = 0.3.
# - Corners (G0 joints, B-splines of degree 1 or 3 with full interior
#   knots): the dump's corner arcs (--trim-dump kind corner) agree with
#   the brute force's circles about the joints, and their count is the
#   closed form's: an L (convex side 1, concave 0), the unit square
#   (outside 4, inside 0), an M whose peaks' arcs cut each other (2), two
#   cubics meeting at an angle (1 on one side, 0 on the other), out and
#   back along a segment (a reversal: 2, half circles round the ends).
#   Polylines of the brute force's trimmed offset (sides and corner arcs)
#   measure within their construction error, and so does one of the
#   square's exact outside offset made here (its sides, each quarter
#   circle as 8 chords: r (1 - cos(pi / 32)) off), which the brute force's
#   distance finds too.
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
curve L
  source an L of two lines: a corner at (0, 0)
  bspline 1
  knots 0 0 1 2 2
  point -1 0
  point 0 0
  point 0 -1
  offset 0.25 -0.25
end
curve square
  source the unit square, counter-clockwise, closed: its outside is d < 0
  bspline 1
  knots 0 0 1 2 3 4 4
  point 0 0
  point 1 0
  point 1 1
  point 0 1
  point 0 0
  offset -0.25 0.25
end
curve M
  source an M: at d = 0.7 the arcs about its peaks cut each other
  bspline 1
  knots 0 0 1 2 3 4 4
  point 0 0
  point 0.5 1
  point 1 0.2
  point 1.5 1
  point 2 0
  offset 0.7
end
curve hairpin
  source out along the x axis and back, closed: the tangent reverses at both joints
  bspline 1
  knots 0 0 1 2 2
  point 0 0
  point 1 0
  point 0 0
  offset 0.2
end
curve twocubics
  source two cubics meeting at an angle at (2, 0)
  bspline 3
  knots 0 0 0 0 1 1 1 2 2 2 2
  point 0 0
  point 0.5 1
  point 1.5 1
  point 2 0
  point 2.8 0.6
  point 3.5 -0.5
  point 4 0.3
  offset 0.3 -0.3
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
    skipped=$((skipped + 25))
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

# corners: the dump's corner arcs against the brute force's circles about the joints
for cd in "L 0.25 1" "L -0.25 0" "square -0.25 4" "square 0.25 0" "M 0.7 2" "twocubics 0.3 0" "twocubics -0.3 1" \
    "hairpin 0.2 2"; do
    set -- $cd
    brute "$T/p.curves" $1 $2
    rc=$? n=$3
    check '[ $rc -eq 0 ] && [ "$(grep -c ^corner, "$T/dump.csv")" -eq $n ]' \
        "$1 d = $2: $3 corner arcs, $(grep -c ^corner, "$T/dump.csv") in the dump: $(cat "$T/e" "$T/b.out")"
done

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
# cornered bases: the brute force's polylines (sides and corner arcs)
for cd in "square -0.25 200" "M 0.7 200" "twocubics -0.3 300"; do
    set -- $cd
    E=$("$PY" "$BRUTE" polyline "$T/p.curves" "$1" "$2" "$T/poly.dxf" "$3" 2>"$T/pe")
    "$OB" measure --curves "$T/p.curves" --curve "$1" --d "$2" --approx "$T/poly.dxf" --trimmed >"$T/t.csv" 2>"$T/e"
    check '[ $? -eq 0 ] && within "$T/t.csv" "$E"' \
        "$1 d = $2: trimmed-hausdorff $(col "$T/t.csv" trimmed-hausdorff max_err) vs construction error $E: $(cat "$T/pe" "$T/e")"
done
# the square's exact outside offset at d = -0.25, made here: its sides and
# each quarter circle about a corner as 8 chords, r (1 - cos(pi / 32)) off
E=$("$PY" - "$T/sq.dxf" <<'PY'
import sys
from math import cos, sin, pi
r, V, out = 0.25, [(0, 0), (1, 0), (1, 1), (0, 1)], []
for k in range(4):
    (x0, y0), (x1, y1) = V[k], V[(k + 1) % 4]
    a = (k - 1) * pi / 2  # side k's outward normal
    out.append((x0 + r * cos(a), y0 + r * sin(a), x1 + r * cos(a), y1 + r * sin(a)))
    for i in range(8):  # the quarter circle about V[k + 1], from a to a + pi / 2
        b, c = a + i * pi / 16, a + (i + 1) * pi / 16
        out.append((x1 + r * cos(b), y1 + r * sin(b), x1 + r * cos(c), y1 + r * sin(c)))
with open(sys.argv[1], "w") as f:
    f.write("0\nSECTION\n2\nENTITIES\n")
    for p in out:
        f.write("0\nLINE\n8\n0\n10\n%.17g\n20\n%.17g\n11\n%.17g\n21\n%.17g\n" % p)
    f.write("0\nENDSEC\n0\nEOF\n")
print("%.17g" % (r * (1 - cos(pi / 32))))
PY
)
"$OB" measure --curves "$T/p.curves" --curve square --d -0.25 --approx "$T/sq.dxf" --trimmed >"$T/t.csv" 2>"$T/e"
a=$(col "$T/t.csv" trimmed-hausdorff max_err)
check '[ $? -eq 0 ] && within "$T/t.csv" "$E"' "square's exact outside offset, arcs as 8 chords: trimmed-hausdorff $a vs $E: $(cat "$T/e")"
b=$("$PY" "$BRUTE" distance "$T/p.curves" square -0.25 "$T/sq.dxf" 2>&1)
check 'awk -v a="$a" -v b="$b" -v e="$E" "BEGIN{x = b - e; if (x < 0) x = -x; exit !(a != \"\" && x <= 1e-4 * e + 2e-5)}"' \
    "square: the brute force's distance $b vs $E (offbench $a)"
echo "  corners: the square's outside offset, arcs as 8 chords: trimmed-hausdorff $a, brute force $b, chord error $E"

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
