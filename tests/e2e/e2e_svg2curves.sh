#!/bin/sh
# End-to-end tests of scripts/svg2curves.py (SVG paths to .curves, docs/curves.md
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

NCHECKS=82
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
# svgcheck's reference, svgelements, takes 1 mm as 3.7795296 px, not CSS's
# 96/25.4 = 3.7795275590551185 (5.4e-7 relative): its geometry to 1e-4, and
# the end point (40, 10) mm exactly at 96 per inch
"$PY" "$CHECK" "$T/mm.svg" "$T/px.curves" --units px --tol 1e-4 > "$T/px.chk" 2>&1
pxrc=$?
pxend=$(awk '/^  point/{x = $2; y = $3} END{print (x - 151.18110236220472 < 1e-9 && 151.18110236220472 - x < 1e-9 && y + 37.795275590551181 < 1e-9 && -37.795275590551181 - y < 1e-9)}' "$T/px.curves")
check '[ $pxrc -eq 0 ] && grep -q "^  bezier 3" "$T/px.curves" && [ "$pxend" = 1 ]' \
      "--units px: 96 per inch, geometry to 1e-4 (svgelements' mm), end (151.18..., -37.79...): $(cat "$T/px.chk")"

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
check 'grep -q "<circle id=\"nil\">: zero size; left out" "$T/shapes.err"' "a circle of radius 0 is named"
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

