#!/bin/sh
# End-to-end tests of scripts/nightly.sh (issue 37) on a small nightly
# configuration (NIGHTLY_METHODS ahn,zhao-rational on NIGHTLY_CURVES
# liu2002_ex1,zhao2017_septic, NIGHTLY_RANDOM 2:2026, the CPU backend), with the program under test (NIGHTLY_BIN: no build), its
# committed baseline and the machines' baselines in scratch directories:
# - exit status: 3 without a baseline, written to OUT/status as well;
# - --accept-committed and --accept take the run just made (no new run);
#   --accept refuses a failed run and one whose own rounds cannot tell a
#   change (compared with itself), and takes a loaded one whose can;
# - two nightly runs of one build on this machine: no quality regression
#   (the timing verdicts of real timings are not asserted: that is
#   scripts/nightly_power.sh's measurement, not a test's);
# - a loaded night is judged (a note says the load), not refused;
# - a planted slowdown (OFFBENCH_TEST_SLOW=zhao-rational:3: its fits done
#   three times, the test hook of `run`) against a baseline recorded on
#   this machine: a timing regression, exit 1;
# - a planted quality change (the baseline's control points lowered): a
#   quality regression, exit 1, timing unaffected;
# - methods the data cannot decide are run again, at most NIGHTLY_RERUNS
#   times, with the rounds compare asks for; still undecided: exit 3.
# The slowdown is triple the fit work of a method whose time is mostly its
# fits (thread CPU time); the load average is the test hook's (an idle
# machine) only where a timing verdict is asserted.
. "$(dirname "$0")/lib_e2e.sh"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
NS="sh $ROOT/scripts/nightly.sh"
printf '0.00 0.00 0.00 1/100 1\n' > "$T/idle"
printf '99.00 50.00 20.00 9/100 1\n' > "$T/busy"
export NIGHTLY_BIN="$OB" NIGHTLY_BASELINE="$T/committed" NIGHTLY_HISTORY=none NIGHTLY_RANDOM=2:2026 \
    NIGHTLY_METHODS=ahn,zhao-rational NIGHTLY_CURVES=liu2002_ex1,zhao2017_septic NIGHTLY_BACKEND=cpu \
    OFFBENCH_MACHINE=e2e-box
unset OFFBENCH_TEST_SLOW
# the load average the hook's (idle) unless a test says busy: a loaded night
# would run the baseline's commit beside this build (docs/nightly.md)
export OFFBENCH_LOADAVG="$T/idle"

# nightly OUT [nightly.sh options]: one night, exit status in $rc, stderr in OUT.err
nightly() {
    o=$1; shift
    $NS --out "$o" "$@" >/dev/null 2>"$o.err"
    rc=$?
}
verdict() { sed -n 3p "$1/report.md"; }

# --- no committed baseline yet: not comparable, 3, in OUT/status too ---
export NIGHTLY_BASELINES="$T/machines"
OFFBENCH_LOADAVG=$T/idle nightly "$T/n0"   # (accepted below: its load must be within the cores)
check '[ $rc -eq 3 ] && [ "$(cat "$T/n0/status")" = 3 ] && grep -q "no baseline in $T/committed/published" "$T/n0/report.md"' \
    "no baseline: exit 3, said, and in OUT/status: rc $rc, $(cat "$T/n0/status" 2>/dev/null) $(tail -n 3 "$T/n0.err")"
check 'grep -q "timings not judged: no baseline of this machine (.e2e-box." "$T/n0/report.md"' "... and no machine baseline: said"
# --accept-committed / --accept: the run just made, no new run
ls -l --time-style=+%s "$T/n0/published/results.csv" > "$T/before"
$NS --accept-committed --out "$T/n0" >/dev/null 2>"$T/err"
check '[ $? -eq 0 ] && [ -f "$T/committed/published/results.csv" ] && [ -f "$T/committed/random/meta.json" ] && ! grep -q "published: exit" "$T/err"' \
    "--accept-committed copies the run, without running: $(cat "$T/err")"
# (--accept first compares the run with itself and refuses rounds too spread
# to tell a 10 % change: how spread real rounds are depends on the machine's
# load, so the runs accepted here have each job's rounds set to their median)
steady() {  # DIR: every round of DIR/published/fits.csv set to its job's median
    awk -F, 'BEGIN {OFS = ","} NR == FNR { if (FNR > 1) { k = $1 FS $2 FS $3 FS $4 FS $5 FS $6; v[k] = v[k] " " $9 }; next }
        FNR == 1 { print; next }
        { k = $1 FS $2 FS $3 FS $4 FS $5 FS $6
          if (!(k in med)) { n = split(v[k], a, " "); for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
                                 if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
                             med[k] = a[int((n + 1) / 2)] }
          $9 = med[k]; print }' "$1/published/fits.csv" "$1/published/fits.csv" >"$T/steady.csv" &&
        mv "$T/steady.csv" "$1/published/fits.csv"
}
steady "$T/n0"
$NS --accept --out "$T/n0" >/dev/null 2>"$T/err"
mdir=$(ls -d "$T"/machines/e2e-box-* 2>/dev/null | head -n 1)
check '[ $? -eq 0 ] && [ -n "$mdir" ] && [ -f "$mdir/published/samples.csv" ] && ! grep -q "published: exit" "$T/err"' \
    "--accept makes it this machine's baseline (NAME-ID/published), without running: $mdir $(cat "$T/err")"
