#!/usr/bin/python3
"""Convert the paths of an SVG file to a .curves file that offbench reads.

Usage: scripts/svg2curves.py FILE.svg --d D[,D...] [--out FILE.curves]
                             [--y up|down] [--units user|px] [--closed open|skip]
                             [--prefix P] [--strict]

The SVG is parsed by svgelements (Debian: python3-svgelements).  Every
<path>, <line>, <polyline>, <polygon>, <rect>, <circle> and <ellipse> is read
with the transforms of the element and of its groups applied; each subpath
becomes one curve (family `svg`), its id the element's id made safe for the
.curves reader (a suffix .N for subpath N when the element has several).
Segments: a line is a degree-1 Bezier segment, a quadratic or cubic Bezier
its own segment, an elliptical arc one exact rational quadratic per piece of
at most 90 degrees (weight cos(theta/2) on the middle point).  A curve has one
degree in the .curves format, so in a subpath that mixes degrees the lower
ones are degree-elevated (exactly: the same point at every parameter); one
segment is written as `bezier`, several as a `bspline` whose interior knots
have full multiplicity (each knot span one SVG segment or arc piece, so the
B-spline is exactly the SVG subpath, C0 at the joins).  See docs/curves.md,
"Curve files" / "SVG paths to .curves".

Exit status: 0 when a .curves file was written (notes on stderr name every
element or segment that was left out or changed), 1 with --strict when
anything was left out (nothing written), 2 on bad input or options, or when
no curve could be converted.
"""
import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import svgsyntax

PROG = "svg2curves"
VALUE_LIMIT = 1e12   # host/io/curvefile.c: |numbers| <= 1e12
SCALE_MIN = 1e-50    # smallest nonzero coordinate, weight, |d|, extent
SCALE_REL = 1e-12    # smallest extent and |d| relative to the largest coordinate
MAX_IDLEN = 63
MAX_POINTS = 10000
MAX_OFFSETS = 1000
ARC_PIECE = math.pi / 2  # largest arc piece, radians
SVG_NS = "http://www.w3.org/2000/svg"
SHAPE_TAGS = ("path", "line", "polyline", "polygon", "rect", "circle", "ellipse")
# elements that draw nothing themselves, or whose content svgelements expands
# (use) or leaves unrendered (defs, symbol, clipPath, ...): never reported
QUIET_TAGS = ("svg", "g", "defs", "title", "desc", "metadata", "style", "symbol",
              "use", "clipPath", "mask", "marker", "pattern", "linearGradient",
              "radialGradient", "stop", "filter", "script", "switch", "a")
HIDDEN_TAGS = ("defs", "symbol", "clipPath", "mask", "marker", "pattern")


class Refused(Exception):
    """A curve the .curves reader would refuse (message says which rule)."""


class BadInput(Exception):
    """The SVG file cannot be converted (message says what is wrong): exit 2."""


def fmt(x):
    """A double as the shortest text that reads back to it (C strtod)."""
    if x == 0:
        return "0"
    s = repr(float(x))
    return s[:-2] if s.endswith(".0") else s


# ---- 2x3 affine maps (a, b, c, d, e, f): x' = a x + c y + e, y' = b x + d y + f

def mat_of(m):
    return (float(m.a), float(m.b), float(m.c), float(m.d), float(m.e), float(m.f))


def mat_apply(m, x, y):
    a, b, c, d, e, f = m
    return (a * x + c * y + e, b * x + d * y + f)


def mat_then(m, n):
    """The map: first m, then n."""
    a, b, c, d, e, f = m
    A, B, C, D, E, F = n
    return (A * a + C * b, B * a + D * b, A * c + C * d, B * c + D * d,
            A * e + C * f + E, B * e + D * f + F)


def mat_inverse(m):
    a, b, c, d, e, f = m
    det = a * d - b * c
    if det == 0 or not math.isfinite(det):
        return None
    ia, ib, ic, id_ = d / det, -b / det, -c / det, a / det
    return (ia, ib, ic, id_, -(ia * e + ic * f), -(ib * e + id_ * f))


# ---- segments: (letter, [(x, y, w), ...]) rational Bezier control points

