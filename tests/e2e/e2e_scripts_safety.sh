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

# --- report.py: odd entries in the store ------------------------------------------
S=$T/store
HDR="curve,d,method,metric,split,tol,ctrl_points,status,fit_ns,eval_ns"
mkgood() {  # DIR DAY: a run with one published row
    mkdir -p "$1/published"
    printf '{"name": "x", "date": "2026-01-0%sT00:00:00Z", "commit": "abcdef%s", "commit_short": "abcdef%s", "status": 0}\n' \
        "$2" "$2" "$2" > "$1/run.json"
    printf '%s\nc1,0.1,tiller,hausdorff,mid,0.01,1%s,ok,1000,200\n' "$HDR" "$2" > "$1/published/results.csv"
    echo '{"cpu_model": "x"}' > "$1/published/meta.json"
    echo "log $2" > "$1/published.log"
}
R1=2026-01-01T000000Z_abcdef1_h R2=2026-01-02T000000Z_abcdef2_h R3=2026-01-03T000000Z_abcdef3_h
BADNAME=$(printf 'caf\351.log')
R8=$(printf '2026-01-08T000000Z_abcdef8_h\351')
for r in "$R1:1" "$R2:2" "$R3:3" "$R8:8"; do mkgood "$S/${r%:*}" "${r##*:}"; done
echo '{oops' > "$S/$R1/published/meta.json"                  # malformed meta.json
mkdir -p "$T/outside"
head -c 2000000 /dev/zero > "$T/outside/big.bin"
ln -s /dev/zero "$S/$R2/zero.log"                           # the 6 GB of the issue
ln -s "$T/outside/big.bin" "$S/$R2/big.csv"                 # a big file outside the store
ln -s "$T/outside" "$S/$R2/outdir"                          # a directory outside
ln -s "../../$R1/published/results.csv" "$S/$R2/published/link.csv"  # a link inside the store
mkfifo "$S/$R2/pipe.log"
echo "dear" > "$S/$R2/$BADNAME"                             # a name that is not UTF-8
echo "secret" > "$S/$R2/secret.log"; chmod 000 "$S/$R2/secret.log"
rm "$S/$R3/published/meta.json"; mkfifo "$S/$R3/published/meta.json"  # reading it would hang
mkdir -p "$S/2026-01-04T000000Z_abcdef4_h"; echo '{"status": 0,' > "$S/2026-01-04T000000Z_abcdef4_h/run.json"
mkdir -p "$S/2026-01-05T000000Z_abcdef5_h"; ln -s "../$R1/run.json" "$S/2026-01-05T000000Z_abcdef5_h/run.json"
mkdir -p "$S/2026-01-06T000000Z_abcdef6_h"
$PY -c 'import sys; open(sys.argv[1], "w").write("[" * 200000 + "]" * 200000)' "$S/2026-01-06T000000Z_abcdef6_h/run.json"
mkdir -p "$S/2026-01-07T000000Z_abcdef7_h"
echo '{"status": "x", "date": null, "seconds": [1], "host": {"a": 1}, "commit_short": "abcdef7", "stage": "\udcff"}' > "$S/2026-01-07T000000Z_abcdef7_h/run.json"
# report SITE [--copy-files]: at most 60 s and 10 MB per file written, so
# that a report that follows /dev/zero or blocks on a FIFO fails, not hangs
report() {
    site=$1; shift
    (ulimit -f 20000; timeout 60 "$PY" "$ROOT/scripts/report.py" "$S" --out "$site" "$@") 2>"$T/rerr"
}
# resolves SITE/index.html: every relative href, percent-decoded, exists
links_ok() {
    "$PY" - "$1" <<'EOF'
import html, os, re, sys, urllib.parse
site = sys.argv[1]
text = open(os.path.join(site, "index.html"), encoding="utf-8").read()
bad = [h for h in re.findall(r'href="([^"#:]+)"', text)
       if not os.path.exists(os.path.join(os.fsencode(site), urllib.parse.unquote_to_bytes(html.unescape(h))))]
print(" ".join(bad))
sys.exit(1 if bad else 0)
EOF
}
nrows() { grep -o '<tr class="run[ "][^>]*data-commit="abcdef[0-9]"' "$1" | wc -l; }
for mode in link copy; do
    site=$T/site-$mode
    if [ $mode = copy ]; then report "$site" --copy-files; else report "$site"; fi
    rc=$?
    check '[ $rc -eq 0 ] && [ -s "$site/index.html" ]' "report.py ($mode): built in spite of the odd entries: exit $rc, $(tail -n 5 "$T/rerr")"
    check '[ "$(nrows "$site/index.html")" -eq 5 ]' "report.py ($mode): the 5 readable runs shown: $(nrows "$site/index.html")"
    check '$PY -c "import sys; open(sys.argv[1], encoding=\"utf-8\").read()" "$site/index.html"' "report.py ($mode): the page is UTF-8"
    for w in "$R2/zero.log" "$R2/big.csv" "$R2/outdir" "$R2/published/link.csv" "$R2/pipe.log" \
             "$R3/published/meta.json" "$R1/published/meta.json" \
             2026-01-04T000000Z_abcdef4_h/run.json 2026-01-05T000000Z_abcdef5_h/run.json 2026-01-06T000000Z_abcdef6_h/run.json; do
        check 'grep -qF -- "$w" "$T/rerr"' "report.py ($mode): a warning names $w: $(cat "$T/rerr")"
    done
    check '! grep -q "zero\.log\"\|big\.csv\"\|pipe\.log\"\|link\.csv\"\|outdir\"" "$site/index.html"' \
        "report.py ($mode): no link to a link or a FIFO"
    check 'grep -q "zero.log" "$site/index.html" && grep -q "pipe.log" "$site/index.html"' \
        "report.py ($mode): the odd entries flagged on the page"
    bad_links=$(links_ok "$site")
    check '[ $? -eq 0 ] && grep -q "caf%E9.log" "$site/index.html"' \
        "report.py ($mode): every link resolves, the non-UTF-8 name percent-encoded: $bad_links"
