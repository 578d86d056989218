#!/bin/sh
# Adding a method (docs/contributing.md "How to add a method", methods/CONTRACT.md):
# `make check-method M=NAME` runs the method contract on one method and
# passes on a good one (tiller, the unregistered template), fails on a
# deliberately broken one naming the rule and what to do, and refuses an
# unknown name with a suggestion; registration is one line in
# methods/registry.def, which lists exactly the methods the files define.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
# the build flavour of the program under test (make SAN=1 test runs build-san/offbench)
case $OB in */build-san/offbench) flavour=1 ;; *) flavour=0 ;; esac
cm() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory SAN=$flavour check-method "$@" >"$T/out" 2>&1; }

cm M=tiller
check '[ $? -eq 0 ] && grep -q "^contract tiller: every rule held" "$T/out" && grep -q "^[0-9]* passed, 0 failed" "$T/out"' \
    "check-method M=tiller passes: $(tail -n 3 "$T/out")"
check '! grep -q "ahn\|cobb" "$T/out"' "check-method M=tiller checks tiller alone"
cm M=template
check '[ $? -eq 0 ] && grep -q "^contract template: every rule held" "$T/out"' \
    "check-method M=template (methods/TEMPLATE.c) passes: $(tail -n 3 "$T/out")"
cm M=sisl
check '[ $? -eq 0 ] && grep -q "SKIP \[halving\] sisl: the method declares OB_CAP_TOL_DRIVEN" "$T/out"' \
    "a declared exception is said, once: $(grep -c SKIP "$T/out") SKIP lines"

cm M=broken-halving
check '[ $? -ne 0 ] && grep -q "^FAIL \[halving\] broken-halving: " "$T/out"' "a broken method fails naming the rule"
check 'grep -q "^  what to do: .*OB_CAP_NONMONOTONE" "$T/out" && grep -q "methods/CONTRACT.md, rule .halving." "$T/out"' \
    "... with what to do and where the rule is written"
check '[ $(grep -c "^FAIL \[halving\]" "$T/out") -le 3 ] && grep -q "^contract broken-halving: FAILED: halving ([0-9]*)" "$T/out"' \
    "... its repeats counted, not all shown: $(grep -c "^FAIL" "$T/out") FAIL lines"
cm M=broken-halving-declared
check '[ $? -eq 0 ]' "the same method declaring OB_CAP_NONMONOTONE passes"
cm M=broken-degree
check '[ $? -ne 0 ] && grep -q "^FAIL \[degree\] broken-degree: .*out_degree says" "$T/out" && ! grep -q "^FAIL \[[a-ce-z]" "$T/out"' \
    "broken-degree fails the degree rule alone"

cm M=tiler
check '[ $? -ne 0 ] && grep -q "unknown method '"'"'tiler'"'"' (did you mean '"'"'tiller'"'"'?)" "$T/out"' \
    "an unknown name: did you mean: $(head -n 1 "$T/out")"
cm M=
check '[ $? -ne 0 ] && grep -q "usage: make check-method M=NAME" "$T/out"' "no name: the usage"

# an external method: the contract on a program (make check-method
# EXTERNAL='NAME=COMMAND', or METHODS_FILE=FILE), here the built-in tiller
# served over the protocol; and a method file's method whose program is
# missing: the contract says it is unavailable and how to get it
cm M=tiller_w EXTERNAL="tiller_w=$OB worker tiller"
check '[ $? -eq 0 ] && grep -q "^contract tiller_w: every rule held" "$T/out"' \
    "check-method on an external method (offbench worker tiller): every rule held: $(tail -n 2 "$T/out" | tr '\n' ' ')"
printf '[ghost]\ncommand = %s/no-such-worker\nbuild = make ghost\n' "$T" >"$T/g.methods"
cm M=ghost METHODS_FILE="$T/g.methods"
check '[ $? -ne 0 ] && grep -q "ghost.*unavailable.*make ghost" "$T/out"' "check-method on an unavailable method says how to get it: $(head -n 2 "$T/out" | tr '\n' ' ')"

# registration: one line per method in registry.def, and exactly the methods defined
defined=$(grep -ho '^const ob_method ob_method_[a-z0-9_]*' methods/*.c | grep -v 'ob_method_template$' | sed 's/.*ob_method_//' | sort)
listed=$(sed -n 's/^OB_METHOD(\([a-z0-9_]*\))$/\1/p' methods/registry.def | sort)
check '[ -n "$defined" ] && [ "$defined" = "$listed" ]' "registry.def lists every method defined: only defined: $(echo "$defined" | grep -vxF "$listed" | tr '\n' ' ') only listed: $(echo "$listed" | grep -vxF "$defined" | tr '\n' ' ')"
check '! grep -q "OB_METHOD(template)" methods/registry.def && ! "$OB" list methods | grep -q "^template "' \
    "the template is not registered (list methods leaves it out)"
check '! grep -q "ob_method_tiller\|ob_method_sisl" methods/registry.c' "registry.c names no method itself (registry.def does)"

# the docs a method author reads
check 'grep -q "make check-method M=" docs/contributing.md && grep -q "methods/CONTRACT.md" docs/contributing.md && grep -q "TEMPLATE.c" docs/contributing.md' \
    "docs/contributing.md points to the template, the contract and check-method"
check 'grep -q "(docs/contributing.md)" README.md' "README links to docs/contributing.md"
e2e_done
