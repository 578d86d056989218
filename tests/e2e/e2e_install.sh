#!/bin/sh
# make install / uninstall (PREFIX, DESTDIR) and make man: the program, its
# manual page (generated from the commands' own --help) and the bash and zsh
# completions land where they belong; the installed program runs from
# anywhere; so does the library: a C program compiled against the installed
# header links the installed liboffbench and fits with sisl, whose server
# it finds in LIBDIR/offbench/, and python loads it through OFFBENCH_LIB;
# uninstall leaves no file behind; nothing is written outside DESTDIR.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
ROOT=$(pwd)
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

# the library, its header and the sisl server
VER=$(sed -n 's/^#define OBX_VERSION "\(.*\)"/\1/p' include/offbench.h)
L=$D$P/lib
check '[ -f "$L/liboffbench.so.$VER" ] && [ -x "$L/liboffbench.so.$VER" ] && [ ! -L "$L/liboffbench.so.$VER" ]' \
    "installed: $P/lib/liboffbench.so.$VER"
check '[ "$(readlink "$L/liboffbench.so.0")" = "liboffbench.so.$VER" ] && [ "$(readlink "$L/liboffbench.so")" = liboffbench.so.0 ]' \
    "the SONAME and .so links: $(readlink "$L/liboffbench.so.0") $(readlink "$L/liboffbench.so")"
check 'cmp -s include/offbench.h "$D$P/include/offbench.h"' "installed: $P/include/offbench.h"
check '[ -f "$L/offbench/offbench-sisl-server" ] && [ -x "$L/offbench/offbench-sisl-server" ]' \
    "installed: $P/lib/offbench/offbench-sisl-server"
if command -v readelf >/dev/null 2>&1; then
    check 'readelf -d "$L/liboffbench.so.$VER" | grep -q "SONAME.*\[liboffbench.so.0\]"' "the installed library's SONAME is liboffbench.so.0"
else
    skipped=$((skipped + 1)); echo "SKIP: no readelf: the SONAME is not read" >&2
fi
# a C program against the installed header and library, run from elsewhere
# with only the staged library on the loader's path (no build/ in sight);
# under SAN the library holds ASan, so the program is built with it too
san=; [ "$flavour" = 1 ] && san="-fsanitize=address,undefined"
cat >"$T/elsewhere/use.c" <<'EOC'
#include <offbench.h>
#include <stdio.h>
#include <string.h>
int main(void)
{
    obx_curveset *s = NULL;
    obx_result *r = NULL;
    obx_error e = {0, ""};
    if (obx_curves_load_default(&s, &e) != 0 ||
        obx_fit(s, obx_curves_find(s, "liu2002_ex1"), "sisl", 1, 1e-2, NULL, NULL, NULL, &r, &e) != 0) {
        printf("error: %s\n", e.message);
        obx_curves_free(s);
        return 1;
    }
    printf("%s %s %s %d\n", obx_version(), OBX_VERSION, obx_result_status(r), obx_result_piece_count(r));
    obx_result_free(r);
    obx_curves_free(s);
    return 0;
}
EOC
(cd "$T/elsewhere" && ${CC:-cc} -std=c11 $san -I"$D$P/include" -o use use.c -L"$L" -loffbench) >"$T/cc.out" 2>&1
check '[ $? -eq 0 ]' "a C program compiles against the installed header and links the installed library: $(head -n 3 "$T/cc.out")"
(cd "$T/elsewhere" && env -u OFFBENCH_SISL_EXE LD_LIBRARY_PATH="$L" ./use) >"$T/use.out" 2>&1
check '[ $? -eq 0 ] && grep -q "^$VER $VER ok [1-9]" "$T/use.out"' \
    "it runs: obx_version, and a sisl fit served from $P/lib/offbench/: $(head -n 2 "$T/use.out")"
check 'env LD_LIBRARY_PATH="$L" ldd "$T/elsewhere/use" | grep -q "liboffbench.so.0 => $L/liboffbench.so.0"' \
    "it loads the installed library: $(env LD_LIBRARY_PATH="$L" ldd "$T/elsewhere/use" | grep liboffbench)"
# python: the package (from python/) on the installed library, through OFFBENCH_LIB
PY=
for p in /usr/bin/python3 python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import numpy' >/dev/null 2>&1; then PY=$p; break; fi
done
if [ "$flavour" = 1 ]; then
    skipped=$((skipped + 1)); echo "SKIP: the SAN build's library holds ASan, which python cannot load without preloading it" >&2
elif [ -z "$PY" ]; then
    skipped=$((skipped + 1)); echo "SKIP: no python3 with numpy (apt-get install python3-numpy): the package is not tried" >&2
