#!/bin/sh
# End-to-end tests of the CAD-kernel example (docs/cad-example.md, issue 39
# item 4): OpenCASCADE's offsets (examples/occt/occt_offset.cpp) written as
# DXF, measured by `measure`, and put beside offbench's methods in one
# table by scripts/occt_table.py.
# - Without OpenCASCADE: the committed results under results/docs/occt
#   are this program's (their DXF files measured again and the methods run
#   again give the committed CSVs and table, byte for byte); the table has
#   the OCCT rows and offbench's; a planted wrong OCCT claim (a MaxError
#   below the measured error) is flagged, and only that row changes; the
#   make target names the Debian packages when the headers are missing.
# - With OpenCASCADE's headers (Debian's libocct-foundation-dev and
#   libocct-modeling-data-dev) and g++: occt_offset builds and runs; the
#   sign of its offsets is offbench's (a line's offset exact to rounding);
#   its DXF files (OCCT's B-splines as they are, spans over the base's
#   joints too) are read by measure and OCCT's claim holds on them; OCCT's
#   statuses (ok, limit where MaxSegments stops it with IsDone true, fail
#   as a row with OCCT's message, a C0 base offset in runs); the driver end
#   to end.  Without them these checks count as skipped, with the reason
#   (E2E_OCCT_ABSENT=1 skips them as if absent; OB_DEPS_OCCT=1 make deps
#   installs them).
# Uses $OFFBENCH (set by make) or ./offbench; /usr/bin/python3 (standard
# library only).
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
ROOT=$(pwd)
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
TAB=$ROOT/scripts/occt_table.py
R=results/docs/occt
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory -C "$ROOT" "$@"; }
# the rows of table.csv with METHOD (name as in the CSV), as curve:d:tol
rows_of() { awkc 'FNR>1 && $c["method"]==m {print $c["curve"] ":" $c["d"] ":" $c["tol"]}' m="$2" "$1"; }

# --- the committed results are this program's ---
cp -R "$R" "$T/c"
"$PY" "$TAB" --no-occt --out "$T/c" --offbench "$OB" >"$T/c.out" 2>&1
check '[ $? -eq 0 ]' "occt_table.py --no-occt on a copy of $R: exit 0 ($(tail -n 3 "$T/c.out" | tr '\n' ' '))"
for f in occt.csv measure.csv offbench.csv table.csv table.md; do
    check 'cmp -s "$R/$f" "$T/c/$f"' \
        "$R/$f is what measure and run give now (refresh: scripts/occt_table.py --no-occt --out $R): $(diff "$R/$f" "$T/c/$f" | head -n 6 | tr '\n' ' ')"
done
check '[ "$(ls "$R"/*.dxf | wc -l)" -eq "$(awkc "FNR>1 && \$c[\"file\"]!=\"\"" "$R/occt.csv" | wc -l)" ]' \
    "every DXF file occt.csv names is committed, and no other"

# --- the table: OCCT's rows beside offbench's ---
T1=$R/table.csv
check 'hascols "$T1" curve d tol method source status ctrl_points max_err claimed claim_holds within_tol' \
    "table.csv has its columns: $(head -n 1 "$T1")"
jobs=$(rows_of "$T1" tiller | sort | tr '\n' ' ')
check '[ -n "$jobs" ]' "table.csv has offbench's rows"
for m in occt-c2 occt-c1 tiller ahn bspline-lsq sisl; do
    check '[ "$(rows_of "$T1" $m | sort | tr "\n" " ")" = "$jobs" ]' "$m has a row for every job: $(rows_of "$T1" $m | tr '\n' ' ')"
done
check '[ -z "$(awkc "FNR>1 && \$c[\"source\"]==\"occt\" && \$c[\"claimed\"]==\"\"" "$T1")" ] && [ -z "$(awkc "FNR>1 && \$c[\"source\"]==\"offbench\" && \$c[\"claimed\"]!=\"\"" "$T1")" ]' \
    "OCCT's rows carry its claim, offbench's none"
check '[ -z "$(awkc "FNR>1 && \$c[\"claim_holds\"]!=\"\" && (\$c[\"max_err\"] + 0 <= \$c[\"claimed\"] + 1e-6 * \$c[\"tol\"] ? \"yes\" : \"no\") != \$c[\"claim_holds\"]" "$T1")" ]' \
    "claim_holds is yes exactly where the measured max_err is at most the claim (and round-off, 1e-6 tol)"
