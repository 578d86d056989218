#!/usr/bin/python3
"""report.py - the HTML report of the nightly history store (docs/nightly.md
"Nightly history and report").

    /usr/bin/python3 scripts/report.py HISTORY_DIR --out SITE_DIR [--copy-files]

HISTORY_DIR is the store scripts/nightly.sh fills (scripts/nightly_history.sh):
one directory per run holding run.json and per run set (published, random)
results.csv, samples.csv and meta.json.  Writes SITE_DIR/index.html (first
the latest run's verdict, its exit status from run.json, and its comparison
with the baseline per run set as HTML tables (scripts/report_compare.py);
then the steps, per run set and method the latest figures with small
charts, the step rule, the runs, report.md as written) and SITE_DIR/method-M.html
per method (charts and a table per run).  Quality per method: summed
ctrl_points, failures (fail or timeout), limits; time: the method total
(fit_ns + eval_ns over its rows) with the interquartile range of the
per-repetition totals of samples.csv as its spread.  Steps: see
scripts/report_steps.py (the rule is printed on the page too).  Links to each
run's regular files are relative (into the store, or with --copy-files into
SITE_DIR/runs/); a symbolic link, FIFO or device in a run is a warning, never
followed, read or copied (report_data.open_regular).  Commits link to
their page when --commit-url, NIGHTLY_COMMIT_URL or the checkout's GitHub
or GitLab remote gives a template (scripts/report_commits.py).  Standard
library only; no network when viewed: charts are inline SVG, the little
script is inline; the only links out of the site are the commit links.
Exit status: 0 written (problems with a run's files are warnings on stderr
and on the page), 2 bad usage or an unreadable store or unwritable site."""

import argparse
import os
import re
import shutil
import sys
import urllib.parse
from html import escape

sys.dont_write_bytecode = True  # no __pycache__ in the checkout
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_commits  # noqa: E402
import report_compare  # noqa: E402
import report_data  # noqa: E402
import report_steps  # noqa: E402
from report_svg import chart  # noqa: E402
from report_steps import fmt_ms  # noqa: E402

CSS = """body{font-family:sans-serif;margin:1.5em;color:#222;max-width:1200px}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px}
th{background:#f3f3f3}td.date{white-space:nowrap}td.num{text-align:right}td.step{background:#fadbd8;font-weight:bold}
tr.failed td.status{background:#f5b7b1}tr.regression td.status{background:#fdebd0}
pre{background:#f8f8f8;border:1px solid #ddd;padding:.5em;overflow:auto;max-height:30em;font-size:12px}
.rule{background:#eef5fb;border-left:4px solid #2e86c1;padding:.4em .8em}.warn{color:#a04000}
#latest{border:1px solid #ddd;padding:.2em 1em 1em;margin-bottom:1.5em}
.verdict{font-size:20px;padding:.4em .8em;margin:.5em 0;border-left:8px solid #7f8c8d;background:#f2f3f4}
.verdict-ok{border-color:#1e8449;background:#e9f7ef}.verdict-regression{border-color:#c0392b;background:#fdedec}
.verdict-error{border-color:#6c3483;background:#f4ecf7}.verdict-not-comparable{border-color:#b9770e;background:#fef5e7}
.badge{font-size:12px;font-weight:normal;padding:1px 6px;border-radius:3px;background:#eee}
.badge-ok{background:#d5f5e3}.badge-regression{background:#fadbd8}.badge-error{background:#e8daef}
.badge-not-comparable{background:#fdebd0}td.v-regression{background:#fadbd8;font-weight:bold}
td.v-improvement{background:#d5f5e3}a.commit{text-decoration:none}"""

# shows only the runs with a step or a failure when the box is ticked; the
# body's data-ready="yes" tells a test that the script ran to its end
JS = """(function () {
  var box = document.getElementById('only-notable');
  document.body.setAttribute('data-ready', 'yes');
  if (!box) { return; }
  box.addEventListener('change', function () {
    var rows = document.querySelectorAll('#run-table tr.run');
    for (var i = 0; i < rows.length; i++) {
      var keep = !box.checked || rows[i].getAttribute('data-notable') === 'yes';
      rows[i].style.display = keep ? '' : 'none';
    }
  });
})();"""


