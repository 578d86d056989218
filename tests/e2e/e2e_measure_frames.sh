#!/bin/sh
# End-to-end tests of measure's verdict, default rows, drawing frames and
# diagnosis (issue 50 items 4 and 2), on an export of liu2002_ex1 at d = -1
# with its links stripped (a plain CAD file: pieces matched by projection):
# - a copy drawn in a CAD frame (x 25.4, y flipped, moved by (100, 50))
#   fails without a frame, and its diagnosis names the inverse map in
#   --transform syntax; with --transform, or with --translate, --scale and
#   --flip-y, it measures as the plain file (to 1e-12 relative);
# - the plain file measured at d = 1 is diagnosed as the wrong sign of d;
# - --tol: exit 0 within, 1 over, a verdict line per file on stderr; 2 for
#   a bad value or a deciding row that is n/a;
# - --svg-units px applies an SVG's root viewBox (user units stay the
#   default), and measures with the inverse map as in user units;
# - without --metric the n/a rows are left out and named on stderr;
#   --metric all writes every row as before;
# - bad values of each new option: exit 2 naming the option.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-3 --backend cpu --out "$T/r" --export "$T/x" 2>"$T/err"
check '[ $? -eq 0 ]' "run --export: exit 0 ($(tail -n 2 "$T/err"))"
S=$T/x/liu2002_ex1__d-1__tiller__tol0.001.dxf
J=$T/x/liu2002_ex1__d-1__tiller__tol0.001.json
# the DXF without its 999 comments (the base links)
awk 'NR % 2 == 1 {c = $0; next} c + 0 == 999 {next} {print c; print $0}' "$S" >"$T/plain.dxf"
# the same drawn in a CAD frame: x' = 25.4 x + 100, y' = -25.4 y + 50
awk 'NR % 2 == 1 {c = $0; next} c + 0 == 999 {next}
     c + 0 == 10 {x = $0; next}
     c + 0 == 20 {printf "10\n%.17g\n20\n%.17g\n", 25.4 * x + 100, -25.4 * $0 + 50; next}
     {print c; print $0}' "$S" >"$T/cad.dxf"
M="$OB measure --curve liu2002_ex1"
err_of() { awkc '$c["metric"] == m {print $c["max_err"]}' m="$2" "$1"; }
relsame() { awk -v a="$1" -v b="$2" 'BEGIN{d = a - b; if (d < 0) d = -d; s = a < 0 ? -a : a; exit !(a != "" && d <= 1e-12 * s)}'; }

# ---- frames ------------------------------------------------------------------
$M --d -1 --approx "$T/plain.dxf" --metric all >"$T/plain.csv" 2>"$T/plain.err"
check '[ $? -eq 0 ]' "the plain file measures ($(head -c 300 "$T/plain.err"))"
$M --d -1 --approx "$T/cad.dxf" >"$T/cad0.csv" 2>"$T/cad0.err"
check '[ $? -eq 2 ]' "the CAD copy without a frame: exit 2"
tr=$(sed -n 's/.*try --transform \([^ ]*\).*/\1/p' "$T/cad0.err" | head -n 1)
check '[ -n "$tr" ] && echo "$tr" | awk -F, "{w[1]=1/25.4; w[2]=0; w[3]=0; w[4]=-1/25.4; w[5]=-100/25.4; w[6]=50/25.4;
      for (i = 1; i <= 6; i++) { d = \$i - w[i]; if (d < 0) d = -d; if (NF != 6 || d > 1e-6) exit 1 } }"' \
    "the diagnosis names the inverse map: '$tr' ($(grep -i 'similarity\|transform' "$T/cad0.err" | head -c 400))"
check '! grep -q "cusps" "$T/cad0.err"' "no hint about cusps for a file in another frame"
INV=$(awk 'BEGIN{printf "%.17g,0,0,%.17g,%.17g,%.17g", 1/25.4, -1/25.4, -100/25.4, 50/25.4}')
$M --d -1 --approx "$T/cad.dxf" --transform "$INV" --metric all >"$T/cad1.csv" 2>"$T/cad1.err"
check '[ $? -eq 0 ]' "the CAD copy with --transform $INV: exit 0 ($(head -c 300 "$T/cad1.err"))"
for m in hausdorff hausdorff-whole normal; do
    a=$(err_of "$T/plain.csv" $m) b=$(err_of "$T/cad1.csv" $m)
    check 'relsame "$a" "$b"' "--transform: $m $b as the plain file's $a"
