#!/bin/sh
# End-to-end differential test of measure's SVG reader against its
# documented reference, scripts/svg2curves.py (docs/export-measure.md,
# "Reading SVG"): every tests/data/svg/xml_*.svg (an attribute's name in
# another's value, '>' in a value before a transform, units, display:none,
# visibility, a nested <svg>'s viewport, comments, CDATA and entities,
# transforms of every form, near-straight and rotated arcs) read by both,
# the same pieces in the same order, control points equal to 1e-12 of the
# file's largest coordinate (tests/e2e/svgdiff.py); and hand.svg, a drawing
# program's sketch.  The C side is
# test_svg_read --dump, built beside the program (make builds it with the
# tests).  Also: what measure says of what it leaves out, and svg2curves.py's
# arcs (radius 0.5 to 1e300 and 1e-300, every flag) on the analytic circle.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(dirname "$OB")
[ "$(basename "$OB")" = offbench ] && [ -d "$BUILD/build" ] && [ "$BUILD" = "$ROOT" ] && BUILD=$ROOT/build
DUMP=$BUILD/tests/unit/test_svg_read

# --- measure notes what is not drawn ---------------------------------------------
"$OB" measure --curve line --d 0.3 --approx "$ROOT/tests/data/svg/xml_display_none.svg" >"$T/m.csv" 2>"$T/m.err"
check 'grep -q "display:none <path> (at line 6)" "$T/m.err" && grep -q "display:none <g> (at line 7)" "$T/m.err"' \
    "display:none: noted with the element and its line: $(head -c 400 "$T/m.err")"
printf '<svg>\n<path d="M0 0 L1 0" transform="translate(1)"/>\n<path d="M0 0 L1 0"' > "$T/bad.svg"
"$OB" measure --curve line --d 0.3 --approx "$T/bad.svg" >"$T/m.csv" 2>"$T/m.err"
check '[ $? -eq 2 ] && grep -q "bad.svg:3: not well-formed XML" "$T/m.err"' "XML cut short: exit 2, FILE:LINE: $(cat "$T/m.err")"
printf '<svg>\n<rect width="1em" height="2"/></svg>' > "$T/em.svg"
"$OB" measure --curve line --d 0.3 --approx "$T/em.svg" >"$T/m.csv" 2>"$T/m.err"
check '[ $? -eq 2 ] && grep -q "em.svg:2: <rect>: width: .*unit" "$T/m.err"' "a unit not read (em): exit 2, FILE:LINE and the attribute: $(cat "$T/m.err")"

# --- svg2curves.py's arcs (scripts/svgpath.py) on the analytic circle --------------
# from (0,0) to (1,0), radius R, every flag: sampled points of every piece
# within 1e-14 of the arc's size of the circle (distance written without the
# far centre), as tests/unit/test_svg_read.c checks the C reader's
/usr/bin/python3 - "$ROOT/scripts" >"$T/arcs.out" 2>&1 <<'PY'
import sys
from fractions import Fraction as F
from math import comb
sys.path.insert(0, sys.argv[1])
import svgpath
bad = 0
for R in (0.5, 0.7, 1e3, 1e8, 1e12, 1e16, 1e20, 1e300, 1e-3, 1e-300):
    for large in (False, True):
        for sweep in (False, True):
            pieces = svgpath.arc((0.0, 0.0), R, R, 0.0, large, sweep, (1.0, 0.0))
            Re = max(R, 0.5)
            sgn = 0 if R < 0.5 else (1 if large != sweep else -1)
            hr = (1 - (F(1, 2) / F(Re)) ** 2)  # (h / R)^2, exact
            worst = 0.0
            for _, p in pieces:
                for i in range(17):
                    t = F(i, 16)
                    n = len(p) - 1
                    b = [comb(n, k) * t ** k * (1 - t) ** (n - k) for k in range(n + 1)]
                    W = sum(bk * F(q[2]) for bk, q in zip(b, p))
                    x = sum(bk * F(q[2]) * F(q[0]) for bk, q in zip(b, p)) / W - F(1, 2)
                    y = sum(bk * F(q[2]) * F(q[1]) for bk, q in zip(b, p)) / W
                    # (|P - C|^2 - R^2) / 2R, C = (1/2, sgn h), h / R = sqrt(hr)
                    d = float((x * x + y * y - F(1, 4)) / (2 * F(Re))) - sgn * (float(hr) ** 0.5) * float(y)
                    worst = max(worst, abs(d))
            size = Re if (large or R < 0.5) else 1.0
            if not worst <= 1e-14 * size or pieces[0][1][0][:2] != (0.0, 0.0) or pieces[-1][1][-1][:2] != (1.0, 0.0):
                bad += 1
                print(f"R {R} large {large} sweep {sweep}: {len(pieces)} pieces, {worst:.3g} from the circle")
print(f"{bad} bad")
PY
check 'grep -q "^0 bad$" "$T/arcs.out"' "svgpath.arc on the analytic circle: $(head -c 600 "$T/arcs.out")"

# --- the C reader and svg2curves.py: the same pieces -------------------------------
if [ ! -x /usr/bin/python3 ]; then
    echo "e2e_svg_xml: no /usr/bin/python3: the comparison with svg2curves.py skipped"
    skipped=$((skipped + 1))
elif [ ! -x "$DUMP" ]; then
    echo "e2e_svg_xml: no $DUMP (make builds it with the tests): the comparison skipped"
    skipped=$((skipped + 1))
else
    for f in "$ROOT"/tests/data/svg/xml_*.svg "$ROOT/tests/data/svg/hand.svg"; do
        s=$(basename "$f" .svg)
        "$DUMP" --dump "$f" >"$T/$s.dump" 2>"$T/$s.derr"
        rc=$?
        /usr/bin/python3 "$ROOT/scripts/svg2curves.py" "$f" --d 0.1 --out "$T/$s.curves" 2>"$T/$s.cerr"
        pc=$?
        : >"$T/$s.diff"
        [ $rc -eq 0 ] && [ $pc -eq 0 ] && /usr/bin/python3 "$ROOT/tests/e2e/svgdiff.py" "$T/$s.dump" "$T/$s.curves" >"$T/$s.diff" 2>&1
        check '[ $? -eq 0 ] && [ $rc -eq 0 ] && [ $pc -eq 0 ]' \
            "$s.svg: the C reader (rc $rc: $(head -c 200 "$T/$s.derr")) and svg2curves.py (rc $pc: $(tail -n 1 "$T/$s.cerr")) differ: $(head -c 1500 "$T/$s.diff")"
    done
fi

e2e_done