class Series:
    """One (run set, method) over the runs: its points and steps."""

    def __init__(self, runs, s, method):
        self.set, self.method = s, method
        self.points = []
        for i, r in enumerate(runs):
            m = r.sets.get(s, {}).get(method)
            if m is not None:
                self.points.append((i, m, report_steps.Point(
                    i, m["jobs"], m["ctrl"], m["fail"] + m["timeout"], m["limit"], m["time_ns"], r.machine[s])))
        pts = [p for _, _, p in self.points]
        self.quality = report_steps.quality_steps(pts)
        self.time = report_steps.time_steps(pts)

    def marks(self, kinds):
        return [m for m in self.quality + self.time if m[1] in kinds]


def page(title, body):
    """A whole HTML page around BODY."""
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<link rel=\"icon\" href=\"data:,\"><title>%s</title><style>%s</style></head>\n<body>\n%s\n"
            "<script>%s</script>\n</body></html>\n" % (escape(title), CSS, body, JS))


def href(path, site):
    """The link from SITE to PATH: relative, each byte that is not plain
    ASCII percent-encoded (names need not be UTF-8)."""
    return urllib.parse.quote(os.fsencode(os.path.relpath(path, site).replace(os.sep, "/")), safe="/")


def copy_file(src, dst):
    """Copies the regular file SRC of the store to DST through DST.tmp: SRC
    is opened by report_data.open_regular, so a symbolic link (to /dev/zero,
    to a file outside the store), a FIFO or a device is refused, never
    followed or read; DST.tmp is never a link either."""
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    tmp = dst + ".tmp"
    try:
        with report_data.open_regular(src, "rb") as fi:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
            with os.fdopen(fd, "wb") as fo:
                shutil.copyfileobj(fi, fo, 1 << 20)
        os.replace(tmp, dst)
    except BaseException:
        if os.path.lexists(tmp):
            os.unlink(tmp)
        raise


def place_files(run, site, copy, warn):
    """(label, href) for each regular file of the run (run.files; nothing
    else is listed), relative to the site; with COPY, into SITE/runs/ (a
    file that cannot be copied is flagged and not listed)."""
    out = []
    for rel in run.files:
        src = os.path.join(run.path, rel)
        if copy:
            dst = os.path.join(site, "runs", run.dirname, rel)
            try:
                copy_file(src, dst)
            except OSError as e:
                run.flag("%s (not copied)" % e, warn)
                continue
            src = dst
        out.append((report_data.shown(rel), href(src, site)))
    return out


def commit_cell(r):
    """The run's short commit, a link when the page has a commit link
    template (report_commits), and "(dirty)" when the tree had changes."""
    url = report_commits.commit_url(COMMIT_TEMPLATE[0], r.commit)
    c = "<code>%s</code>" % escape(r.short)
    if url:
        c = '<a class="commit" href="%s">%s</a>' % (escape(url), c)
    return c + (" (dirty)" if r.dirty else "")


COMMIT_TEMPLATE = [None]  # set by build(): the commit link template or None


def run_rows(runs, series):
    """The runs table, newest first."""
    steps_at = {}
    for se in series:
        for i, kind, _ in se.marks(("quality", "time")):
            steps_at[i] = steps_at.get(i, 0) + 1
    out = ['<table id="run-table"><tr><th>#</th><th>date (UTC)</th><th>commit</th><th>host</th>'
           '<th>status</th><th>stage</th><th>s</th><th>steps</th><th>files</th></tr>']
    for i in reversed(range(len(runs))):
        r = runs[i]
        failed = r.status not in (0, 1, 3)
        cls = "run" + (" failed" if failed else "") + (" regression" if r.status == 1 else "")
        notable = "yes" if steps_at.get(i) or failed or r.status == 1 else "no"
        files = " ".join('<a href="%s">%s</a>' % (escape(h), escape(l)) for l, h in r.links)
        probs = "".join('<div class="warn">%s</div>' % escape(p) for p in r.problems)
        out.append('<tr class="%s" id="run-%s" data-run="%s" data-commit="%s" data-status="%s" data-host="%s" '
                   'data-notable="%s"><td class="num">%d</td><td class="date">%s</td><td>%s</td><td>%s</td>'
                   '<td class="status">%s %s</td><td>%s</td><td class="num">%s</td><td class="num%s">%d</td>'
                   '<td>%s%s</td></tr>'
                   % (cls, escape(r.name), escape(r.name), escape(r.short), escape(str(r.status)), escape(r.host),
                      notable, i + 1, escape(r.date), commit_cell(r),
                      escape(r.host), escape(str(r.status)), escape(r.status_text), escape(r.stage),
                      "-" if r.seconds is None else escape(str(r.seconds)), " step" if steps_at.get(i) else "", steps_at.get(i, 0), files, probs))
    out.append("</table>")
    return "\n".join(out)


