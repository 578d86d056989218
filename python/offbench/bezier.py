"""Bezier: one Bézier segment or piece (a curve's segments, a fit's pieces,
what measure is given), and the conversion of a list of them to the flat
arrays the C API takes (degrees[], xy[], w[] or NULL)."""

import ctypes
from typing import Any, List, Optional, Tuple

import numpy as np

from ._typing import ArrayLike
from .errors import InvalidError

MAX_DEGREE = 20  # the curve files' and the C API's largest degree


def _points(points, what):
    """A read-only (n+1, 2) float array of finite points; InvalidError
    naming what."""
    try:
        p = np.array(points, dtype=float)
    except (TypeError, ValueError) as e:
        raise InvalidError("%s: points: %s" % (what, e)) from None
    if p.ndim != 2 or p.shape[1] != 2 or not 2 <= p.shape[0] <= MAX_DEGREE + 1:
        raise InvalidError("%s: points must be an array of shape (n+1, 2) for a degree n of 1 to %d, not %s"
                           % (what, MAX_DEGREE, "shape %s" % (p.shape,)))
    if not np.all(np.isfinite(p)):
        raise InvalidError("%s: point %d is not finite" % (what, int(np.argmin(np.all(np.isfinite(p), axis=1)))))
    p.setflags(write=False)
    return p


def _weights(weights, n, what):
    """None, or a read-only (n,) array of finite weights > 0; InvalidError
    naming what."""
    if weights is None:
        return None
    try:
        w = np.array(weights, dtype=float)
    except (TypeError, ValueError) as e:
        raise InvalidError("%s: weights: %s" % (what, e)) from None
    if w.shape != (n,):
        raise InvalidError("%s: weights must be an array of shape (%d,) (one per point), not shape %s"
                           % (what, n, w.shape))
    bad = ~(np.isfinite(w) & (w > 0))
    if bad.any():
        k = int(np.argmax(bad))
        raise InvalidError("%s: weight %d is %r (must be > 0, finite)" % (what, k, float(w[k])))
    w.setflags(write=False)
    return w


def _params(t: ArrayLike) -> np.ndarray:
    """t as a float array, every value in [0, 1]; InvalidError (a
    ValueError) naming the first that is not (NaN included)."""
    try:
        ts = np.asarray(t, dtype=float)
    except (TypeError, ValueError) as e:
        raise InvalidError("Bezier.eval: t: %s" % e) from None
    bad = ~((ts >= 0.0) & (ts <= 1.0))
    if bad.any():
        raise InvalidError("Bezier.eval: t = %r is outside [0, 1]" % float(ts[bad].flat[0]))
    return ts


