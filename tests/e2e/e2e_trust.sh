#!/bin/sh
# Results you can trust (issue 16): a --resume refuses, journal or not, a run
# of other options, data or build, naming what differs; one process owns a
# run directory at a time (DIR/.lock); a plain run never truncates an
# interrupted run's journal and leaves no stale files of an earlier run; jobs
# that never ran (out of memory) are never written as results; --version;
# compare --out leaves no .tmp; a run that cannot start creates no --out.
. "$(dirname "$0")/lib_e2e.sh"

S="--random 4:5 --tols 1e-2 --backend cpu --threads 2"
# a run long enough (some seconds) to be caught while it works
L="--random 12:5 --methods tiller,cobb,ahn,zhao,interp --backend cpu --threads 2"
waitfor() { n=0; while [ ! -s "$1" ] && [ $n -lt 200 ]; do sleep 0.05; n=$((n + 1)); done; }

# 1. a finished run resumed with other options: refused, naming the option;
# results.csv and meta.json untouched (an option left out is the run's own:
# --resume takes it, tests/e2e/e2e_resume.sh)
$OB run $S --methods tiller,cobb --samples 8 --max-segments 5 --out "$T/f" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/f/results.csv" ] && [ ! -e "$T/f/results.journal.csv" ]' "finished run"
cp "$T/f/results.csv" "$T/f.csv"; cp "$T/f/meta.json" "$T/f.json"
$OB run $S --methods tiller,cobb --samples 256 --resume "$T/f" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--samples 256" "$T/e.txt" && cmp -s "$T/f.csv" "$T/f/results.csv" && cmp -s "$T/f.json" "$T/f/meta.json"' \
    "resume of a finished run with another --samples: exit 2 naming --samples: $(cat "$T/e.txt")"
$OB run $S --methods tiller --samples 8 --max-segments 5 --resume "$T/f" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--methods" "$T/e.txt" && cmp -s "$T/f.csv" "$T/f/results.csv"' \
    "resume of a finished run with other --methods: exit 2 naming --methods: $(cat "$T/e.txt")"
$OB run $S --methods tiller,cobb --tols 1e-3 --samples 8 --max-segments 5 --resume "$T/f" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--tols" "$T/e.txt"' "resume with other --tols: $(cat "$T/e.txt")"
body "$T/f.csv" > "$T/f.csv.body"
$OB run $S --methods tiller,cobb --samples 8 --max-segments 5 --resume "$T/f" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && body "$T/f/results.csv" | cmp -s - "$T/f.csv.body"' "resume with the same options keeps the rows: $(cat "$T/e.txt")"

# 2. the fingerprint covers the data and the build: a changed curve file, a
# journal of another commit or method version, is refused
cp datasets/reference.curves "$T/ref.curves" 2>/dev/null || cp "$(dirname "$0")/../../datasets/reference.curves" "$T/ref.curves"
$OB run --curves "$T/ref.curves" --methods tiller,cobb --tols 1e-2 --backend cpu --out "$T/c" >/dev/null 2>&1
sed 's/^  point 2 3$/  point 2 3.0001/' "$T/ref.curves" > "$T/ref2.curves" && mv "$T/ref2.curves" "$T/ref.curves"
$OB run --curves "$T/ref.curves" --methods tiller,cobb --tols 1e-2 --backend cpu --resume "$T/c" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -qi "curve data" "$T/e.txt"' "resume after a curve file changed: exit 2 naming the data: $(cat "$T/e.txt")"
rm -rf "$T/i"
$OB run $L --out "$T/i" >/dev/null 2>&1 &
pid=$!
waitfor "$T/i/results.journal.csv"
kill -INT $pid; wait $pid
check '[ -s "$T/i/results.journal.csv" ] && head -n 1 "$T/i/results.journal.csv" | grep -q " git=" && head -n 1 "$T/i/results.journal.csv" | grep -q " cflags=" && head -n 1 "$T/i/results.journal.csv" | grep -q " data_hash="' \
    "the journal's fingerprint records the build and the data: $(head -n 1 "$T/i/results.journal.csv" | cut -c1-300)"
