"""A method written in Python: a plain function fit(piece, d, tol, **params)
returning a list of Bézier pieces (offbench/worker.py), given to run and fit
in place of a method's name.

It runs as an external method (docs/external-methods.md): the library
starts worker processes, one per fitting thread, each importing the
function from its file, so the fits use every core, not one interpreter's
GIL.  Hence the function must be importable from its file: a module-level
function, not a lambda or a function defined inside another.
"""

import ctypes
import json
import os
import shlex
import sys
from typing import Any, Callable, Dict, Optional

from . import _lib
from .methods import forget

_PKG_PARENT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_WORKER = os.path.join(_PKG_PARENT, "offbench", "worker.py")
ATTR = "offbench_method"  # where method() keeps the metadata on the function


def method(fn: Optional[Callable] = None, *, name: Optional[str] = None, citation: Optional[str] = None,
           degree: Any = None, continuity: Optional[str] = None, **more: Any) -> Any:
    """Decorator: the name and METHOD-style metadata (worker.py's serve
    arguments: citation, degree ("same" or a number), continuity, caps,
    params, uses_tol, ...) of a Python method.  @method or @method(...)."""
    meta = dict(more, citation=citation, degree=degree, continuity=continuity)
    meta = {k: v for k, v in meta.items() if v is not None}

    def mark(f: Callable) -> Callable:
        setattr(f, ATTR, dict(meta, name=name or f.__name__))
        return f
    return mark(fn) if fn is not None else mark


def _source(fn: Callable) -> str:
    """fn's file, after checking a worker can import fn from it by its
    qualified name; TypeError saying why not."""
    qual = getattr(fn, "__qualname__", "")
    mod = sys.modules.get(getattr(fn, "__module__", None) or "")
    path = getattr(mod, "__file__", None)
    why = None
    if "<lambda>" in qual:
        why = "a lambda has no name to import it by"
    elif "<locals>" in qual:
        why = "%s is defined inside a function (a local function or closure)" % qual
    elif not path or not path.endswith(".py"):
        why = "its module %r has no .py file" % getattr(fn, "__module__", None)
    else:
        obj = mod
        for part in qual.split("."):
            obj = getattr(obj, part, None)
        if obj is not fn:
            why = "%s is not %s.%s (decorated into another object?)" % (qual, mod.__name__, qual)
    if why:
        raise TypeError("methods: a Python method runs in worker processes that import it from its file, "
                        "so it must be a module-level function: %s" % why)
    return os.path.abspath(path)


def command(fn: Callable) -> str:
    """The shell command of fn's worker: this interpreter on worker.py by
    its path (a worker needs neither numpy nor the library), the package
    on PYTHONPATH for a file that imports offbench, fn's metadata as JSON."""
    meta: Dict[str, Any] = dict(getattr(fn, ATTR, {}))
    meta.pop("name", None)
    py = sys.executable or "/usr/bin/python3"
    spec = "%s:%s" % (_source(fn), fn.__qualname__)
    args = [py, _WORKER, spec] + (["--meta", json.dumps(meta, sort_keys=True)] if meta else [])
    return 'PYTHONPATH=%s${PYTHONPATH:+:$PYTHONPATH} exec %s' % (shlex.quote(_PKG_PARENT),
                                                                 " ".join(shlex.quote(a) for a in args))


def name_of(fn: Callable) -> str:
    """The method name of fn: method()'s name, a str `name` attribute, else __name__."""
    meta_name = getattr(fn, ATTR, {}).get("name")
    attr = getattr(fn, "name", None)
    return meta_name or (attr if isinstance(attr, str) else fn.__name__)


def register(fn: Callable) -> str:
    """Register fn in the library (again: a no-op) and return its name."""
    name, cmd = name_of(fn), command(fn)
    err = _lib.ObxError()
    _lib.check(_lib.optional("obx_external_register")(name.encode(), cmd.encode(), ctypes.byref(err)), err)
    forget()  # the method list grew
    return name
