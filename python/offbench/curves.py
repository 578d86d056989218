"""Curve sets: curves(), curve_from_segments(), and the Curve and CurveSet
classes over the library's read-only obx_curveset (freed when the last
Python object using it goes)."""

import ctypes
import difflib
import os
import threading
import weakref
from typing import Any, Iterator, List, Optional, Sequence, Union

import numpy as np

from . import _lib
from ._typing import ArrayLike
from .bezier import Bezier, as_beziers, dptr, flat_arrays, from_buffers
from .errors import CurveIndexError, InvalidError, InvalidTypeError, UnknownCurveError


def _read_only(name: str) -> AttributeError:
    """What setting a Curve's field raises, naming the field."""
    return AttributeError("Curve.%s is read-only: a Curve is one curve of its set (set[i] or set[id] gives "
                          "another)" % name)


class CurveSet:
    """A read-only set of curves: len(), iteration (Curve objects in the
    file's order), set[id] or set[i], `id in set`, .ids.  Any number of
    threads may use it at once."""

    def __init__(self, handle: Any, source: str) -> None:
        self._h = handle
        self.source = source  # the file, "built-in" or "arrays"
        self._fin = weakref.finalize(self, _lib.lib().obx_curves_free, handle)
        n = _lib.lib().obx_curves_count(handle)
        self._curves = [Curve(self, i) for i in range(n)]
        self._index = {c.id: c for c in self._curves}

    @property
    def ids(self) -> List[str]:
        return [c.id for c in self._curves]

    def __len__(self) -> int:
        return len(self._curves)

    def __iter__(self) -> Iterator["Curve"]:
        return iter(self._curves)

    def __contains__(self, key: object) -> bool:
        return key in self._index if isinstance(key, str) else key in self._curves

    def __getitem__(self, key: Union[str, int]) -> "Curve":
        if isinstance(key, str):
            c = self._index.get(key)
            if c is None:
                raise unknown_curve(key, self)
            return c
        if isinstance(key, (int, np.integer)) and not isinstance(key, bool):
            return self._curves[key]
        raise InvalidError("a curve set is indexed by curve id (str) or position (int), not %s"
                           % type(key).__name__)

    def __repr__(self) -> str:
        head = ", ".join(self.ids[:4]) + (", ..." if len(self) > 4 else "")
        return "CurveSet(%s: %d curves: %s)" % (self.source, len(self), head)


class Curve:
    """One curve of a set: .id, .family, .segments (a list of Bezier),
    .offsets (the d values its file lists: a float array, empty for a
    curve made from arrays), .set (the CurveSet it belongs to).  Read-only:
    it names curve .index of .set (set[i] gives another)."""

    __slots__ = ("_set", "_index", "_id", "_family", "_segments", "_offsets")

    def __init__(self, cset: CurveSet, index: int) -> None:
        if not isinstance(cset, CurveSet):
            raise InvalidTypeError("Curve: set: a CurveSet (offbench.curves()), not %s" % type(cset).__name__)
        self._set = cset
        self._index = index
        h, i = self.handle()
        L = _lib.lib()
        self._id = _lib.text(L.obx_curves_id(h, i))
        self._family = _lib.text(L.obx_curves_family(h, i))
        self._segments: Optional[List[Bezier]] = None
        d = ctypes.POINTER(ctypes.c_double)()
        n = L.obx_curves_offsets(h, i, ctypes.byref(d))
        self._offsets = np.array([d[k] for k in range(n)], dtype=float)
        self._offsets.setflags(write=False)

    def handle(self) -> Any:
        """(the set's obx_curveset, the index) as the library takes them,
        checked: TypeError or IndexError naming the index (a value a C int
        would wrap, or one past the set, never reaches the library)."""
        i = self._index
        if isinstance(i, bool) or not isinstance(i, (int, np.integer)):
            raise InvalidTypeError("Curve.index: a whole number, not %s" % type(i).__name__)
        n = _lib.lib().obx_curves_count(self._set._h)
        if not 0 <= i < n:
            raise CurveIndexError("Curve.index %d out of range: the set has %d curve%s"
                                  % (i, n, "" if n == 1 else "s"))
        return self._set._h, int(i)

    @property
    def set(self) -> CurveSet:
        """The CurveSet this curve is one of."""
        return self._set

    @property
    def index(self) -> int:
        """The curve's position in its set."""
        return self._index

    @property
    def id(self) -> str:
        return self._id

    @property
    def family(self) -> str:
        return self._family

    def __setattr__(self, name: str, value: object) -> None:
        """Refuses every public field (set, index, id, family, ...), so a
        Curve always names curve .index of .set; a type checker reads the
        properties above, which have no setter, as read-only too."""
        if not name.startswith("_"):
            raise _read_only(name)
        object.__setattr__(self, name, value)

    @property
    def offsets(self) -> np.ndarray:
        return self._offsets

    @property
    def segments(self) -> List[Bezier]:
        if self._segments is None:
            L = _lib.lib()
            err = _lib.ObxError()
            h, i = self.handle()
            segs = []
            for k in range(L.obx_curves_segment_count(h, i)):
                deg = _lib.check(L.obx_curves_segment(h, i, k, None, None, 0, ctypes.byref(err)), err)
                xy = (ctypes.c_double * (2 * deg + 2))()
                w = (ctypes.c_double * (deg + 1))()
                _lib.check(L.obx_curves_segment(h, i, k, xy, w, deg + 1, ctypes.byref(err)), err)
                segs.append(from_buffers(deg, xy, w))
            self._segments = segs
        return list(self._segments)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Curve) and other.set is self.set and other.index == self.index

    def __hash__(self) -> int:
        return hash((id(self.set), self.index))

    def __repr__(self) -> str:
        n = _lib.lib().obx_curves_segment_count(*self.handle())
        offs = "[" + ", ".join("%g" % d for d in self._offsets) + "]"
        return "Curve(%r, %s, %d segment%s, offsets %s)" % (self.id, self.family, n, "" if n == 1 else "s", offs)