cp "$T/i/results.journal.csv" "$T/i.journal"
sed '1s/ git=[^ ]*/ git=0123456789abcdef0123456789abcdef01234567/' "$T/i.journal" > "$T/i/results.journal.csv"
$OB run $L --resume "$T/i" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "build" "$T/e.txt"' "resume of another commit's journal: exit 2 naming the build: $(cat "$T/e.txt")"
sed '1s/ version\.tiller=[0-9]*/ version.tiller=999/' "$T/i.journal" > "$T/i/results.journal.csv"
$OB run $L --resume "$T/i" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "tiller" "$T/e.txt"' "resume of a journal of another tiller version: exit 2 naming it: $(cat "$T/e.txt")"
cp "$T/i.journal" "$T/i/results.journal.csv"

# 3. one owner per directory: a second run into a working run's directory
# exits 2 at once naming the directory and the holder's pid; a plain run over
# an interrupted run refuses (its journal kept); after a kill, --resume works
rm -rf "$T/o"
$OB run $L --out "$T/o" >/dev/null 2>&1 &
pid=$!
waitfor "$T/o/results.journal.csv"
$OB run $L --out "$T/o" >/dev/null 2>"$T/e.txt"
rc=$?
$OB run $L --resume "$T/o" >/dev/null 2>"$T/e2.txt"
rc2=$?
check '[ $rc -eq 2 ] && grep -q "$T/o" "$T/e.txt" && grep -q "$pid" "$T/e.txt" && [ $rc2 -eq 2 ] && grep -q "$pid" "$T/e2.txt"' \
    "a second run (and a --resume) into a locked directory: exit $rc/$rc2, naming it and pid $pid: $(cat "$T/e.txt" "$T/e2.txt")"
kill -9 $pid; wait $pid 2>/dev/null
cp "$T/o/results.journal.csv" "$T/o.journal"
$OB run $L --out "$T/o" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--resume" "$T/e.txt" && cmp -s "$T/o.journal" "$T/o/results.journal.csv"' \
    "a plain run over an interrupted run: exit 2, journal untouched: $(cat "$T/e.txt")"
$OB run $L --resume "$T/o" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ -s "$T/o/results.csv" ] && [ ! -e "$T/o/results.journal.csv" ]' "after the kill --resume finishes: $(tail -n 2 "$T/e.txt")"
body "$T/o/results.csv" > "$T/o.body"
cp "$T/i.journal" "$T/i/results.journal.csv"
$OB run $L --force --out "$T/i" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && body "$T/i/results.csv" | cmp -s - "$T/o.body" && [ ! -e "$T/i/results.journal.csv" ]' "--force over a journal runs afresh: $(tail -n 2 "$T/e.txt")"
# a finished run in --out is never replaced silently: refused (exit 2,
# naming the file and --force), its files untouched; --force replaces it
$OB run $S --methods tiller --out "$T/f" >/dev/null 2>&1
cp "$T/f/results.csv" "$T/f.before"
for extra in "" "--split maxerr" "--shard 1/2" "--reps 1"; do
    $OB run $S --methods tiller $extra --out "$T/f" >/dev/null 2>"$T/e.txt"
    check '[ $? -eq 2 ] && grep -q "holds a finished run" "$T/e.txt" && grep -q -- "--force" "$T/e.txt" && cmp -s "$T/f/results.csv" "$T/f.before"' \
        "a finished run in --out is refused ($extra): $(cat "$T/e.txt")"
done
$OB run $S --methods cobb --force --out "$T/f" >/dev/null 2>&1
check '[ $? -eq 0 ] && grep -q ",cobb," "$T/f/results.csv" && ! grep -q ",tiller," "$T/f/results.csv"' \
    "--force replaces a finished run"

