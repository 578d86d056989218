#!/bin/sh
# scripts/slurm_array.sh against a stand-in for sbatch that runs each array
# task (and then the merge job) at once, in order: the recipe's commands must
# produce the unsharded run's results.csv.
. "$(dirname "$0")/lib_e2e.sh"

# sbatch stand-in: reads the batch script from stdin, runs it once per array
# index with SLURM_ARRAY_TASK_ID set (or once), prints a job id
mkdir "$T/bin"
cat > "$T/bin/sbatch" <<'EOF'
#!/bin/sh
array=""
for a in "$@"; do case "$a" in --array=*) array=${a#--array=} ;; esac; done
cat > "$0.script.$$"
if [ -n "$array" ]; then
    i=${array%-*}; last=${array#*-}
    while [ "$i" -le "$last" ]; do
        SLURM_ARRAY_TASK_ID=$i SLURM_CPUS_PER_TASK=1 sh "$0.script.$$" >/dev/null 2>&1 || exit 1
        i=$((i + 1))
    done
else
    sh "$0.script.$$" >/dev/null 2>&1 || exit 1
fi
rm -f "$0.script.$$"
echo 4242
EOF
chmod +x "$T/bin/sbatch"

# the recipe runs ./offbench of the project directory
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ "$OB" != "$root/offbench" ]; then
    echo "SKIP: the recipe runs $root/offbench, the tests run $OB" >&2
    echo "0 passed, 0 failed, 3 skipped"
    exit 0
fi
R="--random 16:9 --methods tiller,ahn --tols 1e-1,1e-3 --backend cpu"
$OB run $R --out "$T/one" 2>/dev/null
PATH="$T/bin:$PATH" sh "$root/scripts/slurm_array.sh" 3 "$T/night" -- $R > "$T/out.txt" 2>&1
check '[ $? -eq 0 ] && grep -q "submitted array job 4242 (3 shards)" "$T/out.txt"' "the recipe submits: $(cat "$T/out.txt")"
check '[ -f "$T/night/merged/results.csv" ] && body "$T/night/merged/results.csv" | cmp -s - "$(body "$T/one/results.csv" > "$T/one.txt"; echo "$T/one.txt")"' \
    "3 array tasks merged equal the single run"
PATH="$T/bin:$PATH" sh "$root/scripts/slurm_array.sh" x "$T/bad" -- $R > /dev/null 2>&1
check '[ $? -eq 2 ]' "a bad shard count is refused"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
