#!/bin/sh
# nightly_history.sh - the store of past nightly runs (docs/nightly.md "Nightly
# history and report"): scripts/nightly.sh records each run here before its
# output directory is overwritten the next night, and prunes old runs.
#
#   sh scripts/nightly_history.sh record --out OUT --history DIR --status N
#        [--stage STAGE] [--started EPOCH] [--random N:SEED] [--baseline DIR]
#        [--commit SHA [--dirty true|false]] [--time EPOCH]
#       copies the nightly output OUT into DIR/STAMP_COMMIT_HOST/ (STAMP the
#       UTC time, e.g. 2026-12-02T031205Z; COMMIT the short commit; HOST the
#       machine's name) and prints that directory.  Per run set (published,
#       random): results.csv, samples.csv, fits.csv, meta.json, the run's log; beside
#       them report.md, compare-*.err, compare-*.json (compare --format json,
#       when the nightly wrote it), build.log, timings.csv (each stage's wall
#       seconds) and run.json (status N, its meaning, the stage that ended
#       the run, commit, dirty flag, host, time, and the committed baseline
#       the run was compared with, DIR, as NIGHTLY_BASELINE named it: null
#       without --baseline).  STAGE "build" (or "build
#       (killed by SIG...)") copies only build.log and timings.csv: OUT then
#       still holds the previous night's files.  A failed run is recorded
#       all the same.
#       --commit, --dirty and --time record a run made elsewhere or earlier
#       (default: the checkout's HEAD, whether it has changes, and now).
#   sh scripts/nightly_history.sh prune --history DIR [--keep N] [--keep-days D]
#       removes the oldest runs beyond the N newest, and runs older than D
#       days (by the time in the name); 0 (the default) keeps all.  The
#       newest run is never removed; only directories (not links) named like
#       a run and holding a run.json are touched, whatever their names hold.
# Exit status: 0 done, 2 bad usage or a copy that failed (said on stderr).
set -u
LC_ALL=C   # byte order for the glob over run names; no locale's text
export LC_ALL

die() { echo "nightly_history: $*" >&2; exit 2; }
need() { [ "$2" -ge 2 ] || die "$1 needs a value"; }
is_count() { case "$1" in ''|*[!0-9]*) return 1 ;; esac; }

# json_str TEXT: TEXT as a JSON string (backslashes, quotes and control
# characters escaped; the values here are short single-line texts)
json_str() { printf '"%s"' "$(printf '%s' "$1" | tr '\n\r\t' '   ' | sed 's/\\/\\\\/g; s/"/\\"/g')"; }

status_text() {
    case "$1" in
        0) echo "no regression" ;; 1) echo "regression" ;; 2) echo "error" ;;
        3) echo "not comparable" ;; *) echo "exit $1" ;;
    esac
}

# copy_run OUT DEST STAGE: the nightly's files that exist, into DEST; at
# the build stage (failed, or killed: "build (killed by SIGTERM)") only
# its log and timings, the rest of OUT being the previous night's
copy_run() {
    o=$1 d=$2
    for f in "$o/build.log" "$o/timings.csv"; do
        [ -f "$f" ] && { cp "$f" "$d/" || return 1; }
    done
    case "$3" in build|"build "*) return 0 ;; esac
    for f in "$o"/report.md "$o"/compare-*.err "$o"/compare-*.json "$o"/*.log; do
        [ -f "$f" ] && { cp "$f" "$d/" || return 1; }
    done
    for set in "$o"/*/; do
        set=${set%/}
        [ -d "$set" ] || continue
        [ -f "$set/results.csv" ] || [ -f "$set/meta.json" ] || continue
        mkdir -p "$d/${set##*/}" || return 1
        for f in results.csv samples.csv fits.csv meta.json; do
            [ -f "$set/$f" ] && { cp "$set/$f" "$d/${set##*/}/" || return 1; }
        done
    done
    return 0
}

# write_meta FILE NAME STATUS STAGE STARTED RANDOM: the run's run.json
# (uses $commit, $dirty, $when, $host and $baseline of record)
write_meta() {
    secs=null
    is_count "$5" && secs=$((when - $5))
    {
        echo "{"
        echo "  \"name\": $(json_str "$2"),"
        echo "  \"date\": $(json_str "$(date -u -d "@$when" +%Y-%m-%dT%H:%M:%SZ)"),"
        echo "  \"commit\": $(json_str "$commit"),"
        echo "  \"commit_short\": $(json_str "$(printf '%s' "$commit" | cut -c1-7)"),"
        echo "  \"dirty\": $dirty,"
        echo "  \"host\": $(json_str "$host"),"
        echo "  \"status\": $3,"
        echo "  \"status_text\": $(json_str "$(status_text "$3")"),"
        echo "  \"stage\": $(json_str "$4"),"
        echo "  \"seconds\": $secs,"
        echo "  \"random\": $(json_str "$6"),"
        echo "  \"baseline\": $([ -n "$baseline" ] && json_str "$baseline" || echo null)"
        echo "}"
    } >"$1"
}