def step_rows(runs, series):
    """Every step and job change, newest first."""
    rows = []
    for se in series:
        for i, kind, text in se.quality + se.time:
            rows.append((i, se.set, se.method, kind, text))
    if not rows:
        return ('<p id="no-steps">No steps between the runs of this history (%d run%s): steps compare each run '
                'with the runs before it. The comparison of the latest run with the baseline, and the verdict, '
                'are at the top of the page.</p>' % (len(runs), "" if len(runs) == 1 else "s"))
    out = ['<table id="step-table"><tr><th>run</th><th>commit</th><th>set</th><th>method</th><th>kind</th>'
           '<th>change</th></tr>']
    for i, s, m, kind, text in sorted(rows, key=lambda t: (-t[0], t[1], t[2], t[3])):
        r = runs[i]
        out.append('<tr class="%s" data-run="%s" data-commit="%s" data-set="%s" data-method="%s" data-kind="%s">'
                   '<td>%s</td><td>%s</td><td>%s</td><td><a href="%s">%s</a></td><td>%s</td>'
                   '<td>%s</td></tr>'
                   % ("step" if kind != "jobs" else "jobs", escape(r.name), escape(r.short), escape(s), escape(m),
                      kind, escape(r.date), commit_cell(r), escape(s), method_href(m), escape(m), kind,
                      escape(text)))
    out.append("</table>")
    return "\n".join(out)


def method_href(m):
    return "method-%s.html" % "".join(c if c.isalnum() or c in "-_." else "_" for c in m)


def time_point(i, m):
    """(index, ms, lo, hi): the total and its repetitions' quartiles."""
    t = m["rep_totals"]
    if len(t) >= 2:
        q = report_data.statistics.quantiles(t, n=4, method="inclusive")
        return (i, m["time_ns"] / 1e6, q[0] / 1e6, q[2] / 1e6)
    return (i, m["time_ns"] / 1e6, None, None)


def set_table(runs, s, series):
    """Per method of run set S: the latest figures and small charts."""
    out = ['<h3 id="set-%s">%s</h3>' % (escape(s), escape(s)),
           '<table class="methods" data-set="%s"><tr><th>method</th><th>rows</th><th>ctrl</th><th>fail</th>'
           '<th>limit</th><th>time ms</th><th>IQR ms</th><th>ctrl over runs</th><th>time over runs</th>'
           '<th>steps</th></tr>' % escape(s)]
    for se in series:
        if se.set != s or not se.points:
            continue
        i, m, _ = se.points[-1]
        q = [(j, mm["ctrl"], None, None) for j, mm, _ in se.points]
        t = [time_point(j, mm) for j, mm, _ in se.points]
        nsteps = len(se.marks(("quality", "time")))
        out.append('<tr class="method" data-set="%s" data-method="%s"><td><a href="%s">%s</a></td>'
                   '<td class="num">%d</td><td class="num">%d</td><td class="num">%d</td><td class="num">%d</td>'
                   '<td class="num">%s</td><td class="num">%s</td><td>%s</td><td>%s</td><td class="num%s">%d</td></tr>'
                   % (escape(s), escape(se.method), method_href(se.method), escape(se.method), m["rows"], m["ctrl"],
                      m["fail"] + m["timeout"], m["limit"], fmt_ms(m["time_ns"]),
                      fmt_ms(m["iqr_ns"]) if m["iqr_ns"] is not None else "-",
                      chart(q, runs, se.marks(("quality", "jobs")), "%s %s: summed ctrl_points" % (s, se.method),
                            "ctrl", width=220, height=40, small=True),
                      chart(t, runs, se.marks(("time",)), "%s %s: method total time" % (s, se.method), "ms",
                            width=220, height=40, small=True),
                      " step" if nsteps else "", nsteps))
    out.append("</table>")
    return "\n".join(out)


def latest_compare(runs):
    """The newest run's report.md as it is (the section at the top shows
    it as tables), folded."""
    for r in reversed(runs):
        if "report.md" not in r.files:
            continue
        try:
            with report_data.open_regular(os.path.join(r.path, "report.md"), encoding="utf-8",
                                          errors="replace") as f:
                text = f.read()
        except OSError:
            continue  # unreadable: the runs table says so
        return ('<details><summary>report.md of run %s (commit %s), as scripts/nightly.sh wrote it</summary>'
                '<pre id="latest-compare">%s</pre></details>' % (escape(r.name), commit_cell(r), escape(text)))
    return '<p id="latest-compare">No run has a compare report.</p>'


