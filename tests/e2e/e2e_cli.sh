#!/bin/sh
# End-to-end tests of ./offbench: the acceptance commands of the foundation
# issue, the CSV contract, determinism across thread counts, and clear errors
# with exit status 2 on bad input.  Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

# column of results.csv by name, the rows on one line
col() { rcols "$1" "$2" | tr '\n' ' ' | sed 's/ $//'; }
# the job keys and results: what results.csv's first 11 columns hold
KR="curve d method metric split tol ctrl_points segments out_degree max_err status"

# --- Liu-Wang Table 1 (Til, Cob) and Ahn Table 1 under their protocols ---
$OB run --curve liu2002_ex1 --methods tiller,cobb --metric bound --split mid \
    --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --out "$T/a" 2>"$T/a.err"
check '[ $? -eq 0 ] && [ -f "$T/a/results.csv" ] && [ -f "$T/a/meta.json" ]' "run exits 0 and writes both files"
got=$(awkc 'NR>1 && $c["d"]==1 {printf "%s:%s ", $c["method"], $c["ctrl_points"]}' "$T/a/results.csv")
want="tiller:10 tiller:31 tiller:97 tiller:322 tiller:886 cobb:10 cobb:31 cobb:94 cobb:316 cobb:865 "
check '[ "$got" = "$want" ]' "Liu-Wang Til/Cob d=1: got '$got'"
got=$(awkc 'NR>1 && $c["d"]==-1 {printf "%s:%s ", $c["method"], $c["ctrl_points"]}' "$T/a/results.csv")
check '[ "$got" = "$want" ]' "Liu-Wang Til/Cob d=-1: got '$got'"

$OB run --curve liu2002_ex1 --methods ahn --metric radial --split mid \
    --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --out "$T/b" 2>/dev/null
got=$(awkc 'NR>1 {printf "%s ", $c["ctrl_points"]}' "$T/b/results.csv")
check '[ "$got" = "13 19 31 43 61 13 19 31 43 61 " ]' "Ahn Table 1 'Our method': got '$got'"

# --- the CSV contract ---
hdr=$(head -n 1 "$T/a/results.csv")
check '[ "$hdr" = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message,family,offset_degree,offset_rational,max_gap,max_kink,continuity,time_iqr_ns,time_cv,err_upper,err_lower,certified,cert_ns,fit_calls,method_ns,method_iqr_ns,trimmed_err,trimmed_cut" ]' "header: $hdr"
check '[ "$(col "$T/a/results.csv" offset_degree | tr " " "\n" | sort -u)" = "10" ] && [ "$(col "$T/a/results.csv" offset_rational | tr " " "\n" | sort -u)" = "no" ]' \
    "liu2002_ex1 (a generic cubic): offset_degree 10, not rational"
check '[ "$(col "$T/a/results.csv" tol | cut -d" " -f1-5)" = "0.1 0.01 0.001 0.0001 1e-05" ]' "tolerances printed exactly"
for k in git_commit compiler cflags omp_threads samples_per_segment argv timestamp; do
    check 'grep -q "\"$k\"" "$T/a/meta.json"' "meta.json has $k"
done
check 'python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$T/a/meta.json" 2>/dev/null || ! command -v python3 >/dev/null' "meta.json is valid JSON"

# --- the joint columns, then the spread of --reps and the certificate: measured continuity and the largest gap ---
# (the header check is by position: the column order is the contract)
J="--curve liu2002_ex1 --methods ahn,cobb,zhao-rational --tols 1e-3"
$OB run $J --backend cpu --out "$T/j" 2>/dev/null
check '[ $? -eq 0 ] && [ "$(head -n 1 "$T/j/results.csv" | cut -d, -f18-)" = "max_gap,max_kink,continuity,time_iqr_ns,time_cv,err_upper,err_lower,certified,cert_ns,fit_calls,method_ns,method_iqr_ns,trimmed_err,trimmed_cut" ]' \
    "the joint columns, then time_iqr_ns and time_cv, then the certificate's, then the method time's: $(head -n 1 "$T/j/results.csv" | cut -d, -f18-)"
