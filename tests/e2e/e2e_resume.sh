#!/bin/sh
# Interrupted runs lose nothing: a run killed with SIGKILL at a random moment
# and rerun with --resume gives the same results.csv as an uninterrupted run
# (timing columns aside); SIGINT ends a run cleanly (exit 130, the finished
# rows kept); a partial last line is cut off; a resume with other options, or
# from nothing, is refused with exit 2.
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
