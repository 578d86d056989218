#!/bin/sh
# The Python package (python/offbench, docs/python.md): its pytest suite,
# python/tests, against this build's library (OFFBENCH_LIB) and program
# (OFFBENCH, for the cross-checks with `offbench run`).  Each pytest test
# counts as one check; the line is "N passed, N failed[, N skipped]".
#
# The interpreter: the first of /usr/bin/python3 (Debian's, with
# python3-numpy, python3-pytest, python3-pandas) and python3 on PATH that
# imports numpy and pytest; without one, every test counts as skipped.
# Under `make SAN=1 test` the library is build-san's, built with ASan and
# UBSan, which an uninstrumented python can load only with the sanitizers'
# runtimes preloaded (ASan must come first in the process): the suite runs
# so, with leak detection off (python keeps what it allocates until exit);
# where the compiler's runtimes are not found, or python does not start
# with them, it is skipped and says why (test_api checks the C API under ASan).
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
NTESTS=$(cat python/tests/test_*.py | grep -c '^def test_')
skip_all() { echo "e2e_python: $*: skipped"; echo "0 passed, 0 failed, $NTESTS skipped"; exit 0; }

PRELOAD=
case $OB in
*/build-fuzz/offbench) skip_all "$OB is a libFuzzer build" ;;
*/build-san/offbench)
    asan=$(${CC:-cc} -print-file-name=libasan.so 2>/dev/null)
    ubsan=$(${CC:-cc} -print-file-name=libubsan.so 2>/dev/null)
    [ -f "$asan" ] && [ -f "$ubsan" ] \
        || skip_all "$OB is a sanitizer build and ${CC:-cc} names no libasan.so and libubsan.so to preload into python"
    PRELOAD=$asan:$ubsan ;;
esac
LIB=$(e2e_liboffbench) || { echo "0 passed, 1 failed"; exit 1; }  # beside the program (lib_e2e.sh)

PY=
for p in /usr/bin/python3 python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import numpy, pytest' >/dev/null 2>&1; then PY=$p; break; fi
done
[ -n "$PY" ] || skip_all "no python3 imports numpy and pytest (Debian: apt-get install python3-numpy python3-pytest)"
# the sanitizers' runtimes first in python (nothing when not a SAN build)
san() {
    if [ -n "$PRELOAD" ]; then
        env LD_PRELOAD="$PRELOAD" ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" "$@"
    else
        "$@"
    fi
}
if [ -n "$PRELOAD" ]; then
    san "$PY" -c 'import numpy, pytest' >"$T/preload.out" 2>&1 \
        || skip_all "$PY does not start with $PRELOAD preloaded ($(head -n 2 "$T/preload.out" | tr '\n' ' '))"
    echo "e2e_python: the sanitizer build's library, with $PRELOAD preloaded"
fi

# -p no:cacheprovider and no bytecode: nothing written into the checkout
san env OFFBENCH_LIB="$LIB" OFFBENCH="$OB" PYTHONDONTWRITEBYTECODE=1 "$PY" -m pytest -q -rfE -p no:cacheprovider \
    --basetemp="$T/pytest" --junitxml="$T/junit.xml" python/tests >"$T/out" 2>&1
rc=$?
counts=$("$PY" -c 'import sys, xml.etree.ElementTree as E
r = E.parse(sys.argv[1]).getroot()
s = r if r.tag == "testsuite" else r.find("testsuite")
n, f, e, k = (int(s.get(a, 0)) for a in ("tests", "failures", "errors", "skipped"))
print(n - f - e - k, f + e, k)' "$T/junit.xml" 2>/dev/null)
if [ -z "$counts" ]; then
    cat "$T/out"
    echo "FAIL: pytest ended without a report (exit $rc)"
    echo "0 passed, 1 failed"
    exit 1
fi
set -- $counts
pass=$1 fail=$2 skipped=$3
# pytest's own summary: the failures, and what it skipped and why
[ "$fail" -eq 0 ] && [ "$rc" -eq 0 ] || tail -n 80 "$T/out"
[ "$rc" -eq 0 ] || [ "$fail" -gt 0 ] || { echo "FAIL: pytest exit $rc"; fail=1; }
echo "e2e_python: $PY ($("$PY" -c 'import numpy, sys; print("numpy", numpy.__version__, "python", sys.version.split()[0])'))"
e2e_done
