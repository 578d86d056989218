#!/bin/sh
# lib2geom's offset as an external method (issue 49 item 3, the graphics
# library; docs/cad-example.md "A graphics library's offset: lib2geom"):
# examples/lib2geom/lib2geom_worker.cpp speaking the protocol of
# docs/external-methods.md.
# - Always: `make lib2geom-worker` where pkg-config finds no lib2geom fails
#   naming the Debian package, building nothing.
# - With lib2geom-dev and g++ (else these checks count as skipped, with the
#   reason and the install line): the worker builds; `list methods` shows it
#   (lib2geom's version, degree 3); its cubics are lib2geom's own
#   path_from_piecewise's, point for point, on requests of degree 1 to 5
#   (--check-path); `run --methods lib2geom,tiller` gives it a row for every
#   job tiller has, ok within the tolerance as offbench measures it on the
#   polynomial curves, skip (with the reason) on the rational one; --threads
#   1 and 2 give the same rows; a straight line's offset lies on the exact
#   one to rounding (the sign of d); malformed requests are error answers.
# Uses $OFFBENCH (set by make) or ./offbench; python3 (scripts/same_rows.py).
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory "$@"; }

# --- the make target without lib2geom ---
mkdir "$T/nopc"
PKG_CONFIG_LIBDIR="$T/nopc" PKG_CONFIG_PATH= mk LIB2GEOM_WORKER="$T/nobin" lib2geom-worker >"$T/nolib.out" 2>&1
check '[ $? -ne 0 ] && grep -q "apt-get install lib2geom-dev g++" "$T/nolib.out" && [ ! -e "$T/nobin" ]' \
    "make lib2geom-worker without lib2geom: fails naming the Debian package: $(tr '\n' ' ' <"$T/nolib.out")"

if ! pkg-config --exists 2geom 2>/dev/null || ! command -v g++ >/dev/null 2>&1 || [ -n "${E2E_LIB2GEOM_ABSENT:-}" ]; then
    echo "e2e_lib2geom_method: no lib2geom (pkg-config 2geom) or no g++ (apt-get install lib2geom-dev g++): 11 checks skipped"
    skipped=$((skipped + 11))
    e2e_done
    exit $?
fi

W=$T/lib2geom_worker
mk LIB2GEOM_WORKER="$W" lib2geom-worker >"$T/build.out" 2>&1
check '[ $? -eq 0 ] && [ -x "$W" ]' "make lib2geom-worker builds the worker: $(tail -n 5 "$T/build.out" | tr '\n' ' ')"

"$OB" --external "lib2geom=$W" list methods >"$T/list" 2>"$T/list.err"
check '[ $? -eq 0 ] && grep -q "^lib2geom .* 3 .*lib2geom [0-9][0-9.]*: B + d rot90(unitVector" "$T/list"' \
    "list methods shows lib2geom, its degree and version: $(grep "^lib2geom" "$T/list") $(cat "$T/list.err")"

# --- the worker's cubics are path_from_piecewise's ---
n=0 same=0 out=""
for req in '"degree":1,"points":[[0,0],[3,1]],"weights":[1,1],"d":0.5,"tol":0.001' \
    '"degree":2,"points":[[0,0],[1,1],[2,0]],"weights":[1,1,1],"d":2,"tol":0.01' \
    '"degree":3,"points":[[0,0],[1,2],[3,2],[4,0]],"weights":[1,1,1,1],"d":0.5,"tol":0.001' \
    '"degree":3,"points":[[0,0],[1,2],[3,2],[4,0]],"weights":[1,1,1,1],"d":-1.5,"tol":1e-6' \
    '"degree":5,"points":[[0,0],[1,3],[2,-1],[3,2],[5,2],[4,0]],"weights":[1,1,1,1,1,1],"d":-0.3,"tol":1e-5'; do
    n=$((n + 1))
    o=$(printf '{"id":1,%s,"params":{}}\n' "$req" | "$W" --check-path) && same=$((same + 1))
    out="$out [$o]"
