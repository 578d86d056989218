#!/bin/sh
# e2e_docs.sh - the documents are current and their links resolve (issue 38):
# scripts/docs.py (make docs) regenerates, in a copy of README.md, docs/,
# results/ and scripts/, every generated part: each docs file's contents,
# the command reference, the figures quoted from the committed results
# under results/, the command transcripts. Any difference from the
# committed text fails, naming the file and lines, so a figure that no
# longer matches its committed results (or a run of this program) fails
# here. A stale figure planted in the copy, or a committed result changed
# under it, must fail the check; every relative link and #anchor of
# README.md and docs/*.md must resolve, and a broken one planted in the copy
# must be caught. The README stays a front door: at most 300 lines, the
# quick start's `make test` (.ci/run runs it), every docs/ file linked.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
C=$T/tree
mkdir "$C" && cp -R README.md docs results scripts "$C"/
gen() { "$PY" "$C/scripts/docs.py" --root "$C" --offbench "$OB" "$@" >"$T/gen.out" 2>&1; }
# a file in the copy with one string replaced (python: no sed -i, no regex)
plant() {
    "$PY" -c 'import sys; p, a, b = sys.argv[1:]; t = open(p, encoding="utf-8").read()
assert a in t, (p, a); open(p, "w", encoding="utf-8").write(t.replace(a, b, 1))' "$@"
}

# --- make docs leaves the documents as they are ---
gen
check '[ $? -eq 0 ]' "scripts/docs.py runs: $(tail -n 3 "$T/gen.out" | tr '\n' ' ')"
for f in README.md docs/*.md results/TABLES.md; do
    check 'cmp -s "$f" "$C/$f"' \
        "$f is current (run make docs): $(diff "$f" "$C/$f" | head -n 8 | tr '\n' ' ')"
done
check '[ "$(ls docs)" = "$(ls "$C/docs")" ]' "make docs writes no other file under docs/"
gen --check
check '[ $? -eq 0 ] && grep -q "the documents are current" "$T/gen.out"' \
    "a second run finds nothing to change: $(tail -n 2 "$T/gen.out" | tr '\n' ' ')"
check '[ -z "$(find "$C" -name ".docs.*")" ]' "no temporary file left behind"

# --- a stale figure fails, and so does a committed result changed under it ---
cp "$C/docs/tables.md" "$T/tables.md"
plant "$C/docs/tables.md" "298, 1564 |" "298, 1576 |"
gen --check
check '[ $? -eq 1 ] && grep -q "^-| d = +1 | 13, 25, 85, 298, 1576" "$T/gen.out" && grep -q "not current: docs/tables.md" "$T/gen.out"' \
    "a stale rigorous count (1576 for 1564) fails --check, naming the file: $(tail -n 1 "$T/gen.out")"
cp "$T/tables.md" "$C/docs/tables.md"
plant "$C/results/baseline/random/meta.json" '"jobs": 33660' '"jobs": 33661'
gen --check
check '[ $? -eq 2 ] && grep -q "results/baseline/random: meta.json says 33661 jobs, results.csv has 33660 rows" "$T/gen.out"' \
    "a baseline whose meta.json and results.csv disagree is refused: $(tail -n 1 "$T/gen.out")"
plant "$C/results/baseline/random/meta.json" '"jobs": 33661' '"jobs": 33660'
plant "$C/results/baseline/published/results.csv" "liu2002_ex1,1,tiller,hausdorff,mid,1e-05,1564," "liu2002_ex1,1,tiller,hausdorff,mid,1e-05,1565,"
gen --check
check '[ $? -eq 1 ] && grep -q "^+| d = +1 | 13, 25, 85, 298, 1565 |" "$T/gen.out"' \
    "the rigorous counts follow the committed baseline: $(grep '^+| d = +1' "$T/gen.out")"
plant "$C/results/tables/tables.csv" "ahn2023,2,liu2002_ex2,0.5,1e-2,lee,M2,paper,92,85,0.9239130434782609,close" \
    "ahn2023,2,liu2002_ex2,0.5,1e-2,lee,M2,paper,92,92,1,match"
gen --check
check '[ $? -eq 1 ] && grep -q "^+| Ahn 2023, Table 2 .* | 78, 92, 120, 176, 302 | 78, 92, 120, 176, 302 |$" "$T/gen.out"' \
    "a changed results/tables/tables.csv changes the published figures (no longer 4 of 5): $(grep '^+| Ahn 2023, Table 2' "$T/gen.out")"
cp results/tables/tables.csv "$C/results/tables/tables.csv"
plant "$C/results/docs/occt/occt.csv" ",0.009792204537153506," ",1e-09,"
gen --check
check '[ $? -eq 1 ] && grep -q "^+| liu2002_ex1, +1 | 1e-2 | 15 · 8.61e-3 | 1.00e-9 \*\*fails\*\* |" "$T/gen.out" && grep -q "^+- OCCT.s own MaxError held for 17 of the 18" "$T/gen.out"' \
    "the CAD example's table follows results/docs/occt: a wrong OCCT claim planted there is flagged: $(grep '^+| liu2002_ex1, +1 | 1e-2' "$T/gen.out")"
cp results/docs/occt/occt.csv "$C/results/docs/occt/occt.csv"

# the nightly's wall time follows results/baseline/nightly_wall.txt (make nightly-wall)
W=$C/results/baseline/nightly_wall.txt
sed -i 's/^seconds_total: .*/seconds_total: 12345.6/' "$W"
gen --check
check '[ $? -eq 1 ] && grep -q "^+| \*\*total\*\* (before the history store and the site) |  | \*\*12345.6\*\* |$" "$T/gen.out"' \
    "a changed nightly_wall.txt changes docs/nightly.md's table: $(grep "total" "$T/gen.out" | head -n 2)"
