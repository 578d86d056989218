#!/bin/sh
# Interrupted runs lose nothing: a run killed with SIGKILL at a random moment
# and rerun with --resume gives the same results.csv as an uninterrupted run
# (timing columns aside); SIGINT ends a run cleanly (exit 130, the finished
# rows kept); a partial last line is cut off; a resume with other options, or
# from nothing, is refused with exit 2.  `run --resume DIR` alone (no other
# option, as the README shows it) takes the run's own options from its
# journal, or from results.fingerprint once it has finished, and ends with
# the uninterrupted run's rows; an option given with it that is not the
# run's own is refused naming the option and its value as given (never
# %-encoded, as 'random%20250:2026' once was).
. "$(dirname "$0")/lib_e2e.sh"
now() { date +%s.%N; }

R="--random 12:5 --methods tiller,cobb,ahn,zhao,interp --backend cpu --threads 2"
t0=$(now)
$OB run $R --out "$T/ref" 2>/dev/null
check '[ $? -eq 0 ]' "reference run"
dur=$(echo "$(now) $t0" | awk '{print $1 - $2}')
body "$T/ref/results.csv" > "$T/ref.txt"

# SIGKILL at random moments within the run (seeded by the clock)
seed=$(date +%s)
for trial in 1 2 3; do
    at=$(awk -v d="$dur" -v s="$seed" -v k="$trial" 'BEGIN{srand(s + k); printf "%.2f", d * (0.1 + 0.8 * rand())}')
    rm -rf "$T/k"
    $OB run $R --out "$T/k" >/dev/null 2>&1 &
    pid=$!
    sleep "$at"
    kill -9 $pid 2>/dev/null
    wait $pid 2>/dev/null
    $OB run $R --resume "$T/k" >/dev/null 2>"$T/k.err"
    rc=$?
    body "$T/k/results.csv" > "$T/k.txt" 2>/dev/null
    check '[ $rc -eq 0 ] && cmp -s "$T/k.txt" "$T/ref.txt" && [ ! -e "$T/k/results.journal.csv" ]' \
        "SIGKILL after ${at} s of ${dur} s, then --resume: exit $rc, $(grep -c . "$T/k.txt" 2>/dev/null) lines; $(tail -n 2 "$T/k.err")"
done

# SIGINT: the current batch ends, finished rows stay in the journal, exit 130
rm -rf "$T/i"
$OB run $R --out "$T/i" >/dev/null 2>"$T/i.err" &
pid=$!
sleep "$(echo "$dur" | awk '{printf "%.2f", $1 / 3}')"
kill -INT $pid
wait $pid
rc=$?
check '[ $rc -eq 130 ] && [ -s "$T/i/results.journal.csv" ] && [ ! -e "$T/i/results.csv" ] && grep -q -- "--resume" "$T/i.err"' \
    "SIGINT: exit $rc (130 wanted), journal kept, no results.csv: $(cat "$T/i.err" | tail -n 1)"
# a journal, or a finished results.csv, of a build without the joint columns
# cannot be continued: refused, naming the file
mkdir -p "$T/oldj" "$T/old"
{ head -n 1 "$T/i/results.journal.csv"; tail -n +2 "$T/i/results.journal.csv" | nojoints /dev/stdin; } \
    > "$T/oldj/results.journal.csv"
$OB run $R --resume "$T/oldj" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "results.journal.csv:2: written by another version of offbench" "$T/e.txt"' \
    "resume of an older build's journal: $(cat "$T/e.txt")"
nojoints "$T/ref/results.csv" > "$T/old/results.csv"
$OB run $R --resume "$T/old" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "older offbench (no max_gap column)" "$T/e.txt"' \
    "resume of an older build's results.csv: $(cat "$T/e.txt")"
# a partial last line (a kill in the middle of a write) is cut off
printf 'rnd5_000001,0.1,tiller,hausd' >> "$T/i/results.journal.csv"
$OB run $R --samples 64 --resume "$T/i" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "results.journal.csv:1: the interrupted run had other options" "$T/e.txt"' \
    "resume with other options: exit 2 naming the journal: $(cat "$T/e.txt")"