done
check '[ $same -eq $n ]' "the worker's cubics are path_from_piecewise's on $same of $n requests:$out"

# --- rows beside tiller's, with 1 and 2 threads ---
R="--curve liu2002_ex1,liu2002_ex2,atlas_circle,ph_cubic,line --tols 1e-2,1e-3,1e-4 --backend cpu --methods lib2geom,tiller"
for th in 1 2; do
    "$OB" run $R --external "lib2geom=$W" --threads $th --out "$T/p$th" >/dev/null 2>"$T/p$th.err"
    check '[ $? -eq 0 ]' "run --methods lib2geom,tiller --threads $th: exit 0: $(tail -n 2 "$T/p$th.err")"
done
P=$T/p1/results.csv
jobs() { awkc 'FNR>1 && $c["method"]==m {print $c["curve"] ":" $c["d"] ":" $c["tol"]}' m="$1" "$P" | sort | tr '\n' ' '; }
check '[ -n "$(jobs tiller)" ] && [ "$(jobs lib2geom)" = "$(jobs tiller)" ]' "lib2geom has a row for every job tiller has: $(jobs lib2geom)"
bad_rows=$(awkc 'FNR>1 && $c["method"]=="lib2geom" && !($c["curve"]=="atlas_circle" ? $c["status"]=="skip" && $c["message"] ~ /rational/ : $c["status"]=="ok" && $c["max_err"] != "" && $c["max_err"] + 0 <= $c["tol"] + 0)' "$P")
check '[ -z "$bad_rows" ]' "lib2geom is ok within the tolerance on the polynomial curves and skips the rational circle: $(echo "$bad_rows" | head -n 3)"
line_err=$(awkc 'FNR>1 && $c["method"]=="lib2geom" && $c["curve"]=="line" {print $c["max_err"]}' "$P" | sort -g | tail -n 1)
check 'awk -v e="$line_err" "BEGIN{exit !(e != \"\" && e + 0 < 1e-12)}"' \
    "a straight line's lib2geom offset is the exact one to rounding (the sign of d): max_err $line_err"
out=$(python3 scripts/same_rows.py "$T/p1/results.csv" "$T/p2/results.csv")
check '[ $? -eq 0 ]' "--threads 1 and 2 give the same rows: $out"

# --- malformed requests by hand: error answers, never a crash ---
printf '%s\n' 'hello' '{"id":1,"degree":2}' '{"id":2,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":0,"tol":0.001,"params":{}}' \
    '{"id":3,"degree":1,"points":[[0,0],[0,0]],"weights":[1,1],"d":0.5,"tol":0.001,"params":{}}' \
    '{"id":4,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":0.5,"tol":0.001,"params":{"k":1}}' \
    '{"id":9,"degree":1,"points":[[0,0],[1,0]],"weights":[1,1],"d":0.5,"tol":0.001,"params":{}}' | "$W" >"$T/hand.out" 2>"$T/hand.err"
rc=$?
# A piece shrunk to a point is no error to lib2geom: its unitVector of a
# zero vector is (1, 0), so the "offset" is the point moved by d along +y.
# The worker passes lib2geom's answer on (the driver never sends such a
# piece; offbench would measure it).
check '[ $rc -eq 0 ] && [ "$(wc -l <"$T/hand.out")" -eq 7 ] && [ "$(grep -c "\"error\":" "$T/hand.out")" -eq 4 ] && tail -n 1 "$T/hand.out" | grep -q "^{\"id\":9,\"pieces\":\[{\"degree\":3,"' \
    "4 malformed requests: 4 error answers, then good ones answered, exit $rc: $(cat "$T/hand.out" "$T/hand.err" | tr '\n' ' ' | cut -c 1-600)"
check 'sed -n 5p "$T/hand.out" | grep -q "^{\"id\":3,\"pieces\":\[{\"degree\":3,\"points\":\[\[0,0.5\],\[0,0.5\]"' \
    "a piece shrunk to a point: lib2geom's answer, the point moved by d along +y: $(sed -n 5p "$T/hand.out")"
e2e_done
