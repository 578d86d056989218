#!/bin/sh
# offbench certify RUN_DIR (issue 47, item 2): a finished run certified after
# the fact gives what `run --certify` gives: the same err_upper, err_lower
# and certified (cert_ns aside), every other column byte for byte the run's
# own, meta.json's certify object, the fingerprint and plan hash of a
# certified run; selections (--methods, --tols, --curves) certify only their
# cells, a second pass the rest and skips what is certified (a pass with
# nothing left certifies 0); SIGINT keeps the jobs certified so far and
# SIGKILL those journaled (the next pass folds them in); a run of other data
# or build, a directory that is not a run, a malformed row and an unknown
# method are refused with exit 2, naming the file and line or the option.
. "$(dirname "$0")/lib_e2e.sh"
R="--random 4:3 --methods tiller,cobb,sisl --tols 1e-2,1e-3 --backend cpu"
$OB run $R --certify --threads 2 --out "$T/c" >/dev/null 2>&1
check '[ $? -eq 0 ]' "run --certify"
$OB run $R --threads 2 --out "$T/p0" >/dev/null 2>&1
check '[ $? -eq 0 ]' "the same run without --certify"
cp -r "$T/p0" "$T/p"
# certified columns without their time; everything but the timings
certs() { dropcols "$1" cert_ns fit_ns eval_ns; }
others() { dropcols "$1" err_upper err_lower certified cert_ns; }
$OB certify "$T/p" --threads 2 >"$T/p.out" 2>"$T/p.err"
check '[ $? -eq 0 ]' "certify RUN_DIR: exit 0: $(tail -n 3 "$T/p.err")"
napp=$(awkc 'NR>1 && ($c["status"]=="ok" || $c["status"]=="limit")' "$T/p0/results.csv" | wc -l)
nset=$(awkc 'NR>1 && $c["err_upper"]!=""' "$T/p/results.csv" | wc -l)
check '[ "$napp" -ge 10 ] && [ "$nset" -eq "$napp" ]' "every job with an approximation certified: $nset of $napp"
check '[ -n "$(certs "$T/p/results.csv")" ] && [ "$(certs "$T/p/results.csv")" = "$(certs "$T/c/results.csv")" ]' \
    "the same certificates as run --certify"
check '[ "$(others "$T/p/results.csv")" = "$(others "$T/p0/results.csv")" ]' \
    "every other column byte for byte the run's own (timings included)"
check '[ "$(wc -l < "$T/p/results.csv")" -eq "$(wc -l < "$T/p0/results.csv")" ]' "no row added or lost"
check 'grep -q "\"certify\": {\"mode\": \"verdict\", \"rtol\": 0.001" "$T/p/meta.json"' "meta.json's certify object: $(grep '"certify"' "$T/p/meta.json" | head -c 200)"
for k in plan_hash plan_seed data_hash; do
    check '[ "$(grep "\"$k\"" "$T/p/meta.json")" = "$(grep "\"$k\"" "$T/c/meta.json")" ]' \
        "meta.json's $k that of a certified run: $(grep "\"$k\"" "$T/p/meta.json") vs $(grep "\"$k\"" "$T/c/meta.json")"
done
check 'cmp -s "$T/p/results.fingerprint" "$T/c/results.fingerprint"' "results.fingerprint that of a certified run"
check '[ "$(grep -v "\"certify\"\|plan_hash\|plan_seed" "$T/p/meta.json")" = "$(grep -v "\"certify\"\|plan_hash\|plan_seed" "$T/p0/meta.json")" ]' \
    "the rest of meta.json unchanged"
check '[ ! -e "$T/p/certify.journal.csv" ] && [ -z "$(ls "$T/p" | grep tmp)" ]' "no journal or temporary left: $(ls "$T/p")"
# the certified run goes on like one run with --certify: compare (results only: timings are noise), resume
$OB compare --no-timing "$T/c/results.csv" "$T/p/results.csv" >/dev/null 2>&1
check '[ $? -eq 0 ]' "compare with the run --certify: the same"
cp "$T/p/results.csv" "$T/p.csv"
$OB run --resume "$T/p" --threads 2 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ "$(certs "$T/p/results.csv")" = "$(certs "$T/p.csv")" ]' "run --resume of it: the rows kept: $(tail -n 1 "$T/e.txt")"
# idempotent: a second pass certifies nothing and says how many it skipped
cp "$T/p/results.csv" "$T/p1.csv"
$OB certify "$T/p" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && grep -q "$napp already certified (skipped), 0 to certify" "$T/e.txt" && cmp -s "$T/p/results.csv" "$T/p1.csv"' \
    "a second pass: 0 certified, $napp skipped, results.csv unchanged: $(cat "$T/e.txt")"
