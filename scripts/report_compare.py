"""report_compare.py - the first section of scripts/report.py's page: the
latest run's verdict and its comparison with the baseline (docs/nightly.md "Nightly
history and report").

The verdict is always the run's exit status as run.json records it (the
exit code of scripts/nightly.sh): 0 no regression, 1 regression, 2 error,
3 not comparable; whatever compare's output says, the page cannot disagree
with the exit code.  The comparison per run set (published, random) is read,
for each set, from compare-SET.json when the run has one (`compare --format
json`), else from report.md: its section for the set (a heading, of any
level, named as the set), in it compare's verdict line (**WORD** (exit N)),
its "not comparable:" reasons and the table under the heading that starts
"Per method" (or "Per-method", or compare's "Verdict by method"), all read as markdown in general (the
columns by the header's names, any heading level, tables with or without
outer pipes), so that a change of report.md's layout costs at most that
table, never the page: a table that cannot be read is left out and
report.md linked.  When the sets' own statuses, combined as nightly.sh does
(2 > 3 > 1 > 0), differ from run.json's the page says so."""

import json
import os
import re

import report_data

VERDICTS = {0: ("ok", "no regression"), 1: ("regression", "regression"), 2: ("error", "error"),
            3: ("not-comparable", "not comparable")}
SEVERITY = {2: 3, 3: 2, 1: 1, 0: 0}   # nightly.sh's worst(): 2 > 3 > 1 > 0
MAX_TEXT = 1 << 20                    # bytes of a report.md or .err read at most
HEADING = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
DELIM_CELL = re.compile(r"^\s*:?-+:?\s*$")
VERDICT_LINE = re.compile(r"^\s*\*\*(.+?)\*\*\s*\(exit (\d+)\)(.*)$")


def verdict_of(status):
    """(css word, shown word) of an exit status; ('unknown', ...) for
    anything but 0-3."""
    if isinstance(status, int) and not isinstance(status, bool) and status in VERDICTS:
        return VERDICTS[status]
    if isinstance(status, int) and not isinstance(status, bool):
        return ("unknown", "exit %d" % status)
    return ("unknown", "unknown")


def worst(statuses):
    """The most severe of the statuses as nightly.sh combines them (None
    for none)."""
    known = [s for s in statuses if s in SEVERITY]
    return max(known, key=lambda s: SEVERITY[s]) if known else None


class Table:
    """A markdown table: header cells, each column's alignment ('left',
    'center', 'right' or ''), body rows padded or cut to the header's
    width, and the line of its header."""

    def __init__(self, header, align, rows, line):
        self.header, self.align, self.rows, self.line = header, align, rows, line


def split_row(line):
    """The cells of a markdown table row: split at | outside code spans and
    not escaped (\\|, which becomes |); outer pipes optional."""
    s = line.strip()
    cells, cur, code, i = [], [], False, 0
    while i < len(s):
        c = s[i]
        if c == "\\" and i + 1 < len(s) and s[i + 1] == "|":
            cur.append("|")
            i += 2
            continue
        if c == "`":
            code = not code
        if c == "|" and not code:
            cells.append("".join(cur))
            cur = []
        else:
            cur.append(c)
        i += 1
    cells.append("".join(cur))
    if s.startswith("|"):
        cells = cells[1:]
    if s.endswith("|") and not s.endswith("\\|") and cells:
        cells = cells[:-1]
    return [c.strip() for c in cells]


def md_tables(text):
    """Every table of the markdown TEXT (a header row, a delimiter row of
    ---, :--, --: or :-: cells, the body rows up to a line without a |)."""
    lines = text.splitlines()
    out, i = [], 0
    while i + 1 < len(lines):
        head, delim = lines[i], lines[i + 1]
        if "|" in head and "-" in delim:
            h, d = split_row(head), split_row(delim)
            if h and len(d) == len(h) and all(DELIM_CELL.match(c) for c in d):
                align = [("center" if c.strip().startswith(":") and c.strip().endswith(":") else
                          "right" if c.strip().endswith(":") else "left" if c.strip().startswith(":") else "")
                         for c in d]
                rows, j = [], i + 2
                while j < len(lines) and "|" in lines[j] and lines[j].strip() and not HEADING.match(lines[j]):
                    r = split_row(lines[j])
                    rows.append((r + [""] * len(h))[:len(h)])
                    j += 1
                out.append(Table(h, align, rows, i))
                i = j
                continue
        i += 1
    return out


def norm(text):
    return re.sub(r"[^a-z0-9]+", " ", text.lower()).strip()