def unknown_curve(key: str, cset: CurveSet) -> UnknownCurveError:
    close = difflib.get_close_matches(key, cset.ids, n=1)
    hint = " (did you mean %r?)" % close[0] if close else ""
    where = "the built-in curves (offbench.curves())" if cset.source == "built-in" else cset.source
    return UnknownCurveError("unknown curve %r in %s%s" % (key, where, hint))


def _load(fn, *args):
    L = _lib.lib()
    h = _lib.CurveSetP()
    err = _lib.ObxError()
    _lib.check(getattr(L, fn)(*args, ctypes.byref(h), ctypes.byref(err)), err)
    return h


_default = None
_default_lock = threading.Lock()


def curves(path: Optional[Union[str, os.PathLike]] = None) -> CurveSet:
    """The curves of a `.curves` file, or with no path the built-in set
    `offbench run` uses by default ($OFFBENCH_DATA when set, else the
    datasets compiled into the library).  ParseError ("FILE:LINE: reason")
    or FileError for a bad file."""
    if path is None:
        return CurveSet(_load("obx_curves_load_default"), "built-in")
    p = os.fspath(path)
    if "\0" in p:
        raise InvalidError("curve file %r: a path may not hold NUL" % p)
    return CurveSet(_load("obx_curves_load_file", p.encode()), p)


def default_set() -> CurveSet:
    """The built-in set, loaded once and shared (a curve id given as a str
    is looked up here)."""
    global _default
    if _default is None:
        with _default_lock:
            if _default is None:
                _default = curves()
    return _default


def curve_from_segments(id: str, segments: Sequence[Union[Bezier, ArrayLike]]) -> Curve:
    """A Curve of its own (in a set of one) from Bézier segments joined end
    to end: a list of Bezier, of (n+1, 2) point arrays, or of (points,
    weights) pairs.  The curve has no offsets of its own: fit and measure
    name d."""
    if not isinstance(id, str):
        raise InvalidError("curve id: a str, not %s" % type(id).__name__)
    if "\0" in id:
        raise InvalidError("curve id %r: may not hold NUL" % id)
    segs = as_beziers(segments, "segments")
    degrees, xy, w = flat_arrays(segs, "segments")
    h = _load("obx_curves_from_arrays", id.encode(), len(segs), degrees, dptr(xy), dptr(w))
    return CurveSet(h, "arrays")[0]


def resolve(curve: Union[Curve, str], what: str = "curve") -> Curve:
    """A Curve from a Curve or a curve id of the built-in set."""
    if isinstance(curve, Curve):
        return curve
    if isinstance(curve, str):
        return default_set()[curve]
    raise InvalidError("%s: a Curve (offbench.curves()[id]) or a built-in curve id, not %s"
                       % (what, type(curve).__name__))


__all__ = ["Bezier", "Curve", "CurveSet", "curves", "curve_from_segments"]
