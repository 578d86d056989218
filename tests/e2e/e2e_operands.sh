#!/bin/sh
# End-to-end tests of the one rule for '--' and operands (docs/commands.md "Command
# line"): after '--' every argument is an operand, by every command; a
# command that takes no operands refuses the first one (exit 2, naming it),
# a command whose operands are files (compare, merge) takes them after '--',
# so a file named like an option can be given; '--' is never an option's
# value.  Nothing is silently ignored, and no default output (./out) is
# written because of it.  Uses $OFFBENCH or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

W=$T/w            # each command runs in an empty directory: nothing may appear there
mkdir -p "$W"
R="--random 2:1 --methods tiller --tols 1e-1"
$OB run $R --backend cpu --out "$T/r1" 2>/dev/null
check '[ -f "$T/r1/results.csv" ]' "setup: a small run"

# refused TEXT CMD...: exit 2, stderr says TEXT, nothing written in the cwd
refused() {
    pat=$1; shift
    (cd "$W" && $OB "$@" >/dev/null 2>"$T/err"); rc=$?
    check '[ $rc -eq 2 ] && grep -qF -- "$pat" "$T/err" && [ -z "$(ls -A "$W")" ]' \
        "'$*': exit 2 saying \"$pat\", nothing written (rc $rc, cwd: $(ls -A "$W" | tr '\n' ' ')): $(cat "$T/err")"
    rm -rf "$W" && mkdir -p "$W"
}

# every command, with the arguments that are valid before '--'
for c in "run $R --backend cpu --out $T/o" \
         "tables --out $T/o" \
         "compare $T/r1 $T/r1" \
         "draw --curve x --method tiller --tol 0.1 --out $T/o.svg" \
         "trace --curve x --method tiller --tol 0.1" \
         "measure --curve x --d 1 --approx $T/none" \
         "atlas --out $T/o" \
         "bench --quick --out $T/o" \
         "list curves" "list methods" "list metrics" "list columns" "list devices" \
         "--version" "help"; do
    # shellcheck disable=SC2086
    refused "'--out'" $c -- --out X         # an option-looking word after '--'
    refused "'stray'" $c -- stray           # a stray operand after '--'
    refused "'--'" $c -- --                 # '--' twice: the second is an operand
    refused "'-x'" $c -- -x
done
# without '--', a stray operand is refused just the same
for c in "run $R --out $T/o" "atlas --out $T/o" "list methods" "list columns" "--version" "measure --curve x"; do
    # shellcheck disable=SC2086
    refused "'stray'" $c stray
done
[ ! -e "$T/o" ]
check '[ $? -eq 0 ]' "no refused command wrote its --out"

# '--' is never an option's value: '--out --' would write a directory named '--'
refused "--out: missing value" run $R --out --
refused "--out: missing value" run $R --out -- --threads 1
refused "--curves: missing value" list curves --curves --
refused "--out: missing value" merge "$T/r1" --out --
refused "--out: missing value (the next word '--force' is an option" run $R --out --force
refused "--tols: missing value" run --tols --out x

# '--' at the end, or before nothing the command refuses: as if absent
(cd "$W" && $OB run $R --backend cpu --out "$T/r2" -- 2>/dev/null)
check '[ $? -eq 0 ] && cmp -s "$T/r1/results.csv" "$T/r2/results.csv" || [ "$(body "$T/r1/results.csv")" = "$(body "$T/r2/results.csv")" ]' \
    "run ... -- (at the end): runs as without it"
check '[ -z "$(ls -A "$W")" ]' "run ... --: no ./out"
# (--no-timing: these check the operands; two single runs' timings may
# differ by more than the threshold on a loaded machine, a verdict that is
# e2e_compare's and e2e_verdict's to test)
$OB compare "$T/r1" "$T/r2" --no-timing -- >/dev/null 2>&1
check '[ $? -eq 0 ]' "compare A B --: compares"
$OB compare --no-timing "$T/r1" -- "$T/r2" >/dev/null 2>&1
check '[ $? -eq 0 ]' "compare A -- B: B is an operand"
$OB compare --no-timing -- "$T/r1" "$T/r2" >/dev/null 2>&1
check '[ $? -eq 0 ]' "compare -- A B"
$OB list methods -- >/dev/null 2>&1
check '[ $? -eq 0 ]' "list methods --"
$OB list -- methods >/dev/null 2>&1
check '[ $? -eq 0 ]' "list -- methods: the subject is an operand"
$OB atlas --out "$T/a" -- >/dev/null 2>&1
check '[ $? -eq 0 ] && [ -f "$T/a/atlas.csv" ]' "atlas --out DIR --"
$OB --version -- >/dev/null 2>&1
check '[ $? -eq 0 ]' "--version --"

# files named like options: after '--' they are operands
cp "$T/r1/results.csv" "$W/-a" && cp "$T/r2/results.csv" "$W/--b"
(cd "$W" && $OB compare -- -a --b >/dev/null 2>"$T/err")
check '[ $? -eq 0 ]' "compare -- -a --b: files named like options: $(cat "$T/err")"
(cd "$W" && $OB compare -a --b >/dev/null 2>"$T/err")
check '[ $? -eq 2 ] && grep -q "unknown option" "$T/err"' "compare -a --b (no '--'): unknown options, exit 2"
(cd "$W" && $OB compare -- -a >/dev/null 2>"$T/err")
check '[ $? -eq 2 ] && grep -q "expected BASE NEW" "$T/err"' "compare -- -a: one operand, exit 2"
(cd "$W" && $OB compare -- -a --b --c >/dev/null 2>"$T/err")
check '[ $? -eq 2 ] && grep -qF -- "--c" "$T/err"' "compare -- A B C: the third operand refused, named"
rm -rf "$W" && mkdir -p "$W"

# merge's shard directories after '--': ones named like options are read as
# directories, and '--out' there is a directory too, not the option
$OB run $R --backend cpu --shard 0/2 --out "$W/-s0" 2>/dev/null
$OB run $R --backend cpu --shard 1/2 --out "$W/--s1" 2>/dev/null
(cd "$W" && $OB merge --out m -- -s0 --s1 2>"$T/err")
check '[ $? -eq 0 ] && [ "$(body "$W/m/results.csv")" = "$(body "$T/r1/results.csv")" ]' \
    "merge --out M -- -s0 --s1: shards named like options: $(cat "$T/err")"
for tail in "--out m2" "stray" "--" "-x"; do
    # shellcheck disable=SC2086
    (cd "$W" && $OB merge --out m2 -- -s0 --s1 $tail >/dev/null 2>"$T/err")
    check '[ $? -eq 2 ] && [ ! -e "$W/m2" ] && grep -qF -- "${tail%% *}" "$T/err"' \
        "merge --out M -- A B $tail: read as shard directories, refused naming them: $(cat "$T/err")"
done

e2e_done
