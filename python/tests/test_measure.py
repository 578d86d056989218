"""measure(): any approximation against the exact offset; a fit's pieces
measure as the fit measured them; bad pieces and arguments are exceptions."""

import math

import numpy as np
import pytest

import offbench


@pytest.mark.parametrize("method, d, tol", [("tiller", 1, 1e-3), ("cobb", -1, 1e-2), ("hoschek", 1, 1e-3),
                                            ("ahn", -1, 1e-2), ("sisl", 1, 1e-3)])
def test_fit_pieces_measure_as_the_fit(method, d, tol):
    """Methods whose pieces end on the offset: measure finds each piece's
    base range where the fit had it, so it measures the fit's max_err (up
    to rounding in the projection).  (A method whose ends are off the offset,
    zhao, is measured against projected ranges and so differently.)"""
    r = offbench.fit("liu2002_ex1", method, d, tol)
    assert r.status == "ok"
    m = offbench.measure("liu2002_ex1", d, r.pieces)
    assert isinstance(m, offbench.Result) and m.kind == "measure"
    assert m.status == "ok" and m.message == ""
    assert m.max_err <= tol and m.max_err == pytest.approx(r.max_err, rel=1e-9)
    assert (m.curve, m.d, m.metric, m.segments) == ("liu2002_ex1", float(d), "hausdorff", len(r.pieces))
    assert 0 <= m.piece < len(r.pieces) and m.out_degree == max(p.degree for p in r.pieces)
    assert m.method is None and m.tol is None and m.ctrl_points is None
    assert m.pieces == r.pieces
    assert offbench.measure("liu2002_ex1", d, r).max_err == m.max_err  # a Result's pieces
    assert repr(m).startswith("Result(measure: curve='liu2002_ex1'") and "piece=" in repr(m)


def test_metrics():
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    normal = offbench.measure("liu2002_ex1", 1, r.pieces, metric="normal")
    assert normal.status == "ok" and normal.metric == "normal" and normal.max_err > 0
    for met in ("bound", "radial", "param"):
        na = offbench.measure("liu2002_ex1", 1, r.pieces, metric=met)
        assert na.status == "n/a" and math.isnan(na.max_err) and na.message, met


def test_certified():
    """certified: a proven upper bound of the Hausdorff distance, never below
    the sampled value and within the enclosure's target (1e-3) of it here;
    a fit under it ends within tol by proof."""
    r = offbench.fit("liu2002_ex1", "ahn", 1, 1e-3)
    h = offbench.measure("liu2002_ex1", 1, r, metric="hausdorff")
    c = offbench.measure("liu2002_ex1", 1, r, metric="certified")
    assert c.status == "ok" and c.metric == "certified"
    assert h.max_err <= c.max_err <= h.max_err * (1 + 2e-3)
    f = offbench.fit("liu2002_ex1", "ahn", 1, 1e-3, metric="certified")
    assert f.status == "ok" and f.metric == "certified" and f.max_err <= 1e-3


def test_hausdorff_whole():
    """hausdorff-whole: at most the per-piece value, the fit's here; pieces
    that leave a gap are refused."""
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    whole = offbench.measure("liu2002_ex1", 1, r.pieces, metric="hausdorff-whole")
    assert whole.status == "ok" and whole.metric == "hausdorff-whole"
    assert whole.max_err <= offbench.measure("liu2002_ex1", 1, r.pieces).max_err * (1 + 1e-12)
    assert whole.max_err == pytest.approx(r.max_err, rel=1e-6)
    with pytest.raises(offbench.MeasureError, match="does not cover the d = 1 offset of curve liu2002_ex1 once"):
        offbench.measure("liu2002_ex1", 1, r.pieces[1:], metric="hausdorff-whole")


def test_arrays_and_pairs():
    r = offbench.fit("liu2002_ex1", "lee", 1, 1e-2)
    as_pairs = [(p.points, p.weights if p.weights is not None else np.ones(p.degree + 1)) for p in r.pieces]
    assert offbench.measure("liu2002_ex1", 1, as_pairs).max_err == offbench.measure("liu2002_ex1", 1, r).max_err
    t = offbench.fit("liu2002_ex1", "tiller", 1, 1e-2)
    as_arrays = [p.points.copy() for p in t.pieces]
    assert offbench.measure("liu2002_ex1", 1, as_arrays).max_err == offbench.measure("liu2002_ex1", 1, t).max_err


