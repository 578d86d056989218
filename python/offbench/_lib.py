"""Finding and loading liboffbench.so.0 (include/offbench.h) with ctypes,
and every obx_* function's signature.

The library is loaded on first use, not at import: read_results and
read_meta need no library, and a missing library is then reported where
it is needed, with where it was looked for.  Where it is looked for, in
this order:

  1. $OFFBENCH_LIB, a path to liboffbench.so.0 (when set, nothing else is
     tried: a wrong path is an error, not a reason to load another copy);
  2. the checkout's build/liboffbench.so.0, when this package is imported
     from the source tree (python/offbench/ beside python/pyproject.toml:
     `pip install -e ./python`, or python/ on sys.path);
  3. the path recorded at install (offbench/_installed.py, which
     python/setup.py writes: the checkout's build/ library, or
     $OFFBENCH_LIB's, as they were when pip built the package);
  4. the package's own directory (a library copied beside it);
  5. the system loader's liboffbench.so.0 (LD_LIBRARY_PATH, ldconfig's
     cache: `make install` into /usr/lib or a PREFIX made known to ldconfig);
  6. sys.prefix/lib (`make install PREFIX=$VIRTUAL_ENV`, or a conda
     environment's prefix);
  7. /usr/local/lib/liboffbench.so.0 (`make install`'s default PREFIX,
     which the loader reads only after ldconfig).
"""

import ctypes
import importlib
import os
import sys
import threading
from typing import List, Optional, Tuple

from .errors import LibraryNotFound, from_code

# The library version this package needs: its MAJOR, and at least this MINOR
# (0.2 added obx_curves_segment*, obx_curves_family; 0.3 obx_measure's
# hausdorff-whole, which an older library refuses as an unknown metric: not
# needed to load; 0.5 obx_run_batch_stop, without which run cannot be
# stopped by its callback or Ctrl-C: OPTIONAL; 0.6 obx_external_register,
# without which a Python function cannot be a method: OPTIONAL; 0.7
# obx_measure's trimmed-hausdorff, refused by an older library as an unknown
# metric, and obx_measure_pieces, without which measure_pieces cannot be:
# OPTIONAL).
NEED_MAJOR = 0
NEED_MINOR = 2
SONAME = "liboffbench.so.0"


class ObxError(ctypes.Structure):
    _fields_ = [("code", ctypes.c_int), ("message", ctypes.c_char * 512)]


class ParamInfo(ctypes.Structure):
    _fields_ = [
        ("name", ctypes.c_char_p),
        ("def_", ctypes.c_double),
        ("min", ctypes.c_double),
        ("max", ctypes.c_double),
        ("integer", ctypes.c_int),
        ("doc", ctypes.c_char_p),
    ]


class JobSpec(ctypes.Structure):
    _fields_ = [
        ("curve", ctypes.c_int),
        ("method", ctypes.c_char_p),
        ("d", ctypes.c_double),
        ("tol", ctypes.c_double),
        ("metric", ctypes.c_char_p),
        ("split", ctypes.c_char_p),
        ("params", ctypes.c_char_p),
    ]


class Measurement(ctypes.Structure):
    _fields_ = [
        ("max_err", ctypes.c_double),
        ("piece", ctypes.c_int),
        ("status", ctypes.c_char * 8),
        ("why", ctypes.c_char * 160),
    ]


class PieceErrorC(ctypes.Structure):
    _fields_ = [
        ("max_err", ctypes.c_double),
        ("seg0", ctypes.c_int),
        ("t0", ctypes.c_double),
        ("seg1", ctypes.c_int),
        ("t1", ctypes.c_double),
        ("seg", ctypes.c_int),
        ("t", ctypes.c_double),
        ("x", ctypes.c_double),
        ("y", ctypes.c_double),
        ("x_off", ctypes.c_double),
        ("y_off", ctypes.c_double),
        ("status", ctypes.c_char * 8),
        ("why", ctypes.c_char * 160),
    ]


