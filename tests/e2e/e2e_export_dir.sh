#!/bin/sh
# What `--export DIR` holds (docs/export-measure.md "The export directory",
# host/io/export_dir.h): exactly this run's files.
# - A job that had an approximation in an earlier export and now has none
#   (skip: the curve became rational for ahn; fail; a method dropped; a curve
#   dropped) loses its four files; the others are rewritten; files of other
#   names, directories, and the targets of links named like exports stay.
# - draw and trace --export: the directory then holds that one job.
# - Shards with one DIR: each writes index.shardK-of-N.csv, never
#   index.csv; merge writes index.csv (equal to the unsharded run's, rows in
#   job order) and removes what it does not list; stale or foreign shard
#   indexes are refused (exit 2); shards in different directories get a
#   warning and no index.csv.
# - DIR may not be a directory curves are loaded from: $OFFBENCH_DATA (any
#   spelling) or the datasets/ the program was built from (exit 2 naming
#   --export, nothing written there); a subdirectory is fine.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
B="--backend cpu --threads 2"

curve() {  # curve FILE WEIGHT: a cubic (rational when WEIGHT != 1) with two offsets
    printf 'curve foo\n  bezier 3\n  point 0 0\n  point 0.3 0.5 %s\n  point 0.7 0.5\n  point 1 0\n  offset 0.1 -0.1\nend\n' "$2" > "$1"
}
stems() { awkc 'NR>1 && $c["stem"] != "" {print $c["stem"]}' "$1" | sort; }
# the export's own files in DIR, sorted (index files included)
# (files and links: a directory named like one is not an export's)
owned() { (cd "$1" && find . -maxdepth 1 ! -type d | sed 's|^\./||' |
           grep -E '(__tol[^_]*\.(json|curves|dxf|svg)(\.tmp)?$)|(^index(\.shard[0-9]+-of-[0-9]+)?\.csv$)' | sort); }
# the files DIR should hold after an export with index INDEX
expected() { { for s in $(stems "$1"); do for e in curves dxf json svg; do echo "$s.$e"; done; done; echo "$2"; } | sort; }

# ---- 1: a job that now has no approximation loses its files ------------------
curve "$T/poly.curves" 1
curve "$T/rat.curves" 2
X="$T/x"
"$OB" run --curves "$T/poly.curves" --methods ahn,tiller --tols 1e-2 $B --out "$T/r1" --export "$X" 2>/dev/null
check '[ $? -eq 0 ] && [ $(stems "$X/index.csv" | wc -l) -eq 4 ]' "first export: 4 approximations"
mkdir -p "$X/keep__d1__tiller__tol1.json"            # a directory named like an export
echo mine > "$X/notes.txt"; echo mine > "$X/foo__d0.1__ahn__tol0.01.png"
echo precious > "$T/outside.json"
ln -s "$T/outside.json" "$X/lnk__d1__tiller__tol1.json"   # a link named like one
echo stale > "$X/gone__d1__cobb__tol0.5.svg"            # an earlier run's job
echo partial > "$X/foo__d0.1__ahn__tol0.01.json.tmp"    # a write cut short
"$OB" run --curves "$T/rat.curves" --methods ahn,tiller --tols 1e-2 $B --out "$T/r2" --export "$X" 2>"$T/err"
check '[ $? -eq 0 ]' "second export: exit 0: $(cat "$T/err")"
check '[ "$(awkc "\$c[\"method\"]==\"ahn\" {print \$c[\"status\"] \":\" \$c[\"stem\"]}" "$X/index.csv" | sort -u)" = "skip:" ]' \
    "ahn is skipped now: $(cat "$X/index.csv")"
check '! owned "$X" | grep -q "__ahn__"' "ahn's earlier files are gone: $(owned "$X" | grep __ahn__ | tr '\n' ' ')"
check '[ "$(owned "$X")" = "$(expected "$X/index.csv" index.csv)" ]' \
    "DIR holds exactly the run's files: $(owned "$X" | tr '\n' ' ')"
check '[ -d "$X/keep__d1__tiller__tol1.json" ] && [ -f "$X/notes.txt" ] && [ -f "$X/foo__d0.1__ahn__tol0.01.png" ]' \
    "other names stay"