# --- hostile files: each exits 2 with "FILE: what is wrong", no traceback, nothing written ---
# hostile NAME TEXT: converts $T/h/NAME (already written), expects exit 2 and
# "svg2curves: $T/h/NAME: ...TEXT" on stderr
mkdir -p "$T/h"
hostile() {
    conv "$T/h/$1" --d 1 --out "$T/h/out.curves" >/dev/null 2>"$T/h/err"; rc=$? pat="svg2curves: $T/h/$1: " txt=$2
    check '[ $rc -eq 2 ] && grep -qF -- "$pat" "$T/h/err" && grep -qF -- "$txt" "$T/h/err" && no_trace "$T/h/err" &&
           [ ! -e "$T/h/out.curves" ]' "$1: exit 2, '$txt' (rc $rc): $(head -c 400 "$T/h/err")"
    rm -f "$T/h/out.curves"
}
SVG='<svg xmlns="http://www.w3.org/2000/svg">'
OKP='<path id="ok" d="M 0 0 L 10 0"/>'   # a good path beside the bad: nothing may be lost silently
printf 'hello world\n' > "$T/h/notxml.svg";               hostile notxml.svg "not well-formed XML"
printf '%s<path d="M 0 0 L 1 1"/>' "$SVG" > "$T/h/trunc.svg"; hostile trunc.svg "not well-formed XML"
printf '%s<path d="M 0 0 L 1 1"' "$SVG" > "$T/h/trunc2.svg";  hostile trunc2.svg "not well-formed XML"
: > "$T/h/empty.svg";                                     hostile empty.svg "empty file"
printf ' \n\t\n' > "$T/h/blank.svg";                      hostile blank.svg "empty file"
printf '%s\377\376<path d="M 0 0 L 1 1"/></svg>' "$SVG" > "$T/h/bytes.svg"; hostile bytes.svg "not well-formed XML"
printf '%s<path id="p\351" d="M 0 0 L 1 1"/></svg>' "$SVG" > "$T/h/latin.svg"; hostile latin.svg "not well-formed XML"
printf '<?xml version="1.0" encoding="bogus"?>%s%s</svg>' "$SVG" "$OKP" > "$T/h/enc.svg"; hostile enc.svg "bogus"
printf '<html><body/></html>' > "$T/h/html.svg";          hostile html.svg "not an SVG document"
printf '%s%s<path id="p" d="M 0 0 L 1x 1e 2"/></svg>' "$SVG" "$OKP" > "$T/h/num.svg"
hostile num.svg '<path id="p">: attribute d: at character 10 ('"'x 1e 2'"'): expected a number (argument 2 of '"'L'"')'
printf '%s%s<path id="p" d="M 0 0 L 1 1 X 3 4 L 5 5"/></svg>' "$SVG" "$OKP" > "$T/h/cmd.svg"
hostile cmd.svg "<path id=\"p\">: attribute d: at character 13 ('X 3 4 L 5 5'): 'X' is not a path command"
printf '%s%s<path d="L 1 1"/></svg>' "$SVG" "$OKP" > "$T/h/nomove.svg"; hostile nomove.svg "<path> number 2 of the file: attribute d: at character 1"
printf '%s%s<path id="p" d="M 0 0 C 1 2 3 4 5"/></svg>' "$SVG" "$OKP" > "$T/h/short.svg"; hostile short.svg "at the end: expected a number (argument 6 of 'C')"
printf '%s%s<path id="p" d="M 0 0 A 5 5 0 2 1 9 9"/></svg>' "$SVG" "$OKP" > "$T/h/flag.svg"; hostile flag.svg "expected an arc flag 0 or 1"
printf '%s%s<path id="p" d="M 0 0 L 1e400 1"/></svg>' "$SVG" "$OKP" > "$T/h/inf.svg"; hostile inf.svg "the number 1e400 is out of range"
printf '%s%s<path id="p" d="M 0 0 A 1e999 5 0 0 1 9 9"/></svg>' "$SVG" "$OKP" > "$T/h/infarc.svg"; hostile infarc.svg "out of range"
printf '%s<path id="p" d="M 0 0 L 1e300 1"/></svg>' "$SVG" > "$T/h/huge.svg"; hostile huge.svg "beyond +-1e12"
printf '%s<g transform="rotate(abc)">%s</g></svg>' "$SVG" "$OKP" > "$T/h/tr.svg"; hostile tr.svg "<g> number 1 of the file: attribute transform"
printf '%s<path transform="scale(1e999)" d="M 0 0 L 1 1"/></svg>' "$SVG" > "$T/h/trbig.svg"; hostile trbig.svg "out of range"
printf '%s%s<polyline id="q" points="0 0 10 10 20"/></svg>' "$SVG" "$OKP" > "$T/h/odd.svg"; hostile odd.svg "an odd number of coordinates (5)"
printf '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 0 0">%s</svg>' "$OKP" > "$T/h/vb0.svg"; hostile vb0.svg "attribute viewBox: width and height must be positive"
printf '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10">%s</svg>' "$OKP" > "$T/h/vb3.svg"; hostile vb3.svg "expected 4 numbers"
printf '%s<path id="z" d="M 5 5 A 0 0 0 0 1 5 5"/></svg>' "$SVG" > "$T/h/arc0.svg"; hostile arc0.svg "no curve to write"
hostile missing.svg "not a readable file"
mkdir -p "$T/h/dir.svg";                                   hostile dir.svg "not a readable file"
nm=$(printf 'n\377.svg'); printf '%s<path d="M 0 0 L 1x"/></svg>' "$SVG" > "$T/h/$nm"; hostile "$nm" "attribute d"
# an arc with a zero radius to another point is a line (SVG 1.1, F.6.2), not an error
printf '%s<path id="r0" d="M 0 0 A 0 5 0 0 1 10 0"/></svg>' "$SVG" > "$T/h/arcline.svg"
conv "$T/h/arcline.svg" --d 1 --out "$T/h/arcline.curves" 2>"$T/h/err"
check '[ $? -eq 0 ] && no_trace "$T/h/err" && grep -q "^  bezier 1" "$T/h/arcline.curves"' "an arc of radius 0: a line, exit 0: $(cat "$T/h/err")"
# nesting deeper than Python's recursion limit: no traceback either way
"$PY" -c 'print("<svg xmlns=\"http://www.w3.org/2000/svg\">" + "<g>" * 5000 + "<path d=\"M 0 0 L 1 1\"/>" + "</g>" * 5000 + "</svg>")' > "$T/h/deep.svg"
conv "$T/h/deep.svg" --d 1 --out "$T/h/deep.curves" >/dev/null 2>"$T/h/err"; rc=$?
check '{ [ $rc -eq 0 ] || { [ $rc -eq 2 ] && grep -q "deep.svg: " "$T/h/err"; }; } && no_trace "$T/h/err"' "5000 nested groups: no traceback (rc $rc): $(head -c 300 "$T/h/err")"
# a well-formed file still converts with the syntax checked (commas, implied commands, packed flags)
printf '%s<path id="w" d="M0,0 10,0,L10,10a5 5 0 0010 10 z" transform="translate(1) rotate(30 0 0),scale(2)"/><polygon id="g" points="0,0 5,0 5 5"/></svg>' "$SVG" > "$T/h/good.svg"
conv "$T/h/good.svg" --d 1 --out "$T/h/good.curves" 2>"$T/h/err"
check '[ $? -eq 0 ] && [ "$(ids "$T/h/good.curves")" = "w g " ]' "well-formed compact syntax converts: $(cat "$T/h/err")"

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
