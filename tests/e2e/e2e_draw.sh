#!/bin/sh
# End-to-end tests of ./offbench draw and ./offbench trace: the SVG is
# well-formed and shows the job run measured (its joints and its figures),
# the trace's error column agrees with the run's max_err, bad options exit 2
# naming the option, and fail/skip jobs are handled.  Uses $OFFBENCH (set by
# make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

if command -v python3 >/dev/null 2>&1; then
    wellformed() { python3 -c 'import xml.dom.minidom,sys; xml.dom.minidom.parse(sys.argv[1])' "$1" 2>/dev/null; }
else
    wellformed() { skipped=$((skipped + 1)); return 0; }
fi

# the row of results.csv for (curve, d): the run's figures, as the SVG title writes them
run_row() {  # dir d -> "status S, ctrl_points = N, segments = N, max_err = E, max_gap = G, continuity = C"
    rcols "$1/results.csv" d status ctrl_points segments max_err max_gap continuity |
        awk -F: -v d="$2" '$1==d {printf "status %s, ctrl_points = %s, segments = %s, max_err = %s, max_gap = %s, continuity = %s", $2, $3, $4, ($5 == "" ? "-" : $5), ($6 == "" ? "-" : $6), ($7 == "" ? "-" : $7)}'
}
svg_summary() { sed -n 's/.*<text class="summary"[^>]*>\([^<]*\)<\/text>.*/\1/p' "$1"; }
joints() { grep -o 'class="joint"' "$1" | wc -l | tr -d ' '; }

C=liu2002_ex1
TOL=1e-2

# --- draw: one job as run measures it -------------------------------------
for m in tiller ahn zhao-rational lee; do
    tol=$TOL
    [ $m = lee ] && tol=1e-3   # a job that ends `limit`: drawn all the same
    $OB run --curve $C --methods $m --tols $tol --out "$T/run_$m" 2>/dev/null
    want=$(run_row "$T/run_$m" 1)
    segs=$(awkc 'NR>1 && $c["d"]==1 {print $c["segments"]}' "$T/run_$m/results.csv")
    $OB draw --curve $C --method $m --tol $tol --out "$T/$m.svg" 2>"$T/$m.err"
    check '[ $? -eq 0 ] && [ -s "$T/$m.svg" ]' "draw $m exits 0 and writes the SVG"
    check 'wellformed "$T/$m.svg"' "draw $m: well-formed XML"
    check '[ -n "$segs" ] && [ "$(joints "$T/$m.svg")" -eq $((segs + 1)) ]' \
        "draw $m: $(joints "$T/$m.svg") joints for $segs segments"
    got=$(svg_summary "$T/$m.svg")
    check '[ -n "$want" ] && [ "$got" = "$want" ]' "draw $m: title '$got', run '$want'"
    check 'grep -q "^offbench: draw $C: $m, d = 1, tol = .*: $want" "$T/$m.err"' \
        "draw $m: the stderr summary has the run's figures: $(grep "^offbench: draw" "$T/$m.err")"
    check 'grep -q "<text class=\"title\"[^>]*>$C: $m, d = 1, tol = [0-9.e-]*, metric hausdorff, split mid</text>" "$T/$m.svg"' \
        "draw $m: the title names the job"
    for k in base offset approx ctrl ctrlpt; do
        check 'grep -q "class=\"$k\"" "$T/$m.svg"' "draw $m: has class $k"
    done
    check 'grep -q "viewBox=" "$T/$m.svg" && ! grep -qiE "nan|inf" "$T/$m.svg"' "draw $m: viewBox, no nan/inf numbers"
done

# any nonzero d, the run options, a rational input curve, a multi-segment curve
$OB draw --curve $C --method tiller --tol 1e-1 --d 0.3 --metric radial --split maxerr --out "$T/d03.svg" 2>/dev/null
check '[ $? -eq 0 ] && wellformed "$T/d03.svg" && grep -q "d = 0.3, tol = 0.1, metric radial, split maxerr" "$T/d03.svg"' \
    "draw --d 0.3 with --metric and --split"