got=$(rcols "$T/j/results.csv" method continuity | tr '\n' ' ')
check '[ "$got" = "ahn:G1 cobb:G0 zhao-rational:open ahn:G1 cobb:G0 zhao-rational:open " ]' "measured continuity: '$got'"
# zhao-rational's pieces are ~tol apart, and ctrl_points counts those ends twice
got=$(rcols "$T/j/results.csv" method max_gap ctrl_points segments out_degree |
      awk -F: '{ok = ($1 == "zhao-rational") ? ($2 > 1e-5 && $3 > 1 + $4 * $5) : ($2 < 1e-12 && $3 == 1 + $4 * $5); if (!ok) print}')
check '[ -z "$got" ]' "max_gap and ctrl_points of open and closed joints: '$got'"
check 'grep -q "\"joints\": {\"open_gap_rel\": 9.9999999999999998e-13" "$T/j/meta.json" && grep -q "\"g1_kink_rad\"" "$T/j/meta.json"' \
    "meta.json names the joint thresholds"
if $OB run $J --backend opencl --out "$T/jcl" 2>/dev/null; then
    body "$T/jcl/results.csv" > "$T/jcl.txt"
    check 'body "$T/j/results.csv" | cmp -s - "$T/jcl.txt"' "--backend opencl and cpu give the same results, joints included"
    check 'grep -q "\"layout\": \"\(groups\|items\)\", \"work_items_per_record\": [1-9]" "$T/jcl/meta.json"' "meta.json: the kernel's layout"
    for lay in groups items; do
        OFFBENCH_CL_LAYOUT=$lay $OB run $J --backend opencl --out "$T/j$lay" 2>/dev/null
        check '[ $? -eq 0 ] && body "$T/j$lay/results.csv" | cmp -s - "$T/jcl.txt" && grep -q "\"layout\": \"$lay\"" "$T/j$lay/meta.json"' \
            "OFFBENCH_CL_LAYOUT=$lay: the same results, recorded in meta.json"
    done
else
    skipped=$((skipped + 4))
fi
msg=$(OFFBENCH_CL_LAYOUT=rows $OB run $J --out "$T/jbad" 2>&1)
check '[ $? -eq 2 ] && echo "$msg" | grep -q "OFFBENCH_CL_LAYOUT=.rows.: expected groups or items"' \
    "a bad OFFBENCH_CL_LAYOUT is an error even under --backend auto: $msg"

# --- default job, every status valid, identical for 1 and 2 threads ---
# (a fixed set of methods of every kind keeps the run time independent of how
# many methods are registered; the nesting is curve x d x method x tol)
DM=tiller,cobb,ahn,liu,zhao
$OB run --methods $DM --tols 1e-1,1e-3 --threads 1 --out "$T/t1" 2>/dev/null
r1=$?
$OB run --methods $DM --tols 1e-1,1e-3 --threads 2 --out "$T/t2" 2>/dev/null
check '[ $r1 -eq 0 ] && [ $? -eq 0 ]' "default runs exit 0"
dropcols "$T/t1/results.csv" fit_ns eval_ns > "$T/t1.cut"
dropcols "$T/t2/results.csv" fit_ns eval_ns > "$T/t2.cut"
check 'cmp -s "$T/t1.cut" "$T/t2.cut"' "--threads 1 and 2 give identical results apart from timings"
n=$(($(wc -l < "$T/t1/results.csv") - 1))
pairs=$(awkc 'NR>1{print $c["curve"]","$c["d"]}' "$T/t1/results.csv" | sort -u | wc -l)
check '[ $pairs -ge 5 ] && [ $n -eq $((pairs * 5 * 2)) ]' "default run: $pairs (curve, d) pairs x 5 methods x 2 tols, got $n rows"
per=$(awkc 'NR>1{print $c["curve"]","$c["d"]}' "$T/t1/results.csv" | uniq -c | awk '{print $1}' | sort -u)
check '[ "$per" = "10" ]' "each (curve, d) has its 10 rows together: '$per'"
check '[ -z "$(col "$T/t1/results.csv" status | tr " " "\n" | grep -vE "^(ok|limit|fail|skip)$")" ]' "status values"

