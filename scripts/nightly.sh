#!/bin/sh
# nightly.sh - the nightly regression run: build, run the nightly
# configuration, judge its quality against the committed baseline
# (results/baseline/) and its timings against this machine's own baseline
# (recorded on this machine with --accept), write a report that leads with
# the verdict and the per-method table that decides it, and exit with the
# worst status of the comparisons:
#   0 no regression, 1 regression, 2 error, 3 not comparable (or timings
#   that cannot be judged for too few repetitions).  A 3 against the
#   committed baseline (its configuration, a method's version or parameters
#   changed) is mended by --accept-committed (make accept-committed-baseline)
#   after a night, then review and commit; --accept (make accept-baseline)
#   is this machine's timing baseline only.
# The status is also written to OUT/status (the number alone): `make
# nightly` exits 2 for every status but 0 (make's own exit status), so CI
# runs this script directly or reads OUT/status (docs/nightly.md "Nightly in CI").
#
# The nightly configuration (two runs, both every method and the tolerances
# 1e-1 ... 1e-5, hausdorff metric, mid split):
#   published  the curves under datasets/, --reps 5: quality, and speed
#              against this machine's baseline (the 5 timed runs after a
#              warm-up give each method's per-repetition totals)
#   random     --random $NIGHTLY_RANDOM (default 250:2026), one run: quality
#              only
# Timing (compare --timing-only --method-timing-only against
# BASELINES/NAME-ID/published, NAME and ID the machine in meta.json): only
# a baseline recorded on this machine counts, never the committed one
# (recorded elsewhere); without one the report says "timings not judged: no
# baseline of this machine" and timing adds nothing to the status.  Methods
# too noisy to judge (their interval wider than the change they would
# report) are run again, alone, up to --reruns times; each re-run is
# compared afresh (nothing is pooled) and the last decides.  A run whose
# load average exceeded its cores is not judged (no re-run: the machine is
# busy).
#
# History: every run, failed or not, is then copied into a store that the
# next night does not overwrite (scripts/nightly_history.sh), one directory
# per run, DIR/STAMP_COMMIT_HOST/ (published/ and random/ with results.csv,
# samples.csv and meta.json; report.md, compare-*.err, logs, run.json with
# the exit status), old runs are pruned (never the newest), and when python3
# is there scripts/report.py rebuilds the HTML report of the store in
# SITE/index.html (a failed report is said on stderr and leaves the exit
# status alone).
#
# Usage:
#   scripts/nightly.sh [--out DIR]      build, run and compare (default out/nightly)
#   scripts/nightly.sh --accept [--out DIR]
#                                       no new run: the run just made in DIR
#                                       becomes this machine's timing baseline
#                                       (BASELINES/NAME-ID/published; refused
#                                       for a run that failed or whose load
#                                       exceeded its cores)
#   scripts/nightly.sh --accept-committed [--out DIR]
#                                       no new run: the run in DIR becomes the
#                                       committed baseline (results/baseline/:
#                                       review `git diff --stat` and commit it)
# Options (each also an environment variable):
#   --baselines DIR NIGHTLY_BASELINES  the machines' own baselines (default
#                                      ${XDG_DATA_HOME:-~/.local/share}/offbench/baselines,
#                                      outside the repository)
#   --reruns N      NIGHTLY_RERUNS     re-runs of methods too noisy to judge (default 2)
#   --history DIR   NIGHTLY_HISTORY    the store (default out/history;
#                                      'none': no store, no report)
#   --keep N        NIGHTLY_KEEP       keep the N newest runs (default 0: all)
#   --keep-days D   NIGHTLY_KEEP_DAYS  drop runs older than D days (0: never)
#   --site DIR      NIGHTLY_SITE       the report (default HISTORY/site)
# Environment: NIGHTLY_RANDOM=N:SEED overrides the random set (a baseline
# made with another set is not comparable: compare exits 3), OFFBENCH_THREADS
# the thread count (default: OpenMP's), NIGHTLY_BACKEND the backend (default
# opencl: the kernel through PoCL on a machine without a GPU),
# NIGHTLY_METHODS the methods (default all), NIGHTLY_CURVES the published
# set's curves (--curve ID,...; default every curve under datasets/: a
# smaller nightly, e.g. for tests), NIGHTLY_BASELINE the committed
# baseline (default results/baseline), NIGHTLY_BIN a built offbench to use
# (no build step), OFFBENCH_MACHINE this machine's name (default: the host
# name; set it where cloned machines share /etc/machine-id and a host name).
# Killed (SIGTERM, SIGINT, SIGHUP: `timeout`, a CI job's time limit): the
# offbench process of the moment is stopped, OUT/status is 2, the night is
# recorded with the stage it reached ("run published (killed by SIGTERM)")
# and the site rebuilt; exit 2.
# Files: OUT/report.md, OUT/status, OUT/timings.csv (each stage's wall
# seconds, then the total), OUT/compare-*.{md,csv,err}, OUT/*.log,
# OUT/published, OUT/random, OUT/reruns/K (the K-th re-run).
set -u
cd "$(dirname "$0")/.."
out=out/nightly
accept=
history=${NIGHTLY_HISTORY:-out/history}
keep=${NIGHTLY_KEEP:-0}
keep_days=${NIGHTLY_KEEP_DAYS:-0}
site=${NIGHTLY_SITE:-}
baselines=${NIGHTLY_BASELINES:-${XDG_DATA_HOME:-${HOME:-.}/.local/share}/offbench/baselines}
reruns=${NIGHTLY_RERUNS:-2}
while [ $# -gt 0 ]; do
    case "$1" in
        --out|--history|--keep|--keep-days|--site|--baselines|--reruns)
            [ $# -ge 2 ] || { echo "nightly: $1 needs a value" >&2; exit 2; }
            case "$1" in
                --out) out=$2 ;; --history) history=$2 ;; --keep) keep=$2 ;;
                --keep-days) keep_days=$2 ;; --site) site=$2 ;; --baselines) baselines=$2 ;;
                --reruns) reruns=$2 ;;
            esac
            shift 2 ;;
        --accept) accept=machine; shift ;;
        --accept-committed) accept=committed; shift ;;
        -h|--help) awk 'NR > 1 && /^set -u$/ { exit } NR > 1' "$0"; exit 0 ;;
        *) echo "nightly: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
