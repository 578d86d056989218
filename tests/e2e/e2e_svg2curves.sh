#!/bin/sh
# End-to-end tests of scripts/svg2curves.py (SVG paths to .curves, README
# "Curve files"): SVGs written here (lines, quadratics, cubics and arcs under
# transforms) and one drawn by hand (tests/data/svg/hand.svg) convert, read
# back with `./offbench list curves`, run with tiller, and match the SVG's
# geometry to 1e-9 (tests/e2e/svgcheck.py: its own reader and de Boor
# evaluation of the .curves text against svgelements' point(t), and arcs on
# their ellipse); every feature the converter leaves out is named on stderr.
# Needs /usr/bin/python3 with svgelements (Debian's python3-svgelements);
# without it every check counts as skipped.  Uses $OFFBENCH or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PY=/usr/bin/python3
CONV=$ROOT/scripts/svg2curves.py
CHECK=$ROOT/tests/e2e/svgcheck.py
HAND=$ROOT/tests/data/svg/hand.svg

NCHECKS=53
if ! "$PY" -c 'import svgelements' >/dev/null 2>&1; then
    echo "e2e_svg2curves: $PY cannot import svgelements (apt-get install python3-svgelements): skipped"
    echo "0 passed, 0 failed, $NCHECKS skipped"
    exit 0
fi

conv() { "$PY" "$CONV" "$@"; }
# runs tiller over FILE at 1e-2 into DIR; every job ok, N rows
runs_ok() { # FILE DIR N
    $OB run --curves "$1" --methods tiller --tols 1e-2 --out "$2" >/dev/null 2>&1 || return 1
    [ "$(rcols "$2/results.csv" status | grep -c '^ok$')" -eq "$3" ] &&
        [ "$(rcols "$2/results.csv" status | wc -l)" -eq "$3" ]
}
ids() { $OB list curves --curves "$1" 2>/dev/null | awk 'NR>2{print $1}' | tr '\n' ' '; }
no_trace() { ! grep -q 'Traceback' "$1"; }

# --- (1) a path of every segment kind under nested transforms ---
# group: rotate + translate; path: a general matrix (skew, unequal scales) so
# that the arcs are general ellipses; a large arc (271.6 degrees: 4 pieces), a
# quarter arc (exactly 90 degrees: 1 piece), relative commands, a second subpath
cat > "$T/mix.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="300" height="200">
 <g transform="translate(20,10) rotate(15)">
  <path id="mix" transform="matrix(1.2,0.3,-0.2,0.9,5,-3)"
        d="M 0 0 L 10 2 Q 15 8 20 0 C 25 -5 30 5 35 0 A 12 6 30 1 1 50 5 a 10 10 0 0 0 10 10 l 5 5
           M 80 0 l 10 0 l 0 10"/>
 </g>
 <path id="curvy" d="M 10 100 Q 30 60 50 100 T 90 100 C 100 120 120 120 130 100 S 160 80 170 100"/>
</svg>
EOF
conv "$T/mix.svg" --d 0.5,-0.25 --out "$T/mix.curves" 2>"$T/mix.err"
check '[ $? -eq 0 ] && [ -s "$T/mix.curves" ]' "svg2curves mix.svg exits 0: $(cat "$T/mix.err")"
check '[ "$(ids "$T/mix.curves")" = "mix.1 mix.2 curvy " ]' "list curves reads back the ids: $(ids "$T/mix.curves")"
$OB list curves --curves "$T/mix.curves" > "$T/mix.list" 2>&1
check 'grep -Eq "^mix\.1 +svg +9 +3 +yes +0\.5 -0\.25" "$T/mix.list"' \
      "mix.1: family svg, 9 segments (L Q C, 4 + 1 arc pieces, L), degree 3, rational: $(cat "$T/mix.list")"
check 'grep -Eq "^mix\.2 +svg +2 +1 +no " "$T/mix.list"' "mix.2: a polyline, degree 1"
check 'grep -Eq "^curvy +svg +4 +3 +no " "$T/mix.list"' "curvy: Q T C S, 4 segments of degree 3"
"$PY" "$CHECK" "$T/mix.svg" "$T/mix.curves" --expect "mix.1:LQCAAAAAL,mix.2:LL,curvy:QQCC" > "$T/mix.chk" 2>&1
check '[ $? -eq 0 ]' "mix.svg geometry to 1e-9: $(cat "$T/mix.chk")"
check 'grep -q "^svgcheck: mix.1: 9 spans ok" "$T/mix.chk"' "svgcheck checked mix.1's 9 spans"
check 'runs_ok "$T/mix.curves" "$T/mixrun" 6' "run --methods tiller over mix.curves: 6 jobs ok"
check 'grep -q "^  bspline 3" "$T/mix.curves" && grep -q "^  knots 0 0 0 0 1 1 1 2 2 2 " "$T/mix.curves"' \
      "a subpath of several segments is a B-spline with knots of full multiplicity"

