"""SVG geometry for scripts/svg2curves.py: the same rules, and the same
arithmetic, as measure's SVG reader (host/io/svg_path.c for path data and
shapes, svg_frame.c for transforms, lengths and viewports,
approx_read_svg.c for the walk over the elements), so that a file reads as
the same Bezier pieces by both (tests/e2e/e2e_svg_xml.sh checks it).  The
rules are written once in docs/export-measure.md, "Reading SVG".

A piece is (letter, [(x, y, w), ...]): L a line, Q or C a Bezier, A one
rational quadratic piece of an arc (at most 90 degrees), Z the closing line.
Errors raise Bad("WHAT: at character K ('...'): reason").
"""
import math
import re

SVG_NS = "http://www.w3.org/2000/svg"
WSP = " \t\n\r\f"
NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")
EPS = 2.0 ** -52
HIDDEN = ("defs", "symbol", "clipPath", "mask", "marker", "pattern")
UNREAD = ("text", "image", "use")
SHAPES = ("path", "line", "polyline", "polygon", "circle", "ellipse", "rect")
UNITS = {"": 1.0, "px": 1.0, "in": 96.0, "cm": 96.0 / 2.54, "mm": 96.0 / 25.4,
         "pt": 96.0 / 72.0, "pc": 16.0}
IDENTITY = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)


class Bad(Exception):
    """Malformed geometry: the message names the attribute and the place."""


class Scan:
    """A cursor over one attribute's text (svg_path.c's ob_svgr_scan)."""

    def __init__(self, text, what):
        self.s, self.i, self.what = text, 0, what

    def fail(self, why):
        near = self.s[self.i:self.i + 12].replace("\n", " ").replace("\r", " ").replace("\t", " ")
        where = f"at character {self.i + 1} ('{near}')" if near else "at the end"
        raise Bad(f"{self.what}: {where}: {why}")

    def more(self):
        return self.i < len(self.s)

    def wsp(self):
        while self.more() and self.s[self.i] in WSP:
            self.i += 1

    def sep(self):
        self.wsp()
        if self.more() and self.s[self.i] == ",":
            self.i += 1
            self.wsp()

    def number(self):
        m = NUMBER.match(self.s, self.i)
        if not m:
            self.fail("expected a number")
        x = float(m.group(0))
        if not math.isfinite(x):
            self.fail("a number out of range")
        self.i = m.end()
        return x

    def flag(self):
        if not self.more() or self.s[self.i] not in "01":
            self.fail("expected an arc flag (0 or 1)")
        self.i += 1
        return float(self.s[self.i - 1])


# ---- maps (a, b, c, d, e, f): x' = a x + c y + e, y' = b x + d y + f

def mul(a, b):
    """a after b."""
    return (a[0] * b[0] + a[2] * b[1], a[1] * b[0] + a[3] * b[1],
            a[0] * b[2] + a[2] * b[3], a[1] * b[2] + a[3] * b[3],
            a[0] * b[4] + a[2] * b[5] + a[4], a[1] * b[4] + a[3] * b[5] + a[5])


def transform_of(fn, a):
    n, r = len(a), (a[0] * (math.pi / 180.0) if a else 0.0)
    if fn == "matrix" and n == 6:
        return tuple(a)
    if fn == "translate" and n in (1, 2):
        return (1.0, 0.0, 0.0, 1.0, a[0], a[1] if n == 2 else 0.0)
    if fn == "scale" and n in (1, 2):
        return (a[0], 0.0, 0.0, a[1] if n == 2 else a[0], 0.0, 0.0)
    if fn == "rotate" and n in (1, 3):
        rot = (math.cos(r), math.sin(r), -math.sin(r), math.cos(r), 0.0, 0.0)
        cx, cy = (a[1], a[2]) if n == 3 else (0.0, 0.0)
        return mul((1.0, 0.0, 0.0, 1.0, cx, cy), mul(rot, (1.0, 0.0, 0.0, 1.0, -cx, -cy)))
    if fn == "skewX" and n == 1:
        return (1.0, 0.0, math.tan(r), 1.0, 0.0, 0.0)
    if fn == "skewY" and n == 1:
        return (1.0, math.tan(r), 0.0, 1.0, 0.0, 0.0)
    return None