check '[ ! -e "$X/lnk__d1__tiller__tol1.json" ] && [ "$(cat "$T/outside.json")" = precious ]' \
    "a link named like an export goes, its target stays"
check 'grep -q "removed .* files of .* not this export" "$T/err"' "the removal is said: $(cat "$T/err")"

# variants: a method dropped, a curve's offsets changed, a job that fails
"$OB" run --curves "$T/rat.curves" --methods tiller --tols 1e-2,1e-1 $B --out "$T/r3" --export "$X" 2>/dev/null
check '[ "$(owned "$X")" = "$(expected "$X/index.csv" index.csv)" ] && [ $(stems "$X/index.csv" | wc -l) -eq 4 ]' \
    "other tolerances: exactly the run's files: $(owned "$X" | tr '\n' ' ')"
sed 's/offset 0.1 -0.1/offset 0.2/' "$T/poly.curves" > "$T/poly2.curves"
"$OB" run --curves "$T/poly2.curves" --methods tiller,cobb --tols 1e-2 $B --out "$T/r4" --export "$X" 2>/dev/null
check '[ "$(owned "$X")" = "$(expected "$X/index.csv" index.csv)" ] && ! owned "$X" | grep -q "__d0.1__"' \
    "another d: the old d's files go: $(owned "$X" | tr '\n' ' ')"
# the same stems, now skipped: --metric bound needs the base's parameter,
# which hoschek and cubic-opt do not keep (the stem has no metric in it)
"$OB" run --curves "$T/poly2.curves" --methods hoschek,cubic-opt,tiller --tols 1e-2 $B --out "$T/r5" --export "$X" 2>/dev/null
check '[ $(stems "$X/index.csv" | wc -l) -eq 3 ]' "hoschek, cubic-opt, tiller exported"
"$OB" run --curves "$T/poly2.curves" --methods hoschek,cubic-opt,tiller --tols 1e-2 --metric bound $B --out "$T/r6" \
    --export "$X" 2>/dev/null
check '[ "$(awkc "\$c[\"status\"]==\"skip\" {n++} END {print n}" "$X/index.csv")" = 2 ] && ! owned "$X" | grep -q -e __hoschek__ -e __cubic-opt__' \
    "the same stems skipped under bound: their files go: $(owned "$X" | tr '\n' ' ')"
check '[ "$(owned "$X")" = "$(expected "$X/index.csv" index.csv)" ]' "and DIR holds exactly the run's files"

# ---- draw and trace --export: the directory holds that job -------------------
D="$T/xd"
"$OB" run --curve liu2002_ex1 --methods tiller,cobb --tols 1e-2 $B --out "$T/rd" --export "$D" 2>/dev/null
"$OB" draw --curve liu2002_ex1 --method ahn --tol 1e-2 --d -1 $B --out "$T/d.svg" --export "$D" 2>/dev/null
check '[ $? -eq 0 ] && [ "$(owned "$D")" = "$(expected "$D/index.csv" index.csv)" ] && [ $(stems "$D/index.csv") = liu2002_ex1__d-1__ahn__tol0.01 ]' \
    "draw --export: the directory holds its job: $(owned "$D" | tr '\n' ' ')"
"$OB" trace --curves "$T/rat.curves" --curve foo --method ahn --tol 1e-2 $B --export "$D" >/dev/null 2>&1
check '[ $? -eq 0 ] && [ "$(owned "$D")" = "index.csv" ] && grep -q ",skip,," "$D/index.csv"' \
    "trace --export of a skipped job: only index.csv: $(owned "$D" | tr '\n' ' ')"

# ---- 2: shards with one export directory -------------------------------------
R="--random 16:3 --methods tiller,ahn,lee --tols 1e-1,1e-3 --backend cpu"
"$OB" run $R --out "$T/all" --export "$T/xall" 2>/dev/null
check '[ $? -eq 0 ]' "unsharded run with --export"
S="$T/xs"
mkdir -p "$S"; echo old > "$S/index.csv"; echo stale > "$S/zz__d1__tiller__tol1.json"; echo mine > "$S/notes.txt"
for k in 0 1 2; do
    "$OB" run $R --shard $k/3 --out "$T/s$k" --export "$S" 2>"$T/s$k.err"
    check '[ $? -eq 0 ] && [ -f "$S/index.shard$k-of-3.csv" ] && [ ! -e "$S/index.csv" ]' \
        "shard $k/3: its own index, no index.csv: $(cat "$T/s$k.err")"