record() {
    out="" hist="" status="" stage="done" started="" random="" commit="" when="" dirty=false baseline=""
    while [ $# -gt 0 ]; do
        case "$1" in
            --out) need "$1" $#; out=$2; shift 2 ;;
            --history) need "$1" $#; hist=$2; shift 2 ;;
            --status) need "$1" $#; status=$2; shift 2 ;;
            --stage) need "$1" $#; stage=$2; shift 2 ;;
            --started) need "$1" $#; started=$2; shift 2 ;;
            --random) need "$1" $#; random=$2; shift 2 ;;
            --baseline) need "$1" $#; baseline=$2; shift 2 ;;
            --commit) need "$1" $#; commit=$2; shift 2 ;;
            --dirty) need "$1" $#; dirty=$2; shift 2 ;;
            --time) need "$1" $#; when=$2; shift 2 ;;
            *) die "record: unknown option '$1'" ;;
        esac
    done
    if [ -z "$out" ] || [ -z "$hist" ]; then die "record needs --out OUT and --history DIR"; fi
    is_count "$status" || die "record: --status needs a number, not '$status'"
    [ -z "$when" ] && when=$(date +%s)
    is_count "$when" || die "record: --time needs seconds since 1970, not '$when'"
    case "$dirty" in true|false) ;; *) die "record: --dirty needs true or false, not '$dirty'" ;; esac
    if [ -z "$commit" ]; then
        dirty=false
        commit=$(git rev-parse HEAD 2>/dev/null || echo unknown)
        [ "$commit" != unknown ] && ! git diff --quiet HEAD -- 2>/dev/null && dirty=true
    fi
    case "$commit" in *[!0-9a-zA-Z]*|'') die "record: --commit needs a commit id, not '$commit'" ;; esac
    mkdir -p "$hist" || die "cannot create the history directory $hist"
    host=$(hostname 2>/dev/null || uname -n)
    hname=$(printf '%s' "$host" | tr -c 'A-Za-z0-9.-' '-' | cut -c1-40)
    short=$(printf '%s' "$commit" | cut -c1-7)
    base="$(date -u -d "@$when" +%Y-%m-%dT%H%M%SZ)_${short}_${hname:-host}"
    name=$base n=1
    while [ -e "$hist/$name" ]; do n=$((n + 1)); name="$base-$n"; done
    # copied under a dot name, then renamed: a store never shows half a run
    tmp="$hist/.tmp-$name"
    rm -rf "$tmp"
    mkdir -p "$tmp" || die "cannot create $tmp"
    copy_run "$out" "$tmp" "$stage" || { rm -rf "$tmp"; die "copying $out into $hist failed"; }
    write_meta "$tmp/run.json" "$name" "$status" "$stage" "$started" "$random" \
        || { rm -rf "$tmp"; die "cannot write $tmp/run.json"; }
    mv "$tmp" "$hist/$name" || { rm -rf "$tmp"; die "cannot rename $tmp"; }
    echo "$hist/$name"
}

# is_run PATH: PATH is one of the store's runs: a directory (not a link)
# named like a run (STAMP_..., the UTC time first) holding a run.json
is_run() {
    [ -d "$1" ] && [ ! -L "$1" ] && [ -f "$1/run.json" ] || return 1
    case "${1##*/}" in
        [0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]T[0-9][0-9][0-9][0-9][0-9][0-9]Z_*) return 0 ;;
    esac
    return 1
}

# stamp_num STAMP: 2026-12-02T031205Z as 20261202031205 (for comparing)
stamp_num() { printf '%s' "$1" | tr -cd 0-9; }

prune() {
    hist="" keep=0 days=0
    while [ $# -gt 0 ]; do
        case "$1" in
            --history) need "$1" $#; hist=$2; shift 2 ;;
            --keep) need "$1" $#; keep=$2; shift 2 ;;
            --keep-days) need "$1" $#; days=$2; shift 2 ;;
            *) die "prune: unknown option '$1'" ;;
        esac
    done
    [ -n "$hist" ] || die "prune needs --history DIR"
    is_count "$keep" || die "--keep needs a count of runs (0: all), not '$keep'"
    is_count "$days" || die "--keep-days needs a number of days (0: no age limit), not '$days'"
    [ -d "$hist" ] || return 0
    # the runs become the positional parameters, oldest first (the glob
    # sorts by name, LC_ALL=C, and names begin with the UTC time): a name is
    # never split or read back as text, so spaces, newlines or glob
    # characters in it cannot make it another name
    set --
    for r in "$hist"/*; do
        is_run "$r" && set -- "$@" "$r"
    done
    total=$#
    [ "$total" -le 1 ] && return 0
    eval "newest=\${$total}"
    cutoff=""
    [ "$days" -gt 0 ] && cutoff=$(stamp_num "$(date -u -d "@$(($(date +%s) - days * 86400))" +%Y-%m-%dT%H%M%SZ)")
    i=0
    for r in "$@"; do
        i=$((i + 1))
        [ "$r" = "$newest" ] && continue
        name=${r##*/}
        old=0
        [ "$keep" -gt 0 ] && [ $((total - i)) -ge "$keep" ] && old=1
        [ -n "$cutoff" ] && [ "$(stamp_num "${name%%_*}")" -lt "$cutoff" ] && old=1
        [ $old -eq 1 ] || continue
        rm -rf -- "$r" && printf 'nightly_history: pruned %s\n' "$name" >&2
    done
    return 0
}

case "${1:-}" in
    record) shift; record "$@" ;;
    prune) shift; prune "$@" ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) die "usage: nightly_history.sh record|prune ... (see --help)" ;;
esac