ls -l --time-style=+%s "$T/n0/published/results.csv" > "$T/after"
check 'cmp -s "$T/before" "$T/after"' "the accepted run is left as it was"
$NS --accept --out "$T/nothere" >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "nothing to accept" "$T/err"' "--accept without a run: 2: $(cat "$T/err")"

# --- two nightly runs of the same build on this machine: 0, never a regression ---
nightly "$T/n1"
check '[ $rc -ne 2 ] && [ "$(cat "$T/n1/status")" = $rc ]' \
    "same build again: no quality regression: $rc $(tail -n 5 "$T/n1.err")"
check 'verdict "$T/n1" | grep -q "quality: published OK: no regression (exit 0), random OK: no regression (exit 0)"' \
    "the report leads with the verdict: $(verdict "$T/n1")"
check 'grep -q "^Timing: judged: .*the methods. own fit time (--time-fits)" "$T/n1/report.md" && [ -s "$T/n1/published/fits.csv" ]' \
    "the methods' own fit time is judged: $(grep "^Timing:" "$T/n1/report.md" | head -n 1)"
check 'grep -q "^## Verdict by method" "$T/n1/report.md" && [ "$(grep -n "^## " "$T/n1/report.md" | head -n 1 | cut -d: -f2-)" = "## Verdict by method" ]' \
    "the first section is the deciding per-method table"
# each stage's wall seconds (OUT/timings.csv), and the file make docs quotes
# them from (scripts/nightly_wall.py): this is a small configuration
# (a timing verdict that a loaded machine leaves open reruns the timing:
# "run reruns/N" and "compare timing-rerunN" pairs, as many as it took)
check '[ -n "$(cut -d, -f1 "$T/n1/timings.csv" | tr "\n" "|" | grep -xE "stage\|run published\|run random\|compare published-quality\|compare random-quality\|compare timing\|(run reruns/[0-9]+\|compare timing-rerun[0-9]+\|)*report\|total\|")" ] && ! grep -v "^stage,seconds$" "$T/n1/timings.csv" | grep -qv "^[a-z0-9/ -]*,[0-9.]*$"' \
    "OUT/timings.csv: each stage in order, then the total: $(tr '\n' ' ' < "$T/n1/timings.csv")"
if [ -x /usr/bin/python3 ]; then
/usr/bin/python3 "$ROOT/scripts/nightly_wall.py" "$T/n1" --out "$T/wall.txt" 2>"$T/err"
check '[ $? -eq 0 ] && grep -qx "configuration: small" "$T/wall.txt" && grep -qx "config: --curve liu2002_ex1,zhao2017_septic, --methods ahn,zhao-rational, --random 2:2026" "$T/wall.txt" && grep -qx "published_runs: 6" "$T/wall.txt" && grep -q "^seconds_compare: [0-9.]*$" "$T/wall.txt" && grep -q "^seconds_total: [0-9.]*$" "$T/wall.txt" && ! grep -q "^seconds_build:" "$T/wall.txt"' \
    "nightly_wall.py: the night's configuration (small), its runs and stages, no build (NIGHTLY_BIN): $(cat "$T/err") $(grep -v "^#" "$T/wall.txt" | tr '\n' '|')"
else
    echo "skipped: no /usr/bin/python3 for scripts/nightly_wall.py"; skipped=$((skipped + 1))
fi

# --- a night under load: judged, the load noted; --accept by the run's own rounds ---
# (a stored baseline against a loaded night is confounded: the baseline's
# commit is run beside this build, interleaved; NIGHTLY_BASE_BIN: that
# build, here this one, so that the test builds nothing)
OFFBENCH_LOADAVG=$T/busy NIGHTLY_BASE_BIN="$OB" nightly "$T/nbusy"
check '[ $rc -ne 2 ] && grep -q "^Timing: judged" "$T/nbusy/report.md" && grep -q "load average reached 99.00 on its [0-9]* core" "$T/nbusy/report.md"' \
    "a busy night: judged, the load noted: $rc $(grep "^Timing:" "$T/nbusy/report.md" | head -n 1)"
