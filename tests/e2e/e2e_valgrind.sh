#!/bin/sh
# The program under valgrind (scripts/valgrind_check.sh): a run with every
# kind of method (sisl's server included), compare, draw and a malformed
# file, free of memory errors and definite leaks.  Skipped without valgrind
# and for the SAN build (ASan's shadow memory and valgrind exclude each other).
. "$(dirname "$0")/lib_e2e.sh"
case $OB in
*/build-san/offbench) skipped=$((skipped + 1)); echo "SKIP: the SAN build cannot run under valgrind" >&2 ;;
*)
    if ! command -v valgrind >/dev/null 2>&1; then
        skipped=$((skipped + 1)); echo "SKIP: valgrind not installed" >&2
    else
        sh "$(dirname "$0")/../../scripts/valgrind_check.sh" "$OB" >"$T/out" 2>&1
        check '[ $? -eq 0 ]' "valgrind_check: $(cat "$T/out")"
    fi ;;
esac
e2e_done
