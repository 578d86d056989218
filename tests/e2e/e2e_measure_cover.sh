#!/bin/sh
# End-to-end tests of what `measure` requires of an approximation (issue 36,
# README "measure"): the pieces must cover the offset once.
# - Exports of several methods pass and give the run's max_err; the
#   hausdorff-whole row (the whole approximation against the whole offset)
#   is there, at most the per-piece hausdorff, and alone with
#   --metric hausdorff-whole.
# - Variants of an export (.curves with and without its base links, JSON):
#   one piece of many, one piece 50 times, a piece missing in the middle, a
#   piece twice, an overlap (a link edited): exit 2, stdout empty, each
#   problem as FILE:LINE with the piece and the base range, then a count;
#   two pieces swapped, the list reversed: exit 0, a warning, the same rows.
# - Pieces of another curve: exit 2.
# - param does not apply to a file without links.
# - Hand-written DXF files with LINE, ARC and LWPOLYLINE (bulges) on exact
#   offsets (a circle, a line): read, measured to round-off; entities that
#   are no pieces named on stderr; an ARC short of the offset: a gap.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
REF=$(cd "$(dirname "$0")/../.." && pwd)/datasets/reference.curves

"$OB" run --curve liu2002_ex1,liu2002_ex2 --methods tiller,lee,bspline-lsq,hoschek --tols 1e-3 --backend cpu \
    --out "$T/r" --export "$T/x" 2>"$T/err"
check '[ $? -eq 0 ]' "run --export: exit 0 ($(tail -n 2 "$T/err"))"

# m FILE CURVE D [ARGS]: measure's CSV in $T/m.csv, stderr in $T/m.err; the exit status
m() { f=$1 c=$2 d=$3; shift 3
      "$OB" measure --curve "$c" --d "$d" --approx "$f" "$@" >"$T/m.csv" 2>"$T/m.err"; }
# the max_err of a metric's row in $T/m.csv
val() { awkc '$c["metric"] == w {print $c["max_err"]}' w="$1" "$T/m.csv"; }

# --- every export passes and gives the run's number --------------------------
n=0
csvcols "$T/x/index.csv" curve d method max_err stem | tail -n +2 > "$T/rows"
while IFS=, read -r c d meth e stem; do
    [ -n "$stem" ] || continue
    n=$((n + 1))
    m "$T/x/$stem.json" "$c" "$d"
    check '[ $? -eq 0 ] && [ "$(val hausdorff)" = "$e" ] && ! grep -q warning "$T/m.err"' \
        "$stem: exit 0, hausdorff $(val hausdorff) (the run $e), no warning: $(head -c 300 "$T/m.err")"
    w=$(val hausdorff-whole)
    check 'awk -v w="$w" -v h="$e" "BEGIN{exit !(w != \"\" && w > 0 && w <= h * (1 + 1e-12))}"' \
        "$stem: hausdorff-whole $w, at most the per-piece $e"
    check '[ "$(tail -n 1 "$T/m.csv" | cut -d, -f1)" = hausdorff-whole ] && tail -n 1 "$T/m.csv" | grep -q "\"the farthest point of the"' \
        "$stem: the last row is hausdorff-whole, saying which side"
done < "$T/rows"
check '[ $n -eq 12 ]' "$n exports measured (12 expected: liu2002_ex1 at d = +-1, liu2002_ex2 at 0.5, 4 methods)"

S=liu2002_ex1__d-1__tiller__tol0.001
X=$T/x/$S.curves
N=$(grep -c '^curve ' "$X")
check '[ $N -ge 10 ]' "$S: $N pieces"
m "$X" liu2002_ex1 -1 --metric hausdorff
check '[ $? -eq 0 ] && [ $(wc -l < "$T/m.csv") -eq 3 ] && [ -n "$(val hausdorff)" ] && [ -n "$(val hausdorff-whole)" ]' \
    "--metric hausdorff: its row and hausdorff-whole's"
m "$X" liu2002_ex1 -1 --metric hausdorff-whole
check '[ $? -eq 0 ] && [ $(wc -l < "$T/m.csv") -eq 2 ] && [ -n "$(val hausdorff-whole)" ]' \
    "--metric hausdorff-whole: that row alone"
