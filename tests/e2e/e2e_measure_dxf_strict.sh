#!/bin/sh
# End-to-end tests of how measure reads a DXF file it must not guess at
# (issue 48 classes 7 and 12), on the offset of reference.curves' line (d =
# 0.3), with the files under tests/data/dxf_strict/:
# - a polyline segment of bulge 1e-16, 1e-20, 1e-200 or a denormal is the
#   chord (to round-off), read in bounded time (timeout 60, then KILL: measure catches TERM; a hang guard);
# - a file that yields no pieces: exit 2, the error lists the skipped
#   entities (FILE:LINE, what, why), 10 of them, then "and N more"; an
#   SVG's skipped elements (<use>, <text>) the same way;
# - a LINE at a constant z = 5: flattened, with a warning at its line; one
#   whose z goes from 0 to 1: skipped (its projection is another curve);
# - a 999 comment inside an entity is a comment, not its end;
# - a group repeated where the entity takes one, a NUL byte, a value of
#   more than 2049 characters (the longest DXF string), a hex float, inf,
#   nan: exit 2 at FILE:LINE.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
REF=$ROOT/datasets/reference.curves
D=$ROOT/tests/data/dxf_strict
m() { timeout -k 5 60 "$OB" measure --curves "$REF" --curve line --d 0.3 --approx "$1" >"$T/m.csv" 2>"$T/m.err"; }
val() { awkc '$c["metric"] == w {print $c["max_err"]}' w="$1" "$T/m.csv"; }
# expect FILE RC PATTERN WHAT: measure of FILE (in $D) exits RC, its stderr matches PATTERN (grep)
expect() {
    m "$D/$1"
    rc=$? want=$2 pat=$3
    check '[ $rc -eq $want ] && grep -q -- "$pat" "$T/m.err"' "$4: exit $rc (want $want), '$pat' not in: $(cat "$T/m.err")"
}
small() { awk -v a="$(val hausdorff-whole)" 'BEGIN{exit !(a != "" && a < 1e-15)}'; }

# --- near-straight bulges: the chord ----------------------------------------------
for b in 1e-16 1e-20 1e-200 4.9406564584124654e-324 -1e-16; do
    printf '0\nLWPOLYLINE\n90\n2\n10\n-0.13416407864998736\n20\n0.26832815729997472\n42\n%s\n10\n0.86583592135001264\n20\n0.76832815729997472\n' \
        "$b" > "$T/b.dxf"
    m "$T/b.dxf"
    rc=$?
    check '[ $rc -eq 0 ] && small' "bulge $b: exit $rc, hausdorff-whole '$(val hausdorff-whole)' (want < 1e-15): $(head -c 300 "$T/m.err")"
done

# --- no pieces: the skipped entities listed ------------------------------------
m "$D/no_pieces.dxf"
check '[ $? -eq 2 ] && grep -q "no_pieces.dxf: no pieces" "$T/m.err" &&
       grep -q "no_pieces.dxf:6: INSERT (" "$T/m.err" && grep -q "no_pieces.dxf:14: ARC off the XY plane (" "$T/m.err" &&
       grep -q "no_pieces.dxf:32: POLYLINE 3D or mesh (" "$T/m.err" && grep -q "no_pieces.dxf:80: TEXT (" "$T/m.err" &&
       ! grep -q "no_pieces.dxf:84: TEXT" "$T/m.err" && grep -q "it skipped 15 entities: .*and 5 more" "$T/m.err"' \
    "no pieces: the first 10 skipped listed, then 'and 5 more': $(cat "$T/m.err")"

# the same list from the SVG reader's notes (one funnel: ob_approx_note_skip)
expect use_only.svg 2 "use_only.svg: no pieces .* it skipped 2 entities: .*use_only.svg:2: <use> (.*use_only.svg:3: <text> (" \
    "an SVG of a <use> and a <text>: both listed"

# --- z --------------------------------------------------------------------------
m "$D/z_elevated.dxf"
check '[ $? -eq 0 ] && small && grep -q "warning: .*z_elevated.dxf:6: LINE at z = 5: flattened onto the XY plane" "$T/m.err"' \
    "LINE at z = 5: measured, with a warning: $(cat "$T/m.err")"
expect z_sloped.dxf 2 "z_sloped.dxf:6: LINE sloped in z (" "LINE from z 0 to 1: skipped, named"
# an ELLIPSE whose major axis climbs in z (31): skipped the same way
expect ellipse_tilted.dxf 2 "ellipse_tilted.dxf:6: ELLIPSE sloped in z (" "ELLIPSE with its axis out of the XY plane"

# --- 999 comments ----------------------------------------------------------------
m "$D/comment.dxf"
check '[ $? -eq 0 ] && small' "a 999 comment inside a LINE: read whole: $(cat "$T/m.err")"

# --- errors at FILE:LINE ----------------------------------------------------------
for c in "repeated.dxf:16: group 10 given twice in one LINE (first at line 8)" \
         "repeated_vertex.dxf:14: group 20 given twice for one vertex (first at line 12)" \
         "repeated_vertex_old.dxf:18: group 10 given twice for one vertex (first at line 14)" \
         "repeated_spline.dxf:10: group 71 given twice in one SPLINE (first at line 8)" \
         "repeated_spline_y.dxf:26: group 20 given twice for one control point (first at line 24)" \
         "nul.dxf:12: a NUL byte" \
         "long_value.dxf:12: a line of 2100 characters (at most 2049)" \
         "hex.dxf:12: group 11: '0x1p3' is not a decimal number" \
         "inf.dxf:12: group 11: 'inf' is not a decimal number" \
         "nan.dxf:26: group 10: 'nan' is not a decimal number"; do
    m "$D/${c%%:*}"
    rc=$?
    check '[ $rc -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -qF -- "$c" "$T/m.err"' "${c%%:*}: exit $rc, want '$c': $(cat "$T/m.err")"
done
e2e_done