def test_a_poor_approximation_measures_large():
    c = offbench.curves()["liu2002_ex1"]
    r = offbench.fit(c, "tiller", 1, 1e-3)
    moved = []
    for p in r.pieces:  # the ends stay on the offset, the inner points move
        q = p.points.copy()
        q[1:-1] += [0, 0.02]
        moved.append(offbench.Bezier(q))
    m = offbench.measure(c, 1, moved)
    assert m.status == "ok" and m.max_err > 5e-3


@pytest.mark.parametrize("kw, exc, words", [
    (dict(pieces=[]), offbench.InvalidError, "pieces: none given"),
    (dict(pieces="skip"), offbench.InvalidError, "the result (status skip) has no pieces"),
    (dict(pieces=[np.zeros((4, 3))]), offbench.InvalidError, "pieces[0]: points must be an array of shape"),
    (dict(pieces=[[[0, 0], [np.inf, 0]]]), offbench.InvalidError, "pieces[0]: point 1 is not finite"),
    (dict(pieces="abc"), offbench.InvalidError, "pieces[0]"),
    (dict(metric="worst"), offbench.InvalidError, "unknown metric 'worst'"),
    (dict(d=float("nan")), offbench.InvalidError, "finite"),
    (dict(d=0), offbench.InvalidError, "liu2002_ex1"),
    (dict(curve="nosuch"), offbench.UnknownCurveError, "nosuch"),
    (dict(pieces=[[[50, 50], [60, 60]]]), offbench.MeasureError, "piece 0"),
])
def test_bad_arguments(kw, exc, words):
    args = dict(curve="liu2002_ex1", d=1, pieces=offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).pieces)
    args.update(kw)
    if args["pieces"] == "skip":
        args["pieces"] = offbench.fit("atlas_circle", "kim2018", 0.125, 1e-3)
    with pytest.raises(exc) as e:
        offbench.measure(args.pop("curve"), args.pop("d"), args.pop("pieces"), **args)
    assert words in str(e.value), str(e.value)
    assert isinstance(e.value, offbench.Error)


def test_a_curve_of_several_segments():
    """liu2002_ex2 (a B-spline: four Bézier segments) at its own offset: its
    fit measures as the fit; one piece over two segments of a user's curve is cut at their
    joint and measured (a CAD system's offset is not cut there)."""
    r = offbench.fit("liu2002_ex2", "tiller", 0.5, 1e-3)
    m = offbench.measure("liu2002_ex2", 0.5, r)
    assert m.status == "ok" and m.max_err == pytest.approx(r.max_err, rel=1e-9)
    two = offbench.curve_from_segments("two", [[[0, 0], [1, 0]], [[1, 0], [2, 0]]])
    whole = offbench.measure(two, 0.1, [[[0, 0.1], [2, 0.1]]])
    assert whole.status == "ok" and whole.max_err < 1e-12 and whole.segments == 1
    off = offbench.measure(two, 0.1, [[[0, 0.1], [1, 0.15], [2, 0.1]]])
    assert off.max_err == pytest.approx(0.025, rel=1e-6)


def _cover_cases():
    """(name, pieces from a fit's N pieces, the count the message gives)."""
    return [("one piece of N", lambda p: p[:1], "gaps"),
            ("50 copies of one piece", lambda p: [p[0]] * 50, "49 duplicates"),
            ("half the pieces", lambda p: p[:len(p) // 2], "1 gaps"),
            ("all but the first", lambda p: p[1:], "1 gaps")]


@pytest.mark.parametrize("metric", ["hausdorff", "normal", "certified", "hausdorff-whole", "bound"])
@pytest.mark.parametrize("case", _cover_cases(), ids=lambda c: c[0])
def test_pieces_must_cover_the_offset_once(case, metric):
    """measure refuses what `offbench measure` refuses (one path): pieces
    that do not cover the offset once, under every metric."""
    name, take, count = case
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    with pytest.raises(offbench.MeasureError, match=r"does not cover the d = 1 offset of curve liu2002_ex1 once "
                       r"\(.*%s" % count):
        offbench.measure("liu2002_ex1", 1, take(r.pieces), metric=metric)


def test_pieces_out_of_order_or_reversed_are_measured():
    """The CLI measures pieces out of order (in the base's order) and
    reversed pieces (matched the other way): so does measure."""
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    ref = offbench.measure("liu2002_ex1", 1, r.pieces).max_err
    p = r.pieces
    assert offbench.measure("liu2002_ex1", 1, p[::2] + p[1::2]).max_err == ref
    assert offbench.measure("liu2002_ex1", 1, p[::-1]).max_err == ref
    flipped = [q.points[::-1].copy() for q in p]
    assert offbench.measure("liu2002_ex1", 1, flipped).max_err == pytest.approx(ref, rel=1e-9)
