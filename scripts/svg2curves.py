#!/usr/bin/python3
"""Convert the paths of an SVG file to a .curves file that offbench reads.

Usage: scripts/svg2curves.py FILE.svg --d D[,D...] [--out FILE.curves]
                             [--y up|down] [--units user|px] [--closed open|skip]
                             [--prefix P] [--strict]

The SVG is parsed by Python's xml.etree (expat) and its geometry read by
scripts/svgpath.py, by the rules and the arithmetic of measure's SVG reader
(docs/export-measure.md, "Reading SVG"; tests/e2e/e2e_svg_xml.sh checks
that both make the same pieces): every <path>, <line>, <polyline>,
<polygon>, <rect>, <circle> and <ellipse> outside defs, symbol, clipPath,
mask, marker and pattern, not under display:none and not invisible, with
the transforms of the element and its groups and each nested <svg>'s
viewport applied, lengths in px, in, cm, mm, pt, pc or %; <use>, <text> and
<image> are left out and named.  Each subpath
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

import svgpath
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
# elements that draw nothing themselves, or whose content is not drawn
# (defs, symbol, clipPath, ...): never reported as unknown
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

def mat_apply(m, x, y):
    a, b, c, d, e, f = m
    return (a * x + c * y + e, b * x + d * y + f)


def mat_then(m, n):
    """The map: first m, then n."""
    a, b, c, d, e, f = m
    A, B, C, D, E, F = n
    return (A * a + C * b, B * a + D * b, A * c + C * d, B * c + D * d,
            A * e + C * f + E, B * e + D * f + F)


# ---- segments: (letter, [(x, y, w), ...]) rational Bezier control points
KIND_NAMES = {"L": "Line", "Q": "QuadraticBezier", "C": "CubicBezier", "A": "Arc", "Z": "Close"}


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


def safe_id(s):
    return re.sub(r"[^A-Za-z0-9_./-]", "_", s)


def safe_text(s):
    """Text for a `source` line: printable, no '#' (a comment there)."""
    return "".join(ch if ch.isprintable() and ch != "#" else "_" for ch in s)[:300]


class Converter:
    def __init__(self, args, note):
        self.a, self.note = args, note
        self.curves, self.ids, self.left_out = [], set(), 0

    def skip(self, msg):
        self.left_out += 1
        self.note(msg)

    def output_map(self, e):
        m = e.ctm
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

    def element(self, e, index):
        tag = e.tag
        name = element_name(e, tag, index)
        m = self.output_map(e)
        subs = e.subs
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
        for num, kind, local in segs:
            got = [(num, letter, [mat_apply(m, x, y) + (w,) for x, y, w in p]) for letter, p in local]
            got = [g for g in got if any(q[:2] != g[2][0][:2] for q in g[2])]
            if not got and kind != "Z":
                self.skip(f"{where}: segment {num} ({KIND_NAMES[kind]}) has zero length; left out")
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
    an SVG document whose geometry attributes are well formed (svgsyntax.py
    names the place of an error)."""
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


def xml_report(root, note):
    """SVG elements that svgpath.shapes neither reads nor names: foreignObject
    (unsupported) and unknown ones."""
    def walk(el, hidden):
        tag = svgpath.local(el.tag)
        if tag is None or not el.tag.startswith("{" + SVG_NS + "}") or svgpath.prop(el, "display") == "none":
            return  # comments, no namespace, other namespaces (inkscape:, sodipodi:), not drawn
        eid = el.get("id")
        name = f'<{tag} id="{eid}">' if eid else f"<{tag}>"
        if tag in svgpath.UNREAD + ("tspan", "textPath"):
            return
        if tag == "foreignObject":
            note(f"{name}: unsupported element ({tag}); left out")
            return
        if tag not in QUIET_TAGS and tag not in SHAPE_TAGS and not hidden:
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
    if a.prefix and (safe_id(a.prefix) != a.prefix or len(a.prefix) > 40):
        print(f"{PROG}: --prefix '{a.prefix[:50]}': at most 40 of letters, digits, '_', '-', '.', '/'",
              file=sys.stderr)
        return 2
    try:
        return convert(a)
    except Exception as ex:  # a case the checks miss: still "FILE: what", exit 2, no traceback
        print(f"{PROG}: {a.svg}: cannot convert ({type(ex).__name__}: {str(ex)[:200]})", file=sys.stderr)
        return 2


def convert(a):
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
    conv = Converter(a, note)
    try:
        shapes = svgpath.shapes(root, a.units, conv.skip)
    except svgpath.Bad as ex:
        print(f"{PROG}: {a.svg}: {ex}", file=sys.stderr)
        return 2
    for i, e in enumerate(shapes, 1):
        conv.element(e, i)
    xml_report(root, conv.skip)
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
