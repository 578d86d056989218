#!/bin/sh
# End-to-end tests of measure's "where is the error" outputs (issue 50 item 3):
# - --per-piece FILE.csv: one row per piece of the file (the file's numbering),
#   with its entity, DXF handle, SVG id, line, base range, its own hausdorff
#   error and the worst point (x, y on the piece; x_off, y_off on the exact
#   offset; seg, t there); the largest max_err of the rows is the hausdorff
#   row's, bit for bit; the CSV on standard output does not change;
# - --draw FILE.svg (and draw --approx): the base, the exact offset, the
#   pieces coloured by their error, a legend, the worst point marked;
# - a local defect hidden under a larger global error is found: an export of
#   a circular arc's offset scaled about the centre (every piece off by E),
#   one piece's control point moved outward by e < E: the bumped piece is the
#   first by max_err, its handle and line are the entity's, its x, y lies on
#   that entity, and the drawing marks it;
# - paths that collide (--per-piece and --draw one file, either an --approx
#   input) are refused, exit 2, nothing written.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

REF=$(cd "$(dirname "$0")/../.." && pwd)/datasets/reference.curves
if command -v python3 >/dev/null 2>&1; then
    wellformed() { python3 -c 'import xml.dom.minidom,sys; xml.dom.minidom.parse(sys.argv[1])' "$1" 2>/dev/null; }
else
    wellformed() { skipped=$((skipped + 1)); return 0; }
fi

# --- the planted defect --------------------------------------------------------
# cubic-opt at 1e-8 on the quarter circle, d = -0.5: 8 cubic pieces on the
# circle of radius 1.5, each within 1.5e-9
"$OB" run --curves "$REF" --curve arc_quarter --methods cubic-opt --tols 1e-8 --backend cpu \
    --out "$T/r" --export "$T/x" 2>"$T/run.err"
check '[ $? -eq 0 ]' "run --export: exit 0 ($(tail -n 2 "$T/run.err"))"
SRC=$T/x/arc_quarter__d-0.5__cubic-opt__tol1e-08.dxf
check '[ -f "$SRC" ] && [ "$(grep -c "^SPLINE$" "$SRC")" -eq 8 ]' "the export: 8 SPLINE entities"

# every control point scaled about the centre by (1.5 + E) / 1.5 (the whole
# approximation off by E = 1e-3), and piece K's second control point moved
# outward by e = 5e-4 more (about 0.44 e on the piece: its error E + 2.2e-4)
K=3
awk -v s="$(awk 'BEGIN{printf "%.17g", (1.5 + 1e-3) / 1.5}')" -v k=$K -v e=5e-4 '
    NR % 2 == 1 { code = $0 + 0; cl = $0; next }
    code == 0 && $0 == "SPLINE" { sp++; cp = 0 }
    sp > 0 && code == 10 { x = $0; next }
    sp > 0 && code == 20 { X = s * x; Y = s * $0
                           if (sp - 1 == k && cp == 1) { r = sqrt(X * X + Y * Y); X *= (r + e) / r; Y *= (r + e) / r }
                           cp++; printf "10\n%.17g\n20\n%.17g\n", X, Y; next }
    { print cl; print }' "$SRC" > "$T/bump.dxf"
HANDLE=$(awk -v k=$K 'NR % 2 == 1 { code = $0 + 0; next } code == 0 && $0 == "SPLINE" { sp++ } code == 5 && sp - 1 == k { print; exit }' "$T/bump.dxf")
LINE=$(awk -v k=$K '$0 == "SPLINE" { if (n++ == k) { print NR; exit } }' "$T/bump.dxf")
check '[ -n "$HANDLE" ] && [ -n "$LINE" ]' "the bumped entity has a handle ($HANDLE) and a line ($LINE)"

M="measure --curves $REF --curve arc_quarter --d -0.5"
$OB $M --approx "$T/bump.dxf" >"$T/plain.csv" 2>"$T/plain.err"
check '[ $? -eq 0 ]' "measure the bumped file: exit 0 ($(head -c 300 "$T/plain.err"))"
$OB $M --approx "$T/bump.dxf" --per-piece "$T/pp.csv" --draw "$T/pp.svg" >"$T/with.csv" 2>"$T/with.err"
check '[ $? -eq 0 ] && [ -s "$T/pp.csv" ] && [ -s "$T/pp.svg" ]' \
    "measure --per-piece --draw: exit 0, both written ($(head -c 300 "$T/with.err"))"
