#!/bin/sh
# Every malformed curve file in tests/bad_curves/ given to the program itself:
# `./offbench run --curves FILE` exits 2 before any work, writes no results,
# and its message names FILE and the line its first line "# expect-line: N"
# gives (a file that needs another loaded first, marked "# also-load:", is
# left to test_curvefile.c and counted as skipped).  Under `make SAN=1 test` $OFFBENCH is the ASan/UBSan build, so a leak
# or a sanitizer report changes the exit status and fails the check.
OB=${OFFBENCH:-./offbench}
OB=$(cd "$(dirname "$OB")" && pwd)/$(basename "$OB")
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0 skipped=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

n=0
for f in tests/bad_curves/*.curves; do
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

echo "$pass passed, $fail failed, $skipped skipped"
[ $fail -eq 0 ]