sed -i '/^seconds_total: /d' "$W"
gen --check
check '[ $? -eq 2 ] && grep -q "nightly_wall.txt: no .seconds_total." "$T/gen.out"' \
    "a nightly_wall.txt without its total is refused: $(tail -n 1 "$T/gen.out")"
cp results/baseline/nightly_wall.txt "$W"

# --- markers ---
cp "$T/tables.md" "$C/docs/tables.md"
printf '\n<!-- generated by make docs: no-such-part -->x<!-- end no-such-part -->\n' >> "$C/docs/plots.md"
gen --check
check '[ $? -eq 2 ] && grep -q "unknown generated part .no-such-part." "$T/gen.out"' \
    "an unknown generated part is refused: $(tail -n 1 "$T/gen.out")"
cp docs/plots.md "$C/docs/plots.md"
printf '\n<!-- generated by make docs: toc -->\n' >> "$C/docs/plots.md"
gen --check
check '[ $? -eq 2 ] && grep -q "docs/plots.md: <!-- generated by make docs: toc --> without its <!-- end toc -->" "$T/gen.out"' \
    "a part without its end marker is refused: $(tail -n 1 "$T/gen.out")"
cp docs/plots.md "$C/docs/plots.md"

# --- links ---
"$PY" scripts/docs.py --links >"$T/links.out" 2>&1
check '[ $? -eq 0 ]' "every relative link of README.md and docs/*.md resolves: $(grep 'broken link' "$T/links.out" | head -n 5 | tr '\n' ' ')"
printf '\n[a](no-such-file.md) [b](methods.md#no-such-heading) [c](#joints) ![d](../results/report.png)\n' >> "$C/docs/plots.md"
printf '\n`[e](not-a-link.md)`\n\n```\n[f](nor-this.md)\n```\n' >> "$C/docs/plots.md"
"$PY" "$C/scripts/docs.py" --root "$C" --links >"$T/links.out" 2>&1
check '[ $? -eq 1 ] && grep -q "docs/plots.md:[0-9]*: no-such-file.md: no such file" "$T/links.out" && grep -q "methods.md#no-such-heading: no heading with anchor" "$T/links.out" && grep -q "docs/plots.md:[0-9]*: #joints: no heading" "$T/links.out"' \
    "broken links are named (a file, an anchor elsewhere, an anchor here): $(cat "$T/links.out" | tr '\n' ' ')"
check '[ "$(grep -c "broken link: docs/plots.md:" "$T/links.out")" -eq 3 ]' \
    "links in code, and links that resolve, are not reported: $(grep "broken link: docs/plots.md:" "$T/links.out" | tr '\n' ' ')"

# --- the README is a front door; every docs file has its contents ---
check '[ "$(wc -l < README.md)" -le 300 ]' "README.md has at most 300 lines: $(wc -l < README.md)"
check 'grep -qx "make run" README.md && grep -qx "make test" README.md && grep -q "N passed, N failed" README.md' \
    "the quick start keeps make run, make test and its last line"
for f in docs/*.md; do
    check 'grep -q "]($f)" README.md' "README.md links $f"
    check '[ "$(sed -n 1p "$f" | cut -c1-2)" = "# " ] && [ "$(sed -n 3p "$f")" = "<!-- generated by make docs: toc -->" ]' \
        "$f: a title, then its contents"
done
e2e_done
