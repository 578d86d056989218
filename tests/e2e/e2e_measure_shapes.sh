#!/bin/sh
# End-to-end tests of measure reading SVG's basic shapes (issue 39 item 3:
# svg2curves.py reads <circle>, <ellipse> and <rect>, so measure does too),
# each the path SVG 2 gives it, on exact offsets:
# - a <circle> and an <ellipse> of equal radii (or rx alone) on the offset
#   of a circle of four quarter arcs: round-off; an <ellipse> 0.05 wider
#   than that offset: hausdorff 0.05, the gap between them on the x axis;
# - a <rect> with rounded corners on the offset of a rounded rectangle:
#   round-off, 8 pieces, 13 control points; ry alone stands for rx;
# - a size of 0 is skipped and named; a negative or malformed one: exit 2
#   naming FILE:LINE and the attribute.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

w=0.70710678118654757
cat > "$T/s.curves" <<CURVES
curve circle4
  bspline 2
  point 1 0 1
  point 1 1 $w
  point 0 1 1
  point -1 1 $w
  point -1 0 1
  point -1 -1 $w
  point 0 -1 1
  point 1 -1 $w
  point 1 0 1
  knots 0 0 0 1 1 2 2 3 3 4 4 4
  offset 0.25
end
curve rrect
  bspline 2
  point 0.5 0 1
  point 2 0 1
  point 3.5 0 1
  point 4 0 $w
  point 4 0.5 1
  point 4 1 1
  point 4 1.5 1
  point 4 2 $w
  point 3.5 2 1
  point 2 2 1
  point 0.5 2 1
  point 0 2 $w
  point 0 1.5 1
  point 0 1 1
  point 0 0.5 1
  point 0 0 $w
  point 0.5 0 1
  knots 0 0 0 1 1 2 2 3 3 4 4 5 5 6 6 7 7 8 8 8
  offset -0.25
end
CURVES
# svg BODY: an SVG whose y axis points up (scale(1,-1) undoes the reader's flip)
svg() { printf '<svg xmlns="http://www.w3.org/2000/svg">\n<g transform="scale(1,-1)">\n%s\n</g></svg>\n' "$1"; }
m() { "$OB" measure --curves "$T/s.curves" --curve "$2" --d "$3" --approx "$1" >"$T/m.csv" 2>"$T/m.err"; }
val() { awkc '$c["metric"] == w {print $c[k]}' w=hausdorff k="$1" "$T/m.csv"; }
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN{d = a - b; if (d < 0) d = -d; exit !(a != "" && d <= t)}'; }

for shape in '<circle cx="0" cy="0" r="0.75"/>' '<ellipse rx="0.75" ry="0.75"/>' '<ellipse rx="0.75"/>'; do
    svg "$shape" > "$T/c.svg"
    m "$T/c.svg" circle4 0.25
    check '[ $? -eq 0 ] && near "$(val max_err)" 0 1e-14 && [ "$(val pieces)" = 4 ] && [ "$(val ctrl_points)" = 9 ]' \
        "$shape on the offset circle: hausdorff $(val max_err), $(val pieces) pieces, $(val ctrl_points) points $(cat "$T/m.err")"
done
svg '<ellipse rx="0.8" ry="0.75"/>' > "$T/e.svg"
m "$T/e.svg" circle4 0.25
check '[ $? -eq 0 ] && near "$(val max_err)" 0.05 1e-12' "an ellipse 0.05 wider: hausdorff $(val max_err) $(cat "$T/m.err")"

for shape in '<rect x="-0.25" y="-0.25" width="4.5" height="2.5" rx="0.75"/>' \
             '<rect x="-0.25" y="-0.25" width="4.5" height="2.5" ry="0.75"/>'; do
    svg "$shape" > "$T/r.svg"
    m "$T/r.svg" rrect -0.25
    check '[ $? -eq 0 ] && near "$(val max_err)" 0 1e-14 && [ "$(val pieces)" = 8 ] && [ "$(val ctrl_points)" = 13 ]' \
        "$shape on the offset of a rounded rectangle: hausdorff $(val max_err), $(val pieces) pieces, $(val ctrl_points) points $(cat "$T/m.err")"
done
# ry="9" is clamped to half the height, 1.25: corners of radii 0.75 x 1.25
# and no vertical sides (6 pieces), not the offset
svg '<rect x="-0.25" y="-0.25" width="4.5" height="2.5" rx="0.75" ry="9"/>' > "$T/r1.svg"
m "$T/r1.svg" rrect -0.25
check '[ $? -eq 0 ] && [ "$(val pieces)" = 6 ] && awk -v e="$(val max_err)" "BEGIN{exit !(e > 0.05)}"' \
    "ry clamped to half the height: $(val pieces) pieces, hausdorff $(val max_err)"
svg '<rect x="-0.25" y="-0.25" width="4.5" height="2.5" rx="1.25"/>' > "$T/r2.svg"
m "$T/r2.svg" rrect -0.25
check '[ $? -eq 0 ] && awk -v e="$(val max_err)" "BEGIN{exit !(e > 0.1)}"' "corners of radius 1.25 are not the offset: hausdorff $(val max_err)"

svg '<circle r="0"/>
<rect width="0" height="3"/>
<circle r="0.75"/>' > "$T/z.svg"
m "$T/z.svg" circle4 0.25
check '[ $? -eq 0 ] && grep -q "skipped 2 entities .*1 zero-size <circle> (at line 3), 1 zero-size <rect> (at line 4)" "$T/m.err"' \
    "sizes of 0 are skipped and named: $(cat "$T/m.err")"
svg '<rect width="-1" height="3"/>' > "$T/n.svg"
m "$T/n.svg" circle4 0.25
check '[ $? -eq 2 ] && grep -q "n.svg:3: <rect>: width: negative" "$T/m.err" && [ ! -s "$T/m.csv" ]' \
    "a negative width: exit 2 naming it: $(cat "$T/m.err")"
svg '<circle r="x"/>' > "$T/b.svg"
m "$T/b.svg" circle4 0.25
check '[ $? -eq 2 ] && grep -q "b.svg:3: <circle>: r" "$T/m.err"' "a malformed radius: exit 2 naming it: $(cat "$T/m.err")"

e2e_done