for v in "$keep" "$keep_days" "$reruns"; do
    case "$v" in ''|*[!0-9]*) echo "nightly: --keep, --keep-days and --reruns need a whole number, not '$v'" >&2; exit 2 ;; esac
done
# the store must outlive the next night's rm -rf of the output directory
case "${history%/}/" in "${out%/}/"*)
    echo "nightly: the history store $history lies inside the output directory $out, which each run removes" >&2; exit 2 ;;
esac
random=${NIGHTLY_RANDOM:-250:2026}
threads=${OFFBENCH_THREADS:+--threads $OFFBENCH_THREADS}
# The nightly measures through OpenCL on the machine's CPU (PoCL) by name:
# --backend auto now takes the CPU backend where there is no GPU, and the
# kernel path is what the nightly guards (NIGHTLY_BACKEND=cpu to skip it).
backend=${NIGHTLY_BACKEND:-opencl}
methods=${NIGHTLY_METHODS:-all}
curves=${NIGHTLY_CURVES:+--curve $NIGHTLY_CURVES}
qbase=${NIGHTLY_BASELINE:-results/baseline}
bin=${NIGHTLY_BIN:-./offbench}

# The machine of a run, from its meta.json's one-line "machine" object
# (written by offbench, host/io/output.c): its id (16 hex digits), its name,
# and its directory among the baselines, BASELINES/NAME-ID (NAME with every
# character outside [A-Za-z0-9._-] as '_').
machine_id() { sed -n 's/^  "machine": {.*"id": "\([0-9a-f]\{16\}\)".*/\1/p' "$1" 2>/dev/null | head -n 1; }
machine_name() { sed -n 's/^  "machine": {"name": "\([^"\\]*\)".*/\1/p' "$1" 2>/dev/null | head -n 1; }
machine_dir() {
    mid=$(machine_id "$1")
    [ -n "$mid" ] || return 1
    mname=$(printf '%s' "$(machine_name "$1")" | tr -c 'A-Za-z0-9._-' '_')
    printf '%s/%s-%s\n' "$baselines" "${mname:-machine}" "$mid"
}
# "LOAD CORES" when the run's largest load average exceeded its cores
# (meta.json "host"), else nothing
over_load() {
    sed -n 's/.*"cores_used": \([0-9]*\),.*"loadavg_max": \([0-9.]*\),.*/\2 \1/p' "$1" 2>/dev/null | head -n 1 |
        awk '$1 > $2 {print}'
}
# copy_set SRC DST: a run set (results.csv, meta.json, samples.csv) into
# DST, through DST.tmp and a rename
copy_set() {
    rm -rf "$2.tmp" && mkdir -p "$2.tmp" && cp "$1/results.csv" "$1/meta.json" "$2.tmp/" &&
        { [ ! -f "$1/samples.csv" ] || cp "$1/samples.csv" "$2.tmp/"; } && rm -rf "$2" && mv "$2.tmp" "$2"
}

