#!/bin/sh
# Input the program must refuse (issue 16, "Results you can trust"): every
# case exits 2 before any work, writes no results.csv, and its message names
# the option or FILE:LINE.  Covers duplicate job keys, unbounded or
# non-regular input files, out-of-range method parameters, repeated options
# and curves whose scale the metrics' double arithmetic cannot measure.
. "$(dirname "$0")/lib_e2e.sh"

# without a sanitizer a runaway read is also stopped by a memory limit
lim=""
case "$OB" in *build-san*|*build-fuzz*) ;; *) lim="ulimit -v 4000000;" ;; esac
# refused WHAT PATTERN ARGS...: `offbench ARGS` exits 2 within 20 s, with
# PATTERN (fixed string) in its message, no results.csv under $T/o and no
# sanitizer report.
refused() {
    what=$1 pat=$2; shift 2
    rm -rf "$T/o"
    (eval "$lim"; timeout 20 "$OB" "$@" >/dev/null 2>"$T/err")
    rc=$?
    if [ $rc -eq 2 ] && grep -q -F -- "$pat" "$T/err" && [ ! -e "$T/o/results.csv" ] \
       && ! grep -q -E "Sanitizer|runtime error" "$T/err"; then ok; else
        bad "$what: exit $rc, expected 2 and '$pat' in: $(head -c 300 "$T/err")"; fi
}
RUN="run --curve liu2002_ex1 --methods tiller --tols 1e-1 --out $T/o"

# ---- 5: duplicate job keys ------------------------------------------------
refused "--tols 1e-2,0.01" "--tols" run --curve liu2002_ex1 --methods tiller --tols 1e-2,0.01 --out "$T/o"
refused "--tols 0.1,0.1" "--tols" run --curve liu2002_ex1 --methods tiller --tols 0.1,0.1 --out "$T/o"
refused "--curve X,X" "--curve" run --curve liu2002_ex1,liu2002_ex1 --methods tiller --tols 1e-1 --out "$T/o"
cat > "$T/dup1.curves" <<'C'
curve dup_a
  bezier 2
  point 0 0
  point 1 1
  point 2 0
  offset 0.1 0.1
end
C
refused "offset 0.1 0.1" "$T/dup1.curves:6:" run --curves "$T/dup1.curves" --methods tiller --tols 1e-1 --out "$T/o"
cat > "$T/dup2.curves" <<'C'
curve dup_b
  bezier 2
  point 0 0
  point 1 1
  point 2 0
  offset 0.1 -0.2
  offset 1e-1
end
C
refused "offset repeated on another line" "$T/dup2.curves:7:" run --curves "$T/dup2.curves" --methods tiller --tols 1e-1 --out "$T/o"

