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
#   published  the curves under datasets/, --reps 5 --time-fits: quality,
#              and speed against this machine's baseline: each method's own
#              fit time (--time-fits: its fits microbenchmarked in
#              $NIGHTLY_FIT_REPS rounds, default 10, fits.csv), and the
#              harness (eval_ns, the 5 timed runs after a warm-up)
#   random     --random $NIGHTLY_RANDOM (default 250:2026), one run: quality
#              only
# --size small (NIGHTLY_SIZE=small), for runners that cannot afford that (a
# minute or two on 2 cores, docs/nightly.md): published on 9 curves under
# datasets/ (the papers' examples, arc_quarter, ph_cubic, atlas_ellipse,
# atlas_cardioid), random --random 20:2026, against the committed baseline of
# that size, results/baseline-small/, and this machine's own small baseline.
#
# A smaller nightly (fewer curves, NIGHTLY_CURVES; methods, NIGHTLY_METHODS;
# a smaller N of the same seed, NIGHTLY_RANDOM; --size small against the
# full baseline, NIGHTLY_BASELINE=results/baseline) compares the rows it
# ran.  compare reads what the run set out to run from its meta.json
# ("selection": curves and their offsets, random set, methods, metrics,
# splits, tolerances):
#   - a baseline row outside that selection is left out: not a regression;
#     the report's "Left out:" lines say what (e.g. "230 random curves
#     (rnd2026_000020 ... rnd2026_000249): 30,600 rows left out"), compare's
#     own report lists the rows (CSV kind left_out), and alone it exits 0;
#   - a baseline row inside the selection that the run lacks is missing: a
#     regression, exit 1;
#   - another random seed makes other curves: not comparable, exit 3 (curve
#     i of a seed is the same for every N, so a smaller N of the same seed
#     is a subset).
# Timing, two ways.  With NIGHTLY_BASE_REF (a git commit or ref, e.g. the
# commit of the last accepted baseline, or HEAD~1): that commit is built
# from this repository (OUT/base-build) and its build and this one run the
# published set alternately, base, new, base, new, half the rounds each
# (asv's "continuous"), their rounds joined (scripts/join_rounds.sh) and
# compared: a burst of load hits both sides, and no stored baseline is
# needed (hosted CI runners).  The commit must have run --time-fits.
# Otherwise (compare --timing-only --method-timing-only against
# BASELINES/NAME-ID/published, small: BASELINES/NAME-ID/small/published,
# NAME and ID the machine in meta.json): only
# a baseline recorded on this machine counts, never the committed one
# (recorded elsewhere); without one the report says "timings not judged: no
# baseline of this machine" and timing adds nothing to the status.  Methods
# the data cannot decide (their interval wider than the change they would
# report: "cannot decide: need N more repetitions") are run again, alone,
# with the repetitions compare asks for, up to --reruns times; each re-run
# is compared afresh (nothing is pooled) and the last decides.  A method
# still undecided after them makes the night exit 3, never 0.  A loaded
# machine is judged all the same: the times are thread CPU time and the
# repetitions' own spread decides (docs/nightly.md "Noise").
#
# History: every run, failed or not, is then copied into a store that the
# next night does not overwrite (scripts/nightly_history.sh), one directory
# per run, DIR/STAMP_COMMIT_HOST/ (published/ and random/ with results.csv,
# samples.csv, fits.csv and meta.json; report.md, compare-*.err, logs, run.json with
# the exit status), old runs are pruned (never the newest), and when python3
# is there scripts/report.py rebuilds the HTML report of the store in
# SITE/index.html (a failed report is said on stderr and leaves the exit
# status alone).
#
# Usage:
#   scripts/nightly.sh [--size full|small] [--out DIR]
#                                       build, run and compare (default out/nightly)
#   scripts/nightly.sh --accept [--out DIR]
#                                       no new run: the run just made in DIR
#                                       becomes this machine's timing baseline
#                                       (BASELINES/NAME-ID/published; refused
#                                       for a run that failed, or whose own
#                                       repetitions cannot tell a change: it
#                                       is compared with itself first)
#   scripts/nightly.sh --accept-committed [--out DIR]
#                                       no new run: the run in DIR becomes the
#                                       committed baseline of its size
#                                       (results/baseline/, small:
#                                       results/baseline-small/: review `git
#                                       diff --stat` and commit it)
#   Both take the run's size from DIR/size; a --size that differs is refused.
# Options (each also an environment variable):
#   --size S        NIGHTLY_SIZE       full (default) or small (above)
#   --baselines DIR NIGHTLY_BASELINES  the machines' own baselines (default
#                                      ${XDG_DATA_HOME:-~/.local/share}/offbench/baselines,
#                                      outside the repository)
#   --reruns N      NIGHTLY_RERUNS     re-runs of methods too noisy to judge (default 2)
#   --history DIR   NIGHTLY_HISTORY    the store (default out/history;
#                                      'none': no store, no report)
#   --keep N        NIGHTLY_KEEP       keep the N newest runs (default 0: all)
#   --keep-days D   NIGHTLY_KEEP_DAYS  drop runs older than D days (0: never)
#   --site DIR      NIGHTLY_SITE       the report (default HISTORY/site)
# Environment: NIGHTLY_RANDOM=N:SEED overrides the random set (another seed
# than the baseline's is not comparable, exit 3; a smaller N of its seed is a
# subset, above), OFFBENCH_THREADS
# the thread count (default: OpenMP's), NIGHTLY_BACKEND the backend (default
# opencl: the kernel through PoCL on a machine without a GPU),
# NIGHTLY_METHODS the methods (default all), NIGHTLY_METHODS_FILE a methods
# file whose external methods the two runs add (e.g. methods/cad.methods:
# OpenCASCADE and lib2geom where built; their rows are "new" against a
# baseline without them, and accepting them into the committed baseline
# makes them "missing" on machines without them), NIGHTLY_FIT_REPS the rounds of
# --time-fits (default 10), NIGHTLY_BASE_REF the baseline commit for
# interleaved timing (above; NIGHTLY_BASE_BIN: its build made elsewhere, no
# build step), NIGHTLY_CURVES the published
# set's curves (--curve ID,...; default every curve under datasets/, small:
# the 9 above), NIGHTLY_BASELINE the committed baseline (default
# results/baseline, small: results/baseline-small), NIGHTLY_BIN a built offbench to use
# (no build step), OFFBENCH_MACHINE this machine's name (default: the host
# name; set it where cloned machines share /etc/machine-id and a host name).
# Killed (SIGTERM, SIGINT, SIGHUP: `timeout`, a CI job's time limit): the
# offbench process of the moment is stopped, OUT/status is 2, the night is
# recorded with the stage it reached ("run published (killed by SIGTERM)")
# and the site rebuilt; exit 2.
# Files: OUT/report.md, OUT/status, OUT/size, OUT/timings.csv (each stage's
# wall seconds, then the total), OUT/compare-*.{md,csv,err}, OUT/*.log,
# OUT/published, OUT/random, OUT/reruns/K (the K-th re-run), OUT/timing
# (NIGHTLY_BASE_REF: the interleaved runs).
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
fit_reps=${NIGHTLY_FIT_REPS:-10}
base_ref=${NIGHTLY_BASE_REF:-}
size=${NIGHTLY_SIZE:-}
while [ $# -gt 0 ]; do
    case "$1" in
        --out|--history|--keep|--keep-days|--site|--baselines|--reruns|--size)
            [ $# -ge 2 ] || { echo "nightly: $1 needs a value" >&2; exit 2; }
            case "$1" in
                --out) out=$2 ;; --history) history=$2 ;; --keep) keep=$2 ;;
                --keep-days) keep_days=$2 ;; --site) site=$2 ;; --baselines) baselines=$2 ;;
                --reruns) reruns=$2 ;; --size) size=$2 ;;
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
# --accept, --accept-committed: the size of the run they take (OUT/size)
if [ -n "$accept" ]; then
    run_size=$(cat "$out/size" 2>/dev/null || echo full)
    if [ -n "$size" ] && [ "$size" != "$run_size" ]; then
        echo "nightly: not accepted: the run in $out is a $run_size nightly, not $size (leave --size out to accept it as it is)" >&2
        exit 2
    fi
    size=$run_size