m "$X" liu2002_ex1 -1
cp "$T/m.csv" "$T/full.csv"

# pick FILE K...: the .curves file's pieces K... in that order (ids renamed:
# the format wants them unique); the line of each block in $T/lines
pick() { f=$1; shift
         awk -v want="$*" 'BEGIN{n=split(want, w, " ")}
             /^curve /{k++} k>0{b[k]=b[k] $0 "\n"}
             END{for(i=1;i<=n;i++){s=b[w[i]+1]; sub(/^curve [^\n]*/, "curve v" i, s); printf "%s", s}}' "$f"; }
seq0() { awk -v a="$1" -v b="$2" 'BEGIN{for(i=a;i<=b;i++) printf "%d ", i}'; }
M=$((N / 2))
for links in with without; do
    if [ $links = with ]; then cp "$X" "$T/v.curves"; else grep -v '^  source' "$X" > "$T/v.curves"; fi
    V=$T/v.curves

    pick "$V" $M > "$T/one.curves"
    m "$T/one.curves" liu2002_ex1 -1
    check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -q "one.curves:1: piece 0: gap: nothing covers base segment 0 from t = 0 to" "$T/m.err" &&
           grep -q "one.curves:1: piece 0: gap: .* to t = 1 (after this piece, the last on the base)" "$T/m.err" &&
           grep -q "does not cover the d = -1 offset of curve liu2002_ex1 once (2 gaps, 0 overlaps, 0 duplicates)" "$T/m.err"' \
        "$links links, one piece of $N: exit 2, two gaps: $(cat "$T/m.err")"

    pick "$V" $(for i in $(seq0 1 50); do printf '%d ' $M; done) > "$T/fifty.curves"
    m "$T/fifty.curves" liu2002_ex1 -1
    check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -q "fifty.curves:[0-9]*: piece 1: duplicate of piece 0 (line 1)" "$T/m.err" &&
           grep -q "fifty.curves: and 46 more like these" "$T/m.err" && grep -q "(2 gaps, 0 overlaps, 49 duplicates)" "$T/m.err" &&
           [ $(grep -c "fifty.curves:[0-9]*: piece" "$T/m.err") -eq 5 ]' \
        "$links links, one piece 50 times: exit 2, the first 5 problems and a count: $(head -c 600 "$T/m.err")"

    pick "$V" $(seq0 0 $((M - 1))) $(seq0 $((M + 1)) $((N - 1))) > "$T/gap.curves"
    line=$(grep -n '^curve v'$((M + 1))'$' "$T/gap.curves" | cut -d: -f1)
    m "$T/gap.curves" liu2002_ex1 -1
    check '[ $? -eq 2 ] && grep -q "gap.curves:$line: piece $M: gap: nothing covers base segment 0 from t = .* (after piece $((M - 1)), line [0-9]*)" "$T/m.err" &&
           grep -q "(1 gaps, 0 overlaps, 0 duplicates)" "$T/m.err"' \
        "$links links, piece $M missing: exit 2, one gap at line $line: $(cat "$T/m.err")"
    if [ $links = with ]; then  # the gap is the missing piece's span, exactly
        span=$(grep "piece $M of" "$X" | sed 's/.* span \([^ ]*\) \([^ ]*\) fit.*/from t = \1 to t = \2/')
        check 'grep -q "$span (after" "$T/m.err"' "the gap is piece $M's span ($span): $(cat "$T/m.err")"
    fi

    pick "$V" $(seq0 0 $((N - 1))) $M > "$T/twice.curves"
    m "$T/twice.curves" liu2002_ex1 -1
    check '[ $? -eq 2 ] && grep -q "twice.curves:[0-9]*: piece $N: duplicate of piece $M" "$T/m.err" &&
           grep -q "warning: .*twice.curves:[0-9]*: piece $N: out of order" "$T/m.err"' \
        "$links links, piece $M again at the end: exit 2, a duplicate: $(cat "$T/m.err")"

    pick "$V" $(seq0 0 $((N - 1))) > "$T/all.curves"
    m "$T/all.curves" liu2002_ex1 -1
    cut -d, -f1-3 "$T/m.csv" > "$T/f3"
    pick "$V" $(seq0 0 $((M - 1))) $((M + 1)) $M $(seq0 $((M + 2)) $((N - 1))) > "$T/swap.curves"
    m "$T/swap.curves" liu2002_ex1 -1
    check '[ $? -eq 0 ] && grep -q "warning: .*swap.curves:[0-9]*: piece $((M + 1)): out of order: it lies before piece $M" "$T/m.err" &&
           grep -q "1 of its $N pieces come after a piece that lies after them on the base" "$T/m.err"' \
        "$links links, two pieces swapped: exit 0 with a warning: $(cat "$T/m.err")"
    # the same errors (the piece numbers of the swapped pair aside)
    check 'cut -d, -f1-3 "$T/m.csv" | cmp -s - "$T/f3"' "$links links, two pieces swapped: the same errors as in order"

    pick "$V" $(awk -v n=$N 'BEGIN{for(i=n-1;i>=0;i--) printf "%d ", i}') > "$T/rev.curves"
    m "$T/rev.curves" liu2002_ex1 -1
    check '[ $? -eq 0 ] && grep -q "$((N - 1)) of its $N pieces come after" "$T/m.err" && cut -d, -f1-3 "$T/m.csv" | cmp -s - "$T/f3"' \
        "$links links, the list reversed: exit 0, the same errors: $(tail -n 2 "$T/m.err")"
done

# an overlap: piece M's span reaches to the end of piece M + 1's
b2=$(grep "piece $((M + 1)) of" "$X" | sed 's/.* span [^ ]* \([^ ]*\) fit.*/\1/')
a=$(grep "piece $M of" "$X" | sed 's/.* span \([^ ]*\) .*/\1/')
awk -v m="piece $M of" -v a="$a" -v b2="$b2" 'index($0, m){sub(/span [^ ]* [^ ]* fit/, "span " a " " b2 " fit")} {print}' \
    "$X" > "$T/over.curves"
m "$T/over.curves" liu2002_ex1 -1
check '[ $? -eq 2 ] && grep -q "over.curves:[0-9]*: piece $((M + 1)): overlap: base segment 0 from t = .* to t = $b2 is covered by piece $M" "$T/m.err"' \
    "a link edited into an overlap: exit 2: $(cat "$T/m.err")"

# the JSON: a piece taken out, and param without links
python3 - "$T/x/$S.json" "$T/gap.json" "$M" <<'PYEOF'
import json, sys
js = json.load(open(sys.argv[1]))
del js['pieces'][int(sys.argv[3])]
json.dump(js, open(sys.argv[2], 'w'), indent=1)
PYEOF
m "$T/gap.json" liu2002_ex1 -1
check '[ $? -eq 2 ] && grep -q "gap.json:[0-9]*: piece $M: gap: nothing covers base segment 0" "$T/m.err"' \
    "JSON without piece $M: exit 2: $(cat "$T/m.err")"
grep -v '^  source' "$X" > "$T/own.curves"
m "$T/own.curves" liu2002_ex1 -1 --metric param
check '[ $? -eq 0 ] && grep -q "^param,n/a,,,,,\".*no link" "$T/m.csv"' "param without links: n/a ($(cat "$T/m.csv"))"
m "$X" liu2002_ex1 -1 --metric param
check '[ $? -eq 0 ] && grep -q "^param,ok," "$T/m.csv"' "param with the links: ok"

# pieces of another curve: liu2002_ex2's, without links, against liu2002_ex1
grep -v '^  source' "$T/x/liu2002_ex2__d0.5__tiller__tol0.001.curves" > "$T/other.curves"
m "$T/other.curves" liu2002_ex1 0.5
check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ]' "liu2002_ex2's pieces against liu2002_ex1: exit 2: $(tail -n 1 "$T/m.err")"

