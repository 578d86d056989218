#!/bin/sh
# Sharded runs: --shard K/N splits the job list, merge puts the shards back
# into exactly the unsharded results.csv (timing columns aside), and refuses
# incomplete, repeated, overlapping or mixed sets with exit status 2.
. "$(dirname "$0")/lib_e2e.sh"

R="--random 24:5 --methods tiller,ahn,zhao,lee --tols 1e-1,1e-3 --backend cpu"
$OB run $R --out "$T/all" 2>/dev/null
check '[ $? -eq 0 ]' "unsharded run"
for k in 0 1 2; do
    $OB run $R --shard $k/3 --out "$T/s$k" 2>"$T/s$k.err"
    check '[ $? -eq 0 ] && [ -f "$T/s$k/shard.csv" ] && grep -q "\"shard\": \"$k/3\"" "$T/s$k/meta.json"' "shard $k/3"
done
n0=$(($(wc -l < "$T/s0/results.csv") - 1)); n1=$(($(wc -l < "$T/s1/results.csv") - 1))
n2=$(($(wc -l < "$T/s2/results.csv") - 1)); nall=$(($(wc -l < "$T/all/results.csv") - 1))
check '[ $((n0 + n1 + n2)) -eq $nall ] && [ $n0 -gt 0 ] && [ $n1 -gt 0 ] && [ $n2 -gt 0 ]' \
    "the shards split the $nall jobs: $n0 + $n1 + $n2"
$OB merge "$T/s2" "$T/s0" "$T/s1" --out "$T/m" 2>"$T/m.err"
check '[ $? -eq 0 ] && body "$T/m/results.csv" | cmp -s - "$(body "$T/all/results.csv" > "$T/all.txt"; echo "$T/all.txt")"' \
    "merged shards equal the unsharded run: $(cat "$T/m.err")"
check 'grep -q "\"shard\": null" "$T/m/meta.json" && grep -q "\"merged_shards\": 3" "$T/m/meta.json" && grep -q "\"jobs\": $nall," "$T/m/meta.json"' \
    "merged meta.json"
$OB compare "$T/all" "$T/m" --no-timing >/dev/null 2>&1
check '[ $? -eq 0 ]' "compare: the merged run is comparable with the unsharded one and the same"

# merged meta.json: what the shards share is kept, what differs is "mixed"
# with each shard's value in "shards" (never shard 0's presented as the run's)
PY=/usr/bin/python3
metaok() {  # metaok FILE EXPR: true when the Python EXPR over meta.json m holds
    "$PY" -c 'import json, sys; m = json.load(open(sys.argv[1])); sys.exit(0 if eval("(" + sys.argv[2] + ")") else 1)' "$1" "$2"
}
metashow() { "$PY" -c 'import json, sys; m = json.load(open(sys.argv[1])); print(eval("(" + sys.argv[2] + ")"))' "$1" "$2" 2>&1 | head -c 300; }
q='m["backend"] == "cpu" and isinstance(m["omp_threads"], int) and [s["shard"] for s in m["shards"]] == ["0/3", "1/3", "2/3"]'
check 'metaok "$T/m/meta.json" "$q"' "shards that agree: backend and threads kept, shards listed in K order"
q='all({"backend", "omp_threads", "host", "engine", "argv", "jobs", "wall_seconds", "dir"} <= set(s) for s in m["shards"])
   and sum(s["jobs"] for s in m["shards"]) == m["jobs"] and m["wall_seconds"] == max(s["wall_seconds"] for s in m["shards"])'
check 'metaok "$T/m/meta.json" "$q"' "every shard's backend, threads, host, engine, argv, jobs and wall time"
R2="--random 12:5 --methods tiller,ahn --tols 1e-1,1e-3"
$OB run $R2 --backend cpu --threads 1 --shard 0/2 --out "$T/t0" 2>/dev/null
$OB run $R2 --backend cpu --threads 2 --shard 1/2 --out "$T/t1" 2>/dev/null
$OB merge "$T/t1" "$T/t0" --out "$T/tm" 2>"$T/e.txt"
q='m["omp_threads"] == "mixed" and [s["omp_threads"] for s in m["shards"]] == [1, 2] and m["engine"]["threads"] == "mixed"
   and m["backend"] == "cpu" and m["engine"]["name"] == m["shards"][0]["engine"]["name"]'
check 'metaok "$T/tm/meta.json" "$q"' "threads 1 and 2: mixed, each shard's listed: $(metashow "$T/tm/meta.json" 'm["omp_threads"], m.get("shards")')"
q='m["host"]["hostname"] == m["shards"][0]["host"]["hostname"] and m["argv"] == "mixed" and m["shards"][1]["argv"][-3] == "1/2"
   and m["timestamp"] == max(s["timestamp"] for s in m["shards"])'
check 'metaok "$T/tm/meta.json" "$q"' "host kept where the shards agree; argv mixed, each shard's own; the last timestamp"
$OB run $R2 --backend cpu --threads 1 --out "$T/t_all" 2>/dev/null
$OB compare "$T/t_all" "$T/tm" > "$T/cmp.md" 2>&1
check '[ $? -eq 0 ] && grep -q "omp_threads: 1 vs mixed" "$T/cmp.md" && grep -q "^Timing: \*\*not judged\*\*" "$T/cmp.md"' \
    "compare: a merged run of mixed threads is not timed against one thread"
