#!/bin/sh
# End-to-end tests of examples/fit_svg.py (docs/cad-example.md): a drawing
# (tests/data/svg/hand.svg) converted, three methods fitted through the
# command line, plotted with matplotlib's Agg backend, also without a
# display: a PNG and an SVG file, one panel per method whose title counts
# the control points the run reports; a method that skips a curve says so;
# an unknown method and a missing drawing exit 2 with the step's message.
# Needs /usr/bin/python3 with matplotlib (Debian's python3-matplotlib;
# svg2curves.py needs only the standard library); without it every check
# counts as skipped.  Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
PY=/usr/bin/python3
FIT=examples/fit_svg.py
HAND=tests/data/svg/hand.svg

NCHECKS=12
if ! "$PY" -c 'import matplotlib' >/dev/null 2>&1; then
    echo "e2e_fit_svg: $PY cannot import matplotlib (apt-get install python3-matplotlib): skipped"
    echo "0 passed, 0 failed, $NCHECKS skipped"
    exit 0
fi
fit() { env -u DISPLAY -u MPLBACKEND "$PY" "$FIT" "$@" --offbench "$OB"; }
is_png() { [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }
svg_text() { "$PY" -c 'import sys, xml.etree.ElementTree as E
print("\n".join("".join(e.itertext()) for e in E.parse(sys.argv[1]).iter() if e.tag.endswith("}text")))' "$1"; }

# --- the defaults, a PNG, the run kept ---
fit "$HAND" --d 2 --out "$T/a.png" --keep "$T/k" >"$T/a.out" 2>"$T/a.err"
check '[ $? -eq 0 ] && is_png "$T/a.png"' "fit_svg.py DRAWING --d 2: a PNG file ($(tail -n 3 "$T/a.err" | tr '\n' ' '))"
check '[ "$(grep -c "^fit_svg.py: \(tiller\|bspline-lsq\|sisl\): 8 curves" "$T/a.out")" -eq 3 ]' \
    "one line per default method, every curve: $(cat "$T/a.out" | tr '\n' ' ')"
check 'grep -q "<text id=\"label\">: unsupported element" "$T/a.err"' "what svg2curves.py left out is passed on"
# the control points printed are the run's, summed over the curves
n=$(awkc 'FNR>1 && $c["method"]=="tiller" {s += $c["ctrl_points"]} END {print s}' "$T/k/run/results.csv")
check '[ -n "$n" ] && grep -q "^fit_svg.py: tiller: 8 curves, $n control points" "$T/a.out"' "tiller's control points are the run's ($n)"
check '[ -s "$T/k/drawing.curves" ] && [ -s "$T/k/export/index.csv" ]' "--keep keeps the curves, the run and the export"

# --- three methods chosen, some curves, an SVG file ---
fit "$HAND" --d -1 --tol 1e-3 --methods tiller,ahn,lee --curve wave,wheel --out "$T/b.svg" >"$T/b.out" 2>"$T/b.err"
check '[ $? -eq 0 ] && [ "$("$PY" -c "import sys, xml.etree.ElementTree as E; print(E.parse(sys.argv[1]).getroot().tag)" "$T/b.svg")" = "{http://www.w3.org/2000/svg}svg" ]' \
    "--out FILE.svg: an SVG document ($(tail -n 2 "$T/b.err" | tr '\n' ' '))"
svg_text "$T/b.svg" >"$T/b.txt"
check 'grep -q "^tiller: [0-9]* control points" "$T/b.txt" && grep -q "^ahn: " "$T/b.txt" && grep -q "^lee: " "$T/b.txt"' \
    "a panel per method, titled with its control points: $(grep "control points" "$T/b.txt" | tr '\n' ' ')"
check 'grep -q "(tol 1e-3)" "$T/b.txt" && grep -q "hand.svg: offsets at d = -1" "$T/b.txt"' "the tolerance and d in the titles"
check 'grep -q "^fit_svg.py: ahn: 2 curves, .*(wheel: skip)" "$T/b.out" && grep -q "wheel: skip" "$T/b.txt"' \
    "ahn skips the rational wheel, and says so in the line and the panel: $(grep ahn "$T/b.out")"

# --- errors ---
fit "$HAND" --d 2 --methods tiller,nosuch,sisl --out "$T/c.png" >"$T/c.out" 2>"$T/c.err"
check '[ $? -eq 2 ] && grep -q "unknown method .nosuch." "$T/c.err" && [ ! -e "$T/c.png" ]' \
    "an unknown method: exit 2 with offbench's message, no file: $(tail -n 1 "$T/c.err")"
fit "$T/none.svg" --d 2 --out "$T/d.png" >"$T/d.out" 2>"$T/d.err"
check '[ $? -eq 2 ] && grep -q "none.svg" "$T/d.err" && ! grep -q Traceback "$T/d.err"' \
    "a missing drawing: exit 2 naming it: $(tail -n 1 "$T/d.err")"
check '[ -z "$(ls -d /tmp/fit_svg.* 2>/dev/null | while read -r d; do [ "$d" -nt "$T/a.png" ] && echo "$d"; done)" ]' \
    "no scratch directory left behind"
e2e_done
