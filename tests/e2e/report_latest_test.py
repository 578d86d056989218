#!/usr/bin/python3
"""report_latest_test.py - unit checks of the nightly report's first section
and links (scripts/report_compare.py: the verdict, compare's markdown tables
read generally and its JSON; scripts/report_commits.py: commit links from
the remote or NIGHTLY_COMMIT_URL; scripts/report_svg.py: the sparklines'
value labels and hover titles); run by tests/e2e/e2e_report.sh.  Prints
"N passed, N failed"."""

import json
import os
import re
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the checkout
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import report_commits  # noqa: E402
import report_compare  # noqa: E402
import report_svg  # noqa: E402

passed = failed = 0


def check(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL: " + what, file=sys.stderr)


# compare's markdown output as scripts/nightly.sh stitches it into report.md
COMPARE_1 = """# offbench compare

- BASE: `b/results.csv` (8 rows; commit 3c4ec9cef560, 2026-12-04T23:05:22Z)
- NEW: `n/results.csv` (8 rows; commit 3c4ec9cef560, 2026-12-04T23:05:22Z)

**REGRESSION** (exit 1): 8 joined rows; 1 regressions (quality 1, timing 0, missing rows 0); 0 improvements.

## Context

- timings: not compared (--no-timing)

## Regressions: quality and timing (1)

| curve | d | method | metric | split | tol | field | base | new | new/base | p | interval |
|---|---:|---|---|---|---:|---|---:|---:|---:|---:|---:|
| liu2002_ex1 | 1 | tiller | hausdorff | mid | 0.01 | ctrl_points | 25 | 27 | 1.08 | - | - |

## Per method (geometric mean of new/base over the joined rows)

| method | rows | ctrl_points | max_err | time | p | time interval | regressions | improvements | verdict |
|---|---:|---:|---:|---:|---:|---:|---:|---:|---|
| tiller | 4 | 1.019 | 1 | - | - | - | 1 | 0 | regression |
| ahn | 4 | 1 | 1 | - | - | - | 0 | 0 | same |
"""
COMPARE_3 = """# offbench compare

**NOT COMPARABLE** (exit 3)

## Context

- not comparable: seed 7 vs 99
- not comparable: samples_per_segment 256 vs 128
"""
NIGHTLY = ("# offbench nightly, 2026-12-02T03:12:05Z\n\nCommit abc; random set 250:2026.\n\n## published\n\n"
           + COMPARE_1 + "\n## random\n\n" + COMPARE_3 + "offbench: not comparable: seed 7 vs 99\n\n"
           "Exit status 3 (0 no regression, 1 regression, 2 error, 3 not comparable); 12 s in all.\n")


def verdict_checks():
    want = {0: ("ok", "no regression"), 1: ("regression", "regression"), 2: ("error", "error"),
            3: ("not-comparable", "not comparable")}
    for st, v in want.items():
        check(report_compare.verdict_of(st) == v, "verdict_of(%d): %s" % (st, report_compare.verdict_of(st)))
    check(report_compare.verdict_of(7)[0] == "unknown" and "7" in report_compare.verdict_of(7)[1],
          "an unknown status is said as such: %s" % (report_compare.verdict_of(7),))
    check(report_compare.verdict_of(None)[0] == "unknown", "no status: unknown")
    check(report_compare.verdict_of(True)[0] == "unknown", "a JSON true is no status")
    check(report_compare.worst([0, 1, 3]) == 3 and report_compare.worst([1, 2, 3]) == 2
          and report_compare.worst([0, 1]) == 1 and report_compare.worst([]) is None,
          "worst: 2 > 3 > 1 > 0, as nightly.sh")


def table_checks():
    t = report_compare.md_tables(COMPARE_1)
    check(len(t) == 2, "two tables in compare's report: %d" % len(t))
    pm = t[1]
    check(pm.header[0] == "method" and pm.header[-1] == "verdict" and len(pm.rows) == 2
          and pm.rows[0][0] == "tiller" and pm.rows[0][-1] == "regression", "the per-method table: %s" % vars(pm))
    check(pm.align[1] == "right" and pm.align[0] == "", "alignment from the delimiter row: %s" % pm.align)
    # markdown tables in general: no outer pipes, escaped pipes, code spans,
    # ragged rows, a blank line or text ending the table
    text = ("a | b | c\n:-- | :-: | --:\nx | `p|q` | y \\| z\n1 | 2\n\nafter\n"
            "| h |\n|---|\n| only |\nnot a row\n")
    t = report_compare.md_tables(text)
    check(len(t) == 2, "tables without outer pipes: %d" % len(t))
    if len(t) == 2:
        check(t[0].header == ["a", "b", "c"] and t[0].align == ["left", "center", "right"], "header: %s" % vars(t[0]))
        check(t[0].rows[0] == ["x", "`p|q`", "y | z"], "pipes in code and escaped: %s" % t[0].rows)
        check(t[0].rows[1] == ["1", "2", ""], "a short row padded: %s" % t[0].rows)
        check(t[1].header == ["h"] and t[1].rows == [["only"]], "one-column table: %s" % vars(t[1]))
    check(report_compare.md_tables("| a | b |\n| c | d |\n") == [], "no delimiter row: no table")
    check(report_compare.md_tables("") == [] and report_compare.md_tables("\x00|||\n|-|\n") is not None,
          "nothing or garbage: no exception")


def section_checks():
    s = report_compare.sections(NIGHTLY, ["published", "random"])
    check([n for n, _ in s] == ["published", "random"], "sections of report.md: %s" % [n for n, _ in s])
    p = report_compare.parse_compare_md(dict(s)["published"])
    check(p["status"] == 1 and p["summary"].startswith("REGRESSION (exit 1)"), "published summary: %s" % p)
    check(p["table"] is not None and [r[0] for r in p["table"].rows] == ["tiller", "ahn"],
          "published: the per-method table, not the regressions table")
    r = report_compare.parse_compare_md(dict(s)["random"])
    check(r["status"] == 3 and r["table"] is None and r["reasons"] == ["seed 7 vs 99", "samples_per_segment 256 vs 128"],
          "random: not comparable, its reasons: %s" % r)
    # another layout: the sets as ### headings, compare's headings one level
    # down, a "Per-method summary" heading
    other = NIGHTLY.replace("## published", "### Published").replace("## random", "### Random") \
        .replace("## Per method (geometric", "#### Per-method summary (geometric")
    s = report_compare.sections(other, ["published", "random"])
    check([n for n, _ in s] == ["published", "random"], "sections at another level, any case: %s" % [n for n, _ in s])
    p = report_compare.parse_compare_md(dict(s).get("published", ""))
    check(p["table"] is not None and p["table"].rows[0][0] == "tiller", "another heading for the per-method table")
    other = NIGHTLY.replace("## published", "## Published runs (1,680 jobs)").replace("## random", "## random: 250:2026")
    s = report_compare.sections(other, ["published", "random"])
    check([n for n, _ in s] == ["published", "random"], "set headings with more words: %s" % [n for n, _ in s])
    # no set headings at all (compare's report alone): one unnamed section
    s = report_compare.sections(COMPARE_1, ["published", "random"])
    check(len(s) == 1 and s[0][0] is None, "no set headings: one section: %s" % [n for n, _ in s])
    # an error section: only compare's message
    e = report_compare.parse_compare_md("offbench: compare: x.csv:1: no column 'method' in the header\n")
    check(e["status"] is None and e["table"] is None, "an error section: no status, no table: %s" % e)
    # a broken table under the heading: no table, no exception
    b = report_compare.parse_compare_md("**OK: no regression** (exit 0)\n\n## Per method\n\n| method | rows\nnone\n")
    check(b["status"] == 0 and b["table"] is None, "a broken per-method table: left out: %s" % b)


def json_checks():
    doc = {"status": 1, "verdict": "regression",
           "context": {"not_comparable": [], "notes": ["a note"]},
           "counts": {"joined": 8, "quality_regressions": 1},
           "methods": [{"method": "tiller", "rows": 4, "ctrl_points_gm": 1.0194265469082735, "max_err_gm": 1,
                        "time_gm": None, "p_value": None, "ci_lo": None, "ci_hi": None, "regressions": 1,
                        "improvements": 0, "verdict": "same", "timing_not_judged": None},
                       {"method": "ahn", "rows": 4, "ctrl_points_gm": 1, "max_err_gm": 1, "time_gm": 0.8,
                        "p_value": 0.01, "ci_lo": 0.7, "ci_hi": 0.9, "regressions": 0, "improvements": 0,
                        "verdict": "faster", "timing_not_judged": None}]}
    p = report_compare.parse_compare_json(doc)
    check(p["status"] == 1 and p["table"] is not None, "JSON: status and table: %s" % p)
    if p["table"] is not None:
        rows = {r[0]: r for r in p["table"].rows}
        h = p["table"].header
        check(h[0] == "method" and h[-1] == "verdict", "JSON: header as compare's markdown: %s" % h)
        check(rows["tiller"][-1] == "regression", "JSON: a method with a row regression is a regression "
              "(the JSON's own verdict is its timing): %s" % rows["tiller"])
        check(rows["ahn"][-1] == "improvement (faster)", "JSON: faster is an improvement: %s" % rows["ahn"])
        check(rows["tiller"][2] == "1.019" and rows["tiller"][4] == "-", "JSON: numbers as compare prints them: %s"
              % rows["tiller"])
    n = report_compare.parse_compare_json({"status": 3, "context": {"not_comparable": ["seed 7 vs 99"]}, "methods": []})
    check(n["status"] == 3 and n["reasons"] == ["seed 7 vs 99"] and n["table"] is None, "JSON: not comparable: %s" % n)
    for bad in ([], {"status": "x"}, {"methods": [1, 2]}, {"methods": [{"method": 3}]}):
        try:
            r = report_compare.parse_compare_json(bad)
            ok = r is None or r["table"] is None or isinstance(r, dict)
        except ValueError:
            ok = True
        except Exception as e:  # noqa: BLE001 - any other is the bug checked for
            ok = False
            print("  %r: %r" % (bad, e), file=sys.stderr)
        check(ok, "malformed compare JSON %r: ValueError or nothing, no other exception" % (bad,))


class FakeRun:
    def __init__(self, path, files, status):
        self.path, self.files, self.status, self.sets = path, files, status, {"published": {}, "random": {}}


def load_checks(tmp):
    """The latest run's comparison: JSON preferred, report.md else, the
    compare messages kept; a report.md that disagrees with run.json is
    said."""
    d = os.path.join(tmp, "run")
    os.makedirs(d)
    with open(os.path.join(d, "report.md"), "w") as f:
        f.write(NIGHTLY)
    with open(os.path.join(d, "compare-random.err"), "w") as f:
        f.write("offbench: not comparable: seed 7 vs 99\n")
    with open(os.path.join(d, "compare-published.err"), "w") as f:
        f.write("")
    run = FakeRun(d, ["compare-published.err", "compare-random.err", "report.md"], 3)
    warns = []
    got = report_compare.load_latest(run, warns.append)
    check([s["name"] for s in got.sets] == ["published", "random"], "load_latest: the sets: %s" % got.sets)
    check(got.sets[0]["source"] == "report.md" and got.sets[0]["table"] is not None, "load_latest: from report.md")
    check(got.sets[1]["err"].startswith("offbench: not comparable"), "load_latest: compare's messages kept")
    check(got.sets[0]["err"] == "", "an empty .err: no message")
    check(got.mismatch is None, "worst of the sets (3) agrees with run.json (3): %s" % got.mismatch)
    run.status = 1
    got = report_compare.load_latest(run, warns.append)
    check(got.mismatch is not None and "3" in got.mismatch, "report.md's 3 against run.json's 1 is said: %s"
          % got.mismatch)
    run.status = 3
    doc = {"status": 1, "methods": [{"method": "m", "rows": 1, "ctrl_points_gm": 1, "max_err_gm": 1, "time_gm": None,
                                     "p_value": None, "ci_lo": None, "ci_hi": None, "regressions": 1,
                                     "improvements": 0, "verdict": "same", "timing_not_judged": None}],
           "context": {"not_comparable": []}}
    with open(os.path.join(d, "compare-published.json"), "w") as f:
        json.dump(doc, f)
    run.files.append("compare-published.json")
    got = report_compare.load_latest(run, warns.append)
    check(got.sets[0]["source"] == "compare-published.json" and got.sets[0]["table"].rows[0][0] == "m",
          "load_latest: compare-SET.json preferred: %s" % got.sets[0])
    with open(os.path.join(d, "compare-published.json"), "w") as f:
        f.write("{not json")
    got = report_compare.load_latest(run, warns.append)
    check(got.sets[0]["source"] == "report.md" and any("compare-published.json" in w for w in warns),
          "a broken compare-SET.json: a warning, report.md read instead: %s" % warns)
    # nothing to read at all: no sets, no exception
    run2 = FakeRun(os.path.join(tmp, "none"), [], 2)
    got = report_compare.load_latest(run2, warns.append)
    check(got.sets == [] and got.report_md is None, "no compare output: no sets")


def commit_checks():
    tf = report_commits.template_from_remote
    cases = [
        ("https://github.com/owner/repo.git", "https://github.com/owner/repo/commit/{sha}"),
        ("https://github.com/owner/repo", "https://github.com/owner/repo/commit/{sha}"),
        ("git@github.com:owner/repo.git", "https://github.com/owner/repo/commit/{sha}"),
        ("ssh://git@github.com/owner/repo.git", "https://github.com/owner/repo/commit/{sha}"),
        ("https://gitlab.com/group/sub/proj.git", "https://gitlab.com/group/sub/proj/-/commit/{sha}"),
        ("git@gitlab.example.org:group/proj.git", "https://gitlab.example.org/group/proj/-/commit/{sha}"),
        ("ssh://git@gitlab.example.org:2222/group/proj.git", "https://gitlab.example.org/group/proj/-/commit/{sha}"),
        # credentials in the remote (GitLab CI's clone URL holds the job
        # token) never reach the page
        ("https://gitlab-ci-token:SECRET@gitlab.example.org/group/proj.git",
         "https://gitlab.example.org/group/proj/-/commit/{sha}"),
        ("https://user:tok@github.com/o/r.git", "https://github.com/o/r/commit/{sha}"),
        ("https://github.example.com/o/r.git", "https://github.example.com/o/r/commit/{sha}"),
        ("/srv/git/offbench.git", None), ("file:///srv/git/x.git", None), ("https://example.org/x/y.git", None),
        ("", None), ("git@github.com:", None), ("https://github.com/", None),
    ]
    for url, want in cases:
        got = tf(url)
        check(got == want, "remote %r: %r, not %r" % (url, got, want))
        check(got is None or "SECRET" not in got and "tok" not in got, "no credentials from %r" % url)
    ct = report_commits.commit_template
    check(ct({"NIGHTLY_COMMIT_URL": "https://h.example/c/{sha}"}, lambda: "git@github.com:o/r.git")[0]
          == "https://h.example/c/{sha}", "NIGHTLY_COMMIT_URL overrides the remote")
    check(ct({"NIGHTLY_COMMIT_URL": "none"}, lambda: "git@github.com:o/r.git")[0] is None, "'none': no links")
    check(ct({}, lambda: "git@github.com:o/r.git")[0] == "https://github.com/o/r/commit/{sha}", "from the remote")
    check(ct({}, lambda: None)[0] is None, "no remote: no links")
    t, problem = ct({"NIGHTLY_COMMIT_URL": "https://h.example/c/"}, lambda: None)
    check(t is None and problem and "{sha}" in problem, "a template without {sha} is refused: %r" % problem)
    t, problem = ct({"NIGHTLY_COMMIT_URL": "javascript:alert(1)//{sha}"}, lambda: None)
    check(t is None and problem, "a template that is not http(s) is refused: %r" % problem)
    cu = report_commits.commit_url
    check(cu("https://h/c/{sha}", "0123456789abcdef") == "https://h/c/0123456789abcdef", "commit_url")
    check(cu("https://h/c/{sha}", "unknown") is None and cu("https://h/c/{sha}", "abc") is None
          and cu("https://h/c/{sha}", "<x>") is None and cu(None, "0123456789ab") is None,
          "only commit ids are linked")


class R:
    def __init__(self, short, date):
        self.short, self.date, self.name, self.status_text = short, date, short, ""


def svg_checks():
    runs = [R("a%06d" % i, "2026-11-%02dT03:00:00Z" % (i + 1)) for i in range(4)]
    pts = [(0, 120, None, None), (1, 125, None, None), (3, 240, 200, 260)]
    s = report_svg.chart(pts, runs, [], "summed ctrl_points", "ctrl", width=220, height=40, small=True)
    ticks = re.findall(r'<text class="(min|max)"[^>]*>([^<]*)</text>', s)
    check(dict(ticks) == {"min": "120", "max": "260"}, "sparkline: its min and max values shown: %s" % ticks)
    titles = re.findall(r"<title>([^<]*)</title>", s)
    check(any("a000003" in t and "240 ctrl" in t and "200" in t and "260" in t for t in titles),
          "sparkline: a point's title holds its commit, value, unit and spread: %s" % titles)
    check(any("a000000" in t and "2026-11-01" in t and "120 ctrl" in t for t in titles),
          "sparkline: a point's title holds its date: %s" % titles)
    check(s.count('class="hit"') == 3, "sparkline: one hover area per point")
    check(re.search(r"<svg[^>]*>\s*<title>summed ctrl_points", s) is not None, "sparkline: a title of its own")
    big = report_svg.chart(pts, runs, [], "summed ctrl_points", "ctrl")
    check(big.count('class="hit"') == 3 and "a000003" in big, "the large chart: hover areas too")
    flat = report_svg.chart([(0, 5, None, None), (2, 5, None, None)], runs, [], "t", "ms", width=220, height=40,
                            small=True)
    check(re.findall(r'<text class="([a-z ]+)"[^>]*>([^<]*)</text>', flat) == [("min max", "5")],
          "a flat sparkline: one label: %s" % re.findall(r"<text[^>]*>[^<]*</text>", flat))
    empty = report_svg.chart([], runs, [], "t", "ms", width=220, height=40, small=True)
    check("<svg" in empty and 'class="hit"' not in empty, "a chart without points")


verdict_checks()
table_checks()
section_checks()
json_checks()
with tempfile.TemporaryDirectory() as d:
    load_checks(d)
commit_checks()
svg_checks()
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
