"""Result: one job's row, typed (offbench/columns.py), and its pieces; or
one measurement, the same kind of object with the columns that apply."""

import csv
import math
from typing import TYPE_CHECKING, Any, Dict, Iterable, List, Mapping, Optional

from .bezier import Bezier

from . import columns

# the columns a repr shows, in this order, when they have a value
_SHOWN = ("curve", "d", "method", "metric", "tol", "status", "ctrl_points", "segments", "max_err", "piece")


class Result:
    """One job (from fit or run) or one measurement (from measure).

    Every column of results.csv is an attribute (r.max_err, r.ctrl_points,
    r.status, ...), typed as offbench/columns.py says; .pieces is the
    approximation (a list of Bezier); .kind is "fit" or "measure"; .row the
    results.csv line itself (fit only).  A measurement has curve, d,
    metric, max_err, status ("ok", "n/a", "fail"), message (why, for n/a
    and fail), segments and out_degree (of the pieces measured) and piece
    (where the error is largest); its other columns are None."""

    def __init__(self, kind: str, values: Mapping[str, Any], pieces: Iterable[Bezier],
                 row: Optional[str] = None) -> None:
        self.kind = kind
        self._columns = list(values)
        self.__dict__.update(values)
        self.pieces = list(pieces)
        self.row = row

    if TYPE_CHECKING:  # every column is an attribute, set from the row: any name for a type checker
        def __getattr__(self, name: str) -> Any: ...

    @property
    def columns(self) -> List[str]:
        """The column names, in results.csv's order."""
        return list(self._columns)

    def as_dict(self) -> Dict[str, Any]:
        """The columns as a dict (results.csv's order)."""
        return {k: getattr(self, k) for k in self._columns}

    def __repr__(self) -> str:
        parts = []
        for k in _SHOWN:
            v = self.__dict__.get(k)
            if v is None or (k == "piece" and self.kind != "measure"):
                continue
            parts.append("%s=%s" % (k, ("%.6g" % v) if isinstance(v, float) and not math.isnan(v) else repr(v)))
        if self.__dict__.get("message"):
            parts.append("message=%r" % self.message)
        parts.append("pieces=%d" % len(self.pieces))
        return "Result(%s%s)" % ("measure: " if self.kind == "measure" else "", ", ".join(parts))


def parse_row(header: str, row: str) -> Dict[str, Any]:
    """The typed columns of one results.csv row, as a dict in order; ValueError
    naming the column when a field does not read as its type."""
    names = next(csv.reader([header]))
    fields = next(csv.reader([row]))
    if len(fields) != len(names):
        raise ValueError("%d fields under a header of %d columns" % (len(fields), len(names)))
    out = {}
    for n, t in zip(names, fields):
        try:
            out[n] = columns.parse(n, t)
        except ValueError as e:
            raise ValueError("column %s: %r: %s" % (n, t, e)) from None
    return out
