#!/bin/sh
# OpenCASCADE's trimmed offset measured by `measure --trimmed` (issue 50
# item 1: "a CAD offset with its loops trimmed ... OpenCASCADE where
# installed"): examples/occt/occt_trimmed.cpp offsets y = x^2 on [-1, 1]
# with BRepOffsetAPI_MakeOffset (an open wire, open result) and writes its
# edges as LINEs (a curved edge as 2000 chords, their chord error printed).
# - Always: `make occt-trimmed` without the headers fails naming the
#   Debian packages, building nothing.
# - With the headers (else skipped with the install line):
#   d = -1, the convex side (no loops): OCCT's edges are offset curves;
#   trimmed-hausdorff is their chord error, within 1e-6 of it relative:
#   OCCT's offset measures within its construction error.
#   d = +1 and 0.75, the concave side (a swallowtail): OCCT trims it but
#   gives straight edges; trimmed-hausdorff is what it is (5.5e-2 and
#   2.0e-2 here), and an independent brute force (tests/e2e/trim_brute.py
#   distance: dense point sets, k-d trees, no code shared) finds the same
#   to 1e-4 of the value plus its sampling's resolution.
#   Polylines with corners (--shape polyline, GeomAbs_Arc: OCCT fills a
#   convex corner with a circle arc): an L at d = +-0.25 and a Z (a right
#   and a left turn) at d = +-0.3 measure within OCCT's chord error (1e-6
#   of it relative, or 1e-12 where its edges are all lines), and the
#   brute force's distance agrees; --shape with another value: exit 2.
# Uses $OFFBENCH (set by make) or ./offbench; /usr/bin/python3 with numpy
# and scipy for the brute force (else those checks are skipped).
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory "$@"; }

mk OCCT_INC="$T/no-occt" OCCT_TRIMMED="$T/nobin" occt-trimmed >"$T/nohdr.out" 2>&1
check '[ $? -ne 0 ] && grep -q "libocct-modeling-algorithms-dev" "$T/nohdr.out" && [ ! -e "$T/nobin" ]' \
    "make occt-trimmed without the headers: fails naming the Debian packages: $(tr '\n' ' ' <"$T/nohdr.out")"
if [ -n "${E2E_OCCT_ABSENT:-}" ] || [ ! -f /usr/include/opencascade/BRepOffsetAPI_MakeOffset.hxx ] ||
    ! command -v g++ >/dev/null 2>&1; then
    echo "e2e_occt_trimmed: no OpenCASCADE offset algorithms (/usr/include/opencascade/BRepOffsetAPI_MakeOffset.hxx) or no g++" \
         "(apt-get install libocct-modeling-algorithms-dev g++, or OB_DEPS_OCCT=1 make deps): 15 checks skipped"
    skipped=$((skipped + 15))
    e2e_done
    exit $?
fi
W=$T/occt_trimmed
mk OCCT_TRIMMED="$W" occt-trimmed >"$T/build.out" 2>&1
check '[ $? -eq 0 ] && [ -x "$W" ]' "make occt-trimmed builds it: $(tail -n 5 "$T/build.out" | tr '\n' ' ')"
cat >"$T/p.curves" <<'CURVES'
curve parabola
  source y = x^2 on [-1, 1]
  bezier 2
  point -1 1
  point 0 -1
  point 1 1
  offset 1 -1 0.75
end
curve L
  source an L: a right turn at (0, 0)
  bspline 1
  knots 0 0 1 2 2
  point -1 0
  point 0 0
  point 0 -1
  offset 0.25 -0.25
end
curve Z
  source three lines: a right turn at (1, 0), a left turn at (1.5, -1)
  bspline 1
  knots 0 0 1 2 3 3
  point 0 0
  point 1 0
  point 1.5 -1
  point 2.5 -1
  offset 0.3 -0.3
end
CURVES
PY=/usr/bin/python3
havepy=0
"$PY" -c 'import numpy, scipy' 2>/dev/null && havepy=1
col() { awk -F, -v m="$2" '$1 == m {print $3}' "$1"; }

