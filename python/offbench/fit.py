"""fit, measure, measure_pieces and run: one job, one measurement, each
piece's error, many jobs (obx_fit, obx_measure, obx_measure_pieces,
obx_run_batch).  Each copies what the library returns into
Python objects and frees the library's at once, so nothing here outlives a
call but the curve sets."""

import ctypes
import numbers
from typing import Any, Callable, Dict, List, NamedTuple, Optional, Sequence, Union

from . import _lib
from ._typing import DataFrame, Numbers, Params
from .bezier import Bezier, as_beziers, dptr, flat_arrays, from_buffers, number
from .curves import Curve, CurveSet, resolve
from .errors import InvalidError
from .methods import Method
from .result import Result, parse_row


def _cstr(value, what, allow_none=True):
    """bytes for a char* argument; InvalidError naming the argument."""
    if value is None and allow_none:
        return None
    if hasattr(value, "name") and not isinstance(value, str):  # a Method
        value = value.name
    if not isinstance(value, str):
        raise InvalidError("%s: a str, not %s" % (what, type(value).__name__))
    if "\0" in value:
        raise InvalidError("%s %r: may not hold NUL" % (what, value))
    return value.encode()


def _params_text(params, what="params"):
    """The "NAME=VALUE,..." text of a method's parameters: a dict, or that
    text itself."""
    if params is None:
        return None
    if isinstance(params, str):
        return _cstr(params, what)
    if not isinstance(params, dict):
        raise InvalidError("%s: a dict {name: value} or 'NAME=VALUE,...', not %s" % (what, type(params).__name__))
    parts = []
    for k, v in params.items():
        if not isinstance(k, str) or any(c in k for c in ",=\0"):
            raise InvalidError("%s: parameter name %r" % (what, k))
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            raise InvalidError("%s: %s=%r is not a number" % (what, k, v))
        parts.append("%s=%r" % (k, float(v)))
    return ",".join(parts).encode() if parts else None


def _result(r):
    """A fit's Result from an obx_result (not freed here)."""
    L = _lib.lib()
    header = _lib.text(L.obx_results_header())
    row = _lib.text(L.obx_result_row(r))
    try:
        values = parse_row(header, row)
    except ValueError as e:  # the library's own row: a mismatch is a bug there
        raise AssertionError("liboffbench's row does not read: %s\n%s\n%s" % (e, header, row)) from None
    err = _lib.ObxError()
    pieces = []
    for k in range(L.obx_result_piece_count(r)):
        deg = _lib.check(L.obx_result_piece(r, k, None, None, 0, ctypes.byref(err)), err)
        xy = (ctypes.c_double * (2 * deg + 2))()
        w = (ctypes.c_double * (deg + 1))()
        _lib.check(L.obx_result_piece(r, k, xy, w, deg + 1, ctypes.byref(err)), err)
        pieces.append(from_buffers(deg, xy, w))
    return Result("fit", values, pieces, row)


def _certify_mode(certify):
    """obx_result_certify's mode for fit's certify (None: no certificate)."""
    if certify is False:
        return None
    if certify is True:
        return b"verdict"
    if certify in ("verdict", "tight"):
        return certify.encode()
    raise InvalidError("certify: True, False, 'verdict' or 'tight', not %r" % (certify,))


def fit(curve: Union[Curve, str], method: Union[str, Method], d: float, tol: float, metric: str = "hausdorff",
        split: str = "mid", params: Params = None, certify: Union[bool, str] = False) -> Result:
    """One job, exactly as one row of `offbench run`: method on curve at
    offset d and tolerance tol, measured under metric, split by split.

    curve: a Curve, or the id of a built-in curve; method: a name of
    methods(), or a Python function fit(piece, d, tol, **params) returning
    Bézier pieces (docs/python.md "Your method in Python"); params: the method's parameters, {name: value} or
    "NAME=VALUE,..." (None: the paper's defaults); certify: True (or
    "verdict") to certify the job's error as `offbench run --certify` does
    (docs/certified.md), "tight" as `--certify=tight`: the Result's
    err_lower <= H <= err_upper (H the two-sided Hausdorff distance to the
    exact offset, whatever the metric; the verdict mode refines only until
    H is shown within tol or over it, tight until err_upper is within 1e-3
    of err_lower), certified (True when err_upper <= tol) and cert_ns; a
    job without an approximation has none (NaN, None).  Returns a Result (a job that ends fail, skip or
    limit is a Result with that status, not an exception).  InvalidError
    for a bad argument (the message names it)."""
    mode = _certify_mode(certify)
    c = resolve(curve)
    m = _cstr(_method_name(method), "method", allow_none=False)
    dd, tt = number(d, "d"), number(tol, "tol")
    L = _lib.lib()
    out = _lib.ResultP()
    err = _lib.ObxError()
    _lib.check(L.obx_fit(*c.handle(), m, dd, tt, _cstr(metric, "metric"), _cstr(split, "split"),
                         _params_text(params), ctypes.byref(out), ctypes.byref(err)), err)
    try:
        if mode is not None:
            _lib.check(_lib.optional("obx_result_certify")(out, mode, None, None, ctypes.byref(err)), err)
        return _result(out)
    finally:
        L.obx_result_free(out)


