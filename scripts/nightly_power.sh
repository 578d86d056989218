#!/bin/sh
# nightly_power.sh - how often the nightly's timing verdicts are right: the
# detection rate of planted fit slowdowns and the false-alarm rate of
# unchanged nights, on this machine, idle or loaded (issue 46).  A script,
# not a test: it times things, so it belongs nowhere near `make test`.
#
# A "night" is the nightly's timing step on a small configuration: one
# `run --time-fits` of every method on a few curves (OFFBENCH_TEST_SLOW
# plants a slowdown of one method's fits), compared with this machine's
# baseline as scripts/nightly.sh does (compare --timing-only
# --method-timing-only), the methods the data cannot decide run again once
# with the rounds compare asks for, the last comparison deciding.  The
# baseline is one such run, accepted once, idle, before the nights (as a
# machine's baseline is in use).
#
# Per condition (idle; loaded: LOAD_PROCS CPU-bound processes beside it,
# default 2, so that the load average is at least 4 on 2 cores), NIGHTS
# unchanged nights and NIGHTS nights for each planted METHOD:FACTOR.
# Printed: per condition and plant, nights detected (the planted method
# "slower"), undecided (exit 3) and false alarms (another method slower or
# faster, or any verdict on an unchanged night), and the load averages seen.
#
# Usage: sh scripts/nightly_power.sh [--nights N] [--conditions idle,loaded]
#            [--plants tiller:1.5,tiller:3,...] [--out DIR]
# Environment: OFFBENCH (default ./offbench), POWER_CURVES (the curves,
# default liu2002_ex1,atlas_folium: 270 jobs),
# LOAD_PROCS, POWER_FIT_REPS (rounds per run, default 10).
set -u
cd "$(dirname "$0")/.."
nights=10
conditions=idle,loaded
plants=tiller:1.5,tiller:3,ahn:1.5,ahn:3,zhao-rational:1.5,zhao-rational:3
out=out/power
while [ $# -gt 0 ]; do
    case "$1" in
        --nights) nights=$2; shift 2 ;;
        --conditions) conditions=$2; shift 2 ;;
        --plants) plants=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        -h|--help) sed -n '2,27p' "$0"; exit 0 ;;
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
# night NAME PLANT: one night; prints "verdicts;load" where verdicts are
# method=verdict pairs of the deciding comparison
night() {
    d="$out/$1"
    OFFBENCH_TEST_SLOW=$2 timed_run "$d" all "$fit_reps" || { echo "error;"; return; }
    "$ob" compare "$out/base" "$d" --timing-only --method-timing-only --format csv --out "$d.csv" 2>/dev/null
    undecided=$(awk -F, '$1 == "method" && $8 == "time_total" && $15 == "noisy" {printf "%s%s", s, $4; s = ","}' "$d.csv")
    final="$d.csv"
    if [ -n "$undecided" ]; then   # the nightly's re-run, once, with the rounds asked for
        need=$(awk -F, -v m="$fit_reps" '$1 == "method" && $8 == "need_reps" && $9 + 0 > m {m = $9 + 0} END {print (m > 60 ? 60 : m)}' "$d.csv")
        OFFBENCH_TEST_SLOW=$2 timed_run "$d-rerun" "$undecided" "$need" &&
            "$ob" compare "$out/base" "$d-rerun" --timing-only --method-timing-only --methods "$undecided" \
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
echo "nightly_power: baseline (idle): $curves, every method, --fit-reps $fit_reps" >&2
timed_run "$out/base" all "$fit_reps" || { echo "nightly_power: the baseline run failed (see $out/base.log)" >&2; exit 2; }
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