# --accept / --accept-committed: the run just made in $out, no new run
if [ -n "$accept" ]; then
    st=$(cat "$out/status" 2>/dev/null)
    if [ ! -f "$out/published/results.csv" ] || [ ! -f "$out/published/meta.json" ] || [ -z "$st" ]; then
        echo "nightly: nothing to accept: no finished nightly run in $out (scripts/nightly.sh --out $out makes one)" >&2
        exit 2
    fi
    case "$st" in 0|1|3) ;; *)
        echo "nightly: not accepted: the run in $out failed (status $st: see $out/report.md and its logs)" >&2; exit 2 ;;
    esac
    if [ "$accept" = committed ]; then
        for name in published random; do
            copy_set "$out/$name" "$qbase/$name" || { echo "nightly: could not copy $out/$name into $qbase/$name" >&2; exit 2; }
        done
        echo "nightly: the run in $out is now the committed baseline in $qbase/ (review git diff --stat $qbase and commit it with the reason)" >&2
        exit 0
    fi
    load=$(over_load "$out/published/meta.json")
    if [ -n "$load" ]; then
        echo "nightly: not accepted: the run's load average reached ${load% *} on its ${load#* } cores, so compare would never judge timings against it: accept a run made on a quiet machine" >&2
        exit 2
    fi
    dir=$(machine_dir "$out/published/meta.json") || {
        echo "nightly: not accepted: $out/published/meta.json records no machine (a run of an older offbench)" >&2; exit 2; }
    copy_set "$out/published" "$dir/published" || { echo "nightly: could not copy $out/published into $dir/published" >&2; exit 2; }
    echo "nightly: the run in $out is now the timing baseline of machine '$(machine_name "$out/published/meta.json")' in $dir" >&2
    exit 0
fi

start=$(date +%s)
# the commit the run is built from, kept for the history (HEAD may move
# while the run goes on)
commit=$(git rev-parse HEAD 2>/dev/null || echo unknown)
dirty=false
[ "$commit" != unknown ] && ! git diff --quiet HEAD -- 2>/dev/null && dirty=true

