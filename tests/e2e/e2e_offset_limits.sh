#!/bin/sh
# Two rules every command applies alike:
# - An offset distance d is checked once, by the curve file format's rule
#   (host/io/curvefile.h ob_offset_check): `draw`, `trace` and `measure`
#   refuse a --d that a curve file's `offset` line would refuse (0, |d| below
#   1e-50 or above 1e12, |d| below 1e-12 times the curve's largest
#   coordinate), exit 2 naming --d and the curve's FILE:LINE, and take the
#   values at the limits; the file and the commands agree on every value.
# - An error that is not finite is never `ok` (methods/metrics/metric.h
#   ob_err_can_pass): measure reports it `fail` with a reason; compare and
#   merge refuse a results.csv row `ok` with max_err inf or nan (exit 2
#   naming FILE:LINE).
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
B="--backend cpu --threads 2"
J="--method tiller --tol 1e-1 --max-segments 8"

printf 'curve big\n  source scale 2e6\n  bezier 2\n  point 0 0\n  point 1e6 1e6\n  point 2e6 0\n  offset 1\nend\n' > "$T/big.curves"
"$OB" run --curves "$T/big.curves" --methods tiller --tols 1e-1 $B --out "$T/rb" --export "$T/xb" 2>/dev/null
check '[ $? -eq 0 ]' "the big curve runs at d = 1"
BJ="$T/xb/big__d1__tiller__tol0.1.json"

# refused: exit 2, naming --d and the curve's file and line, no output
refused_d() {  # refused_d D CURVE-OPTIONS...
    d=$1; shift
    for cmd in draw trace measure; do
        case $cmd in
            draw) args="$J $B --out $T/o.svg" ;;
            trace) args="$J $B --out $T/o.csv" ;;
            measure) args="--approx $AP" ;;
        esac
        rm -f "$T/o.svg" "$T/o.csv"
        "$OB" $cmd "$@" --d "$d" $args >"$T/out" 2>"$T/err"
        rc=$?
        check '[ $rc -eq 2 ] && grep -q -- "$cmd: --d: curve .*$WHERE" "$T/err" && [ ! -e "$T/o.svg" ] && [ ! -e "$T/o.csv" ] && [ ! -s "$T/out" ]' \
            "$cmd --d $d: exit $rc: $(cat "$T/err")"
    done
}
taken_d() {  # taken_D D CURVE-OPTIONS...
    d=$1; shift
    for cmd in draw trace measure; do
        case $cmd in
            draw) args="$J $B --out $T/o.svg" ;;
            trace) args="$J $B --points 2 --out $T/o.csv" ;;
            measure) args="--approx $AP --metric hausdorff" ;;
        esac
        "$OB" $cmd "$@" --d "$d" $args >/dev/null 2>"$T/err"
        rc=$?
        check '[ $rc -eq 0 ]' "$cmd --d $d is within the limits: exit $rc: $(cat "$T/err")"
    done
}

AP=$BJ WHERE="/big.curves:1): offset .* below 1e-12 times its largest coordinate 2e+06"
for d in 1e-7 -1e-7 1.9e-6 -1.99e-6; do refused_d $d --curves "$T/big.curves" --curve big; done
for d in 2e-6 -2e-6; do taken_d $d --curves "$T/big.curves" --curve big; done

"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-1 $B --out "$T/rl" --export "$T/xl" 2>/dev/null
AP="$T/xl/liu2002_ex1__d1__tiller__tol0.1.json"
WHERE="(datasets/published.curves:[0-9]*): offset distance .* is too small"
for d in 1e-60 -1e-51 9.99e-51; do refused_d $d --curve liu2002_ex1; done
WHERE="(datasets/published.curves:[0-9]*): offset distance .* is too large"
for d in 1e13 -1.000001e12; do refused_d $d --curve liu2002_ex1; done
# at the limits: measure only (a run at d = 1e12 is no quick test); the
# curve's coordinates reach 2.5, so its smallest |d| is 2.5e-12
for d in 2.5e-12 -1e12; do
    "$OB" measure --curve liu2002_ex1 --d $d --approx "$AP" --metric hausdorff >/dev/null 2>"$T/err"
    check '[ $? -eq 0 ]' "measure --d $d (a limit) is taken: $(cat "$T/err")"
done
# random curves: the same limits (their coordinates are in the unit box)
AP="$T/xl/liu2002_ex1__d1__tiller__tol0.1.json" WHERE="rnd1_000001': offset distance .* too small"
refused_d 1e-55 --random 3 --curve rnd1_000001
WHERE="(datasets/published.curves:[0-9]*): offset .* below 1e-12 times its largest coordinate 2.5"
for d in 1e-50 2.4e-12; do refused_d $d --curve liu2002_ex1; done
# d = 0 and non-numbers stay the option parser's refusals
for cmd in draw trace measure; do
    "$OB" $cmd --curve liu2002_ex1 --d 0 $J --approx "$AP" --out "$T/o.x" >/dev/null 2>"$T/err"
    check '[ $? -eq 2 ] && grep -q -- "--d" "$T/err"' "$cmd --d 0: $(cat "$T/err")"
