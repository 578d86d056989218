"""offbench from Python: the curves, methods, driver and metrics of offbench
(a benchmarking harness for planar offset-curve approximation) over its C
library liboffbench.so.0, with numpy arrays in and out.

    import offbench
    r = offbench.fit("liu2002_ex1", "tiller", d=1, tol=1e-3)
    r.max_err, r.ctrl_points, r.status, r.pieces[0].points

Functions: curves, curve_from_segments, methods, fit, measure,
measure_pieces, run (a Python function may be a method: the method
decorator names it), read_results, read_meta; library_version and library_path say which
library is loaded.  Errors are offbench.Error (subclasses per kind).  See
docs/python.md in the offbench repository.
"""

from . import _lib
from .bezier import Bezier
from .curves import Curve, CurveSet, curve_from_segments, curves
from .errors import (CurveIndexError, Error, FileError, InvalidError, InvalidTypeError, LibraryNotFound, MeasureError,
                     OutOfMemoryError, ParseError, StoppedError, UnknownCurveError, UnsupportedError)
from .fit import PieceError, fit, measure, measure_pieces, run
from .methods import Method, Param, methods
from .pymethod import method
from .result import Result
from .results import read_meta, read_results

__version__ = "0.3.0"


def library_version() -> str:
    """The loaded liboffbench's version, "MAJOR.MINOR.PATCH" (loads it)."""
    return _lib.text(_lib.lib().obx_version())


def library_path() -> str:
    """Where the loaded liboffbench came from (loads it)."""
    return _lib.path()


__all__ = [
    "Bezier", "Curve", "CurveIndexError", "CurveSet", "Error", "FileError", "InvalidError", "InvalidTypeError",
    "LibraryNotFound", "MeasureError", "Method", "OutOfMemoryError", "Param", "ParseError", "PieceError", "Result",
    "StoppedError", "UnknownCurveError", "UnsupportedError", "curve_from_segments", "curves", "fit", "library_path",
    "library_version", "measure", "measure_pieces", "method", "methods", "read_meta", "read_results", "run",
]