# --- the stages, their wall time, and a night that is killed on the way ---
# now: seconds since 1970, with decimals (GNU date)
now() { date +%s.%N; }
t_start=$(now)
stage=start t_stage=$t_start timings= child=
# stage_begin NAME: the night is in stage NAME from now on (what a signal records)
stage_begin() { stage=$1; t_stage=$(now); }
# stage_end [LABEL]: the stage's wall seconds, a line of OUT/timings.csv
stage_end() {
    timings="$timings${1:-$stage},$(awk -v a="$t_stage" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }')
"
}
# OUT/timings.csv: each stage's wall seconds in the order run, then the
# night's total up to here (the history store and the site come after it)
write_timings() {
    { echo "stage,seconds"; printf '%s' "$timings"
      echo "total,$(awk -v a="$t_start" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }')"; } >"$out/timings.csv"
}
# bg CMD...: CMD in the background, waited for; its exit status.  Why: a
# POSIX sh runs a trap only once its foreground child has returned, which
# for a run is minutes, while `wait` is cut short by a trapped signal, so
# the trap below runs at once; $child names CMD meanwhile (the trap stops it)
bg() {
    "$@" &
    child=$!
    wait "$child"
    bg_rc=$?
    child=
    return $bg_rc
}
# alive PID: PID is a child of this script that has not ended (read in
# /proc; without it, not known: false)
alive() {
    # shellcheck disable=SC2046
    set -- $(sed 's/.*) //' "/proc/$1/stat" 2>/dev/null)
    [ $# -ge 2 ] && [ "$1" != Z ] && [ "$2" = $$ ]
}
# stop_child: the child of the moment ($child, or $! when the signal came
# before it was noted) asked to stop with TERM, killed if it is still there
# 2 s later (a run ends its batch first, which may wait on a SISL fit: the
# night is over, and the journal it leaves is never resumed), and reaped
stop_child() {
    p=${child:-${!:-}}
    [ -n "$p" ] && alive "$p" || return 0
    kill -TERM "$p" 2>/dev/null
    i=0
    while [ $i -lt 20 ] && alive "$p"; do sleep 0.1; i=$((i + 1)); done
    kill -KILL "$p" 2>/dev/null
    wait "$p" 2>/dev/null
    child=
}
# on_signal SIG: TERM, INT or HUP (`timeout`, a CI job's time limit, a
# closed terminal) ends the night as a failed one that still reports: its
# child stopped, status 2 with the stage it reached, recorded and the site
# rebuilt.  Further signals are ignored from here on, and by the recording's
# children too (an ignored signal stays ignored across exec), so that a
# second one cannot cut the store's copy short (a run is copied under a dot
# name and renamed whole: even SIGKILL leaves no half run in it).
on_signal() {
    trap '' TERM INT HUP
    stop_child
    echo "nightly: killed by SIG$1 in stage '$stage'" >&2
    killed="$stage (killed by SIG$1)"
    stage_end "$killed"
    [ "$stage" = build ] && mkdir -p "$out" && mv "$out.build.log" "$out/build.log" 2>/dev/null
    finish 2 "$killed"
}
trap 'on_signal TERM' TERM
trap 'on_signal INT' INT
trap 'on_signal HUP' HUP

# finish STATUS STAGE: writes OUT/status and OUT/timings.csv, records the
# run in the history store, prunes it, rebuilds the report, and exits with
# STATUS (the store and the report never change it: their failures are
# said on stderr).  No signal interrupts it (on_signal above).
finish() {
    trap '' TERM INT HUP
    mkdir -p "$out" 2>/dev/null && echo "$1" >"$out/status" && write_timings
    if [ "$history" != none ]; then
        run_dir=$(sh scripts/nightly_history.sh record --out "$out" --history "$history" --status "$1" \
                  --stage "$2" --started "$start" --random "$random" --baseline "$qbase" --commit "$commit" \
                  --dirty $dirty) \
            && echo "nightly: recorded in $run_dir" >&2 \
            || echo "nightly: could not record this run in $history (see above)" >&2
        sh scripts/nightly_history.sh prune --history "$history" --keep "$keep" --keep-days "$keep_days" \
            || echo "nightly: pruning $history failed (see above)" >&2
        if [ -x /usr/bin/python3 ]; then
            /usr/bin/python3 scripts/report.py "$history" --out "${site:-$history/site}" \
                && echo "nightly: report in ${site:-$history/site}/index.html" >&2 \
                || echo "nightly: scripts/report.py failed (see above); the exit status is the run's" >&2
        else
            echo "nightly: no /usr/bin/python3: no HTML report" >&2
        fi
    fi
    exit "$1"
}

mkdir -p "$(dirname "$out")" || exit 2
rm -f "$out/status"
stage_begin build
if [ -n "${NIGHTLY_BIN:-}" ]; then
    echo "not built: NIGHTLY_BIN=$bin" >"$out.build.log"
else
    bg make >"$out.build.log" 2>&1 || { stage_end; mkdir -p "$out"; mv "$out.build.log" "$out/build.log" 2>/dev/null;
        echo "nightly: the build failed (see $out/build.log)" >&2; finish 2 build; }
    stage_end
fi
rm -rf "$out"
mkdir -p "$out"
mv "$out.build.log" "$out/build.log"

run() {  # DIR METHODS [run options]: one run into $out/DIR, its log in $out/DIR.log
    name=$1 m=$2; shift 2
    t0=$(date +%s)
    stage_begin "run $name"
    mkdir -p "$(dirname "$out/$name")"
    # shellcheck disable=SC2086
    bg "$bin" run --methods "$m" --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --metric hausdorff --split mid \
        $threads --backend "$backend" "$@" --out "$out/$name" 2>"$out/$name.log"
    rc=$?
    stage_end
    echo "nightly: $name: exit $rc in $(($(date +%s) - t0)) s ($(tail -n 1 "$out/$name.log"))" >&2
    [ $rc -eq 0 ] || { echo "nightly: the $name run failed (see $out/$name.log)" >&2; finish 2 "run $name"; }
}
# shellcheck disable=SC2086
run published "$methods" --reps 5 $curves
run random "$methods" --random "$random"

status=0
worst() {  # keeps the most severe status: 2 > 3 > 1 > 0
    case "$1:$status" in
        2:*|*:2) status=2 ;;
        3:*|*:3) status=3 ;;
        1:*|*:1) status=1 ;;
    esac
}
# compare_to LABEL BASE NEW [options]: compare's report as Markdown
# (OUT/compare-LABEL.md) and as CSV (OUT/compare-LABEL.csv, read below),
# its messages in OUT/compare-LABEL.err; its status into the nightly's
compare_to() {
    label=$1 b=$2 n=$3; shift 3
    stage_begin "compare $label"
    bg "$bin" compare "$b" "$n" "$@" --format csv --out "$out/compare-$label.csv" 2>/dev/null
    bg "$bin" compare "$b" "$n" "$@" --format md --out "$out/compare-$label.md" 2>"$out/compare-$label.err"
    crc=$?
    stage_end
    echo "nightly: compare $label: exit $crc" >&2
    worst $crc
}
# the methods whose timing a compare CSV says is too noisy to judge, comma separated
noisy_methods() {
    awk -F, '$1 == "method" && $8 == "time_total" && $15 == "noisy" {printf "%s%s", s, $4; s = ","}' "$1" 2>/dev/null
}