# the other mode is refused, not mixed in: the run is certified by the verdict
$OB certify "$T/p" --tight >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "certified in mode verdict" "$T/e.txt" && cmp -s "$T/p/results.csv" "$T/p1.csv"' \
    "certify --tight of a run certified by the verdict: refused, nothing written: $(cat "$T/e.txt")"
# a journal left by a pass killed after it wrote its files: read, and removed
{ printf '#offbench-certify-journal 1 %s\n' "$(cat "$T/p0/results.fingerprint")"; head -n 3 "$T/c/results.csv"; } > "$T/p/certify.journal.csv"
$OB certify "$T/p" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ ! -e "$T/p/certify.journal.csv" ] && cmp -s "$T/p/results.csv" "$T/p1.csv"' \
    "a stale journal of a certified run: removed, results.csv unchanged: $(cat "$T/e.txt")"

# limit jobs are certified as run --certify certifies them; fail rows stay empty
L="--random 2:3 --methods tiller,sisl --tols 1e-5 --max-segments 3 --backend cpu"
$OB run $L --certify --out "$T/lc" >/dev/null 2>&1
$OB run $L --out "$T/lp" >/dev/null 2>&1
$OB certify "$T/lp" >/dev/null 2>"$T/e.txt"
nlim=$(awkc 'NR>1 && $c["status"]=="limit" && $c["err_upper"]!=""' "$T/lp/results.csv" | wc -l)
nfail=$(awkc 'NR>1 && $c["status"]!="limit" && $c["status"]!="ok" && $c["err_upper"]==""' "$T/lp/results.csv" | wc -l)
check '[ "$nlim" -ge 2 ] && [ "$nfail" -ge 1 ] && [ "$(certs "$T/lp/results.csv")" = "$(certs "$T/lc/results.csv")" ]' \
    "limit jobs: as run --certify ($nlim certified; $nfail rows without an approximation left empty): $(cat "$T/e.txt")"

# selection: --methods and --tols first, then the rest; the same in the end
cp -r "$T/p0" "$T/s"
$OB certify "$T/s" --methods cobb --tols 1e-3 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ]' "certify --methods cobb --tols 1e-3: $(cat "$T/e.txt")"
nsel=$(awkc 'NR>1 && ($c["status"]=="ok" || $c["status"]=="limit") && $c["method"]=="cobb" && $c["tol"]=="0.001"' "$T/s/results.csv" | wc -l)
wrong=$(awkc 'NR>1 && ($c["err_upper"]!="") != (($c["status"]=="ok" || $c["status"]=="limit") && $c["method"]=="cobb" && $c["tol"]=="0.001")' "$T/s/results.csv" | wc -l)
check '[ "$nsel" -ge 2 ] && [ "$wrong" -eq 0 ]' "only the cells selected are certified ($nsel; $wrong others)"
check 'grep -q "\"certify\": {" "$T/s/meta.json" && grep -q "certify=no" "$T/s/results.fingerprint"' \
    "a part certified: meta.json has the certify object, the fingerprint stays the run's"
$OB certify "$T/s" --curves rnd3_000001,rnd3_000002 --methods tiller,cobb >/dev/null 2>"$T/e.txt"
wrong=$(awkc 'NR>1 && $c["err_upper"]!="" && !($c["method"]=="cobb" && $c["tol"]=="0.001") && !(($c["curve"]=="rnd3_000001" || $c["curve"]=="rnd3_000002") && $c["method"]!="sisl")' "$T/s/results.csv" | wc -l)
check '[ "$wrong" -eq 0 ]' "--curves and --methods: only those cells ($wrong others)"
$OB certify "$T/s" >/dev/null 2>"$T/e.txt"
nskip=$(sed -n 's/.* \([0-9][0-9]*\) already certified (skipped).*/\1/p' "$T/e.txt")
check '[ $? -eq 0 ] && [ "$(certs "$T/s/results.csv")" = "$(certs "$T/c/results.csv")" ] && [ "$nskip" -gt "$nsel" ] && [ "$nskip" -lt "$napp" ]' \
    "then the rest: the same certificates as run --certify, $nskip skipped: $(cat "$T/e.txt")"
