#!/bin/sh
# End-to-end tests of measure on pieces that are not cut where the base's
# segments join (issue 39 item 3: a CAD system cuts its offset where it
# likes).  A piece that runs over several base segments is cut where it
# crosses the normal line of the offset at each joint (an exact de
# Casteljau subdivision) and each part measured against its segment; the
# file's pieces and control points are counted as read.
# - a DXF LINE over a straight base of three segments: error 0, 1 piece,
#   2 control points;
# - a cubic base given as one segment and as the same curve cut at
#   t = 0.4 (a two-segment B-spline): each method's export, its links
#   removed, measures the same against both (to 1e-12 relative), the same
#   as the run's max_err, with the same pieces and control points;
# - on an offset with loops, a piece that crosses a joint's line away from
#   the offset's point there is refused; a per-piece hausdorff far above
#   hausdorff-whole is warned of;
# - a circle of four quarter arcs, its offset as three DXF ARCs of 120
#   degrees: error at round-off, also when they start at 45 degrees and the
#   last runs over the closed curve's start point.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

# the curves: 'two' is 'one' cut at t = 0.4 (de Casteljau, in Python)
/usr/bin/env python3 - "$T/j.curves" <<'PY'
import sys
P = [(0, 0), (1, 2), (3, 2), (4, 0)]
def split(P, t):
    L, R, Q = [P[0]], [P[-1]], P
    while len(Q) > 1:
        Q = [(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t) for a, b in zip(Q, Q[1:])]
        L.append(Q[0]); R.append(Q[-1])
    return L, R[::-1]
L, R = split(P, 0.4)
pts = lambda ps: ''.join('  point %.17g %.17g\n' % p for p in ps)
w = 0.70710678118654757
circle = [(1, 0, 1), (1, 1, w), (0, 1, 1), (-1, 1, w), (-1, 0, 1), (-1, -1, w), (0, -1, 1), (1, -1, w), (1, 0, 1)]
with open(sys.argv[1], 'w') as f:
    f.write('curve one\n  bezier 3\n' + pts(P) + '  offset -0.3\nend\n')
    f.write('curve two\n  bspline 3\n' + pts(L + R[1:]) + '  knots 0 0 0 0 0.4 0.4 0.4 1 1 1 1\n  offset -0.3\nend\n')
    f.write('curve line3\n  bspline 1\n' + pts([(0, 0), (1, 0), (2, 0), (3, 0)]) + '  knots 0 0 1 2 3 3\n  offset 0.5\nend\n')
    f.write('curve circle4\n  bspline 2\n' + ''.join('  point %.17g %.17g %.17g\n' % p for p in circle)
            + '  knots 0 0 0 1 1 2 2 3 3 4 4 4\n  offset 0.25\nend\n')
PY
C=$T/j.curves
dxf() { printf '0\nSECTION\n2\nENTITIES\n'; cat; printf '0\nENDSEC\n0\nEOF\n'; }
# col FILE METRIC COLUMN: a column of the row of METRIC
col() { awk -F, -v m="$2" -v c="$3" 'NR == 1 {for (i = 1; i <= NF; i++) k[$i] = i; next} $1 == m {print $k[c]}' "$1"; }

# --- a line over three segments
printf '0\nLINE\n10\n3\n20\n0.5\n11\n0\n21\n0.5\n' | dxf > "$T/line.dxf"
"$OB" measure --curves "$C" --curve line3 --d 0.5 --approx "$T/line.dxf" >"$T/l.csv" 2>"$T/l.err"
check '[ $? -eq 0 ]' "a LINE over three base segments is measured: $(cat "$T/l.err")"
check 'awk -v e="$(col "$T/l.csv" hausdorff max_err)" "BEGIN{exit !(e != \"\" && e + 0 <= 1e-15)}"' \
    "its hausdorff error is 0: $(col "$T/l.csv" hausdorff max_err)"
check '[ "$(col "$T/l.csv" hausdorff pieces)" = 1 ] && [ "$(col "$T/l.csv" hausdorff ctrl_points)" = 2 ] && [ "$(col "$T/l.csv" hausdorff piece)" = 0 ]' \
    "one piece of the file, 2 control points, the worst is piece 0"

