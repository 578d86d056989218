"""Type hints (PEP 484, PEP 561): every public function and every public
method or property of a public class has hints for each parameter and its
return, that typing.get_type_hints can resolve (on this interpreter, so no
syntax newer than the package's Python 3.8); the package ships py.typed so
that a type checker reads them.  mypy itself is not needed (Debian's
python3-mypy is not a build dependency): where one is found (this
interpreter's, or mypy on PATH) the package and a user's script are
checked with it, else that test is skipped."""

import inspect
import shutil
import subprocess
import sys
import typing

import pytest

import offbench

from conftest import ROOT

def _public(cls):
    """(name, function) of cls's own public methods, __init__ and
    __call__, and its properties' getters and setters."""
    for name, v in vars(cls).items():
        if name.startswith("_") and name not in ("__init__", "__call__"):
            continue
        if isinstance(v, property):
            for f in (v.fget, v.fset):
                if f is not None:
                    yield "%s.%s" % (cls.__name__, name), f
        elif isinstance(v, (staticmethod, classmethod)):
            yield "%s.%s" % (cls.__name__, name), v.__func__
        elif inspect.isfunction(v):
            yield "%s.%s" % (cls.__name__, name), v


def _callables():
    """Every public callable of the package: the functions of __all__ and
    the public members of its classes."""
    for name in offbench.__all__:
        obj = getattr(offbench, name)
        if inspect.isclass(obj):
            yield from _public(obj)
        else:
            yield name, obj


def _missing(name, f):
    """What f lacks a hint for (its parameters, 'return')."""
    hints = typing.get_type_hints(f)
    params = [p for p in inspect.signature(f).parameters if p not in ("self", "cls")]
    return ["%s(%s)" % (name, p) for p in params + ["return"] if p not in hints]


def test_every_public_callable_is_annotated():
    missing = [m for name, f in _callables() for m in _missing(name, f)]
    assert not missing, "no type hint: " + ", ".join(missing)


def test_named_tuples_have_typed_fields():
    for cls in (offbench.Method, offbench.Param):
        hints = typing.get_type_hints(cls)
        assert set(cls._fields) <= set(hints), (cls.__name__, cls._fields, hints)


def test_hints_name_numpy_arrays_where_arrays_come_out():
    import numpy as np
    assert typing.get_type_hints(offbench.Bezier.eval)["return"] is np.ndarray
    assert typing.get_type_hints(offbench.Bezier.sample)["return"] is np.ndarray


@pytest.mark.parametrize("name", ["fit", "measure", "run", "curves", "read_results"])
def test_documented_functions_have_docstrings(name):
    assert (getattr(offbench, name).__doc__ or "").strip()


def _mypy():
    """The command that runs mypy, or None."""
    if subprocess.run([sys.executable, "-m", "mypy", "--version"], stdout=subprocess.DEVNULL,
                      stderr=subprocess.DEVNULL).returncode == 0:
        return [sys.executable, "-m", "mypy"]
    exe = shutil.which("mypy")
    return [exe] if exe else None


USER = """import numpy as np
import offbench
r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
e: float = r.max_err
p: np.ndarray = r.pieces[0](np.linspace(0, 1, 5))
s = offbench.curves()["liu2002_ex1"].segments[0].sample(10)
bad = offbench.fit("liu2002_ex1", "tiller", "one", 1e-3)
"""


def test_mypy_reads_the_hints(tmp_path):
    cmd = _mypy()
    if cmd is None:
        pytest.skip("no mypy here (python3 -m mypy, mypy on PATH): the hints are checked by get_type_hints above")
    env = {"MYPYPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin"}
    own = subprocess.run(cmd + ["--cache-dir", str(tmp_path / "cache"), str(ROOT / "python" / "offbench")],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, env=env)
    assert own.returncode == 0, own.stdout
    (tmp_path / "user.py").write_text(USER)
    user = subprocess.run(cmd + ["--cache-dir", str(tmp_path / "cache"), str(tmp_path / "user.py")],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, env=env)
    # the one wrong call is found, and nothing else is
    want = 'user.py:7: error: Argument 3 to "fit" has incompatible type "str"; expected "float"'
    assert user.returncode == 1 and user.stdout.count("error:") == 1 and want in user.stdout, user.stdout
