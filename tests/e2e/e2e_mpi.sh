#!/bin/sh
# mpirun -n 2 ./offbench run ... (the build with make MPI=1): the ranks split
# the run and rank 0 writes exactly the single-process results.csv.  Skipped
# (and counted so) when the program is not built with MPI or mpirun is
# missing: `make MPI=1 test` runs it.
. "$(dirname "$0")/lib_e2e.sh"

if ! command -v mpirun >/dev/null 2>&1 || ! ldd "$OB" 2>/dev/null | grep -q libmpi; then
    echo "SKIP: $OB is not built with MPI (make MPI=1) or mpirun is missing" >&2
    echo "0 passed, 0 failed, 6 skipped"
    exit 0
fi
# Open MPI refuses root unless told; --oversubscribe: 2 ranks on any core count
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
MPIRUN="mpirun -n 2 --oversubscribe"

R="--random 24:5 --methods tiller,ahn,zhao,lee --tols 1e-1,1e-3 --backend cpu --threads 1"
$OB run $R --out "$T/one" 2>/dev/null
check '[ $? -eq 0 ]' "single-process run"
$MPIRUN "$OB" run $R --out "$T/two" >/dev/null 2>"$T/two.err"
check '[ $? -eq 0 ] && body "$T/two/results.csv" | cmp -s - "$(body "$T/one/results.csv" > "$T/one.txt"; echo "$T/one.txt")"' \
    "mpirun -n 2 equals the single-process run: $(tail -n 1 "$T/two.err")"
check 'grep -q "\"mpi_ranks\": 2" "$T/two/meta.json" && grep -q "\"shard\": null" "$T/two/meta.json"' "meta.json says 2 ranks"
$MPIRUN "$OB" run $R --reps 2 --out "$T/reps" >/dev/null 2>&1
n=$(($(wc -l < "$T/one/results.csv") - 1))
check '[ $? -eq 0 ] && [ $(($(wc -l < "$T/reps/samples.csv") - 1)) -eq $((2 * n)) ] && body "$T/reps/results.csv" | cmp -s - "$T/one.txt"' \
    "mpirun with --reps 2: results and samples.csv gathered"
$MPIRUN "$OB" run $R --shard 0/2 --out "$T/x" >/dev/null 2>"$T/e.txt"
check '[ $? -ne 0 ] && grep -q -- "--shard" "$T/e.txt"' "--shard under mpirun is refused: $(head -n 1 "$T/e.txt")"
$OB compare "$T/one" "$T/two" --no-timing >/dev/null 2>&1
check '[ $? -eq 0 ]' "compare: the MPI run is the same"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
