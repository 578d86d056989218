#!/bin/sh
# join_rounds.sh OUT RUN... - one run set from several `run --time-fits`
# runs of one build and one configuration, for interleaved timing (asv's
# "continuous": the baseline build and the new one run alternately in one
# night, so that a burst of load hits both sides; scripts/nightly.sh with
# NIGHTLY_BASE_REF, scripts/nightly_power.sh).
#
# OUT gets the first RUN's results.csv and meta.json, a fits.csv holding
# every RUN's rounds one after the other, renumbered 1..R1, R1+1..R1+R2,
# ...: compare then sees them as one run's rounds; and likewise a
# samples.csv of every RUN's repetitions (--reps) when each RUN has one,
# meta.json's reps then their total.  Every RUN must have a fits.csv (the
# header of run --time-fits); compare's
# reader checks that each round's fit_calls is the row's (the runs did the
# same jobs).  Exit 0, or 2 with the reason.
set -u
[ $# -ge 2 ] || { echo "join_rounds: usage: join_rounds.sh OUT RUN..." >&2; exit 2; }
out=$1; shift
first=$1
for r in "$@"; do
    [ -f "$r/fits.csv" ] && [ -f "$r/results.csv" ] && [ -f "$r/meta.json" ] ||
        { echo "join_rounds: $r: not a run with --time-fits (results.csv, meta.json, fits.csv)" >&2; exit 2; }
    [ "$(head -n 1 "$r/fits.csv")" = "curve,d,method,metric,split,tol,round,fit_calls,method_ns" ] ||
        { echo "join_rounds: $r/fits.csv: not the header of run --time-fits" >&2; exit 2; }
done
rm -rf "$out.tmp" && mkdir -p "$out.tmp" || exit 2
cp "$first/results.csv" "$first/meta.json" "$out.tmp/" || exit 2
# join FILE OUTFILE RUN...: RUN/FILE one after the other, each file's
# repetitions shifted by those before it; the repetition is the third field
# from the end in both files (round,fit_calls,method_ns and rep,fit_ns,
# eval_ns: a quoted curve id with a comma cannot move it)
join() {
    f=$1 o=$2; shift 2
    for r in "$@"; do set -- "$@" "$r/$f"; shift; done  # paths kept whole
    awk -F, 'BEGIN {OFS = ","}
        FNR == 1 { if (NR == 1) print; base += last; last = 0; next }
        { rc = NF - 2; r = $rc + 0; if (r > last) last = r; $rc = r + base; print }' "$@" >"$o"
}
join fits.csv "$out.tmp/fits.csv" "$@" || exit 2
all_samples=1
for r in "$@"; do [ -f "$r/samples.csv" ] || all_samples=0; done
if [ $all_samples = 1 ]; then
    join samples.csv "$out.tmp/samples.csv" "$@" || exit 2
    # meta.json's reps must say how many the joined samples.csv holds (compare checks it)
    total=$(awk -F, 'NR > 1 {r = $(NF - 2) + 0; if (r > m) m = r} END {print m + 0}' "$out.tmp/samples.csv")
    sed "s/^  \"reps\": [0-9]*,/  \"reps\": $total,/" "$first/meta.json" >"$out.tmp/meta.json" || exit 2
fi
rm -rf "$out" && mv "$out.tmp" "$out"