# stale files of an earlier run do not survive a new run
$OB run $S --methods tiller --reps 1 --out "$T/s" >/dev/null 2>&1
$OB run $S --methods tiller --shard 1/2 --force --out "$T/s" >/dev/null 2>&1
check '[ -s "$T/s/shard.csv" ] && [ ! -e "$T/s/samples.csv" ]' "a shard run leaves no samples.csv of the run before"
$OB run $S --methods tiller --force --out "$T/s" >/dev/null 2>&1
check '[ $? -eq 0 ] && [ ! -e "$T/s/shard.csv" ] && [ ! -e "$T/s/samples.csv" ]' "a plain run leaves no shard.csv: $(ls "$T/s")"

# 4. jobs that never ran (out of memory, through the test hook) are not results
rm -rf "$T/m"
OFFBENCH_TEST_OOM_AFTER=5 $OB run $S --methods tiller,cobb --out "$T/m" >/dev/null 2>"$T/e.txt"
rc=$?
check '[ $rc -eq 1 ] && [ -s "$T/m/results.journal.csv" ] && ! grep -q "out of memory" "$T/m/results.csv" 2>/dev/null && ! grep -q "out of memory" "$T/m/results.journal.csv"' \
    "out of memory: exit $rc (1 wanted), journal kept, no 'out of memory' row: $(cat "$T/e.txt")"
$OB run $S --methods tiller,cobb --out "$T/mref" >/dev/null 2>&1
body "$T/mref/results.csv" > "$T/mref.body"
$OB run $S --methods tiller,cobb --resume "$T/m" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && body "$T/m/results.csv" | cmp -s - "$T/mref.body" && ! grep -q "out of memory" "$T/m/results.csv"' \
    "after out of memory, --resume gives the uninterrupted run's rows: $(cat "$T/e.txt")"

# 11. --version; exit status of an unwritable --out; compare --out DIR; a
# run that cannot start creates no directory
$OB --version > "$T/v.txt" 2>&1
check '[ $? -eq 0 ] && grep -q "^offbench " "$T/v.txt" && grep -q "git commit" "$T/v.txt" && grep -q "dirty" "$T/v.txt" && grep -q "cflags" "$T/v.txt" && grep -qi "opencl" "$T/v.txt"' \
    "--version: $(cat "$T/v.txt")"
if [ "$(id -u)" -eq 0 ]; then ro=/proc; else mkdir -p "$T/ro"; chmod 555 "$T/ro"; ro="$T/ro"; fi
$OB run $S --methods tiller --out "$ro" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 1 ]' "an unwritable existing --out: exit 1 as docs/commands.md says: $(cat "$T/e.txt")"
mkdir -p "$T/cdir"
$OB compare "$T/f/results.csv" "$T/f/results.csv" --out "$T/cdir" >/dev/null 2>&1
check '[ ! -e "$T/cdir.tmp" ]' "compare --out DIR leaves no DIR.tmp"
$OB run --random 4:5 --tols 1e-2 --methods tiller --device NOSUCH --out "$T/nodev" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && [ ! -e "$T/nodev" ]' "--device NOSUCH: exit 2, no --out created: $(cat "$T/e.txt")"

$OB tables --table liu2002:1 --device NOSUCH --out "$T/nodevt" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && [ ! -e "$T/nodevt" ]' "tables --device NOSUCH: exit 2, no --out created: $(cat "$T/e.txt")"

# 7. outputs that are inputs: an --out that is, or holds, an input is refused
# (exit 2, naming both) and the input is left as it was
mkdir -p "$T/p"
$OB run $S --methods tiller --shard 0/2 --out "$T/p/sh0" >/dev/null 2>&1
$OB run $S --methods tiller --shard 1/2 --out "$T/p/sh1" >/dev/null 2>&1
cp -r "$T/p/sh0" "$T/sh0.orig"
$OB compare "$T/p/sh0" "$T/p/sh1" --out "$T/p/sh0/results.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "$T/p/sh0/results.csv" "$T/e.txt" && cmp -s "$T/sh0.orig/results.csv" "$T/p/sh0/results.csv"' \
    "compare A B --out A/results.csv: exit 2 naming it, A untouched: $(cat "$T/e.txt")"