check 'cmp -s "$T/plain.csv" "$T/with.csv"' "standard output is the same with --per-piece and --draw"

PPH='file,piece,entity,handle,id,line,degree,seg0,t0,seg1,t1,max_err,seg,t,x,y,x_off,y_off'
check '[ "$(head -n 1 "$T/pp.csv" 2>/dev/null | cut -d, -f1-18)" = "$PPH" ]' "the per-piece header ($(head -n 1 "$T/pp.csv" 2>/dev/null))"
check '[ "$(tail -n +2 "$T/pp.csv" 2>/dev/null | wc -l)" -eq 8 ]' "8 rows, one per piece"
check '[ "$(csvcols "$T/pp.csv" piece | tail -n +2 | tr "\n" " ")" = "0 1 2 3 4 5 6 7 " ]' "the rows in the file's piece order"
check '[ "$(csvcols "$T/pp.csv" entity degree | tail -n +2 | sort -u)" = "SPLINE,3" ]' "entity SPLINE, degree 3"
# the hausdorff row is dominated by the global error; the bumped piece stands out
H=$(awkc '$c["metric"] == "hausdorff" {print $c["max_err"]}' "$T/plain.csv")
check 'awk -v h="$H" "BEGIN{exit !(h > 1e-3 && h < 1.5e-3)}"' "the hausdorff row: $H, between E and 1.5 E"
TOP=$(awkc 'NR > 1 {print $c["max_err"], $c["piece"]}' "$T/pp.csv" | sort -g -r | head -n 1)
check '[ "${TOP#* }" = "$K" ]' "sorted by max_err, the bumped piece $K comes first ($TOP)"
check 'awkc "NR > 1 && \$c[\"piece\"] != k {if (\$c[\"max_err\"] > 1.01e-3 || \$c[\"max_err\"] < 0.99e-3) bad = 1} END {exit bad}" k=$K "$T/pp.csv"' \
    "every other piece is off by E (within 1%)"
check '[ "$(awkc "NR > 1 && \$c[\"piece\"] == k {print \$c[\"handle\"] \",\" \$c[\"line\"]}" k=$K "$T/pp.csv")" = "$HANDLE,$LINE" ]' \
    "the bumped row names the entity's handle and line ($HANDLE,$LINE)"
# the largest max_err of the rows is the hausdorff row's, as text
check '[ "$(awkc "NR > 1 {print \$c[\"max_err\"]}" "$T/pp.csv" | sort -g -r | head -n 1)" = "$H" ]' \
    "the largest per-piece max_err is the hausdorff row's ($H)"
# x, y lies on the bumped SPLINE (its control points, from the file), x_off,
# y_off on the circle of radius 1.5, and they are max_err apart
awk -v k=$K 'NR % 2 == 1 { code = $0 + 0; next } code == 0 && $0 == "SPLINE" { sp++ }
    sp - 1 == k && code == 10 { printf "%s ", $0 } sp - 1 == k && code == 20 { printf "%s ", $0 }' "$T/bump.dxf" > "$T/ctrl"
WROW=$(awkc 'NR > 1 && $c["piece"] == k {print $c["x"], $c["y"], $c["x_off"], $c["y_off"], $c["max_err"]}' k=$K "$T/pp.csv")
ONIT=$(echo "$WROW $(cat "$T/ctrl")" | awk '{x = $1; y = $2; for (i = 0; i < 4; i++) { px[i] = $(6 + 2 * i); py[i] = $(7 + 2 * i) }
    best = 1e9; n = 4000
    for (j = 0; j <= n; j++) { t = j / n; u = 1 - t
        X[j] = u*u*u*px[0] + 3*u*u*t*px[1] + 3*u*t*t*px[2] + t*t*t*px[3]; Y[j] = u*u*u*py[0] + 3*u*u*t*py[1] + 3*u*t*t*py[2] + t*t*t*py[3] }
    for (j = 0; j < n; j++) { dx = X[j+1] - X[j]; dy = Y[j+1] - Y[j]; L = dx*dx + dy*dy
        s = L > 0 ? ((x - X[j]) * dx + (y - Y[j]) * dy) / L : 0; s = s < 0 ? 0 : s > 1 ? 1 : s
        ex = X[j] + s * dx - x; ey = Y[j] + s * dy - y; dd = sqrt(ex*ex + ey*ey); if (dd < best) best = dd }
    print (best < 1e-7) ? "yes" : "no " best}')
