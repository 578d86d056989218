#!/bin/sh
# End-to-end tests of the nightly history (docs/nightly.md "Nightly history and
# report"):
# - scripts/nightly_history.sh record: a nightly output copied into
#   STORE/STAMP_COMMIT_HOST/ with run.json (status, stage), a failed run
#   recorded, a build failure recording only build.log, two runs in the same
#   second kept apart; prune --keep / --keep-days, never the newest run nor a
#   directory that is not a run; bad values: exit 2;
# - scripts/nightly.sh: bad history options exit 2 before building;
# - the step rule and the reading of results.csv by column name
#   (tests/e2e/report_steps_test.py);
# - scripts/report.py on a synthetic store (tests/e2e/report_fixture.sh, five
#   nights of real runs edited to hold one quality and one time step): every
#   run in the page, exactly the two steps marked (index and method pages),
#   the failed run shown, relative links that resolve, no external resource;
#   a broken results.csv is a warning naming FILE:LINE, not a lost report;
#   sparklines with their min and max and hover values;
# - commit links: NIGHTLY_COMMIT_URL, the checkout's remote (credentials
#   left out), a bad template refused;
# - the first section on first nights (tests/e2e/report_verdict_fixture.sh)
#   ending 0, 1, 2 (at compare and at the build), 3, and with compare's JSON:
#   the verdict is run.json's exit status, first on the page, the
#   per-method tables HTML tables (tests/e2e/report_verdict_check.py); a
#   report.md that disagrees with run.json is said, not shown as the verdict;
# - the page in headless Chromium (Debian chromium-headless-shell or
#   chromium; skipped and counted so without one): the rendered DOM holds the
#   runs and the steps, the inline script ran, no console message (checked
#   to catch an error injected on purpose), and for each exit status 0-3 the
#   verdict shown is the exit code.  OB_CHROMIUM=PATH picks the
#   browser, OB_CHROMIUM=none skips these checks.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
HIST="sh $ROOT/scripts/nightly_history.sh"
REPORT="$PY $ROOT/scripts/report.py"
VC="$PY $ROOT/tests/e2e/report_verdict_check.py"
# no commit links unless a check asks for them (the checkout's remote would
# give some)
NIGHTLY_COMMIT_URL=none
export NIGHTLY_COMMIT_URL

# --- record ------------------------------------------------------------------
O=$T/out
mkdir -p "$O/published" "$O/random"
for s in published random; do
    echo "curve,d,method" > "$O/$s/results.csv"; echo "{}" > "$O/$s/meta.json"
done
echo "rep" > "$O/published/samples.csv"
echo "# report" > "$O/report.md"; echo "err" > "$O/compare-random.err"; echo "log" > "$O/published.log"
echo "{}" > "$O/compare-random.json"
echo "build" > "$O/build.log"; echo "junk" > "$O/published/other.txt"
d=$($HIST record --out "$O" --history "$T/h" --status 1 --commit 0123456789ab --time 1795000000 2>"$T/err")
check '[ $? -eq 0 ] && [ "$d" = "$T/h/2026-11-18T110640Z_0123456_$(printf %s "$(hostname)" | tr -c "A-Za-z0-9.-" - | cut -c1-40)" ]' \
    "record: prints STORE/STAMP_COMMIT_HOST: '$d' $(cat "$T/err")"
for f in published/results.csv published/samples.csv published/meta.json random/results.csv random/meta.json \
         report.md compare-random.err compare-random.json published.log build.log run.json; do
    check '[ -f "$d/$f" ]' "record: $f copied"
done
check '[ ! -e "$d/published/other.txt" ] && [ ! -e "$d/random/samples.csv" ]' "record: only the run's files"
check 'grep -q "\"status\": 1," "$d/run.json" && grep -q "\"status_text\": \"regression\"" "$d/run.json" \
       && grep -q "\"commit\": \"0123456789ab\"" "$d/run.json" && grep -q "\"date\": \"2026-11-18T11:06:40Z\"" "$d/run.json"' \
    "run.json: status, commit, date"
check '$PY -c "import json,sys; json.load(open(sys.argv[1]))" "$d/run.json"' "run.json is JSON"
d2=$($HIST record --out "$O" --history "$T/h" --status 2 --stage "run random" --commit 0123456789ab --time 1795000000)
check '[ "$d2" = "$d-2" ] && [ -d "$d" ] && grep -q "\"stage\": \"run random\"" "$d2/run.json"' \
    "record: a second run in the same second beside the first, a failed one recorded: '$d2'"