# --- hand-written DXF -----------------------------------------------------------
# the quarter circle of reference.curves (radius 1, d = 0.5: radius 0.5; d =
# -0.5: radius 1.5), as an ARC, and as a polyline of two 45-degree bulge arcs
dxf() { printf '0\nSECTION\n2\nENTITIES\n'; cat; printf '0\nENDSEC\n0\nEOF\n'; }
printf '0\nTEXT\n1\nnote\n0\nARC\n8\n0\n10\n0\n20\n0\n40\n0.5\n50\n0\n51\n90\n0\nTEXT\n1\nmore\n' | dxf > "$T/arc.dxf"
m "$T/arc.dxf" arc_quarter 0.5 --curves "$REF"
check '[ $? -eq 0 ] && awk -v a="$(val hausdorff)" -v b="$(val hausdorff-whole)" "BEGIN{exit !(a < 1e-15 && b < 1e-15)}" &&
       grep -q "warning: measure: .*arc.dxf: skipped 2 entities that are no pieces measure reads: 2 TEXT (the first at line 6)" "$T/m.err"' \
    "ARC on the offset: hausdorff $(val hausdorff), whole $(val hausdorff-whole); TEXT named: $(cat "$T/m.err")"
b=$(awk 'BEGIN{printf "%.17g", sin(atan2(1, 1) / 4) / cos(atan2(1, 1) / 4)}')
r=$(awk 'BEGIN{printf "%.17g", 1.5 * sqrt(0.5)}')
printf '0\nLWPOLYLINE\n90\n3\n70\n0\n10\n1.5\n20\n0\n42\n%s\n10\n%s\n20\n%s\n42\n%s\n10\n0\n20\n1.5\n' "$b" "$r" "$r" "$b" | dxf > "$T/poly.dxf"
m "$T/poly.dxf" arc_quarter -0.5 --curves "$REF"
check '[ $? -eq 0 ] && awk -v a="$(val hausdorff)" -v b="$(val hausdorff-whole)" "BEGIN{exit !(a < 1e-14 && b < 1e-14)}" && ! grep -q warning "$T/m.err"' \
    "LWPOLYLINE of two bulge arcs on the offset: hausdorff $(val hausdorff), whole $(val hausdorff-whole): $(cat "$T/m.err")"