check '[ "$ONIT" = "yes" ]' "x, y lies on the bumped SPLINE ($ONIT; $WROW)"
check 'echo "$WROW" | awk "{r = sqrt(\$3 * \$3 + \$4 * \$4); g = sqrt((\$1 - \$3)^2 + (\$2 - \$4)^2); exit !(r - 1.5 < 1e-12 && 1.5 - r < 1e-12 && g - \$5 < 1e-9 * \$5 && \$5 - g < 1e-9 * \$5)}"' \
    "x_off, y_off on the exact offset (radius 1.5), max_err from x, y ($WROW)"
# the drawing: well-formed, a legend, every piece, the worst marked at piece K
check 'wellformed "$T/pp.svg"' "the drawing is well-formed XML"
check '[ "$(grep -o "class=\"piece\"" "$T/pp.svg" | wc -l)" -eq 8 ]' "the drawing has 8 pieces"
check 'grep -q "class=\"legend\"" "$T/pp.svg"' "the drawing has a legend"
check 'grep -q "class=\"worst\"[^>]*data-piece=\"$K\"" "$T/pp.svg"' "the drawing marks the worst point at piece $K"
check 'grep -q "class=\"offset\"" "$T/pp.svg" && grep -q "class=\"base\"" "$T/pp.svg"' "the drawing shows the base and the exact offset"
# draw --approx: the same figure
$OB draw --curves "$REF" --curve arc_quarter --d -0.5 --approx "$T/bump.dxf" --out "$T/d.svg" 2>"$T/d.err"
check '[ $? -eq 0 ] && cmp -s "$T/d.svg" "$T/pp.svg"' "draw --approx writes the same figure ($(head -c 300 "$T/d.err"))"

# --- several files, a JSON, SVG ids, the max rule on another job -----------------
"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-3 --backend cpu --out "$T/r2" --export "$T/x2" 2>/dev/null
J=$T/x2/liu2002_ex1__d-1__tiller__tol0.001.json
S=$T/x2/liu2002_ex1__d-1__tiller__tol0.001.svg
awk '/<path/ { sub(/<path/, "<path id=\"p" n++ "\"") } { print }' "$S" > "$T/ids.svg"
$OB measure --curve liu2002_ex1 --d -1 --approx "$J" --approx "$T/ids.svg" --per-piece "$T/two.csv" >"$T/two.out" 2>"$T/two.err"
check '[ $? -eq 0 ]' "two files: exit 0 ($(head -c 300 "$T/two.err"))"
NJ=$(awkc '$c["metric"] == "hausdorff" && $c["file"] == f {print $c["pieces"]}' f="$J" "$T/two.out")
check '[ "$(awkc "NR > 1 && \$c[\"file\"] == f" f="$J" "$T/two.csv" | wc -l)" -eq "$NJ" ] && [ "$(awkc "NR > 1 {print \$c[\"file\"]}" "$T/two.csv" | uniq | wc -l)" -eq 2 ]' \
    "rows of each file, in the order given ($NJ pieces in the JSON)"
for f in "$J" "$T/ids.svg"; do
    h=$(awkc '$c["metric"] == "hausdorff" && $c["file"] == f {print $c["max_err"]}' f="$f" "$T/two.out")
    m=$(awkc 'NR > 1 && $c["file"] == f {print $c["max_err"]}' f="$f" "$T/two.csv" | sort -g -r | head -n 1)
    check '[ -n "$h" ] && [ "$m" = "$h" ]' "$(basename "$f"): max of the per-piece rows $m = the hausdorff row $h"
done
check '[ "$(awkc "NR > 1 && \$c[\"file\"] == f {print \$c[\"id\"]}" f="$T/ids.svg" "$T/two.csv" | head -n 2 | tr "\n" " ")" = "p0 p1 " ]' \
    "the SVG rows carry the elements' ids"