class _CurveSet(ctypes.Structure):
    pass


class _Result(ctypes.Structure):
    pass


CurveSetP = ctypes.POINTER(_CurveSet)
ResultP = ctypes.POINTER(_Result)
PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t)
PROGRESS_STOP = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t)

_int, _long, _dbl, _str, _size = ctypes.c_int, ctypes.c_long, ctypes.c_double, ctypes.c_char_p, ctypes.c_size_t
_ip, _dp, _ep = ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ObxError)

# name: (restype, argtypes), as include/offbench.h declares them
SIGNATURES = {
    "obx_version": (_str, []),
    "obx_curves_load_file": (_int, [_str, ctypes.POINTER(CurveSetP), _ep]),
    "obx_curves_load_default": (_int, [ctypes.POINTER(CurveSetP), _ep]),
    "obx_curves_from_arrays": (_int, [_str, _int, _ip, _dp, _dp, ctypes.POINTER(CurveSetP), _ep]),
    "obx_curves_free": (None, [CurveSetP]),
    "obx_curves_count": (_int, [CurveSetP]),
    "obx_curves_id": (_str, [CurveSetP, _int]),
    "obx_curves_find": (_int, [CurveSetP, _str]),
    "obx_curves_offsets": (_int, [CurveSetP, _int, ctypes.POINTER(_dp)]),
    "obx_curves_segment_count": (_int, [CurveSetP, _int]),
    "obx_curves_segment": (_int, [CurveSetP, _int, _int, _dp, _dp, _int, _ep]),
    "obx_curves_family": (_str, [CurveSetP, _int]),
    "obx_method_count": (_int, []),
    "obx_method_name": (_str, [_int]),
    "obx_method_citation": (_str, [_int]),
    "obx_method_param_count": (_int, [_int]),
    "obx_method_param": (_int, [_int, _int, ctypes.POINTER(ParamInfo), _ep]),
    "obx_fit": (_int, [CurveSetP, _int, _str, _dbl, _dbl, _str, _str, _str, ctypes.POINTER(ResultP), _ep]),
    "obx_result_free": (None, [ResultP]),
    "obx_result_status": (_str, [ResultP]),
    "obx_result_max_err": (_dbl, [ResultP]),
    "obx_result_ctrl_points": (_long, [ResultP]),
    "obx_result_segments": (_int, [ResultP]),
    "obx_result_message": (_str, [ResultP]),
    "obx_result_row": (_str, [ResultP]),
    "obx_results_header": (_str, []),
    "obx_result_piece_count": (_int, [ResultP]),
    "obx_result_piece": (_int, [ResultP, _int, _dp, _dp, _int, _ep]),
    "obx_run_batch": (_int, [CurveSetP, ctypes.POINTER(JobSpec), _size, PROGRESS, ctypes.c_void_p,
                             ctypes.POINTER(ResultP), _ep]),
    "obx_measure": (_int, [CurveSetP, _int, _dbl, _int, _ip, _dp, _dp, _str, ctypes.POINTER(Measurement), _ep]),
}

# name: (restype, argtypes) of functions a library of NEED_MINOR may lack
# (declared where present; the call that needs one says which version has it)
OPTIONAL = {
    "obx_result_certify": ((0, 4), _int, [ResultP, _str, _dp, _dp, _ep]),
    "obx_run_batch_stop": ((0, 5), _int, [CurveSetP, ctypes.POINTER(JobSpec), _size, PROGRESS_STOP, ctypes.c_void_p,
                                          ctypes.POINTER(ResultP), _ep]),
    "obx_external_register": ((0, 6), _int, [_str, _str, _ep]),
    "obx_measure_pieces": ((0, 7), _int, [CurveSetP, _int, _dbl, _int, _ip, _dp, _dp, ctypes.POINTER(PieceErrorC),
                                          _ep]),
}