d3=$($HIST record --out "$O" --history "$T/h" --status 2 --stage build --commit abc --time 1795000100)
check '[ -f "$d3/build.log" ] && [ ! -e "$d3/report.md" ] && [ ! -e "$d3/published" ]' \
    "record --stage build: only build.log (the rest is last night's)"
check '[ -z "$(ls -A "$T/h" | grep "^\.")" ]' "record: no temporary directory left"
d4=$($HIST record --out "$O" --history "$T/h" --status 0 --commit abc --dirty true --time 1795000200)
check 'grep -q "\"dirty\": true," "$d4/run.json"' "record --dirty true: in run.json"
$HIST record --out "$O" --history "$T/h" --status 0 --commit abc --dirty maybe >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q -- "--dirty" "$T/err"' "record --dirty maybe: exit 2"
$HIST record --out "$O" --history "$T/h" --status x >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q -- "--status" "$T/err"' "record --status x: exit 2"
$HIST record --history "$T/h" --status 0 >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q -- "--out" "$T/err"' "record without --out: exit 2"

# --- prune -------------------------------------------------------------------
P=$T/p
now=$(date +%s)
for days in 30 20 10 5 1; do
    $HIST record --out "$O" --history "$P" --status 0 --commit c$days --time $((now - days * 86400)) >/dev/null
done
mkdir -p "$P/site" "$P/2020-01-01T000000Z_x_y"   # not runs: no run.json
nruns() { ls "$P" | grep -c '^20.*Z_c'; }
$HIST prune --history "$P" 2>/dev/null
check '[ $(nruns) -eq 5 ]' "prune without limits keeps all"
$HIST prune --history "$P" --keep-days 15 2>"$T/err"
check '[ $(nruns) -eq 3 ] && ! ls "$P" | grep -q "_c30_\|_c20_" && grep -q "pruned" "$T/err"' \
    "--keep-days 15: the runs of 20 and 30 days ago gone: $(ls "$P" | tr '\n' ' ')"
$HIST prune --history "$P" --keep 2 2>/dev/null
check '[ $(nruns) -eq 2 ] && ls "$P" | grep -q "_c1_" && ls "$P" | grep -q "_c5_"' "--keep 2: the 2 newest left"
$HIST prune --history "$P" --keep-days 0 --keep 1 2>/dev/null
$HIST prune --history "$P" --keep-days 1 2>/dev/null
check '[ $(nruns) -eq 1 ] && ls "$P" | grep -q "_c1_"' "the newest run is never pruned, even when too old"
check '[ -d "$P/site" ] && [ -d "$P/2020-01-01T000000Z_x_y" ]' "prune leaves what is not a run alone"
$HIST prune --history "$P" --keep x >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q -- "--keep" "$T/err"' "prune --keep x: exit 2"
sh "$ROOT/scripts/nightly.sh" --keep-days -1 --out "$T/nn" >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "keep" "$T/err" && [ ! -e "$T/nn.build.log" ]' "nightly.sh --keep-days -1: exit 2 before building"
sh "$ROOT/scripts/nightly.sh" --out "$T/nn" --history "$T/nn/h" >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "inside the output directory" "$T/err" && [ ! -e "$T/nn.build.log" ]' \
    "nightly.sh: a store inside --out (removed each night) refused"
sh "$ROOT/scripts/nightly.sh" --history >/dev/null 2>"$T/err"
check '[ $? -eq 2 ] && grep -q -- "--history needs" "$T/err"' "nightly.sh --history without a value: exit 2"
sh "$ROOT/scripts/nightly.sh" --help > "$T/help" 2>&1
check 'grep -q -- "--keep-days D" "$T/help" && grep -q NIGHTLY_HISTORY "$T/help"' "nightly.sh --help documents the history"