done
n=0; for k in 0 1 2; do n=$((n + $(wc -l < "$S/index.shard$k-of-3.csv") - 1)); done
check '[ $n -eq $(($(wc -l < "$T/all/results.csv") - 1)) ]' "the shard indexes hold every job once: $n"
check 'grep -q "\"export_dir\": \"$S\"" "$T/s0/meta.json"' "meta.json records the export directory"
"$OB" merge "$T/s1" "$T/s2" "$T/s0" --out "$T/m" 2>"$T/m.err"
check '[ $? -eq 0 ] && cmp -s "$S/index.csv" "$T/xall/index.csv"' \
    "merge: index.csv is the unsharded run's: $(cat "$T/m.err")"
check '[ ! -e "$S/zz__d1__tiller__tol1.json" ] && [ -f "$S/notes.txt" ]' "merge removes what index.csv does not list"
{ expected "$S/index.csv" index.csv; for k in 0 1 2; do echo index.shard$k-of-3.csv; done; } | sort > "$T/want"
check '[ "$(owned "$S")" = "$(cat "$T/want")" ]' "the merged export directory holds the run's files: $(owned "$S" | wc -l) names"
for f in $(stems "$T/xall/index.csv" | head -n 5); do
    check 'cmp -s "$S/$f.json" "$T/xall/$f.json"' "$f.json: the shard's export equals the unsharded run's"
done
# a shard index of another run (a row's status edited) or a missing one: refused
cp "$S/index.shard1-of-3.csv" "$T/keep1.csv"
awkc 'BEGIN{OFS=","} NR==2{$c["status"]=($c["status"]=="ok" ? "fail" : "ok")} {print}' "$T/keep1.csv" > "$S/index.shard1-of-3.csv"
"$OB" merge "$T/s0" "$T/s1" "$T/s2" --out "$T/m2" 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "index.shard1-of-3.csv:2: not the job and status" "$T/e.txt" && [ ! -e "$T/m2/results.csv" ]' \
    "an edited shard index: exit 2, nothing written: $(cat "$T/e.txt")"
head -n 2 "$T/keep1.csv" > "$S/index.shard1-of-3.csv"
"$OB" merge "$T/s0" "$T/s1" "$T/s2" --out "$T/m2" 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "index.shard1-of-3.csv: expected the header" "$T/e.txt"' \
    "a shard index with rows missing: exit 2: $(cat "$T/e.txt")"
rm -f "$S/index.shard1-of-3.csv"
"$OB" merge "$T/s0" "$T/s1" "$T/s2" --out "$T/m2" 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "index.shard1-of-3.csv.*run it again" "$T/e.txt"' "a missing shard index: exit 2: $(cat "$T/e.txt")"
# a shard run again rewrites its index (and removes a stale index.csv)
echo old > "$S/index.csv"
"$OB" run $R --shard 1/3 --force --out "$T/s1" --export "$S" 2>/dev/null
check '[ -f "$S/index.shard1-of-3.csv" ] && [ ! -e "$S/index.csv" ]' "shard 1 again: its index back, the stale index.csv gone"
"$OB" merge "$T/s0" "$T/s1" "$T/s2" --out "$T/m3" 2>/dev/null
check '[ $? -eq 0 ] && cmp -s "$S/index.csv" "$T/xall/index.csv"' "merged again"
# shards in different directories: a warning, no index.csv, the results merged
for k in 0 1; do "$OB" run $R --shard $k/2 --out "$T/d$k" --export "$T/dx$k" 2>/dev/null; done
"$OB" merge "$T/d0" "$T/d1" --out "$T/dm" 2>"$T/e.txt"
check '[ $? -eq 0 ] && grep -q "different directories" "$T/e.txt" && [ ! -e "$T/dx0/index.csv" ] && [ -f "$T/dx0/index.shard0-of-2.csv" ]' \
    "shards in different directories: $(cat "$T/e.txt")"