def transform(text, what):
    c, t = Scan(text, what), IDENTITY
    c.sep()
    while c.more():
        m = re.compile(r"[A-Za-z]{1,15}").match(c.s, c.i)
        c.i = m.end() if m else c.i
        c.wsp()
        if not m or not c.more() or c.s[c.i] != "(":
            c.fail("expected a transform (matrix, translate, scale, rotate, skewX, skewY) and '('")
        c.i += 1
        c.wsp()
        a = []
        while c.more() and c.s[c.i] != ")":
            if len(a) == 6:
                c.fail("too many arguments")
            a.append(c.number())
            c.sep()
        if not c.more():
            c.fail("expected ')'")
        c.i += 1
        f = transform_of(m.group(0), a)
        if f is None:
            c.fail("a transform with a wrong number of arguments, or an unknown one")
        t = mul(t, f)
        c.sep()
    return t


def length(text, what, axis, vp):
    """A length in user units (svg_frame.c's ob_svgr_length)."""
    c = Scan(text, what)
    c.wsp()
    x = c.number()
    m = re.compile(r"[A-Za-z%]*").match(c.s, c.i)
    unit = m.group(0).lower()
    if unit not in UNITS and unit != "%":
        c.fail("a unit measure does not read (lengths: user units, px, in, cm, mm, pt, pc, %)")
    at, c.i = c.i, m.end()
    c.wsp()
    if c.more():
        c.fail("text after the length")
    if unit != "%":
        return x * UNITS[unit]
    ref = math.sqrt(0.5 * (vp[0] * vp[0] + vp[1] * vp[1])) if axis == 2 else vp[axis]
    if not ref > 0:
        c.i = at
        c.fail("a percentage of a viewport whose size is not known (give the <svg> a viewBox)")
    return x * (0.01 * ref)


def viewbox(text, what):
    c = Scan(text, what)
    c.wsp()
    vb = []
    for k in range(4):
        if k:
            c.sep()
        vb.append(c.number())
    c.wsp()
    if c.more():
        c.fail("text after the four numbers")
    if not (vb[2] > 0 and vb[3] > 0):
        c.fail("a width or height not above 0")
    return vb


def viewport(box, vb_text, aspect, what):
    """A viewport box (x, y, w, h) and its viewBox: the map and the new
    viewport size (svg_frame.c's ob_svgr_viewport)."""
    if vb_text is None:
        return (1.0, 0.0, 0.0, 1.0, box[0], box[1]), (box[2], box[3])
    vb = viewbox(vb_text, f"{what}: viewBox")
    words = (aspect or "").split()
    k = 1 if words[:1] == ["defer"] else 0
    align, slice_ = [1, 1], False
    if len(words) > k and words[k] == "none":
        align = [-1, -1]
    elif len(words) > k:
        w = words[k]
        pos = {"Min": 0, "Mid": 1, "Max": 2}
        if not (len(w) == 8 and w[0] == "x" and w[4] == "Y" and w[1:4] in pos and w[5:8] in pos):
            Scan(aspect, f"{what}: preserveAspectRatio").fail("expected none or xMinYMin ... xMaxYMax")
        align = [pos[w[1:4]], pos[w[5:8]]]
    if len(words) > k + 1 and words[k + 1] not in ("meet", "slice"):
        Scan(aspect, f"{what}: preserveAspectRatio").fail("expected meet or slice")
    slice_ = len(words) > k + 1 and words[k + 1] == "slice"
    sx, sy = box[2] / vb[2], box[3] / vb[3]
    if align[0] >= 0:
        sx = sy = max(sx, sy) if slice_ else min(sx, sy)
    s = (sx, sy)
    t = [box[a] - vb[a] * s[a] + (0.5 * align[a] * (box[2 + a] - vb[2 + a] * s[a]) if align[a] > 0 else 0.0)
         for a in (0, 1)]
    return (sx, 0.0, 0.0, sy, t[0], t[1]), (vb[2], vb[3])