fi
size=${size:-full}
case "$size" in full|small) ;; *) echo "nightly: --size is full or small, not '$size'" >&2; exit 2 ;; esac
# The small configuration: a subset of the full one (its curves among
# datasets/, the first 20 curves of the full random set), so that a small
# nightly is judged against the full baseline too (its other rows left out).
small_curves=liu2002_ex1,liu2002_ex2,liu2002_ex2_unclamped,zhao2017_quintic,zhao2017_septic,arc_quarter,ph_cubic,atlas_ellipse,atlas_cardioid
if [ "$size" = small ]; then
    random=${NIGHTLY_RANDOM:-20:2026}
    curve_list=${NIGHTLY_CURVES:-$small_curves}
    qbase=${NIGHTLY_BASELINE:-results/baseline-small}
    mset=small/published  # this machine's small timing baseline, BASELINES/NAME-ID/small/published
    small='small '
else
    random=${NIGHTLY_RANDOM:-250:2026}
    curve_list=${NIGHTLY_CURVES:-}
    qbase=${NIGHTLY_BASELINE:-results/baseline}
    mset=published
    small=
fi
threads=${OFFBENCH_THREADS:+--threads $OFFBENCH_THREADS}
# The nightly measures through OpenCL on the machine's CPU (PoCL) by name:
# --backend auto now takes the CPU backend where there is no GPU, and the
# kernel path is what the nightly guards (NIGHTLY_BACKEND=cpu to skip it).
backend=${NIGHTLY_BACKEND:-opencl}
methods=${NIGHTLY_METHODS:-all}
curves=${curve_list:+--curve $curve_list}
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
# copy_set SRC DST: a run set (results.csv, meta.json, samples.csv,
# fits.csv) into DST, through DST.tmp and a rename
copy_set() {
    rm -rf "$2.tmp" && mkdir -p "$2.tmp" && cp "$1/results.csv" "$1/meta.json" "$2.tmp/" &&
        { [ ! -f "$1/samples.csv" ] || cp "$1/samples.csv" "$2.tmp/"; } &&
        { [ ! -f "$1/fits.csv" ] || cp "$1/fits.csv" "$2.tmp/"; } && rm -rf "$2" && mv "$2.tmp" "$2"
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
        echo "nightly: the $size run in $out is now the committed baseline in $qbase/ (review git diff --stat $qbase and commit it with the reason)" >&2
        exit 0
    fi
    # A loaded night is accepted when its own repetitions are consistent:
    # compared with itself, every method's timing must be decidable (no
    # change); a run whose rounds spread wider than the 10 % band could
    # never be a baseline that tells a change.
    bin_a=${NIGHTLY_BIN:-./offbench}
    "$bin_a" compare "$out/published" "$out/published" --timing-only --method-timing-only --strict-timing \
        --format csv --out "$out/accept-self.csv" 2>"$out/accept-self.err"
    arc=$?
    if [ $arc -ne 0 ]; then
        load=$(over_load "$out/published/meta.json")
        echo "nightly: not accepted: the run's own repetitions cannot tell a 10 % change (compared with itself, compare exits $arc: $(grep -m 1 . "$out/accept-self.err"))${load:+; its load average reached ${load% *} on its ${load#* } cores}: run the nightly again (more --fit-reps: NIGHTLY_FIT_REPS) and accept that" >&2
        exit 2
    fi
    dir=$(machine_dir "$out/published/meta.json") || {
        echo "nightly: not accepted: $out/published/meta.json records no machine (a run of an older offbench)" >&2; exit 2; }
    copy_set "$out/published" "$dir/$mset" || { echo "nightly: could not copy $out/published into $dir/$mset" >&2; exit 2; }
    echo "nightly: the run in $out is now the $size timing baseline of machine '$(machine_name "$out/published/meta.json")' in $dir/$mset" >&2
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
echo "$size" >"$out/size"  # what --accept and --accept-committed take it for

run() {  # DIR METHODS [run options]: one run into $out/DIR, its log in $out/DIR.log
    name=$1 m=$2; shift 2
    t0=$(date +%s)
    stage_begin "run $name"
    mkdir -p "$(dirname "$out/$name")"
    # shellcheck disable=SC2086
    bg "$bin" $mfile_opt run --methods "$m" --tols 1e-1,1e-2,1e-3,1e-4,1e-5 --metric hausdorff --split mid \
        $threads --backend "$backend" "$@" --out "$out/$name" 2>"$out/$name.log"
    rc=$?
    stage_end
    echo "nightly: $name: exit $rc in $(($(date +%s) - t0)) s ($(tail -n 1 "$out/$name.log"))" >&2
    [ $rc -eq 0 ] || { echo "nightly: the $name run failed (see $out/$name.log)" >&2; finish 2 "run $name"; }
}
# NIGHTLY_BASE_REF: the baseline build, built once from git in a shared
# clone under OUT/base-build (its log OUT/base-build.log); base_bin
build_base() {
    if [ -n "${NIGHTLY_BASE_BIN:-}" ]; then   # built elsewhere (and the tests)
        base_bin=$NIGHTLY_BASE_BIN bsha=$base_ref
        echo "not built: NIGHTLY_BASE_BIN=$base_bin" >"$out/base-build.log"
        return
    fi
    bsha=$(git rev-parse --verify -q "$base_ref^{commit}") || {
        echo "nightly: NIGHTLY_BASE_REF '$base_ref' is not a commit of this repository" >"$out/base-build.log"
        cat "$out/base-build.log" >&2; finish 2 "build base"; }
    rm -rf "$out/base-build"
    stage_begin "build base"
    # (the make in the background, waited for: a signal's trap fires at once)
    { git clone --quiet --shared --no-checkout . "$out/base-build" && git -C "$out/base-build" checkout --quiet --detach "$bsha" &&
        bg make -C "$out/base-build"; } >"$out/base-build.log" 2>&1 || {
        echo "nightly: the baseline build of $base_ref ($bsha) failed (see $out/base-build.log)" >&2; finish 2 "build base"; }
    stage_end
    base_bin="$out/base-build/offbench"
    echo "nightly: the baseline build: $base_ref ($(printf '%s' "$bsha" | cut -c1-12))" >&2
}
# timing_pair NAME METHODS ROUNDS: the baseline build and this one run
# alternately (base, new, base, new; asv's "continuous"), each time half the
# rounds, on the published set, --time-fits; their rounds joined into
# OUT/NAME/base and OUT/NAME/new (scripts/join_rounds.sh): a burst of load
# hits both sides alike
timing_pair() {
    h=$(( ($3 + 1) / 2 ))
    for half in 1 2; do
        new_bin=$bin bin=$base_bin
        # shellcheck disable=SC2086
        run "$1/base$half" "$2" --reps 2 --time-fits --fit-reps "$h" $curves
        bin=$new_bin
        # shellcheck disable=SC2086
        run "$1/new$half" "$2" --reps 2 --time-fits --fit-reps "$h" $curves
    done
    sh scripts/join_rounds.sh "$out/$1/base" "$out/$1/base1" "$out/$1/base2" &&
        sh scripts/join_rounds.sh "$out/$1/new" "$out/$1/new1" "$out/$1/new2" ||
        { echo "nightly: joining the rounds of $1 failed" >&2; finish 2 "timing $1"; }
}
# NIGHTLY_METHODS_FILE: the external methods it names (their rows are new
# against a baseline without them) in the two runs, not in the timing pairs
# (a baseline build may not know --methods-file)
mfile_opt=${NIGHTLY_METHODS_FILE:+--methods-file $NIGHTLY_METHODS_FILE}
# shellcheck disable=SC2086
run published "$methods" --reps 5 --time-fits --fit-reps "$fit_reps" $curves
run random "$methods" --random "$random"
mfile_opt=

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
# the methods whose timing a compare CSV says the data cannot decide, comma separated
noisy_methods() {
    awk -F, '$1 == "method" && $8 == "time_total" && $15 == "noisy" {printf "%s%s", s, $4; s = ","}' "$1" 2>/dev/null
}
# the rounds those methods need per side (the largest need_reps of the CSV), at least $fit_reps
needed_rounds() {
    awk -F, -v at_least="$fit_reps" '$1 == "method" && $8 == "need_reps" && $9 + 0 > n {n = $9 + 0}
        END {print (n > at_least ? (n > 200 ? 200 : n) : at_least)}' "$1" 2>/dev/null
}
# The timing status from the last verdict of each method (first run, or its
# last re-run) in the CSVs given in run order: 1 when one is slower (or the
# harness, where it counts), else 3 when one is still undecided, else 0.
timing_status() {
    # shellcheck disable=SC2086
    awk -F, '$1 == "method" && $8 == "time_total" { v[$4] = $15 }
        $1 == "harness" && $8 == "time_total" && $15 == "slower" { h = 1 }
        END { s = h; for (m in v) if (v[m] == "slower") s = 1
              if (!s) for (m in v) if (v[m] == "noisy") s = 3
              print s + 0 }' "$@"
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

# timing: against this machine's own baseline, or (NIGHTLY_BASE_REF) the
# baseline build run alternately with this one tonight; the methods the
# data cannot decide run again
mname=$(machine_name "$out/published/meta.json")
mid=$(machine_id "$out/published/meta.json")
mdir=$(machine_dir "$out/published/meta.json")
timing_csvs= timing_note= k=0 tbase=
# A stored baseline against a loaded night (or a baseline made under load)
# is confounded: load moves every method's thread CPU time (caches, memory
# bandwidth), and measured that way 8 of 10 unchanged loaded nights were
# false alarms (docs/nightly.md "How often the verdicts are right").  Then
# the baseline's own commit is built and run alternately with this one
# (interleaved, as NIGHTLY_BASE_REF), where git has that commit; where it
# has not, the night cannot decide its timings (3), never a guess.
if [ -z "$base_ref" ] && [ -n "$mdir" ] && [ -f "$mdir/$mset/results.csv" ] &&
    { [ -n "$(over_load "$out/published/meta.json")" ] || [ -n "$(over_load "$mdir/$mset/meta.json")" ]; }; then
    bc=$(sed -n 's/^  "git_commit": "\([0-9a-f]\{40\}\)",$/\1/p' "$mdir/$mset/meta.json" | head -n 1)
    if [ -n "$bc" ] && git rev-parse --verify -q "$bc^{commit}" >/dev/null 2>&1; then
        base_ref=$bc
        echo "nightly: loaded: timing against the baseline's commit $(printf '%s' "$bc" | cut -c1-12), built and run alternately with this build" >&2
    else
        timing_note="timings not decided: the machine was loaded (load average above its cores) and the stored baseline's commit (${bc:-unknown}) is not in this repository to run beside this build: set NIGHTLY_BASE_REF"
        echo "nightly: $timing_note" >&2
        worst 3
    fi
fi
if [ -n "$base_ref" ]; then
    build_base
    timing_pair timing "$methods" "$fit_reps"
    tbase="$out/timing/base"
elif [ -n "$mdir" ] && [ -f "$mdir/$mset/results.csv" ] && [ -z "$timing_note" ]; then
    tbase="$mdir/$mset"
fi
if [ -n "$tbase" ]; then
    # the timing compares' own exit statuses count only as errors (2): the
    # verdict is each method's last (timing_status), so that a method the
    # first run could not decide and a re-run decided does not end the night 3
    tstatus=$status
    compare_to timing "$tbase" "$([ -n "$base_ref" ] && echo "$out/timing/new" || echo "$out/published")" \
        --timing-only --method-timing-only
    [ "$crc" -eq 2 ] || status=$tstatus
    timing_csvs="$out/compare-timing.csv"
    noisy=$(noisy_methods "$out/compare-timing.csv")
    while [ -n "$noisy" ] && [ "$k" -lt "$reruns" ]; do
        k=$((k + 1))
        rounds=$(needed_rounds "$out/compare-timing$([ $k -gt 1 ] && echo "-rerun$((k - 1))").csv")
        echo "nightly: re-running the methods the data cannot decide: $noisy ($k of $reruns, $rounds rounds)" >&2
        if [ -n "$base_ref" ]; then
            timing_pair "reruns/$k" "$noisy" "$rounds"
            rb="$out/reruns/$k/base" rn="$out/reruns/$k/new"
        else
            # shellcheck disable=SC2086
            run "reruns/$k" "$noisy" --reps 5 --time-fits --fit-reps "$rounds" $curves
            rb="$tbase" rn="$out/reruns/$k"
        fi
        tstatus=$status
        compare_to "timing-rerun$k" "$rb" "$rn" --timing-only --method-timing-only --methods "$noisy"
        [ "$crc" -eq 2 ] || status=$tstatus
        timing_csvs="$timing_csvs $out/compare-timing-rerun$k.csv"
        noisy=$(noisy_methods "$out/compare-timing-rerun$k.csv")
    done
    # shellcheck disable=SC2086
    worst "$(timing_status $timing_csvs)"
elif [ -z "$timing_note" ]; then
    timing_note="timings not judged: no ${small}baseline of this machine ('${mname:-unknown}', id ${mid:-unknown}) in $baselines: \`scripts/nightly.sh --accept\` after a quiet night makes the run just made this machine's baseline"
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
            by[$4] = tf == 1 ? "first run" : "re-run " (tf - 1); need[$4] = ""
        }
        role == "t" && $1 == "method" && $8 == "need_reps" { need[$4] = $10 }
        role == "t" && $1 == "harness" && $8 == "time_total" {
            htb = $9; htn = $10; hest = $11; hlo = $13; hhi = $14; hv = $15; hseen = 1
        }
        function ms(x) { return x == "" ? "-" : sprintf("%.4g ms", x / 1e6) }
        function num(x) { return x == "" ? "-" : sprintf("%.4g", x) }
        END {
            print "| method | time base | time new | time new/base | interval | timing | quality regressions | decided by |"
            print "|---|---:|---:|---:|---:|---|---:|---|"
            for (i = 1; i <= n; i++) {
                m = order[i]
                w = v[m] == "" ? "-" : v[m] == "same" ? "no change" : \
                    v[m] == "noisy" ? "cannot decide: need " (need[m] == "" ? "more" : need[m] " more") " repetitions" : \
                    v[m] == "few_reps" ? "not judged: too few repetitions" : v[m]
                iv = lo[m] == "" ? "-" : (hi[m] == "inf" ? "unbounded" : sprintf("[%.4g, %.4g]", lo[m], hi[m]))
                printf "| %s | %s | %s | %s | %s | %s | %d | %s |\n", m, ms(tb[m]), ms(tn[m]), num(est[m]), iv, w,
                       q[m] + 0, m in by ? by[m] : "-"
            }
            if (hseen) {
                iv = hlo == "" ? "-" : (hhi == "inf" ? "unbounded" : sprintf("[%.4g, %.4g]", hlo, hhi))
                split(hv, hw, " ")
                w = hw[1] == "same" ? "no change" : hw[1] == "noisy" ? "cannot decide" : \
                    hw[1] == "few_reps" ? "not judged: too few repetitions" : hw[1]
                printf "| *harness* (eval_ns) | %s | %s | %s | %s | %s%s | - | first run |\n", ms(htb), ms(htn), num(hest), iv, w,
                       hw[2] == "reported_only" ? " (reported only)" : ""
            }
        }' role=t $timing_csvs role=q "$out/compare-published-quality.csv" "$out/compare-random-quality.csv"
}
# the per-method timing verdicts of the table, counted: "N slower (a, b), N faster, ..."
timing_counts() {
    # shellcheck disable=SC2086
    awk -F, '$1 == "method" && $8 == "time_total" { v[$4] = $15 }
        END { for (m in v) { c[v[m]]++; if (v[m] == "slower") s = s (s == "" ? "" : ", ") m }
              printf "%d slower%s, %d faster, %d no change, %d undecided", c["slower"] + 0, s == "" ? "" : " (" s ")",
                     c["faster"] + 0, c["same"] + 0, c["noisy"] + c["few_reps"] }' $timing_csvs
}
# what each quality comparison left out of the baseline (compare's "Left
# out:" line: the rows outside this run's selection, not regressions)
left_out_lines() {
    for name in published random; do
        sed -n "s/^Left out: \(.*\) (rows of BASE outside NEW's selection: not regressions)\.\$/Left out of $name (a subset chosen on purpose, not regressions): \1./p" \
            "$out/compare-$name-quality.md" 2>/dev/null | head -n 1
    done
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
        tline="timing: $(timing_counts) (each method's own fit time, against $([ -n "$base_ref" ] && echo "$base_ref built and run alternately tonight" || echo "this machine's baseline"))"
    elif [ -n "$timing_csvs" ]; then
        tline="timing: not judged"
    else
        tline="timing: $(case "$timing_note" in "timings not decided"*) echo "not decided (loaded, the baseline's commit not at hand)" ;; *) echo "not judged (no ${small}baseline of this machine)" ;; esac)"
    fi
    echo "**$(status_word $status)** (exit $status): $tline; quality: published $(first_line "$out/compare-published-quality.md"), random $(first_line "$out/compare-random-quality.md")."
    if [ -n "$timing_csvs" ]; then
        printf '%s' "$(grep -m 1 '^Timing: ' "$out/compare-timing.md")"
        [ "$k" -eq 0 ] || printf ' The methods the data could not decide were run again %d time(s): the table says which run decided.' "$k"
        echo
    else
        case "$timing_note" in
            "timings not decided"*) echo "Timing: **not decided**: ${timing_note#timings not decided: }." ;;
            *) echo "Timing: **not judged**: no ${small}baseline of this machine ('${mname:-unknown}', id ${mid:-unknown})." ;;
        esac
    fi
    left_out_lines
    echo
    echo "Commit $(printf '%s' "$commit" | cut -c1-12)$([ "$dirty" = true ] && echo ' (dirty)'); machine '${mname:-unknown}' (id ${mid:-unknown}); quality against $qbase/ (committed); timing against $([ -n "$base_ref" ] && echo "the build of $base_ref ($(printf '%s' "${bsha:-}" | cut -c1-12)), run alternately with this one tonight" || echo "${mdir:-none}/$mset$([ -n "$timing_csvs" ] || echo ' (none yet)')"); size $size; random set $random; methods $methods."
    echo
    echo "## Verdict by method"
    echo
    verdict_table
    echo
    if [ -n "$timing_csvs" ]; then
        section "published: timing against $([ -n "$base_ref" ] && echo "the build of $base_ref, interleaved" || echo "this machine's baseline")" timing
        i=1
        while [ "$i" -le "$k" ]; do
            section "published: timing, re-run $i of the methods the data could not decide" "timing-rerun$i"
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