# --- the step rule, unit checks -------------------------------------------------
"$PY" "$ROOT/tests/e2e/report_steps_test.py" > "$T/unit" 2>&1
line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$T/unit" | tail -n 1)
up=$(echo "$line" | sed -nE 's/^([0-9]+) passed.*/\1/p') uf=$(echo "$line" | sed -nE 's/.* ([0-9]+) failed.*/\1/p')
pass=$((pass + ${up:-0})); fail=$((fail + ${uf:-1}))
[ "${uf:-1}" -eq 0 ] || cat "$T/unit" >&2
# the first section (verdict, compare's tables), commit links, sparklines
"$PY" "$ROOT/tests/e2e/report_latest_test.py" > "$T/unit" 2>&1
line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$T/unit" | tail -n 1)
up=$(echo "$line" | sed -nE 's/^([0-9]+) passed.*/\1/p') uf=$(echo "$line" | sed -nE 's/.* ([0-9]+) failed.*/\1/p')
pass=$((pass + ${up:-0})); fail=$((fail + ${uf:-1}))
[ "${uf:-1}" -eq 0 ] || cat "$T/unit" >&2

# --- report.py on the synthetic store -------------------------------------------
sh "$ROOT/tests/e2e/report_fixture.sh" "$OB" "$T/s" "$T/scratch" 2>"$T/err"
check '[ $? -eq 0 ] && [ $(ls "$T/s" | wc -l) -eq 5 ]' "the synthetic store: 5 runs: $(cat "$T/err")"
mkdir -p "$T/s/site-old"
$REPORT "$T/s" --out "$T/site" 2>"$T/err"
check '[ $? -eq 0 ] && [ -s "$T/site/index.html" ] && [ -s "$T/site/method-cobb.html" ] && [ -s "$T/site/method-tiller.html" ]' \
    "report.py: index and method pages: $(cat "$T/err")"
I=$T/site/index.html
check '[ "$(grep -o "<tr class=\"run[ \"][^>]*data-commit=\"[a-e]\{7\}\"" "$I" | wc -l)" -eq 5 ]' "index: 5 run rows"
# the steps: exactly these three, as "commit set method kind" (the
# harness's line sums every row's eval_ns: tiller's tripled moves it too)
steps() { grep -o '<tr class="step"[^>]*>' "$1" | sed -E 's/.*data-commit="([^"]*)" data-set="([^"]*)" data-method="([^"]*)" data-kind="([^"]*)".*/\1 \2 \3 \4/' | sort | tr '\n' ';'; }
check '[ "$(steps "$I")" = "ddddddd published cobb quality;eeeeeee published (harness) time;eeeeeee published tiller time;" ]' \
    "index: the steps are cobb's quality, tiller's time and the harness's: '$(steps "$I")'"
check 'grep -q "<g class=\"step\" data-run=\"[^\"]*_ddddddd_[^\"]*\" data-commit=\"ddddddd\" data-kind=\"quality\"" "$T/site/method-cobb.html"' \
    "method-cobb.html: the quality step in its chart"
qd=$(sed -n 's|.*<td class="step" data-kind="quality">ctrl \([0-9]*\) -&gt; \([0-9]*\)</td>.*|\1 \2|p' "$T/site/method-cobb.html")
check '[ -n "$qd" ] && [ $(echo $qd | awk "{print \$2 - \$1}") -eq 5 ]' \
    "method-cobb.html: the quality step (ctrl +5) in its table: '$qd'"
check '[ $(grep -c "<td class=\"step\"" "$T/site/method-cobb.html") -eq 1 ] && [ $(grep -c "<td class=\"step\" data-kind=\"time\"" "$T/site/method-tiller.html") -eq 1 ] && [ $(grep -c "<td class=\"step\"" "$T/site/method-tiller.html") -eq 1 ]' \
    "method pages: one step cell each"
check 'grep -q "<tr class=\"run failed\"[^>]*data-commit=\"ccccccc\" data-status=\"2\"" "$I"' "index: the failed run shown with status 2"
check 'grep -q "id=\"step-rule\"" "$I" && grep -q "10 %" "$I" && grep -q "<pre id=\"latest-compare\"># offbench nightly (synthetic)" "$I"' \
    "index: the step rule and the latest compare report"