# --- one cubic base, and the same cut in two; each method's export without its links
"$OB" run --curves "$C" --curve one --methods tiller,hoschek,sisl --tols 1e-3 --backend cpu --out "$T/r" \
    --export "$T/x" >/dev/null 2>"$T/r.err"
check '[ $? -eq 0 ]' "run --export on 'one': $(tail -n 1 "$T/r.err")"
for m in tiller hoschek sisl; do
    # 999 comments carry the links: without them measure matches by position
    awk 'NR % 2 == 1 {c = $0; next} c + 0 != 999 {print c; print}' "$T/x/one__d-0.3__${m}__tol0.001.dxf" > "$T/$m.dxf"
    "$OB" measure --curves "$C" --curve one --d -0.3 --approx "$T/$m.dxf" --metric hausdorff >"$T/one.csv" 2>"$T/e1"
    r1=$?
    "$OB" measure --curves "$C" --curve two --d -0.3 --approx "$T/$m.dxf" --metric hausdorff >"$T/two.csv" 2>"$T/e2"
    r2=$?
    check '[ $r1 -eq 0 ] && [ $r2 -eq 0 ]' "$m: measured against 'one' and 'two' ($(cat "$T/e1" "$T/e2"))"
    e1=$(col "$T/one.csv" hausdorff max_err) e2=$(col "$T/two.csv" hausdorff max_err)
    run=$(awk -F, -v m="$m" '$3 == m {print $10 " " $7 " " $8}' "$T/r/results.csv")
    check 'awk -v a="$e1" -v b="$e2" -v r="${run%% *}" "BEGIN{d = a - b; if (d < 0) d = -d; e = a - r; if (e < 0) e = -e; exit !(a > 0 && d <= 1e-12 * a && e <= 1e-12 * a)}"' \
        "$m: the same error over one segment ($e1) and over two ($e2), the run's ($run)"
    check '[ "$(col "$T/two.csv" hausdorff ctrl_points) $(col "$T/two.csv" hausdorff pieces)" = "$(echo "$run" | cut -d" " -f2-)" ]' \
        "$m: the run's control points and pieces ($(col "$T/two.csv" hausdorff ctrl_points) $(col "$T/two.csv" hausdorff pieces) vs $run)"
done

# --- a circle of four quarters; its offset (radius 0.75) as three ARCs of 120 degrees
arc() { printf '0\nARC\n10\n0\n20\n0\n40\n0.75\n50\n%s\n51\n%s\n' "$1" "$2"; }
{ arc 0 120; arc 120 240; arc 240 360; } | dxf > "$T/arcs.dxf"
"$OB" measure --curves "$C" --curve circle4 --d 0.25 --approx "$T/arcs.dxf" >"$T/c.csv" 2>"$T/c.err"
check '[ $? -eq 0 ]' "three ARCs over four quarters: measured ($(cat "$T/c.err"))"
check 'awk -v e="$(col "$T/c.csv" hausdorff max_err)" "BEGIN{exit !(e != \"\" && e + 0 <= 1e-12)}"' \
    "their hausdorff error is round-off: $(col "$T/c.csv" hausdorff max_err)"
check '[ "$(col "$T/c.csv" hausdorff pieces)" = 6 ] && [ "$(col "$T/c.csv" hausdorff ctrl_points)" = 13 ]' \
    "6 pieces as read (each ARC in two of 60 degrees), 13 control points: $(col "$T/c.csv" hausdorff pieces) $(col "$T/c.csv" hausdorff ctrl_points)"
# the same offset started at 45 degrees: the last ARC runs over the closed
# curve's start point, its pieces cut there too
{ arc 45 165; arc 165 285; arc 285 405; } | dxf > "$T/seam.dxf"
"$OB" measure --curves "$C" --curve circle4 --d 0.25 --approx "$T/seam.dxf" >"$T/s.csv" 2>"$T/s.err"
check '[ $? -eq 0 ] && awk -v e="$(col "$T/s.csv" hausdorff max_err)" "BEGIN{exit !(e != \"\" && e + 0 <= 1e-12)}" && [ "$(col "$T/s.csv" hausdorff pieces)" = 6 ]' \
    "ARCs over the closed curve's start: measured, hausdorff $(col "$T/s.csv" hausdorff max_err) ($(cat "$T/s.err"))"