check 'cmp -s "$T/s/results.fingerprint" "$T/c/results.fingerprint"' "all certified at last: the fingerprint of a certified run"

# SIGINT: the jobs certified so far are kept, a second pass does the rest
# (the curves but the septic, the costliest: the test stays short)
K="--curves rnd3_000000,rnd3_000001,rnd3_000003"
kc() { certs "$1" | grep -v rnd3_000002; }
nk=$(awkc 'NR>1 && ($c["status"]=="ok" || $c["status"]=="limit") && $c["curve"]!="rnd3_000002"' "$T/p0/results.csv" | wc -l)
cp -r "$T/p0" "$T/i"
$OB certify "$T/i" $K --threads 1 >/dev/null 2>"$T/i.err" &
pid=$!
n=0
while [ $n -lt 400 ] && [ "$(cat "$T/i/certify.journal.csv" 2>/dev/null | wc -l)" -lt 4 ]; do sleep 0.02; n=$((n + 1)); done
kill -INT $pid 2>/dev/null
wait $pid
rc=$?
nint=$(awkc 'NR>1 && $c["err_upper"]!=""' "$T/i/results.csv" | wc -l)
if [ $rc -eq 0 ]; then
    skipped=$((skipped + 1)); echo "SKIP: the pass ended before SIGINT came" >&2
else
    check '[ $rc -eq 130 ] && [ "$nint" -ge 2 ] && [ "$nint" -lt "$nk" ] && [ ! -e "$T/i/certify.journal.csv" ] && grep -q "certify $T/i" "$T/i.err"' \
        "SIGINT: exit $rc, $nint of $nk certified kept: $(tail -n 2 "$T/i.err")"
    check '[ "$(others "$T/i/results.csv")" = "$(others "$T/p0/results.csv")" ]' "SIGINT: the other columns unchanged"
fi
$OB certify "$T/i" $K >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ "$(kc "$T/i/results.csv")" = "$(kc "$T/c/results.csv")" ] && grep -q "$nint already certified (skipped)" "$T/e.txt"' \
    "after SIGINT, a second pass: the rest, the same certificates: $(cat "$T/e.txt")"
# SIGKILL: the journal keeps the jobs certified; the next pass folds them in
cp -r "$T/p0" "$T/k"
$OB certify "$T/k" $K --threads 1 >/dev/null 2>&1 &
pid=$!
n=0
while [ $n -lt 400 ] && [ "$(cat "$T/k/certify.journal.csv" 2>/dev/null | wc -l)" -lt 4 ]; do sleep 0.02; n=$((n + 1)); done
kill -KILL $pid 2>/dev/null
wait $pid
rc=$?
$OB certify "$T/k" $K >/dev/null 2>"$T/e.txt"
if [ $rc -eq 0 ]; then
    skipped=$((skipped + 1)); echo "SKIP: the pass ended before SIGKILL came" >&2
else
    check 'grep -q "from $T/k/certify.journal.csv" "$T/e.txt"' "SIGKILL: the journal folded in: $(cat "$T/e.txt")"
fi
check '[ "$(kc "$T/k/results.csv")" = "$(kc "$T/c/results.csv")" ] && [ ! -e "$T/k/certify.journal.csv" ]' \
    "after SIGKILL, the next pass: the same certificates"

# shards: each certified after the fact, merged: the run with --certify;
# a merged run has no fingerprint: refused (its shards are certified instead)
S="--random 2:3 --methods tiller,cobb --tols 1e-2 --backend cpu"
$OB run $S --certify --out "$T/sc" >/dev/null 2>&1
$OB run $S --shard 0/2 --out "$T/s0" >/dev/null 2>&1
$OB run $S --shard 1/2 --out "$T/s1" >/dev/null 2>&1
$OB certify "$T/s0" >/dev/null 2>&1 && $OB certify "$T/s1" >/dev/null 2>&1 && $OB merge "$T/s0" "$T/s1" --out "$T/sm" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ "$(certs "$T/sm/results.csv")" = "$(certs "$T/sc/results.csv")" ]' \
    "shards certified after the fact, merged: the run with --certify: $(cat "$T/e.txt")"
