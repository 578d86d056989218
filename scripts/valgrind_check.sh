#!/bin/sh
# valgrind_check.sh [PROGRAM] - a short run, compare and draw of the program
# under valgrind (memcheck), and a malformed curve file: definite leaks and
# memory errors fail it (libgomp's thread pool is "possibly lost" and not
# ours).  Every method named runs in the checked process or, for sisl, in
# the server it executes, so a run with a failed job fails the check: the
# server must start under valgrind too (it once did not: /proc/self/exe was
# valgrind's own image).  Exit 0 clean, 1 a check failed, 77 no valgrind.
# Used by .ci/run and tests/e2e/e2e_valgrind.sh.
set -u
OB=${1:-./offbench}
command -v valgrind >/dev/null 2>&1 || { echo "valgrind_check: valgrind not available" >&2; exit 77; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
vg="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite --show-possibly-lost=no"
fails=0
step() { # what, expected exit status, command...
    what=$1 want=$2
    shift 2
    "$@" >"$out/log" 2>&1
    rc=$?
    if [ "$rc" -ne "$want" ]; then
        echo "valgrind_check: FAIL: $what: exit $rc, expected $want" >&2
        tail -20 "$out/log" >&2
        fails=$((fails + 1))
    fi
}
step "run" 0 $vg "$OB" run --curve liu2002_ex1 --methods tiller,ahn,zhao,sisl --tols 1e-1,1e-2 \
    --backend cpu --reps 4 --out "$out/a"
# every job ended ok or limit: none failed (a server that cannot start fails its jobs)
if [ -f "$out/a/results.csv" ]; then
    bad=$(awk -F, 'NR==1{for(i=1;i<=NF;i++) if($i=="status") s=i; next} $s!="ok" && $s!="limit"{n++} END{print n+0}' "$out/a/results.csv")
    [ "$bad" -eq 0 ] || { echo "valgrind_check: FAIL: $bad jobs neither ok nor limit" >&2; fails=$((fails + 1)); }
fi
# (a run against itself; the band so wide that the verdict cannot depend on
# how much valgrind's slowdown spread the repetitions: the timing code runs,
# its outcome is fixed)
step "compare" 0 $vg "$OB" compare "$out/a" "$out/a" --time-threshold 1000 --out "$out/report.md"
step "draw" 0 $vg "$OB" draw --curve liu2002_ex1 --method ahn --tol 1e-2 --backend cpu --out "$out/ahn.svg"
here=$(cd "$(dirname "$0")/.." && pwd)
step "malformed curves" 2 $vg "$OB" run --curves "$here/tests/data/bad_curves/nan.curves" --out "$out/bad"
[ "$fails" -eq 0 ] || exit 1
echo "valgrind: clean"