# ---- pieces

def arc(p0, rx, ry, phi_deg, large, sweep, p1):
    """The arc of SVG's endpoint form as pieces (svg_path.c's add_arc: in
    the frame where the ellipse is the unit circle; one piece from the
    chord and the half angle, no far centre)."""
    if p0 == p1:
        return []
    rx, ry = abs(rx), abs(ry)
    if rx == 0 or ry == 0:
        return [("L", [p0 + (1.0,), p1 + (1.0,)])]
    phi = math.fmod(phi_deg, 360.0) * (math.pi / 180.0)
    cp, sp = math.cos(phi), math.sin(phi)
    mid = (0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1]))
    dx2, dy2 = 0.5 * (p0[0] - p1[0]), 0.5 * (p0[1] - p1[1])
    ux, uy = (cp * dx2 + sp * dy2) / rx, (-sp * dx2 + cp * dy2) / ry
    s = math.hypot(ux, uy)
    if s == 0:
        return [("L", [p0 + (1.0,), p1 + (1.0,)])]
    if s >= 1:
        rx, ry, ux, uy, s = rx * s, ry * s, ux / s, uy / s, 1.0

    def point(u):
        return (mid[0] + cp * rx * u[0] - sp * ry * u[1], mid[1] + sp * rx * u[0] + cp * ry * u[1])

    c = 0.0 if s == 1.0 else math.sqrt(max(0.0, 1.0 - ux * ux - uy * uy))
    sgn = 1.0 if large != sweep else -1.0
    theta = 2.0 * math.pi - 2.0 * math.atan2(s, c) if large else 2.0 * math.atan2(s, c)
    n = max(1, math.ceil(theta / (0.5 * math.pi) - 1e-9))
    if n == 1:
        q1 = point((-sgn * uy * s / c, sgn * ux * s / c))
        if math.hypot(q1[0] - mid[0], q1[1] - mid[1]) <= EPS * math.hypot(dx2, dy2):
            return [("L", [p0 + (1.0,), p1 + (1.0,)])]
        return [("A", [p0 + (1.0,), q1 + (c,), p1 + (1.0,)])]
    cu = (sgn * c * uy / s, -sgn * c * ux / s)
    t1 = math.atan2(uy - cu[1], ux - cu[0])
    h = 0.5 * (theta if sweep else -theta) / n
    out, prev = [], p0
    for i in range(n):
        a0 = t1 + 2.0 * h * i
        q1 = point((cu[0] + math.cos(a0 + h) / math.cos(h), cu[1] + math.sin(a0 + h) / math.cos(h)))
        q2 = point((cu[0] + math.cos(a0 + 2.0 * h), cu[1] + math.sin(a0 + 2.0 * h))) if i < n - 1 else p1
        out.append(("A", [prev + (1.0,), q1 + (math.cos(h),), q2 + (1.0,)]))
        prev = q2
    return out


def line(p0, p1, letter="L"):
    return [(letter, [p0 + (1.0,), p1 + (1.0,)])]


PATH_ARGS = {"M": "nn", "L": "nn", "T": "nn", "H": "n", "V": "n", "C": "nnnnnn",
             "S": "nnnn", "Q": "nnnn", "A": "nnnffnn", "Z": ""}


class Subpaths:
    """Collects an element's subpaths: lists of (segment number, kind,
    pieces) and a closed flag, as svg2curves.py groups them into curves."""

    def __init__(self):
        self.out, self.cur, self.closed, self.num = [], None, False, 0

    def move(self):
        if self.cur:
            self.out.append((self.cur, self.closed))
        self.cur, self.closed = [], False

    def add(self, kind, pieces):
        self.num += 1
        if self.cur is None or self.closed:  # a command after Z starts a new subpath
            self.move()
        self.cur.append((self.num, kind, pieces))
        if kind == "Z":
            self.closed = True

    def done(self):
        self.move()
        return self.out