done
C=$T/site-copy/runs
check '[ -f "$C/$R2/published/results.csv" ] && [ -f "$C/$R2/run.json" ] && [ -f "$C/$R2/$BADNAME" ] && [ -f "$C/$R8/published/results.csv" ]' \
    "--copy-files: the regular files copied, odd names too"
check '[ ! -e "$C/$R2/zero.log" ] && [ ! -e "$C/$R2/big.csv" ] && [ ! -e "$C/$R2/pipe.log" ] && [ ! -e "$C/$R2/outdir" ] && [ ! -e "$C/$R2/published/link.csv" ]' \
    "--copy-files: no link, FIFO or directory outside copied"
check '[ "$(du -sk "$T/site-copy" | cut -f1)" -lt 500 ]' "--copy-files: the site is small: $(du -sk "$T/site-copy" | cut -f1) kB"
# an unreadable file: only a user other than root cannot read it
if [ "$(id -u)" -ne 0 ]; then
    report "$T/site-u" --copy-files; rc=$?
elif command -v setpriv >/dev/null 2>&1; then
    chmod 755 "$T"; mkdir -p "$T/site-u"; chown 65534 "$T/site-u"
    (ulimit -f 20000; timeout 60 setpriv --reuid=65534 --regid=65534 --clear-groups \
        "$PY" "$ROOT/scripts/report.py" "$S" --out "$T/site-u" --copy-files) 2>"$T/rerr"; rc=$?
else
    rc=skip
fi
if [ "$rc" = skip ]; then
    skipped=$((skipped + 1))
else
    check '[ "$rc" -eq 0 ] && grep -q "secret.log" "$T/rerr" && [ -f "$T/site-u/runs/$R2/published/results.csv" ] && [ "$(nrows "$T/site-u/index.html")" -eq 5 ]' \
        "--copy-files with an unreadable file: a warning naming it, the rest copied: exit $rc, $(cat "$T/rerr")"
fi

# --- merge --out a directory another process has locked -----------------------------
R="--random 4:5 --methods tiller --tols 1e-2 --backend cpu --threads 1"
$OB run $R --shard 0/2 --out "$T/sh0" >/dev/null 2>&1 && $OB run $R --shard 1/2 --out "$T/sh1" >/dev/null 2>&1
check '[ $? -eq 0 ]' "two shards"
# hold DIR/.lock as run does (an fcntl write lock), pid written, until killed
hold() {
    mkdir -p "$1"
    "$PY" -c 'import fcntl, os, sys, time
fd = os.open(sys.argv[1] + "/.lock", os.O_RDWR | os.O_CREAT, 0o666)
fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
os.ftruncate(fd, 0); os.write(fd, b"%d\n" % os.getpid())
open(sys.argv[1] + "/.held", "w").close()
time.sleep(120)' "$1" &
    holder=$!
    n=0; while [ ! -e "$1/.held" ] && [ $n -lt 200 ]; do sleep 0.05; n=$((n + 1)); done
}
hold "$T/m"; h1=$holder
$OB run $R --out "$T/m" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "pid $holder" "$T/e.txt"' "the stand-in holds the lock as run sees it: $(cat "$T/e.txt")"
$OB merge "$T/sh0" "$T/sh1" --out "$T/m" >/dev/null 2>"$T/e.txt"
rc=$?
check '[ $rc -eq 2 ] && grep -q "$T/m/.lock" "$T/e.txt" && grep -q "pid $holder" "$T/e.txt" && [ ! -e "$T/m/results.csv" ] && [ ! -e "$T/m/meta.json" ]' \
    "merge --out a locked directory: exit 2 naming the lock and its holder, nothing written: exit $rc, $(cat "$T/e.txt")"
hold "$T/m2/sub"
$OB merge "$T/sh0" "$T/sh1" --out "$T/m2/sub/" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "\.lock" "$T/e.txt" && [ ! -e "$T/m2/sub/results.csv" ]' \
    "merge --out DIR/ (another spelling) locked: exit 2: $(cat "$T/e.txt")"
kill "$h1" "$holder"; wait "$h1" "$holder" 2>/dev/null
$OB merge "$T/sh0" "$T/sh1" --out "$T/m" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ -s "$T/m/results.csv" ]' "merge once the lock is free: $(cat "$T/e.txt")"