check '! grep -q -i "src=\"http\|href=\"http\|@import\|url(http" "$T"/site/*.html' "no external resource"
$VC "$I" "$T/s/$(ls "$T/s" | grep _eeeeeee_)/run.json" --methods tiller,cobb > "$T/vc" 2>&1
check '[ $? -eq 0 ] && ! grep -q "mismatch" "$I"' "index: the latest run's verdict (status 0) and tables are the first section: $(cat "$T/vc")"
check '[ $(grep -o "<svg[^>]*class=\"chart small\"" "$I" | wc -l) -eq 12 ] && [ $(grep -o "<text class=\"min[ \"]" "$I" | wc -l) -eq 12 ] && [ $(grep -o "<text class=\"[a-z ]*max\"" "$I" | wc -l) -eq 12 ] && grep -q "<text class=\"min max\"[^>]*>[0-9][0-9]*<" "$I"' \
    "index: every sparkline shows its min and max (one label when flat)"
check 'grep -q "<rect class=\"hit\"[^>]*><title>eeeeeee 2026-[^<]*: [0-9.]* ms" "$I"' "index: the sparklines' points have hover values"
bad_links=""
for h in $(grep -o 'href="[^"#:]*"' "$I" | sed 's/href="//; s/"$//'); do
    [ -e "$T/site/$h" ] || bad_links="$bad_links $h"
done
check '[ -z "$bad_links" ] && grep -q "href=\"../s/[^\"]*_eeeeeee_[^\"]*/published/results.csv\"" "$I"' \
    "index: relative links to the run files resolve:$bad_links"
$REPORT "$T/s" --out "$T/sitec" --copy-files 2>/dev/null
check '[ -f "$T/sitec/runs/$(ls "$T/s" | grep _eeeeeee_)/published/results.csv" ] && grep -q "href=\"runs/" "$T/sitec/index.html"' \
    "--copy-files: the files in the site"
# a broken run: a warning naming FILE:LINE, the other runs reported
b=$(ls "$T/s" | grep _bbbbbbb_)
sed -i '3s/,ok,/,ok,/; 3s/^\([^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,\)[0-9]*/\1x7/' "$T/s/$b/published/results.csv"
$REPORT "$T/s" --out "$T/site2" 2>"$T/err"
check '[ $? -eq 0 ] && grep -q "$b/published/results.csv:3: ctrl_points is .x7." "$T/err" && grep -q "class=\"warn\"" "$T/site2/index.html"' \
    "a broken results.csv: warning with FILE:LINE, shown on the page: $(cat "$T/err")"
check '[ "$(grep -o "<tr class=\"run[ \"][^>]*data-commit" "$T/site2/index.html" | wc -l)" -eq 5 ]' "a broken run set leaves the other runs"
$REPORT "$T/nope" --out "$T/site3" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q "nope: no such directory" "$T/err"' "report.py on a missing store: exit 2"
$REPORT "$T/s" 2>/dev/null
check '[ $? -eq 2 ]' "report.py without --out: exit 2"

# --- commit links ----------------------------------------------------------------
NIGHTLY_COMMIT_URL='https://example.org/c/{sha}' $REPORT "$T/s" --out "$T/sitel" 2>"$T/err"
L=$T/sitel/index.html
check '[ $? -eq 0 ] && [ $(grep -o "<tr class=\"run[^>]*>.\{0,400\}<a class=\"commit\" href=\"https://example.org/c/[a-e]\{7\}[0-9]\{4\}\"" "$L" | wc -l) -eq 5 ]' \
    "NIGHTLY_COMMIT_URL: a link per run row: $(cat "$T/err")"
check 'grep -q "<tr class=\"step\"[^>]*data-commit=\"ddddddd\".\{0,200\}<a class=\"commit\" href=\"https://example.org/c/ddddddd4444\"" "$L" && grep -q "<a class=\"commit\" href=\"https://example.org/c/eeeeeee5555\"" "$T/sitel/method-tiller.html"' \
    "NIGHTLY_COMMIT_URL: the step table and the method pages link too"
check '! grep -q -i "src=\"http\|@import\|url(http" "$L" && [ -z "$(grep -o "<a [^>]*href=\"http[^>]*>" "$L" | grep -v "^<a class=\"commit\"")" ]' \
    "with commit links: still no external resource, only commit links leave the page"
NIGHTLY_COMMIT_URL='https://example.org/c/' $REPORT "$T/s" --out "$T/sitel2" 2>"$T/err"
check '[ $? -eq 0 ] && grep -q "NIGHTLY_COMMIT_URL.*{sha}" "$T/err" && ! grep -q "class=\"commit\"" "$T/sitel2/index.html"' \
    "NIGHTLY_COMMIT_URL without {sha}: said, no links: $(cat "$T/err")"