check '[ "$(col "$T/a/results.csv" family | tr " " "\n" | sort -u)" = "published" ]' "liu2002_ex1 has family 'published'"
check 'grep -q "\"seed\": null" "$T/t1/meta.json"' "meta.json: seed null without --random"

# --- random test families ---
# (dropcols finds fit_ns and eval_ns by name; a quoted message may hold
# commas, the helpers keep it whole.  --max-segments bounds the time should a method grind
# on a nearly degenerate curve: that shows as `limit`, not as a slow test.)
$OB run --random 24:3 --tols 1e-1,1e-2 --max-segments 2000 --threads 1 --out "$T/r1" 2>/dev/null
r1=$?
$OB run --random 24:3 --tols 1e-1,1e-2 --max-segments 2000 --threads 2 --out "$T/r2" 2>/dev/null
check '[ $r1 -eq 0 ] && [ $? -eq 0 ]' "--random 24:3 runs exit 0"
dropcols "$T/r1/results.csv" fit_ns eval_ns > "$T/r1.cut"
dropcols "$T/r2/results.csv" fit_ns eval_ns > "$T/r2.cut"
check '[ -s "$T/r1.cut" ] && cmp -s "$T/r1.cut" "$T/r2.cut"' "--random 24:3: --threads 1 and 2 give identical results apart from timings"
check '[ -z "$(col "$T/r1/results.csv" status | tr " " "\n" | grep -vE "^(ok|limit|fail|skip)$")" ]' "--random 24:3: status values"
check '[ "$(col "$T/r1/results.csv" curve | tr " " "\n" | sort -u | wc -l)" -eq 24 ]' "--random 24:3: 24 curves in results.csv"
check '[ "$(rcols "$T/r1/results.csv" curve | sort -u | head -n 1)" = "rnd3_000000" ]' "random ids: rnd3_000000 ..."
fams=$(rcols "$T/r1/results.csv" family | sort -u | tr '\n' ' ')
check '[ "$fams" = "cubic degenerate inflection loop quintic rational septic tight " ]' "every family in the family column: '$fams'"
check 'grep -q "\"seed\": 3," "$T/r1/meta.json"' "meta.json records the seed"
check 'python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$T/r1/meta.json" 2>/dev/null || ! command -v python3 >/dev/null' "meta.json with a seed is valid JSON"

$OB list curves --random 16:7 > "$T/lr16.txt"
check '[ $? -eq 0 ] && [ $(grep -c "^rnd7_" "$T/lr16.txt") -eq 16 ]' "list curves --random 16:7 lists 16 curves"
check 'grep -qE "^rnd7_000006 +loop +1 +3 " "$T/lr16.txt"' "list shows id, family, segments, degree"
$OB list curves --random 100:7 | grep "^rnd7_" | head -n 16 > "$T/lr100.txt"
check 'grep "^rnd7_" "$T/lr16.txt" | cmp -s - "$T/lr100.txt"' "curve i of --random 100:7 is curve i of --random 16:7"
$OB list curves --random 16 | grep -q "^rnd1_000015 "
check '[ $? -eq 0 ]' "the default seed is 1"

# with --curves both are loaded (the file first); --curve picks among them
$OB run --curves datasets/published.curves --random 8:2 --curve rnd2_000005,liu2002_ex1 \
    --methods cobb --tols 1e-1 --out "$T/rc" 2>/dev/null
check '[ $? -eq 0 ]' "--curves with --random and --curve runs"
got=$(rcols "$T/rc/results.csv" curve family | awk '!s[$0]++' | tr '\n' ' ')
check '[ "$got" = "liu2002_ex1:published rnd2_000005:tight " ]' "file curves first, then the selected random one: '$got'"
$OB run --random 8:2 --curve rnd2_000008 --out "$T/rx" >/dev/null 2>"$T/rx.err"
check '[ $? -eq 2 ] && grep -q -- "--curve" "$T/rx.err"' "--curve naming a random curve past N exits 2"