def arc_center(seg, u, v):
    """The centre of the ellipse of axes u, v (orthogonal) through the arc's
    two ends, the one nearer svgelements' centre.  svgelements computes it
    with sqrt(1 - lambda), which after its scaling of too-small radii (SVG
    1.1, Appendix F.6.6) is the square root of round-off: centres 1e-8 of
    the radius off the chord's midpoint.  Here, in the frame where the
    ellipse is the unit circle, lambda within 1e-12 of 1 is that case and
    puts the centre on the midpoint."""
    rx, ry = math.hypot(*u), math.hypot(*v)
    eu, ev = (u[0] / rx, u[1] / rx), (v[0] / ry, v[1] / ry)
    mx, my = (seg.start.x + seg.end.x) / 2, (seg.start.y + seg.end.y) / 2
    hx, hy = (seg.start.x - seg.end.x) / 2, (seg.start.y - seg.end.y) / 2
    dx, dy = (hx * eu[0] + hy * eu[1]) / rx, (hx * ev[0] + hy * ev[1]) / ry  # unit-circle frame
    lam = dx * dx + dy * dy
    k = math.sqrt((1 - lam) / lam) if 0 < lam < 1 - 1e-12 else 0.0
    best = None
    for sgn in (1.0, -1.0):  # centre m + k perp(d), back from the unit-circle frame
        px, py = -sgn * k * dy * rx, sgn * k * dx * ry
        c = (mx + px * eu[0] + py * ev[0], my + px * eu[1] + py * ev[1])
        dist = math.hypot(c[0] - seg.center.x, c[1] - seg.center.y)
        if best is None or dist < best[0]:
            best = (dist, c)
    return best[1]


def arc_pieces(seg):
    """An svgelements Arc (local coordinates) as rational quadratics of at
    most 90 degrees each, or [] when it has no extent.  The ellipse is
    E(t) = c + u cos t + v sin t, u = prx - c, v = pry - c (svgelements'
    axes, orthogonal in the path's own coordinates; c from arc_center); a piece [a, b] of half-angle h = (b - a)/2 has the end points
    E(a), E(b) and the middle point c + (u cos m + v sin m)/cos h with weight
    cos h, m = (a + b)/2: the standard circle-arc form (Piegl & Tiller, The
    NURBS Book, 1997, Section 7.5) mapped by the affine map of the unit circle
    onto the ellipse."""
    c = (seg.center.x, seg.center.y)
    u = (seg.prx.x - c[0], seg.prx.y - c[1])
    v = (seg.pry.x - c[0], seg.pry.y - c[1])
    det = u[0] * v[1] - u[1] * v[0]
    sweep = float(seg.sweep or 0.0)
    if det == 0 or sweep == 0 or not math.isfinite(sweep):
        return []
    c = arc_center(seg, u, v)
    sx, sy = seg.start.x - c[0], seg.start.y - c[1]
    cos0 = (sx * v[1] - sy * v[0]) / det  # solve (sx, sy) = u cos t0 + v sin t0
    sin0 = (u[0] * sy - u[1] * sx) / det
    t0 = math.atan2(sin0, cos0)
    n = max(1, math.ceil(abs(sweep) / ARC_PIECE - 1e-9))
    step = sweep / n
    E = lambda t: (c[0] + u[0] * math.cos(t) + v[0] * math.sin(t),
                   c[1] + u[1] * math.cos(t) + v[1] * math.sin(t))
    out = []
    for k in range(n):
        a, b = t0 + k * step, t0 + (k + 1) * step
        h, m = (b - a) / 2, (a + b) / 2
        p0 = (seg.start.x, seg.start.y) if k == 0 else E(a)
        p2 = (seg.end.x, seg.end.y) if k == n - 1 else E(b)
        ch = math.cos(h)
        p1 = (c[0] + (u[0] * math.cos(m) + v[0] * math.sin(m)) / ch,
              c[1] + (u[1] * math.cos(m) + v[1] * math.sin(m)) / ch)
        out.append([(p0[0], p0[1], 1.0), (p1[0], p1[1], ch), (p2[0], p2[1], 1.0)])
    return out


def pt(p):
    return (float(p.x), float(p.y), 1.0)


