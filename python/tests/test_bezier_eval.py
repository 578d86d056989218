"""Bezier evaluation: b(t), b.eval(t, derivative=1), b.sample(n), checked
against an independent evaluation: the Bernstein sum with math.comb in
exact fractions (the package uses de Casteljau in floats), rational weights
included, and t outside [0, 1] refused."""

import math
from fractions import Fraction

import numpy as np
import pytest

import offbench

CUBIC = offbench.Bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
# a quarter of the unit circle, as a rational quadratic
ARC = offbench.Bezier([[1, 0], [1, 1], [0, 1]], [1, math.sqrt(0.5), 1])
# degree 7, uneven weights: every term of the sum matters
RNG = np.random.default_rng(49)
HIGH = offbench.Bezier(RNG.uniform(-3, 3, (8, 2)), RNG.uniform(0.2, 5, 8))

TS = [0, Fraction(1, 10), Fraction(1, 3), Fraction(1, 2), Fraction(7, 9), 1]


def _bernstein(n, i, t):
    """B_{i,n}(t) exactly (0 outside 0..n)."""
    if i < 0 or i > n:
        return Fraction(0)
    return math.comb(n, i) * t ** i * (1 - t) ** (n - i)


def _weights(b):
    return [1] * (b.degree + 1) if b.weights is None else list(b.weights)


def exact(b, t, derivative=0):
    """The point (or first derivative) of b at t: sum w_i B_i P_i / sum w_i
    B_i in fractions, the derivative by the quotient rule."""
    n, t = b.degree, Fraction(t)
    w = [Fraction(x) for x in _weights(b)]
    p = [(Fraction(x), Fraction(y)) for x, y in b.points]
    B = [_bernstein(n, i, t) for i in range(n + 1)]
    dB = [n * (_bernstein(n - 1, i - 1, t) - _bernstein(n - 1, i, t)) for i in range(n + 1)]
    D = sum(w[i] * B[i] for i in range(n + 1))
    dD = sum(w[i] * dB[i] for i in range(n + 1))
    out = []
    for k in range(2):
        N = sum(w[i] * B[i] * p[i][k] for i in range(n + 1))
        dN = sum(w[i] * dB[i] * p[i][k] for i in range(n + 1))
        out.append(N / D if derivative == 0 else (dN * D - N * dD) / (D * D))
    return np.array([float(v) for v in out])


@pytest.mark.parametrize("b", [CUBIC, ARC, HIGH], ids=["cubic", "arc", "rational7"])
@pytest.mark.parametrize("derivative", [0, 1])
def test_eval_matches_the_exact_bernstein_sum(b, derivative):
    ts = np.array([float(t) for t in TS])
    got = b.eval(ts, derivative=derivative)
    want = np.array([exact(b, t, derivative) for t in TS])
    assert got.shape == (len(TS), 2)
    scale = max(1.0, float(np.abs(want).max()))
    assert np.allclose(got, want, rtol=1e-13, atol=1e-13 * scale), (got, want)


def test_scalar_t_gives_one_point_and_call_is_eval():
    p = CUBIC(0.25)
    assert isinstance(p, np.ndarray) and p.shape == (2,)
    assert np.array_equal(p, CUBIC.eval(0.25))
    assert np.allclose(p, exact(CUBIC, Fraction(1, 4)), rtol=1e-15)
    assert CUBIC(np.array([0.25])).shape == (1, 2)


def test_ends_are_the_end_points():
    assert np.array_equal(CUBIC(0.0), CUBIC.points[0]) and np.array_equal(CUBIC(1.0), CUBIC.points[-1])
    for b in (ARC, HIGH):
        assert np.allclose(b(0.0), b.points[0], rtol=1e-15) and np.allclose(b(1.0), b.points[-1], rtol=1e-15)
    # the end tangent of a polynomial segment: n (P1 - P0)
    assert np.allclose(CUBIC.eval(0.0, derivative=1), 3 * (CUBIC.points[1] - CUBIC.points[0]))


def test_rational_arc_stays_on_the_circle():
    pts = ARC.sample(101)
    assert np.allclose(np.hypot(pts[:, 0], pts[:, 1]), 1.0, rtol=0, atol=1e-15)
    # and its tangent is perpendicular to the radius
    ts = np.linspace(0, 1, 11)
    assert np.allclose(np.sum(ARC(ts) * ARC.eval(ts, derivative=1), axis=1), 0.0, atol=1e-14)


def test_sample_is_eval_on_an_even_grid():
    s = HIGH.sample(17)
    assert s.shape == (17, 2)
    assert np.array_equal(s, HIGH(np.linspace(0.0, 1.0, 17)))
    assert np.allclose(s[[0, -1]], HIGH.points[[0, -1]], rtol=1e-15)


@pytest.mark.parametrize("t", [-1e-9, 1.0000001, -1.0, 2.0, float("nan"), float("inf"), [0.5, 1.5]])
def test_t_outside_the_unit_interval_is_refused(t):
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        CUBIC.eval(t)


@pytest.mark.parametrize("call", [lambda: CUBIC.eval(0.5, derivative=2), lambda: CUBIC.eval("x"),
                                  lambda: CUBIC.sample(1), lambda: CUBIC.sample(2.5), lambda: CUBIC.sample(True)])
def test_bad_arguments_are_value_errors(call):
    with pytest.raises(ValueError):
        call()


def test_fit_pieces_join_end_to_end():
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    for a, b in zip(r.pieces, r.pieces[1:]):
        assert np.allclose(a(1.0), b(0.0), rtol=0, atol=1e-12)
