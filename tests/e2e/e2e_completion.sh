#!/bin/sh
# Shell completion (scripts/completion/offbench.bash, scripts/completion/_offbench):
# commands, options, method names, curve ids and the other values, read from
# the program under test; the same answers from bash and (when installed)
# zsh, whose scripts share one core word for word; bash's completion
# function fills COMPREPLY from COMP_WORDS, '=' split or not.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
B=scripts/completion/offbench.bash Z=scripts/completion/_offbench

# cands SHELL WORD...: the core's candidates after $OB WORD..., on one line, sorted
cands() {
    sh_=$1; shift
    case $sh_ in
        bash) bash --norc --noprofile -c '. "$1"; shift; _offbench_candidates "$@"' _ "$B" "$OB" "$@" ;;
        zsh) zsh -f -c '. "$1"; shift; _offbench_candidates "$@"' _ "$Z" "$OB" "$@" ;;
    esac 2>"$T/cerr" | sort | tr '\n' ' ' | sed 's/ $//'
}
# expect SHELL "WANT" WORD...: the candidates are exactly WANT
expect() {
    sh_=$1 want=$(printf '%s\n' $2 | sort | tr '\n' ' ' | sed 's/ $//'); shift 2
    got=$(cands "$sh_" "$@")
    check '[ "$got" = "$want" ] && [ ! -s "$T/cerr" ]' "$sh_: offbench $* -> '$got', want '$want' $(head -c 200 "$T/cerr")"
}
# has SHELL "NAME" WORD...: NAME is among the candidates
has() {
    sh_=$1 want=$2; shift 2
    got=$(cands "$sh_" "$@")
    check 'case " $got " in *" $want "*) true ;; *) false ;; esac' "$sh_: offbench $* offers '$want': '$got'"
}

shells=bash
if command -v zsh >/dev/null 2>&1; then shells="bash zsh"; else skipped=$((skipped + 1)); echo "SKIP: zsh not installed: its completion not run" >&2; fi
commands=$("$OB" --help | sed -n 's/^  \.\/offbench \([a-z][a-z-]*\).*/\1/p' | sort | tr '\n' ' ' | sed 's/ $//')
methods=$("$OB" list methods | awk 'NR > 1 && /^[a-z]/ { print $1 }')
liu=$("$OB" list curves | awk '$1 ~ /^liu2002_/ { print $1 }')
for s in $shells; do
    expect $s "$commands help" ""
    expect $s "run" r
    expect $s "list" li
    expect $s "--help --version" --
    has $s --methods run --me
    has $s --metric run --me
    expect $s "--method-timing-only" compare --method-t
    has $s --format compare --fo
    expect $s "md csv json" compare --format ""
    expect $s "tiller" run --methods ti
    expect $s "all $methods" run --methods ""
    expect $s "tiller,cobb tiller,coquillart" run --methods tiller,co
    expect $s "tiller,cobb,coquillart" run --methods tiller,cobb,co
    expect $s "zhao zhao-rational" run --methods=zh
    expect $s "ahn" draw --curve liu2002_ex1 --method a
    expect $s "$liu" run --curve liu2002_
    has $s liu2002_ex1 run --curve liu2002_
    expect $s "$(printf '%s\n' $liu | grep -vx liu2002_ex1 | sed 's/^/liu2002_ex1,/')" run --curve liu2002_ex1,liu
    expect $s "rnd7_000000 rnd7_000001" run --random 2:7 --curve rnd
    expect $s "mid maxerr greedy optimal" run --split ""
    expect $s "hausdorff" run --metric h
    has $s all measure --metric ""
    expect $s "yes no" run --inflections ""
    expect $s "zhao.degree=" run --param zhao.d
    expect $s "@dirs" run --out ""
    expect $s "@files" run --curves ""
    expect $s "@files" compare ""
    expect $s "@dirs" certify ""
    has $s --threads certify --thr
    expect $s "methods metrics" list m
    expect $s "--random" list curves --r
    expect $s "" run --threads ""
    expect $s "" nosuchcommand --x
done
# the values the scripts know (the options' --help gives them as prose) are the program's
for v in mid maxerr greedy optimal; do check '"$OB" run --help | grep -- "--split" | grep -qw "$v"' "--split $v is in run --help"; done
for v in auto opencl cpu; do check '"$OB" run --help | grep -- "--backend" | grep -qw "$v"' "--backend $v is in run --help"; done
for v in auto group level device; do check '"$OB" run --help | grep -- "--engine" | grep -qw "$v"' "--engine $v is in run --help"; done

# bash's completion function, COMP_WORDS as bash splits them
reply() { # reply WORD...: COMPREPLY after "offbench WORD..." (the last word under the cursor)
    bash --norc --noprofile -c '. "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _offbench; printf "%s\n" "${COMPREPLY[@]}"' \
        _ "$B" "$OB" "$@" 2>"$T/rerr" | sort | tr '\n' ' ' | sed 's/ $//'
}
got=$(reply run --methods ti); check '[ "$got" = tiller ] && [ ! -s "$T/rerr" ]' "_offbench: run --methods ti: '$got' $(cat "$T/rerr")"
got=$(reply run --methods = zh); check '[ "$got" = "zhao zhao-rational" ]' "_offbench: --methods=zh split at '=': '$got'"
got=$(reply run --split =); check '[ "$got" = "=greedy =maxerr =mid =optimal" ]' "_offbench: --split= (the cursor after '='): '$got'"
got=$(reply li); check '[ "$got" = list ]' "_offbench: li: '$got'"
mkdir -p "$T/dir.d"; : > "$T/file.curves"
got=$(reply run --out "$T/di"); check '[ "$got" = "$T/dir.d" ]' "_offbench: --out completes directories: '$got'"
got=$(reply run --curves "$T/fi"); check '[ "$got" = "$T/file.curves" ]' "_offbench: --curves completes files: '$got'"
got=$(reply run --threads ""); check '[ -z "$got" ]' "_offbench: nothing for --threads N: '$got'"
check 'bash --norc --noprofile -c ". \"$B\"; complete -p offbench ./offbench" | grep -c "_offbench" | grep -qx 2' \
    "bash: offbench and ./offbench are completed by _offbench"

# the two scripts share one core, word for word
core() { sed -n '/^# ---- begin shared core/,/^# ---- end shared core/p' "$1"; }
check '[ -n "$(core "$B")" ] && [ "$(core "$B")" = "$(core "$Z")" ]' "offbench.bash and _offbench share the core: $(core "$B" | wc -l) and $(core "$Z" | wc -l) lines"
check 'bash -n "$B"' "offbench.bash parses"
if command -v zsh >/dev/null 2>&1; then
    check 'zsh -n "$Z"' "_offbench parses"
    check 'head -n 1 "$Z" | grep -q "^#compdef offbench"' "_offbench starts with #compdef"
fi
e2e_done
