#!/bin/sh
# run --certify (issue 41): every job with an approximation gains err_upper,
# err_lower, certified and cert_ns; the other columns are the same as
# without it, bit for bit; err_lower <= err_upper, the sampled hausdorff
# max_err <= err_upper, certified = yes exactly when err_upper <= tol (a job
# ok by its samples whose bound is over tol says no); the certificate is the
# same for any thread count and engine, through --reps, --resume and shards
# with merge; a resume or merge that would mix certified and uncertified
# rows is refused.
. "$(dirname "$0")/lib_e2e.sh"
R="--curve liu2002_ex1,zhao2017_quintic --methods tiller,ahn,zhao-rational,hoschek,kim2018,lee --tols 1e-2,1e-3 --backend cpu"
$OB run $R --certify --threads 2 --out "$T/c" >/dev/null 2>"$T/c.err"
check '[ $? -eq 0 ]' "run --certify: $(cat "$T/c.err")"
$OB run $R --threads 2 --out "$T/p" >/dev/null 2>&1
check '[ $? -eq 0 ]' "the same run without --certify"
# (then --time-fits' three: the fields counted from the end below skip them)
check '[ "$(head -n 1 "$T/c/results.csv" | cut -d, -f23-)" = "err_upper,err_lower,certified,cert_ns,fit_calls,method_ns,method_iqr_ns,trimmed_err,trimmed_cut" ]' \
    "the certificate's columns come after the joints and the spread, before the method time's: $(head -n 1 "$T/c/results.csv")"
# the other columns bit for bit; without --certify the four are empty
drop4() { dropcols "$1" err_upper err_lower certified cert_ns fit_ns eval_ns; }
check '[ -n "$(drop4 "$T/c/results.csv")" ] && [ "$(drop4 "$T/c/results.csv")" = "$(drop4 "$T/p/results.csv")" ]' \
    "the other columns are those of the run without --certify"
check '[ "$(awkc "NR>1 && (v(\"err_upper\") != \"\" || v(\"certified\") != \"\" || v(\"cert_ns\") != \"\")" "$T/p/results.csv" | wc -l)" -eq 0 ]' \
    "without --certify the columns are empty"
# which rows have one: exactly those with an approximation
nset=$(awkc 'NR>1 && ($c["status"]=="ok" || $c["status"]=="limit") && $c["err_upper"]!="" && $c["err_lower"]!="" && $c["certified"]!="" && $c["cert_ns"]!=""' "$T/c/results.csv" | wc -l)
nappr=$(awkc 'NR>1 && ($c["status"]=="ok" || $c["status"]=="limit")' "$T/c/results.csv" | wc -l)
nother=$(awkc 'NR>1 && $c["status"]!="ok" && $c["status"]!="limit" && ($c["err_upper"]!="" || $c["certified"]!="")' "$T/c/results.csv" | wc -l)
check '[ "$nappr" -ge 30 ] && [ "$nset" -eq "$nappr" ] && [ "$nother" -eq 0 ]' \
    "every job with an approximation is certified ($nset of $nappr), none without ($nother)"
bad=$(awkc 'NR>1 && $c["err_upper"]!="" && !($c["err_lower"] + 0 <= $c["err_upper"] + 0 && $c["max_err"] + 0 <= $c["err_upper"] + 0)' "$T/c/results.csv")
check '[ -z "$bad" ]' "err_lower <= err_upper and the sampled max_err <= err_upper: $bad"
bad=$(awkc 'NR>1 && $c["certified"]!="" && (($c["certified"]=="yes") != ($c["err_upper"] + 0 <= $c["tol"] + 0))' "$T/c/results.csv")
check '[ -z "$bad" ]' "certified is yes exactly when err_upper <= tol: $bad"
# the verdict (the default): every job decided, within tol (err_upper <= tol)
# or over it (err_lower > tol); --certify=tight: err_upper within 1 % of
# err_lower on most ok jobs, and the same verdicts
undecided=$(awkc 'NR>1 && $c["err_upper"]!="" && !($c["err_upper"] + 0 <= $c["tol"] + 0 || $c["err_lower"] + 0 > $c["tol"] + 0)' "$T/c/results.csv")
check '[ -z "$undecided" ]' "every job decided by the verdict: $undecided"
$OB run $R --certify=tight --threads 2 --out "$T/ct" >/dev/null 2>"$T/ct.err"
check '[ $? -eq 0 ]' "run --certify=tight: $(cat "$T/ct.err")"
tight=$(awkc 'NR>1 && $c["status"]=="ok" && $c["err_lower"] > 0 && $c["err_upper"] <= $c["err_lower"] * 1.01' "$T/ct/results.csv" | wc -l)
nok=$(awkc 'NR>1 && $c["status"]=="ok"' "$T/ct/results.csv" | wc -l)
check '[ "$tight" -ge $((nok * 9 / 10)) ]' "tight: err_upper within 1 % of err_lower on most ok jobs: $tight of $nok"
check '[ "$(rcols "$T/c/results.csv" curve d method tol certified)" = "$(rcols "$T/ct/results.csv" curve d method tol certified)" ]' \
    "tight and the verdict give the same verdicts"