# from the checkout's remote (git@ form, GitLab): a copy of the scripts in
# a repository of its own
mkdir -p "$T/repo/scripts" && cp "$ROOT"/scripts/report*.py "$T/repo/scripts/"
git -C "$T/repo" init -q 2>/dev/null && git -C "$T/repo" remote add origin git@gitlab.com:group/sub/offbench.git
env -u NIGHTLY_COMMIT_URL "$PY" "$T/repo/scripts/report.py" "$T/s" --out "$T/sitel3" 2>"$T/err"
check '[ $? -eq 0 ] && grep -q "<a class=\"commit\" href=\"https://gitlab.com/group/sub/offbench/-/commit/eeeeeee5555\"" "$T/sitel3/index.html"' \
    "commit links from the remote (git@gitlab.com:...): $(cat "$T/err")"
git -C "$T/repo" remote set-url origin "https://gitlab-ci-token:SECRET123@gitlab.example.org/g/p.git"
env -u NIGHTLY_COMMIT_URL "$PY" "$T/repo/scripts/report.py" "$T/s" --out "$T/sitel4" 2>"$T/err"
check 'grep -q "href=\"https://gitlab.example.org/g/p/-/commit/eeeeeee5555\"" "$T/sitel4/index.html" && ! grep -rq SECRET123 "$T/sitel4"' \
    "a remote with credentials: linked without them"

# --- the verdict: the first thing on the page, the nightly's exit status ---------
# first nights (one run: no steps) ending 0, 1, 2 (compare's error, and the
# build), 3; one with compare's JSON beside report.md
VARIANTS="0 1 2 3 2-build 1-json"
for v in $VARIANTS; do
    st=${v%%-*} stage=compare extra=
    case $v in *-build) stage=build ;; *-json) extra=--json ;; esac
    sh "$ROOT/tests/e2e/report_verdict_fixture.sh" "$OB" "$T/v$v" "$T/vscratch" "$st" "$stage" $extra 2>"$T/err" \
        && $REPORT "$T/v$v" --out "$T/vsite$v" 2>>"$T/err"
    check '[ $? -eq 0 ] && [ -s "$T/vsite$v/index.html" ]' "first night, exit $v: store and report: $(cat "$T/err")"
    case $v in
        1|1-json) want="--methods tiller,cobb --regressed cobb" ;;
        2-build) want="" ;;
        *) want="--methods tiller,cobb" ;;
    esac
    # shellcheck disable=SC2086
    $VC "$T/vsite$v/index.html" "$(ls -d "$T/v$v"/2*)/run.json" $want > "$T/vc" 2>&1
    check '[ $? -eq 0 ]' "first night, exit $v: the verdict is run.json's, first on the page: $(cat "$T/vc")"
done
check 'grep -q "id=\"no-steps\"[^>]*>[^<]*baseline" "$T/vsite1/index.html"' "first night: 'no steps' points to the baseline comparison"
check 'grep -q "no column [^ ]*method[^ ]* in the header" "$T/vsite2/index.html"' "exit 2 at compare: compare's message shown"
check 'grep -q "seed 7 vs 99" "$T/vsite3/index.html"' "exit 3: the reasons shown"
# the baseline the run was compared with (NIGHTLY_BASELINE), not results/baseline/
check 'grep -qF "\"baseline\": \"$T/vscratch/base\"" "$(ls -d "$T/v1"/2*)/run.json" && grep -qF "committed baseline ($T/vscratch/base/)" "$T/vsite1/index.html" && ! grep -q "results/baseline" "$T/vsite1/index.html"' \
    "the page names the baseline the run was compared with: $(grep -o "committed baseline ([^)]*)" "$T/vsite1/index.html")"
check 'grep -q "class=\"stage\"[^>]*>[^<]*<[^>]*>build<" "$T/vsite2-build/index.html" && ! grep -q "compare-methods" "$T/vsite2-build/index.html" && grep -q "href=\"[^\"]*build.log\"" "$T/vsite2-build/index.html"' \
    "exit 2 at the build: the stage said, build.log linked, no table"
check 'grep -q "<table class=\"compare-methods\" data-set=\"published\" data-source=\"compare-published.json\"" "$T/vsite1-json/index.html" && grep -q "<table class=\"compare-methods\" data-set=\"published\" data-source=\"report.md\"" "$T/vsite1/index.html"' \
    "compare-SET.json preferred to report.md when the run has it"