$OB draw --curve arc_quarter --method exact --tol 1e-3 --out "$T/arc.svg" 2>/dev/null
check '[ $? -eq 0 ] && wellformed "$T/arc.svg" && [ "$(joints "$T/arc.svg")" -ge 2 ]' "draw of a rational curve"
$OB run --curve liu2002_ex2 --methods cobb --tols 1e-2 --split greedy --out "$T/run_ex2" 2>/dev/null
$OB draw --curve liu2002_ex2 --method cobb --tol 1e-2 --split greedy --out "$T/ex2.svg" 2>/dev/null
rc=$?
want=$(run_row "$T/run_ex2" 0.5)
check '[ $rc -eq 0 ] && [ "$(svg_summary "$T/ex2.svg")" = "$want" ]' "draw liu2002_ex2 greedy: $(svg_summary "$T/ex2.svg") vs $want"

# --- trace -------------------------------------------------------------------
HDR="curve,d,method,metric,split,tol,seg,piece,t,u,err,x,y"
# trace.csv read by name: u never goes down; every row's piece in range, t in
# [0,1], u = seg + t, and the job columns (trace_ok FILE SEGS CURVE METHOD METRIC)
u_sorted() { awkc 'NR>2 && $c["u"] < u {exit 1} {u = $c["u"]}' "$1"; }
trace_ok() {
    awkc 'NR>1 && ($c["piece"] < 0 || $c["piece"] >= n || $c["t"] < 0 || $c["t"] > 1 || $c["seg"] + $c["t"] != $c["u"] ||
                   $c["curve"] != cv || $c["method"] != me || $c["metric"] != mt) {exit 1}' n="$2" cv="$3" me="$4" mt="$5" "$1"
}
for m in tiller ahn zhao; do
    for me in hausdorff radial normal; do
        $OB run --curve $C --methods $m --tols $TOL --metric $me --out "$T/tr_$m$me" 2>/dev/null
        maxerr=$(awkc 'NR>1 && $c["d"]==1 {print $c["max_err"]}' "$T/tr_$m$me/results.csv")
        segs=$(awkc 'NR>1 && $c["d"]==1 {print $c["segments"]}' "$T/tr_$m$me/results.csv")
        $OB trace --curve $C --method $m --tol $TOL --metric $me --out "$T/tr_$m$me.csv" 2>/dev/null
        f="$T/tr_$m$me.csv"
        check '[ $? -eq 0 ] && [ "$(head -n 1 "$f")" = "$HDR" ]' "trace $m $me: exit 0, header"
        check '[ $(($(wc -l < "$f") - 1)) -eq $((segs * 64)) ]' "trace $m $me: 64 rows per piece ($segs pieces)"
        mx=$(awkc 'NR>1 && $c["err"]>m {m=$c["err"]} END {printf "%.17g", m}' "$f")
        check 'awk -v a="$mx" -v b="$maxerr" "BEGIN{exit !(b > 0 && a <= b * (1 + 1e-9) && a >= 0.5 * b)}"' \
            "trace $m $me: max err $mx within [0.5, 1] x the run's max_err $maxerr"
        check 'u_sorted "$f"' "trace $m $me: u non-decreasing"
        check 'trace_ok "$f" "$segs" "$C" "$m" "$me"' \
            "trace $m $me: columns (piece in range, t in [0,1], u = seg + t, job columns)"
        check '[ "$(rcols "$f" piece | uniq | wc -l)" -eq "$segs" ]' "trace $m $me: pieces in order, each once"
    done
done
# the default output is stdout; --points; the job's columns as in results.csv
$OB trace --curve $C --method tiller --tol 1e-1 --points 3 > "$T/p3.csv" 2>"$T/p3.err"
rc=$?
$OB run --curve $C --methods tiller --tols 1e-1 --out "$T/p3run" 2>/dev/null
segs=$(awkc 'NR>1 && $c["d"]==1 {print $c["segments"]}' "$T/p3run/results.csv")
check '[ $rc -eq 0 ] && [ $(($(wc -l < "$T/p3.csv") - 1)) -eq $((segs * 3)) ]' "trace --points 3 to stdout: 3 rows per piece"
jc=$(csvcols "$T/p3.csv" curve d method metric split tol | sed -n 2p)
check '[ "$jc" = "$C,1,tiller,hausdorff,mid,0.1" ]' "trace job columns: $jc"
check 'grep -q "x,y is the exact offset point" "$T/p3.err"' "trace says what x,y is"
$OB trace --curve $C --method tiller --tol 1e-1 --metric bound --out "$T/bound.csv" 2>"$T/bound.err"
check '[ $? -eq 0 ] && grep -q "radial" "$T/bound.err" && [ $(wc -l < "$T/bound.csv") -gt 1 ]' "trace under bound uses the radial error and says so"