def link_to(r, label):
    """An <a> to the run's file LABEL (its link in the runs table), or the
    name as text when the run has no such file."""
    for l, h in r.links:
        if l == label:
            return '<a href="%s">%s</a>' % (escape(h), escape(l))
    return "<code>%s</code>" % escape(label)


def stage_files(r):
    """The files that tell why a run ended at its stage (a killed night's
    stage is said "run published (killed by SIGTERM)": its log all the same)."""
    stage = r.stage.split(" (killed by ", 1)[0]
    if stage == "build":
        want = ["build.log"]
    elif stage.startswith("run "):
        want = [stage[4:] + ".log"]
    else:
        want = ["report.md"] + [l for l, _ in r.links if l.startswith("compare-")]
    return [w for w in want if any(l == w for l, _ in r.links)]


def compare_table(entry, methods):
    """One set's per-method comparison as an HTML table."""
    t = entry["table"]
    vcol = next((k for k, h in enumerate(t.header) if h.strip().lower() == "verdict"), None)
    out = ['<table class="compare-methods" data-set="%s" data-source="%s"><tr>%s</tr>'
           % (escape(entry["name"] or ""), escape(entry["source"] or ""),
              "".join("<th>%s</th>" % escape(h) for h in t.header))]
    for row in t.rows:
        cells = []
        for k, c in enumerate(row):
            cls = []
            if t.align[k] == "right":
                cls.append("num")
            if k == vcol and c:
                cls.append("v-" + re.sub(r"[^a-z-]", "", c.split()[0].lower()))
            text = escape(c)
            if k == 0 and c in methods:
                text = '<a href="%s">%s</a>' % (method_href(c), text)
            cells.append('<td%s>%s</td>' % (' class="%s"' % " ".join(cls) if cls else "", text))
        out.append('<tr class="compare-method" data-method="%s">%s</tr>' % (escape(row[0]), "".join(cells)))
    out.append("</table>")
    return "\n".join(out)


def baseline_of(r):
    """the committed baseline the run was compared with, as nightly.sh
    recorded it in run.json (NIGHTLY_BASELINE: results/baseline by default)"""
    b = r.meta.get("baseline")
    return escape(b.rstrip("/") + "/") if isinstance(b, str) and b else "its path not recorded in run.json"