cp "$T/m.csv" "$T/lw.csv"
# the same arcs as an old-style POLYLINE: its header's point (10/20, the
# elevation) is no vertex, each VERTEX has its bulge, SEQEND ends it; then
# the rows of the LWPOLYLINE
printf '0\nPOLYLINE\n8\n0\n66\n1\n10\n0\n20\n0\n30\n0\n70\n0\n0\nVERTEX\n8\n0\n10\n1.5\n20\n0\n42\n%s\n0\nVERTEX\n10\n%s\n20\n%s\n42\n%s\n70\n0\n0\nVERTEX\n10\n0\n20\n1.5\n0\nSEQEND\n8\n0\n' \
    "$b" "$r" "$r" "$b" | dxf > "$T/oldpoly.dxf"
m "$T/oldpoly.dxf" arc_quarter -0.5 --curves "$REF"
check '[ $? -eq 0 ] && [ "$(dropcols "$T/m.csv" file)" = "$(dropcols "$T/lw.csv" file)" ] && ! grep -q "warning" "$T/m.err"' \
    "POLYLINE/VERTEX/SEQEND read as the LWPOLYLINE: $(cat "$T/m.csv" "$T/m.err")"
check '[ "$(csvcols "$T/m.csv" pieces ctrl_points | sed -n 2p)" = "2,5" ]' \
    "POLYLINE: 2 pieces, 5 control points ($(csvcols "$T/m.csv" pieces ctrl_points | sed -n 2p))"