# --- slurm_array.sh: values passed through literally --------------------------------
# a project directory with a stand-in offbench that writes its arguments,
# one per line (NUL-free), to $ARGS_FILE
PJ="$T/pro 'j\" \$(touch $T/pwned1) \`touch $T/pwned2\`; touch $T/pwned3"
mkdir -p "$PJ/scripts" "$T/sbin"
cp "$ROOT/scripts/slurm_array.sh" "$PJ/scripts/"
cat > "$PJ/offbench" <<'EOF'
#!/bin/sh
: > "$ARGS_FILE"
for a in "$@"; do printf '%s\0' "$a" >> "$ARGS_FILE"; done
EOF
chmod +x "$PJ/offbench"
# sbatch stand-in: keeps each batch script and its arguments, prints an id
cat > "$T/sbin/sbatch" <<'EOF'
#!/bin/sh
n=$(ls "$SB_DIR" | grep -c '^job.*\.sh$')
cat > "$SB_DIR/job$n.sh"
for a in "$@"; do printf '%s\0' "$a"; done > "$SB_DIR/job$n.args"
echo "10$n"
EOF
chmod +x "$T/sbin/sbatch"
SB=$T/sb; mkdir -p "$SB"
OUTD="$T/o u't\"  \$(touch $T/pwned4) \`touch $T/pwned5\`; touch $T/pwned6 %j \$HOME
x"
P1="--param" P2="tiller.x=\$(touch $T/pwned7);\`touch $T/pwned8\` 'q\" \$HOME *" P3="--methods" P4="a b;c"
SB_DIR=$SB PATH="$T/sbin:$PATH" sh "$PJ/scripts/slurm_array.sh" 3 "$OUTD" -- "$P1" "$P2" "$P3" "$P4" >"$T/sl.out" 2>&1
rc=$?
check '[ $rc -eq 0 ] && [ -f "$SB/job0.sh" ] && [ -f "$SB/job1.sh" ] && [ -d "$OUTD/logs" ]' \
    "slurm_array.sh with odd OUT, project directory and options: submitted: exit $rc, $(cat "$T/sl.out")"
check 'sh -n "$SB/job0.sh" && sh -n "$SB/job1.sh"' "the batch scripts parse (sh -n)"
# the NUL-separated arguments file, as lines with the NULs shown as |
args() { tr '\0' '|' < "$1"; }
for k in 1 0; do
    ARGS_FILE=$T/a$k SLURM_ARRAY_TASK_ID=$k SLURM_CPUS_PER_TASK=2 sh "$SB/job0.sh" >/dev/null 2>"$T/job.err"
    check '[ "$(args "$T/a$k")" = "run|$P1|$P2|$P3|$P4|--shard|$k/3|--threads|2|--out|$OUTD/shard-$k|" ]' \
        "array task $k: offbench run gets the options and OUT literally: $(args "$T/a$k" 2>&1) $(cat "$T/job.err")"
done
mkdir -p "$OUTD/shard-1"; : > "$OUTD/shard-1/results.journal.csv"
ARGS_FILE=$T/ar SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=2 sh "$SB/job0.sh" >/dev/null 2>&1
check '[ "$(args "$T/ar")" = "run|$P1|$P2|$P3|$P4|--shard|1/3|--threads|2|--resume|$OUTD/shard-1|" ]' \
    "a requeued task with a journal resumes \$OUT/shard-K literally: $(args "$T/ar")"
mkdir -p "$OUTD/shard-0" "$OUTD/shard-2"
ARGS_FILE=$T/am sh "$SB/job1.sh" >/dev/null 2>&1
check '[ "$(args "$T/am")" = "merge|$OUTD/shard-0|$OUTD/shard-1|$OUTD/shard-2|--out|$OUTD/merged|" ]' \
    "the merge job gets the shard directories and OUT literally: $(args "$T/am")"
# has_arg FILE VALUE: VALUE is one of the NUL-separated arguments in FILE
has_arg() { "$PY" -c 'import sys; sys.exit(0 if sys.argv[2].encode() in open(sys.argv[1], "rb").read().split(b"\0") else 1)' "$1" "$2"; }
check 'has_arg "$SB/job0.args" "--output=$(printf %s "$OUTD" | sed "s/%/%%/g")/logs/shard-%a.log" && has_arg "$SB/job1.args" "--output=$(printf %s "$OUTD" | sed "s/%/%%/g")/logs/merge.log"' \
    "sbatch --output: OUT with its % doubled (Slurm's file name patterns): $(args "$SB/job0.args")"
check '[ -z "$(ls "$T" | grep pwned)" ]' "nothing in the values was run: $(ls "$T" | grep pwned | tr '\n' ' ')"
SBATCH_CPUS='2; touch x' SB_DIR=$SB PATH="$T/sbin:$PATH" sh "$PJ/scripts/slurm_array.sh" 3 "$OUTD" -- --x >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q SBATCH_CPUS "$T/e.txt"' "SBATCH_CPUS that is not a count: exit 2 naming it: $(cat "$T/e.txt")"

e2e_done
