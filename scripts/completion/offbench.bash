# offbench.bash - bash completion for offbench: commands, options, their
# values (method names, curve ids, metrics, split rules, ...), files.
# Installed by `make install` as PREFIX/share/bash-completion/completions/offbench
# (loaded by bash-completion on first use); in a checkout:
#   source scripts/completion/offbench.bash
# Completes `offbench` (on PATH) and `./offbench`.

# ---- begin shared core: the same text in offbench.bash and _offbench ----
# (tests/e2e/e2e_completion.sh checks that the two copies are equal)
# What to complete, worked out the same way in bash and zsh: plain shell that
# both run alike.  Every name comes from the program itself, so a new
# command, option, method or curve is completed without changing this:
# commands from `offbench --help`, options and their values from each
# command's --help, methods, parameters, metrics and curve ids from
# `offbench list methods|metrics|curves`.

# _offbench_candidates PROG WORD...: the completions of the last WORD (the
# one being typed, maybe empty) after `PROG WORD...`, one a line, those that
# begin with it.  The single line "@files" or "@dirs": complete a file or a
# directory name instead.  For a word --OPT=VALUE the completions are of
# VALUE alone.
_offbench_candidates() {
    local prog cmd cur prev opt value n w
    prog=$1
    shift
    [ $# -ge 1 ] || return 0
    n=$#
    cur= prev=
    for w in "$@"; do
        prev=$cur cur=$w
    done
    if [ "$n" -eq 1 ]; then
        case $cur in
            -*) printf '%s\n' --help --version | _offbench_narrow "$cur" ;;
            *) _offbench_commands "$prog" | _offbench_narrow "$cur" ;;
        esac
        return 0
    fi
    cmd=$1
    if [ "$cmd" = list ] && [ "$n" -ge 3 ] && [ "$2" = curves ]; then
        cmd="list curves"
    elif [ "$cmd" = list ]; then
        [ "$n" -eq 2 ] && _offbench_subjects "$prog" | _offbench_narrow "$cur"
        return 0
    fi
    case $cur in
        --*=*)
            opt=${cur%%=*}
            _offbench_value "$prog" "$cmd" "$opt" "${cur#*=}" "$@"
            return 0
            ;;
        -*)
            _offbench_options "$prog" "$cmd" | _offbench_narrow "$cur"
            return 0
            ;;
    esac
    case $prev in
        --*=*) ;;
        --*)
            if [ -n "$(_offbench_takes "$prog" "$cmd" "$prev")" ]; then
                _offbench_value "$prog" "$cmd" "$prev" "$cur" "$@"
                return 0
            fi
            ;;
    esac
    case $cmd in
        compare) echo @files ;;
        merge) echo @dirs ;;
        certify) echo @dirs ;;
    esac
}

# The lines of stdin that begin with $1.
_offbench_narrow() {
    local line
    while IFS= read -r line; do
        case $line in "$1"*) printf '%s\n' "$line" ;; esac
    done
}

# The commands: each "  ./offbench NAME" line of the usage, and help.
_offbench_commands() {
    "$1" --help 2>/dev/null | sed -n 's/^  \.\/offbench \([a-z][a-z-]*\).*/\1/p'
    echo help
}

# The subjects of list: the first word of each line of `list --help`.
_offbench_subjects() {
    "$1" list --help 2>/dev/null | sed -n 's/^  \([a-z][a-z]*\)  .*/\1/p'
}

# The options of command $2 (maybe "list curves"), from its --help.
_offbench_options() {
    _offbench_help "$1" "$2" | sed -n 's/^  \(--[a-z0-9][a-z0-9-]*\).*/\1/p'
    echo --help
}

_offbench_help() {
    if [ "$2" = "list curves" ]; then "$1" list curves --help 2>/dev/null; else "$1" "$2" --help 2>/dev/null; fi
}

# What option $3 of command $2 takes, as its --help shows it ("FILE",
# "LIST|all", ...); nothing when it takes no value.
# $3 is a word as typed: compared as a string, never put into a sed or awk
# program or a pattern (completion evaluates nothing typed).
_offbench_takes() {
    _offbench_help "$1" "$2" | {
        local line rest
        while IFS= read -r line; do
            case $line in
                "  $3 "[!\ ]*)
                    rest=${line#"  $3 "}
                    printf '%s\n' "${rest%% *}"
                    break
                    ;;
            esac
        done
        cat >/dev/null
    }
}