def command(sub, pen, up, rel, a):
    """One path command (svg_path.c's command)."""
    cur = pen["cur"]
    ox, oy = cur if rel else (0.0, 0.0)
    end = cur
    if up == "M":
        end = pen["start"] = (a[0] + ox, a[1] + oy)
        sub.move()
    elif up in "LHV":
        end = (cur[0] if up == "V" else a[0] + ox,
               cur[1] if up == "H" else a[0] + oy if up == "V" else a[1] + oy)
        sub.add("L", line(cur, end) if end != cur else [])
    elif up in "CSQT":
        cubic, smooth = up in "CS", up in "ST"
        q = [cur]
        if smooth:
            reflect = pen["last"] == ("C" if cubic else "Q")
            c = pen["ctrl"]
            q.append((2.0 * cur[0] - c[0], 2.0 * cur[1] - c[1]) if reflect else cur)
        for k in range(0, len(a), 2):
            q.append((a[k] + ox, a[k + 1] + oy))
        end, deg = q[-1], len(q) - 1
        pen["ctrl"] = q[deg - 1]
        same = all(p == q[0] for p in q)
        sub.add("C" if cubic else "Q", [] if same else [("C" if cubic else "Q", [p + (1.0,) for p in q])])
    elif up == "A":
        end = (a[5] + ox, a[6] + oy)
        sub.add("A", arc(cur, a[0], a[1], a[2], a[3] != 0, a[4] != 0, end))
    else:
        end = pen["start"]
        sub.add("Z", line(cur, end, "Z") if end != cur else [])
    pen["cur"] = end
    pen["last"] = {"S": "C", "T": "Q"}.get(up, up)


def path(d, what):
    """Path data d (SVG 1.1 8.3.9) as subpaths (svg_path.c's ob_svgr_path)."""
    c, sub = Scan(d, what), Subpaths()
    pen = {"cur": (0.0, 0.0), "start": (0.0, 0.0), "ctrl": (0.0, 0.0), "last": ""}
    cmd = ""
    c.wsp()
    while c.more():
        ch = c.s[c.i]
        if ch.isalpha():
            if ch.upper() not in PATH_ARGS:
                c.fail("not a path command (M L H V C S Q T A Z, or lower case)")
            if not cmd and ch.upper() != "M":
                c.fail("path data must begin with M or m")
            cmd = ch
            c.i += 1
            c.wsp()
        elif not cmd or cmd.upper() == "Z" or not (ch.isdigit() or ch in ".+-"):
            c.fail("expected a command" if cmd else "path data must begin with M or m")
        up, a = cmd.upper(), []
        for k, kind in enumerate(PATH_ARGS[up]):
            if k:
                c.sep()
            a.append(c.flag() if kind == "f" else c.number())
        command(sub, pen, up, cmd.islower(), a)
        if up == "M":
            cmd = "l" if cmd == "m" else "L"
        if up != "Z":
            c.sep()
        else:
            c.wsp()
    return sub.done()


def points(text, what, closed):
    """A polyline's or polygon's points (svg_path.c's ob_svgr_points)."""
    c, sub, pts = Scan(text, what), Subpaths(), []
    c.wsp()
    while c.more():
        x = c.number()
        c.sep()
        y = c.number()
        c.sep()
        if pts:
            sub.add("L", line(pts[-1], (x, y)) if (x, y) != pts[-1] else [])
        else:
            sub.move()
        pts.append((x, y))
    if closed and len(pts) > 1 and pts[-1] != pts[0]:
        sub.add("Z", line(pts[-1], pts[0], "Z"))
    return sub.done()


