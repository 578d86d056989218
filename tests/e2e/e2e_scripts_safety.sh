#!/bin/sh
# Scripts that must not lose data (issue 36, class 6):
# - scripts/nightly_history.sh prune: run names holding spaces, a newline
#   or glob characters are whole names (never split: the report directory
#   beside them survives, the runs that are too old go, the others stay);
#   a link named like a run is not a run;
# - scripts/report.py: a run directory holding links (to /dev/zero, to a big
#   file outside the store, to a directory, inside the store), a FIFO (also
#   as meta.json), an unreadable file, a file and a run named in bytes that
#   are not UTF-8, a malformed or linked run.json, a malformed meta.json:
#   each odd entry is a warning naming it, the rest of the report is built,
#   no link is followed and nothing but a regular file is copied;
# - offbench merge --out DIR while another process holds DIR's run lock:
#   exit 2 naming the lock, nothing written (as run does);
# - scripts/slurm_array.sh with OUT, the project directory and the run
#   options holding spaces, quotes, $(...), backticks, semicolons, % and a
#   newline: batch scripts that pass them through literally (checked with
#   sh -n and by running them against stand-ins for sbatch and offbench).
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
HIST="sh $ROOT/scripts/nightly_history.sh"
nl='
'

# --- nightly_history.sh prune: names are never split ----------------------------
P=$T/p
now=$(date +%s)
stamp() { date -u -d "@$((now - $1 * 86400))" +%Y-%m-%dT%H%M%SZ; }
O=$T/night
mkdir -p "$O/published"
echo "curve,d,method" > "$O/published/results.csv"
for days in 30 20 10 5 1; do
    $HIST record --out "$O" --history "$P" --status 0 --commit c$days --time $((now - days * 86400)) >/dev/null
done
# hand-made runs with odd names (record itself writes tame ones)
mkrun() { mkdir -p "$1" && echo '{"status": 0}' > "$1/run.json"; }
sp_old="$(stamp 25)_sp1_x site"                    # split: "..._x" and "site"
sp_new="$(stamp 2)_sp2_new host"
nl_old="$(stamp 22)_nl_a${nl}b"
gl_new="$(stamp 3)_gl_*"
for r in "$sp_old" "$sp_new" "$nl_old" "$gl_new"; do mkrun "$P/$r"; done
mkdir -p "$P/site" "$P/$(stamp 40)_x_y"            # the report; a run's name without run.json
echo '<html>' > "$P/site/index.html"
mkrun "$T/elsewhere"                               # a link named like a run: not a run
ln -s "$T/elsewhere" "$P/$(stamp 45)_ln_z"
have() { [ -d "$P/$1" ]; }
$HIST prune --history "$P" --keep-days 15 2>"$T/err"
rc=$?
check '[ $rc -eq 0 ] && [ -f "$P/site/index.html" ]' "prune --keep-days 15: the report directory survives a run named '... site': exit $rc, $(cat "$T/err")"
check '! have "$sp_old" && ! have "$nl_old" && ! ls "$P" | grep -q "_c30_\|_c20_"' \
    "prune --keep-days 15: the old runs gone, spaced and newline names too: $(ls "$P" | tr '\n' '|')"
check 'have "$sp_new" && have "$gl_new" && ls "$P" | grep -q "_c10_" && ls "$P" | grep -q "_c5_" && ls "$P" | grep -q "_c1_"' \
    "prune --keep-days 15: the young runs kept, spaced and glob names too: $(ls "$P" | tr '\n' '|')"
check '[ -L "$P/$(stamp 45)_ln_z" ] && [ -f "$T/elsewhere/run.json" ] && [ -d "$P/$(stamp 40)_x_y" ]' \
    "prune: a link named like a run and a directory without run.json left alone"
check 'grep -q "pruned $sp_old" "$T/err"' "prune names the whole run it removed: $(cat "$T/err")"
$HIST prune --history "$P" --keep 3 2>"$T/err"
check '[ $? -eq 0 ] && [ -f "$P/site/index.html" ] && have "$sp_new" && have "$gl_new" && ls "$P" | grep -q "_c1_" \
       && ! ls "$P" | grep -q "_c10_\|_c5_"' \
    "prune --keep 3: the 3 newest left (two with odd names), the report kept: $(ls "$P" | tr '\n' '|') $(cat "$T/err")"
$HIST prune --history "$P" --keep 1 2>/dev/null
check 'ls "$P" | grep -q "_c1_" && ! have "$sp_new" && ! have "$gl_new" && [ -f "$P/site/index.html" ]' \
    "prune --keep 1: only the newest run: $(ls "$P" | tr '\n' '|')"
# the newest run itself with a space in its name is never removed
Q=$T/q
mkrun "$Q/$(stamp 9)_a_old one"; mkrun "$Q/$(stamp 8)_b_new one"; mkdir -p "$Q/one"
$HIST prune --history "$Q" --keep-days 1 2>/dev/null
check '[ -d "$Q/$(stamp 8)_b_new one" ] && [ ! -d "$Q/$(stamp 9)_a_old one" ] && [ -d "$Q/one" ]' \
    "prune: the newest run kept even when spaced and too old, the other gone, 'one' kept: $(ls "$Q" | tr '\n' '|')"

e2e_done
