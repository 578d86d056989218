#!/bin/sh
# Runs every test program and test script given as arguments, then prints the
# sum of their "N passed, N failed[, N skipped]" lines as the last line.
# A program that crashes, or ends without such a line, counts as one failure.
passed=0 failed=0 skipped=0
for t in "$@"; do
    out=$(mktemp)
    case "$t" in
        *.sh) sh "$t" >"$out" 2>&1 ;;
        *)    "$t" >"$out" 2>&1 ;;
    esac
    rc=$?
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$out" | tail -n 1)
    if [ -z "$line" ]; then
        echo "== $t: no result line (exit $rc)"; cat "$out"
        failed=$((failed + 1))
    else
        p=$(echo "$line" | sed -E 's/^([0-9]+) passed.*/\1/')
        f=$(echo "$line" | sed -E 's/^[0-9]+ passed, ([0-9]+) failed.*/\1/')
        s=$(echo "$line" | sed -nE 's/.*, ([0-9]+) skipped.*/\1/p')
        passed=$((passed + p)); failed=$((failed + f)); skipped=$((skipped + ${s:-0}))
        if [ "$f" -ne 0 ] || [ "$rc" -ne 0 ]; then
            echo "== $t: $line (exit $rc)"; grep -E 'FAIL|error|ERROR|runtime error' "$out" | head -n 40
            [ "$f" -eq 0 ] && failed=$((failed + 1))
        else
            echo "== $t: $line"
        fi
    fi
    rm -f "$out"
done
if [ "$skipped" -gt 0 ]; then
    echo "$passed passed, $failed failed, $skipped skipped"
else
    echo "$passed passed, $failed failed"
fi
[ "$failed" -eq 0 ]