def ellipse(cx, cy, rx, ry):
    """SVG 2 (10.4): from (cx + rx, cy) four quarter arcs of sweep 1."""
    p = [(cx + rx, cy), (cx, cy + ry), (cx - rx, cy), (cx, cy - ry), (cx + rx, cy)]
    sub = Subpaths()
    sub.move()
    for k in range(4):
        sub.add("A", arc(p[k], rx, ry, 0.0, False, True, p[k + 1]))
    sub.closed = True
    return sub.done()


def rect(x, y, w, h, rx, ry):
    """SVG 2 (10.2): from (x + rx, y) along the top, corners quarter arcs."""
    X, Y = x + w, y + h
    p = [(x + rx, y), (X - rx, y), (X, y + ry), (X, Y - ry), (X - rx, Y),
         (x + rx, Y), (x, Y - ry), (x, y + ry), (x + rx, y)]
    sub = Subpaths()
    sub.move()
    for k in range(8):
        if p[k] != p[k + 1]:
            sub.add("A", arc(p[k], rx, ry, 0.0, False, True, p[k + 1])) if k % 2 else sub.add("L", line(p[k], p[k + 1]))
    sub.closed = True
    return sub.done()


# ---- the elements (approx_read_svg.c's walk)

class Shape:
    """One shape element: its tag, id, map to the file's coordinates and
    subpaths (local coordinates)."""

    def __init__(self, tag, eid, ctm, subs):
        self.tag, self.id, self.ctm, self.subs = tag, eid, ctm, subs


def local(tag):
    """The local name of an element in the SVG namespace or none, else None."""
    if not isinstance(tag, str):
        return None  # a comment or processing instruction
    if tag.startswith("{"):
        ns, _, name = tag[1:].partition("}")
        return name if ns == SVG_NS else None
    return tag


def prop(el, key):
    """A presentation property: the style attribute's, else the attribute's;
    lower case, trimmed (approx_read_svg.c's property)."""
    v = el.get(key)
    for decl in (el.get("style") or "").split(";"):
        k, colon, val = decl.partition(":")
        if colon and k.strip().lower() == key:
            v = val
    if v is None:
        return None
    return v.split("!")[0].strip().lower()


def lengths(el, what, keys, axes, vp):
    return [length(el.get(k), f"{what}: {k}", a, vp) if el.get(k) is not None else None
            for k, a in zip(keys, axes)]


def basic(el, tag, vp, note, name):
    """<circle>, <ellipse>, <rect>: SVG 2's rules (approx_read_svg.c's basic_shape)."""
    keys = {"circle": ("cx", "cy", "r"), "ellipse": ("cx", "cy", "rx", "ry"),
            "rect": ("x", "y", "width", "height", "rx", "ry")}[tag]
    axes = {"circle": (0, 1, 2), "ellipse": (0, 1, 0, 1), "rect": (0, 1, 0, 1, 0, 1)}[tag]
    got = lengths(el, f"<{tag}>", keys, axes, vp)
    v = [0.0 if g is None else g for g in got]
    for k in range(2, len(keys)):
        if v[k] < 0:
            raise Bad(f"<{tag}>: {keys[k]}: negative ({v[k]!r})")
    rx, ry = v[2], (v[2] if tag == "circle" else v[3])
    if tag == "ellipse" and (got[2] is None) != (got[3] is None):
        rx = ry = v[2] if got[2] is not None else v[3]
    if tag == "rect":
        rx = v[4] if got[4] is not None else v[5] if got[5] is not None else 0.0
        ry = v[5] if got[5] is not None else rx
        rx, ry = min(rx, 0.5 * v[2]), min(ry, 0.5 * v[3])
        if rx == 0 or ry == 0:
            rx = ry = 0.0
    w, h = (v[2], v[3]) if tag == "rect" else (rx, ry)
    if w == 0 or h == 0:
        note(f"{name}: zero size; left out")
        return []
    return rect(v[0], v[1], v[2], v[3], rx, ry) if tag == "rect" else ellipse(v[0], v[1], rx, ry)


