#!/bin/sh
# join_rounds.sh OUT RUN... - one run set from several `run --time-fits`
# runs of one build and one configuration, for interleaved timing (asv's
# "continuous": the baseline build and the new one run alternately in one
# night, so that a burst of load hits both sides; scripts/nightly.sh with
# NIGHTLY_BASE_REF, scripts/nightly_power.sh).
#
# OUT gets the first RUN's results.csv, meta.json and samples.csv (when it
# has one), and a fits.csv holding every RUN's rounds one after the other,
# renumbered 1..R1, R1+1..R1+R2, ...: compare then sees them as one run's
# rounds.  Every RUN must have a fits.csv with the same header; compare's
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
[ ! -f "$first/samples.csv" ] || cp "$first/samples.csv" "$out.tmp/" || exit 2
for r in "$@"; do set -- "$@" "$r/fits.csv"; shift; done  # the runs' fits.csv, paths kept whole
# each file's rounds shifted by the rounds before it; the round is the
# third field from the end (round,fit_calls,method_ns: a quoted curve id
# with a comma cannot move it)
awk -F, 'BEGIN {OFS = ","}
    FNR == 1 { if (NR == 1) print; base += last; last = 0; next }
    { rc = NF - 2; r = $rc + 0; if (r > last) last = r; $rc = r + base; print }' "$@" >"$out.tmp/fits.csv" || exit 2
rm -rf "$out" && mv "$out.tmp" "$out"