# --y down keeps SVG's coordinates; --y up (default) is their mirror
conv "$T/mix.svg" --d 0.5 --y down --out "$T/down.curves" 2>/dev/null
"$PY" "$CHECK" "$T/mix.svg" "$T/down.curves" --y down > "$T/down.chk" 2>&1
check '[ $? -eq 0 ]' "--y down geometry to 1e-9: $(cat "$T/down.chk")"
"$PY" "$CHECK" "$T/mix.svg" "$T/down.curves" > /dev/null 2>&1
check '[ $? -eq 1 ]' "the checker sees --y down's curves are not --y up's (it can fail)"
check 'grep -q "^  point 10 100$" "$T/down.curves" && grep -q "^  point 10 -100$" "$T/mix.curves"' \
      "curvy starts at (10, 100) with --y down, (10, -100) with --y up"

# --units: user units of the viewBox (default) or CSS px
cat > "$T/mm.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 100 50">
 <path id="seg" d="M 10 10 C 20 0 30 20 40 10"/>
</svg>
EOF
conv "$T/mm.svg" --d 1 --out "$T/mm.curves" 2>/dev/null
check 'grep -q "^  point 40 -10$" "$T/mm.curves"' "--units user: the viewBox's units"
conv "$T/mm.svg" --d 1 --units px --out "$T/px.curves" 2>/dev/null
"$PY" "$CHECK" "$T/mm.svg" "$T/px.curves" --units px > "$T/px.chk" 2>&1
check '[ $? -eq 0 ] && grep -q "^  bezier 3" "$T/px.curves" && ! grep -q "^  point 40 -10$" "$T/px.curves"' \
      "--units px: 96 per inch, geometry to 1e-9: $(cat "$T/px.chk")"

# --- shapes, closed subpaths, degenerate segments, ids ---
cat > "$T/shapes.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">
 <path id="zero" d="M 0 0 L 0 0 L 10 0 Q 10 0 10 0 C 15 5 20 5 25 0"/>
 <path id="dot" d="M 5 5 L 5 5"/>
 <path id="box" d="M 0 0 H 10 V 10 H 0 Z"/>
 <circle id="ring" cx="50" cy="50" r="10"/>
 <path id="bad id#1" d="M 0 0 L 5 5"/>
 <path id="dup" d="M 0 0 L 5 5"/>
 <path id="dup" d="M 0 0 L 6 6"/>
 <path d="M 0 0 L 7 7"/>
 <path id="flat" d="M 10 10 A 0 5 0 0 1 20 20"/>
 <text id="words" x="0" y="0">hi</text>
 <image id="pic" x="0" y="0" width="5" height="5" href="x.png"/>
 <blob xmlns="http://www.w3.org/2000/svg" id="what"/>
 <circle id="nil" cx="1" cy="1" r="0"/>
</svg>
EOF
conv "$T/shapes.svg" --d 0.5 --out "$T/shapes.curves" 2>"$T/shapes.err"
check '[ $? -eq 0 ] && no_trace "$T/shapes.err"' "shapes.svg converts, no traceback: $(cat "$T/shapes.err")"
$OB list curves --curves "$T/shapes.curves" > "$T/shapes.list" 2>&1
check '[ "$(ids "$T/shapes.curves")" = "zero box ring bad_id_1 dup dup-2 path8 flat " ]' \
      "ids: sanitized, made unique, 'path8' without an id: $(ids "$T/shapes.curves")"
check 'grep -q "<path id=\"zero\">: segment 1 (Line) has zero length; left out" "$T/shapes.err" &&
       grep -q "<path id=\"zero\">: segment 3 (QuadraticBezier) has zero length; left out" "$T/shapes.err"' \
      "zero-length segments named, element and segment"
check 'grep -Eq "^zero +svg +2 +3 " "$T/shapes.list"' \
      "zero keeps its 2 segments of nonzero length"
check 'grep -q "<path id=\"dot\">: no segment of nonzero length; left out" "$T/shapes.err"' "a path of zero length is left out, named"
check 'grep -q "<path id=\"box\">: closed subpath written as an open curve" "$T/shapes.err" &&
       grep -q "<circle id=\"ring\">: closed subpath written as an open curve" "$T/shapes.err"' "closed subpaths named"
