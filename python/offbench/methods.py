"""methods(): the registered methods and their parameters, as
`offbench list methods` lists them (constant: read once)."""

import ctypes
from typing import List, NamedTuple, Optional

from . import _lib


class Param(NamedTuple):
    """One parameter of a method, a choice its paper leaves open: the
    paper's reading (default), the accepted values min..max (both included),
    integer (whole numbers only) and what the values mean."""

    name: str
    default: float
    min: float
    max: float
    integer: bool
    meaning: str


class Method(NamedTuple):
    """A method: its name (as fit and run take it), a short reference and
    its parameters (a list of Param)."""

    name: str
    citation: str
    params: List[Param]

_methods: Optional[List[Method]] = None


def _read() -> List[Method]:
    L = _lib.lib()
    out = []
    for i in range(L.obx_method_count()):
        params = []
        for k in range(L.obx_method_param_count(i)):
            p = _lib.ParamInfo()
            err = _lib.ObxError()
            _lib.check(L.obx_method_param(i, k, ctypes.byref(p), ctypes.byref(err)), err)
            params.append(Param(_lib.text(p.name), p.def_, p.min, p.max, bool(p.integer), _lib.text(p.doc)))
        out.append(Method(_lib.text(L.obx_method_name(i)), _lib.text(L.obx_method_citation(i)), params))
    return out


def methods() -> List[Method]:
    """Every registered method, in `offbench list methods` order: a list of
    Method(name, citation, params=[Param(name, default, min, max, integer,
    meaning), ...])."""
    global _methods
    if _methods is None:
        _methods = _read()
    return list(_methods)


def forget() -> None:
    """Read the list again at the next methods(): it grew (offbench/pymethod.py)."""
    global _methods
    _methods = None