else
    (cd "$T/elsewhere" && env -u OFFBENCH_SISL_EXE OFFBENCH_LIB="$L/liboffbench.so.0" PYTHONPATH="$ROOT/python" \
        PYTHONDONTWRITEBYTECODE=1 "$PY" -c 'import offbench
print(offbench.library_path())
print(offbench.fit("liu2002_ex1", "sisl", 1, 1e-2).status)') >"$T/py.out" 2>&1
    check '[ $? -eq 0 ] && [ "$(cat "$T/py.out")" = "$L/liboffbench.so.0
ok" ]' "python loads the installed library through OFFBENCH_LIB and fits with sisl: $(tail -n 3 "$T/py.out")"
fi

mk uninstall DESTDIR="$D" PREFIX="$P" >"$T/un.out" 2>&1
check '[ $? -eq 0 ] && [ -z "$(find "$D" ! -type d)" ]' "make uninstall leaves no file: $(find "$D" ! -type d | head -n 3)"
mk uninstall DESTDIR="$D" PREFIX="$P" >"$T/un2.out" 2>&1
check '[ $? -eq 0 ]' "make uninstall twice: still exit 0"

# a manifest: install writes PREFIX/share/offbench/install-manifest.txt (the
# paths it wrote, one a line), uninstall removes exactly those and the
# manifest, nothing else, whatever the PREFIX holds (spaces, a glob char);
# the files a PREFIX split at its space or globbed would name are decoys
installed="bin/offbench share/man/man1/offbench.1 share/bash-completion/completions/offbench share/zsh/site-functions/_offbench
lib/liboffbench.so.$VER lib/liboffbench.so.0 lib/liboffbench.so include/offbench.h lib/offbench/offbench-sisl-server"
for P in "$T/my prefix" "$T/st*r dir"; do
    mkdir -p "$P/bin" "$T/star dir/bin"
    echo decoy >"$P/bin/other"; echo decoy >"${P%% *}"; echo decoy >"$T/star dir/bin/offbench"
    mk install PREFIX="$P" >"$T/sp.out" 2>&1
    check '[ $? -eq 0 ]' "make install PREFIX='$P': $(tail -n 3 "$T/sp.out")"
    for f in $installed; do
        check '[ -f "$P/$f" ]' "installed into '$P': $f"
    done
    man=$P/share/offbench/install-manifest.txt
    check '[ -f "$man" ] && [ "$(sort "$man")" = "$(for f in $installed; do printf "%s\n" "$P/$f"; done | sort)" ]' \
        "the manifest lists exactly the installed files: $(head -n 3 "$man" 2>&1)"
    mk uninstall PREFIX="$P" >"$T/spu.out" 2>&1
    check '[ $? -eq 0 ]' "make uninstall PREFIX='$P': $(tail -n 3 "$T/spu.out")"
    check '[ "$(cd "$P" && find . ! -type d)" = ./bin/other ]' "uninstall removed exactly the installed files and the manifest from '$P': $(cd "$P" && find . ! -type d | head -n 12 | tr '\n' ' ')"
    check '[ "$(cat "$P/bin/other" "${P%% *}" "$T/star dir/bin/offbench" 2>&1)" = "decoy
decoy
decoy" ]' "uninstall left the files it never installed (beside them, named like the prefix's first word, matched by its glob)"
    rm -f "${P%% *}"
done
# with DESTDIR (a space in it too): the manifest holds the paths under PREFIX
D2="$T/de st" P2="/opt/off bench"
mk install DESTDIR="$D2" PREFIX="$P2" >"$T/sd.out" 2>&1
check '[ $? -eq 0 ] && grep -qx "$P2/bin/offbench" "$D2$P2/share/offbench/install-manifest.txt"' \
    "install DESTDIR PREFIX: the manifest names the files as PREFIX will hold them: $(tail -n 3 "$T/sd.out")"
mk uninstall DESTDIR="$D2" PREFIX="$P2" >/dev/null 2>&1
check '[ -z "$(find "$D2" ! -type d)" ]' "uninstall DESTDIR PREFIX with spaces: $(find "$D2" ! -type d | head -n 3)"
# no manifest: uninstall says so and removes nothing
P3="$T/no manifest"
mkdir -p "$P3/bin" && echo theirs >"$P3/bin/offbench"
mk uninstall PREFIX="$P3" >"$T/nm.out" 2>&1
check '[ "$(cat "$P3/bin/offbench")" = theirs ] && grep -q "manifest" "$T/nm.out"' \
    "uninstall without a manifest removes nothing and says so: $(cat "$T/nm.out")"
# a manifest line that is not a plain absolute path is refused, not followed
mkdir -p "$P3/share/offbench" "$T/outside" && echo keep >"$T/outside/f"
printf '%s\n' "$P3/bin/../../outside/f" "$T/outside/./f" >"$P3/share/offbench/install-manifest.txt"
mk uninstall PREFIX="$P3" >"$T/bm.out" 2>&1
check '[ -f "$T/outside/f" ] && [ "$(cat "$P3/bin/offbench")" = theirs ]' "a manifest line with a . or .. component is not followed: $(cat "$T/bm.out")"

# PREFIX alone
mk install PREFIX="$T/pfx" >"$T/inst2.out" 2>&1
check '[ $? -eq 0 ] && [ -x "$T/pfx/bin/offbench" ] && "$T/pfx/bin/offbench" --version >/dev/null' "make install PREFIX=DIR"
mk uninstall PREFIX="$T/pfx" >/dev/null 2>&1
check '[ -z "$(find "$T/pfx" ! -type d)" ]' "make uninstall PREFIX=DIR"
e2e_done