# ---- 6: unbounded readers, non-regular files -----------------------------
"$OB" $RUN >/dev/null 2>&1 && mkdir -p "$T/base" && cp "$T/o/results.csv" "$T/o/meta.json" "$T/base/"
check '[ -s "$T/base/results.csv" ]' "a run to compare against"
cmp_refused() {
    what=$1 pat=$2; shift 2
    (eval "$lim"; timeout 20 "$OB" compare "$@" >/dev/null 2>"$T/err")
    rc=$?
    if [ $rc -eq 2 ] && grep -q -F -- "$pat" "$T/err" && ! grep -q -E "Sanitizer|runtime error" "$T/err"; then ok; else
        bad "$what: exit $rc, expected 2 and '$pat' in: $(head -c 300 "$T/err")"; fi
}
cmp_refused "compare BASE /dev/zero" "/dev/zero: not a regular file" "$T/base/results.csv" /dev/zero
mkdir -p "$T/zero" && ln -s /dev/zero "$T/zero/results.csv" && cp "$T/base/meta.json" "$T/zero/"
cmp_refused "compare BASE DIR with results.csv -> /dev/zero" "not a regular file" "$T/base" "$T/zero"
mkdir -p "$T/zmeta" && cp "$T/base/results.csv" "$T/zmeta/" && ln -s /dev/zero "$T/zmeta/meta.json"
cmp_refused "compare BASE DIR with meta.json -> /dev/zero" "meta.json: not a regular file" "$T/base" "$T/zmeta"
mkfifo "$T/fifo.csv" 2>/dev/null && cmp_refused "compare BASE FIFO" "fifo.csv: not a regular file" "$T/base/results.csv" "$T/fifo.csv"
# a (sparse) results.csv beyond the cap is refused from its size
mkdir -p "$T/big" && cp "$T/base/meta.json" "$T/big/" && truncate -s 1100M "$T/big/results.csv"
cmp_refused "compare BASE results.csv over the cap" "too large" "$T/base" "$T/big"
rm -f "$T/big/results.csv"
# the journal of --resume
mkdir -p "$T/jr" && cp "$T/base/meta.json" "$T/jr/" && ln -s /dev/zero "$T/jr/results.journal.csv"
refused "--resume with journal -> /dev/zero" "not a regular file" run --curve liu2002_ex1 --methods tiller --tols 1e-1 --resume "$T/jr"
# shard.csv of merge
"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-1 --shard 0/2 --out "$T/s0" >/dev/null 2>&1
"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-1 --shard 1/2 --out "$T/s1" >/dev/null 2>&1
rm -f "$T/s1/shard.csv" && ln -s /dev/zero "$T/s1/shard.csv"
(eval "$lim"; timeout 20 "$OB" merge "$T/s0" "$T/s1" --out "$T/m" >/dev/null 2>"$T/err")
rc=$?
if [ $rc -eq 2 ] && grep -q -F "shard.csv: not a regular file" "$T/err"; then ok; else
    bad "merge with shard.csv -> /dev/zero: exit $rc: $(head -c 300 "$T/err")"; fi

# ---- 8: method parameters ---------------------------------------------------
for p in elber.iterations=-1 elber.iterations=2.5 liu.nodes=0 chebyshev.nodes=1025 lee.tol_frac=-5 \
         zhao.degree=99 exact.detect_tol=-1 sisl.timeout=0 coquillart.reading=4 hoschek.samples=-1 \
         lstsq.target=0.5 zhao.npfac=17 elber.rounds=nan; do
    name=${p%%=*}
    refused "--param $p" "--param $name" $RUN --param "$p"
done
grep -q -F "range" "$T/err" && ok || bad "--param: the message gives the range: $(cat "$T/err")"
# a long value is read whole, not truncated to 255 characters
z=$(printf '%0300d' 0)
rm -rf "$T/o"
"$OB" $RUN --param "elber.iterations=${z}3" >/dev/null 2>"$T/err"
rc=$?
if [ $rc -eq 0 ] && grep -q '"elber.iterations": 3,' "$T/o/meta.json"; then ok; else
    bad "--param with a 300-character value: exit $rc, $(grep -o '"elber.iterations": [^,]*' "$T/o/meta.json" 2>/dev/null) $(head -c 200 "$T/err")"; fi

# ---- 11: repeated options ---------------------------------------------------
refused "--tols twice" "--tols" $RUN --tols 1e-2
refused "--metric twice" "--metric" $RUN --metric radial --metric bound
refused "--samples twice" "--samples" $RUN --samples 64 --samples 128
refused "--curve twice" "--curve" $RUN --curve liu2002_ex2
refused "--methods twice" "--methods" $RUN --methods cobb
refused "--param M.N twice" "--param elber.iterations" $RUN --param elber.iterations=3 --param elber.iterations=4
# ... and in the other commands
cmp_refused "compare --format twice" "--format: given twice" "$T/base" "$T/base" --format md --format csv
cmp_refused "compare --err-rtol twice" "--err-rtol: given twice" "$T/base" "$T/base" --err-rtol=0.1 --err-rtol 0.2
refused "tables --protocols twice" "--protocols: given twice" tables --protocols paper --protocols best --out "$T/o"
refused "list curves --curves twice" "--curves: given twice" list curves --curves datasets/published.curves --curves datasets/reference.curves
refused "draw --d twice" "--d: given twice" draw --curve liu2002_ex1 --method tiller --tol 1e-1 --d 1 --d -1 --out "$T/o.svg"
refused "draw --out twice" "--out: given twice" draw --curve liu2002_ex1 --method tiller --tol 1e-1 --out "$T/a.svg" --out "$T/b.svg"
refused "trace --points twice" "--points: given twice" trace --curve liu2002_ex1 --method tiller --tol 1e-1 --points 10 --points 20
# different parameters may be given side by side
rm -rf "$T/o"
"$OB" $RUN --param elber.iterations=3 --param elber.update=1 >/dev/null 2>"$T/err"
check '[ $? -eq 0 ] && [ -s "$T/o/results.csv" ]' "--param for two parameters: $(head -c 200 "$T/err")"

