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
# 02:00:00), SBATCH_EXTRA (more sbatch options, e.g. "-p long -A proj").
set -eu
[ $# -ge 3 ] && [ "$3" = "--" ] || { sed -n '2,25p' "$0"; exit 2; }
N=$1
OUT=$2
shift 3
case "$N" in ''|*[!0-9]*) echo "slurm_array: N must be a whole number, got '$N'" >&2; exit 2 ;; esac
[ "$N" -ge 1 ] || { echo "slurm_array: N must be >= 1" >&2; exit 2; }
command -v sbatch >/dev/null 2>&1 || { echo "slurm_array: sbatch not found (not a Slurm login node?)" >&2; exit 2; }
cd "$(dirname "$0")/.."
[ -x ./offbench ] || { echo "slurm_array: build first: make" >&2; exit 2; }
mkdir -p "$OUT/logs"
cpus=${SBATCH_CPUS:-8}
# the run options, quoted for the batch script
opts=""
for a in "$@"; do opts="$opts '$(printf %s "$a" | sed "s/'/'\\\\''/g")'"; done

# shellcheck disable=SC2086
array=$(sbatch --parsable --array=0-$((N - 1)) --cpus-per-task="$cpus" --time="${SBATCH_TIME:-02:00:00}" \
    --requeue --job-name=offbench-shard --output="$OUT/logs/shard-%a.log" ${SBATCH_EXTRA:-} <<EOF
#!/bin/sh
set -eu
cd "$PWD"
K=\$SLURM_ARRAY_TASK_ID
DIR="$OUT/shard-\$K"
if [ -f "\$DIR/results.journal.csv" ]; then resume="--resume \$DIR"; else resume="--out \$DIR"; fi
exec ./offbench run $opts --shard \$K/$N --threads \${SLURM_CPUS_PER_TASK:-1} \$resume
EOF
)
# shellcheck disable=SC2086
merge=$(sbatch --parsable --dependency=afterok:"$array" --time=00:30:00 --job-name=offbench-merge \
    --output="$OUT/logs/merge.log" ${SBATCH_EXTRA:-} <<EOF
#!/bin/sh
set -eu
cd "$PWD"
exec ./offbench merge "$OUT"/shard-* --out "$OUT/merged"
EOF
)
echo "slurm_array: submitted array job $array ($N shards) and merge job $merge; results in $OUT/merged"
