#!/bin/sh
# End-to-end tests of measure reading SVG (issue 39 item 3): the paths of an
# SVG file, read as scripts/svg2curves.py reads them with its defaults (y up,
# user units, the transforms of the element and its groups applied):
# - an export's STEM.svg (native C pieces under scale(1,-1)) measures as its
#   JSON does: the same pieces, the same hausdorff-whole;
# - hand-written paths on exact offsets: arcs (A, relative, under transforms
#   that cancel), lines and curves of every command (M L H V C S Q T Z, both
#   cases) measured to round-off;
# - the same files through svg2curves.py: the same hausdorff-whole;
# - the format by first bytes; a circle of radius 0 is skipped and named; malformed path
#   data: exit 2 with FILE:LINE and the character.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
REF=$ROOT/datasets/reference.curves

# m FILE CURVE D [ARGS]: measure's CSV in $T/m.csv, stderr in $T/m.err; the exit status
m() { f=$1 c=$2 d=$3; shift 3
      "$OB" measure --curves "$REF" --curve "$c" --d "$d" --approx "$f" "$@" >"$T/m.csv" 2>"$T/m.err"; }
val() { awkc '$c["metric"] == w {print $c["max_err"]}' w="$1" "$T/m.csv"; }
col() { csvcols "$T/m.csv" "$1" | sed -n 2p; }
small() { awk -v a="$1" -v t="$2" 'BEGIN{exit !(a != "" && a + 0 < t + 0)}'; }
near() { awk -v a="$1" -v b="$2" 'BEGIN{d = a - b; if (d < 0) d = -d; exit !(a != "" && b != "" && d <= 1e-12 * (a < 0 ? -a : a) + 1e-16)}'; }

# --- an export's SVG against its JSON ---------------------------------------
"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-3 --backend cpu --out "$T/r" --export "$T/x" 2>"$T/err"
check '[ $? -eq 0 ]' "run --export: exit 0"
S=$T/x/liu2002_ex1__d-1__tiller__tol0.001
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$S.json" --metric hausdorff-whole >"$T/m.csv" 2>"$T/m.err"
wj=$(val hausdorff-whole) pj=$(col pieces) cj=$(col ctrl_points)
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$S.svg" --metric hausdorff-whole >"$T/m.csv" 2>"$T/m.err"
check '[ $? -eq 0 ] && near "$(val hausdorff-whole)" "$wj" && [ "$(col pieces)" = "$pj" ] && [ "$(col ctrl_points)" = "$cj" ]' \
    "export SVG: hausdorff-whole $(val hausdorff-whole) (JSON $wj), pieces $(col pieces) ($pj), ctrl_points $(col ctrl_points) ($cj): $(head -c 300 "$T/m.err")"

# --- arcs on the offsets of arc_quarter (radius 0.5 and 1.5 about 0) --------
# y up: SVG's (x, -y); the transforms cancel
cat > "$T/arc.svg" <<'X'
<?xml version="1.0" encoding="UTF-8"?>
<!-- a <path> in a comment is no path -->
<svg xmlns="http://www.w3.org/2000/svg" viewBox="-2 -2 4 4">
  <defs><path id="hidden" d="M 9 9 L 10 10"/></defs>
  <g transform="translate(10,20) rotate(30)">
    <path id="outer" transform="rotate(-30) translate(-10 -20)" d="M1.5,0 a1.5,1.5 0 0 0 -1.5,-1.5"/>
  </g>
</svg>
X
m "$T/arc.svg" arc_quarter -0.5
check '[ $? -eq 0 ] && small "$(val hausdorff-whole)" 1e-14 && small "$(val hausdorff)" 1e-14 && [ "$(col pieces)" = 1 ] && ! grep -q warning "$T/m.err"' \
    "arc (relative A under transforms): 1 piece, hausdorff $(val hausdorff), whole $(val hausdorff-whole): $(cat "$T/m.err")"