# --- fail / skip jobs ------------------------------------------------------------
# hoschek's output is not in the base's parameter: bound cannot measure it (skip)
$OB draw --curve $C --method hoschek --tol 1e-2 --metric bound --out "$T/skip.svg" 2>"$T/skip.err"
check '[ $? -eq 0 ] && wellformed "$T/skip.svg"' "draw of a skipped job exits 0 with a well-formed SVG"
check 'svg_summary "$T/skip.svg" | grep -q "^status skip" && grep -q "class=\"message\"" "$T/skip.svg"' "the SVG title has the status and message"
check '[ "$(joints "$T/skip.svg")" -eq 0 ] && grep -q "class=\"base\"" "$T/skip.svg" && grep -q "class=\"offset\"" "$T/skip.svg"' \
    "a skipped job: curve and offset, no approximation"
check 'grep -q "skip" "$T/skip.err"' "draw prints the status on stderr"
$OB trace --curve $C --method hoschek --tol 1e-2 --metric bound --out "$T/skip.csv" 2>"$T/skipt.err"
check '[ $? -eq 0 ] && [ "$(cat "$T/skip.csv")" = "$HDR" ] && grep -q "skip" "$T/skipt.err"' "trace of a skipped job: header only, says why"

# --- bad options: exit 2 (1 for an unwritable output) naming the option ---------
expect() {  # code text cmd args...
    code=$1 txt=$2 cmd=$3
    shift 3
    has_out=0
    for a in "$@"; do [ "$a" = --out ] && has_out=1; done
    if [ "$cmd" = draw ] && [ $has_out -eq 0 ]; then set -- --out "$T/bad.svg" "$@"; fi
    $OB $cmd "$@" >/dev/null 2>"$T/e.txt"
    rc=$?
    if [ $rc -eq "$code" ] && grep -q -- "$txt" "$T/e.txt"; then ok; else bad "$cmd $* -> exit $rc (want $code), '$(cat "$T/e.txt")'"; fi
}
for cmd in draw trace; do
    expect 2 "--curve" $cmd --method tiller --tol 1e-2
    expect 2 "--curve" $cmd --curve $C,liu2002_ex2 --method tiller --tol 1e-2
    expect 2 "--curve" $cmd --curve $C --curve liu2002_ex2 --method tiller --tol 1e-2
    expect 2 "--curve" $cmd --curve no_such_curve --method tiller --tol 1e-2
    expect 2 "--method" $cmd --curve $C --method nosuch --tol 1e-2
    expect 2 "--method" $cmd --curve $C --tol 1e-2
    expect 2 "--tol" $cmd --curve $C --method tiller --tol -1
    expect 2 "--tol" $cmd --curve $C --method tiller --tol abc
    expect 2 "--tol" $cmd --curve $C --method tiller
    expect 2 "--d" $cmd --curve $C --method tiller --tol 1e-2 --d 0
    expect 2 "--d" $cmd --curve $C --method tiller --tol 1e-2 --d nan
    expect 2 "--d" $cmd --curve $C --method tiller --tol 1e-2 --d x
    expect 2 "--methods" $cmd --curve $C --methods tiller --tol 1e-2
    expect 2 "--metric" $cmd --curve $C --method tiller --tol 1e-2 --metric euclid
    expect 2 "--param" $cmd --curve $C --method tiller --tol 1e-2 --param tiller.nosuch=1
    expect 2 "missing value" $cmd --curve $C --method tiller --tol
    expect 2 "unknown option" $cmd --curve $C --method tiller --tol 1e-2 --frobnicate 1
    expect 1 "--out" $cmd --curve $C --method tiller --tol 1e-2 --out "$T"
    expect 1 "--out" $cmd --curve $C --method tiller --tol 1e-2 --out "$T/no/dir/x.svg"
done
expect 2 "--points" trace --curve $C --method tiller --tol 1e-2 --points 1
expect 2 "--points" trace --curve $C --method tiller --tol 1e-2 --points 100001
expect 2 "--points" trace --curve $C --method tiller --tol 1e-2 --points x
expect 2 "--points" draw --curve $C --method tiller --tol 1e-2 --points 8
$OB draw --curve $C --method tiller --tol 1e-2 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--out" "$T/e.txt"' "draw without --out exits 2 naming --out"
check '[ ! -e "$T/bad.svg" ]' "no SVG is left behind by a bad command line"

e2e_done