def _pieces_arrays(pieces, what="pieces"):
    """The Bezier list and the flat arrays of measure's pieces: a list of
    pieces or a Result (its pieces)."""
    if isinstance(pieces, Result):
        if not pieces.pieces:
            raise InvalidError("%s: the result (status %s) has no pieces" % (what, pieces.status))
        pieces = pieces.pieces
    bz = as_beziers(pieces, what)
    return (bz,) + flat_arrays(bz, what)


def measure(curve: Union[Curve, str], d: float, pieces: Union[Result, Sequence[Union[Bezier, Any]]],
            metric: str = "hausdorff") -> Result:
    """The error of an approximation, Bézier pieces in curve order, against
    curve's exact d-offset under metric, as `offbench measure` measures a
    file without base links.  pieces: a list of Bezier (a Result's .pieces),
    of (n+1, 2) arrays or of (points, weights) pairs, or a Result.
    metric="trimmed-hausdorff" (library 0.7) measures against the trimmed
    offset instead, as `offbench measure --trimmed`: the pieces and the
    points at distance |d| from the curve as point sets, no match and no
    cover check.

    Returns a Result of kind "measure": max_err (NaN where the metric does
    not apply: bound and radial need the base's parameter, param read
    links), status "ok", "n/a" or "fail", message (why), piece (where the
    error is largest).  MeasureError when a piece cannot be matched on the
    offset."""
    c = resolve(curve)
    bz, degrees, xy, w = _pieces_arrays(pieces)
    dd = number(d, "d")
    L = _lib.lib()
    m = _lib.Measurement()
    err = _lib.ObxError()
    _lib.check(L.obx_measure(*c.handle(), dd, len(bz), degrees, dptr(xy), dptr(w), _cstr(metric, "metric"),
                             ctypes.byref(m), ctypes.byref(err)), err)
    names = _lib.text(L.obx_results_header()).split(",")
    values = dict.fromkeys(names)
    values.update(curve=c.id, d=dd, metric=metric if metric is not None else "hausdorff", max_err=m.max_err,
                  status=_lib.text(m.status), message=_lib.text(m.why), segments=len(bz),
                  out_degree=max(b.degree for b in bz), family=c.family)
    values["piece"] = m.piece
    return Result("measure", values, bz)


class PieceError(NamedTuple):
    """One piece's own error (measure_pieces), a row of `offbench measure
    --per-piece`: piece (its index), max_err (hausdorff, against its base
    piece), its base range from t0 of base segment seg0 to t1 of seg1,
    where the error is largest (base segment seg, parameter t of the exact
    offset point (x_off, y_off) there; (x, y) the piece's point nearest to
    it), status ("ok", "fail": not finite) and message (why)."""

    piece: int
    max_err: float
    seg0: int
    t0: float
    seg1: int
    t1: float
    seg: int
    t: float
    x: float
    y: float
    x_off: float
    y_off: float
    status: str
    message: str