$OB compare "$T/tm" "$T/tm" > "$T/cmp.md" 2>&1
check '[ $? -eq 0 ] && grep -q "omp_threads: mixed vs mixed" "$T/cmp.md"' "compare: mixed vs mixed is not the same setting"
if $OB run $R2 --backend opencl --shard 1/2 --out "$T/o1b" >/dev/null 2>&1; then
    $OB merge "$T/t0" "$T/o1b" --out "$T/om" 2>"$T/e.txt"
    q='m["backend"] == "mixed" and [s["backend"] for s in m["shards"]] == ["cpu", "opencl"] and m["opencl"] == "mixed"'
    check 'metaok "$T/om/meta.json" "$q"' "cpu and opencl shards: backend mixed: $(metashow "$T/om/meta.json" 'm["backend"], m["opencl"]')"
else
    echo "e2e_shard: no OpenCL device: the mixed-backend merge is skipped"
    skipped=$((skipped + 1))
fi

# refused sets: exit 2, saying why
refuse() {  # expected text, then merge arguments
    want=$1; shift
    $OB merge "$@" --out "$T/bad" >/dev/null 2>"$T/e.txt"
    rc=$?
    if [ $rc -eq 2 ] && grep -q -- "$want" "$T/e.txt"; then ok; else bad "merge $* -> exit $rc, '$(cat "$T/e.txt")'"; fi
}
refuse "shard 2/3 is missing" "$T/s0" "$T/s1"
refuse "given twice" "$T/s0" "$T/s1" "$T/s1" "$T/s2"
$OB run $R --samples 64 --shard 2/3 --out "$T/x2" 2>/dev/null
refuse "not shards of one run: plan_hash" "$T/s0" "$T/s1" "$T/x2"
$OB run $R --shard 1/2 --out "$T/y1" 2>/dev/null
refuse "another shard count" "$T/s0" "$T/s1" "$T/y1"
mkdir "$T/empty"
refuse "not a finished shard" "$T/s0" "$T/s1" "$T/empty"
refuse "not a run with --shard" "$T/s0" "$T/s1" "$T/all"
cp -r "$T/s1" "$T/o1"
first0=$(rcols "$T/s0/shard.csv" job | head -n 1)
awkc 'BEGIN{OFS=","} NR==2{$c["job"]=f} {print}' f="$first0" "$T/s1/shard.csv" > "$T/o1/shard.csv"
refuse "overlapping shards" "$T/s0" "$T/o1" "$T/s2"
head -n 3 "$T/s1/shard.csv" > "$T/o1/shard.csv"
refuse "one index per row" "$T/s0" "$T/o1" "$T/s2"
refuse "usage"
# merge checks every row's key against the plan's job index (exit 2 naming
# the shard file and line), and takes no unfinished shard (a journal)
rm -rf "$T/o1" && cp -r "$T/s1" "$T/o1"
own=$(rcols "$T/s1/results.csv" curve | sed -n 2p)
other=$(rcols "$T/all/results.csv" curve | grep -v -x -F "$own" | head -n 1)
awkc 'BEGIN{OFS=","} NR==3{$c["curve"]=o} {print}' o="$other" "$T/s1/results.csv" > "$T/o1/results.csv"
refuse "o1/results.csv:3: " "$T/s0" "$T/o1" "$T/s2"
{ head -n 1 "$T/s1/results.csv"; tail -n +2 "$T/s1/results.csv" | sed -n '1!G;h;$p'; } > "$T/o1/results.csv"
refuse "o1/results.csv:2: " "$T/s0" "$T/o1" "$T/s2"
cp "$T/s1/results.csv" "$T/o1/results.csv"
# job indices swapped in shard.csv alone: the rows no longer sit at their jobs
awk 'NR==2{a=$0; next} NR==3{print; print a; next} {print}' "$T/s1/shard.csv" > "$T/o1/shard.csv"  # (whole lines)
refuse "o1/results.csv:2: " "$T/s0" "$T/o1" "$T/s2"
# only the job indices swapped (each key kept with its row): the plan hash
awkc 'BEGIN{OFS=","} NR==2{a=$c["job"]; b=$c["key"]; next} NR==3{x=$c["key"]; $c["key"]=b; print; $c["job"]=a; $c["key"]=x; print; next} {print}' \
    "$T/s1/shard.csv" > "$T/o1/shard.csv"
refuse "not the run's jobs" "$T/s0" "$T/o1" "$T/s2"
cp "$T/s1/shard.csv" "$T/o1/shard.csv"
: > "$T/o1/results.journal.csv"
refuse "o1: an unfinished shard" "$T/s0" "$T/o1" "$T/s2"
rm -f "$T/o1/results.journal.csv"
$OB merge "$T/s0" "$T/o1" "$T/s2" --out "$T/m2" 2>"$T/e.txt"
check '[ $? -eq 0 ]' "the untouched copy merges: $(cat "$T/e.txt")"

# repetitions: samples.csv is merged too
for k in 0 1; do $OB run $R --reps 2 --shard $k/2 --out "$T/r$k" 2>/dev/null; done
$OB merge "$T/r0" "$T/r1" --out "$T/rm" 2>/dev/null
check '[ $? -eq 0 ] && [ $(($(wc -l < "$T/rm/samples.csv") - 1)) -eq $((2 * nall)) ] && body "$T/rm/results.csv" | cmp -s - "$T/all.txt"' \
    "shards with --reps 2: results and samples.csv merged"

# bad --shard specs
for spec in 3/3 1/0 x -1/2 1/2/3 0/100001 ""; do
    $OB run $R --shard "$spec" --out "$T/z" >/dev/null 2>"$T/e.txt"
    check '[ $? -eq 2 ] && grep -q -- "--shard" "$T/e.txt"' "--shard '$spec': $(cat "$T/e.txt")"
done

e2e_done