loose=$(awkc 'NR>1 && $c["status"]=="ok" && $c["err_lower"] > 0 && $c["err_upper"] <= $c["err_lower"] * 1.01' "$T/c/results.csv" | wc -l)
check '[ "$loose" -lt "$tight" ]' "the verdict does not refine as far as tight ($loose of $nok within 1 %, tight $tight)"
yes=$(awkc 'NR>1 && $c["certified"]=="yes"' "$T/c/results.csv" | wc -l)
check 'grep -q "certified within tol $yes of $nset" "$T/c.err"' "the closing line counts them: $(tail -n 1 "$T/c.err")"
check 'grep -q "\"certify\": {\"mode\": \"verdict\", \"rtol\": 0.001" "$T/c/meta.json" && grep -q "\"certify\": {\"mode\": \"tight\"" "$T/ct/meta.json" && grep -q "\"certify\": null" "$T/p/meta.json"' \
    "meta.json says what the certificate is, and null without"
# ok by its metric, not within tol by the certified distance: tiller on
# Liu-Wang's Example 1 at d = 1 under the radial metric (max_err 0.90e-3 at
# tol 1e-3; the Hausdorff distance to the offset, whose 1 - d kappa nears 0
# there, is certified in [1.7950e-3, 1.7953e-3])
$OB run --curve liu2002_ex1 --methods tiller --tols 1e-3 --metric radial --backend cpu --certify --out "$T/n" >/dev/null 2>&1
row=$(awkc 'NR>1 && $c["d"]=="1" {print $c["status"], ($c["max_err"] <= $c["tol"]), $c["certified"], ($c["err_lower"] > 0.0017)}' "$T/n/results.csv")
check '[ "$row" = "ok 1 no 1" ]' "an ok job whose certified distance exceeds tol: certified no ($row)"
# an enclosure that straddles tol is refined to a verdict (lstsq on a septic
# curve: sampled 0.99927e-3; at rtol alone [0.99926e-3, 1.00022e-3], no verdict)
$OB run --random 200:7 --curve rnd7_000170 --methods lstsq --tols 1e-3 --backend cpu --certify --out "$T/v" >/dev/null 2>&1
row=$(awkc 'NR>1 && $c["d"]=="-0.1034" {print $c["status"], $c["certified"], ($c["err_upper"] <= $c["tol"] || $c["err_lower"] > $c["tol"])}' "$T/v/results.csv")
check '[ "$row" = "ok yes 1" ]' "a straddling enclosure refined to a verdict: ($row)"
# threads and engines: the same certificate (cert_ns aside)
for v in "--threads 1 --engine level" "--threads 2 --engine group" "--threads 3 --engine level --chunk 7"; do
    rm -rf "$T/t"
    $OB run $R --certify $v --out "$T/t" >/dev/null 2>&1
    check '[ $? -eq 0 ] && [ "$(body "$T/t/results.csv")" = "$(body "$T/c/results.csv")" ]' "$v: the same rows and certificates"
done
# --reps: the first run's pieces are certified, the timings repeated
$OB run $R --certify --reps 2 --out "$T/r" >/dev/null 2>&1
check '[ $? -eq 0 ] && [ "$(dropcols "$T/r/results.csv" time_iqr_ns time_cv | body /dev/stdin)" = "$(body "$T/c/results.csv")" ]' \
    "--reps 2 --certify: the same rows and certificates"
