#!/bin/sh
# End-to-end tests of ./offbench: the acceptance commands of the foundation
# issue, the CSV contract, determinism across thread counts, and clear errors
# with exit status 2 on bad input.  Uses $OFFBENCH (set by make) or ./offbench.
OB=${OFFBENCH:-./offbench}
OB=$(cd "$(dirname "$OB")" && pwd)/$(basename "$OB")
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
check() { if eval "$1"; then ok; else bad "$2"; fi; }

# column of results.csv by name
col() { awk -F, -v c="$2" 'NR==1{for(i=1;i<=NF;i++)if($i==c)k=i;next}{print $k}' "$1" | tr '\n' ' ' | sed 's/ $//'; }

# --- Liu-Wang Table 1 (Til, Cob) and Ahn Table 1 under their protocols ---
$OB run --curve liu2002_ex1 --methods tiller,cobb --metric bound --split mid \
    --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --out "$T/a" 2>"$T/a.err"
check '[ $? -eq 0 ] && [ -f "$T/a/results.csv" ] && [ -f "$T/a/meta.json" ]' "run exits 0 and writes both files"
got=$(awk -F, 'NR>1 && $2==1 {printf "%s:%s ", $3, $7}' "$T/a/results.csv")
want="tiller:10 tiller:31 tiller:97 tiller:322 tiller:886 cobb:10 cobb:31 cobb:94 cobb:316 cobb:865 "
check '[ "$got" = "$want" ]' "Liu-Wang Til/Cob d=1: got '$got'"
got=$(awk -F, 'NR>1 && $2==-1 {printf "%s:%s ", $3, $7}' "$T/a/results.csv")
check '[ "$got" = "$want" ]' "Liu-Wang Til/Cob d=-1: got '$got'"

$OB run --curve liu2002_ex1 --methods ahn --metric radial --split mid \
    --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --out "$T/b" 2>/dev/null
got=$(awk -F, 'NR>1 {printf "%s ", $7}' "$T/b/results.csv")
check '[ "$got" = "13 19 31 43 61 13 19 31 43 61 " ]' "Ahn Table 1 'Our method': got '$got'"

# --- the CSV contract ---
hdr=$(head -n 1 "$T/a/results.csv")
check '[ "$hdr" = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message" ]' "header: $hdr"
check '[ "$(col "$T/a/results.csv" tol | cut -d" " -f1-5)" = "0.1 0.01 0.001 0.0001 1e-05" ]' "tolerances printed exactly"
for k in git_commit compiler cflags omp_threads samples_per_segment argv timestamp; do
    check 'grep -q "\"$k\"" "$T/a/meta.json"' "meta.json has $k"
done
check 'python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$T/a/meta.json" 2>/dev/null || ! command -v python3 >/dev/null' "meta.json is valid JSON"

# --- default job, every status valid, identical for 1 and 2 threads ---
$OB run --tols 1e-1,1e-3 --threads 1 --out "$T/t1" 2>/dev/null
r1=$?
$OB run --tols 1e-1,1e-3 --threads 2 --out "$T/t2" 2>/dev/null
check '[ $r1 -eq 0 ] && [ $? -eq 0 ]' "default runs exit 0"
cut -d, -f1-11,14 "$T/t1/results.csv" > "$T/t1.cut"
cut -d, -f1-11,14 "$T/t2/results.csv" > "$T/t2.cut"
check 'cmp -s "$T/t1.cut" "$T/t2.cut"' "--threads 1 and 2 give identical results apart from timings"
n=$(($(wc -l < "$T/t1/results.csv") - 1))
check '[ $n -eq $((5 * 3 * 2)) ]' "default run: 5 offsets x 3 methods x 2 tols = 30 rows, got $n"
check '[ -z "$(col "$T/t1/results.csv" status | tr " " "\n" | grep -vE "^(ok|limit|fail|skip)$")" ]' "status values"

# the embedded data: a copy of the program with no datasets/ in reach
cp "$OB" "$T/offbench-copy"
(cd "$T" && unset OFFBENCH_DATA && ./offbench-copy list curves > "$T/lc.txt" 2>&1)
check 'grep -q "^# curves from embedded" "$T/lc.txt"' "away from the tree the embedded curves are used: $(head -n 1 "$T/lc.txt")"
(cd "$T" && unset OFFBENCH_DATA && ./offbench-copy run --methods cobb --tols 1e-1 --out emb >/dev/null 2>&1)
check '[ $(($(wc -l < "$T/emb/results.csv") - 1)) -eq 5 ]' "a run on the embedded curves writes 5 rows"
for id in liu2002_ex1 liu2002_ex2 zhao2017_septic zhao2017_quintic; do
    check 'grep -q "^$id " "$T/lc.txt"' "curve $id is listed"
done
$OB list methods > "$T/lm.txt"
for m in tiller cobb ahn; do check 'grep -q "^$m " "$T/lm.txt"' "method $m is listed"; done

# --- bad input: exit 2 and a message naming the file and line or the option ---
printf 'curve ok\n  bezier 2\n  point 0 0\n  point 1 oops\n  point 2 0\n  offset 1\nend\n' > "$T/bad.curves"
$OB run --curves "$T/bad.curves" --out "$T/c" 2>"$T/bad.err"
check '[ $? -eq 2 ]' "malformed curve file exits 2"
check 'grep -q "bad.curves:4:" "$T/bad.err"' "message names FILE:LINE: $(cat "$T/bad.err")"
check '[ ! -e "$T/c/results.csv" ]' "no results are written for a malformed file"

expect2() {  # args: expected text in stderr, then the run options
    want_txt=$1; shift
    $OB run --out "$T/x" "$@" >/dev/null 2>"$T/e.txt"
    rc=$?
    if [ $rc -eq 2 ] && grep -q -- "$want_txt" "$T/e.txt"; then ok; else bad "run $* -> exit $rc, '$(cat "$T/e.txt")'"; fi
}
expect2 "--methods" --methods tiller,nosuch
expect2 "--metric" --metric euclid
expect2 "--split" --split half
expect2 "--tols" --tols 1e-2,-1
expect2 "--tols" --tols 1e-2,abc
expect2 "--tols" --tols nan
expect2 "--threads" --threads 0
expect2 "--curve" --curve no_such_curve
expect2 "--samples" --samples 3
expect2 "missing value" --tols
expect2 "unknown option" --frobnicate 1
expect2 "--backend" --backend gpu
expect2 "--param" --param tiller.nosuch=1
expect2 "--param" --param nosuch.x=1
expect2 "--param" --param tiller
$OB frobnicate >/dev/null 2>&1
check '[ $? -eq 2 ]' "unknown command exits 2"
$OB list nothing >/dev/null 2>&1
check '[ $? -eq 2 ]' "list of an unknown subject exits 2"

# an unwritable output directory is a run-time failure (1), after a message
if [ "$(id -u)" != 0 ]; then
    mkdir "$T/ro" && chmod 500 "$T/ro"
    $OB run --curve liu2002_ex1 --methods tiller --tols 1e-1 --out "$T/ro/sub" 2>"$T/ro.err"
    check '[ $? -eq 1 ]' "unwritable --out exits 1"
fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