check '[ "$(awkc "NR > 1 && \$c[\"file\"] == f {print \$c[\"entity\"]}" f="$T/ids.svg" "$T/two.csv" | sort -u)" = "path" ]' \
    "the SVG rows' entity is the element (path)"

# --- a piece cut at a base joint by the match is one row -------------------------
# 'two' is the cubic 'one' cut at t = 0.4 (de Casteljau); tiller's export of
# 'one' without its links (the 999 comments) is matched against 'two'
awk 'function pt(x, y) { printf "  point %.17g %.17g\n", x, y }
BEGIN { split("0 1 3 4", X, " "); split("0 2 2 0", Y, " "); t = 0.4
    for (i = 1; i <= 4; i++) { x[0, i] = X[i]; y[0, i] = Y[i] }
    for (r = 1; r < 4; r++) for (i = 1; i <= 4 - r; i++) {
        x[r, i] = x[r-1, i] + (x[r-1, i+1] - x[r-1, i]) * t; y[r, i] = y[r-1, i] + (y[r-1, i+1] - y[r-1, i]) * t }
    print "curve one\n  bezier 3"; for (i = 1; i <= 4; i++) pt(X[i], Y[i]); print "  offset -0.3\nend"
    print "curve two\n  bspline 3"
    for (r = 0; r < 4; r++) pt(x[r, 1], y[r, 1])
    for (r = 2; r >= 0; r--) pt(x[r, 4 - r], y[r, 4 - r])
    print "  knots 0 0 0 0 0.4 0.4 0.4 1 1 1 1\n  offset -0.3\nend" }' > "$T/j.curves"
"$OB" run --curves "$T/j.curves" --curve one --methods tiller --tols 1e-3 --backend cpu --out "$T/r3" --export "$T/x3" 2>/dev/null
awk 'NR % 2 == 1 { c = $0 + 0; cl = $0; next } c != 999 { print cl; print }' "$T/x3/one__d-0.3__tiller__tol0.001.dxf" > "$T/nolink.dxf"
$OB measure --curves "$T/j.curves" --curve two --d -0.3 --approx "$T/nolink.dxf" --per-piece "$T/cut.csv" >"$T/cut.out" 2>"$T/cut.err"
check '[ $? -eq 0 ]' "the export without links against the cut curve: exit 0 ($(head -c 300 "$T/cut.err"))"
NP=$(awkc '$c["metric"] == "hausdorff" {print $c["pieces"]}' "$T/cut.out")
check '[ -n "$NP" ] && [ "$(tail -n +2 "$T/cut.csv" | wc -l)" -eq "$NP" ]' "one row per piece of the file ($NP), none per part"
check '[ "$(awkc "NR > 1 && \$c[\"seg0\"] == 0 && \$c[\"seg1\"] == 1" "$T/cut.csv" | wc -l)" -eq 1 ]' \
    "one row runs over the joint (seg0 0, seg1 1)"
check '[ "$(awkc "NR > 1 {print \$c[\"max_err\"]}" "$T/cut.csv" | sort -g -r | head -n 1)" = "$(awkc "\$c[\"metric\"] == \"hausdorff\" {print \$c[\"max_err\"]}" "$T/cut.out")" ]' \
    "matched and cut: the largest row is the hausdorff row"
check '[ "$(csvcols "$T/cut.csv" entity | tail -n +2 | sort -u)" = "SPLINE" ] && [ "$(csvcols "$T/cut.csv" handle | tail -n +2 | grep -c .)" -eq "$NP" ]' \
    "every row, the cut one too, names its SPLINE and handle"

# --- a polyline's pieces name its handle, not its VERTEX's ----------------------
# two bulge arcs on the circle of radius 1.5 (the d = -0.5 offset of
# arc_quarter) as an old-style POLYLINE with handles on every entity
dxf() { printf '0\nSECTION\n2\nENTITIES\n'; cat; printf '0\nENDSEC\n0\nEOF\n'; }
b=$(awk 'BEGIN{printf "%.17g", sin(atan2(1, 1) / 4) / cos(atan2(1, 1) / 4)}')
r=$(awk 'BEGIN{printf "%.17g", 1.5 * sqrt(0.5)}')
printf '0\nPOLYLINE\n5\n2A\n8\n0\n66\n1\n10\n0\n20\n0\n30\n0\n70\n0\n0\nVERTEX\n5\n2B\n8\n0\n10\n1.5\n20\n0\n42\n%s\n0\nVERTEX\n5\n2C\n10\n%s\n20\n%s\n42\n%s\n0\nVERTEX\n5\n2D\n10\n0\n20\n1.5\n0\nSEQEND\n5\n2E\n' \
    "$b" "$r" "$r" "$b" | dxf > "$T/poly.dxf"