def local_segments(seg, se):
    """One svgelements segment as a list of (letter, control points) in local
    coordinates; [] when it has zero length."""
    if isinstance(seg, se.Arc):
        pieces = arc_pieces(seg)
        if pieces:
            return [("A", p) for p in pieces]
        if seg.start != seg.end:  # rx or ry 0: a line (SVG 1.1, Appendix F.6.2)
            return [("L", [pt(seg.start), pt(seg.end)])]
        return []
    if isinstance(seg, se.CubicBezier):
        cps, letter = [seg.start, seg.control1, seg.control2, seg.end], "C"
    elif isinstance(seg, se.QuadraticBezier):
        cps, letter = [seg.start, seg.control, seg.end], "Q"
    else:  # Line, Close
        cps, letter = [seg.start, seg.end], "Z" if isinstance(seg, se.Close) else "L"
    pts = [pt(p) for p in cps]
    if all(p[:2] == pts[0][:2] for p in pts):
        return []
    return [(letter, pts)]


def elevate(pts, deg):
    """Degree elevation of a rational Bezier segment (homogeneous points),
    repeated up to degree deg: the same curve, point for point."""
    h = [(x * w, y * w, w) for x, y, w in pts]
    while len(h) - 1 < deg:
        n = len(h) - 1
        g = [h[0]]
        for i in range(1, n + 1):
            a = i / (n + 1)
            g.append(tuple(a * h[i - 1][q] + (1 - a) * h[i][q] for q in range(3)))
        g.append(h[n])
        h = g
    return [(X / W, Y / W, W) for X, Y, W in h]


# ---- the document

def element_name(e, tag, index):
    return f'<{tag} id="{e.id}">' if e.id else f"<{tag}> (shape {index} of the document)"


def tag_of(e, se):
    for cls, tag in ((se.Path, "path"), (se.SimpleLine, "line"), (se.Polygon, "polygon"),
                     (se.Polyline, "polyline"), (se.Rect, "rect"), (se.Circle, "circle"),
                     (se.Ellipse, "ellipse")):
        if isinstance(e, cls):
            return tag
    return type(e).__name__.lower()


def subpaths(e, se):
    """The element's subpaths: lists of (svg segment number, segment) and a
    closed flag; segments in local (untransformed) coordinates."""
    segs = e.segments(transformed=False) if not isinstance(e, se.Path) else list(e)
    out, cur, closed, num = [], None, False, 0
    for s in segs:
        if isinstance(s, se.Move):
            if cur:
                out.append((cur, closed))
            cur, closed = [], False
            continue
        num += 1
        if cur is None or closed:  # a command after Z starts a new subpath
            if cur:
                out.append((cur, closed))
            cur, closed = [], False
        cur.append((num, s))
        if isinstance(s, se.Close):
            closed = True
    if cur:
        out.append((cur, closed))
    return out


def safe_id(s):
    return re.sub(r"[^A-Za-z0-9_./-]", "_", s)


def safe_text(s):
    """Text for a `source` line: printable, no '#' (a comment there)."""
    return "".join(ch if ch.isprintable() and ch != "#" else "_" for ch in s)[:300]