def sections(text, names):
    """report.md cut at its headings named as a run set (any level, any
    case, the name alone or first: "## published", "### Random set: 250
    curves"): [(name, the text up to the next such heading)], in order; one
    (None, TEXT) when no heading names a set."""
    want = {norm(n): n for n in names}
    cuts = []
    lines = text.splitlines()
    for k, line in enumerate(lines):
        m = HEADING.match(line)
        h = norm(m.group(2)) if m else ""
        hit = next((want[w] for w in want if w and (h == w or h.startswith(w + " "))), None)
        if hit is not None:
            cuts.append((k, hit))
    if not cuts:
        return [(None, text)]
    out = []
    for n, (k, name) in enumerate(cuts):
        end = cuts[n + 1][0] if n + 1 < len(cuts) else len(lines)
        out.append((name, "\n".join(lines[k + 1:end])))
    return out


def parse_compare_md(text):
    """One set's compare report (markdown): {status (compare's exit, or
    None), summary (its verdict line, unbolded), reasons (not comparable),
    notes, table (the per-method Table or None)}."""
    got = {"status": None, "summary": "", "reasons": [], "notes": [], "table": None}
    lines = text.splitlines()
    for line in lines:
        m = VERDICT_LINE.match(line)
        if m and got["status"] is None:
            got["status"] = int(m.group(2))
            got["summary"] = ("%s (exit %s)%s" % (m.group(1), m.group(2), m.group(3))).strip()
        r = re.match(r"^\s*[-*]\s+not comparable:\s*(.*)$", line)
        if r:
            got["reasons"].append(r.group(1).strip())
        r = re.match(r"^\s*[-*]\s+note:\s*(.*)$", line)
        if r:
            got["notes"].append(r.group(1).strip())
    # the per-method heading, then the first table before the next heading
    for k, line in enumerate(lines):
        m = HEADING.match(line)
        if not m or not (norm(m.group(2)).startswith("per method") or norm(m.group(2)).startswith("verdict by method")):
            continue
        end = next((j for j in range(k + 1, len(lines)) if HEADING.match(lines[j])), len(lines))
        tables = md_tables("\n".join(lines[k + 1:end]))
        if tables and tables[0].header and norm(tables[0].header[0]) == "method" and tables[0].rows:
            got["table"] = tables[0]
        break
    return got


def num(v, fmt):
    """A number of compare's JSON as its markdown prints it ('-' for null)."""
    if v is None:
        return "-"
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ValueError("not a number: %r" % (v,))
    return fmt % v


JSON_HEADER = ["method", "rows", "ctrl_points", "max_err", "time", "p", "time interval", "regressions",
               "improvements", "verdict"]


def parse_compare_json(doc):
    """compare --format json's document as parse_compare_md's dict; the
    method's verdict as the markdown's (a row regression or a slower total
    is a regression; the JSON's own "verdict" is the timing's).  ValueError
    when the document is not compare's."""
    if not isinstance(doc, dict):
        raise ValueError("not a JSON object")
    st = doc.get("status")
    if st is not None and (isinstance(st, bool) or not isinstance(st, int)):
        raise ValueError("status is %r" % (st,))
    ctx = doc.get("context") if isinstance(doc.get("context"), dict) else {}
    got = {"status": st, "summary": "", "reasons": [str(x) for x in ctx.get("not_comparable") or []],
           "notes": [str(x) for x in ctx.get("notes") or []], "table": None}
    if st is not None:
        got["summary"] = "%s (exit %d)" % (str(doc.get("verdict", verdict_of(st)[1])).replace("_", " ").upper(), st)
    methods = doc.get("methods") or []
    if not isinstance(methods, list):
        raise ValueError("methods is not a list")
    rows = []
    harness = doc.get("harness")
    if isinstance(harness, dict):  # offbench's own measuring, its own line (compare.h)
        harness = dict(harness, method="(harness)", regressions=0, improvements=0)
        if not doc.get("harness_counts"):
            harness["method_verdict"] = "same"
            harness["timing_not_judged"] = "reported only (a batch backend's eval_ns is wall time)"
        methods = list(methods) + [harness]
    for m in methods:
        if not isinstance(m, dict) or not isinstance(m.get("method"), str):
            raise ValueError("a method entry without a name: %r" % (m,))
        reg, imp = m.get("regressions") or 0, m.get("improvements") or 0
        if not isinstance(reg, int) or not isinstance(imp, int):
            raise ValueError("%s: regressions or improvements not counts" % m["method"])
        # compare's JSON: "timing" (and, as before, "verdict") the timing's
        # verdict; "method_verdict" the method's, as report.md's table says
        tv = m.get("timing", m.get("verdict"))
        overall = m.get("method_verdict")
        word = (overall if overall in ("regression", "improvement", "same") else
                "regression" if reg > 0 or tv == "slower" else "improvement" if imp > 0 or tv == "faster"
                else "same")
        word += " (slower)" if tv == "slower" else " (faster)" if tv == "faster" else ""
        if m.get("timing") == "noisy" and isinstance(m.get("timing_words"), str):
            word += "; " + m["timing_words"]  # "cannot decide: need N more repetitions per side"
        elif m.get("timing_not_judged"):
            word += "; timing not judged: %s" % m["timing_not_judged"]
        lo, hi = m.get("ci_lo"), m.get("ci_hi")
        ci = "-" if lo is None or hi is None else "%s..%s" % (num(lo, "%.3g"), num(hi, "%.3g"))
        rows.append([m["method"], num(m.get("rows"), "%d"), num(m.get("ctrl_points_gm"), "%.4g"),
                     num(m.get("max_err_gm"), "%.4g"), num(m.get("time_estimate", m.get("time_gm")), "%.4g"), num(m.get("p_value"), "%.3g"),
                     ci, "%d" % reg, "%d" % imp, word])
    if rows:
        got["table"] = Table(list(JSON_HEADER), ["", "right", "right", "right", "right", "right", "right", "right",
                                                 "right", ""], rows, 0)
    return got