# ---- 10: curves beyond the scale the metrics can measure -------------------
mk() {  # mk NAME X1 Y1 X2 Y2 X3 Y3 D
    printf 'curve %s\n  bezier 2\n  point %s %s\n  point %s %s\n  point %s %s\n  offset %s\nend\n' "$@" > "$T/$1.curves"
}
mk tiny 0 0 1e-160 1e-160 2e-160 0 1e-161
refused "extent 1e-160" "$T/tiny.curves:4:" run --curves "$T/tiny.curves" --methods ahn,hoschek,kim2018 --tols 1e-1 --out "$T/o"
mk smallext 1e-49 1e-49 1.01e-49 1.02e-49 1.02e-49 1e-49 1e-49
refused "extent 2e-51 (coordinates above 1e-50)" "$T/smallext.curves:1:" run --curves "$T/smallext.curves" --methods ahn --tols 1e-1 --out "$T/o"
mk smalld 0 0 1e6 1e6 2e6 0 1e-7
refused "offset below 1e-12 of the coordinates" "$T/smalld.curves:1:" run --curves "$T/smalld.curves" --methods ahn --tols 1e-1 --out "$T/o"
mk denorm 0 0 1 1e-310 2 0 0.1
refused "denormal coordinate" "$T/denorm.curves:4:" run --curves "$T/denorm.curves" --methods ahn --tols 1e-1 --out "$T/o"
mk smallco 0 0 1 1e-101 2 0 0.1
refused "coordinate below 1e-100" "$T/smallco.curves:4:" run --curves "$T/smallco.curves" --methods ahn --tols 1e-1 --out "$T/o"
mk tinyd 0 0 1 1 2 0 1e-120
refused "offset below 1e-100" "$T/tinyd.curves:6:" run --curves "$T/tinyd.curves" --methods ahn --tols 1e-1 --out "$T/o"
mk flat 1e6 1e6 1e6 1.0000000000001e6 1e6 1e6 0.1
refused "extent below 1e-12 of the coordinates" "$T/flat.curves:1:" run --curves "$T/flat.curves" --methods ahn --tols 1e-1 --out "$T/o"
rm -f "$T/t.svg"
timeout 20 "$OB" draw --curves "$T/tiny.curves" --curve tiny --method ahn --tol 1e-1 --out "$T/t.svg" >/dev/null 2>"$T/err"
rc=$?
if [ $rc -eq 2 ] && grep -q -F "$T/tiny.curves:4:" "$T/err" && ! grep -q nan "$T/t.svg" 2>/dev/null; then ok; else
    bad "draw of the tiny curve: exit $rc: $(head -c 200 "$T/err")"; fi
# the limits themselves are accepted: extent, coordinates and d at 1e-50
mk edge 0 0 1e-50 1e-50 2e-50 0 1e-50
rm -rf "$T/o"
"$OB" run --curves "$T/edge.curves" --methods tiller --tols 1e-1 --out "$T/o" >/dev/null 2>"$T/err"
check '[ $? -eq 0 ] && [ -s "$T/o/results.csv" ]' "a curve at the scale limits is accepted: $(head -c 200 "$T/err")"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
