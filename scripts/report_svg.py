"""report_svg.py - the inline SVG charts of scripts/report.py: one series
over the runs (x: the run's position in run order, labelled with its short
commit), an optional spread bar per point, the steps as marked groups
(<g class="step" data-run=... data-kind=...>) and runs without figures as
crosses (<g class="missing" data-run=...>).  Values: the large charts have a
y axis with three ticks; the small ones (sparklines) their minimum and
maximum at the left (<text class="min">, <text class="max">; one <text
class="min max"> when they are equal); in both,
hovering over a run's column shows its commit, date, value and spread (a
transparent <rect class="hit"> with a <title>).  No scripts, no external
resources: the page works offline."""

from html import escape

COLORS = {"quality": "#c0392b", "time": "#d35400", "jobs": "#7f8c8d"}


def chart(points, runs, marks, title="", unit="", width=640, height=200, small=False):
    """points: [(run index, y, lo, hi)] (lo/hi None: no bar); runs: the
    Run objects in order (for labels and data-run); marks: [(run index,
    kind, text)].  Returns the <svg> element as text."""
    pad_l, pad_r, pad_t, pad_b = (34, 4, 5, 5) if small else (64, 12, 22, 46)
    w, h = width - pad_l - pad_r, height - pad_t - pad_b
    ys = [p[1] for p in points] + [p[3] for p in points if p[3] is not None] \
        + [p[2] for p in points if p[2] is not None]
    lo, hi = (min(ys), max(ys)) if ys else (0, 1)
    ymin, ymax = lo, hi
    if hi == lo:
        lo, hi = lo - 1 if lo >= 1 else 0, hi + 1
    n = max(len(runs), 1)

    def px(i):
        return pad_l + (w * (i + 0.5) / n)

    def py(y):
        return pad_t + h - h * (y - lo) / (hi - lo)

    out = ['<svg xmlns="http://www.w3.org/2000/svg" class="chart%s" width="%d" height="%d" '
           'viewBox="0 0 %d %d" role="img" aria-label="%s">'
           % (" small" if small else "", width, height, width, height, escape(title))]
    if title:
        out.append("<title>%s%s</title>" % (escape(title), (" (%s)" % escape(unit)) if unit else ""))
    if not small:
        out += axes(pad_l, pad_t, w, h, lo, hi, title, unit, runs, px)
    elif points:
        out += min_max(pad_l, pad_t, h, ymin, ymax, py)
    out += bars_and_line(points, px, py)
    out += hits(points, runs, unit, px, pad_t, h, w / n)
    out += mark_groups(marks, runs, px, pad_t, h, small)
    out += missing(points, runs, px, pad_t + h, small)
    out.append("</svg>")
    return "\n".join(out)


