#!/bin/sh
# NIGHTLY_METHODS_FILE (scripts/nightly.sh): the nightly's two runs add the
# external methods a methods file names (docs/external-methods.md "A
# methods file"), OpenCASCADE's and lib2geom's where built; against a
# baseline without them their rows are new, not regressions.  Here a
# method every build has stands in for them: `offbench worker tiller`.
# The small nightly on two methods, the CPU backend: some 15 s.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2

printf '[tiller_w]\ncommand = %s worker tiller\n' "$OB" >"$T/w.methods"
NIGHTLY_BIN=$OB NIGHTLY_METHODS=tiller,tiller_w NIGHTLY_METHODS_FILE=$T/w.methods NIGHTLY_BACKEND=cpu \
    sh scripts/nightly.sh --size small --out "$T/n" --history none >"$T/out" 2>&1
rc=$?
check '[ $rc -eq 0 ] && [ "$(cat "$T/n/status")" = 0 ]' "the nightly with a methods file: exit 0: $(tail -n 4 "$T/out")"
for r in published random; do
    n=$(awkc 'FNR > 1 && $c["method"] == "tiller_w"' "$T/n/$r/results.csv" | wc -l)
    k=$(awkc 'FNR > 1 && $c["method"] == "tiller"' "$T/n/$r/results.csv" | wc -l)
    check '[ "$n" -gt 0 ] && [ "$n" -eq "$k" ]' "the $r run has tiller_w's rows, as many as tiller's: $n and $k"
done
check 'grep -q "[1-9][0-9]* new rows" "$T/n/compare-published-quality.md"' \
    "against the committed baseline they are new rows: $(grep -o "[0-9]* new rows" "$T/n/compare-published-quality.md")"
# without the variable the runs are as before: no external method
NIGHTLY_BIN=$OB NIGHTLY_METHODS=tiller NIGHTLY_BACKEND=cpu sh scripts/nightly.sh --size small --out "$T/m" --history none \
    >"$T/out2" 2>&1
check '[ $? -eq 0 ] && [ -z "$(awkc "FNR > 1 && \$c[\"method\"] != \"tiller\"" "$T/m/published/results.csv")" ]' \
    "without NIGHTLY_METHODS_FILE only the methods asked: $(tail -n 2 "$T/out2")"
e2e_done