$OB run $S --shard 0/2 --out "$T/u0" >/dev/null 2>&1
$OB run $S --shard 1/2 --out "$T/u1" >/dev/null 2>&1
$OB merge "$T/u0" "$T/u1" --out "$T/um" >/dev/null 2>&1
$OB certify "$T/um" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "no results.fingerprint" "$T/e.txt"' "a merged run: refused, saying why: $(cat "$T/e.txt")"

# a row its job does not repeat (edited): that job is not certified (exit 1), the others are
cp -r "$T/p0" "$T/q"
awk -F, 'BEGIN{OFS=","} NR==2{$10="0.0085"} {print}' "$T/p0/results.csv" > "$T/q/results.csv"
$OB certify "$T/q" --curves rnd3_000000 --methods tiller >/dev/null 2>"$T/e.txt"
rc=$?
row2=$(awkc 'NR==2 {print $c["err_upper"]}' "$T/q/results.csv")
nq=$(awkc 'NR>2 && $c["err_upper"]!=""' "$T/q/results.csv" | wc -l)
check '[ $rc -eq 1 ] && grep -q "results.csv:2: .*does not repeat its row" "$T/e.txt" && [ -z "$row2" ] && [ "$nq" -ge 1 ]' \
    "a row the rerun does not repeat: not certified, exit 1, the others certified ($nq): $(cat "$T/e.txt")"

# refusals: other data, other build, not a run, malformed, unknown names
printf 'curve bez1\n  bezier 3\n  point 0 0\n  point 1 1\n  point 2 -1\n  point 3 0\n  offset 0.1 -0.1\nend\n' > "$T/one.curves"
$OB run --curves "$T/one.curves" --methods tiller --tols 1e-3 --backend cpu --out "$T/d" >/dev/null 2>&1
sed -i 's/point 2 -1/point 2 -1.5/' "$T/one.curves"
cp "$T/d/results.csv" "$T/d.csv"
$OB certify "$T/d" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "curve data" "$T/e.txt" && cmp -s "$T/d/results.csv" "$T/d.csv"' "changed data: refused: $(cat "$T/e.txt")"
cp -r "$T/p0" "$T/b"
sed -i 's/ git=[^ ]*/ git=0123456789abcdef/' "$T/b/results.fingerprint"
$OB certify "$T/b" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "the build (git commit)" "$T/e.txt"' "another build: refused: $(cat "$T/e.txt")"
$OB certify "$T/nothere" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "nothere" "$T/e.txt"' "a missing directory: $(cat "$T/e.txt")"
mkdir -p "$T/empty"
$OB certify "$T/empty" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "not a run" "$T/e.txt"' "a directory that is not a run: $(cat "$T/e.txt")"
cp -r "$T/p0" "$T/f"
rm "$T/f/results.fingerprint"
$OB certify "$T/f" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "results.fingerprint" "$T/e.txt"' "a run without its fingerprint: $(cat "$T/e.txt")"
cp -r "$T/p0" "$T/m"
awk -F, 'BEGIN{OFS=","} NR==3{$7="x"} {print}' "$T/p0/results.csv" > "$T/m/results.csv"
$OB certify "$T/m" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "results.csv:3:" "$T/e.txt"' "a malformed row: named: $(cat "$T/e.txt")"
$OB certify "$T/p0" --methods tiler >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--methods" "$T/e.txt" && grep -q "tiler" "$T/e.txt"' "an unknown method: $(cat "$T/e.txt")"
$OB certify "$T/p0" --tols 1e-5 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--tols" "$T/e.txt"' "a tolerance not in the run: $(cat "$T/e.txt")"
$OB certify "$T/p0" --curves nope >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--curves" "$T/e.txt"' "a curve not in the run: $(cat "$T/e.txt")"
check '[ -z "$(awkc "NR>1 && \$c[\"err_upper\"]!=\"\"" "$T/p0/results.csv")" ]' "refused passes wrote nothing"
$OB certify --help >"$T/h.txt" 2>&1
check '[ $? -eq 0 ] && grep -q "RUN_DIR" "$T/h.txt" && grep -q -- "--threads" "$T/h.txt"' "--help"
$OB certify >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "RUN_DIR" "$T/e.txt"' "no RUN_DIR: $(cat "$T/e.txt")"
e2e_done