"$W" --d -1 --points "-1,1 0,-1 1,1" --out "$T/m1.dxf" >"$T/m1.out" 2>&1
ce=$(awk '$1 == "chord_error" {print $2}' "$T/m1.out")
"$OB" measure --curves "$T/p.curves" --curve parabola --d -1 --approx "$T/m1.dxf" --trimmed >"$T/m1.csv" 2>"$T/m1.err"
e=$(col "$T/m1.csv" trimmed-hausdorff)
check 'awk -v e="$e" -v c="$ce" "BEGIN{exit !(e != \"\" && c > 0 && e <= c * (1 + 1e-6) && e >= c * (1 - 1e-6))}"' \
    "d = -1 (no loops): OCCT's offset curves measure within their chord error: trimmed-hausdorff $e, chord error $ce: $(cat "$T/m1.out" "$T/m1.err")"

for d in 1 0.75; do
    "$W" --d $d --points "-1,1 0,-1 1,1" --out "$T/p$d.dxf" >"$T/p$d.out" 2>&1
    "$OB" measure --curves "$T/p.curves" --curve parabola --d $d --approx "$T/p$d.dxf" --trimmed >"$T/p$d.csv" 2>"$T/p$d.err"
    rc=$? e=$(col "$T/p$d.csv" trimmed-hausdorff)
    check '[ $rc -eq 0 ] && [ -n "$e" ]' "d = $d (a swallowtail): OCCT's trimmed offset measured: trimmed-hausdorff $e ($(tr '\n' ' ' <"$T/p$d.out"))"
    echo "  occt_trimmed, parabola d = $d: trimmed-hausdorff $e ($(head -n 1 "$T/p$d.out"))"
    if [ $havepy = 1 ]; then
        b=$("$PY" tests/e2e/trim_brute.py distance "$T/p.curves" parabola $d "$T/p$d.dxf" 2>&1)
        check 'awk -v e="$e" -v b="$b" "BEGIN{x = e - b; if (x < 0) x = -x; exit !(e != \"\" && x <= 1e-4 * e + 2e-5)}"' \
            "d = $d: the brute force finds the same distance: offbench $e, brute force $b"
    else
        skipped=$((skipped + 1))
    fi
done

# polylines with corners: OCCT's arcs on the convex side, its lines cut on the concave side
"$W" --shape zigzag --d 1 --points "0,0 1,0" --out "$T/x.dxf" >"$T/x.out" 2>&1
check '[ $? -eq 2 ] && grep -q -- "--shape" "$T/x.out"' "--shape zigzag: exit 2 naming it: $(cat "$T/x.out")"
for cd in "L 0.25 -1,0 0,0 0,-1" "L -0.25 -1,0 0,0 0,-1" "Z 0.3 0,0 1,0 1.5,-1 2.5,-1" "Z -0.3 0,0 1,0 1.5,-1 2.5,-1"; do
    set -- $cd
    id=$1 d=$2
    shift 2
    "$W" --shape polyline --d $d --points "$*" --out "$T/c.dxf" >"$T/c.out" 2>&1
    ce=$(awk '$1 == "chord_error" {print $2}' "$T/c.out")
    "$OB" measure --curves "$T/p.curves" --curve $id --d $d --approx "$T/c.dxf" --trimmed >"$T/c.csv" 2>"$T/c.err"
    e=$(col "$T/c.csv" trimmed-hausdorff)
    check 'awk -v e="$e" -v c="$ce" "BEGIN{x = e - c; if (x < 0) x = -x; exit !(e != \"\" && c != \"\" && x <= 1e-6 * c + 1e-12)}"' \
        "$id d = $d (corners): OCCT's offset measures within its chord error: trimmed-hausdorff $e, chord error $ce: $(cat "$T/c.out" "$T/c.err")"
    echo "  occt_trimmed --shape polyline, $id d = $d: trimmed-hausdorff $e, chord error $ce ($(head -n 1 "$T/c.out"))"
    if [ $havepy = 1 ]; then
        b=$("$PY" tests/e2e/trim_brute.py distance "$T/p.curves" $id $d "$T/c.dxf" 2>&1)
        check 'awk -v e="$e" -v b="$b" "BEGIN{x = e - b; if (x < 0) x = -x; exit !(e != \"\" && x <= 1e-4 * e + 2e-5)}"' \
            "$id d = $d: the brute force finds the same distance: offbench $e, brute force $b"
    else
        skipped=$((skipped + 1))
    fi
done
e2e_done
