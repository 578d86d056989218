#!/bin/sh
# slurm_array.sh - a large offbench run as a Slurm job array: one array task
# per shard (`run --shard K/N`), then one job that merges the shards into the
# results.csv a single run writes (`merge`, which refuses a missing,
# repeated or foreign shard).
#
# Usage (from the project directory, on the cluster's login node, after
# `make` there):
#   scripts/slurm_array.sh N OUT -- RUN-OPTIONS...
#   e.g. scripts/slurm_array.sh 64 /scratch/$USER/night -- --random 100000:7 --methods all
#
# It submits
#   1. an array job of N tasks; task K runs
#        ./offbench run RUN-OPTIONS --shard K/N --threads $SLURM_CPUS_PER_TASK --out OUT/shard-K
#      (a task that dies is rerun with the same command plus --resume OUT/shard-K:
#      `sbatch --requeue` does this on node failure; by hand: scontrol requeue);
#   2. a merge job that starts when every task has succeeded:
#        ./offbench merge OUT/shard-* --out OUT/merged
# Each task's cost is balanced by offbench's estimate, not by job count.
# Environment: SBATCH_CPUS (default 8 cores per task), SBATCH_TIME (default
# 02:00:00), SBATCH_EXTRA (more sbatch options, e.g. "-p long -A proj",
# split at blanks).  OUT, the project directory and RUN-OPTIONS reach the
# batch scripts single-quoted: any character in them is passed on literally
# (a % in OUT is doubled for sbatch --output).
set -eu
[ $# -ge 3 ] && [ "$3" = "--" ] || { sed -n '2,24p' "$0"; exit 2; }
N=$1
OUT=$2
shift 3
case "$N" in ''|*[!0-9]*) echo "slurm_array: N must be a whole number, got '$N'" >&2; exit 2 ;; esac
[ "$N" -ge 1 ] || { echo "slurm_array: N must be >= 1" >&2; exit 2; }
[ -n "$OUT" ] || { echo "slurm_array: OUT must not be empty" >&2; exit 2; }
cpus=${SBATCH_CPUS:-8}
case "$cpus" in ''|*[!0-9]*|0) echo "slurm_array: SBATCH_CPUS must be a whole number of cores >= 1, got '$cpus'" >&2; exit 2 ;; esac
command -v sbatch >/dev/null 2>&1 || { echo "slurm_array: sbatch not found (not a Slurm login node?)" >&2; exit 2; }
cd "$(dirname "$0")/.."
[ -x ./offbench ] || { echo "slurm_array: build first: make" >&2; exit 2; }
mkdir -p "$OUT/logs"

# sq VALUE: VALUE as one single-quoted sh word ('it'\''s').  Every value the
# user gives reaches the batch scripts only this way, so spaces, quotes,
# $(...), backticks, semicolons or newlines in it are passed on as they are:
# never run, split or globbed.
sq() {
    printf "'"
    printf '%s' "$1" | sed "s/'/'\\\\''/g"
    printf "'"
}
# OUT in a file name for sbatch --output, whose patterns take %% for a %
log_out=$(printf '%s.' "$OUT" | sed 's/%/%%/g')
log_out=${log_out%.}

# the start of both batch scripts: the project directory, OUT and N as
# variables, the run options (ARGS) as the positional parameters
script_head() {
    printf '#!/bin/sh\nset -eu\ncd %s\nOUT=%s\nN=%s\nset --' "$(sq "$PWD")" "$(sq "$OUT")" "$N"
    for a in "$@"; do printf ' %s' "$(sq "$a")"; done
    printf '\n'
}
# the rest is fixed text: no value is expanded into it
array_script() {
    script_head "$@"
    cat <<'EOF'
K=$SLURM_ARRAY_TASK_ID
DIR=$OUT/shard-$K
if [ -f "$DIR/results.journal.csv" ]; then where=--resume; else where=--out; fi
exec ./offbench run "$@" --shard "$K/$N" --threads "${SLURM_CPUS_PER_TASK:-1}" "$where" "$DIR"
EOF
}
merge_script() {
    script_head
    cat <<'EOF'
exec ./offbench merge "$OUT"/shard-* --out "$OUT/merged"
EOF
}

set -f  # SBATCH_EXTRA is split into sbatch options at blanks, never globbed
# shellcheck disable=SC2086
array=$(array_script "$@" | sbatch --parsable --array=0-$((N - 1)) --cpus-per-task="$cpus" \
    --time="${SBATCH_TIME:-02:00:00}" --requeue --job-name=offbench-shard \
    --output="$log_out/logs/shard-%a.log" ${SBATCH_EXTRA:-})
# shellcheck disable=SC2086
merge=$(merge_script | sbatch --parsable --dependency=afterok:"$array" --time=00:30:00 \
    --job-name=offbench-merge --output="$log_out/logs/merge.log" ${SBATCH_EXTRA:-})
echo "slurm_array: submitted array job $array ($N shards) and merge job $merge; results in $OUT/merged"