printf '<svg xmlns="http://www.w3.org/2000/svg">\n<g transform="scale(1,-1)">\n<circle r="0"/>\n<path d="M 0.5 0 A 0.5 0.5 0 0 1 0.35355339059327379 0.35355339059327373 A .5 .5 0 0 1 0 0.5"/></g></svg>\n' > "$T/arc2.txt"
m "$T/arc2.txt" arc_quarter 0.5
check '[ $? -eq 0 ] && small "$(val hausdorff-whole)" 1e-14 && [ "$(col pieces)" = 2 ] && [ "$(col ctrl_points)" = 5 ] &&
       grep -q "skipped 1 entity .*1 zero-size <circle> (at line 3)" "$T/m.err"' \
    "two absolute arcs under scale(1,-1), read by first bytes; the circle named: $(col pieces) pieces, $(val hausdorff-whole): $(cat "$T/m.err")"
# radii too small for the chord: SVG scales them up to the circle on the
# chord, a half circle (2 pieces), far from the offset but measured
printf '<svg><path d="M 0.5 0 A 0.1 0.1 0 0 0 0 -0.5"/></svg>\n' > "$T/arc3.svg"
m "$T/arc3.svg" arc_quarter 0.5
check '[ $? -eq 0 ] && [ "$(col pieces)" = 2 ]' "radii too small: a half circle in 2 pieces: $(col pieces) $(cat "$T/m.err")"

# --- every command on the offset of line ((0,0)-(1,0.5), d = 0.3) ------------
awk 'BEGIN{n = sqrt(1.25); ox = -0.5 * 0.3 / n; oy = 0.3 / n
     printf "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\""
     printf "M%.17g,%.17g l0.1-0.05 L%.17g %.17g ", ox, -oy, 0.2 + ox, -0.1 - oy
     printf "q0.05-0.025 0.1-0.05 t0.1-0.05 Q%.17g %.17g %.17g %.17g T%.17g %.17g ", 0.45 + ox, -0.225 - oy, 0.5 + ox, -0.25 - oy, 0.6 + ox, -0.3 - oy
     printf "c0.02-0.01 0.05-0.025 0.1-0.05 s0.07-0.035 0.1-0.05 C%.17g %.17g %.17g %.17g %.17g %.17g ", 0.82 + ox, -0.41 - oy, 0.85 + ox, -0.425 - oy, 0.9 + ox, -0.45 - oy
     printf "S%.17g %.17g %.17g %.17g\"/>\n", 0.95 + ox, -0.475 - oy, 1 + ox, -0.5 - oy
     printf "<path d=\"M 5 5 h 1 v 1 H 5 V 5 z\" transform=\"translate(100)\"/></svg>\n"}' > "$T/line.svg"
# the second path (a square far away) is no part of the offset: the cover fails; alone it passes
sed 's|<path d="M 5 5.*/></svg>|</svg>|' "$T/line.svg" > "$T/line1.svg"
m "$T/line1.svg" line 0.3
check '[ $? -eq 0 ] && small "$(val hausdorff-whole)" 1e-14 && [ "$(col pieces)" = 10 ]' \
    "M l L q t Q T c s C S on the offset of line: 10 pieces, whole $(val hausdorff-whole): $(head -c 300 "$T/m.err")"
m "$T/line.svg" line 0.3
check '[ $? -eq 2 ] && grep -q "line.svg:2: piece 1[0-9]" "$T/m.err"' "h v H V z: a square away from the offset fails the cover, named at its line (2): $(head -c 300 "$T/m.err")"

# --- svg2curves.py reads the same curves ---------------------------------------
if [ -x /usr/bin/python3 ]; then  # svg2curves.py: the standard library only
    for f in arc:arc_quarter:-0.5 arc3:arc_quarter:0.5 line1:line:0.3; do
        IFS=: read -r s c d <<Y
