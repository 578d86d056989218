#!/bin/sh
# End-to-end test of `run --time-fits` (issue 46, host/run/fittime.h): each
# method's own time as a microbenchmark.  What is checked is what cannot
# depend on the machine's speed or load (no timed assertion):
# - the columns fit_calls, method_ns, method_iqr_ns: set exactly for the
#   jobs with an approximation (ok, limit), empty for the others and
#   without --time-fits; fit_calls is the job's accepted fits (its
#   segments for one-piece fits), the same in every run;
# - fits.csv: one row per timed job and round, its fit_calls the row's,
#   method_ns the median of its rounds (results.csv);
# - no other column moves: rows with and without --time-fits are the same,
#   timing columns aside, and the same with 1 and 2 threads;
# - meta.json's fit_timing; the options' errors (--fit-reps without
#   --time-fits, --resume with it, bad values);
# - compare reads the method times: it judges them (the per-method table
#   says "the methods' own fit time") and its reader refuses a fits.csv
#   whose fit_calls is not the row's.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

J="--curve liu2002_ex1 --methods tiller,ahn,sisl,lee --tols 1e-2,1e-4 --metric radial --backend cpu"
"$OB" run $J --time-fits --fit-reps 4 --fit-min-time 0.2 --out "$T/a" 2>"$T/a.err"
check '[ $? -eq 0 ] && [ -s "$T/a/fits.csv" ]' "run --time-fits: exit 0, fits.csv written: $(tail -n 1 "$T/a.err")"
check 'grep -q "fits timed [1-9][0-9]* (" "$T/a.err"' "the closing line counts the timed jobs: $(tail -n 1 "$T/a.err")"
# set exactly for ok and limit; sisl is skipped under radial (no same parameter): empty there
bad=$(awkc 'NR>1 { has = $c["fit_calls"] != "" && $c["method_ns"] != "";
                   want = $c["status"] == "ok" || $c["status"] == "limit";
                   if (has != want) print $c["method"], $c["tol"], $c["status"], $c["fit_calls"] }' "$T/a/results.csv")
check '[ -z "$bad" ]' "the method time is set exactly for jobs with an approximation: $bad"
check 'awkc "NR>1 && \$c[\"status\"]==\"skip\"" "$T/a/results.csv" | grep -q .' "the fixture has skipped jobs (sisl under radial)"
check 'awkc "NR>1 && \$c[\"status\"]==\"ok\" && \$c[\"method_ns\"] + 0 > 0 && \$c[\"method_iqr_ns\"] != \"\"" "$T/a/results.csv" | grep -q .' \
    "ok jobs have a positive method_ns and a spread (4 rounds)"
# fit_calls: one fit per accepted piece; tiller and ahn fit one segment per piece
bad=$(awkc 'NR>1 && ($c["method"] == "tiller" || $c["method"] == "ahn") && $c["fit_calls"] != $c["segments"] {print}' "$T/a/results.csv")
check '[ -z "$bad" ]' "fit_calls is the segments of one-piece fits: $bad"

# fits.csv: rounds x timed jobs, fit_calls the row's, method_ns their median
timed=$(awkc 'NR>1 && $c["fit_calls"] != ""' "$T/a/results.csv" | wc -l)
check '[ "$(head -n 1 "$T/a/fits.csv")" = "curve,d,method,metric,split,tol,round,fit_calls,method_ns" ] && [ $(($(wc -l <"$T/a/fits.csv") - 1)) -eq $((4 * timed)) ]' \
    "fits.csv: the header and 4 rounds of each of the $timed timed jobs"