class Converter:
    def __init__(self, args, se, note):
        self.a, self.se, self.note = args, se, note
        self.curves, self.ids, self.left_out = [], set(), 0

    def skip(self, msg):
        self.left_out += 1
        self.note(msg)

    def output_map(self, e, root_inv):
        m = mat_of(e.transform)
        if root_inv is not None:
            m = mat_then(m, root_inv)
        if self.a.y == "up":
            m = mat_then(m, (1.0, 0.0, 0.0, -1.0, 0.0, 0.0))
        return m

    def unique_id(self, base, name):
        cid, k = base, 1
        while cid in self.ids:
            k += 1
            suffix = f"-{k}"
            cid = base[:MAX_IDLEN - len(suffix)] + suffix
        if cid != base:
            self.note(f"{name}: id '{base}' already used; written as '{cid}'")
        self.ids.add(cid)
        return cid

    def element(self, e, index, root_inv):
        tag = tag_of(e, self.se)
        name = element_name(e, tag, index)
        m = self.output_map(e, root_inv)
        subs = subpaths(e, self.se)
        base = self.a.prefix + (safe_id(e.id) if e.id else f"{tag}{index}")
        if e.id and base != e.id:
            self.note(f"{name}: id has characters the .curves reader refuses; written as '{base}'")
        for k, (segs, closed) in enumerate(subs, 1):
            where = name if len(subs) == 1 else f"{name} subpath {k}"
            if closed and self.a.closed == "skip":
                self.skip(f"{where}: closed subpath left out (--closed skip)")
                continue
            pieces = self.pieces(segs, m, where)
            if not pieces:
                self.skip(f"{where}: no segment of nonzero length; left out")
                continue
            if closed:
                self.note(f"{where}: closed subpath written as an open curve from its first point "
                          f"back to it (--closed skip leaves it out)")
            suffix = f".{k}" if len(subs) > 1 else ""
            cid = self.unique_id(base[:MAX_IDLEN - len(suffix)] + suffix, where)
            try:
                self.curves.append(self.curve(cid, where, pieces))
            except Refused as r:
                self.ids.discard(cid)
                self.skip(f"{where}: left out, the .curves reader would refuse it: {r}")

    def pieces(self, segs, m, where):
        """The subpath's segments mapped to the output coordinates, those of
        zero length (there) left out with a note; a closing segment (Z) of
        zero length, or shorter than 1e-12 times the largest coordinate (the
        round-off of the arcs before it), is left out silently."""
        out = []
        for num, s in segs:
            got = [(num, letter, [mat_apply(m, x, y) + (w,) for x, y, w in p])
                   for letter, p in local_segments(s, self.se)]
            got = [g for g in got if any(q[:2] != g[2][0][:2] for q in g[2])]
            if not got and not isinstance(s, self.se.Close):
                self.skip(f"{where}: segment {num} ({type(s).__name__}) has zero length; left out")
            out += got
        if out and out[-1][1] == "Z":
            M = max(abs(v) for _, _, p in out for q in p for v in q[:2])
            z = out[-1][2]
            if max(abs(z[1][q] - z[0][q]) for q in (0, 1)) < SCALE_REL * M:
                out.pop()
        return out

    def curve(self, cid, where, pieces):
        """The text of one curve block (raises Refused)."""
        deg = max(len(p) - 1 for _, _, p in pieces)
        segs = [elevate(p, deg) for _, _, p in pieces]
        for k in range(1, len(segs)):
            if segs[k][0][:2] != segs[k - 1][-1][:2]:
                raise Refused(f"its segments {k - 1} and {k} do not join")
        pts = [segs[0][0]] + [q for s in segs for q in s[1:]]
        check_curve(pts, segs, self.a.d)
        if len(pts) > MAX_POINTS:
            raise Refused(f"{len(pts)} control points (the reader takes at most {MAX_POINTS}; "
                          f"split the path)")
        lines = [f"curve {cid}",
                 f"  source svg2curves {safe_text(os.path.basename(self.a.svg))} {safe_text(where)}",
                 "  family svg"]
        for k, (num, letter, _) in enumerate(pieces):
            lines.append(f"  # span {k}: SVG segment {num} ({letter})")
        if len(segs) == 1:
            lines.append(f"  bezier {deg}")
        else:
            knots = [0] * (deg + 1) + [i for i in range(1, len(segs)) for _ in range(deg)] \
                + [len(segs)] * (deg + 1)
            lines.append(f"  bspline {deg}")
            for i in range(0, len(knots), 32):  # the reader's lines are <= 4096 bytes
                lines.append("  knots " + " ".join(str(u) for u in knots[i:i + 32]))
        for x, y, w in pts:
            lines.append(f"  point {fmt(x)} {fmt(y)}" + ("" if w == 1.0 else f" {fmt(w)}"))
        lines.append("  offset " + " ".join(fmt(d) for d in self.a.d))
        lines.append("end")
        return "\n".join(lines) + "\n"


def check_curve(pts, segs, offsets):
    """The reader's scale rules (host/io/curvefile.c, docs/curves.md "Curve files")."""
    M = 0.0
    for x, y, w in pts:
        for v in (x, y):
            if not math.isfinite(v) or abs(v) > VALUE_LIMIT:
                raise Refused(f"coordinate {v!r} is beyond +-1e12")
            if v != 0 and abs(v) < SCALE_MIN:
                raise Refused(f"coordinate {v!r} is nonzero but below 1e-50")
            M = max(M, abs(v))
        if not w >= SCALE_MIN:
            raise Refused(f"weight {w!r} is below 1e-50")
    for k, s in enumerate(segs):
        ext = max(max(p[q] for p in s) - min(p[q] for p in s) for q in (0, 1))
        if not (ext >= SCALE_MIN and ext >= SCALE_REL * M):
            raise Refused(f"its segment {k} spans {ext:.3g}, below 1e-12 times the largest "
                          f"coordinate {M:.3g}")
    for d in offsets:
        if not abs(d) >= SCALE_REL * M:
            raise Refused(f"offset {d!r} is below 1e-12 times its largest coordinate {M:.3g}")