done
$M --d -1 --approx "$T/cad.dxf" --translate -100,-50 --scale "$(awk 'BEGIN{printf "%.17g", 1/25.4}')" --flip-y \
    >"$T/cad2.csv" 2>"$T/cad2.err"
check '[ $? -eq 0 ]' "the CAD copy with --translate, --scale, --flip-y: exit 0 ($(head -c 300 "$T/cad2.err"))"
a=$(err_of "$T/plain.csv" hausdorff-whole) b=$(err_of "$T/cad2.csv" hausdorff-whole)
check 'relsame "$a" "$b"' "--translate --scale --flip-y: hausdorff-whole $b as the plain file's $a"

# ---- the wrong sign of d -------------------------------------------------------
$M --d 1 --approx "$T/plain.dxf" >"$T/sign.csv" 2>"$T/sign.err"
check 'grep -q "within .* of the offset at d = -1: wrong sign of --d?" "$T/sign.err"' \
    "the d = -1 file at d = 1: diagnosed as the wrong sign ($(head -c 400 "$T/sign.err"))"
check '! grep -q "cusps" "$T/sign.err"' "no hint about cusps for the wrong sign"

# ---- --tol -------------------------------------------------------------------------
$M --d -1 --approx "$J" --approx "$T/plain.dxf" --tol 1e-2 >"$T/t0.csv" 2>"$T/t0.err"
check '[ $? -eq 0 ]' "--tol 1e-2: exit 0"
check '[ $(grep -c "within tolerance 0.01: hausdorff-whole = " "$T/t0.err") -eq 2 ]' \
    "--tol: a within line per file ($(grep tolerance "$T/t0.err"))"
check 'grep -q "measure: $T/plain.dxf: within tolerance" "$T/t0.err"' "the verdict line names the file"
check '[ $(wc -l <"$T/t0.csv") -gt 2 ]' "--tol: the CSV is written"
$M --d -1 --approx "$J" --approx "$T/plain.dxf" --tol 1e-4 >"$T/t1.csv" 2>"$T/t1.err"
check '[ $? -eq 1 ]' "--tol 1e-4: exit 1"
check '[ $(grep -c "over tolerance 0.0001: hausdorff-whole = " "$T/t1.err") -eq 2 ]' "--tol: an over line per file"
check 'cmp -s "$T/t0.csv" "$T/t1.csv"' "--tol changes no row"
$M --d -1 --approx "$T/plain.dxf" --metric normal --tol 1e-2 >/dev/null 2>"$T/t2.err"
check '[ $? -eq 0 ] && grep -q "within tolerance 0.01: normal = " "$T/t2.err"' "--metric normal decides ($(cat "$T/t2.err"))"
$M --d -1 --approx "$T/plain.dxf" --metric bound --tol 1e-2 >/dev/null 2>"$T/t3.err"
check '[ $? -eq 2 ] && grep -q -- "--tol" "$T/t3.err" && grep -q "n/a" "$T/t3.err"' \
    "--tol with a deciding row that is n/a: exit 2, says why ($(cat "$T/t3.err"))"

# ---- default rows ----------------------------------------------------------------
$M --d -1 --approx "$T/plain.dxf" >"$T/def.csv" 2>"$T/def.err"
check '[ $? -eq 0 ]' "default: exit 0"
check '[ "$(csvcols "$T/def.csv" metric | tail -n +2 | tr "\n" " ")" = "normal hausdorff hausdorff-whole " ]' \
    "default rows: those that apply ($(csvcols "$T/def.csv" metric | tail -n +2 | tr "\n" " "))"