def latest_section(runs, latest, methods):
    """The top of the page: the newest run's verdict, which is its exit
    status in run.json (the nightly's exit code), and its comparison with
    the baseline per run set as HTML tables."""
    if not runs:
        return ('<section id="latest"><h2>Latest run</h2><p>No runs in the store yet.</p></section>')
    r = runs[-1]
    cls, word = report_compare.verdict_of(r.status)
    out = ['<section id="latest" data-run="%s"><h2>Latest run: %s</h2>' % (escape(r.name), escape(word)),
           '<div id="verdict" class="verdict verdict-%s" data-status="%s"><strong class="verdict-word">%s</strong>'
           ' &mdash; nightly exit status %s</div>'
           % (cls, escape(str(r.status)), escape(word[:1].upper() + word[1:]), escape(str(r.status))),
           '<p class="run-facts">Run <a href="#run-%s">%s</a>, commit %s, host %s%s. The verdict is the exit '
           'status of scripts/nightly.sh as run.json records it (0 no regression, 1 regression, 2 error, 3 not '
           'comparable)%s.%s</p>'
           % (escape(r.name), escape(r.date), commit_cell(r), escape(r.host),
              (", %s s" % escape(str(r.seconds))) if r.seconds is not None else "",
              "; below, per run set, compare's verdict and per-method table against the committed baseline "
              "(%s)" % baseline_of(r) if latest.sets else "",
              " It is the first run of this history: there is nothing to draw a step from yet."
              if len(runs) == 1 else "")]
    if r.status not in (0, 1, 3) or r.stage not in ("compare", ""):
        files = stage_files(r)
        out.append('<p class="stage">The run ended at stage <b>%s</b>%s.</p>'
                   % (escape(r.stage or "unknown"),
                      (": see " + ", ".join(link_to(r, f) for f in files)) if files else ""))
    if latest.mismatch:
        out.append('<p class="warn mismatch">%s.</p>' % escape(latest.mismatch))
    for e in latest.sets:
        name = e["name"] or "comparison"
        badge = ""
        if e["status"] is not None:
            bc, bw = report_compare.verdict_of(e["status"])
            badge = ' <span class="badge badge-%s">%s (exit %d)</span>' % (bc, escape(bw), e["status"])
        elif e["err"]:
            badge = ' <span class="badge badge-error">no verdict: see compare\'s messages</span>'
        out.append('<div class="compare-set" data-set="%s" data-status="%s"><h3>%s%s</h3>'
                   % (escape(e["name"] or ""), "" if e["status"] is None else e["status"], escape(name), badge))
        if e["summary"]:
            out.append('<p class="compare-summary">%s</p>' % escape(e["summary"]))
        if e["reasons"]:
            out.append('<ul class="reasons">%s</ul>'
                       % "".join("<li>not comparable: %s</li>" % escape(x) for x in e["reasons"]))
        if e["notes"]:
            out.append('<ul class="notes">%s</ul>' % "".join("<li>note: %s</li>" % escape(x) for x in e["notes"]))
        if e["table"] is not None:
            out.append(compare_table(e, methods))
        elif e["status"] in (0, 1):
            out.append('<p class="no-table warn">No per-method table could be read; see %s.</p>'
                       % link_to(r, e["source"] or "report.md"))
        if e["err"]:
            lines = e["err"].splitlines()
            out.append('<div class="compare-err"><b>compare\'s messages</b> (%s)<pre>%s%s</pre></div>'
                       % (link_to(r, "compare-%s.err" % e["name"]) if e["name"] else "stderr",
                          escape("\n".join(lines[:20])), "\n..." if len(lines) > 20 else ""))
        out.append("</div>")
    if not latest.sets and r.stage in ("compare", ""):
        out.append('<p class="warn">This run has no compare output%s.</p>'
                   % ("" if "report.md" not in r.files else ": see " + link_to(r, "report.md")))
    out.append("</section>")
    return "\n".join(out)


def index_page(store, runs, series, sets, latest):
    head = ('<h1>offbench nightly history</h1><p id="summary">%d run%s in <code>%s</code>%s.</p>'
            % (len(runs), "" if len(runs) == 1 else "s", escape(os.path.abspath(store)),
               (", %s to %s" % (escape(runs[0].date), escape(runs[-1].date))) if runs else ""))
    rule = '<p class="rule" id="step-rule"><b>Step rule.</b> %s</p>' % escape(report_steps.rule_text())
    methods = {se.method for se in series}
    body = [head, latest_section(runs, latest, methods), '<h2>Steps</h2>', step_rows(runs, series), rule,
            '<h2>Methods</h2>',
            '<p>Latest run\'s figures per method; ctrl is the summed control points, fail counts status fail '
            'and timeout, time the method total fit_ns + eval_ns (ms), its IQR that of the per-repetition '
            'totals (samples.csv). Charts: one point per run in run order; red bands mark steps, grey '
            'job changes, crosses runs without figures.</p>']
    body += [set_table(runs, s, series) for s in sets]
    body += ['<h2>Runs</h2><label><input type="checkbox" id="only-notable"> only runs with a step, a '
             'regression or a failure</label>', run_rows(runs, series),
             '<h2>Full compare report</h2>', latest_compare(runs)]
    return page("offbench nightly history", "\n".join(body))


def method_page(runs, method, series):
    """Per run set: ctrl, failures/limits and time charts, and a table."""
    body = ['<p><a href="index.html">&larr; all methods</a></p><h1>%s</h1>' % escape(method),
            '<p class="rule">%s</p>' % escape(report_steps.rule_text())]
    for se in series:
        if se.method != method or not se.points:
            continue
        qm, tm = se.marks(("quality", "jobs")), se.marks(("time",))
        body.append('<h2 id="set-%s">%s</h2><div class="charts" data-set="%s">' % (escape(se.set), escape(se.set),
                                                                                 escape(se.set)))
        body.append(chart([(i, m["ctrl"], None, None) for i, m, _ in se.points], runs, qm, "summed ctrl_points"))
        body.append(chart([(i, m["fail"] + m["timeout"] + m["limit"], None, None) for i, m, _ in se.points], runs,
                          qm, "failures + limits", "rows"))
        body.append(chart([time_point(i, m) for i, m, _ in se.points], runs, tm,
                          "method total fit_ns + eval_ns, bar: IQR of the repetitions", "ms"))
        body.append("</div>")
        body.append(method_table(runs, se))
    return page("offbench nightly: " + method, "\n".join(body))