$OB run $R --resume "$T/i" >/dev/null 2>&1
check '[ $? -eq 0 ] && body "$T/i/results.csv" | cmp -s - "$T/ref.txt"' "SIGINT, partial line, then --resume: same results"
# resuming a finished run rewrites the same file
$OB run $R --resume "$T/i" >/dev/null 2>&1
check '[ $? -eq 0 ] && body "$T/i/results.csv" | cmp -s - "$T/ref.txt"' "resuming a finished run changes nothing"

# --resume DIR alone: the options come from the journal (a run stopped by the
# out-of-memory test hook after 20 jobs: interrupted for certain), then,
# once finished, from results.fingerprint
rm -rf "$T/a"
OFFBENCH_TEST_OOM_AFTER=20 $OB run $R --out "$T/a" >/dev/null 2>&1
check '[ $? -eq 1 ] && [ -s "$T/a/results.journal.csv" ] && [ ! -e "$T/a/results.csv" ]' "a run stopped after 20 jobs: its journal kept"
$OB run --resume "$T/a" >/dev/null 2>"$T/e.txt"
rc=$?
check '[ $rc -eq 0 ] && body "$T/a/results.csv" | cmp -s - "$T/ref.txt" && [ ! -e "$T/a/results.journal.csv" ]' \
    "--resume DIR alone finishes the interrupted run with the uninterrupted run's rows: exit $rc, $(tail -n 2 "$T/e.txt")"
$OB run --resume "$T/a" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && body "$T/a/results.csv" | cmp -s - "$T/ref.txt"' \
    "--resume DIR alone on the finished run (results.fingerprint): the same rows: $(tail -n 2 "$T/e.txt")"
# an option given with it must be the run's own: refused naming it, its value as given
rm -rf "$T/a"
OFFBENCH_TEST_OOM_AFTER=20 $OB run $R --out "$T/a" >/dev/null 2>&1
cp "$T/a/results.journal.csv" "$T/a.journal"
k=0
for opt in "--random 3:5" "--tols 1e-3" "--methods tiller" "--param elber.iterations=7"; do
    k=$((k + 1))
    # shellcheck disable=SC2086
    $OB run --resume "$T/a" $opt >/dev/null 2>"$T/e$k.txt"
    rc=$?
    check '[ $rc -eq 2 ] && grep -qF -- "$opt" "$T/e$k.txt" && grep -q "results.journal.csv:1: the interrupted run had other options" "$T/e$k.txt" && ! grep -q "%[0-9A-F][0-9A-F]" "$T/e$k.txt" && cmp -s "$T/a/results.journal.csv" "$T/a.journal"' \
        "--resume DIR $opt, not the run's own: refused (2), the value as given, nothing changed: exit $rc: $(cat "$T/e$k.txt")"
done
check 'grep -qF -- "--random 12:5" "$T/e1.txt"' "... and the run's own value, as the run was given it: $(cat "$T/e1.txt")"
$OB run --resume "$T/a" --random 12:5 --tols 1e-1,1e-2,1e-3,1e-4,1e-5 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && body "$T/a/results.csv" | cmp -s - "$T/ref.txt"' \
    "--resume DIR with some of the run's own options: accepted, the same rows: $(tail -n 2 "$T/e.txt")"
# a finished run: a differing option named the same way, from results.fingerprint
$OB run --resume "$T/a" --samples 64 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -qF -- "--samples 64" "$T/e.txt" && grep -q "results.fingerprint: the finished run had other options" "$T/e.txt"' \
    "--resume DIR --samples 64 on a finished run: refused naming it: $(cat "$T/e.txt")"

# refused: nothing to resume, another --out, with --reps
$OB run $R --resume "$T/none" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "nothing to resume" "$T/e.txt"' "--resume of an empty place: $(cat "$T/e.txt")"
$OB run $R --resume "$T/i" --out "$T/other" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--out" "$T/e.txt"' "--resume with another --out: $(cat "$T/e.txt")"
$OB run $R --resume "$T/i" --reps 2 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--reps" "$T/e.txt"' "--resume with --reps: $(cat "$T/e.txt")"
printf 'not a journal\ncurve\n' > "$T/g.csv"
mkdir -p "$T/g" && mv "$T/g.csv" "$T/g/results.journal.csv"
$OB run $R --resume "$T/g" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "results.journal.csv:1: not an offbench journal" "$T/e.txt"' "garbage journal: $(cat "$T/e.txt")"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
