#!/bin/sh
# run --certify with --job-timeout (issue 47): a job whose certificate runs
# past the timeout (thread seconds, as the driver's) gets no verdict:
# err_upper, err_lower and certified empty, cert_ns set (the time it ran),
# a warning naming the job; never a wrong verdict.  --resume restores it as
# timed out (not certified again, not shown as certified); compare and
# summary read it.
. "$(dirname "$0")/lib_e2e.sh"
# lee on rnd7_000010 (d = -0.0258) is a limit job of 52 pieces: ~30 ms in
# the driver, ~5 s of certificate at --certify=tight (the verdict alone is
# shown in ~0.2 s: over tol); tiller's job ~5 ms and ~0.1 s
R="--random 20:7 --curve rnd7_000010 --methods lee,tiller --tols 1e-3 --backend cpu --job-timeout 0.5"
$OB run $R --certify=tight --threads 2 --out "$T/t" >/dev/null 2>"$T/t.err"
check '[ $? -eq 0 ]' "run --certify --job-timeout: $(cat "$T/t.err")"
lee=$(rcols "$T/t/results.csv" method status err_upper err_lower certified | grep '^lee:')
check '[ "$lee" = "lee:limit:::" ]' "the certificate past the timeout: no verdict ($lee)"
ns=$(rcols "$T/t/results.csv" method cert_ns | awk -F: '$1=="lee"{print $2}')
check '[ -n "$ns" ] && awk -v n="$ns" "BEGIN{exit !(n >= 0.5e9 && n < 4e9)}"' "its cert_ns is the time it ran, past 0.5 s: $ns"
tiller=$(rcols "$T/t/results.csv" method status certified | grep '^tiller:')
check '[ "$tiller" = "tiller:ok:yes" ]' "a certificate within the timeout is as before ($tiller)"
check 'grep -q "warning: --certify: rnd7_000010 d=-0.0258 lee tol=0.001: the certificate passed --job-timeout" "$T/t.err"' \
    "a warning names the job: $(grep -i timeout "$T/t.err")"
check 'grep -q "certified within tol 1 of 2 (1 timed out" "$T/t.err"' "the closing line counts it: $(tail -n 1 "$T/t.err")"
# --resume restores it as it is: nothing is certified again
cp "$T/t/results.csv" "$T/t.csv"
$OB run --threads 2 --resume "$T/t" >/dev/null 2>"$T/r.err"
check '[ $? -eq 0 ] && [ "$(body "$T/t/results.csv")" = "$(body "$T/t.csv")" ] && grep -q "2 of 2 jobs restored" "$T/r.err" && ! grep -q certifying "$T/r.err"' \
    "--resume: the timed-out certificate restored, not run again: $(cat "$T/r.err")"
# the same from a journal (a run stopped after the lee job's certificate)
mkdir -p "$T/j"
{ printf '#offbench-journal 1 %s\n' "$(cat "$T/t/results.fingerprint")"; head -n 1 "$T/t.csv"; grep '^rnd7_000010,[^,]*,lee,' "$T/t.csv"; } > "$T/j/results.journal.csv"
$OB run $R --certify=tight --threads 2 --resume "$T/j" >/dev/null 2>"$T/j.err"
check '[ $? -eq 0 ] && [ "$(body "$T/j/results.csv")" = "$(body "$T/t.csv")" ] && grep -q "1 of 2 jobs restored" "$T/j.err" && grep -q "certifying 1 jobs" "$T/j.err"' \
    "--resume from a journal: the timed-out row kept, the other job run: $(cat "$T/j.err")"
# the readers: compare, summary
$OB compare "$T/t.csv" "$T/j/results.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ]' "compare reads a timed-out certificate: $(cat "$T/e.txt")"
$OB summary "$T/t.csv" >"$T/s.txt" 2>"$T/e.txt"
check '[ $? -eq 0 ]' "summary reads it: $(cat "$T/e.txt")"
# a verdict without err_upper is still refused
awk -F, 'BEGIN{OFS=","} NR==3{$(NF-8)=""} {print}' "$T/t.csv" > "$T/x.csv"
$OB compare "$T/t.csv" "$T/x.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "x.csv:3: err_upper, err_lower, certified and cert_ns are all empty or all set" "$T/e.txt"' \
    "a verdict without err_upper: refused: $(cat "$T/e.txt")"
e2e_done