# closed (flag 1): a square of 4 LINE segments around the origin is no
# offset of arc_quarter: exit 2 for the cover, but 4 pieces were read (the
# closing one from the last vertex, at its line)
printf '0\nPOLYLINE\n66\n1\n70\n1\n0\nVERTEX\n10\n0\n20\n0\n0\nVERTEX\n10\n1\n20\n0\n0\nVERTEX\n10\n1\n20\n1\n0\nVERTEX\n10\n0\n20\n1\n0\nSEQEND\n' | dxf > "$T/square.dxf"
m "$T/square.dxf" arc_quarter -0.5 --curves "$REF"
check '[ $? -eq 2 ] && grep -q "square.dxf:30: piece 3" "$T/m.err"' "closed POLYLINE: its closing segment is piece 3, at its last VERTEX: $(head -c 400 "$T/m.err")"
# a 3D polyline or a mesh is no planar curve: skipped, named
printf '0\nPOLYLINE\n66\n1\n70\n8\n0\nVERTEX\n10\n0\n20\n0\n30\n1\n0\nVERTEX\n10\n1\n20\n0\n30\n2\n0\nSEQEND\n' | dxf > "$T/poly3d.dxf"
cat "$T/oldpoly.dxf" | sed '$d' | sed '$d' | sed '$d' | sed '$d' > "$T/both.dxf"
printf '0\nPOLYLINE\n66\n1\n70\n8\n0\nVERTEX\n10\n0\n20\n0\n30\n1\n0\nVERTEX\n10\n1\n20\n0\n30\n2\n0\nSEQEND\n0\nENDSEC\n0\nEOF\n' >> "$T/both.dxf"
m "$T/both.dxf" arc_quarter -0.5 --curves "$REF"
check '[ $? -eq 0 ] && grep -q "skipped 1 entity .*1 POLYLINE 3D or mesh" "$T/m.err"' \
    "a 3D POLYLINE beside a 2D one: skipped and named: $(cat "$T/m.err")"
# a VERTEX with flag 16 (a spline frame's control point) is not drawn: not a vertex
printf '0\nPOLYLINE\n66\n1\n70\n4\n0\nVERTEX\n10\n1.5\n20\n0\n42\n%s\n70\n8\n0\nVERTEX\n10\n9\n20\n9\n70\n16\n0\nVERTEX\n10\n%s\n20\n%s\n42\n%s\n70\n8\n0\nVERTEX\n10\n0\n20\n1.5\n70\n8\n0\nSEQEND\n' \
    "$b" "$r" "$r" "$b" | dxf > "$T/fitpoly.dxf"
m "$T/fitpoly.dxf" arc_quarter -0.5 --curves "$REF"
check '[ $? -eq 0 ] && [ "$(dropcols "$T/m.csv" file)" = "$(dropcols "$T/lw.csv" file)" ]' \
    "spline-fit POLYLINE: its frame's control points (VERTEX flag 16) left out: $(cat "$T/m.csv" "$T/m.err")"
# the line of reference.curves, d = 0.3: its offset as two LINEs, the second first
awk 'BEGIN{n = sqrt(1.25); ox = -0.5 * 0.3 / n; oy = 0.3 / n
      printf "0\nLINE\n10\n%.17g\n20\n%.17g\n11\n%.17g\n21\n%.17g\n", 0.4 + ox, 0.2 + oy, 1 + ox, 0.5 + oy
      printf "0\nLINE\n10\n%.17g\n20\n%.17g\n11\n%.17g\n21\n%.17g\n", ox, oy, 0.4 + ox, 0.2 + oy}' | dxf > "$T/lines.dxf"
m "$T/lines.dxf" line 0.3 --curves "$REF"
check '[ $? -eq 0 ] && awk -v a="$(val hausdorff-whole)" "BEGIN{exit !(a < 1e-15)}" && grep -q "lines.dxf:[0-9]*: piece 1: out of order" "$T/m.err"' \
    "two LINEs on the offset, out of order: exit 0, whole $(val hausdorff-whole), a warning: $(cat "$T/m.err")"
# an ARC that stops at 60 degrees: the last 30 are a gap
printf '0\nARC\n10\n0\n20\n0\n40\n0.5\n50\n0\n51\n60\n' | dxf > "$T/short.dxf"
m "$T/short.dxf" arc_quarter 0.5 --curves "$REF"
check '[ $? -eq 2 ] && grep -q "short.dxf:6: piece 0: gap: nothing covers base segment 0 from t = .* to t = 1 (after this piece" "$T/m.err"' \
    "an ARC short of the offset: exit 2 at its line: $(cat "$T/m.err")"

e2e_done