def _casteljau(h: np.ndarray, ts: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """De Casteljau's steps on homogeneous points h, (n+1, 3), at each t of
    ts, (m,), stopped one step short: the two (m, 3) points whose segment
    holds the curve's point at t and whose difference, times n, is its
    derivative."""
    u = ts[:, None, None]
    q = np.broadcast_to(h, (ts.shape[0],) + h.shape)
    while q.shape[1] > 2:
        q = (1.0 - u) * q[:, :-1] + u * q[:, 1:]
    return q[:, 0], q[:, 1]


class Bezier:
    """A Bézier segment of degree n: points, an (n+1, 2) float array of its
    Euclidean control points; weights, an (n+1,) array of positive weights,
    or None for a polynomial segment (all weights 1).  Both are checked when
    set (points of another count than the weights: set weights to None
    first), and again where they are handed to the library."""

    __slots__ = ("_points", "_weights")

    def __init__(self, points: ArrayLike, weights: Optional[ArrayLike] = None, *, what: str = "segment") -> None:
        p = _points(points, what)
        self._weights = _weights(weights, p.shape[0], what)
        self._points = p

    @property
    def points(self) -> np.ndarray:
        return self._points

    @points.setter
    def points(self, value: ArrayLike) -> None:
        p = _points(value, "Bezier.points")
        if self._weights is not None and p.shape[0] != self._weights.shape[0]:
            raise InvalidError("Bezier.points: %d points, but %d weights (set weights to None first)"
                               % (p.shape[0], self._weights.shape[0]))
        self._points = p

    @property
    def weights(self) -> Optional[np.ndarray]:
        return self._weights

    @weights.setter
    def weights(self, value: Optional[ArrayLike]) -> None:
        self._weights = _weights(value, self._points.shape[0], "Bezier.weights")

    def checked(self, what: str) -> "Bezier":
        """self after its arrays are checked again (changed in place, or set
        under the properties), where it is handed to the library."""
        p = _points(self._points, what)
        _weights(self._weights, p.shape[0], what)
        return self

    @property
    def degree(self) -> int:
        return self.points.shape[0] - 1

    @property
    def rational(self) -> bool:
        return self.weights is not None

    def eval(self, t: ArrayLike, derivative: int = 0) -> np.ndarray:
        """The point (derivative=0) or first derivative (1) at parameter t:
        a float gives a (2,) array, an array of shape S one of shape S + (2,).
        t must lie in [0, 1] (InvalidError, a ValueError, otherwise: a piece
        is only a piece of its curve there).  De Casteljau's algorithm in
        homogeneous coordinates (w x, w y, w), so a rational segment is
        exact where the weights say, and stable up to degree 20."""
        if isinstance(derivative, bool) or derivative not in (0, 1):
            raise InvalidError("Bezier.eval: derivative 0 or 1, not %r" % (derivative,))
        ts = _params(t)
        q0, q1 = _casteljau(self._homogeneous(), ts.reshape(-1))
        n = self.degree
        h = (1.0 - ts.reshape(-1, 1)) * q0 + ts.reshape(-1, 1) * q1  # the curve, homogeneous
        if derivative == 0:
            out = h[:, :2] / h[:, 2:]
        else:  # the quotient rule on H' = n (q1 - q0)
            dh = n * (q1 - q0)
            out = (dh[:, :2] * h[:, 2:] - h[:, :2] * dh[:, 2:]) / (h[:, 2:] ** 2)
        return out.reshape(ts.shape + (2,))

    __call__ = eval

    def sample(self, n: int) -> np.ndarray:
        """n points at evenly spaced parameters from 0 to 1, ends included:
        an (n, 2) array (n >= 2, a whole number)."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
            raise InvalidError("Bezier.sample: n, a whole number >= 2, not %r" % (n,))
        return self.eval(np.linspace(0.0, 1.0, int(n)))

    def _homogeneous(self) -> np.ndarray:
        """The (n+1, 3) control points (w x, w y, w)."""
        w = np.ones(self.degree + 1) if self._weights is None else self._weights
        return np.column_stack([self._points * w[:, None], w])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Bezier):
            return NotImplemented
        wa = self.weights if self.weights is not None else np.ones(self.degree + 1)
        wb = other.weights if other.weights is not None else np.ones(other.degree + 1)
        return self.points.shape == other.points.shape and np.array_equal(self.points, other.points) and \
            np.array_equal(wa, wb)

    __hash__ = None  # type: ignore[assignment]  # mutable: not hashable

    def __repr__(self) -> str:
        pts = ", ".join("(%.6g, %.6g)" % (x, y) for x, y in self.points)
        w = "" if self.weights is None else ", weights=[%s]" % ", ".join("%.6g" % v for v in self.weights)
        return "Bezier(degree %d: %s%s)" % (self.degree, pts, w)


def from_buffers(degree, xy, w):
    """A Bezier from the C API's buffers (weights None when all are 1)."""
    n = degree + 1
    points = np.array(xy[:2 * n], dtype=float).reshape(n, 2)
    weights = np.array(w[:n], dtype=float)
    b = Bezier.__new__(Bezier)
    points.setflags(write=False)
    if np.all(weights == 1.0):
        weights = None
    else:
        weights.setflags(write=False)
    b._points, b._weights = points, weights
    return b


def as_beziers(items: Any, what: str) -> List[Bezier]:
    """A list of Bezier from a list of Bezier, (n+1, 2) arrays or
    (points, weights) pairs; `what` names the argument in messages."""
    if isinstance(items, (Bezier, np.ndarray)):
        items = [items]
    try:
        items = list(items)
    except TypeError:
        raise InvalidError("%s: a list of Bezier pieces or (n+1, 2) arrays, not %s"
                           % (what, type(items).__name__)) from None
    if not items:
        raise InvalidError("%s: none given" % what)
    out = []
    for k, it in enumerate(items):
        name = "%s[%d]" % (what, k)
        if isinstance(it, Bezier):
            out.append(it)
        elif isinstance(it, tuple) and len(it) == 2 and not np.isscalar(it[0]) and \
                np.ndim(it[0]) == 2:
            out.append(Bezier(it[0], it[1], what=name))
        else:
            out.append(Bezier(it, what=name))
    return out


def flat_arrays(beziers, what):
    """ctypes arrays (degrees, xy, w or None) of a list of Bezier, each
    checked again (InvalidError naming what[k])."""
    beziers = [b.checked("%s[%d]" % (what, k)) for k, b in enumerate(beziers)]
    degrees = (ctypes.c_int * len(beziers))(*[b.degree for b in beziers])
    xy = np.ascontiguousarray(np.concatenate([b.points.reshape(-1) for b in beziers]), dtype=float)
    w = None
    if any(b.weights is not None for b in beziers):
        w = np.ascontiguousarray(np.concatenate(
            [b.weights if b.weights is not None else np.ones(b.degree + 1) for b in beziers]), dtype=float)
    return degrees, xy, w


def dptr(a):
    """A double* into numpy array a (None stays NULL)."""
    return None if a is None else a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


def number(value, what):
    """float(value), or InvalidError naming the argument (NaN and the like
    pass: the library says what is wrong with them)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InvalidError("%s: %r is not a number" % (what, value)) from None
    return v