# the embedded data: a copy of the program with no datasets/ in reach
cp "$OB" "$T/offbench-copy"
(cd "$T" && unset OFFBENCH_DATA && ./offbench-copy list curves > "$T/lc.txt" 2>&1)
check 'grep -q "^# curves from embedded" "$T/lc.txt"' "away from the tree the embedded curves are used: $(head -n 1 "$T/lc.txt")"
(cd "$T" && unset OFFBENCH_DATA && ./offbench-copy run --methods cobb --tols 1e-1 --out emb >/dev/null 2>&1)
$OB run --methods cobb --tols 1e-1 --out "$T/tree" >/dev/null 2>&1
csvcols "$T/emb/results.csv" $KR > "$T/emb.cut"
csvcols "$T/tree/results.csv" $KR > "$T/tree.cut"
check '[ -s "$T/emb.cut" ] && cmp -s "$T/emb.cut" "$T/tree.cut"' "the embedded curves give the same rows as datasets/"
for id in liu2002_ex1 liu2002_ex2 zhao2017_septic zhao2017_quintic; do
    check 'grep -q "^$id " "$T/lc.txt"' "curve $id is listed"
done
$OB list methods > "$T/lm.txt"
for m in tiller cobb ahn; do check 'grep -q "^$m " "$T/lm.txt"' "method $m is listed"; done