# a LINE over the middle three segments' offset that stops short of its
# ends: cut and measured, then refused for the gaps it leaves (no CSV)
printf '0\nLINE\n10\n2.5\n20\n0.5\n11\n0.5\n21\n0.5\n' | dxf > "$T/l2.dxf"
"$OB" measure --curves "$C" --curve line3 --d 0.5 --approx "$T/l2.dxf" --approx "$T/line.dxf" >"$T/l2.csv" 2>"$T/l2.err"
check '[ $? -eq 2 ] && grep -q "l2.dxf does not cover the d = 0.5 offset of curve line3 once (2 gaps" "$T/l2.err" && [ ! -s "$T/l2.csv" ]' \
    "a LINE short of the offset's ends: its two gaps, exit 2, no CSV: $(cat "$T/l2.err")"

# four quarter ARCs on the quarters themselves: each end ties between the
# closing point and a joint (found by the OCCT example: refused before
# segments were taken cyclically)
{ arc 0 90; arc 90 180; arc 180 270; arc 270 360; } | dxf > "$T/ring4.dxf"
"$OB" measure --curves "$C" --curve circle4 --d 0.25 --approx "$T/ring4.dxf" >"$T/q.csv" 2>"$T/q.err"
check '[ $? -eq 0 ] && awk -v e="$(col "$T/q.csv" hausdorff max_err)" "BEGIN{exit !(e != \"\" && e + 0 <= 1e-12)}" && [ "$(col "$T/q.csv" hausdorff pieces)" = 4 ]' \
    "four quarter ARCs on the quarters: measured, hausdorff $(col "$T/q.csv" hausdorff max_err) ($(cat "$T/q.err"))"

# --- an offset with loops (liu2002_ex2 at d = 0.5), exports without links:
# a piece that crosses a joint's line away from the offset's point there
# (near a loop) is refused; pieces matched onto another branch of a loop
# give a per-piece hausdorff far from hausdorff-whole, and a warning says so
"$OB" run --curve liu2002_ex2 --methods zhao-rational,bspline-lsq --tols 1e-2,1e-5 --backend cpu \
    --out "$T/lr" --export "$T/lx" >/dev/null 2>"$T/lr.err"
check '[ $? -eq 0 ]' "run --export on liu2002_ex2: $(tail -n 1 "$T/lr.err")"
for j in zhao-rational__tol1e-05 bspline-lsq__tol0.01; do
    awk 'NR % 2 == 1 {c = $0; next} c + 0 != 999 {print c; print}' "$T/lx/liu2002_ex2__d0.5__$j.dxf" > "$T/$j.dxf"
done
"$OB" measure --curve liu2002_ex2 --d 0.5 --approx "$T/zhao-rational__tol1e-05.dxf" >"$T/z.csv" 2>"$T/z.err"
check '[ $? -eq 2 ] && grep -q "zhao-rational__tol1e-05.dxf:[0-9]*: piece 19 runs from base segment 1 to 2 and crosses the normal line where segments 1 and 2 join away from the offset.s point there" "$T/z.err"' \
    "a piece crossing a joint's line near a loop: refused, named: $(cat "$T/z.err")"
"$OB" measure --curve liu2002_ex2 --d 0.5 --approx "$T/bspline-lsq__tol0.01.dxf" >"$T/b.csv" 2>"$T/b.err"
check '[ $? -eq 0 ] && grep -q "warning: measure: .*bspline-lsq__tol0.01.dxf: hausdorff .* and hausdorff-whole .* differ by a factor .*: some pieces matched by projection may lie near another branch" "$T/b.err"' \
    "pieces on another branch: measured, with a warning: $(grep branch "$T/b.err")"
# an export of the same job measured by its links: no such warning
"$OB" measure --curve liu2002_ex2 --d 0.5 --approx "$T/lx/liu2002_ex2__d0.5__bspline-lsq__tol0.01.dxf" >/dev/null 2>"$T/b2.err"
check '[ $? -eq 0 ] && ! grep -q "another branch" "$T/b2.err"' "with its links: no branch warning"

e2e_done
