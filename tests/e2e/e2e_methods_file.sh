#!/bin/sh
# --methods-file FILE (host/cli/methods_file.c, docs/external-methods.md
# "A methods file"): external methods named in a file are registered when
# their program is there; a missing one is listed by `list methods` as
# unavailable with its build and needs lines, and naming it in --methods
# is an error that says the same; a program that is there but speaks no
# protocol, and every malformed line, is an error naming FILE:LINE.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2

cat >"$T/m.methods" <<EOT
# two methods: one served, one not built
[tiller_w]
command = $OB worker tiller

[ghost]
command = $T/no/such_worker --flag
build   = make ghost-worker
needs   = apt-get install ghost-dev
EOT
"$OB" --methods-file "$T/m.methods" list methods >"$T/list" 2>"$T/list.err"
check '[ $? -eq 0 ] && grep -q "^tiller_w .*built in, served by offbench worker" "$T/list"' \
    "the method whose program is there is registered: $(grep "^tiller_w" "$T/list") $(cat "$T/list.err")"
check 'grep -q "^ghost .*unavailable: .*no/such_worker is not there" "$T/list" && grep -q "build it: make ghost-worker" "$T/list" && grep -q "which needs: apt-get install ghost-dev" "$T/list"' \
    "the missing one is listed unavailable with its build and needs lines: $(grep -A2 "^ghost" "$T/list" | tr '\n' ' ')"

"$OB" --methods-file "$T/m.methods" run --methods ghost --curve line --out "$T/r0" 2>"$T/r0.err"
check '[ $? -eq 2 ] && grep -q "ghost.*unavailable.*make ghost-worker.*apt-get install ghost-dev" "$T/r0.err"' \
    "run --methods ghost: exit 2 with how to get it: $(cat "$T/r0.err")"

"$OB" --methods-file="$T/m.methods" run --methods tiller,tiller_w --curve liu2002_ex1,line --tols 1e-2,1e-3 --out "$T/r1" >/dev/null 2>"$T/r1.err"
check '[ $? -eq 0 ]' "run --methods tiller,tiller_w: exit 0: $(tail -n 2 "$T/r1.err")"
pair() { rcols "$T/r1/results.csv" method curve d tol status ctrl_points max_err | awk -F: -v m="$1" '$1 == m {sub(/^[^:]*:/, ""); print}'; }
check '[ -n "$(pair tiller)" ] && [ "$(pair tiller)" = "$(pair tiller_w)" ]' "tiller_w's rows are tiller's: $(pair tiller_w | tr '\n' ' ')"

# errors: each names the file and line, exit 2
bad() { # NAME TEXT WHAT: the file holding TEXT is refused with WHAT in the message
    b_name=$1 b_what=$3
    printf '%b' "$2" >"$T/$b_name.methods"
    "$OB" --methods-file "$T/$b_name.methods" list methods >/dev/null 2>"$T/$b_name.err"
    check '[ $? -eq 2 ] && grep -q "$b_what" "$T/$b_name.err"' "$b_name: exit 2 with '$b_what': $(cat "$T/$b_name.err")"
}
bad nokey '[a]\nbuild = x\n' "$T/nokey.methods:1: \[a\] has no command"
bad unknown '[a]\ncommand = /bin/true\nflavour = x\n' "$T/unknown.methods:3: unknown key"
bad twice '[a]\ncommand = /bin/true\ncommand = /bin/true\n' "$T/twice.methods:3: key given twice"
bad section '[a b]\n' "$T/section.methods:1: a section is \[NAME\]"
bad orphan 'command = /bin/true\n' "$T/orphan.methods:1: expected \[NAME\] or KEY = VALUE"
bad mute '[mute]\ncommand = /bin/true\n' "$T/mute.methods:1: \[mute\]: .*hello"
"$OB" --methods-file "$T/none.methods" list methods >/dev/null 2>"$T/none.err"
check '[ $? -eq 2 ] && grep -q "cannot open" "$T/none.err"' "a missing file: exit 2: $(cat "$T/none.err")"
"$OB" list methods --methods-file 2>"$T/nofile.err" >/dev/null
check '[ $? -eq 2 ] && grep -q "expected FILE" "$T/nofile.err"' "--methods-file without FILE: exit 2: $(cat "$T/nofile.err")"
printf '[p]\ncommand = no_such_program_zz9 --x\n' >"$T/p.methods"
"$OB" --methods-file "$T/p.methods" list methods >"$T/p.list" 2>&1
check '[ $? -eq 0 ] && grep -q "^p .*unavailable: no program no_such_program_zz9 in PATH" "$T/p.list"' \
    "a program looked up in PATH and not found: unavailable: $(grep "^p " "$T/p.list")"
e2e_done