rcols "$T/a/results.csv" curve d method tol fit_calls method_ns | awk -F: '$5 != ""' >"$T/rows.txt"
med=$(awk -F, 'NR==FNR {if (FNR > 1) {k=$1 ":" $2 ":" $3 ":" $6; v[k]=v[k] " " $9; calls[k]=$8}; next}
    {k=$1 ":" $2 ":" $3 ":" $4; n=split(v[k], a, " ")
     for (i=1;i<=n;i++) for (j=i+1;j<=n;j++) if (a[j]+0 < a[i]+0) {t=a[i]; a[i]=a[j]; a[j]=t}
     m = (a[2] + a[3]) / 2; print (n == 4 && m == $6 + 0 && calls[k] == $5) ? "same" : "differs " k " " m " " $6}' FS=, "$T/a/fits.csv" FS=: "$T/rows.txt" | sort -u)
check '[ "$med" = "same" ]' "method_ns is the median of the row's rounds in fits.csv, fit_calls the same: $med"
check 'grep -q "\"fit_timing\": {\"rounds\": 4, \"min_time_ms\": 0.2," "$T/a/meta.json"' "meta.json's fit_timing"

# no other column moves: without --time-fits, and on 1 thread
"$OB" run $J --out "$T/b" 2>/dev/null
"$OB" run $J --time-fits --fit-reps 2 --fit-min-time 0.1 --threads 1 --out "$T/c" 2>/dev/null
check '[ "$(dropcols "$T/a/results.csv" fit_ns eval_ns method_ns method_iqr_ns fit_calls)" = "$(dropcols "$T/b/results.csv" fit_ns eval_ns method_ns method_iqr_ns fit_calls)" ]' \
    "rows with and without --time-fits are the same, timings aside"
check '[ "$(csvcols "$T/b/results.csv" fit_calls method_ns method_iqr_ns | sort -u)" = "$(printf ",,\nfit_calls,method_ns,method_iqr_ns")" ]' \
    "without --time-fits the three columns are empty"
check '[ "$(dropcols "$T/a/results.csv" fit_ns eval_ns method_ns method_iqr_ns)" = "$(dropcols "$T/c/results.csv" fit_ns eval_ns method_ns method_iqr_ns)" ]' \
    "2 threads and 1 thread: the same rows and fit_calls"
check 'grep -q "\"fit_timing\": null" "$T/b/meta.json" && [ ! -e "$T/b/fits.csv" ]' "no fits.csv, fit_timing null without it"

# the options' errors
"$OB" run $J --fit-reps 3 --out "$T/e1" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "add --time-fits" "$T/err"' "--fit-reps without --time-fits: exit 2: $(cat "$T/err")"
"$OB" run $J --time-fits --fit-min-time 0 --out "$T/e2" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q -- "--fit-min-time: expected milliseconds > 0" "$T/err"' "--fit-min-time 0: exit 2: $(cat "$T/err")"
"$OB" run $J --time-fits --fit-reps 0 --out "$T/e3" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q -- "--fit-reps" "$T/err"' "--fit-reps 0: exit 2: $(cat "$T/err")"
"$OB" run --resume "$T/b" $J --time-fits 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "not with --time-fits" "$T/err"' "--resume with --time-fits: exit 2: $(cat "$T/err")"

# compare judges the method times; a fits.csv that does not match is refused
"$OB" run $J --time-fits --fit-reps 4 --fit-min-time 0.2 --out "$T/d" 2>/dev/null
"$OB" compare "$T/a" "$T/d" --timing-only --method-timing-only >"$T/out" 2>"$T/err"
rc=$?
check '[ $rc -ne 2 ] && grep -q "the methods. own fit time (--time-fits)" "$T/out" && grep -q "^| tiller | .*per-round\|^| tiller |" "$T/out"' \
    "compare judges the methods' own fit time (exit $rc): $(grep '^Timing' "$T/out")"
# NEW with many more rounds than BASE (its 4 joined 6 times: 24): every
# round is read and judged (the per-method buffers once had room for BASE's
# count only: a heap overflow)
sh "$(dirname "$0")/../../scripts/join_rounds.sh" "$T/d24" "$T/d" "$T/d" "$T/d" "$T/d" "$T/d" "$T/d"
"$OB" compare "$T/a" "$T/d24" --timing-only --method-timing-only --format csv >"$T/out" 2>"$T/err"
rc=$?
check '[ $rc -ne 2 ] && [ "$(awk -F, "NR>1 {print \$7}" "$T/d24/fits.csv" | sort -n | tail -n 1)" = 24 ] && grep -q "^method,,,tiller,,,,time_total," "$T/out"' \
    "24 rounds against 4: judged (exit $rc): $(grep "time_total" "$T/out" | head -n 1) $(head -c 300 "$T/err")"
mkdir "$T/f" && cp "$T/a/results.csv" "$T/a/meta.json" "$T/f/"
awk -F, 'BEGIN{OFS=","} NR==2{$8=$8+1} {print}' "$T/a/fits.csv" >"$T/f/fits.csv"
"$OB" compare "$T/a" "$T/f" >"$T/out" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "fits.csv:2: fit_calls differs from the job.s in results.csv" "$T/err"' \
    "a fits.csv whose fit_calls is not the row's: exit 2 naming FILE:LINE: $(cat "$T/err")"
e2e_done