_lock = threading.Lock()
_loaded = None  # (CDLL, path)


def _recorded() -> Optional[str]:
    """The library path setup.py recorded when pip built this copy, or None
    (a copy imported from the source tree, or built with no library)."""
    try:
        return importlib.import_module("._installed", __package__).LIBRARY or None
    except ImportError:
        return None


def candidates() -> List[Tuple[str, str]]:
    """[(where, path)] in the order tried (see the module's text)."""
    env = os.environ.get("OFFBENCH_LIB")
    if env:
        return [("$OFFBENCH_LIB", env)]
    out = []
    pkg = os.path.dirname(os.path.abspath(__file__))
    src = os.path.dirname(pkg)
    if os.path.isfile(os.path.join(src, "pyproject.toml")):
        out.append(("the checkout's build/", os.path.join(os.path.dirname(src), "build", SONAME)))
    rec = _recorded()
    if rec:
        out.append(("the path recorded at install", rec))
    out.append(("the package's directory", os.path.join(pkg, SONAME)))
    out.append(("the system loader", SONAME))
    default = os.path.join("/usr/local/lib", SONAME)
    env_prefix = os.path.join(sys.prefix, "lib", SONAME)
    if env_prefix != default:
        out.append(("the environment's PREFIX", env_prefix))
    out.append(("make install's default PREFIX", default))
    return out


def _declare(dll):
    for name, (res, args) in SIGNATURES.items():
        f = getattr(dll, name)  # AttributeError: an older library; caught by the version check first
        f.restype = res
        f.argtypes = args
    for name, (_since, res, args) in OPTIONAL.items():
        f = getattr(dll, name, None)
        if f is not None:
            f.restype = res
            f.argtypes = args


def optional(name):
    """The library's function `name` of OPTIONAL; UnsupportedError naming
    the version that has it when the loaded library is older."""
    L = lib()
    f = getattr(L, name, None)
    if f is None:
        from .errors import UnsupportedError
        since = OPTIONAL[name][0]
        raise UnsupportedError("%s needs liboffbench %d.%d or newer (loaded: %s at %s); rebuild it with `make lib`"
                               % (name, since[0], since[1], text(L.obx_version()), path()))
    return f


def _open():
    tried = []
    for where, path in candidates():
        try:
            dll = ctypes.CDLL(path)
        except OSError as e:
            tried.append("%s: %s (%s)" % (where, path, e))
            continue
        version = dll.obx_version
        version.restype = ctypes.c_char_p
        v = version().decode()
        parts = v.split(".")
        if int(parts[0]) != NEED_MAJOR or int(parts[1]) < NEED_MINOR:
            raise LibraryNotFound(
                "liboffbench %s at %s (%s): this package needs %d.%d or newer with the same major version; "
                "rebuild it with `make lib`" % (v, path, where, NEED_MAJOR, NEED_MINOR))
        _declare(dll)
        return dll, path
    raise LibraryNotFound(
        "liboffbench.so.0 not found; looked in:\n  " + "\n  ".join(tried) +
        "\nBuild it with `make lib` in the offbench checkout, then reinstall this package from there "
        "(pip records build/'s library) or set OFFBENCH_LIB=/path/to/checkout/build/liboffbench.so.0 "
        "(or `make install` it: docs/python.md)")


def lib():
    """The loaded library (loaded on the first call; LibraryNotFound when it
    cannot be)."""
    global _loaded
    if _loaded is None:
        with _lock:
            if _loaded is None:
                _loaded = _open()
    return _loaded[0]


def path():
    """The path the library was loaded from."""
    lib()
    return _loaded[1]


def check(rc, err):
    """Raises the exception for err when a call returned -1."""
    if rc < 0:
        raise from_code(err.code, err.message.decode("utf-8", "replace"))
    return rc


def text(b):
    return None if b is None else b.decode("utf-8", "replace")
