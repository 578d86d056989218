"""offbench.worker - the protocol loop of an external method, so that a
method in Python is one function (docs/external-methods.md):

    from offbench.worker import serve

    def fit(piece, d, tol, **params):
        ...                       # piece.degree, piece.points, piece.weights
        return [{"points": [[x, y], ...], "weights": [...]}]

    serve(fit, citation="...", degree="same", continuity="G0")

and `./offbench run --external NAME="python3 FILE.py"`.  Or, without the
call to serve, run this file on yours:

    ./offbench run --external NAME="python3 python/offbench/worker.py FILE.py[:FUNCTION]"

which calls FUNCTION (default fit) with FILE's METHOD dict as serve's
keyword arguments (citation, degree, continuity, caps, params, ...).
Standard library
only: a worker needs neither numpy nor liboffbench.  Numbers go out as
Python's repr (the shortest text that reads back to the same double), so
nothing is lost on the way.
"""

import json
import sys

PROTOCOL = 1


class Fail(Exception):
    """Raised by fit: no approximation (the row's status `fail`, the text its message)."""
    status = "fail"


class Skip(Exception):
    """Raised by fit: the method does not apply to this piece (status `skip`)."""
    status = "skip"


class RetrySmaller(Exception):
    """Raised by fit: no answer for this piece; offbench splits it and asks again."""
    status = "retry_smaller"


class Piece:
    """The base piece of one request: degree, points [(x, y)], weights."""

    def __init__(self, req):
        self.degree = req["degree"]
        self.points = [tuple(p) for p in req["points"]]
        self.weights = list(req["weights"])
        self.rational = any(w != 1.0 for w in self.weights)


def _piece_out(b):
    """One returned Bézier as the protocol's piece: a dict with "points"
    (and "weights"), or a sequence of points."""
    if isinstance(b, dict):
        pts, w = b["points"], b.get("weights")
    else:
        pts, w = b, None
    out = {"degree": len(pts) - 1, "points": [[float(p[0]), float(p[1])] for p in pts]}
    if w is not None:
        out["weights"] = [float(x) for x in w]
    return out


def _answer(fit, req):
    try:
        res = fit(Piece(req), req["d"], req["tol"], **req["params"])
        if isinstance(res, dict):  # {"pieces": [...], "t": [...], "ctrl_points": n}
            ans = dict(res, pieces=[_piece_out(b) for b in res["pieces"]])
        else:
            ans = {"pieces": [_piece_out(b) for b in res]}
        ans["id"] = req["id"]
        return json.dumps(ans, allow_nan=False)
    except (Fail, Skip, RetrySmaller) as e:
        return json.dumps({"id": req["id"], "error": str(e) or type(e).__name__, "status": e.status})
    except Exception as e:  # the method's bug is its row's message, not the worker's end
        return json.dumps({"id": req["id"], "error": "%s: %s" % (type(e).__name__, e)})


def serve(fit, citation, degree, continuity, caps=(), params=(), uses_tol=False, version=1, max_turn=0.0,
          stdin=None, stdout=None):
    """Say hello, then answer each request line with fit's pieces until EOF.
    params: dicts {"name", "default", "min", "max", "integer"?, "doc"?}."""
    stdin = stdin or sys.stdin
    stdout = stdout or sys.stdout
    hello = {"protocol": PROTOCOL, "citation": citation, "degree": degree, "continuity": continuity,
             "caps": list(caps), "params": list(params), "uses_tol": bool(uses_tol), "version": version,
             "max_turn": max_turn}
    stdout.write(json.dumps(hello) + "\n")
    stdout.flush()
    for line in stdin:
        stdout.write(_answer(fit, json.loads(line)) + "\n")
        stdout.flush()


def _load(spec):
    """FILE.py[:FUNCTION] -> (function, the file's METHOD dict).  FUNCTION
    may be a qualified name (Class.method); FILE's directory goes first on
    sys.path, as `python3 FILE.py` would put it, for FILE's own imports."""
    import importlib.util
    import os
    path, _, name = spec.partition(":")
    path = os.path.abspath(path)
    mspec = importlib.util.spec_from_file_location("offbench_user_method", path)
    if mspec is None:
        raise SystemExit("offbench/worker.py: %s is not a Python file" % path)
    sys.path.insert(0, os.path.dirname(path))
    mod = importlib.util.module_from_spec(mspec)
    mspec.loader.exec_module(mod)
    fn = mod
    for part in (name or "fit").split("."):
        fn = getattr(fn, part, None)
    if not callable(fn):
        raise SystemExit("offbench/worker.py: %s has no function %s" % (path, name or "fit"))
    return fn, dict(getattr(mod, "METHOD", {}))


def _main(argv):
    """worker.py FILE.py[:FUNCTION] [--meta JSON]: serve FUNCTION with
    FILE's METHOD dict, updated by JSON (offbench.method()'s metadata, which
    offbench/pymethod.py passes: the decorator ran in the caller's process)."""
    if len(argv) not in (2, 4) or (len(argv) == 4 and argv[2] != "--meta"):
        raise SystemExit("usage: python3 offbench/worker.py FILE.py[:FUNCTION] [--meta JSON]  "
                         "(docs/external-methods.md)")
    fn, meta = _load(argv[1])
    if len(argv) == 4:
        meta.update(json.loads(argv[3]))
    meta.setdefault("citation", "(no citation given)")
    meta.setdefault("degree", "same")
    meta.setdefault("continuity", "none")
    serve(fn, **meta)


if __name__ == "__main__":
    _main(sys.argv)