check 'grep -q "nightly: loaded: timing against the baseline.s commit [0-9a-f]\{12\}, built and run alternately" "$T/nbusy.err" && [ -s "$T/nbusy/timing/base/fits.csv" ] && [ -s "$T/nbusy/timing/new/fits.csv" ]' \
    "... against the stored baseline's commit, interleaved: $(grep loaded: "$T/nbusy.err")"
# the baseline's commit not in this repository: not decided, 3
for f in "$T"/machines/e2e-box-*/published/meta.json; do
    cp "$f" "$f.orig"
    sed -i 's/^  "git_commit": "[0-9a-f]*",$/  "git_commit": "0000000000000000000000000000000000000000",/' "$f"
done
OFFBENCH_LOADAVG=$T/busy nightly "$T/nbusy0"
for f in "$T"/machines/e2e-box-*/published/meta.json; do mv "$f.orig" "$f"; done
check '[ $rc -eq 3 ] && grep -q "^Timing: \*\*not decided\*\*: the machine was loaded" "$T/nbusy0/report.md"' \
    "loaded, the baseline's commit not at hand: not decided, exit 3: $rc $(grep "^Timing:" "$T/nbusy0/report.md")"
# (its rounds set by hand, so that what is asserted does not depend on the load)
setrounds() {  # DIR EXPR: every round's method_ns of DIR/published/fits.csv (awk: r the round)
    awkc 'BEGIN{OFS=","} NR>1 {r=$c["round"]; $c["method_ns"]='"$2"'} {print}' "$1/published/fits.csv" >"$T/f.csv" &&
        mv "$T/f.csv" "$1/published/fits.csv"
}
setrounds "$T/nbusy" '(r % 2 ? 100000 : 300000)'
$NS --accept --out "$T/nbusy" >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "not accepted: the run.s own repetitions cannot tell a 10 % change" "$T/err" && grep -q "load average reached 99.00" "$T/err"' \
    "--accept refuses a run whose rounds spread wider than the band: $(cat "$T/err")"
setrounds "$T/nbusy" '100000 + 10 * r'
$NS --accept --baselines "$T/machines-busy" --out "$T/nbusy" >/dev/null 2>"$T/err"
check '[ $? -eq 0 ] && ls "$T"/machines-busy/e2e-box-*/published/fits.csv >/dev/null 2>&1' \
    "--accept takes a loaded night whose rounds are consistent: $(cat "$T/err")"

# --- a planted slowdown, against a baseline recorded on this (idle) machine: 1 ---
export NIGHTLY_BASELINES="$T/machines2" OFFBENCH_LOADAVG="$T/idle"
nightly "$T/i0"
steady "$T/i0"
$NS --accept --out "$T/i0" >/dev/null 2>"$T/err"
check '[ $? -eq 0 ]' "the idle night accepted: $(cat "$T/err")"
OFFBENCH_TEST_SLOW=zhao-rational:3 nightly "$T/i1"
check '[ $rc -eq 1 ] && [ "$(cat "$T/i1/status")" = 1 ] && verdict "$T/i1" | grep -q "^\*\*REGRESSION\*\* (exit 1)"' \
    "zhao-rational's fits 3x: exit 1: $rc $(verdict "$T/i1")"
check 'grep -q "^| zhao-rational | .* | slower |" "$T/i1/report.md"' "zhao-rational is slower: $(grep "^| zhao-rational |" "$T/i1/report.md" | head -n 1)"
check 'grep -q "\"test_slow\": \"zhao-rational:3\"" "$T/i1/published/meta.json"' "meta.json records the test hook"

# --- a planted quality change: the committed baseline's control points lowered: 1 ---
# (the load average the hook's, idle: a loaded night would run the baseline's
# commit beside it, and this test is about quality)
cp -R "$T/committed" "$T/committed.orig"
awkc 'BEGIN{OFS=","} NR==2{$c["ctrl_points"]=$c["ctrl_points"]-1} {print}' "$T/committed/published/results.csv" > "$T/cp.csv"
mv "$T/cp.csv" "$T/committed/published/results.csv"
export NIGHTLY_BASELINES="$T/machines"
nightly "$T/q1"
check '[ $rc -eq 1 ] && grep -q "| ctrl_points |" "$T/q1/report.md" && grep -q "^\*\*REGRESSION\*\* (exit 1)" "$T/q1/report.md"' \
    "a quality change is a regression: $rc $(verdict "$T/q1")"