def measure_pieces(curve: Union[Curve, str], d: float,
                   pieces: Union[Result, Sequence[Union[Bezier, Any]]]) -> List[PieceError]:
    """Where an approximation's error is: one PieceError per piece, in the
    pieces' order, the numbers `offbench measure --per-piece` writes
    (library 0.7, obx_measure_pieces).  The pieces are taken, matched and
    checked as measure takes them (they must cover the offset once); the
    largest max_err is measure's hausdorff max_err, at its piece.
    InvalidError for a bad argument, MeasureError for pieces that cannot be
    matched or do not cover the offset once; UnsupportedError with an
    older library."""
    c = resolve(curve)
    bz, degrees, xy, w = _pieces_arrays(pieces)
    dd = number(d, "d")
    f = _lib.optional("obx_measure_pieces")
    out = (_lib.PieceErrorC * len(bz))()
    err = _lib.ObxError()
    _lib.check(f(*c.handle(), dd, len(bz), degrees, dptr(xy), dptr(w), out, ctypes.byref(err)), err)
    return [PieceError(k, o.max_err, o.seg0, o.t0, o.seg1, o.t1, o.seg, o.t, o.x, o.y, o.x_off, o.y_off,
                       _lib.text(o.status), _lib.text(o.why)) for k, o in enumerate(out)]


def _as_list(v, what):
    if v is None:
        return None
    if isinstance(v, (str, bytes)) or not hasattr(v, "__iter__"):
        return [v]
    out = list(v)
    if not out:
        raise InvalidError("%s: none given" % what)
    return out


def _curve_list(curves):
    from .curves import CurveSet
    if isinstance(curves, CurveSet):
        return list(curves)
    return [resolve(c, "curves") for c in _as_list(curves, "curves")]


def _method_name(m):
    """A method as its name: a Python function is registered first
    (offbench/pymethod.py); a str or Method is left to _cstr."""
    if callable(m) and not isinstance(m, (str, tuple)):  # a Method is a NamedTuple
        from .pymethod import register
        return register(m)
    return m


def _method_list(methods):
    out = []
    for m in _as_list(methods, "methods"):
        if isinstance(m, str):
            out.extend(x for x in m.split(",") if x)  # "tiller,cobb" as run's --methods
        else:
            out.append(_method_name(m))
    if out == ["all"]:
        from .methods import methods as all_methods
        return [x.name for x in all_methods()]
    return [_cstr(m, "methods", allow_none=False).decode() for m in out]


def _method_params(params, names):
    """{method: "NAME=VALUE,..."} from run's params {"METHOD.NAME": value}."""
    if params is None:
        return {}
    if not isinstance(params, dict):
        raise InvalidError("params: a dict {'METHOD.NAME': value}, not %s" % type(params).__name__)
    per = {}
    for k, v in params.items():
        if not isinstance(k, str) or "." not in k:
            raise InvalidError("params: %r: a key is METHOD.NAME (as run's --param)" % (k,))
        meth, name = k.split(".", 1)
        if meth not in names:
            raise InvalidError("params: %r: method %r is not among the run's methods (%s)"
                               % (k, meth, ", ".join(names)))
        per.setdefault(meth, {})[name] = v
    return {m: _params_text(p, "params") for m, p in per.items()}


def _specs(curves, methods, tols, d, metric, split, params):
    """[(Curve, method, d, tol)] in run's order (curve, d, method, tol),
    and each method's parameter text."""
    cs = _curve_list(curves)
    ms = _method_list(methods)
    ts = [number(t, "tols") for t in _as_list(tols, "tols")]
    ds = None if d is None else [number(x, "d") for x in _as_list(d, "d")]
    jobs = []
    for c in cs:
        cd = ds if ds is not None else list(c.offsets)
        if not cd:
            raise InvalidError("curve %r has no offsets of its own: give d" % c.id)
        for dv in cd:
            for m in ms:
                for t in ts:
                    jobs.append((c, m, float(dv), t))
    return jobs, _method_params(params, ms)