$f
Y
        /usr/bin/python3 "$ROOT/scripts/svg2curves.py" "$T/$s.svg" --d 0.1 --out "$T/$s.curves" 2>"$T/conv.err"
        m "$T/$s.curves" "$c" "$d" --metric hausdorff-whole
        wc=$(val hausdorff-whole)
        m "$T/$s.svg" "$c" "$d" --metric hausdorff-whole
        check 'near "$(val hausdorff-whole)" "$wc" && [ -n "$wc" ]' "$s.svg: hausdorff-whole $(val hausdorff-whole), through svg2curves.py $wc"
    done
    # tests/data/svg/hand.svg, drawn by hand (relative c s q t, Z, an arc
    # rotated -20 degrees with the large-arc flag, under a group's
    # translate): each path alone, against the curve svg2curves.py makes of
    # it, at d = 1e-6: hausdorff-whole is 1e-6 to round-off when both read
    # the same curve (a lone path: the file's other elements left out)
    HAND=$ROOT/tests/data/svg/hand.svg
    /usr/bin/python3 "$ROOT/scripts/svg2curves.py" "$HAND" --d 1e-6 --out "$T/hand.curves" 2>"$T/conv.err"
    for id in wave heart big-arc; do
        awk -v id="$id" '/<path|<circle|<ellipse|<rect|<polyline|<text/{inel=1; buf=""}
            inel{buf=buf $0 "\n"; if ($0 ~ /\/>|<\/text>/) {if (buf ~ "id=\"" id "\"") printf "%s", buf; inel=0}; next} {print}' \
            "$HAND" > "$T/$id.svg"
        "$OB" measure --curves "$T/hand.curves" --curve "$id" --d 1e-6 --approx "$T/$id.svg" --metric hausdorff-whole >"$T/m.csv" 2>"$T/m.err"
        w=$(val hausdorff-whole)
        check 'awk -v w="$w" "BEGIN{exit !(w != \"\" && w - 1e-6 < 1e-12 && 1e-6 - w < 1e-12)}"' \
            "hand.svg's $id: hausdorff-whole $w against svg2curves.py's curve at d = 1e-6: $(head -c 300 "$T/m.err")"
    done
else
    echo "e2e_measure_svg: no /usr/bin/python3: the comparison with svg2curves.py skipped"
    skipped=$((skipped + 6))
fi

# --- bad input ----------------------------------------------------------------------
printf '<svg>\n<path\n d="M 0 0 L 1"/></svg>\n' > "$T/bad.svg"
m "$T/bad.svg" line 0.3
check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -q "bad.svg:2: <path>: d: at the end: expected a number" "$T/m.err"' "a missing number: $(cat "$T/m.err")"
printf '<svg><path d="L 0 0 1 1"/></svg>\n' > "$T/bad2.svg"
m "$T/bad2.svg" line 0.3
check '[ $? -eq 2 ] && grep -q "bad2.svg:1: <path>: d: at character 1 (.L 0 0 1 1.): path data must begin with M" "$T/m.err"' "no moveto: $(cat "$T/m.err")"
printf '<svg><g transform="rotate(1,2)"><path d="M0 0 L 1 1"/></g></svg>\n' > "$T/bad3.svg"
m "$T/bad3.svg" line 0.3
check '[ $? -eq 2 ] && grep -q "bad3.svg:1: <g>: transform: .*wrong number of arguments" "$T/m.err"' "rotate with 2 arguments: $(cat "$T/m.err")"
printf '<svg><line x1="0" y1="a"/></svg>\n' > "$T/bad4.svg"
m "$T/bad4.svg" line 0.3
check '[ $? -eq 2 ] && grep -q "bad4.svg:1: <line>: y1: at character 1 (.a.): expected a number" "$T/m.err"' "a line's y1 not a number: $(cat "$T/m.err")"
printf '<svg><text>hi</text></svg>\n' > "$T/none.svg"
m "$T/none.svg" line 0.3
check '[ $? -eq 2 ] && grep -q "none.svg: no pieces" "$T/m.err"' "no paths: $(cat "$T/m.err")"

e2e_done