# --- undecided methods run again, at most NIGHTLY_RERUNS times ---
# (this machine's baseline changed by hand: ahn's even rounds three times
# as long, so that every comparison with it is too wide to decide;
# zhao-rational's ten times as long, so that it is judged faster at once)
rm -rf "$T/committed" && mv "$T/committed.orig" "$T/committed"
awkc 'BEGIN{OFS=","} NR>1 && $c["method"]=="ahn" && $c["round"]%2==0 {$c["method_ns"]*=3}
      NR>1 && $c["method"]=="zhao-rational" {$c["method_ns"]*=10} {print}' \
    "$mdir/published/fits.csv" > "$T/s.csv" && mv "$T/s.csv" "$mdir/published/fits.csv"
# (and its measuring ten times as long: the harness's line, judged on real
# eval_ns on the CPU backend, is then faster whatever the load, and cannot
# make the night a regression)
awkc 'BEGIN{OFS=","} NR>1 {$c["eval_ns"]*=10} {print}' "$mdir/published/samples.csv" > "$T/s.csv" &&
    mv "$T/s.csv" "$mdir/published/samples.csv"
OFFBENCH_LOADAVG=$T/idle NIGHTLY_RERUNS=2 nightly "$T/r1"
check '[ $rc -eq 3 ] && [ -f "$T/r1/reruns/1/results.csv" ] && [ -f "$T/r1/reruns/2/results.csv" ] && [ ! -e "$T/r1/reruns/3" ]' \
    "an undecided method is run again twice, still undecided: exit 3: $rc $(ls "$T/r1")"
check 'grep -q "nightly: re-running the methods the data cannot decide: ahn (1 of 2, [0-9]* rounds)" "$T/r1.err" && ! awkc "\$c[\"method\"]==\"zhao-rational\"" "$T/r1/reruns/1/results.csv" | grep -q .' \
    "only the undecided method is run again: $(grep re-running "$T/r1.err")"
check 'grep -q "^| ahn | .* | cannot decide: need [0-9]* more repetitions | .* | re-run 2 |" "$T/r1/report.md"' \
    "the verdict table says which run decided: $(grep "^| ahn |" "$T/r1/report.md" | head -n 1)"
check 'grep -q "^| zhao-rational | .* | faster | .* | first run |" "$T/r1/report.md"' \
    "zhao-rational judged on the first run: $(grep "^| zhao-rational |" "$T/r1/report.md" | head -n 1)"

# --- interleaved timing (NIGHTLY_BASE_REF; the baseline build given by
# NIGHTLY_BASE_BIN: no build here): base, new, base, new, rounds joined ---
OFFBENCH_LOADAVG=$T/idle NIGHTLY_BASE_REF=HEAD NIGHTLY_BASE_BIN="$OB" NIGHTLY_FIT_REPS=4 NIGHTLY_RERUNS=0 nightly "$T/il"
check '[ $rc -ne 2 ] && grep -q "^Commit .*timing against the build of HEAD (HEAD), run alternately with this one tonight" "$T/il/report.md"' \
    "interleaved: judged against the baseline build run tonight: $rc $(grep "^Commit" "$T/il/report.md")"
check 'for d in base1 new1 base2 new2; do [ -s "$T/il/timing/$d/fits.csv" ] || exit 1; done' "interleaved: base, new, base, new: $(ls "$T/il/timing" | tr "\n" " ")"
check '[ "$(awkc "NR>1 {print \$c[\"round\"]}" "$T/il/timing/base/fits.csv" | sort -u | tr "\n" " ")" = "1 2 3 4 " ] && grep -q "\"reps\": 4," "$T/il/timing/new/meta.json"' \
    "the halves' rounds joined (1 2 3 4), and their repetitions (reps 4)"
check 'grep -q "^| ahn | .* | first run |" "$T/il/report.md" && grep -q "^| \*harness\* (eval_ns) |" "$T/il/report.md"' \
    "the per-method table and the harness line: $(grep "^| ahn" "$T/il/report.md")"
NIGHTLY_BASE_REF=no-such-ref nightly "$T/ilbad"
check '[ $rc -eq 2 ] && grep -q "NIGHTLY_BASE_REF .no-such-ref. is not a commit" "$T/ilbad.err"' "a baseline ref that is no commit: exit 2: $(tail -n 2 "$T/ilbad.err")"
sh "$ROOT/scripts/join_rounds.sh" "$T/j" "$T/il/timing/base1" "$T/n1/random" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "not a run with --time-fits" "$T/err" && [ ! -e "$T/j" ]' "join_rounds refuses a run without fits.csv: $(cat "$T/err")"

# --- the usage ---
$NS --reruns x >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "reruns" "$T/err"' "--reruns x: 2"
$NS --help > "$T/help" 2>&1
check 'grep -q -- "--accept-committed" "$T/help" && grep -q NIGHTLY_BASELINES "$T/help" && grep -q "OUT/status" "$T/help"' "--help"

e2e_done
