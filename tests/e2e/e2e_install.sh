#!/bin/sh
# make install / uninstall (PREFIX, DESTDIR) and make man: the program, its
# manual page (generated from the commands' own --help) and the bash and zsh
# completions land where they belong; the installed program runs from
# anywhere; uninstall leaves no file behind; nothing is written outside
# DESTDIR.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
case $OB in */build-san/offbench) flavour=1 build=build-san ;; *) flavour=0 build=build ;; esac
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory SAN=$flavour "$@"; }

# the manual page
mk man >"$T/man.out" 2>&1
M=$build/offbench.1
check '[ $? -eq 0 ] && [ -s "$M" ] && head -n 2 "$M" | grep -q "^\.TH OFFBENCH 1 "' "make man writes $M: $(tail -n 3 "$T/man.out")"
for c in $("$OB" --help | sed -n 's/^  \.\/offbench \([a-z][a-z-]*\).*/\1/p' | sort -u); do
    check 'grep -q "^\.SS $c\$" "$M"' "the manual has a section for every command of --help: $c"
done
check 'grep -q "^\\\\-\\\\-methods LIST|all" "$M" || grep -q "\\\\-\\\\-methods LIST|all" "$M"' "the manual holds run's options as --help prints them"
check '! grep -q "\./offbench" "$M"' "the manual names the installed program, offbench"
if command -v groff >/dev/null 2>&1; then
    check '[ -z "$(groff -man -Tutf8 -ww -z "$M" 2>&1)" ]' "groff reads the manual without a warning: $(groff -man -Tutf8 -ww -z "$M" 2>&1 | head -n 3)"
    check 'groff -man -Tutf8 "$M" 2>/dev/null | grep -q -- "--methods LIST|all"' "the rendered manual shows --methods as typed"
else
    skipped=$((skipped + 1)); echo "SKIP: groff not installed: the manual is not rendered" >&2
fi

# install into DESTDIR under a PREFIX that does not exist outside it
P=/offbench-e2e-prefix-$$
D=$T/dest
mk install DESTDIR="$D" PREFIX="$P" >"$T/inst.out" 2>&1
check '[ $? -eq 0 ]' "make install DESTDIR PREFIX: $(tail -n 3 "$T/inst.out")"
for f in bin/offbench share/man/man1/offbench.1 share/bash-completion/completions/offbench share/zsh/site-functions/_offbench; do
    check '[ -f "$D$P/$f" ]' "installed: $P/$f"
done
check '[ -x "$D$P/bin/offbench" ] && [ ! -x "$D$P/share/man/man1/offbench.1" ]' "the program is executable, the page is not"
check '[ ! -e "$P" ]' "nothing written outside DESTDIR"
check 'cmp -s scripts/completion/offbench.bash "$D$P/share/bash-completion/completions/offbench" && cmp -s scripts/completion/_offbench "$D$P/share/zsh/site-functions/_offbench" && cmp -s "$M" "$D$P/share/man/man1/offbench.1"' \
    "the installed completions and page are the built ones"
mkdir -p "$T/elsewhere"
(cd "$T/elsewhere" && "$D$P/bin/offbench" --version) >"$T/ver.out" 2>&1
check '[ $? -eq 0 ] && head -n 1 "$T/ver.out" | grep -q "^offbench [0-9u]"' "the installed program's --version, from another directory: $(head -n 1 "$T/ver.out")"
(cd "$T/elsewhere" && "$D$P/bin/offbench" list methods) >"$T/lm.out" 2>&1
check '[ $? -eq 0 ] && grep -q "^tiller " "$T/lm.out"' "the installed program lists the methods (built-in data)"
got=$(bash --norc --noprofile -c '. "$1"; _offbench_candidates "$2" run --methods ti' _ \
    "$D$P/share/bash-completion/completions/offbench" "$D$P/bin/offbench" 2>&1)
check '[ "$got" = tiller ]' "the installed bash completion with the installed program: '$got'"

mk uninstall DESTDIR="$D" PREFIX="$P" >"$T/un.out" 2>&1
check '[ $? -eq 0 ] && [ -z "$(find "$D" ! -type d)" ]' "make uninstall leaves no file: $(find "$D" ! -type d | head -n 3)"
mk uninstall DESTDIR="$D" PREFIX="$P" >"$T/un2.out" 2>&1
check '[ $? -eq 0 ]' "make uninstall twice: still exit 0"

# PREFIX alone
mk install PREFIX="$T/pfx" >"$T/inst2.out" 2>&1
check '[ $? -eq 0 ] && [ -x "$T/pfx/bin/offbench" ] && "$T/pfx/bin/offbench" --version >/dev/null' "make install PREFIX=DIR"
mk uninstall PREFIX="$T/pfx" >/dev/null 2>&1
check '[ -z "$(find "$T/pfx" ! -type d)" ]' "make uninstall PREFIX=DIR"
e2e_done
