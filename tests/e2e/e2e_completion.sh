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
# zsh's completion function, compadd and its kin stubbed to print what they are given
zreply() {
    zsh -f -c '. "$1"; shift; compadd() { print -rl -- "$@"; }; compset() { :; }; _files() { echo @files; }; words=("$@"); CURRENT=$#; _offbench' \
        _ "$Z" "$OB" "$@" 2>"$T/zerr"
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

# completion never evaluates what is typed: words that would run a command
# if expanded, eval'd or fed to sed's `e` (in any position: the word under
# the cursor, the one before it, an option's value, --opt=value, the command)
# are only ever passed on as quoted arguments
pwn=$T/pwn
payloads() { # one a line: each touches $pwn.N when evaluated
    printf '%s\n' "\$(touch $pwn.1)" "\`touch $pwn.2\`" "';touch $pwn.3;'" "\";touch $pwn.4;\"" \
        "--a//;1e touch $pwn.5;#" "--a/\\1/e;s/x/touch $pwn.6/e;#" "--\$(touch $pwn.7)" "--\`touch $pwn.8\`" \
        "*(e:'touch $pwn.9':)" "\${IFS}\$(touch\${IFS}$pwn.10)"
}
tried=0
while IFS= read -r p; do
    for s in $shells; do
        for words in "run|$p" "run|$p|" "run|--methods|$p" "run|--methods=$p" "run|--curve|$p" "run|$p|--curve|" \
            "run|--random|$p|--curve|" "run|--random=$p|--curve|r" "run|--curves|$p|--curve|" "$p|--help" \
            "list|curves|$p|" "run|--param|$p" "compare|--format|$p"; do
            old_ifs=$IFS; IFS='|'; set -f; set -- $words; set +f; IFS=$old_ifs
            [ "${words%|}" != "$words" ] && set -- "$@" ""
            cands "$s" "$@" >/dev/null
            [ "$s" = bash ] && reply "$@" >/dev/null
            [ "$s" = zsh ] && zreply "$@" >/dev/null
            tried=$((tried + 1))
        done
    done
done <<EOP
$(payloads)
EOP
check '[ "$tried" -gt 100 ] && [ -z "$(ls "$T" | grep "^pwn")" ]' "completion ran a command typed on the line: $(ls "$T" | grep "^pwn" | tr '\n' ' ') ($tried tries)"
# zsh's completion function on its own word: a glob qualifier in the program's name runs nothing
if command -v zsh >/dev/null 2>&1; then
    zsh -f -c '. "$1"; compadd() { :; }; compset() { :; }; _files() { :; }; words=("$2" run --m); CURRENT=3; _offbench' \
        _ "$Z" "$(dirname "$OB")/*(e:'touch $pwn.z':)" >/dev/null 2>&1
    check '[ ! -e "$pwn.z" ]' "zsh: _offbench glob-expanded the program's name and ran its qualifier"
fi

# completion stays fast whatever is typed: a huge --random, a --curves that
# is no regular file; finishes well within a generous bound
for s in $shells; do
    for words in "run --random 10000000 --curve rnd1_00000" "run --random=10000000:3 --curve rnd3_00000" \
        "run --random 99999999999999999999999999 --curve rnd" "run --random 1e9 --curve rnd" \
        "list curves --random 10000000 --curves /dev/zero --r" "run --curves /dev/zero --curve liu2002_ex"; do
        set -f; set -- $words; set +f
        case $s in
            bash) timeout 10 bash --norc --noprofile -c '. "$1"; shift; _offbench_candidates "$@"' _ "$B" "$OB" "$@" ;;
            zsh) timeout 10 zsh -f -c '. "$1"; shift; _offbench_candidates "$@"' _ "$Z" "$OB" "$@" ;;
        esac >"$T/fast.out" 2>/dev/null
        rc=$?
        last=$(eval "printf '%s' \"\${$#}\"")
        check '[ "$rc" -eq 0 ] && ! grep -qv "^$last" "$T/fast.out"' \
            "$s: completion after offbench $words: status $rc (124: took over 10 s), $(wc -l <"$T/fast.out") lines: $(head -n 3 "$T/fast.out" | tr '\n' ' ')"
    done
    got=$(cands "$s" run --random 10000000 --curve rnd1_00000 | cut -d ' ' -f 1-2)
    check '[ "$got" = "rnd1_000000 rnd1_000001" ]' "$s: a huge --random still completes its first ids: '$got'"
done

# the two scripts share one core, word for word
core() { sed -n '/^# ---- begin shared core/,/^# ---- end shared core/p' "$1"; }
check '[ -n "$(core "$B")" ] && [ "$(core "$B")" = "$(core "$Z")" ]' "offbench.bash and _offbench share the core: $(core "$B" | wc -l) and $(core "$Z" | wc -l) lines"
check 'bash -n "$B"' "offbench.bash parses"
if command -v zsh >/dev/null 2>&1; then
    check 'zsh -n "$Z"' "_offbench parses"
    check 'head -n 1 "$Z" | grep -q "^#compdef offbench"' "_offbench starts with #compdef"
fi
e2e_done
