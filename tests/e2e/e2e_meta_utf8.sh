#!/bin/sh
# e2e_meta_utf8.sh - meta.json is valid UTF-8 JSON that offbench's own
# readers (summary, compare, --resume) take back, whatever the environment
# and the command line hold (issue 48, item 12): $OFFBENCH_MACHINE, the
# user's name for the machine, is refused with exit 2 when it could not be
# one (no UTF-8, a control character, too long); other strings (a run
# directory or argv with a byte that is no UTF-8) are written with U+FFFD.
. "$(dirname "$0")/lib_e2e.sh"

RUN="run --random 3:1 --methods tiller"

# refused NAME VALUE: a run with OFFBENCH_MACHINE=VALUE exits 2 before it
# starts, names the variable, and leaves no run directory
refused() {
    OFFBENCH_MACHINE=$2 "$OB" $RUN --out "$T/$1" >/dev/null 2>"$T/$1.err"
    rc=$?
    check "[ $rc = 2 ]" "$1: exit status $rc, not 2 ($(tail -n 1 "$T/$1.err"))"
    check "grep -q 'OFFBENCH_MACHINE' $T/$1.err" "$1: stderr does not name OFFBENCH_MACHINE: $(tail -n 1 "$T/$1.err")"
    check "[ ! -e $T/$1/meta.json ]" "$1: a meta.json was written"
}
refused latin1 "$(printf 'a\377b')"
refused control "$(printf 'a\tb')"
refused escape "$(printf 'lab\033[31m')"
refused long "$(head -c 10000 /dev/zero | tr '\0' x)"

# a UTF-8 name is taken as it is
OFFBENCH_MACHINE="Maschine-$(printf '\303\274')" "$OB" $RUN --out "$T/u" >/dev/null 2>"$T/u.err"
check "[ $? = 0 ]" "utf8 name: run failed: $(tail -n 1 "$T/u.err")"
check "grep -q '\"name\": \"Maschine-$(printf '\303\274')\"' $T/u/meta.json" "utf8 name: not in meta.json as given"

# a run directory (so argv and the paths in meta.json) with a byte that is no UTF-8
D="$T/d$(printf '\377')ir"
"$OB" $RUN --out "$D" --export "$D/x" >/dev/null 2>"$T/d.err"
check "[ $? = 0 ]" "latin1 dir: run failed: $(tail -n 1 "$T/d.err")"
check "! LC_ALL=C grep -q \"$(printf '\377')\" $D/meta.json" "latin1 dir: meta.json holds the raw byte"
check "grep -q 'd\\\\ufffdir' $D/meta.json" "latin1 dir: meta.json has no U+FFFD for the byte"
"$OB" summary "$D" >/dev/null 2>"$T/s.err"
check "[ $? = 0 ]" "latin1 dir: summary refused it: $(tail -n 1 "$T/s.err")"
"$OB" compare "$D" "$T/u" >/dev/null 2>"$T/c.err"
rc=$?
check "[ $rc = 0 ] || [ $rc = 1 ]" "latin1 dir: compare exit $rc: $(tail -n 1 "$T/c.err")"
check "! grep -q 'UTF-8' $T/c.err" "latin1 dir: compare: $(tail -n 1 "$T/c.err")"
"$OB" run --resume "$D" >/dev/null 2>"$T/r.err"
check "[ $? = 0 ]" "latin1 dir: --resume failed: $(tail -n 1 "$T/r.err")"
# merge reads each shard's meta.json
S="$T/s$(printf '\377')"
"$OB" $RUN --shard 0/2 --out "${S}0" >/dev/null 2>&1 && "$OB" $RUN --shard 1/2 --out "${S}1" >/dev/null 2>&1
check "[ $? = 0 ]" "latin1 shards: run failed"
"$OB" merge "${S}0" "${S}1" --out "${S}m" >/dev/null 2>"$T/m.err"
check "[ $? = 0 ]" "latin1 shards: merge refused them: $(tail -n 1 "$T/m.err")"
if command -v python3 >/dev/null 2>&1; then
    check "python3 -c 'import json,sys; json.load(open(sys.argv[1], encoding=\"utf-8\"))' $D/meta.json" \
        "latin1 dir: meta.json is not valid UTF-8 JSON"
else
    skipped=$((skipped + 1))
fi

e2e_done