def run(curves: Union[CurveSet, Curve, str, Sequence[Union[Curve, str]]],
        methods: Union[str, Method, Sequence[Union[str, Method]]], tols: Numbers, d: Optional[Numbers] = None,
        metric: str = "hausdorff", split: str = "mid", params: Params = None,
        progress: Optional[Callable[[int, int], Any]] = None,
        as_frame: bool = False) -> Union[List[Result], DataFrame]:
    """Many jobs at once, as `offbench run` runs them (OpenMP threads over
    all of them; jobs that differ only in tol share pieces): every curve x
    d x method x tol, in that nesting.

    curves: a CurveSet, a Curve, a built-in id, or a list of those; methods:
    a name, "a,b" or a list ("all": every method), a Python function among
    them (as fit's method; its worker processes use every core); tols: a number or a list;
    d: a number or a list (None: each curve's own offsets); params:
    {"METHOD.NAME": value}; progress: None or progress(done, total), called
    by this thread as jobs finish, done rising strictly (it may call fit or
    run itself); an exception it raises, KeyboardInterrupt (Ctrl-C) among
    them, stops the run at its next batch of work and is raised here (with
    a library older than 0.5: after the run).  Returns a list of
    Result, one per job in that order, each what fit() gives for it; with
    as_frame=True a pandas DataFrame of their rows (read_results' dtypes)."""
    jobs, per_method = _specs(curves, methods, tols, d, metric, split, params)
    if progress is not None and not callable(progress):
        raise InvalidError("progress: a function progress(done, total), not %s" % type(progress).__name__)
    if as_frame:
        from .results import require_pandas
        require_pandas("run(as_frame=True)")
    met, spl = _cstr(metric, "metric"), _cstr(split, "split")
    # one batch per curve set (obx_run_batch takes one), in job order
    groups: Dict[int, List[int]] = {}
    for i, (c, m, dv, t) in enumerate(jobs):
        groups.setdefault(id(c.set), []).append(i)
    results: List[Any] = [None] * len(jobs)
    tell = _Tell(progress, len(jobs))
    names = {m: m.encode() for _, m, _, _ in jobs}  # the specs' char * point into these
    for idx in groups.values():
        specs = (_lib.JobSpec * len(idx))()
        for k, i in enumerate(idx):
            c, m, dv, t = jobs[i]
            specs[k] = _lib.JobSpec(c.handle()[1], names[m], dv, t, met, spl, per_method.get(m))
        for i, r in zip(idx, _group(jobs[idx[0]][0].set, specs, idx, tell)):
            results[i] = r
        tell.before += len(idx)
    tell.raise_failure()
    if as_frame:
        from .results import frame
        return frame([r.as_dict() for r in results])
    return results


class _Tell:
    """run's callback to the library: progress with the run's counts; 1
    stops the batch.  Called even without progress: running Python here
    lets a Ctrl-C's KeyboardInterrupt be raised, and stop the run."""

    def __init__(self, progress, total):
        self.progress, self.total, self.before, self.failure = progress, total, 0, []

    def __call__(self, _ctx, done, _total):
        if self.failure:
            return 1
        try:
            if self.progress is not None:
                self.progress(self.before + done, self.total)
        except BaseException as e:  # C cannot unwind: the batch stops, e is raised after it
            self.failure.append(e)
            return 1
        return 0

    def raise_failure(self):
        if self.failure:
            raise self.failure[0]


def _group(cset, specs, idx, tell):
    """The Results of one batch (jobs idx of the run, on one curve set)."""
    L = _lib.lib()
    out = (_lib.ResultP * len(idx))()
    err = _lib.ObxError()
    rc = _run_batch(L, cset, specs, len(idx), tell, tell.progress is not None, out, err)
    try:
        tell.raise_failure()
        if rc < 0:
            _lib.check(rc, _renumber(err, idx))
        return [_result(out[k]) for k in range(len(idx))]
    finally:
        for k in range(len(idx)):
            L.obx_result_free(out[k])


def _run_batch(L, cset, specs, n, tell, told, out, err):
    """obx_run_batch_stop with tell (1: stop); with a library older than 0.5
    obx_run_batch, whose callback cannot stop it (tell only where told)."""
    stop = getattr(L, "obx_run_batch_stop", None)
    if stop is not None:
        return stop(cset._h, specs, n, _lib.PROGRESS_STOP(tell), None, out, ctypes.byref(err))
    def plain(c, done, total):
        tell(c, done, total)
    cb = _lib.PROGRESS(plain) if told else _lib.PROGRESS()
    return L.obx_run_batch(cset._h, specs, n, cb, None, out, ctypes.byref(err))


def _renumber(err, idx):
    """A batch's "job K: " message with K the job's number in the whole run."""
    msg = err.message.decode("utf-8", "replace")
    if msg.startswith("job "):
        head, _, rest = msg[4:].partition(": ")
        if head.isdigit() and int(head) < len(idx):
            err.message = ("job %d: %s" % (idx[int(head)], rest)).encode()[:511]
    return err


__all__ = ["PieceError", "fit", "measure", "measure_pieces", "run"]