# only some shards exported
"$OB" run $R --shard 1/2 --force --out "$T/d1" 2>/dev/null
"$OB" merge "$T/d0" "$T/d1" --out "$T/dm2" 2>"$T/e.txt"
check '[ $? -eq 0 ] && grep -q "only 1 of the 2 shards ran with --export" "$T/e.txt"' "only some shards exported: $(cat "$T/e.txt")"
# a plain run into a shard directory removes the shard indexes
"$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-2 $B --out "$T/rp" --export "$S" 2>/dev/null
check '[ "$(owned "$S")" = "$(expected "$S/index.csv" index.csv)" ]' \
    "a plain run over a sharded export: exactly its files: $(owned "$S" | wc -l) names"

# ---- 3: never into a directory curves are loaded from -------------------------
mkdir -p "$T/data/sub"
cp "$ROOT/datasets/published.curves" "$T/data/"
before=$(ls "$T/data" | sort)
for spell in "$T/data" "$T/data/" "$T/data/." "$T/data/sub/.."; do
    OFFBENCH_DATA="$T/data" "$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-2 $B --out "$T/rx" --export "$spell" 2>"$T/e.txt"
    check '[ $? -eq 2 ] && grep -q -- "--export .*OFFBENCH_DATA" "$T/e.txt" && [ ! -e "$T/rx" ] && [ "$(ls "$T/data" | sort)" = "$before" ]' \
        "--export $spell = \$OFFBENCH_DATA: exit 2, nothing written: $(cat "$T/e.txt")"
done
ln -s "$T/data" "$T/alias"
OFFBENCH_DATA="$T/alias" "$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-2 $B --out "$T/rx" --export "$T/data" 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q OFFBENCH_DATA "$T/e.txt"' "\$OFFBENCH_DATA through a link: $(cat "$T/e.txt")"
for cmd in draw trace; do
    out="--out $T/q.$cmd"
    OFFBENCH_DATA="$T/data" "$OB" $cmd --curve liu2002_ex1 --method tiller --tol 1e-2 $B $out --export "$T/data" >/dev/null 2>"$T/e.txt"
    check '[ $? -eq 2 ] && grep -q -- "$cmd: --export" "$T/e.txt" && [ "$(ls "$T/data" | sort)" = "$before" ]' \
        "$cmd --export \$OFFBENCH_DATA: exit 2: $(cat "$T/e.txt")"
done
OFFBENCH_DATA="$T/data" "$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-2 $B --out "$T/rs" --export "$T/data/sub" 2>/dev/null
check '[ $? -eq 0 ] && [ -f "$T/data/sub/index.csv" ]' "a subdirectory of \$OFFBENCH_DATA is fine"
OFFBENCH_DATA="$T/data" "$OB" list curves > "$T/lc.txt" 2>&1
check '[ $? -eq 0 ] && ! grep -q "tiller.p" "$T/lc.txt"' "the default curves are untouched by that export"
# the datasets/ the program was built from (this checkout's, for this build)
DS=$(cd "$ROOT/datasets" && pwd)
ds_before=$(ls "$DS" | sort)
ln -s "$DS" "$T/dsl"
for spell in "$DS" "$DS/" "$T/dsl"; do
    (unset OFFBENCH_DATA; "$OB" run --curve liu2002_ex1 --methods tiller --tols 1e-2 $B --out "$T/ry" --export "$spell" 2>"$T/e.txt")
    rc=$?
    if [ "$(ls "$DS" | sort)" != "$ds_before" ]; then  # never leave an export in the checkout
        (cd "$DS" && rm -f index.csv liu2002_ex1__d*__tiller__tol0.01.*)
    fi
    if grep -q "built from" "$T/e.txt" || [ $rc -ne 0 ]; then
        check '[ $rc -eq 2 ] && grep -q -- "--export .*built from" "$T/e.txt" && [ ! -e "$T/ry" ]' \
            "--export $spell (the build's datasets/): exit 2: $(cat "$T/e.txt")"
    else
        bad "--export $spell (the build's datasets/) was taken: exit $rc"
    fi
done

e2e_done