def method_table(runs, se):
    """One row per run with figures; step cells marked class "step"."""
    q = {i: t for i, k, t in se.quality if k == "quality"}
    j = {i: t for i, k, t in se.quality if k == "jobs"}
    tt = {i: t for i, _, t in se.time}
    out = ['<table class="method-runs" data-set="%s"><tr><th>run</th><th>commit</th><th>rows</th><th>ctrl</th>'
           '<th>fail</th><th>limit</th><th>quality</th><th>time ms</th><th>IQR ms</th><th>time</th></tr>'
           % escape(se.set)]
    for i, m, _ in reversed(se.points):
        r = runs[i]
        qcell = ('<td class="step" data-kind="quality">%s</td>' % escape(q[i]) if i in q else
                 '<td class="jobs">%s</td>' % escape(j[i]) if i in j else "<td></td>")
        tcell = '<td class="step" data-kind="time">%s</td>' % escape(tt[i]) if i in tt else "<td></td>"
        out.append('<tr class="run" data-run="%s" data-commit="%s"><td class="date">%s</td><td>%s</td>'
                   '<td class="num">%d</td><td class="num">%d</td><td class="num">%d</td><td class="num">%d</td>%s'
                   '<td class="num">%s</td><td class="num">%s</td>%s</tr>'
                   % (escape(r.name), escape(r.short), escape(r.date), commit_cell(r), m["rows"], m["ctrl"],
                      m["fail"] + m["timeout"], m["limit"], qcell, fmt_ms(m["time_ns"]),
                      fmt_ms(m["iqr_ns"]) if m["iqr_ns"] is not None else "-", tcell))
    out.append("</table>")
    return "\n".join(out)


def build(store, site, copy, commit_url=None):
    """Reads the store and writes the site; returns the warnings' count.
    COMMIT_URL: the commit link template (None: NIGHTLY_COMMIT_URL, else
    the checkout's remote; see report_commits)."""
    warnings = []

    def warn(text):
        warnings.append(text)
        print("report: " + text, file=sys.stderr)

    env = dict(os.environ)
    if commit_url is not None:
        env[report_commits.ENV] = commit_url
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    COMMIT_TEMPLATE[0], problem = report_commits.commit_template(env, lambda: report_commits.git_remote(root))
    if problem:
        warn(problem)
    runs = report_data.load_store(store, warn)
    sets = []
    for r in runs:
        sets += [s for s in r.sets if s not in sets]
    series = [Series(runs, s, m) for s in sets
              for m in sorted({m for r in runs for m in r.sets.get(s, {})})]
    os.makedirs(site, exist_ok=True)
    for r in runs:
        r.links = place_files(r, site, copy, warn)
    latest = report_compare.load_latest(runs[-1], warn) if runs else report_compare.Latest()
    write(os.path.join(site, "index.html"), index_page(store, runs, series, sets, latest))
    for m in sorted({se.method for se in series}):
        write(os.path.join(site, method_href(m)), method_page(runs, m, series))
    return len(warnings)


def write(path, text):
    """TEXT into PATH through PATH.tmp, as UTF-8; what cannot be UTF-8 (a
    name's bytes or a lone surrogate that shown() did not see) becomes '?'
    rather than stopping the report."""
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8", errors="replace") as f:
        f.write(text)
    os.replace(tmp, path)


def main(argv):
    ap = argparse.ArgumentParser(prog="report.py", description="HTML report of the nightly history store")
    ap.add_argument("history", metavar="HISTORY_DIR")
    ap.add_argument("--out", required=True, metavar="SITE_DIR")
    ap.add_argument("--copy-files", action="store_true", help="copy each run's files into SITE_DIR/runs/")
    ap.add_argument("--commit-url", metavar="TEMPLATE",
                    help="link commits to TEMPLATE with {sha} for the commit id ('none': no links; default: "
                         "NIGHTLY_COMMIT_URL, else the checkout's GitHub or GitLab remote)")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.history):
        print("report: %s: no such directory" % a.history, file=sys.stderr)
        return 2
    try:
        build(a.history, a.out, a.copy_files, a.commit_url)
    except OSError as e:
        print("report: %s" % e, file=sys.stderr)
        return 2
    print("report: wrote %s" % os.path.join(a.out, "index.html"), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
