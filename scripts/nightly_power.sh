#!/bin/sh
# nightly_power.sh - how often the nightly's timing verdicts are right: the
# detection rate of planted fit slowdowns and the false-alarm rate of
# unchanged nights, on this machine, idle or loaded (issue 46).  A script,
# not a test: it times things, so it belongs nowhere near `make test`.
#
# A "night" is the nightly's timing step on a small configuration: `run
# --time-fits` of every method on a few curves (OFFBENCH_TEST_SLOW plants a
# slowdown of one method's fits), compared as scripts/nightly.sh does
# (compare --timing-only --method-timing-only), the methods the data cannot
# decide run again once with the rounds compare asks for, the last
# comparison deciding.  Two protocols (--protocol):
#   interleaved  the nightly with NIGHTLY_BASE_REF (asv's continuous): each
#                night the baseline build (here: the same build without the
#                plant) and the new one run alternately, base, new, base,
#                new, half the rounds each time, their rounds joined
#                (scripts/join_rounds.sh): a burst of load hits both sides;
#   stored       the nightly with a machine baseline: one run, made once at
#                the start (in the first condition's state), is every
#                night's baseline.
#
# Per condition (idle; loaded: LOAD_PROCS CPU-bound processes beside it,
# default 2, so that the load average is at least 4 on 2 cores), NIGHTS
# unchanged nights and NIGHTS nights for each planted METHOD:FACTOR.
# Printed: per condition and plant, nights detected (the planted method
# "slower"), undecided (exit 3) and false alarms (another method slower or
# faster, or any verdict on an unchanged night), and the load averages seen.
#
# Usage: sh scripts/nightly_power.sh [--nights N] [--conditions idle,loaded]
#            [--plants tiller:1.5,tiller:3,...] [--protocol interleaved|stored]
#            [--out DIR]
# Environment: OFFBENCH (default ./offbench), POWER_CURVES (the curves,
# default liu2002_ex1,atlas_folium: 270 jobs),
# LOAD_PROCS, POWER_FIT_REPS (rounds per run, default 10).
set -u
cd "$(dirname "$0")/.."
nights=10
conditions=idle,loaded
plants=tiller:1.5,tiller:3,ahn:1.5,ahn:3,zhao-rational:1.5,zhao-rational:3
out=out/power
protocol=interleaved
while [ $# -gt 0 ]; do
    case "$1" in
        --nights) nights=$2; shift 2 ;;
        --conditions) conditions=$2; shift 2 ;;
        --plants) plants=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --protocol) protocol=$2; shift 2 ;;
        -h|--help) sed -n '2,37p' "$0"; exit 0 ;;
        *) echo "nightly_power: unknown option '$1'" >&2; exit 2 ;;
    esac
done
ob=${OFFBENCH:-./offbench}
curves=${POWER_CURVES:-liu2002_ex1,atlas_folium}
fit_reps=${POWER_FIT_REPS:-10}
[ -x "$ob" ] || { echo "nightly_power: no $ob (make first)" >&2; exit 2; }
rm -rf "$out" && mkdir -p "$out" || exit 2