def axes(x0, y0, w, h, lo, hi, title, unit, runs, px):
    """Frame, three y ticks, the title and the commit labels."""
    out = ['<rect x="%d" y="%d" width="%d" height="%d" fill="#fff" stroke="#bbb"/>' % (x0, y0, w, h)]
    for k in range(3):
        y = lo + (hi - lo) * k / 2
        yy = y0 + h - h * k / 2
        out.append('<text x="%d" y="%.1f" font-size="10" text-anchor="end">%s</text>' % (x0 - 4, yy + 3, fmt(y)))
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#eee"/>' % (x0, yy, x0 + w, yy))
    out.append('<text x="%d" y="14" font-size="12" font-weight="bold">%s%s</text>'
               % (x0, escape(title), (" (%s)" % escape(unit)) if unit else ""))
    step = max(1, len(runs) // 12)
    for i, r in enumerate(runs):
        if i % step:
            continue
        out.append('<text x="%.1f" y="%d" font-size="9" text-anchor="end" transform="rotate(-40 %.1f %d)">%s</text>'
                   % (px(i), y0 + h + 12, px(i), y0 + h + 12, escape(r.short)))
    return out


def min_max(x0, y0, h, ymin, ymax, py):
    """A sparkline's value labels: its maximum at the top, its minimum at
    the bottom (spreads included), each beside a faint rule at its height."""
    if ymin == ymax:  # flat: one label, at the line
        return ['<text class="min max" x="%d" y="%.1f" font-size="9" fill="#555" text-anchor="end" '
                'dominant-baseline="middle">%s</text>' % (x0 - 3, py(ymin), fmt(ymin))]
    out = []
    for cls, y, base in (("max", ymax, "hanging"), ("min", ymin, "auto")):
        yy = py(y)
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#e5e5e5"/>' % (x0 - 2, yy, x0 + 2, yy))
        out.append('<text class="%s" x="%d" y="%.1f" font-size="9" fill="#555" text-anchor="end" '
                   'dominant-baseline="%s">%s</text>' % (cls, x0 - 3, y0 if cls == "max" else y0 + h, base, fmt(y)))
    return out


def hits(points, runs, unit, px, y0, h, col):
    """A transparent column per point whose title is the run and its value
    (what the browser shows on hover)."""
    out = []
    u = (" " + unit) if unit else ""
    for i, y, lo, hi in points:
        r = runs[i]
        spread = (" (IQR %s..%s%s)" % (fmt(lo), fmt(hi), u)) if lo is not None and hi is not None else ""
        out.append('<rect class="hit" x="%.1f" y="%d" width="%.1f" height="%d" fill="transparent">'
                   '<title>%s %s: %s%s%s</title></rect>'
                   % (px(i) - col / 2, y0, col, h, escape(r.short), escape(r.date), fmt(y), escape(u), escape(spread)))
    return out


def bars_and_line(points, px, py):
    """The series as a polyline with a dot per run and the spread bars."""
    out = []
    for i, y, lo, hi in points:
        if lo is not None and hi is not None:
            out.append('<line class="spread" x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#7fb3d5" '
                       'stroke-width="5"/>' % (px(i), py(lo), px(i), py(hi)))
    if len(points) > 1:
        out.append('<polyline fill="none" stroke="#2e86c1" stroke-width="1.5" points="%s"/>'
                   % " ".join("%.1f,%.1f" % (px(i), py(y)) for i, y, _, _ in points))
    for i, y, _, _ in points:
        out.append('<circle class="point" cx="%.1f" cy="%.1f" r="2.5" fill="#2e86c1"><title>%s</title></circle>'
                   % (px(i), py(y), fmt(y)))
    return out


def mark_groups(marks, runs, px, y0, h, small):
    """A vertical band per step (class "step") or job change (class "jobs")."""
    out = []
    for i, kind, text in marks:
        cls = "jobs" if kind == "jobs" else "step"
        out.append('<g class="%s" data-run="%s" data-commit="%s" data-kind="%s"><title>%s: %s</title>'
                   '<rect x="%.1f" y="%d" width="6" height="%d" fill="%s" opacity="0.35"/>'
                   '<circle cx="%.1f" cy="%d" r="%d" fill="%s"/></g>'
                   % (cls, escape(runs[i].name), escape(runs[i].short), kind, escape(runs[i].short), escape(text),
                      px(i) - 3, y0, h, COLORS.get(kind, "#c0392b"), px(i), y0 + (2 if small else 5),
                      2 if small else 4, COLORS.get(kind, "#c0392b")))
    return out


def missing(points, runs, px, ybase, small):
    """A cross at the foot of the chart for each run without figures."""
    have = {p[0] for p in points}
    out = []
    s = 2 if small else 4
    for i, r in enumerate(runs):
        if i in have:
            continue
        x = px(i)
        out.append('<g class="missing" data-run="%s"><title>%s: no figures (%s)</title>'
                   '<path d="M%.1f %.1fL%.1f %.1fM%.1f %.1fL%.1f %.1f" stroke="#c0392b" stroke-width="1.5"/></g>'
                   % (escape(r.name), escape(r.short), escape(r.status_text or "missing"),
                      x - s, ybase - 2 * s, x + s, ybase, x - s, ybase, x + s, ybase - 2 * s))
    return out


def fmt(y):
    """A tick or tooltip value: integers as such, else 4 significant digits."""
    if abs(y - round(y)) < 1e-9 and abs(y) < 1e12 or 1e4 <= abs(y) < 1e12:
        return "%d" % round(y)
    return "%.4g" % y
