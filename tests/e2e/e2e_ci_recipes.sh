#!/bin/sh
# The CI recipes of scripts/ci/ (docs/nightly.md "Nightly in CI"):
# - tests/e2e/ci_recipes_check.py: github-nightly.yml and gitlab-nightly.yml
#   parse as YAML, run on a schedule, call only commands that exist (the
#   repository's scripts and make targets, tools the image has or the
#   recipe installs), run `sh scripts/nightly.sh` under a `timeout` below the
#   job's limit and pass its exit status to the job (run with stand-ins:
#   pass on 0, fail on 1 and 2, warn on 3), keep the history store across
#   runs, publish the site and cite only documents and sections that exist
#   (README.md, docs/*.md); without PyYAML
#   (Debian python3-yaml) these count as skipped;
# - scripts/ci/history_from_site.sh: a store restored from a site written
#   with report.py --copy-files (what a runner that starts empty gets from
#   the last published site) holds the same runs and files, gives the same
#   report, and runs already in the store are left alone.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
ROOT=$(cd "$(dirname "$0")/../.." && pwd)

# --- the lint -----------------------------------------------------------------
"$PY" "$ROOT/tests/e2e/ci_recipes_check.py" "$ROOT" > "$T/lint" 2>&1
line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$T/lint" | tail -n 1)
up=$(echo "$line" | sed -nE 's/^([0-9]+) passed.*/\1/p') uf=$(echo "$line" | sed -nE 's/.* ([0-9]+) failed.*/\1/p')
us=$(echo "$line" | sed -nE 's/.*, ([0-9]+) skipped.*/\1/p')
pass=$((pass + ${up:-0})); fail=$((fail + ${uf:-1})); skipped=$((skipped + ${us:-0}))
[ "${uf:-1}" -eq 0 ] || cat "$T/lint" >&2
grep -q "skipped" "$T/lint" && grep -v "passed" "$T/lint"

# without PyYAML (python -S: no dist-packages) the lint is skipped and says why
"$PY" -S "$ROOT/tests/e2e/ci_recipes_check.py" "$ROOT" > "$T/nolint" 2>&1
check '[ $? -eq 0 ] && grep -q "no PyYAML (Debian python3-yaml)" "$T/nolint" && grep -q "^0 passed, 0 failed, [1-9][0-9]* skipped$" "$T/nolint"' \
    "lint without PyYAML: skipped with the reason: $(cat "$T/nolint")"
# the lint catches what it is there for: each broken copy of a recipe fails
# with its reason (skipped with the lint when there is no PyYAML)
NBROKEN=11
if grep -q "skipped" "$T/lint"; then
    skipped=$((skipped + NBROKEN))
else
    # broken FILE SED-PROGRAM EXPECTED-TEXT WHAT
    broken() {
        rm -rf "$T/r0" && mkdir -p "$T/r0" && cp -R "$ROOT/scripts" "$ROOT/Makefile" "$T/r0/"
        sed -i "$2" "$T/r0/scripts/ci/$1"
        if cmp -s "$T/r0/scripts/ci/$1" "$ROOT/scripts/ci/$1"; then bad "broken $1: the edit '$2' changed nothing"; return; fi
        "$PY" "$ROOT/tests/e2e/ci_recipes_check.py" "$T/r0" > "$T/bl" 2>&1
        check '[ $? -ne 0 ] && grep -q -- "$3" "$T/bl"' "lint: $4: $(grep FAIL "$T/bl" | head -n 3)"
    }
    broken github-nightly.yml 's|sh scripts/nightly.sh --out out/nightly|make nightly|' "make nightly: make turns" \
        "make nightly refused"
    broken gitlab-nightly.yml 's|sh scripts/nightly.sh|sh scripts/nightlyy.sh|' "no such script" "a missing script"
    broken github-nightly.yml 's|1) echo "::error title=nightly: regression::see the report and report.md (exit 1)"; exit 1 ;;|1) echo regression ;;|' \
        "nightly exit 1: the job should fail, it would pass" "a regression that passes the job"
    broken gitlab-nightly.yml 's|    - exit $status|    - echo done|' "nightly exit 2: the job should fail, it would pass" \
        "the exit status dropped"
    broken gitlab-nightly.yml 's|^    when: always$|    when: on_success|' "cached, also after a failed night" \
        "the store not saved after a failed night"
    broken github-nightly.yml '/Save the history store/,/key:/d' "saved after the nightly" "no cache save"
    broken gitlab-nightly.yml 's|ca-certificates git gcc make python3 curl unzip|ca-certificates git gcc make python3 unzip|' \
        "curl: its package curl is not installed" "a tool the image lacks"
    broken gitlab-nightly.yml "s|    - 'echo \"nightly: exit status \$status\"'|    - echo \"nightly: exit status \$status\"|" \
        "a line of text, not" "an unquoted colon makes a mapping"
    broken github-nightly.yml 's|docs/nightly.md "Nightly in CI")|docs/nightly.md "Nightly on CI")|' \
        'cites docs/nightly.md "Nightly on CI": docs/nightly.md has no such section' "a section cited that is not there"
    broken gitlab-nightly.yml 's|timeout --preserve-status -s TERM 280m sh scripts/nightly.sh|sh scripts/nightly.sh|' \
        "below the job's time limit" "a nightly without a timeout of its own"
    broken github-nightly.yml 's|TERM 280m sh|TERM 400m sh|' "below the job's time limit" \
        "a nightly whose timeout is past the job's"