# timed_run DIR METHODS ROUNDS: the nightly's timed run on the small set
timed_run() {
    "$ob" run --curve "$curves" --methods "$2" --backend cpu --time-fits --fit-reps "$3" \
        --out "$1" --force >/dev/null 2>"$1.log"
}
# pair DIR PLANT METHODS ROUNDS: DIR/base and DIR/new with ROUNDS rounds
# each: interleaved, base new base new (half the rounds each, joined);
# stored, DIR/base is the stored baseline and new one run
pair() {
    mkdir -p "$1"
    if [ "$protocol" = stored ]; then
        rm -rf "$1/base" && ln -s "$(cd "$out" && pwd)/base" "$1/base" &&
            OFFBENCH_TEST_SLOW=$2 timed_run "$1/new" "$3" "$4"
        return
    fi
    h=$(( ($4 + 1) / 2 ))
    timed_run "$1/b1" "$3" "$h" && OFFBENCH_TEST_SLOW=$2 timed_run "$1/n1" "$3" "$h" &&
        timed_run "$1/b2" "$3" "$h" && OFFBENCH_TEST_SLOW=$2 timed_run "$1/n2" "$3" "$h" &&
        sh scripts/join_rounds.sh "$1/base" "$1/b1" "$1/b2" && sh scripts/join_rounds.sh "$1/new" "$1/n1" "$1/n2"
}
# night NAME PLANT: one night; prints "verdicts;load" where verdicts are
# method=verdict pairs of the deciding comparison
night() {
    d="$out/$1"
    pair "$d" "$2" all "$fit_reps" || { echo "error;"; return; }
    "$ob" compare "$d/base" "$d/new" --timing-only --method-timing-only --format csv --out "$d.csv" 2>/dev/null
    undecided=$(awk -F, '$1 == "method" && $8 == "time_total" && $15 == "noisy" {printf "%s%s", s, $4; s = ","}' "$d.csv")
    final="$d.csv"
    if [ -n "$undecided" ]; then   # the nightly's re-run, once, with the rounds asked for
        need=$(awk -F, -v m="$fit_reps" '$1 == "method" && $8 == "need_reps" && $9 + 0 > m {m = $9 + 0} END {print (m > 60 ? 60 : m)}' "$d.csv")
        pair "$d-rerun" "$2" "$undecided" "$need" &&
            "$ob" compare "$d-rerun/base" "$d-rerun/new" --timing-only --method-timing-only --methods "$undecided" \
                --format csv --out "$d-rerun.csv" 2>/dev/null
        [ -s "$d-rerun.csv" ] && final="$d.csv $d-rerun.csv"
    fi
    # shellcheck disable=SC2086
    v=$(awk -F, '$1 == "method" && $8 == "time_total" {v[$4] = $15} END {for (m in v) printf "%s=%s ", m, v[m]}' $final)
    echo "$v;$(cut -d' ' -f1 /proc/loadavg)"
}
# tally CONDITION PLANT FILE: one line of the table
tally() {
    awk -v cond="$1" -v plant="$2" -F';' '
        { n++; split($1, kv, " "); det = 0; und = 0; fa = 0
          pm = plant; sub(/:.*/, "", pm)
          for (i in kv) { split(kv[i], p, "="); m = p[1]; v = p[2]
              if (plant != "none" && m == pm) { if (v == "slower") det = 1; else if (v == "noisy") und = 1 }
              else if (v == "slower" || v == "faster") fa = 1
              else if (v == "noisy") und = 1 }
          D += det; U += und; F += fa; if ($2 + 0 > L) L = $2 + 0; S += $2 }
        END { printf "| %s | %s | %d | %s | %d | %d | %.1f (max %.1f) |\n", cond, plant, n,
                     plant == "none" ? "-" : D "/" n, U, F, n ? S / n : 0, L }' "$3"
}

hogs=
stop_hogs() { [ -z "$hogs" ] || kill $hogs 2>/dev/null; hogs=; }
trap 'stop_hogs' EXIT INT TERM
if [ "$protocol" = stored ]; then
    echo "nightly_power: the stored baseline: $curves, every method, --fit-reps $fit_reps" >&2
    timed_run "$out/base" all "$fit_reps" || { echo "nightly_power: the baseline run failed (see $out/base.log)" >&2; exit 2; }
fi
echo "Protocol $protocol; curves $curves, every method, 1e-1 ... 1e-5, --fit-reps $fit_reps; $(nproc) CPUs ($(grep -m 1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')); $(date -u +%Y-%m-%d)."
echo
echo "| condition | plant | nights | detected | undecided | false alarms | load average (1 min) |"
echo "|---|---|---:|---:|---:|---:|---:|"
for cond in $(echo "$conditions" | tr ',' ' '); do
    if [ "$cond" = loaded ]; then
        k=0
        while [ "$k" -lt "${LOAD_PROCS:-2}" ]; do
            sh -c 'while :; do :; done' &
            hogs="$hogs $!"
            k=$((k + 1))
        done
        sleep 30   # let the 1-minute load average climb
    fi
    for plant in none $(echo "$plants" | tr ',' ' '); do
        : >"$out/$cond-$plant.txt"
        i=1
        while [ "$i" -le "$nights" ]; do
            night "$cond-$plant-$i" "$([ "$plant" = none ] && echo "" || echo "$plant")" >>"$out/$cond-$plant.txt"
            i=$((i + 1))
        done
        tally "$cond" "$plant" "$out/$cond-$plant.txt"
    done
    stop_hogs
done
