"""The syntax of the SVG attributes that carry geometry, checked before
scripts/svgpath.py reads them (used by scripts/svg2curves.py): every error
of the document at once, named with the element.

Why: on an error in path data an SVG renderer draws the path up to the
error and drops the rest without a word (SVG 1.1, Appendix F.2), and it
drops a malformed transform, points list or viewBox the same way; the
converted curves would then silently lack part of the drawing, or be
placed wrongly.  So every such attribute is parsed here
against the grammar (SVG 1.1 8.3.9 paths, 7.6 transforms, 9.7 points,
7.7 viewBox) and an error is named with where it is.

Each check returns None when the text is well formed, else a message saying
what is wrong and at which character.
"""
import math
import re

WSP = " \t\n\r\f"
NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")
# path commands and the kinds of their arguments: n a number, f an arc flag
PATH_ARGS = {"m": "nn", "l": "nn", "t": "nn", "h": "n", "v": "n", "c": "nnnnnn",
             "s": "nnnn", "q": "nnnn", "a": "nnnffnn", "z": ""}
TRANSFORM_ARGS = {"matrix": (6,), "translate": (1, 2), "scale": (1, 2), "rotate": (1, 3),
                  "skewX": (1,), "skewY": (1,)}


class _Bad(Exception):
    pass


class _Scanner:
    """A cursor over one attribute's text; fail() raises with the place."""

    def __init__(self, text):
        self.s, self.i = text, 0

    def fail(self, what):
        near = self.s[self.i:self.i + 12]
        where = f"character {self.i + 1} ('{near}')" if near else "the end"
        raise _Bad(f"at {where}: {what}")

    def at_end(self):
        return self.i >= len(self.s)

    def peek(self):
        return self.s[self.i] if self.i < len(self.s) else ""

    def wsp(self):
        while self.peek() and self.peek() in WSP:
            self.i += 1

    def comma_wsp(self):
        """Blanks, an optional comma, blanks."""
        self.wsp()
        if self.peek() == ",":
            self.i += 1
            self.wsp()

    def number(self, what):
        m = NUMBER.match(self.s, self.i)
        if not m:
            self.fail(f"expected a number ({what})")
        if not math.isfinite(float(m.group())):
            self.fail(f"the number {m.group()[:30]} is out of range")
        self.i = m.end()
        return float(m.group())

    def flag(self, what):
        if not self.peek() or self.peek() not in "01":
            self.fail(f"expected an arc flag 0 or 1 ({what})")
        self.i += 1


def _checked(fn, text):
    try:
        fn(_Scanner(text))
    except _Bad as ex:
        return str(ex)
    return None


def _path(sc):
    sc.wsp()
    if sc.at_end():
        return  # no path data: nothing to draw (svg2curves names the element)
    if sc.peek() not in "Mm":
        sc.fail("path data must begin with a moveto (M or m)")
    while not sc.at_end():
        cmd = sc.peek()
        kinds = PATH_ARGS.get(cmd.lower()) if cmd.isalpha() else None
        if kinds is None:
            sc.fail(f"'{cmd}' is not a path command (M L H V C S Q T A Z, or lower case)")
        sc.i += 1
        sc.wsp()
        if not kinds:
            continue
        while True:  # one or more argument groups, the command implied
            for k, kind in enumerate(kinds):
                what = f"argument {k + 1} of '{cmd}'"
                sc.number(what) if kind == "n" else sc.flag(what)
                sc.comma_wsp()  # (a comma before the next command: taken, as renderers do)
            if sc.at_end() or sc.peek().isalpha():
                break


def _numbers(sc, what):
    """Numbers separated by blanks or a comma, to the end; their count."""
    n = 0
    sc.wsp()
    while not sc.at_end():
        sc.number(what)
        n += 1
        sc.comma_wsp()
    return n


def _points(sc):
    n = _numbers(sc, "a coordinate")
    if n % 2:
        raise _Bad(f"an odd number of coordinates ({n}): the last point has no y")


def _transform(sc):
    sc.wsp()
    while not sc.at_end():
        m = re.compile(r"[A-Za-z]+").match(sc.s, sc.i)
        name = m.group() if m else ""
        if name not in TRANSFORM_ARGS:
            sc.fail("expected matrix, translate, scale, rotate, skewX or skewY")
        sc.i = m.end()
        sc.wsp()
        if sc.peek() != "(":
            sc.fail(f"expected '(' after {name}")
        sc.i += 1
        sc.wsp()
        n = 0
        while sc.peek() != ")":
            if sc.at_end():
                sc.fail(f"{name}(: no closing ')'")
            sc.number(f"argument {n + 1} of {name}")
            n += 1
            sc.comma_wsp()
        if n not in TRANSFORM_ARGS[name]:
            sc.fail(f"{name} takes {' or '.join(map(str, TRANSFORM_ARGS[name]))} numbers, not {n}")
        sc.i += 1
        sc.comma_wsp()


def _viewbox(sc):
    vals = []
    sc.wsp()
    while not sc.at_end() and len(vals) < 5:
        vals.append(sc.number("min-x, min-y, width, height"))
        sc.comma_wsp()
    if len(vals) != 4:
        raise _Bad(f"expected 4 numbers (min-x min-y width height), got {len(vals)}")
    if vals[2] <= 0 or vals[3] <= 0:
        raise _Bad(f"width and height must be positive (got {vals[2]:g} and {vals[3]:g}): "
                   f"nothing would be drawn")


def path_data_error(text):
    """None, or what is wrong with a <path>'s d attribute and where."""
    return _checked(_path, text)


def points_error(text):
    """None, or what is wrong with a <polyline>/<polygon>'s points."""
    return _checked(_points, text)


def transform_error(text):
    """None, or what is wrong with a transform attribute."""
    return _checked(_transform, text)


def viewbox_error(text):
    """None, or what is wrong with an <svg>'s viewBox."""
    return _checked(_viewbox, text)


# attribute -> (its check, the elements it is checked on; None: every element)
CHECKS = {"d": (path_data_error, ("path",)),
          "points": (points_error, ("polyline", "polygon")),
          "transform": (transform_error, None),
          "viewBox": (viewbox_error, ("svg",))}


def syntax_errors(root, svg_ns):
    """Messages for every malformed geometry attribute of the SVG elements
    under root (an ElementTree element), each naming the element and the
    attribute; the walk is iterative, so any depth of nesting is fine."""
    out, count, stack = [], {}, [root]
    while stack:
        el = stack.pop()
        tag = el.tag if isinstance(el.tag, str) else ""
        if tag.startswith("{" + svg_ns + "}"):
            tag = tag[len(svg_ns) + 2:]
        elif tag.startswith("{"):
            continue  # another namespace (inkscape:, sodipodi:): not drawn
        count[tag] = count.get(tag, 0) + 1
        for attr, (check, tags) in CHECKS.items():
            text = el.get(attr)
            if text is None or (tags and tag not in tags):
                continue
            bad = check(text)
            if bad:
                eid = el.get("id")
                name = f'<{tag} id="{eid}">' if eid else f"<{tag}> number {count[tag]} of the file"
                out.append(f"{name}: attribute {attr}: {bad}")
        stack.extend(reversed(list(el)))
    return out
