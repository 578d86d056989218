"""read_results and read_meta: a run directory's results.csv and meta.json
(docs/output.md), without the library.  results.csv is read here, field by
field, with the types of offbench/columns.py, so that a DataFrame and the
plain records hold the same values, and a field that does not read names
its file, line and column."""

import csv
import json
import math
import os
from typing import Any, Dict, List, Optional, Union

from . import columns
from ._typing import DataFrame
from .errors import FileError, InvalidError, ParseError


def _pandas():
    """pandas, or None without it (a function, so tests can take it away)."""
    try:
        import pandas
    except ImportError:
        return None
    return pandas


def require_pandas(what: str) -> Any:
    """pandas, or ImportError saying how to install it (the [pandas] extra)."""
    pd = _pandas()
    if pd is None:
        raise ImportError("%s needs pandas (Debian: apt-get install python3-pandas; pip: pip install "
                          "'offbench[pandas]' (the package's extra), or pip install pandas)" % what)
    return pd


def _path(path, name):
    """The file: path itself, or path/name when path is a directory."""
    p = os.fspath(path)
    return os.path.join(p, name) if os.path.isdir(p) else p


def _open(p):
    try:
        return open(p, newline="", encoding="utf-8")
    except OSError as e:
        raise FileError("%s: %s" % (p, e.strerror or e)) from None


def _records(p):
    """The header and the typed rows of results.csv file p."""
    with _open(p) as f:
        try:
            rows = csv.reader(f)
            header = next(rows, None)
            if not header or "curve" not in header or "method" not in header:
                raise ParseError("%s:1: not a results.csv (its header has no curve and method columns: %s)"
                                 % (p, ",".join(header or [])[:200]))
            out = []
            for fields in rows:
                line = rows.line_num
                if len(fields) != len(header):
                    raise ParseError("%s:%d: %d fields under a header of %d columns"
                                     % (p, line, len(fields), len(header)))
                rec = {}
                for n, t in zip(header, fields):
                    try:
                        rec[n] = columns.parse(n, t)
                    except ValueError:
                        raise ParseError("%s:%d: column %s: %r is not %s" % (p, line, n, t, _what(n))) from None
                bad = _certificate_fault(rec)
                if bad:
                    raise ParseError("%s:%d: %s" % (p, line, bad))
                out.append(rec)
        except (csv.Error, UnicodeDecodeError) as e:
            raise ParseError("%s:%d: %s" % (p, rows.line_num, e)) from None
    return header, out


_CERT = ("err_upper", "err_lower", "certified", "cert_ns")


def _certificate_fault(rec):
    """What is wrong with a typed row's certificate columns, or None: the
    checks of the C reader (host/io/results_csv.c, read_cert), so that a row
    one refuses the other refuses.  All empty, all set and consistent on a
    row with an approximation (status ok or limit), or cert_ns alone (a
    certificate stopped by --job-timeout)."""
    if not all(c in rec for c in _CERT):
        return None  # an older file, before run --certify
    up, lo, cert, ns = (rec[c] for c in _CERT)
    have = [not math.isnan(up), not math.isnan(lo), cert is not None, ns is not None]
    if not any(have) or have == [False, False, False, True]:
        return None
    if not all(have):
        return ("err_upper, err_lower, certified and cert_ns are all empty or all set (or cert_ns alone: a "
                "certificate stopped by --job-timeout)")
    if rec.get("status") not in ("ok", "limit"):
        return ("status %s has no approximation to certify: err_upper, err_lower, certified and cert_ns must be "
                "empty" % rec.get("status"))
    if not 0 <= lo <= up:
        return "err_lower is not a finite number from 0 to err_upper"
    if cert != (up <= rec.get("tol", math.nan)):
        return "certified must be yes exactly when err_upper <= tol"
    return None


def _what(name):
    return {"float": "a number", "int": "a whole number", "int?": "a whole number or empty",
            "yesno": "yes, no or empty"}.get(columns.kind(name), "text")


def frame(records: List[Dict[str, Any]], header: Optional[List[str]] = None) -> DataFrame:
    """A pandas DataFrame of typed records, with the columns' dtypes."""
    pd = require_pandas("a DataFrame")
    names = header if header is not None else (list(records[0]) if records else list(columns.KINDS))
    data = {}
    for n in names:
        vals = [r[n] for r in records]
        dt = columns.PANDAS_DTYPES[columns.kind(n)]
        if dt == "Int64" or dt == "boolean":
            vals = [pd.NA if v is None else v for v in vals]
        data[n] = pd.Series(vals, dtype=dt)
    return pd.DataFrame(data, columns=names)


def read_results(path: Union[str, os.PathLike],
                 as_frame: Optional[bool] = None) -> Union[List[Dict[str, Any]], DataFrame]:
    """A run's results.csv (path: the run directory or the file itself).
    With pandas (as_frame None or True): a DataFrame with the documented
    dtypes (docs/python.md); without it, or as_frame=False: a list of dicts,
    one per row, the values typed the same way.  FileError when it cannot be
    read, ParseError ("FILE:LINE: column NAME: ...") when it is not a
    results.csv."""
    if as_frame not in (None, True, False):
        raise InvalidError("as_frame: None, True or False, not %r" % (as_frame,))
    header, recs = _records(_path(path, "results.csv"))
    if as_frame is False or (as_frame is None and _pandas() is None):
        return recs
    return frame(recs, header)


def read_meta(path: Union[str, os.PathLike]) -> Dict[str, Any]:
    """A run's meta.json as a dict (path: the run directory or the file)."""
    p = _path(path, "meta.json")
    with _open(p) as f:
        try:
            meta = json.load(f)
        except json.JSONDecodeError as e:
            raise ParseError("%s:%d: %s" % (p, e.lineno, e.msg)) from None
        except UnicodeDecodeError as e:
            raise ParseError("%s: %s" % (p, e)) from None
    if not isinstance(meta, dict):
        raise ParseError("%s:1: not a meta.json (a JSON object)" % p)
    return meta
