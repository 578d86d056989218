"""Python objects that reach the library: a Bezier's points and weights, a
Curve's set and index.  Every change is checked where it is made or where it
crosses to C, with an error naming the field: nothing wrong reaches C (a
weights array shorter than the points read past its end; an index of 2**40
wrapped to curve 0; Curve(set, 9999) was a curve of nothing)."""

import numpy as np
import pytest

import offbench
from offbench.curves import Curve

from conftest import PUBLISHED

LINE = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]


def _quad(weights=(1.0, 2.0, 1.0)):
    return offbench.Bezier(LINE, list(weights))


@pytest.mark.parametrize("value, exc, words", [
    (np.array([1.0]), ValueError, "weights"),              # fewer than the points: read past the end
    ([1.0, 2.0, 1.0, 1.0], ValueError, "weights"),
    ([1.0, np.nan, 1.0], ValueError, "weight 1"),
    ([1.0, -2.0, 1.0], ValueError, "weight 1"),
    ([1.0, np.inf, 1.0], ValueError, "weight 1"),
    ("abc", ValueError, "weights"),
    ([[1.0, 2.0, 1.0]], ValueError, "weights"),
])
def test_bezier_weights_checked_when_set(value, exc, words):
    b = _quad()
    with pytest.raises(exc) as e:
        b.weights = value
    assert words in str(e.value)
    assert np.array_equal(b.weights, [1.0, 2.0, 1.0])  # left as it was


@pytest.mark.parametrize("value, words", [
    ([[0.0, 0.0], [1.0, 0.0]], "points"),                   # 2 points, 3 weights
    ([[0.0, 0.0], [1.0, np.nan], [2.0, 1.0]], "point 1 is not finite"),
    ([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]], "points"),
    (np.zeros((22, 2)), "points"),
    (None, "points"),
])
def test_bezier_points_checked_when_set(value, words):
    b = _quad()
    with pytest.raises(ValueError) as e:
        b.points = value
    assert words in str(e.value)
    assert np.array_equal(b.points, LINE)


def test_bezier_fields_set_consistently():
    b = _quad()
    b.weights = None  # polynomial now: its degree may change
    b.points = [[0.0, 0.0], [1.0, 1.0]]
    assert b.degree == 1 and not b.rational
    b.weights = [1.0, 3.0]
    assert b.rational and b.points.flags.writeable is False and b.weights.flags.writeable is False
    c = offbench.curve_from_segments("set_fields", [b])
    assert c.segments[0] == b


def test_bezier_changed_in_place_is_checked_at_the_library():
    """An array made writable again and changed: checked where the pieces
    cross to C, naming the piece."""
    b = _quad()
    p = b.points
    p.setflags(write=True)
    p[1, 0] = np.nan
    with pytest.raises(ValueError, match=r"segments\[0\].*point 1 is not finite"):
        offbench.curve_from_segments("x", [b])
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-2)
    w = r.pieces[0]
    w._weights = np.array([1.0])  # under the property: still checked at the crossing
    with pytest.raises(ValueError, match=r"pieces\[0\].*weights"):
        offbench.measure("liu2002_ex1", 1, r.pieces)


@pytest.mark.parametrize("field", ["index", "set", "id", "family"])
def test_curve_fields_are_read_only(field):
    s = offbench.curves(PUBLISHED)
    c = s["liu2002_ex1"]
    with pytest.raises(AttributeError, match="Curve.%s is read-only" % field):
        setattr(c, field, 2 ** 40 if field == "index" else None)
    assert c.set is s and s[c.index] is c and c.id == "liu2002_ex1" and c.family == "published"


@pytest.mark.parametrize("index, exc, words", [
    (9999, IndexError, "index 9999"),
    (-1, IndexError, "index -1"),
    (2 ** 40, IndexError, "index 1099511627776"),
    (1.0, TypeError, "index"),
    (True, TypeError, "index"),
    ("1", TypeError, "index"),
])
def test_curve_made_with_a_bad_index(index, exc, words):
    s = offbench.curves(PUBLISHED)
    with pytest.raises(exc) as e:
        Curve(s, index)
    assert words in str(e.value)


def test_curve_made_without_a_set():
    with pytest.raises(TypeError, match="set"):
        Curve("liu2002_ex1", 0)


def test_curve_tampered_underneath_is_checked_at_the_library():
    c = offbench.curves(PUBLISHED)["liu2002_ex1"]
    object.__setattr__(c, "_index", 2 ** 40)
    for call in (lambda: offbench.fit(c, "tiller", 1, 1e-2), lambda: offbench.measure(c, 1, [LINE]),
                 lambda: offbench.run(c, "tiller", 1e-2, d=1)):
        with pytest.raises(IndexError, match="index 1099511627776"):
            call()
