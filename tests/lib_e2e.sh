# lib_e2e.sh - sourced by the tests/e2e_*.sh scripts (not a test itself):
# the program under test ($OFFBENCH, set by make, else ./offbench) as an
# absolute path in $OB, a scratch directory $T removed on exit, and the
# counters behind the "N passed, N failed[, N skipped]" line.
OB=${OFFBENCH:-./offbench}
OB=$(cd "$(dirname "$OB")" && pwd)/$(basename "$OB")
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0 skipped=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
check() { if eval "$1"; then ok; else bad "$2"; fi; }
# a results.csv without its timing columns (fit_ns, eval_ns)
body() { cut -d, -f1-11,14- "$1"; }