# Completions of the value $4 of option $3 of command $2 (the command
# line's words follow, for --curves and --random).
_offbench_value() {
    local prog cmd opt cur kind
    prog=$1 cmd=$2 opt=$3 cur=$4
    shift 4
    kind=$(_offbench_takes "$prog" "$cmd" "$opt")
    case $opt in
        --methods) { echo all; _offbench_methods "$prog"; } | _offbench_list "$cur" ;;
        --method) _offbench_methods "$prog" | _offbench_narrow "$cur" ;;
        --curve) _offbench_curves "$prog" "$@" | _offbench_list "$cur" ;;
        --metric)
            { "$prog" list metrics 2>/dev/null | sed 's/ .*//'
              case $kind in *'|all'*) echo all ;; esac; } | _offbench_narrow "$cur" ;;
        --param)
            "$prog" list methods 2>/dev/null | sed -n 's/^ *--param \([a-z0-9-]*\.[a-z0-9_]*\)=.*/\1=/p' |
                _offbench_narrow "$cur" ;;
        --split) printf '%s\n' mid maxerr greedy optimal | _offbench_narrow "$cur" ;;
        --backend) printf '%s\n' auto opencl cpu | _offbench_narrow "$cur" ;;
        --engine) printf '%s\n' auto group level device | _offbench_narrow "$cur" ;;
        *)
            case $kind in
                *DIR*) echo @dirs ;;
                *FILE*) echo @files ;;
                *'|'*) printf '%s\n' "$kind" | tr '|' '\n' | grep -v '[A-Z]' | _offbench_narrow "$cur" ;;
            esac
            ;;
    esac
}

# The registered methods.
_offbench_methods() {
    "$1" list methods 2>/dev/null | awk 'NR > 1 && /^[a-z]/ { print $1 }'
}

# The curve ids a run of these words would load (their --curves and --random).
# Fast whatever is typed: a --curves that is no regular file, or is over
# 16 MiB, is left out, and so is a --random that is not N or N:SEED in
# digits; a --random N over 1000 gives the ids of its first 1000 curves.
_offbench_curves() {
    local prog file random w prev n
    prog=$1
    shift
    file= random= prev=
    for w in "$@"; do
        case $prev in --curves) file=$w ;; --random) random=$w ;; esac
        case $w in --curves=*) file=${w#*=} ;; --random=*) random=${w#*=} ;; esac
        prev=$w
    done
    if [ -n "$file" ]; then
        if [ ! -f "$file" ] || [ ! -r "$file" ] || [ "$(wc -c <"$file" | tr -d ' ')" -gt 16777216 ]; then
            file=
        fi
    fi
    case $random in
        '' | :* | *:*:* | *[!0-9:]* | *:) random= ;;
        *)
            n=${random%%:*}
            while case $n in 0?*) true ;; *) false ;; esac; do n=${n#0}; done
            if [ "${#n}" -gt 4 ] || [ "$n" -gt 1000 ]; then random=1000${random#"$n"}; fi
            ;;
    esac
    {
        if [ -n "$file" ] && [ -n "$random" ]; then
            "$prog" list curves --curves "$file" --random "$random"
        elif [ -n "$file" ]; then
            "$prog" list curves --curves "$file"
        elif [ -n "$random" ]; then
            "$prog" list curves --random "$random"
        else
            "$prog" list curves
        fi
    } 2>/dev/null | awk '!/^#/ && $1 != "id" { print $1 }'
}

# A comma list: $1 is what is typed ("a,b,c"), stdin the names, one a
# line; completes its last item, leaving out the names already listed.
_offbench_list() {
    local cur head tail name
    cur=$1
    case $cur in
        *,*) head=${cur%,*}, tail=${cur##*,} ;;
        *) head= tail=$cur ;;
    esac
    while IFS= read -r name; do
        case ",$head" in *",$name,"*) continue ;; esac
        case $name in "$tail"*) printf '%s%s\n' "$head" "$name" ;; esac
    done
}
# ---- end shared core ----

# The completion function (complete -F): COMP_WORDS glued back where bash
# split them at '=' ("--out" "=" "DIR"), then the shared core.
_offbench() {
    local i w prog out cur lead
    local -a words=()
    for ((i = 1; i <= COMP_CWORD; i++)); do
        w=${COMP_WORDS[i]}
        if ((${#words[@]} > 0)) && [[ $w == "=" || ${COMP_WORDS[i - 1]} == "=" ]]; then
            words[${#words[@]} - 1]+=$w
        else
            words+=("$w")
        fi
    done
    prog=${COMP_WORDS[0]}
    [[ $prog == "~/"* ]] && prog=$HOME/${prog#"~/"}
    cur=${COMP_WORDS[COMP_CWORD]}
    lead=
    if [[ $cur == "=" ]]; then # the cursor right after '=': bash replaces the '='
        cur= lead==
    fi
    out=$(_offbench_candidates "$prog" "${words[@]}")
    COMPREPLY=()
    case $out in
        @files) compopt -o filenames 2>/dev/null; mapfile -t COMPREPLY < <(compgen -f -- "$cur") ;;
        @dirs) compopt -o filenames 2>/dev/null; mapfile -t COMPREPLY < <(compgen -d -- "$cur") ;;
        "") ;;
        *) mapfile -t COMPREPLY <<<"$out" ;;
    esac
    if [[ -n $lead ]]; then
        for i in "${!COMPREPLY[@]}"; do COMPREPLY[i]=$lead${COMPREPLY[i]}; done
    fi
    # a name to be continued (METHOD.NAME=, a comma list): no space after it
    if ((${#COMPREPLY[@]} == 1)) && [[ ${COMPREPLY[0]} == *[=,] ]]; then
        compopt -o nospace 2>/dev/null
    fi
    return 0
}
complete -F _offbench offbench ./offbench
