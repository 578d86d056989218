"""curves() and curve_from_segments(): the built-in set, a file, arrays;
bad files named FILE:LINE, bad arrays named by segment and point."""

import subprocess

import numpy as np
import pytest

import offbench

from conftest import PROGRAM, PUBLISHED


def test_builtin_set_is_the_programs():
    s = offbench.curves()
    out = subprocess.run([str(PROGRAM), "list", "curves"], stdout=subprocess.PIPE, universal_newlines=True).stdout
    for cid in ("liu2002_ex1", "atlas_circle"):
        assert cid in s and cid in out
    assert len(s) == len(list(s)) == len(s.ids) > 5
    assert [c.id for c in s] == s.ids
    assert s[0] is s[s.ids[0]] and s[-1].id == s.ids[-1]
    assert "built-in" in repr(s)


def test_a_curve():
    c = offbench.curves(PUBLISHED)["liu2002_ex1"]
    assert isinstance(c, offbench.Curve) and c.id == "liu2002_ex1" and c.family == "published"
    assert list(c.offsets) == [1.0, -1.0] and c.offsets.dtype == float
    (seg,) = c.segments
    assert isinstance(seg, offbench.Bezier) and seg.degree == 3 and seg.weights is None and not seg.rational
    assert seg.points.shape == (4, 2)
    assert np.array_equal(seg.points, [[-0.785938, 0.891849], [-0.993306, -0.59695], [0.3, -2.5], [0.9, -0.2]])
    assert "liu2002_ex1" in repr(c) and "offsets [1, -1]" in repr(c)
    with pytest.raises(ValueError):
        seg.points[0, 0] = 1  # read-only: the curve's data


def test_rational_and_bspline_segments():
    s = offbench.curves()
    circle = s["atlas_circle"]
    assert circle.family == "atlas" and any(b.rational for b in circle.segments)
    for b in circle.segments:
        if b.rational:
            assert b.weights.shape == (b.degree + 1,) and np.all(b.weights > 0)
    # liu2002_ex2 is a cubic B-spline in its file: its Bézier segments
    ex2 = s["liu2002_ex2"]
    assert len(ex2.segments) == 4 and all(b.degree == 3 for b in ex2.segments)
    for a, b in zip(ex2.segments, ex2.segments[1:]):
        assert np.allclose(a.points[-1], b.points[0])


def test_lookup_errors():
    s = offbench.curves()
    with pytest.raises(offbench.UnknownCurveError) as e:
        s["liu2002_ex"]
    assert "liu2002_ex" in str(e.value) and "did you mean 'liu2002_ex" in str(e.value)
    assert isinstance(e.value, KeyError) and isinstance(e.value, offbench.Error)
    with pytest.raises(IndexError):
        s[10 ** 6]
    with pytest.raises(offbench.InvalidError):
        s[1.5]
    assert "nosuch" not in s


def test_file_errors(tmp_path):
    bad = tmp_path / "bad.curves"
    bad.write_text("curve bad\n  bezier 3\n  point 0 zero\nend\n")
    with pytest.raises(offbench.ParseError) as e:
        offbench.curves(bad)
    assert str(e.value).startswith("%s:3:" % bad) and e.value.code == 2
    missing = tmp_path / "missing.curves"
    with pytest.raises(offbench.FileError) as e:
        offbench.curves(missing)
    assert str(missing) in str(e.value) and isinstance(e.value, OSError)
    with pytest.raises(offbench.InvalidError):
        offbench.curves("a\0b")


def test_from_segments():
    c = offbench.curve_from_segments("ex1", [np.array([[-0.785938, 0.891849], [-0.993306, -0.59695], [0.3, -2.5],
                                                        [0.9, -0.2]])])
    assert c.id == "ex1" and c.family == "user" and len(c.offsets) == 0
    assert c.segments[0] == offbench.curves(PUBLISHED)["liu2002_ex1"].segments[0]
    # a rational quarter circle, as a (points, weights) pair and as a Bezier
    q = ([[1, 0], [1, 1], [0, 1]], [1, 0.5 ** 0.5, 1])
    for seg in (q, offbench.Bezier(*q)):
        arc = offbench.curve_from_segments("arc", [seg])
        (b,) = arc.segments
        assert b.rational and np.allclose(b.weights, q[1], rtol=0, atol=1e-15)
        assert np.allclose(b.points, q[0], rtol=0, atol=1e-15)
    two = offbench.curve_from_segments("two", [[[0, 0], [1, 1]], [[1, 1], [2, 0], [3, 1]]])
    assert [b.degree for b in two.segments] == [1, 2]


@pytest.mark.parametrize("segments, words", [
    ([[[0, 0], [1, np.nan]]], "point 1 is not finite"),
    ([[[0, 0, 0], [1, 1, 1]]], "shape (n+1, 2)"),
    ([[[0, 0]]], "shape (n+1, 2)"),
    ([np.zeros((22, 2))], "degree n of 1 to 20"),
    ([[0, 1, 2]], "shape (n+1, 2)"),
    ([([[0, 0], [1, 0], [1, 1]], [1, -1, 1])], "weight 1"),
    ([([[0, 0], [1, 0], [1, 1]], [1, 1])], "weights must be an array of shape (3,)"),
    ([[["a", 0], [1, 1]]], "points"),
    ([], "none given"),
    (5, "a list of Bezier"),
])
def test_from_segments_bad(segments, words):
    with pytest.raises(offbench.InvalidError) as e:
        offbench.curve_from_segments("x", segments)
    assert words in str(e.value) and isinstance(e.value, ValueError)


def test_from_segments_bad_in_the_library():
    # what only the library checks: the id, a segment that is one point
    with pytest.raises(offbench.InvalidError) as e:
        offbench.curve_from_segments("bad id!", [[[0, 0], [1, 1]]])
    assert "id" in str(e.value) and e.value.code == 1
    with pytest.raises(offbench.InvalidError):
        offbench.curve_from_segments("x", [[[1, 1], [1, 1]]])
    with pytest.raises(offbench.InvalidError):
        offbench.curve_from_segments(7, [[[0, 0], [1, 1]]])


def test_set_outlives_its_name():
    c = offbench.curves(PUBLISHED)["liu2002_ex1"]  # the set is only referenced by c
    import gc
    gc.collect()
    assert c.set["liu2002_ex1"] is c and offbench.fit(c, "tiller", 1, 1e-2).status == "ok"