# run.json rules: a report.md that says otherwise is a warning, not the verdict
cp -R "$T/v1" "$T/vx"
rj=$(ls -d "$T/vx"/2*)/run.json
sed -i 's/"status": 1,/"status": 0,/; s/"status_text": "regression"/"status_text": "no regression"/' "$rj"
$REPORT "$T/vx" --out "$T/vsitex" 2>/dev/null
$VC "$T/vsitex/index.html" "$rj" > "$T/vc" 2>&1
check '[ $? -eq 0 ] && grep -q "class=\"warn mismatch\"" "$T/vsitex/index.html"' \
    "run.json's status 0 against report.md's regression: the verdict is run.json's, the disagreement said: $(cat "$T/vc")"

# --- the page in headless Chromium ----------------------------------------------
NBROWSER=12
CHROME=${OB_CHROMIUM:-$(command -v chromium-headless-shell || command -v chromium || true)}
if [ -z "$CHROME" ] || [ "$CHROME" = none ]; then
    echo "e2e_report: no chromium-headless-shell or chromium (OB_DEPS_BROWSER=1 make deps): browser checks skipped"
    skipped=$((skipped + NBROWSER))
else
    # render FILE NAME: the DOM after the scripts in $T/NAME.dom, the log in $T/NAME.log
    render() {
        timeout 90 "$CHROME" --headless --no-sandbox --disable-gpu --user-data-dir="$T/ud-$2" \
            --enable-logging=stderr --v=0 --dump-dom "file://$1" >"$T/$2.dom" 2>"$T/$2.log"
    }
    console() { grep -E "CONSOLE|Uncaught" "$T/$1.log"; }
    render "$I" index
    check '[ $? -eq 0 ] && grep -q "data-ready=\"yes\"" "$T/index.dom"' "chromium: the page's script ran"
    check '[ -z "$(console index)" ]' "chromium: console messages: $(console index | head -n 3)"
    check '[ "$(grep -o "<tr class=\"run[ \"][^>]*data-commit=\"[a-e]\{7\}\"" "$T/index.dom" | wc -l)" -eq 5 ] && [ "$(steps "$T/index.dom")" = "ddddddd published cobb quality;eeeeeee published (harness) time;eeeeeee published tiller time;" ]' \
        "chromium: the rendered index holds the 5 runs and the 3 steps: '$(steps "$T/index.dom")'"
    render "$T/site/method-tiller.html" tiller
    check '[ -z "$(console tiller)" ] && grep -q "<g class=\"step\"[^>]*data-commit=\"eeeeeee\" data-kind=\"time\"" "$T/tiller.dom"' \
        "chromium: method-tiller.html rendered with its time step, no console message"
    # the detection itself: an error injected on purpose must be seen
    sed 's|</body>|<script>no_such_function();</script></body>|' "$I" > "$T/site/broken.html"
    render "$T/site/broken.html" broken
    check 'console broken | grep -q "no_such_function"' "chromium: an injected script error is caught"
    # the verdict shown equals the exit code, as rendered, for every exit status
    for v in $VARIANTS; do
        render "$T/vsite$v/index.html" "v$v"
        case $v in 2-build) want="" ;; 1|1-json) want="--methods tiller,cobb --regressed cobb" ;; *) want="--methods tiller,cobb" ;; esac
        # shellcheck disable=SC2086
        $VC "$T/v$v.dom" "$(ls -d "$T/v$v"/2*)/run.json" $want > "$T/vc" 2>&1
        check '[ $? -eq 0 ] && [ -z "$(console "v$v")" ]' "chromium: first night, exit $v: the verdict shown is the exit code: $(cat "$T/vc") $(console "v$v" | head -n 2)"
    done
    timeout 90 "$CHROME" --headless --no-sandbox --disable-gpu --user-data-dir="$T/ud-shot" --hide-scrollbars \
        --window-size=1000,800 --screenshot="$T/shot.png" "file://$I" >/dev/null 2>&1
    check '[ "$(head -c 8 "$T/shot.png" | od -An -tx1 | tr -d " \n")" = "89504e470d0a1a0a" ]' "chromium: a screenshot of the page"
fi

e2e_done