check 'grep -Eq "^box +svg +4 +1 " "$T/shapes.list" && grep -Eq "^ring +svg +4 +2 +yes" "$T/shapes.list"' \
      "box: 4 lines back to its start; ring: 4 quarter arcs"
check '[ "$(sed -n "/^curve ring/,/^end/p" "$T/shapes.curves" | grep -c " 0\.7071067811865476$")" -eq 4 ]' \
      "ring: each quarter arc's middle weight is cos(45 degrees)"
check 'grep -q "id has characters the .curves reader refuses; written as .bad_id_1." "$T/shapes.err"' "sanitized id named"
check 'grep -q "<path id=\"dup\">: id .dup. already used; written as .dup-2." "$T/shapes.err"' "duplicate id named"
check 'grep -Eq "^flat +svg +1 +1 " "$T/shapes.list"' "an arc with a zero radius is a line (SVG 1.1, F.6.2)"
check 'grep -q "<text id=\"words\">: unsupported element (text)" "$T/shapes.err" &&
       grep -q "<image id=\"pic\">: unsupported element (image)" "$T/shapes.err" &&
       grep -q "<blob id=\"what\">: unknown element" "$T/shapes.err"' "unsupported and unknown elements named"
check 'grep -q "<circle id=\"nil\">: the SVG parser dropped it" "$T/shapes.err"' "a circle of radius 0 is named"
check 'runs_ok "$T/shapes.curves" "$T/shrun" 8' "run over shapes.curves: 8 jobs ok"
conv "$T/shapes.svg" --d 0.5 --closed skip --out "$T/skip.curves" 2>"$T/skip.err"
check '[ "$(ids "$T/skip.curves")" = "zero bad_id_1 dup dup-2 path8 flat " ] &&
       grep -q "<circle id=\"ring\">: closed subpath left out (--closed skip)" "$T/skip.err"' "--closed skip leaves them out, named"
conv "$T/shapes.svg" --d 0.5 --strict --out "$T/strict.curves" 2>"$T/strict.err"
check '[ $? -eq 1 ] && [ ! -e "$T/strict.curves" ] && grep -q "strict" "$T/strict.err"' "--strict: exit 1, nothing written"
conv "$T/mix.svg" --d 0.5 --strict --out "$T/strict2.curves" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/strict2.curves" ]' "--strict passes a file with nothing left out"
conv "$T/mix.svg" --d 0.5 --prefix u/ --out "$T/pre.curves" 2>/dev/null
check '[ "$(ids "$T/pre.curves")" = "u/mix.1 u/mix.2 u/curvy " ]' "--prefix: $(ids "$T/pre.curves")"

# --- curves the reader would refuse: left out with the rule ---
cat > "$T/refuse.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">
 <path id="huge" d="M 0 0 L 2e12 0"/>
 <path id="tiny" d="M 1e11 0 L 1e11 1e-3 L 0 0"/>
 <path id="fine" d="M 0 0 L 10 0"/>
</svg>
EOF
conv "$T/refuse.svg" --d 0.5 --out "$T/refuse.curves" 2>"$T/refuse.err"
check '[ $? -eq 0 ] && [ "$(ids "$T/refuse.curves")" = "fine " ]' "only 'fine' is written: $(cat "$T/refuse.err")"
check 'grep -q "<path id=\"huge\">: left out, the .curves reader would refuse it: coordinate .* beyond +-1e12" "$T/refuse.err"' "huge: named, with the rule"
check 'grep -q "<path id=\"tiny\">: left out, the .curves reader would refuse it: its segment 0 spans 0.001, below 1e-12" "$T/refuse.err"' "tiny: named, with the rule"
conv "$T/refuse.svg" --d 1e-20 --out "$T/small.curves" 2>"$T/small.err"
check '[ $? -eq 2 ] && grep -q "<path id=\"fine\">: .*offset 1e-20 is below 1e-12 times" "$T/small.err" &&
       grep -q "no curve to write" "$T/small.err"' "--d below the curve's scale: named; no curve: exit 2"