fi

# --- the store from a published site ---------------------------------------------
NIGHTLY_COMMIT_URL=none
export NIGHTLY_COMMIT_URL
FROM="sh $ROOT/scripts/ci/history_from_site.sh"
sh "$ROOT/tests/e2e/report_fixture.sh" "$OB" "$T/h" "$T/scratch" 2>"$T/err"
"$PY" "$ROOT/scripts/report.py" "$T/h" --out "$T/public" --copy-files 2>>"$T/err"
check '[ $? -eq 0 ] && [ -d "$T/public/runs" ]' "a site with the runs' files: $(cat "$T/err")"
$FROM "$T/public" "$T/r" 2>"$T/err"
check '[ $? -eq 0 ] && [ "$(ls "$T/r")" = "$(ls "$T/h")" ] && diff -r "$T/h" "$T/r" >/dev/null' \
    "history_from_site: the same runs and files: $(cat "$T/err"; diff -r "$T/h" "$T/r" | head -n 3)"
"$PY" "$ROOT/scripts/report.py" "$T/r" --out "$T/site-r" 2>/dev/null
"$PY" "$ROOT/scripts/report.py" "$T/h" --out "$T/site-h" 2>/dev/null
strip() { sed -e "s|$1|STORE|g" "$2"; }
check '[ "$(strip "$T/r" "$T/site-r/index.html" | sed "s|\.\./r/|../X/|g")" = "$(strip "$T/h" "$T/site-h/index.html" | sed "s|\.\./h/|../X/|g")" ]' \
    "history_from_site: the restored store gives the same report"
# a run already there stays as it is; the others come back
rm -rf "$T"/r/*_aaaaaaa_*
for d in "$T"/r/*_bbbbbbb_*; do echo mine > "$d/report.md"; done
$FROM "$T/public" "$T/r" 2>"$T/err"
check '[ $? -eq 0 ] && [ $(ls "$T/r" | wc -l) -eq 5 ] && [ "$(cat "$T"/r/*_bbbbbbb_*/report.md)" = mine ] && grep -q "1 runs restored" "$T/err"' \
    "history_from_site: only the missing run copied: $(cat "$T/err")"
check '[ -z "$(ls -A "$T/r" | grep "^\.")" ]' "history_from_site: no temporary directory left"
# not runs: the site's own files, a directory without run.json, a link
mkdir -p "$T/public/runs/2026-01-01T000000Z_x_y" "$T/public/runs/notarun"
echo '{}' > "$T/public/runs/notarun/run.json"
for d in "$T"/h/*_ccccccc_*; do ln -s "$d" "$T/public/runs/2026-01-02T000000Z_l_l"; done
$FROM "$T/public" "$T/r2" 2>/dev/null
check '[ $(ls "$T/r2" | wc -l) -eq 5 ] && [ ! -e "$T/r2/notarun" ] && [ ! -e "$T/r2/2026-01-01T000000Z_x_y" ] && [ ! -e "$T/r2/2026-01-02T000000Z_l_l" ]' \
    "history_from_site: only directories named and made like runs: $(ls "$T/r2" | tr '\n' ' ')"
$FROM "$T/nosite" "$T/r3" 2>"$T/err"
check '[ $? -eq 0 ] && grep -q "no runs to restore" "$T/err"' "history_from_site: no site yet: nothing to restore, exit 0"
$FROM "$T/public" 2>"$T/err"
check '[ $? -eq 2 ] && grep -q usage "$T/err"' "history_from_site: bad usage: exit 2"

e2e_done