# resume: a journal with some rows certified and one uncertified (a stop
# between the run and its certificate): the uncertified job runs again
mkdir -p "$T/j"
{ printf '#offbench-journal 1 %s\n' "$(cat "$T/c/results.fingerprint")"; head -n 6 "$T/c/results.csv"; } > "$T/j/results.journal.csv"
awk -F, 'BEGIN{OFS=","} NR==7{for(i=NF-8;i<=NF-5;i++) $i=""} NR>=7 && NR<=7' "$T/c/results.csv" >> "$T/j/results.journal.csv"
$OB run $R --certify --threads 2 --resume "$T/j" >/dev/null 2>"$T/j.err"
check '[ $? -eq 0 ] && [ "$(body "$T/j/results.csv")" = "$(body "$T/c/results.csv")" ] && grep -q "5 of [0-9]* jobs restored" "$T/j.err"' \
    "--resume --certify: certified rows restored, the uncertified one rerun: $(cat "$T/j.err" | head -n 2)"
# --certify is the run's own: taken when left out, refused when the run had none
cp "$T/c/results.csv" "$T/c.csv"
$OB run --threads 2 --resume "$T/c" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ "$(body "$T/c/results.csv")" = "$(body "$T/c.csv")" ]' \
    "resume of a certified run without --certify: taken from the run, the same rows and certificates: $(cat "$T/e.txt")"
$OB run $R --out "$T/u" >/dev/null 2>&1
$OB run --certify --resume "$T/u" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--certify (as given), the run.s no --certify" "$T/e.txt"' \
    "resume of an uncertified run with --certify: refused, naming it: $(cat "$T/e.txt")"
# shards: merged, the whole run; a certified shard with an uncertified one: refused
$OB run $R --certify --shard 0/2 --out "$T/s1" >/dev/null 2>&1
$OB run $R --certify --shard 1/2 --out "$T/s2" >/dev/null 2>&1
$OB merge "$T/s1" "$T/s2" --out "$T/m" >/dev/null 2>"$T/m.err"
check '[ $? -eq 0 ] && [ "$(body "$T/m/results.csv")" = "$(body "$T/c/results.csv")" ]' "merged certified shards: the whole run: $(cat "$T/m.err")"
$OB run $R --shard 1/2 --out "$T/u2" >/dev/null 2>&1
$OB merge "$T/s1" "$T/u2" --out "$T/mu" >/dev/null 2>"$T/e.txt"
check '[ $? -ne 0 ] && [ ! -e "$T/mu/results.csv" ]' "a certified shard merged with an uncertified one: refused: $(head -n 1 "$T/e.txt")"
# the reader: compare reads them; a certificate that contradicts itself is refused, naming the line
$OB compare "$T/c/results.csv" "$T/t/results.csv" >/dev/null 2>&1
check '[ $? -eq 0 ]' "compare of two certified runs"
awk -F, 'BEGIN{OFS=","} NR==2{$(NF-6)=($(NF-6)=="yes"?"no":"yes")} {print}' "$T/c/results.csv" > "$T/x.csv"
$OB compare "$T/c/results.csv" "$T/x.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "x.csv:2: certified must be yes exactly when err_upper <= tol" "$T/e.txt"' \
    "a certified column that contradicts err_upper: $(cat "$T/e.txt")"
awk -F, 'BEGIN{OFS=","} NR==2{$(NF-5)=""} {print}' "$T/c/results.csv" > "$T/x.csv"
$OB compare "$T/c/results.csv" "$T/x.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "x.csv:2: err_upper, err_lower, certified and cert_ns are all empty or all set" "$T/e.txt"' \
    "a certificate without its time: $(cat "$T/e.txt")"
# compare: a job certified within tol in BASE and not in NEW is a regression
awk -F, 'BEGIN{OFS=","} NR>1 && !done && $(NF-6)=="yes" {$(NF-8)=$6*2; $(NF-6)="no"; done=1} {print}' "$T/c/results.csv" > "$T/x.csv"
$OB compare "$T/c/results.csv" "$T/x.csv" >"$T/cmp.txt" 2>&1
check '[ $? -eq 1 ] && grep -q "certified" "$T/cmp.txt"' "compare: certified yes to no is a regression: $(grep -i certified "$T/cmp.txt" | head -n 2)"
$OB compare "$T/x.csv" "$T/c/results.csv" >"$T/cmp.txt" 2>&1
check '[ $? -eq 0 ]' "compare: certified no to yes is not a regression"
# draw and trace show one job: --certify is not theirs
$OB draw --curve liu2002_ex1 --method tiller --tol 1e-2 --certify --out "$T/d.svg" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ]' "draw --certify: refused: $(cat "$T/e.txt")"
e2e_done