# --- long paths: knots split over lines (<= 4096 bytes each); past the
# reader's 10000 control points a curve is left out, named
"$PY" -c 'import sys
n = int(sys.argv[1])
d = "M 0 0 " + " ".join("C %d 1 %d -1 %d 0" % (3 * i + 1, 3 * i + 2, 3 * i + 3) for i in range(n))
print("<svg xmlns=\"http://www.w3.org/2000/svg\"><path id=\"long\" d=\"%s\"/></svg>" % d)' 3333 > "$T/long.svg"
conv "$T/long.svg" --d 0.1 --out "$T/long.curves" 2>"$T/long.err"
check '[ $? -eq 0 ] && $OB list curves --curves "$T/long.curves" 2>&1 | grep -Eq "^long +svg +3333 +3 "' \
      "a path of 3333 cubics (10000 control points) reads back: $(head -c 300 "$T/long.err")"
sed 's/"\/>/ L 0 0"\/>/' "$T/long.svg" > "$T/long2.svg"
conv "$T/long2.svg" --d 0.1 --out "$T/long2.curves" 2>"$T/long2.err"
check '[ $? -eq 2 ] && grep -q "<path id=\"long\">: left out, .*10003 control points (the reader takes at most 10000" "$T/long2.err"' \
      "one segment more (10003 points): left out, named: $(cat "$T/long2.err")"

# --- bad input and options: exit 2, a message, no traceback ---
conv "$T/mix.svg" --out "$T/x.curves" 2>"$T/e1"
check '[ $? -eq 2 ] && grep -q -- "--d" "$T/e1"' "--d is required"
for bad in 0 0.5,0.5 abc inf; do
    conv "$T/mix.svg" --d "$bad" 2>"$T/e2" >/dev/null
    check '[ $? -eq 2 ] && grep -q -- "--d" "$T/e2" && no_trace "$T/e2"' "--d $bad refused: $(cat "$T/e2")"
done
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 1' > "$T/broken.svg"
conv "$T/broken.svg" --d 1 2>"$T/e3" >/dev/null
check '[ $? -eq 2 ] && grep -q "broken.svg" "$T/e3" && no_trace "$T/e3"' "malformed XML: exit 2, named: $(cat "$T/e3")"
conv "$T/nonexistent.svg" --d 1 2>"$T/e4" >/dev/null
check '[ $? -eq 2 ] && grep -q "nonexistent.svg: not a readable file" "$T/e4"' "a missing file: exit 2"
printf '<svg xmlns="http://www.w3.org/2000/svg"><text>only words</text></svg>' > "$T/empty.svg"
conv "$T/empty.svg" --d 1 2>"$T/e5" >/dev/null
check '[ $? -eq 2 ] && grep -q "no curve to write" "$T/e5" && grep -q "unsupported element (text)" "$T/e5"' "no paths: exit 2"
conv "$T/mix.svg" --d 1 --prefix "a b" 2>"$T/e6" >/dev/null
check '[ $? -eq 2 ] && grep -q -- "--prefix" "$T/e6"' "a bad --prefix refused"

# --- (2) a drawing made by hand ---
conv "$HAND" --d 1,-0.5 --out "$T/hand.curves" 2>"$T/hand.err"
check '[ $? -eq 0 ] && no_trace "$T/hand.err"' "hand.svg converts: $(cat "$T/hand.err")"
check '[ "$(ids "$T/hand.curves")" = "wave heart bracket big-arc wheel egg card zigzag " ]' \
      "hand.svg: 8 curves: $(ids "$T/hand.curves")"
check 'grep -q "<text id=\"label\">: unsupported element (text)" "$T/hand.err" &&
       [ "$(grep -c "unsupported\|unknown" "$T/hand.err")" -eq 1 ]' \
      "its label is reported; its editor metadata and defs are not"
"$PY" "$CHECK" "$HAND" "$T/hand.curves" --expect "wave:CCQQ,heart:CCCC,bracket:LLAL,big-arc:AA,wheel:AAAA,card:LALALALA,zigzag:LLLL" \
    > "$T/hand.chk" 2>&1
check '[ $? -eq 0 ]' "hand.svg geometry to 1e-9: $(cat "$T/hand.chk")"
check 'runs_ok "$T/hand.curves" "$T/handrun" 16' "run --methods tiller over hand.curves: 16 jobs ok"
# tiller (control polygon legs moved by d, the weights kept) is exact on lines
# and on circular arcs given as rational quadratics: the wheel (a circle of 4
# quarter arcs) and the zigzag come back within 1e-12
check '[ "$(rcols "$T/handrun/results.csv" curve max_err | awk -F: "\$1==\"wheel\"||\$1==\"zigzag\"{if (\$2 > 1e-12) b=1; n++} END{print (n==4 && !b)}")" = 1 ]' \
      "wheel and zigzag offsets are exact (max_err <= 1e-12)"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
