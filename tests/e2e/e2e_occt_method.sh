#!/bin/sh
# OpenCASCADE as an external method (issue 49 item 3, docs/cad-example.md
# "OCCT as a method"): examples/occt/occt_worker.cpp speaking the protocol
# of docs/external-methods.md.
# - Always: `make occt-worker` without OpenCASCADE's headers fails naming
#   the Debian packages, building nothing.
# - With the headers and g++ (else these checks count as skipped, with the
#   reason and the install line; E2E_OCCT_ABSENT=1 skips them as if absent):
#   the worker builds; `list methods` shows it (OCCT's version, degree 8);
#   `run --methods occt,tiller` gives occt a row for every job tiller has,
#   all ok, with max_err measured by offbench within the tolerance;
#   --threads 1 and 2 give the same rows; on a one-piece curve its counts
#   (poles, spans) are examples/occt/occt_offset.cpp's for the same job,
#   a check of the protocol's route independent of it; malformed requests
#   sent by hand are answered with errors, and the worker goes on.
# Uses $OFFBENCH (set by make) or ./offbench; python3 (scripts/same_rows.py).
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory "$@"; }

# --- the make target without OpenCASCADE's headers ---
occt_nohdr occt-worker OCCT_WORKER

occt_require e2e_occt_method 13

W=$T/occt_worker
mk OCCT_WORKER="$W" occt-worker >"$T/build.out" 2>&1
check '[ $? -eq 0 ] && [ -x "$W" ]' "make occt-worker builds the worker: $(tail -n 5 "$T/build.out" | tr '\n' ' ')"

"$OB" --external "occt=$W" list methods >"$T/list" 2>"$T/list.err"
check '[ $? -eq 0 ] && grep -q "^occt .* 8 .*OpenCASCADE [0-9][0-9.]*: Geom2dConvert_ApproxCurve" "$T/list" && grep -q "external method: $W" "$T/list"' \
    "list methods shows occt, its degree and OCCT's version: $(grep "^occt" "$T/list") $(cat "$T/list.err")"

# --- rows beside tiller's, with 1 and 2 threads ---
R="--curve liu2002_ex1,liu2002_ex2,atlas_circle,ph_cubic --tols 1e-2,1e-3,1e-4 --backend cpu --methods occt,tiller"
for th in 1 2; do
    "$OB" run $R --external "occt=$W" --threads $th --out "$T/p$th" >/dev/null 2>"$T/p$th.err"
    check '[ $? -eq 0 ]' "run --methods occt,tiller --threads $th: exit 0: $(tail -n 2 "$T/p$th.err")"
done
P=$T/p1/results.csv
jobs() { awkc 'FNR>1 && $c["method"]==m {print $c["curve"] ":" $c["d"] ":" $c["tol"]}' m="$1" "$P" | sort | tr '\n' ' '; }
check '[ -n "$(jobs tiller)" ] && [ "$(jobs occt)" = "$(jobs tiller)" ]' "occt has a row for every job tiller has: $(jobs occt)"
check '[ -z "$(awkc "FNR>1 && \$c[\"method\"]==\"occt\" && \$c[\"status\"]!=\"ok\"" "$P")" ]' \
    "every occt row is ok: $(awkc 'FNR>1 && $c["method"]=="occt" && $c["status"]!="ok"' "$P" | head -n 3)"
check '[ -z "$(awkc "FNR>1 && \$c[\"method\"]==\"occt\" && !(\$c[\"max_err\"] != \"\" && \$c[\"max_err\"] + 0 <= \$c[\"tol\"] + 0)" "$P")" ]' \
    "offbench measured every occt row within its tolerance"
out=$(python3 scripts/same_rows.py "$T/p1/results.csv" "$T/p2/results.csv")
check '[ $? -eq 0 ]' "--threads 1 and 2 give the same rows: $out"

# --- the same approximation as occt_offset's, job for job ---
# liu2002_ex1 is one Bezier piece that the driver fits whole, so the
# worker's answer is occt_offset's B-spline: its poles are the row's
# ctrl_points, its spans the row's segments (occt_offset's C2, degree 8,
# with the worker's 64 segments at most).
O=$T/occt_offset
mk OCCT_BIN="$O" occt-bin >"$T/obuild.out" 2>&1 && mkdir "$T/o" &&
    "$O" --curves datasets/published.curves --curve liu2002_ex1 --d 1,-1 --tols 1e-2,1e-3,1e-4 \
        --max-segments 64 --out "$T/o" 2>/dev/null
check '[ $? -eq 0 ]' "occt_offset on liu2002_ex1: $(tail -n 3 "$T/obuild.out")"
want=$(awkc 'FNR>1 {print $c["d"] ":" $c["tol"] ":" $c["poles"] ":" $c["spans"]}' "$T/o/occt.csv" | sort | tr '\n' ' ')
got=$(awkc 'FNR>1 && $c["method"]=="occt" && $c["curve"]=="liu2002_ex1" {print $c["d"] ":" $c["tol"] ":" $c["ctrl_points"] ":" $c["segments"]}' "$P" | sort | tr '\n' ' ')
check '[ -n "$want" ] && [ "$got" = "$want" ]' "the worker's poles and spans are occt_offset's: occt_offset $want; worker $got"

# --- malformed requests by hand: error answers, never a crash ---
good='{"id":9,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":0.5,"tol":0.001,"params":{}}'
printf '%s\n' 'hello' '{"id":1,"degree":2}' '{"id":2,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":NaN,"tol":0.001,"params":{}}' \
    '{"id":3,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":0.5,"tol":0.001,"params":{},"extra":1}' \
    '{"id":4,"degree":1,"points":[[0,0],[1,0]],"weights":[1,-1],"d":0.5,"tol":0.001,"params":{}}' \
    '[[[[[[[[1]]]]]]]]' '{"id":5,"degree":2,"points":[[0,0],[0,0],[0,0]],"weights":[1,1,1],"d":0.5,"tol":0.001,"params":{}}' \
    "$good" | "$W" >"$T/hand.out" 2>"$T/hand.err"
rc=$?
check '[ $rc -eq 0 ] && [ "$(wc -l <"$T/hand.out")" -eq 9 ] && [ "$(grep -c "\"error\":" "$T/hand.out")" -eq 7 ]' \
    "7 malformed or degenerate requests: 7 error answers, exit $rc: $(cat "$T/hand.out" "$T/hand.err" | tr '\n' ' ' | cut -c 1-600)"
check 'tail -n 1 "$T/hand.out" | grep -q "^{\"id\":9,\"pieces\":\[{\"degree\":8,"' \
    "after them a good request is answered: $(tail -n 1 "$T/hand.out" | cut -c 1-200)"
check 'sed -n 3p "$T/hand.out" | grep -q "^{\"id\":1,\"error\":\"bad request: no .\"points.\"" && sed -n 2p "$T/hand.out" | grep -q "^{\"id\":null,"' \
    "an error answer carries the request's id when it has one: $(sed -n 2,3p "$T/hand.out" | tr '\n' ' ')"
e2e_done