class Latest:
    """The newest run's comparison: sets [{name, status, summary, reasons,
    notes, table, err, source}], report_md (its text or None), mismatch
    (what disagrees with run.json's status, or None)."""

    def __init__(self):
        self.sets, self.report_md, self.mismatch = [], None, None


def read_text(path):
    """The regular file PATH as text (at most MAX_TEXT bytes, undecodable
    bytes replaced)."""
    with report_data.open_regular(path, "rb") as f:
        return f.read(MAX_TEXT).decode("utf-8", "replace")


def load_latest(run, warn):
    """RUN's comparison (its compare-SET.json, report.md, compare-SET.err);
    warn(text) for files that cannot be read.  Never raises for their
    content."""
    got = Latest()
    names = []
    for f in run.files:
        m = re.match(r"^compare-(.+)\.(err|json)$", f)
        if m and m.group(1) not in names:
            names.append(m.group(1))
    for s in list(getattr(run, "sets", {})) + list(report_data.SET_ORDER):
        if s not in names:
            names.append(s)
    if "report.md" in run.files:
        try:
            got.report_md = read_text(os.path.join(run.path, "report.md"))
        except OSError as e:
            warn("%s (the latest comparison read without it)" % e)
    parts = dict(sections(got.report_md, names)) if got.report_md is not None else {}
    order = {n: k for k, n in enumerate(names)}
    present = [n for n in names if n in parts or "compare-%s.json" % n in run.files
               or "compare-%s.err" % n in run.files]
    for s in sorted(present, key=lambda n: order[n]):
        entry, source = None, None
        jf = "compare-%s.json" % s
        if jf in run.files:
            try:
                entry = parse_compare_json(json.loads(read_text(os.path.join(run.path, jf))))
                source = jf
            except (OSError, ValueError, RecursionError) as e:
                warn("%s: %s (report.md read instead)" % (os.path.join(run.path, jf), e))
        if entry is None:
            entry = parse_compare_md(parts.get(s, ""))
            source = "report.md" if s in parts else None
        entry["name"], entry["source"], entry["err"] = s, source, ""
        ef = "compare-%s.err" % s
        if ef in run.files:
            try:
                entry["err"] = read_text(os.path.join(run.path, ef)).strip()
            except OSError as e:
                warn("%s (left out)" % e)
        got.sets.append(entry)
    if None in parts and parts[None].strip():
        got.sets.append(dict(parse_compare_md(parts[None]), name=None, source="report.md", err=""))
    # a set without a verdict line (compare failed: its message is in the
    # .err) could only make the combination worse: then only a combination
    # worse than run.json's status disagrees
    sts = [e["status"] for e in got.sets if e["status"] is not None]
    w = worst(sts)
    st = run.status
    partial = len(sts) < len(got.sets)
    if w is not None and verdict_of(st)[0] != "unknown" and w != st \
            and (not partial or SEVERITY[w] > SEVERITY[st]):
        got.mismatch = ("compare's reports combine to exit %d (%s), run.json records exit status %s: the verdict "
                        "shown is run.json's, the nightly's exit code" % (w, verdict_of(w)[1], st))
    return got