done
# the file and the commands agree on every value, at the big curve's scale
for d in 1e-7 1.99e-6 2e-6 1e-3 1 1e12 1.1e12; do
    sed "s/offset 1/offset $d/" "$T/big.curves" > "$T/bd.curves"
    "$OB" list curves --curves "$T/bd.curves" >/dev/null 2>&1; file_rc=$?
    "$OB" measure --curves "$T/big.curves" --curve big --d $d --approx "$BJ" --metric hausdorff >/dev/null 2>&1; cmd_rc=$?
    check '[ $file_rc -eq $cmd_rc ] && { [ $file_rc -eq 0 ] || [ $file_rc -eq 2 ]; }' \
        "d = $d: the curve file exits $file_rc, measure --d exits $cmd_rc"
done

# ---- an error that is not finite is never ok ----------------------------------
J1="$T/xl/liu2002_ex1__d1__tiller__tol0.1.json"
"$PY" - "$J1" "$T/pole.json" <<'PYEOF'
import json, sys
d = json.load(open(sys.argv[1]))
p = d['pieces'][0]
w = [1, -1, 1, 1][:len(p['points'])]
p['weights'], p['rational'] = w, True
p['homogeneous'] = [[q[0] * wi, q[1] * wi, wi] for q, wi in zip(p['points'], w)]
json.dump(d, open(sys.argv[2], 'w'), indent=1)
PYEOF
"$OB" measure --curve liu2002_ex1 --d 1 --approx "$T/pole.json" > "$T/m.csv" 2>"$T/err"
check '[ $? -eq 0 ] && grep -q "^bound,fail,inf,.*not finite" "$T/m.csv"' "measure: bound inf is fail, not ok: $(cat "$T/m.csv")"
check '! awkc "\$c[\"status\"] == \"ok\" && \$c[\"max_err\"] !~ /^[0-9.e+-]+$/ {print}" "$T/m.csv" | grep -q .' \
    "no ok row without a finite max_err"
"$OB" measure --curve liu2002_ex1 --d 1 --approx "$T/pole.json" --metric bound > "$T/m1.csv" 2>/dev/null
check '[ $? -eq 0 ] && [ $(wc -l < "$T/m1.csv") -eq 2 ] && grep -q "^bound,fail," "$T/m1.csv"' "--metric bound alone: fail"
"$OB" measure --curve liu2002_ex1 --d 1 --approx "$J1" --metric bound > "$T/m2.csv" 2>/dev/null
check 'grep -q "^bound,ok,[0-9]" "$T/m2.csv"' "the unedited file: bound ok: $(cat "$T/m2.csv")"

# readers: a results.csv row ok with a max_err that is not finite is refused
for v in inf nan ""; do
    mkdir -p "$T/bad$v"
    cp "$T/rl/meta.json" "$T/bad$v/"
    awkc 'BEGIN{OFS=","} NR==2{$c["max_err"]=e} {print}' e="$v" "$T/rl/results.csv" > "$T/bad$v/results.csv"
    "$OB" compare "$T/rl" "$T/bad$v" --no-timing >/dev/null 2>"$T/err"
    check '[ $? -eq 2 ] && grep -q "bad$v/results.csv:2: .*status ok with a max_err that is not a finite number" "$T/err"' \
        "compare: an ok row with max_err '$v': $(cat "$T/err")"
done
R="--curve liu2002_ex1 --methods tiller --tols 1e-1,1e-2 $B"
for k in 0 1; do "$OB" run $R --shard $k/2 --out "$T/s$k" 2>/dev/null; done
awkc 'BEGIN{OFS=","} NR==2{$c["max_err"]="inf"} {print}' "$T/s1/results.csv" > "$T/r.tmp" && mv "$T/r.tmp" "$T/s1/results.csv"
"$OB" merge "$T/s0" "$T/s1" --out "$T/m" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "s1/results.csv:2: .*never ok" "$T/err" && [ ! -e "$T/m/results.csv" ]' \
    "merge: a shard's ok row with max_err inf: $(cat "$T/err")"
# a row limit with an infinite error is a result, read as one
awkc 'BEGIN{OFS=","} NR==2{$c["max_err"]="inf"; $c["status"]="limit"} {print}' "$T/rl/results.csv" > "$T/badinf/results.csv"
"$OB" compare "$T/rl" "$T/badinf" --no-timing >/dev/null 2>"$T/err"
check '[ $? -eq 1 ]' "compare: ok -> limit with inf is a regression: exit $? $(cat "$T/err")"

e2e_done