# quality: against the committed baseline
for name in published random; do
    if [ -f "$qbase/$name/results.csv" ]; then
        compare_to "$name-quality" "$qbase/$name" "$out/$name" --no-timing
    else
        printf '# no baseline\n\n**NOT COMPARABLE** (exit 3): no baseline in %s (scripts/nightly.sh --accept-committed makes the run just made the committed baseline)\n' \
            "$qbase/$name" >"$out/compare-$name-quality.md"
        : >"$out/compare-$name-quality.csv"
        echo "nightly: no baseline in $qbase/$name" | tee "$out/compare-$name-quality.err" >&2
        worst 3
    fi
done

# timing: against this machine's own baseline, the noisy methods run again
mname=$(machine_name "$out/published/meta.json")
mid=$(machine_id "$out/published/meta.json")
mdir=$(machine_dir "$out/published/meta.json")
timing_csvs= timing_note= k=0
if [ -n "$mdir" ] && [ -f "$mdir/published/results.csv" ]; then
    compare_to timing "$mdir/published" "$out/published" --timing-only --method-timing-only
    timing_csvs="$out/compare-timing.csv"
    noisy=$(noisy_methods "$out/compare-timing.csv")
    while [ -n "$noisy" ] && [ "$k" -lt "$reruns" ]; do
        k=$((k + 1))
        echo "nightly: re-running the methods too noisy to judge: $noisy ($k of $reruns)" >&2
        # shellcheck disable=SC2086
        run "reruns/$k" "$noisy" --reps 5 $curves
        compare_to "timing-rerun$k" "$mdir/published" "$out/reruns/$k" --timing-only --method-timing-only --methods "$noisy"
        timing_csvs="$timing_csvs $out/compare-timing-rerun$k.csv"
        noisy=$(noisy_methods "$out/compare-timing-rerun$k.csv")
    done
else
    timing_note="timings not judged: no baseline of this machine ('${mname:-unknown}', id ${mid:-unknown}) in $baselines: \`scripts/nightly.sh --accept\` after a quiet night makes the run just made this machine's baseline"
    echo "nightly: $timing_note" >&2
fi

