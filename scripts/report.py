#!/usr/bin/python3
"""report.py - the HTML report of the nightly history store (README
"Nightly history and report").

    /usr/bin/python3 scripts/report.py HISTORY_DIR --out SITE_DIR [--copy-files]

HISTORY_DIR is the store scripts/nightly.sh fills (scripts/nightly_history.sh):
one directory per run holding run.json and per run set (published, random)
results.csv, samples.csv and meta.json.  Writes SITE_DIR/index.html (the
runs, the steps, per run set and method the latest figures with small
charts, the step rule, the latest compare report) and SITE_DIR/method-M.html
per method (charts and a table per run).  Quality per method: summed
ctrl_points, failures (fail or timeout), limits; time: the method total
(fit_ns + eval_ns over its rows) with the interquartile range of the
per-repetition totals of samples.csv as its spread.  Steps: see
scripts/report_steps.py (the rule is printed on the page too).  Links to each
run's regular files are relative (into the store, or with --copy-files into
SITE_DIR/runs/); a symbolic link, FIFO or device in a run is a warning, never
followed, read or copied (report_data.open_regular).  Standard library only; no network when viewed: charts are
inline SVG, the little script is inline.
Exit status: 0 written (problems with a run's files are warnings on stderr
and on the page), 2 bad usage or an unreadable store or unwritable site."""

import argparse
import os
import shutil
import sys
import urllib.parse
from html import escape

sys.dont_write_bytecode = True  # no __pycache__ in the checkout
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_data  # noqa: E402
import report_steps  # noqa: E402
from report_svg import chart  # noqa: E402
from report_steps import fmt_ms  # noqa: E402

CSS = """body{font-family:sans-serif;margin:1.5em;color:#222;max-width:1200px}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px}
th{background:#f3f3f3}td.date{white-space:nowrap}td.num{text-align:right}td.step{background:#fadbd8;font-weight:bold}
tr.failed td.status{background:#f5b7b1}tr.regression td.status{background:#fdebd0}
pre{background:#f8f8f8;border:1px solid #ddd;padding:.5em;overflow:auto;max-height:30em;font-size:12px}
.rule{background:#eef5fb;border-left:4px solid #2e86c1;padding:.4em .8em}.warn{color:#a04000}"""

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
                   'data-notable="%s"><td class="num">%d</td><td class="date">%s</td><td><code>%s</code>%s</td><td>%s</td>'
                   '<td class="status">%s %s</td><td>%s</td><td class="num">%s</td><td class="num%s">%d</td>'
                   '<td>%s%s</td></tr>'
                   % (cls, escape(r.name), escape(r.name), escape(r.short), escape(str(r.status)), escape(r.host),
                      notable, i + 1, escape(r.date), escape(r.short), " (dirty)" if r.dirty else "",
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
        return '<p id="no-steps">No steps.</p>'
    out = ['<table id="step-table"><tr><th>run</th><th>commit</th><th>set</th><th>method</th><th>kind</th>'
           '<th>change</th></tr>']
    for i, s, m, kind, text in sorted(rows, key=lambda t: (-t[0], t[1], t[2], t[3])):
        r = runs[i]
        out.append('<tr class="%s" data-run="%s" data-commit="%s" data-set="%s" data-method="%s" data-kind="%s">'
                   '<td>%s</td><td><code>%s</code></td><td>%s</td><td><a href="%s">%s</a></td><td>%s</td>'
                   '<td>%s</td></tr>'
                   % ("step" if kind != "jobs" else "jobs", escape(r.name), escape(r.short), escape(s), escape(m),
                      kind, escape(r.date), escape(r.short), escape(s), method_href(m), escape(m), kind,
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
                      chart(q, runs, se.marks(("quality", "jobs")), width=180, height=34, small=True),
                      chart(t, runs, se.marks(("time",)), width=180, height=34, small=True),
                      " step" if nsteps else "", nsteps))
    out.append("</table>")
    return "\n".join(out)


def latest_compare(runs):
    """The newest run's report.md, preformatted."""
    for r in reversed(runs):
        if "report.md" not in r.files:
            continue
        try:
            with report_data.open_regular(os.path.join(r.path, "report.md"), encoding="utf-8",
                                          errors="replace") as f:
                text = f.read()
        except OSError:
            continue  # unreadable: the runs table says so
        return ('<p>From run %s (commit <code>%s</code>).</p><pre id="latest-compare">%s</pre>'
                    % (escape(r.name), escape(r.short), escape(text)))
    return '<p id="latest-compare">No run has a compare report.</p>'


def index_page(store, runs, series, sets):
    head = ('<h1>offbench nightly history</h1><p id="summary">%d runs in <code>%s</code>%s.</p>'
            % (len(runs), escape(os.path.abspath(store)),
               (", %s to %s" % (escape(runs[0].date), escape(runs[-1].date))) if runs else ""))
    rule = '<p class="rule" id="step-rule"><b>Step rule.</b> %s</p>' % escape(report_steps.rule_text())
    body = [head, '<h2>Steps</h2>', step_rows(runs, series), rule, '<h2>Methods</h2>',
            '<p>Latest run\'s figures per method; ctrl is the summed control points, fail counts status fail '
            'and timeout, time the method total fit_ns + eval_ns (ms), its IQR that of the per-repetition '
            'totals (samples.csv). Charts: one point per run in run order; red bands mark steps, grey '
            'job changes, crosses runs without figures.</p>']
    body += [set_table(runs, s, series) for s in sets]
    body += ['<h2>Runs</h2><label><input type="checkbox" id="only-notable"> only runs with a step, a '
             'regression or a failure</label>', run_rows(runs, series),
             '<h2>Latest compare report</h2>', latest_compare(runs)]
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
        out.append('<tr class="run" data-run="%s" data-commit="%s"><td class="date">%s</td><td><code>%s</code></td>'
                   '<td class="num">%d</td><td class="num">%d</td><td class="num">%d</td><td class="num">%d</td>%s'
                   '<td class="num">%s</td><td class="num">%s</td>%s</tr>'
                   % (escape(r.name), escape(r.short), escape(r.date), escape(r.short), m["rows"], m["ctrl"],
                      m["fail"] + m["timeout"], m["limit"], qcell, fmt_ms(m["time_ns"]),
                      fmt_ms(m["iqr_ns"]) if m["iqr_ns"] is not None else "-", tcell))
    out.append("</table>")
    return "\n".join(out)


def build(store, site, copy):
    """Reads the store and writes the site; returns the warnings' count."""
    warnings = []

    def warn(text):
        warnings.append(text)
        print("report: " + text, file=sys.stderr)

    runs = report_data.load_store(store, warn)
    sets = []
    for r in runs:
        sets += [s for s in r.sets if s not in sets]
    series = [Series(runs, s, m) for s in sets
              for m in sorted({m for r in runs for m in r.sets.get(s, {})})]
    os.makedirs(site, exist_ok=True)
    for r in runs:
        r.links = place_files(r, site, copy, warn)
    write(os.path.join(site, "index.html"), index_page(store, runs, series, sets))
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
    a = ap.parse_args(argv)
    if not os.path.isdir(a.history):
        print("report: %s: no such directory" % a.history, file=sys.stderr)
        return 2
    try:
        build(a.history, a.out, a.copy_files)
    except OSError as e:
        print("report: %s" % e, file=sys.stderr)
        return 2
    print("report: wrote %s" % os.path.join(a.out, "index.html"), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