$OB $M --approx "$T/poly.dxf" --per-piece "$T/poly.csv" >/dev/null 2>"$T/poly.err"
check '[ $? -eq 0 ] && [ "$(csvcols "$T/poly.csv" entity handle line | tail -n +2 | tr "\n" " ")" = "POLYLINE,2A,22 POLYLINE,2A,34 " ]' \
    "a POLYLINE's two arcs: its type and handle, each at its first VERTEX's line ($(csvcols "$T/poly.csv" entity handle line | tail -n +2 | tr "\n" " "); $(head -c 200 "$T/poly.err"))"

# --- collisions and bad values: exit 2, nothing written -------------------------
cp "$T/bump.dxf" "$T/keep.dxf"
$OB $M --approx "$T/bump.dxf" --per-piece "$T/same.out" --draw "$T/same.out" >"$T/c.csv" 2>"$T/c.err"
check '[ $? -eq 2 ] && [ ! -e "$T/same.out" ] && [ ! -s "$T/c.csv" ] && grep -q -- "--draw" "$T/c.err"' \
    "--per-piece and --draw one file: exit 2 naming --draw ($(head -c 300 "$T/c.err"))"
$OB $M --approx "$T/bump.dxf" --per-piece "$T/bump.dxf" >"$T/c.csv" 2>"$T/c.err"
check '[ $? -eq 2 ] && cmp -s "$T/bump.dxf" "$T/keep.dxf" && [ ! -s "$T/c.csv" ] && grep -q -- "--per-piece" "$T/c.err"' \
    "--per-piece an --approx input: exit 2, the input untouched ($(head -c 300 "$T/c.err"))"
$OB $M --approx "$T/bump.dxf" --draw "$T/x/../bump.dxf" >"$T/c.csv" 2>"$T/c.err"
check '[ $? -eq 2 ] && cmp -s "$T/bump.dxf" "$T/keep.dxf" && grep -q -- "--draw" "$T/c.err"' \
    "--draw an --approx input (another spelling): exit 2 ($(head -c 300 "$T/c.err"))"
$OB $M --approx "$T/bump.dxf" --per-piece= >"$T/c.csv" 2>"$T/c.err"
check '[ $? -eq 2 ] && grep -q -- "--per-piece" "$T/c.err"' "--per-piece with no name: exit 2 naming it ($(head -c 200 "$T/c.err"))"
$OB draw --curves "$REF" --curve arc_quarter --d -0.5 --approx "$T/bump.dxf" --out "$T/bump.dxf" 2>"$T/c.err"
check '[ $? -eq 2 ] && cmp -s "$T/bump.dxf" "$T/keep.dxf"' "draw --approx --out the input: exit 2 ($(head -c 200 "$T/c.err"))"
$OB draw --curves "$REF" --curve arc_quarter --approx "$T/bump.dxf" --out "$T/nod.svg" 2>"$T/c.err"
check '[ $? -eq 2 ] && [ ! -e "$T/nod.svg" ] && grep -q -- "--d" "$T/c.err"' "draw --approx without --d: exit 2 naming --d ($(head -c 200 "$T/c.err"))"
# a file that fails: no per-piece file either
printf 'curve x\ndegree 3\nbogus\n' > "$T/bad.curves"
$OB $M --approx "$T/bump.dxf" --approx "$T/bad.curves" --per-piece "$T/nb.csv" --draw "$T/nb.svg" >"$T/c.csv" 2>"$T/c.err"
check '[ $? -eq 2 ] && [ ! -e "$T/nb.csv" ] && [ ! -e "$T/nb.svg" ]' "a file that fails: no --per-piece and no --draw file"

e2e_done