check '[ -z "$(awkc "FNR>1 && \$c[\"max_err\"]!=\"\" && (\$c[\"max_err\"] + 0 <= \$c[\"tol\"] + 0 ? \"yes\" : \"no\") != \$c[\"within_tol\"]" "$T1")" ]' \
    "within_tol is yes exactly where the measured max_err is at most the tolerance"
check 'grep -q "^| curve, d | tol | \`occt-c2\` |" "$R/table.md" && grep -q "| \`sisl\` |" "$R/table.md"' \
    "table.md: one row per job, OCCT's columns beside the methods': $(head -n 1 "$R/table.md")"

# --- a wrong claim is flagged ---
cp -R "$R" "$T/w"
# the first ok row of occt-c2: its MaxError replaced by 1e-9
"$PY" - "$T/w/occt.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
r = next(r for r in rows if r["method"] == "occt-c2" and r["status"] == "ok")
r["max_error"] = "1e-09"
with open(sys.argv[1], "w", newline="") as f:
    w = csv.DictWriter(f, rows[0].keys(), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)

EOF
"$PY" "$TAB" --table-only --out "$T/w" >"$T/w.out" 2>&1
check '[ $? -eq 0 ]' "occt_table.py --table-only: exit 0 ($(tail -n 2 "$T/w.out"))"
check '[ "$(diff "$R/table.csv" "$T/w/table.csv" | grep -c "^[<>]")" -eq 2 ]' \
    "only the planted row changes in table.csv: $(diff "$R/table.csv" "$T/w/table.csv" | tr '\n' ' ')"
check '[ "$(awkc "FNR>1 && \$c[\"claimed\"]==\"1e-09\" {print \$c[\"method\"], \$c[\"claim_holds\"]}" "$T/w/table.csv")" = "occt-c2 no" ]' \
    "the planted claim is flagged: claim_holds no"
check 'grep -q "1.00e-9 \*\*fails\*\*" "$T/w/table.md" && [ "$(grep -c "\*\*fails\*\*" "$R/table.md")" -lt "$(grep -c "\*\*fails\*\*" "$T/w/table.md")" ]' \
    "table.md shows it as failing: $(grep "fails" "$T/w/table.md" | head -n 1)"