def read_xml(path):
    """The document's root element, or raises BadInput saying why it is not
    an SVG document whose geometry attributes are well formed (svgelements
    would drop what follows an error unreported: svgsyntax.py)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as ex:
        raise BadInput(f"cannot read: {ex.strerror or ex}")
    if not data.strip():
        raise BadInput("empty file (no XML)")
    try:
        root = ET.fromstring(data)
    except ET.ParseError as ex:
        raise BadInput(f"not well-formed XML ({ex})")
    except (ValueError, LookupError) as ex:  # an unknown or wrong encoding declared
        raise BadInput(f"cannot decode the XML ({ex})")
    if root.tag not in ("{" + SVG_NS + "}svg", "svg"):
        raise BadInput(f"the root element is <{root.tag}>, not <svg>: not an SVG document")
    bad = svgsyntax.syntax_errors(root, SVG_NS)
    if bad:
        raise BadInput("; ".join(bad[:5]) + (f"; and {len(bad) - 5} more" if len(bad) > 5 else ""))
    return root


def xml_report(root, seen_ids, note):
    """Elements svgelements does not turn into geometry: unsupported or
    unknown SVG elements, and shapes it drops unreported (zero size)."""
    def walk(el, hidden):
        if not isinstance(el.tag, str) or not el.tag.startswith("{" + SVG_NS + "}"):
            return  # comments, other namespaces (inkscape:, sodipodi:)
        tag = el.tag[len(SVG_NS) + 2:]
        style = (el.get("style") or "").replace(" ", "")
        if el.get("display") == "none" or "display:none" in style:
            return
        eid = el.get("id")
        name = f'<{tag} id="{eid}">' if eid else f"<{tag}>"
        if tag in SHAPE_TAGS:
            if not hidden and eid is not None and eid not in seen_ids:
                note(f"{name}: the SVG parser dropped it (zero size or invalid); left out")
        elif tag in ("text", "image", "foreignObject", "tspan", "textPath"):
            if tag not in ("tspan", "textPath"):
                note(f"{name}: unsupported element ({tag}); left out")
            return
        elif tag not in QUIET_TAGS:
            note(f"{name}: unknown element; left out")
        for ch in el:
            walk(ch, hidden or tag in HIDDEN_TAGS)

    walk(root, False)


def parse_offsets(s):
    out = []
    for tok in s.split(","):
        try:
            d = float(tok)
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{tok}' is not a number")
        if not math.isfinite(d) or d == 0 or abs(d) > VALUE_LIMIT or abs(d) < SCALE_MIN:
            raise argparse.ArgumentTypeError(f"{tok}: every d must be nonzero, finite and "
                                             f"of magnitude 1e-50 to 1e12")
        if d in out:
            raise argparse.ArgumentTypeError(f"{tok} given twice (every d of a curve must differ)")
        out.append(d)
    if len(out) > MAX_OFFSETS:
        raise argparse.ArgumentTypeError(f"more than {MAX_OFFSETS} offsets")
    return out


def parse_args(argv):
    p = argparse.ArgumentParser(prog="scripts/svg2curves.py",
                                description="Convert the paths of an SVG file to a .curves file.")
    p.add_argument("svg", help="the SVG file")
    p.add_argument("--d", type=parse_offsets, required=True, metavar="D[,D...]",
                   help="offset distances of every curve (required; d > 0 on the left of the "
                        "direction of travel)")
    p.add_argument("--out", default="-", help="the .curves file (default: standard output)")
    p.add_argument("--y", choices=("up", "down"), default="up",
                   help="up (default): y = -y_svg, so the curve looks as drawn in a browser; "
                        "down: SVG's coordinates as they are")
    p.add_argument("--units", choices=("user", "px"), default="user",
                   help="user (default): the units of the root viewBox; px: CSS pixels "
                        "(the root's width/height scaling applied, 96 per inch)")
    p.add_argument("--closed", choices=("open", "skip"), default="open",
                   help="open (default): a closed subpath is written as an open curve back to "
                        "its first point; skip: left out")
    p.add_argument("--prefix", default="", help="prefix of every curve id")
    p.add_argument("--strict", action="store_true",
                   help="fail (exit 1, nothing written) when anything is left out")
    return p.parse_args(argv)


def main(argv):
    # file names are bytes: one that is not UTF-8 is printed as it was given
    sys.stderr.reconfigure(errors="surrogateescape")
    a = parse_args(argv)
    try:
        import svgelements as se
    except ImportError:
        print(f"{PROG}: cannot import svgelements: install python3-svgelements "
              f"(apt-get install python3-svgelements)", file=sys.stderr)
        return 2
    if a.prefix and (safe_id(a.prefix) != a.prefix or len(a.prefix) > 40):
        print(f"{PROG}: --prefix '{a.prefix[:50]}': at most 40 of letters, digits, '_', '-', '.', '/'",
              file=sys.stderr)
        return 2
    try:
        return convert(a, se)
    except Exception as ex:  # a case the checks miss: still "FILE: what", exit 2, no traceback
        print(f"{PROG}: {a.svg}: cannot convert ({type(ex).__name__}: {str(ex)[:200]})", file=sys.stderr)
        return 2


def convert(a, se):
    """Converts a.svg to a.out; the exit status."""
    def note(msg):
        print(f"{PROG}: {a.svg}: {msg}", file=sys.stderr)

    if not os.path.isfile(a.svg):
        print(f"{PROG}: {a.svg}: not a readable file", file=sys.stderr)
        return 2
    try:
        root = read_xml(a.svg)
    except BadInput as ex:
        print(f"{PROG}: {a.svg}: {ex}", file=sys.stderr)
        return 2
    try:
        doc = se.SVG.parse(a.svg, reify=False)
    except Exception as ex:  # svgelements raises many kinds on bad XML
        print(f"{PROG}: {a.svg}: cannot parse the SVG: {ex}", file=sys.stderr)
        return 2
    if not isinstance(doc, se.SVG):
        print(f"{PROG}: {a.svg}: no <svg> root element", file=sys.stderr)
        return 2
    root_inv = None
    if a.units == "user" and doc.viewbox_transform:
        root_inv = mat_inverse(mat_of(se.Matrix(doc.viewbox_transform)))
    conv = Converter(a, se, note)
    shapes = [e for e in doc.elements() if isinstance(e, se.Shape) and not isinstance(e, se.Image)]
    for i, e in enumerate(shapes, 1):
        try:
            conv.element(e, i, root_inv)
        except Exception as ex:  # whatever svgelements hands over: named, never a crash
            conv.skip(f"{element_name(e, tag_of(e, se), i)}: cannot convert ({ex}); left out")
    xml_report(root, {e.id for e in shapes if e.id}, conv.skip)
    if not conv.curves:
        print(f"{PROG}: {a.svg}: no curve to write", file=sys.stderr)
        return 2
    if a.strict and conv.left_out:
        print(f"{PROG}: {a.svg}: --strict: {conv.left_out} thing(s) left out (above); nothing written",
              file=sys.stderr)
        return 1
    text = (f"# written by scripts/svg2curves.py from {safe_text(os.path.basename(a.svg))} "
            f"(--y {a.y}, --units {a.units}, --closed {a.closed})\n\n" + "\n".join(conv.curves))
    if a.out == "-":
        try:
            sys.stdout.write(text)
            sys.stdout.flush()
        except OSError as ex:
            print(f"{PROG}: standard output: cannot write: {ex.strerror or ex}", file=sys.stderr)
            return 2
    else:
        try:
            with open(a.out, "w", encoding="utf-8") as f:
                f.write(text)
        except OSError as ex:
            print(f"{PROG}: {a.out}: cannot write: {ex}", file=sys.stderr)
            return 2
    print(f"{PROG}: {a.svg}: {len(conv.curves)} curve(s) written to {a.out}"
          + (f", {conv.left_out} left out" if conv.left_out else ""), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