def shape_subpaths(el, tag, vp, note, name):
    if tag in ("circle", "ellipse", "rect"):
        return basic(el, tag, vp, note, name)
    if tag == "line":
        v = [0.0 if g is None else g for g in lengths(el, "<line>", ("x1", "y1", "x2", "y2"), (0, 1, 0, 1), vp)]
        sub = Subpaths()
        sub.add("L", line((v[0], v[1]), (v[2], v[3])) if v[:2] != v[2:] else [])
        return sub.done()
    key = "d" if tag == "path" else "points"
    text = el.get(key)
    if text is None:
        return []
    return path(text, f"<{tag}>: d") if tag == "path" else points(text, f"<{tag}>: points", tag == "polygon")


def element_state(el, tag, st, depth, units, note):
    """The element's state from its parent's (approx_read_svg.c's element_state)."""
    st = dict(st)
    if prop(el, "display") == "none" and not st["unrendered"]:
        note(f"<{tag}>: display:none; left out with what it holds")
        st["unrendered"] = True
    st["unrendered"] = st["unrendered"] or tag in HIDDEN
    vis = prop(el, "visibility")
    if vis in ("hidden", "collapse", "visible"):
        st["invisible"] = vis != "visible"
    if el.get("transform") is not None:
        st["ctm"] = mul(st["ctm"], transform(el.get("transform"), f"<{tag}>: transform"))
    if tag != "svg":
        return st
    if depth == 0:
        return root_state(el, st, units)
    box = lengths(el, "<svg>", ("x", "y", "width", "height"), (0, 1, 0, 1), st["vp"])
    box = [box[0] or 0.0, box[1] or 0.0] + [st["vp"][k] if box[2 + k] is None else box[2 + k] for k in (0, 1)]
    if not (box[2] > 0 and box[3] > 0):
        if not st["unrendered"]:
            note("<svg>: zero size; left out with what it holds")
        st["unrendered"] = True
        return st
    t, st["vp"] = viewport(box, el.get("viewBox"), el.get("preserveAspectRatio"), "<svg>")
    st["ctm"] = mul(st["ctm"], t)
    return st


def root_state(el, st, units):
    """The root's viewport size; with units px, its viewBox applied too."""
    try:
        size = [length(el.get(k), "<svg>", a, (0.0, 0.0)) if el.get(k) is not None else 0.0
                for k, a in (("width", 0), ("height", 1))]
    except Bad:  # 100%, em: the size is not known
        size = [0.0, 0.0]
    vb = el.get("viewBox")
    if vb is None:
        st["vp"] = tuple(size)
        return st
    v = viewbox(vb, "<svg>: viewBox")
    st["vp"] = (v[2], v[3])
    if units == "px" and size[0] > 0 and size[1] > 0:
        t, _ = viewport([0.0, 0.0] + size, vb, el.get("preserveAspectRatio"), "<svg>")
        st["ctm"] = mul(st["ctm"], t)
    return st


def shapes(root, units, note):
    """The shapes of the document under root, in document order, and notes
    (note(msg)) for what is left out."""
    out = []

    def walk(el, st, depth):
        tag = local(el.tag)
        if tag is not None:
            st = element_state(el, tag, st, depth, units, note)
            eid = el.get("id")
            name = f'<{tag} id="{eid}">' if eid else f"<{tag}>"
            if not st["unrendered"] and tag in UNREAD:
                note(f"{name}: unsupported element ({tag}); left out")
            elif not st["unrendered"] and tag in SHAPES:
                if st["invisible"]:
                    note(f"{name}: visibility hidden; left out")
                else:
                    out.append(Shape(tag, eid, st["ctm"], shape_subpaths(el, tag, st["vp"], note, name)))
        for ch in el:
            walk(ch, st, depth + 1)

    if local(root.tag) != "svg":
        raise Bad(f"the root element is <{root.tag}>, not <svg>: not an SVG document")
    walk(root, {"ctm": IDENTITY, "vp": (0.0, 0.0), "unrendered": False, "invisible": False}, 0)
    return out