# a claim below the measured error by rounding only (a millionth of the
# tolerance and less) is no failure: where OCCT is exact both are rounding
cp "$R/occt.csv" "$T/w/occt.csv"
"$PY" - "$T/w/occt.csv" "$T/w/measure.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
r = next(r for r in rows if r["method"] == "occt-c1" and r["status"] == "ok")
m = next(m for m in csv.DictReader(open(sys.argv[2], newline="")) if m["file"] == r["file"] and m["metric"] == "hausdorff")
r["max_error"] = repr(float(m["max_err"]) - 0.5e-6 * float(r["tol"]))
with open(sys.argv[1], "w", newline="") as f:
    w = csv.DictWriter(f, rows[0].keys(), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
EOF
"$PY" "$TAB" --table-only --out "$T/w" >"$T/w.out" 2>&1
check '[ $? -eq 0 ] && [ "$(awkc "FNR>1 {print \$c[\"claim_holds\"]}" "$T/w/table.csv" | sort | uniq -c | awk "{print \$1 \$2}" | tr "\n" " ")" = "$(awkc "FNR>1 {print \$c[\"claim_holds\"]}" "$T1" | sort | uniq -c | awk "{print \$1 \$2}" | tr "\n" " ")" ]' \
    "a claim short of the measured error by half a millionth of the tolerance still holds"

# --- the make target without OpenCASCADE's headers ---
occt_nohdr occt-bin OCCT_BIN

# --- with OpenCASCADE ---
occt_require e2e_occt 21
X=$T/occt_offset
mk OCCT_BIN="$X" occt-bin >"$T/build.out" 2>&1
check '[ $? -eq 0 ] && [ -x "$X" ]' "make occt-bin builds occt_offset: $(tail -n 5 "$T/build.out" | tr '\n' ' ')"
"$X" --help >"$T/help.out" 2>&1
check '[ $? -eq 0 ] && grep -q "^usage: occt_offset" "$T/help.out"' "occt_offset --help: exit 0"
"$X" --curves datasets/published.curves --curve nosuch --tols 1e-2 --out "$T" >"$T/bad.out" 2>&1
check '[ $? -eq 2 ] && grep -q "no curve .nosuch." "$T/bad.out"' "an unknown curve: exit 2 naming it: $(cat "$T/bad.out")"

# the sign of d: OCCT's normal is the right one, offbench's the left; a
# line's offset is a translate, which OCCT reproduces to rounding
mkdir "$T/ref"
"$X" --curves datasets/reference.curves --curve line,arc_quarter --tols 1e-3 --out "$T/ref" 2>"$T/ref.err"
check '[ $? -eq 0 ] && [ -f "$T/ref/occt.csv" ]' "occt_offset on the reference line and arc: exit 0 ($(tail -n 2 "$T/ref.err"))"
msr() { # CURVES CURVE D FILE [METRIC]: measure's max_err of one metric (default hausdorff)
    "$OB" measure --curves "$1" --curve "$2" --d "$3" --approx "$4" --metric "${5:-hausdorff}" >"$T/msr.csv" 2>>"$T/m.err"
    awkc 'FNR>1 && $c["metric"]==m {print $c["max_err"]}' m="${5:-hausdorff}" "$T/msr.csv"
}
e=$(msr datasets/reference.curves line 0.3 "$T/ref/line__d0.3__occt__tol0.001.dxf")
check 'awk -v e="$e" "BEGIN{exit !(e != \"\" && e < 1e-12)}"' "the line's offset at d = 0.3 on offbench's side: hausdorff $e"
for d in 0.5 -0.5; do
    e=$(msr datasets/reference.curves arc_quarter $d "$T/ref/arc_quarter__d${d}__occt__tol0.001.dxf")
    check 'awk -v e="$e" "BEGIN{exit !(e != \"\" && e <= 1e-3)}"' "the quarter circle's offset at d = $d within 1e-3: $e"
done

# liu2002_ex1 at d = -1 (one base segment) and liu2002_ex2 (four, whose
# joints OCCT's spans run over): read by measure, OCCT's claim checked
mkdir "$T/l"
"$X" --curves datasets/published.curves --curve liu2002_ex1,liu2002_ex2 --d -1 --tols 1e-3 --out "$T/l" 2>/dev/null
L=$T/l/liu2002_ex1__d-1__occt__tol0.001.dxf
check '[ "$(awkc "FNR>1 && \$c[\"curve\"]==\"liu2002_ex1\" {print \$c[\"status\"], \$c[\"is_done\"], \$c[\"has_result\"], \$c[\"runs\"]}" "$T/l/occt.csv")" = "ok 1 1 1" ]' \
    "liu2002_ex1, d = -1, 1e-3: ok, IsDone, HasResult, one run: $(sed -n 2p "$T/l/occt.csv")"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$L" --metric all >"$T/l.csv" 2>"$T/l.err"
check '[ $? -eq 0 ] && [ "$(csvcols "$T/l.csv" metric status | tr "\n" " ")" = "metric,status bound,n/a radial,n/a normal,ok hausdorff,ok param,n/a hausdorff-whole,ok " ]' \
    "measure reads the DXF: matched by projection, the metrics that need the base's parameter n/a ($(csvcols "$T/l.csv" metric status | tr '\n' ' ') $(cat "$T/l.err" | tr '\n' ' '))"
check '[ "$(awkc "FNR>1 && \$c[\"metric\"]==\"hausdorff\" {print \$c[\"pieces\"]}" "$T/l.csv")" = "$(awkc "FNR>1 && \$c[\"curve\"]==\"liu2002_ex1\" {print \$c[\"spans\"]}" "$T/l/occt.csv")" ]' \
    "measure finds OCCT's spans, one piece each"
a=$(awkc 'FNR>1 && $c["metric"]=="hausdorff" {print $c["max_err"]}' "$T/l.csv")
c=$(awkc 'FNR>1 && $c["curve"]=="liu2002_ex1" {print $c["max_error"]}' "$T/l/occt.csv")
check 'awk -v a="$a" -v c="$c" "BEGIN{exit !(a > 0 && a <= c && c <= 1e-3)}"' "OCCT's claim holds here: measured $a <= MaxError $c <= 1e-3"
e=$(msr datasets/published.curves liu2002_ex2 -1 "$T/l/liu2002_ex2__d-1__occt__tol0.001.dxf")
check 'awk -v e="$e" "BEGIN{exit !(e != \"\" && e <= 1e-3)}"' "liu2002_ex2: OCCT's spans over the base's joints measured: $e ($(tail -n 2 "$T/m.err" | tr '\n' ' '))"
"$OB" measure --curve liu2002_ex1 --d 1 --approx "$L" >/dev/null 2>"$T/w.err"
check 'grep -q "liu2002_ex1__d-1__occt__tol0.001" "$T/w.err"' "measured at another d: measure warns, naming the job ($(head -c 200 "$T/w.err"))"

# statuses: limit (MaxSegments stops the cutting: OCCT says done, MaxError
# above the tolerance), fail (an OCCT exception, as a row), C0 runs
mkdir "$T/s"
"$X" --curves datasets/published.curves --curve liu2002_ex1 --d 1 --tols 1e-6 --max-segments 1 --out "$T/s" --method lim 2>/dev/null
check '[ "$(awkc "FNR>1 {print \$c[\"status\"], \$c[\"is_done\"]}" "$T/s/lim.csv")" = "limit 1" ]' \
    "one segment at 1e-6: status limit although IsDone is true: $(tail -n 1 "$T/s/lim.csv")"
cat >"$T/s/odd.curves" <<'EOF'
curve stalled
  bezier 3
  point 0 0
  point 0 0
  point 1 1
  point 2 0
  offset 0.1
end
curve corner
  bspline 2
  knots 0 0 0 1 1 2 2 2
  point 0 0
  point 1 0
  point 2 0
  point 2 1
  point 2 2
  offset 0.25
end
EOF
"$X" --curves "$T/s/odd.curves" --tols 1e-3 --out "$T/s" --method odd 2>/dev/null
check '[ $? -eq 0 ] && [ "$(awkc "FNR>1 && \$c[\"curve\"]==\"stalled\" {print \$c[\"status\"], \$c[\"file\"]}" "$T/s/odd.csv")" = "fail " ] && grep -q "stalled.*Null derivative" "$T/s/odd.csv"' \
    "a zero first derivative: a fail row with OCCT's message, no file: $(grep stalled "$T/s/odd.csv")"
check '[ "$(awkc "FNR>1 && \$c[\"curve\"]==\"corner\" {print \$c[\"status\"], \$c[\"runs\"]}" "$T/s/odd.csv")" = "ok 2" ]' \
    "a C0 corner: two runs, each offset on its own: $(grep corner "$T/s/odd.csv")"
e=$(msr "$T/s/odd.curves" corner 0.25 "$T/s/corner__d0.25__odd__tol0.001.dxf")
check 'awk -v e="$e" "BEGIN{exit !(e != \"\" && e < 1e-12)}"' "the corner's two straight runs: exact to rounding: $e"

# the driver end to end, small; in DIR a file of the user's stays, an
# earlier run's approximation goes
mkdir "$T/d" && : >"$T/d/mine.dxf" && : >"$T/d/old__d1__occt-c2__tol0.5.dxf"
"$PY" "$TAB" --out "$T/d" --offbench "$OB" --occt "$X" --curve liu2002_ex1 --tols 1e-2 --methods tiller,ahn >"$T/d.out" 2>&1
check '[ $? -eq 0 ]' "occt_table.py end to end: exit 0 ($(tail -n 3 "$T/d.out" | tr '\n' ' '))"
check '[ "$(awkc "FNR>1 {print \$c[\"method\"]}" "$T/d/table.csv" | sort | uniq -c | awk "{print \$1 \$2}" | tr "\n" " ")" = "2ahn 2occt-c1 2occt-c2 2tiller " ]' \
    "its table: two jobs, OCCT's two rows and the two methods' each: $(awkc 'FNR>1 {print $c["method"]}' "$T/d/table.csv" | tr '\n' ' ')"
check '[ -z "$(awkc "FNR>1 && \$c[\"source\"]==\"occt\" && \$c[\"max_err\"]==\"\"" "$T/d/table.csv")" ] && grep -q "^| liu2002_ex1, −1 | 1e-2 |" "$T/d/table.md"' \
    "OCCT's rows measured, table.md written"
check '[ -e "$T/d/mine.dxf" ] && [ ! -e "$T/d/old__d1__occt-c2__tol0.5.dxf" ]' "the user's file stays, the earlier run's goes: $(ls "$T/d" | tr '\n' ' ')"
e2e_done