# --- --reps: a warm-up, N timed runs, samples.csv, medians in results.csv ---
$OB run --curve liu2002_ex1 --methods tiller,ahn --tols 1e-1,1e-3 --reps 3 --out "$T/reps" 2>/dev/null
check '[ $? -eq 0 ] && [ -f "$T/reps/samples.csv" ]' "--reps 3 writes samples.csv"
check '[ "$(head -n 1 "$T/reps/samples.csv")" = "curve,d,method,metric,split,tol,rep,fit_ns,eval_ns" ]' "samples.csv header"
njobs=$(($(wc -l < "$T/reps/results.csv") - 1))
check '[ $(($(wc -l < "$T/reps/samples.csv") - 1)) -eq $((3 * njobs)) ] && [ $njobs -eq 8 ]' "samples.csv: 3 rows per job"
# the timing columns are the medians of the repetitions (of 3: sum - min - max)
med=$(awkc 'function m3(x,y,z){ return x+y+z-(x<y?(x<z?x:z):(y<z?y:z))-(x>y?(x>z?x:z):(y>z?y:z)) }
     NR>1{k=$c["curve"]","$c["d"]","$c["method"]","$c["metric"]","$c["split"]","$c["tol"]
          n[k]++; f[k,n[k]]=$c["fit_ns"]; e[k,n[k]]=$c["eval_ns"]; if(n[k]==1) ks[++nk]=k}
     END{for(i=1;i<=nk;i++){k=ks[i]; print k","m3(f[k,1],f[k,2],f[k,3])","m3(e[k,1],e[k,2],e[k,3])}}' "$T/reps/samples.csv")
got=$(csvcols "$T/reps/results.csv" curve d method metric split tol fit_ns eval_ns | sed 1d)
check '[ -n "$med" ] && [ "$med" = "$got" ]' "results.csv timings are the per-job medians of samples.csv"
$OB run --curve liu2002_ex1 --methods tiller,ahn --tols 1e-1,1e-3 --out "$T/noreps" 2>/dev/null
check '[ "$(csvcols "$T/reps/results.csv" $KR)" = "$(csvcols "$T/noreps/results.csv" $KR)" ]' "--reps gives the same results as one run"
check 'grep -q "\"reps\": 3" "$T/reps/meta.json" && grep -q "\"method_versions\": {\"tiller\": 1" "$T/reps/meta.json"' "meta.json: reps and method_versions"
check 'grep -q "\"rep_mismatches\": 0" "$T/reps/meta.json"' "repetitions agree with the warm-up"

# --- --job-timeout: a job past its budget ends with status timeout; the rest go on ---
$OB run --curve liu2002_ex1 --methods tiller,ahn --tols 1e3,1e-5 --job-timeout 1e-6 --out "$T/jt" 2>"$T/jt.err"
check '[ $? -eq 0 ]' "a run with timeouts exits 0"
got=$(awkc 'NR>1 && $c["d"]==1 {printf "%s:%s:%s ", $c["method"], $c["tol"], $c["status"]}' "$T/jt/results.csv")
check '[ "$got" = "tiller:1000:ok tiller:1e-05:timeout ahn:1000:ok ahn:1e-05:timeout " ]' "timeout rows: '$got'"
check 'grep -q "job timeout: .* limit 1e-06 s" "$T/jt/results.csv" && grep -q "timeout 4;" "$T/jt.err"' \
    "timeout message in results.csv and the count on stderr"
check 'grep -q "\"job_timeout_seconds\": 1e-06" "$T/jt/meta.json"' "meta.json records the job timeout"

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
expect2 "--job-timeout" --job-timeout 0
expect2 "--job-timeout" --job-timeout -1
expect2 "--job-timeout" --job-timeout abc
expect2 "--reps" --reps 0
expect2 "--reps" --reps x
expect2 "--curve" --curve no_such_curve
expect2 "--samples" --samples 3
expect2 "missing value" --tols
expect2 "unknown option" --frobnicate 1
expect2 "--backend" --backend gpu
expect2 "--param" --param tiller.nosuch=1
expect2 "--param" --param nosuch.x=1
expect2 "--param" --param tiller
for spec in 0 abc 5: 5:x -3 10000001 1:2:3; do expect2 "--random" --random "$spec"; done
expect2 "--threads: given twice" --threads=1 --threads 2
expect2 "--force: takes no value" --force=yes
$OB run --out= >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--out: empty directory name" "$T/e.txt"' "--out= is an empty name: $(cat "$T/e.txt")"
expect2 "unexpected argument 'stray'" stray

# --- one parser for every command: --help on stdout with exit 0, --opt=value ---
for cmd in run draw trace tables; do
    $OB $cmd --help >"$T/help.out" 2>"$T/help.err"
    check '[ $? -eq 0 ] && grep -q -- "--threads N" "$T/help.out" && [ ! -s "$T/help.err" ]' \
        "$cmd --help: exit 0, the flag table on stdout: $(head -c 300 "$T/help.err")"
done
check '$OB trace --help | grep -q -- "--points N"' "trace --help lists --points"
check '! $OB draw --help | grep -q -- "--points N"' "draw --help does not list trace's --points"
for cmd in merge certify atlas bench "list" "list curves" compare; do
    $OB $cmd --help >"$T/help.out" 2>"$T/help.err"
    check '[ $? -eq 0 ] && grep -q "usage" "$T/help.out" && [ ! -s "$T/help.err" ]' "$cmd --help: exit 0 on stdout"
done
$OB list curves --random=3:7 >"$T/lc.out" 2>"$T/e.txt"
check '[ $? -eq 0 ] && grep -q rnd7_000002 "$T/lc.out"' "list curves --random=N:SEED: $(cat "$T/e.txt")"
$OB atlas --out= >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--out: empty directory name" "$T/e.txt"' "atlas --out=: refused by name"
$OB bench --quick=1 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--quick: takes no value" "$T/e.txt"' "bench --quick=1: $(cat "$T/e.txt")"

# --- the column table: list columns says what results.csv holds, in its order ---
$OB list columns >"$T/cols.out"
check '[ $? -eq 0 ] && [ "$(head -n 1 "$T/cols.out")" = "# results.csv, in this order: $(head -n 1 "$T/a/results.csv")" ]' \
    "list columns gives results.csv's header: $(head -n 1 "$T/cols.out")"
check '[ $(($(wc -l <"$T/cols.out") - 1)) -eq $(head -n 1 "$T/a/results.csv" | tr , "\n" | wc -l) ]' \
    "list columns: one line per column"

$OB run --curve=liu2002_ex1 --methods=tiller --tols=1e-2 --threads=1 --out="$T/eq" 2>/dev/null
$OB run --curve liu2002_ex1 --methods tiller --tols 1e-2 --threads 1 --out "$T/sp" 2>/dev/null
check '[ -s "$T/eq/results.csv" ] && [ "$(body "$T/eq/results.csv")" = "$(body "$T/sp/results.csv")" ]' \
    "--opt=value runs the same job as --opt value"
$OB list curves --random 0 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--random" "$T/e.txt"' "list curves --random 0 exits 2 naming the option"
$OB frobnicate >/dev/null 2>&1
check '[ $? -eq 2 ]' "unknown command exits 2"
$OB list nothing >/dev/null 2>&1
check '[ $? -eq 2 ]' "list of an unknown subject exits 2"
$OB list metrics >"$T/metrics.txt" 2>&1
check '[ $? -eq 0 ] && [ "$(cut -d" " -f1 "$T/metrics.txt" | tr "\n" " ")" = "bound radial normal hausdorff param certified " ]' \
    "list metrics: the six metrics in order"
$OB run --curve liu2002_ex1 --methods tiller,hoschek --tols 1e-2 --metric param --threads 1 --out "$T/param" 2>/dev/null
check '[ $? -eq 0 ] && [ "$(rcols "$T/param/results.csv" method metric status | sort -u | tr "\n" " ")" = "hoschek:param:ok tiller:param:ok " ]' \
    "--metric param runs every method (hoschek too), rows say param"
check 'grep -q "\"param\": \"max |(A(t) - C(t) - d N(t)) . N(t)|" "$T/param/meta.json"' "meta.json defines the param metric"

# --- tables: the published cells under the paper protocol ---
$OB tables --table liu2002:1,ahn2023:1,ahn2023:3-left,zhao2017:1 --protocols paper --out "$T/tab" 2>"$T/tab.err"
check '[ $? -eq 0 ] && [ -s "$T/tab/tables.csv" ] && [ -s "$T/tab/tables.md" ] && [ -s "$T/tab/zhao_sweep.csv" ]' \
    "tables writes tables.csv, tables.md and zhao_sweep.csv"
hdr=$(head -n 1 "$T/tab/tables.csv")
check '[ "${hdr#source,table,curve,d,tol,method,label,protocol,published,ours,ratio,status}" != "$hdr" ]' "tables.csv header: $hdr"
tab() { awkc 'NR>1 && $c["source"]==s && $c["label"]==l {printf "%s:%s ", $c["ours"], $c["status"]}' l="$1" s="$2" "$T/tab/tables.csv"; }
check '[ "$(tab Til liu2002)" = "10:match 31:match 97:match 322:match 886:match " ]' "Til under paper: $(tab Til liu2002)"
check '[ "$(tab Cob liu2002)" = "10:match 31:match 94:match 316:match 865:match " ]' "Cob under paper: $(tab Cob liu2002)"
got=$(awkc 'NR>1 && $c["source"]=="ahn2023" && $c["table"]=="1" && $c["method"]=="ahn" {printf "%s:%s ", $c["ours"], $c["status"]}' "$T/tab/tables.csv")
check '[ "$got" = "13:match 19:match 31:match 43:match 61:match " ]' "Ahn 'Our method' under paper: $got"
check '[ "$(tab Lst liu2002)" = "7:match 13:match 19:match 31:match 50:match " ]' "Liu-Wang T1 Lst (bspline-lsq) under paper: $(tab Lst liu2002)"
check '[ "$(tab Lst ahn2023)" = "7:match 13:match 19:match 31:match 50:match " ]' "Ahn T1 Lst (bspline-lsq) under paper: $(tab Lst ahn2023)"
check '[ "$(tab M2 ahn2023)" = "22:match 29:match 43:match 71:match 127:match " ]' "Ahn T1 M2 under paper: $(tab M2 ahn2023)"
cnt=$(awkc 'NR>1 && $c["method"]=="cl" && $c["status"]!="no-method"' "$T/tab/tables.csv" | wc -l)
check '[ "$cnt" -eq 0 ]' "CL is no-method"
cnt=$(awkc 'NR>1 && $c["table"]=="3-left" && $c["method"]=="ahn" && $c["status"]=="no-data"' "$T/tab/tables.csv" | wc -l)
check '[ "$cnt" -eq 5 ]' "the S is no-data"
check '[ "$(grep -c "" "$T/tab/tables.csv")" -eq $((1 + 35 + 35 + 25 + 9)) ]' "one row per published cell"
check 'grep -q "^## Liu & Wang 2002" "$T/tab/tables.md" && grep -q "Per column, match / close / differs" "$T/tab/tables.md"' "tables.md lays out the tables"
# Zhao-Zhou under their error at the given parameter; the sweep of radius and cut point
cnt=$(awkc 'NR>1 && $c["source"]=="zhao2017" && $c["method"]!="ahn2004" && $c["metric"]!="param"' "$T/tab/tables.csv" | wc -l)
check '[ "$cnt" -eq 0 ]' "Zhao-Zhou Table 1 under paper: metric param"
sw=$T/tab/zhao_sweep.csv
check '[ "$(head -n 1 "$sw")" = "curve,piece,d,method,protocol,metric,max_err,status,variant" ]' "zhao_sweep.csv header"
cnt=$(awkc '$c["piece"]=="C1@0.45" && $c["d"]=="4" && $c["method"]=="zhao-rational" && $c["metric"]=="param" && $c["variant"]==""' "$sw" | wc -l)
cnt2=$(awkc '$c["variant"]=="zhao-rational.weighted=0" && $c["piece"]=="C"' "$sw" | wc -l)
check '[ "$cnt" -eq 1 ] && [ "$cnt2" -eq 14 ]' \
    "the sweep reaches d = 4, cut 0.45, and has the unweighted variant"
# Example 2 on the clamped reading without the pre-split: Liu-Wang's Til and Cob
$OB tables --table liu2002:2 --protocols paper --out "$T/tab4" 2>/dev/null
tab4() { awkc 'NR>1 && $c["label"]==l {printf "%s:%s ", $c["ours"], $c["status"]}' l="$1" "$T/tab4/tables.csv"; }
check '[ "$(tab4 Til)" = "25:match 67:match 202:match 640:match 1918:match " ]' "Liu-Wang T2 Til under paper: $(tab4 Til)"
check '[ "$(tab4 Cob)" = "28:match 73:match 208:match 637:match 1846:match " ]' "Liu-Wang T2 Cob under paper: $(tab4 Cob)"
$OB tables --table nosuch:1 --out "$T/tab2" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--table" "$T/e.txt"' "tables --table of an unknown table exits 2"
$OB tables --table liu2002:2,liu2002:7 --out "$T/tab2" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "no table .liu2002:7.*the tables are: liu2002:1, liu2002:2" "$T/e.txt"' \
    "a typo in one --table name is refused with the valid names: $(cat "$T/e.txt")"
check '[ "$(grep -c "^## " "$T/tab4/tables.md")" -eq 1 ] && grep -q "^## Liu & Wang 2002.*Table 2" "$T/tab4/tables.md" && [ ! -e "$T/tab4/zhao_sweep.csv" ]' \
    "tables --table liu2002:2 writes that table's section only, and no Zhao-Zhou sweep"
$OB tables --protocols fast --out "$T/tab2" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--protocols" "$T/e.txt"' "tables --protocols of an unknown protocol exits 2"
printf 'source,table,curve,d,tol,method,label,value,unit\nliu2002,1,liu2002_ex1,1,1e-1,tiller,Til,"10,ctrl_points\n' > "$T/badpub.csv"
OFFBENCH_PUBLISHED="$T/badpub.csv" $OB tables --out "$T/tab3" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "badpub.csv:2: unterminated quote" "$T/e.txt"' "a malformed published file names file and line"

# an unwritable output directory is a run-time failure (1), after a message
if [ "$(id -u)" != 0 ]; then
    mkdir "$T/ro" && chmod 500 "$T/ro"
    $OB run --curve liu2002_ex1 --methods tiller --tols 1e-1 --out "$T/ro/sub" 2>"$T/ro.err"
    check '[ $? -eq 1 ]' "unwritable --out exits 1"
fi

# --- the command reference (docs/commands.md) is what the program's --help prints ---
sh scripts/command_reference.sh "$OB" > "$T/cmdref.md" 2>/dev/null
awk '/^<!-- command reference: generated/{s=1} s{print} /^<!-- end of command reference -->/{s=0}' docs/commands.md > "$T/cmdref.doc"
check 'cmp -s "$T/cmdref.md" "$T/cmdref.doc"' \
    "docs/commands.md command reference is current (make docs, or sh scripts/command_reference.sh --update): $(diff "$T/cmdref.doc" "$T/cmdref.md" | head -n 4 | tr '\n' ' ')"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