check '! grep -q ",n/a," "$T/def.csv"' "default: no n/a row"
check 'grep -q "not shown.*bound, radial.*param" "$T/def.err"' "default: the rows left out named ($(grep 'not shown' "$T/def.err"))"
check '[ $(wc -l <"$T/plain.csv") -eq 7 ] && [ $(grep -c ",n/a," "$T/plain.csv") -eq 3 ]' "--metric all: every row, n/a too"
$M --d -1 --approx "$J" >"$T/defj.csv" 2>"$T/defj.err"
check '[ $(wc -l <"$T/defj.csv") -eq 7 ] && ! grep -q "not shown" "$T/defj.err"' "an export with links: all six rows apply"

# ---- an SVG's root viewBox: --svg-units px ------------------------------------------
# the export's paths under a root <svg viewBox="-2 -1.5 4 4" width="100mm"
# height="100mm">: in user units (the default) the base's coordinates; in
# px X = s x + 2 s, Y' = s y - 1.5 s after the y flip, s = 100 mm / 4 in px
SV=$T/x/liu2002_ex1__d-1__tiller__tol0.001.svg
{ echo '<svg xmlns="http://www.w3.org/2000/svg" viewBox="-2 -1.5 4 4" width="100mm" height="100mm">'
  echo '<g transform="scale(1,-1)">'; grep '<path' "$SV" | sed 's/ data-piece="[0-9]*" data-seg="[0-9]*"//'; echo '</g></svg>'; } >"$T/vb.svg"
$M --d -1 --approx "$T/vb.svg" >"$T/vb0.csv" 2>"$T/vb0.err"
check '[ $? -eq 0 ]' "the SVG in user units (default): exit 0 ($(head -c 300 "$T/vb0.err"))"
a=$(err_of "$T/plain.csv" hausdorff-whole) b=$(err_of "$T/vb0.csv" hausdorff-whole)
check 'awk -v a="$a" -v b="$b" "BEGIN{exit !(a != \"\" && (a - b) * (a - b) <= 1e-20 * a * a)}"' \
    "the SVG in user units: hausdorff-whole $b as the DXF's $a (to 1e-10: SVG writes fewer digits)"
$M --d -1 --approx "$T/vb.svg" --svg-units px >/dev/null 2>"$T/vb1.err"
check '[ $? -eq 2 ] && grep -q "try --transform" "$T/vb1.err"' "--svg-units px without a frame: the viewBox applied, exit 2, diagnosed"
PXT=$(awk 'BEGIN{s = 100 * 96 / 25.4 / 4; printf "%.17g,0,0,%.17g,-2,1.5", 1 / s, 1 / s}')
$M --d -1 --approx "$T/vb.svg" --svg-units px --transform "$PXT" >"$T/vb2.csv" 2>"$T/vb2.err"
check '[ $? -eq 0 ]' "--svg-units px --transform $PXT: exit 0 ($(head -c 300 "$T/vb2.err"))"
b2=$(err_of "$T/vb2.csv" hausdorff-whole)
check 'relsame "$b" "$b2"' "--svg-units px and its inverse map: hausdorff-whole $b2 as in user units $b"

# ---- bad values --------------------------------------------------------------------
for bad in "--tol 0" "--tol -1" "--tol nan" "--tol inf" "--tol abc" \
           "--transform 1,2,3" "--transform 1,2,2,4,0,0" "--transform 1,0,0,1,nan,0" "--transform 1,0,0,1,0,x" \
           "--translate 1" "--translate 1,inf" "--scale 0" "--scale 1,0" "--scale nan" "--scale 1,2,3" "--flip-y=yes" \
           "--svg-units mm" "--svg-units="; do
    opt=${bad%% *}; opt=${opt%%=*}
    $M --d -1 --approx "$T/plain.dxf" $bad >"$T/bad.csv" 2>"$T/bad.err"
    rc=$?
    check '[ $rc -eq 2 ] && grep -q -- "$opt" "$T/bad.err" && [ ! -s "$T/bad.csv" ]' \
        "$bad: exit 2 naming $opt (exit $rc: $(head -c 200 "$T/bad.err"))"
done

e2e_done
