#!/bin/sh
# Every malformed curve file in tests/data/bad_curves/ given to the program itself:
# `./offbench run --curves FILE` exits 2 before any work, writes no results,
# and its message names FILE and the line its first line "# expect-line: N"
# gives (a file that needs another loaded first, marked "# also-load:", is
# left to test_curvefile.c and counted as skipped).  Under `make SAN=1 test` $OFFBENCH is the ASan/UBSan build, so a leak
# or a sanitizer report changes the exit status and fails the check.
. "$(dirname "$0")/lib_e2e.sh"

n=0
for f in tests/data/bad_curves/*.curves; do
    n=$((n + 1))
    line=$(head -n 1 "$f" | sed -n 's/^# expect-line: \([0-9][0-9]*\).*/\1/p')
    if [ -z "$line" ]; then
        bad "$f: no '# expect-line: N' first line"
        continue
    fi
    if grep -q '^# also-load: ' "$f"; then  # needs another file loaded first: test_curvefile.c covers it
        skipped=$((skipped + 1))
        continue
    fi
    "$OB" run --curves "$f" --methods tiller --tols 1e-1 --out "$T/out$n" >/dev/null 2>"$T/err"
    rc=$?
    if [ $rc -eq 2 ] && grep -q -F "$f:$line:" "$T/err" && [ ! -e "$T/out$n/results.csv" ] \
       && ! grep -q -E "Sanitizer|runtime error" "$T/err"; then
        ok
    else
        bad "$f: exit $rc, expected 2 and '$f:$line:' in: $(head -c 300 "$T/err")"
    fi
done
if [ $n -ge 50 ]; then ok; else bad "only $n malformed curve files (at least 50 wanted)"; fi

# Degenerate geometry inside a run (tests/data/hostile/geometry.curves: a cusp, an
# arc offset by its own radius, a line, nearly parallel legs, a doubled
# control point): every method ends every job with a status, non-ok ones with
# a message; the run goes on and exits 0.  SISL runs away on the collapsing
# arc: its deadline (1 s here) stops it (its wall-clock cap set far beyond:
# the CPU deadline is what this checks, whatever the machine's load).
"$OB" run --curves tests/data/hostile/geometry.curves --methods all --tols 1e-2 --param sisl.timeout=1 \
    --param sisl.wall_timeout=3600 --out "$T/hostile" >/dev/null 2>"$T/err"
rc=$?
rows=$(($(wc -l < "$T/hostile/results.csv") - 1))
nm=$(rcols "$T/hostile/results.csv" method | sort -u | wc -l)
nomsg=$(awkc 'NR>1 && $c["status"] != "ok" && $c["message"] == ""' "$T/hostile/results.csv" | wc -l)
badst=$(awkc 'NR>1 && $c["status"] !~ /^(ok|limit|fail|skip)$/' "$T/hostile/results.csv" | wc -l)
if [ $rc -eq 0 ] && [ $nm -ge 16 ] && [ $rows -eq $((7 * nm)) ] && [ $nomsg -eq 0 ] && [ $badst -eq 0 ]; then ok; else
    bad "hostile geometry: exit $rc, $rows rows (7 x $nm methods wanted), $nomsg non-ok rows without a message, $badst bad statuses"; fi
if grep -q '^arc_d_is_radius,1,sisl,.*,fail,.*did not finish in 1 s' "$T/hostile/results.csv"; then ok; else
    bad "SISL's runaway on the collapsing arc is stopped: $(grep '^arc_d_is_radius,1,sisl' "$T/hostile/results.csv")"; fi

echo "$pass passed, $fail failed, $skipped skipped"
[ $fail -eq 0 ]