# The report.  First the verdict and the per-method table that decides it:
# per method its last timing verdict (the first comparison, or the re-run
# that judged it last) and its quality regressions in both sets; then each
# comparison's own report (headings one level down), its messages quoted.
status_word() {
    case "$1" in 0) echo "OK: no regression" ;; 1) echo "REGRESSION" ;; 2) echo "ERROR" ;; *) echo "NOT COMPARABLE" ;; esac
}
# the per-method table: timing CSVs (role t, in run order), then quality CSVs (role q)
verdict_table() {
    # shellcheck disable=SC2086
    awk -F, '
        FNR == 1 { if (role == "t") tf++ }
        function add(m) { if (!(m in seen)) { seen[m] = 1; order[++n] = m } }
        role == "q" && $1 == "method" && $8 == "ctrl_points_gm" { add($4) }
        role == "q" && ($1 == "regression" || $1 == "missing") && $4 != "" { add($4); q[$4]++ }
        role == "t" && $1 == "method" && $8 == "time_total" {
            add($4); tb[$4] = $9; tn[$4] = $10; est[$4] = $11; lo[$4] = $13; hi[$4] = $14; v[$4] = $15
            by[$4] = tf == 1 ? "first run" : "re-run " (tf - 1)
        }
        function ms(x) { return x == "" ? "-" : sprintf("%.4g ms", x / 1e6) }
        function num(x) { return x == "" ? "-" : sprintf("%.4g", x) }
        END {
            print "| method | time base | time new | time new/base | interval | timing | quality regressions | decided by |"
            print "|---|---:|---:|---:|---:|---|---:|---|"
            for (i = 1; i <= n; i++) {
                m = order[i]
                w = v[m] == "" ? "-" : v[m] == "same" ? "no change" : v[m] == "noisy" ? "not judged: noisy" : \
                    v[m] == "few_reps" ? "not judged: too few repetitions" : v[m]
                iv = lo[m] == "" ? "-" : (hi[m] == "inf" ? "unbounded" : sprintf("[%.4g, %.4g]", lo[m], hi[m]))
                printf "| %s | %s | %s | %s | %s | %s | %d | %s |\n", m, ms(tb[m]), ms(tn[m]), num(est[m]), iv, w,
                       q[m] + 0, m in by ? by[m] : "-"
            }
        }' role=t $timing_csvs role=q "$out/compare-published-quality.csv" "$out/compare-random-quality.csv"
}
# the per-method timing verdicts of the table, counted: "N slower (a, b), N faster, ..."
timing_counts() {
    # shellcheck disable=SC2086
    awk -F, '$1 == "method" && $8 == "time_total" { v[$4] = $15 }
        END { for (m in v) { c[v[m]]++; if (v[m] == "slower") s = s (s == "" ? "" : ", ") m }
              printf "%d slower%s, %d faster, %d no change, %d not judged", c["slower"] + 0, s == "" ? "" : " (" s ")",
                     c["faster"] + 0, c["same"] + 0, c["noisy"] + c["few_reps"] }' $timing_csvs
}
first_line() { sed -n 's/^\*\*\([^*]*\)\*\* (exit \([0-9]\)).*/\1 (exit \2)/p' "$1" | head -n 1; }
section() {  # TITLE LABEL: one comparison's report, headings one level down, its messages quoted
    echo "## $1"
    echo
    sed '1{/^# /d}' "$out/compare-$2.md" | sed '1{/^$/d}' | sed 's/^\(#\{1,5\}\) /#\1 /'
    if [ -s "$out/compare-$2.err" ]; then
        echo
        sed 's/^/> /' "$out/compare-$2.err"
    fi
    echo
}
report="$out/report.md"
stage_begin report
{
    echo "# offbench nightly, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo
    if [ -n "$timing_csvs" ] && grep -q '^method,.*,time_total,' $timing_csvs; then
        tline="timing: $(timing_counts) (against this machine's baseline)"
    elif [ -n "$timing_csvs" ]; then
        tline="timing: not judged"
    else
        tline="timing: not judged (no baseline of this machine)"
    fi
    echo "**$(status_word $status)** (exit $status): $tline; quality: published $(first_line "$out/compare-published-quality.md"), random $(first_line "$out/compare-random-quality.md")."
    if [ -n "$timing_csvs" ]; then
        printf '%s' "$(grep -m 1 '^Timing: ' "$out/compare-timing.md")"
        [ "$k" -eq 0 ] || printf ' The methods too noisy to judge were run again %d time(s): the table says which run decided.' "$k"
        echo
    else
        echo "Timing: **not judged**: no baseline of this machine ('${mname:-unknown}', id ${mid:-unknown})."
    fi
    echo
    echo "Commit $(printf '%s' "$commit" | cut -c1-12)$([ "$dirty" = true ] && echo ' (dirty)'); machine '${mname:-unknown}' (id ${mid:-unknown}); quality against $qbase/ (committed); timing against ${mdir:-none}/published$([ -n "$timing_csvs" ] || echo ' (none yet)'); random set $random; methods $methods."
    echo
    echo "## Verdict by method"
    echo
    verdict_table
    echo
    if [ -n "$timing_csvs" ]; then
        section "published: timing against this machine's baseline" timing
        i=1
        while [ "$i" -le "$k" ]; do
            section "published: timing, re-run $i of the methods too noisy to judge" "timing-rerun$i"
            i=$((i + 1))
        done
    else
        echo "## published: timing"
        echo
        echo "$timing_note."
        echo
    fi
    section "published: quality against $qbase/published" published-quality
    section "random: quality against $qbase/random" random-quality
    echo "Exit status $status ($(status_word $status); 0 no regression, 1 regression, 2 error, 3 not comparable); $(($(date +%s) - start)) s in all."
} >"$report"
stage_end
echo "nightly: report in $report; exit $status" >&2
finish $status compare