$OB merge "$T/p/sh0" "$T/p/sh1" --out "$T/p/sh0" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "$T/p/sh0" "$T/e.txt" && diff -r -x .lock "$T/sh0.orig" "$T/p/sh0" >/dev/null' \
    "merge S0 S1 --out S0: exit 2 naming S0, the shard untouched: $(cat "$T/e.txt")"
$OB merge "$T/p/sh0" "$T/p/sh1" --out "$T/p" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "$T/p" "$T/e.txt" && [ ! -e "$T/p/results.csv" ]' \
    "merge --out a directory that holds the shards: exit 2: $(cat "$T/e.txt")"
$OB run $S --methods tiller --shard 1/2 --resume "$T/p/sh0" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && diff -r -x .lock "$T/sh0.orig" "$T/p/sh0" >/dev/null' \
    "run --shard 1/2 --resume <shard 0>: exit 2, shard 0 untouched: $(cat "$T/e.txt")"
mkdir -p "$T/rc"
cp "$T/ref.curves" "$T/rc/results.csv"
$OB run --curves "$T/rc/results.csv" --methods tiller --tols 1e-2 --backend cpu --out "$T/rc" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "$T/rc" "$T/e.txt" && cmp -s "$T/ref.curves" "$T/rc/results.csv"' \
    "run --curves DIR/results.csv --out DIR: exit 2, the curve file untouched: $(cat "$T/e.txt")"
cp "$T/ref.curves" "$T/dr.curves"
id=$(grep -m 1 '^curve ' "$T/dr.curves" | awk '{print $2}')
$OB draw --curves "$T/dr.curves" --curve "$id" --method tiller --tol 1e-2 --backend cpu --out "$T/dr.curves" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && cmp -s "$T/ref.curves" "$T/dr.curves"' "draw --curves F --out F: exit 2, F untouched: $(cat "$T/e.txt")"

# 11a. results.csv and meta.json change together: a write that fails (a file
# size limit: results.csv fits, meta.json does not) leaves neither
rm -rf "$T/w"
OFFBENCH_TEST_OOM_AFTER=3 $OB run $S --methods tiller,cobb --out "$T/w" >/dev/null 2>&1
(trap '' XFSZ; ulimit -f 5; $OB run $S --methods tiller,cobb --resume "$T/w" >/dev/null 2>"$T/e.txt")
rc=$?
check '[ $rc -ne 0 ] && [ ! -e "$T/w/results.csv" ] && [ ! -e "$T/w/meta.json" ] && [ -s "$T/w/results.journal.csv" ]' \
    "a failed meta.json write: exit $rc, neither results.csv nor meta.json written, journal kept: $(ls "$T/w"; cat "$T/e.txt")"
check '[ -z "$(ls "$T/w" | grep "\.tmp$")" ]' "a failed write leaves no .tmp: $(ls "$T/w")"

# 11b. a corrupted journal line N is reported as line N
rm -rf "$T/jl"
OFFBENCH_TEST_OOM_AFTER=5 $OB run $S --methods tiller,cobb --out "$T/jl" >/dev/null 2>&1
sed '4s/$/,extra/' "$T/jl/results.journal.csv" > "$T/jl.j" && cp "$T/jl.j" "$T/jl/results.journal.csv"
$OB run $S --methods tiller,cobb --resume "$T/jl" >/dev/null 2>"$T/e.txt"
check '[ $? -ne 0 ] && grep -q "results.journal.csv:4:" "$T/e.txt"' "journal line 4 corrupted is named line 4: $(cat "$T/e.txt")"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
