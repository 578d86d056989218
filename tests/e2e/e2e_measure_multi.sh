#!/bin/sh
# End-to-end tests of measure with several approximations in one call and of
# the columns that join its CSV with results.csv (issue 39 item 3):
# - --approx repeats: each file measured on its own, its rows in the order
#   the files were given, each row the same as measure of that file alone;
# - the columns metric,status,max_err,piece,seg,t,message come first as
#   before, then file,curve,d,pieces,ctrl_points; curve and d are results.csv's
#   text, pieces its segments and ctrl_points its ctrl_points (1 + the sum of
#   the degrees, one more per open joint) for methods that output Bézier
#   pieces;
# - one bad file (malformed, missing, not covering the offset): exit 2 naming
#   it (FILE:LINE where there is a line), and no CSV at all, also for the
#   good files given with it.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

"$OB" run --curve liu2002_ex1 --methods tiller,lee --tols 1e-3 --backend cpu \
    --out "$T/r" --export "$T/x" 2>"$T/err"
check '[ $? -eq 0 ]' "run --export: exit 0 ($(tail -n 2 "$T/err"))"
A=$T/x/liu2002_ex1__d-1__tiller__tol0.001.json
B=$T/x/liu2002_ex1__d-1__lee__tol0.001.curves
check '[ -f "$A" ] && [ -f "$B" ]' "the two exports are there"

"$OB" measure --curve liu2002_ex1 --d -1 --approx "$A" >"$T/a.csv" 2>"$T/a.err"
check '[ $? -eq 0 ]' "measure A alone: exit 0 ($(head -c 300 "$T/a.err"))"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$B" >"$T/b.csv" 2>"$T/b.err"
check '[ $? -eq 0 ]' "measure B alone: exit 0 ($(head -c 300 "$T/b.err"))"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$A" --approx "$B" >"$T/ab.csv" 2>"$T/ab.err"
check '[ $? -eq 0 ]' "measure A and B: exit 0 ($(head -c 300 "$T/ab.err"))"

H='metric,status,max_err,piece,seg,t,message,file,curve,d,pieces,ctrl_points'
check '[ "$(head -n 1 "$T/ab.csv")" = "$H" ] && [ "$(head -n 1 "$T/a.csv")" = "$H" ]' \
    "the header: the old columns first, the new ones at the end ($(head -n 1 "$T/ab.csv"))"
check '[ $(wc -l < "$T/ab.csv") -eq 13 ]' "12 rows: 6 per file ($(wc -l < "$T/ab.csv") lines)"
# the rows of A and B in the combined CSV are those of each alone
check '[ "$(sed -n 2,7p "$T/ab.csv")" = "$(tail -n +2 "$T/a.csv")" ] && [ "$(sed -n 8,13p "$T/ab.csv")" = "$(tail -n +2 "$T/b.csv")" ]' \
    "each file's rows as measure of it alone, in the order given"
check '[ "$(csvcols "$T/ab.csv" file | tail -n +2 | sort | uniq -c | awk "{print \$1}" | tr "\n" " ")" = "6 6 " ]' \
    "the file column names each file six times"
check '[ "$(csvcols "$T/ab.csv" file | sed -n 2p)" = "$A" ] && [ "$(csvcols "$T/ab.csv" file | sed -n 8p)" = "$B" ]' \
    "the file column is the path as given"

# the join with results.csv: curve and d are its text, pieces its segments,
# ctrl_points its ctrl_points
for meth in tiller lee; do
    want=$(awkc '$c["method"] == m && $c["d"] == -1 {print $c["curve"] "," $c["d"] "," $c["segments"] "," $c["ctrl_points"] "," $c["max_err"]}' \
           m="$meth" "$T/r/results.csv")
    got=$(awkc '$c["file"] ~ m && $c["metric"] == "hausdorff" {print $c["curve"] "," $c["d"] "," $c["pieces"] "," $c["ctrl_points"] "," $c["max_err"]}' \
          m="__${meth}__" "$T/ab.csv")
    check '[ -n "$want" ] && [ "$got" = "$want" ]' "$meth: curve,d,pieces,ctrl_points,max_err $got (results.csv $want)"
done

# DXF lines on the exact offset of curve line (the translate by d N): two
# that meet, 1 + 1 + 1 control points; two with a gap of 1e-9 (an open
# joint: its two ends count as two points), 1 + 1 + 1 + 1
REF=$(cd "$(dirname "$0")/../.." && pwd)/datasets/reference.curves
lines() { awk -v g="$1" 'BEGIN{d = 0.3; n = sqrt(1.25); ox = -0.5 / n * d; oy = 1 / n * d
      printf "0\nSECTION\n2\nENTITIES\n"
      printf "0\nLINE\n10\n%.17g\n20\n%.17g\n11\n%.17g\n21\n%.17g\n", ox, oy, 0.5 + ox, 0.25 + oy
      printf "0\nLINE\n10\n%.17g\n20\n%.17g\n11\n%.17g\n21\n%.17g\n", 0.5 + g + ox, 0.25 + g / 2 + oy, 1 + ox, 0.5 + oy
      printf "0\nENDSEC\n0\nEOF\n"}'; }
lines 0 > "$T/l2.dxf"
lines 1e-9 > "$T/l2open.dxf"
"$OB" measure --curves "$REF" --curve line --d 0.3 --approx "$T/l2.dxf" --approx "$T/l2open.dxf" --metric hausdorff >"$T/l.csv" 2>"$T/l.err"
check '[ $? -eq 0 ] && [ "$(csvcols "$T/l.csv" pieces ctrl_points | sed -n 2p)" = "2,3" ]' \
    "two lines end to end: 2 pieces, 3 control points ($(csvcols "$T/l.csv" pieces ctrl_points | sed -n 2p); $(head -c 300 "$T/l.err"))"
check '[ "$(csvcols "$T/l.csv" pieces ctrl_points | sed -n 4p)" = "2,4" ]' \
    "two lines with a gap: 2 pieces, 4 control points ($(csvcols "$T/l.csv" pieces ctrl_points | sed -n 4p))"
check '[ "$(csvcols "$T/l.csv" curve d | sed -n 2p)" = "line,0.3" ]' "curve and d: line,0.3"

# --- a bad file: exit 2, naming it, and no CSV for any ---------------------------
printf 'curve x\ndegree 3\nbogus\n' > "$T/bad.curves"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$A" --approx "$T/bad.curves" --approx "$B" >"$T/m.csv" 2>"$T/m.err"
check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -q "bad.curves:[0-9]" "$T/m.err"' \
    "a malformed second file: exit 2, FILE:LINE, stdout empty ($(head -c 300 "$T/m.err"))"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$A" --approx "$T/none.json" >"$T/m.csv" 2>"$T/m.err"
check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -q "none.json" "$T/m.err"' \
    "a missing file: exit 2 naming it, stdout empty ($(head -c 300 "$T/m.err"))"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$T/l2.dxf" --approx "$A" >"$T/m.csv" 2>"$T/m.err"
check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -q "l2.dxf" "$T/m.err"' \
    "a file that does not cover the offset: exit 2 naming it, stdout empty ($(head -c 300 "$T/m.err"))"
"$OB" measure --curve liu2002_ex1 --d -1 --approx "$A" --approx "" >"$T/m.csv" 2>"$T/m.err"
check '[ $? -eq 2 ] && [ ! -s "$T/m.csv" ] && grep -q -- "--approx" "$T/m.err"' \
    "an empty file name: exit 2 naming --approx"

e2e_done
