"""A method written in Python, passed to run and fit as a function (issue 49
item 2): registered as an external method whose worker processes (one per
fitting thread) import it from its file.  The tiller port of
examples/external/tiller.py gives the built-in's rows; a function that
raises gives fail rows; a lambda or a clashing name is refused."""

import importlib.util

import pytest

import offbench

from conftest import ROOT

_spec = importlib.util.spec_from_file_location("tiller_port", str(ROOT / "examples" / "external" / "tiller.py"))
tiller_port = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(tiller_port)

JOBS = dict(tols=[1e-2, 1e-3], d=[-1.0, 1.0])
CURVES = ["liu2002_ex1", "atlas_circle", "zhao2017_septic"]


def broken(piece, d, tol, **params):
    """A method with a bug: every fit raises."""
    raise ValueError("no fit at d=%g" % d)


@offbench.method(name="tiller_py", citation="Tiller & Hanson 1984 (Python port)", degree="same",
                 continuity="G0", caps=["poly_out", "rational_in", "same_param", "interp_ends"])
def port(piece, d, tol, **params):
    """The tiller port under its own name (its file's function is `fit`)."""
    return tiller_port.fit(piece, d, tol, **params)


def test_port_gives_the_builtins_rows():
    rows = offbench.run(CURVES, methods=[port, "tiller"], **JOBS)
    mine = [r for r in rows if r.method == "tiller_py"]
    theirs = [r for r in rows if r.method == "tiller"]
    assert len(mine) == len(theirs) == len(CURVES) * 2 * 2
    for a, b in zip(mine, theirs):
        assert (a.curve, a.d, a.tol) == (b.curve, b.d, b.tol)
        assert (a.status, a.segments, a.ctrl_points, a.max_err) == (b.status, b.segments, b.ctrl_points, b.max_err), \
            (a.as_dict(), b.as_dict())


def test_fit_takes_a_function():
    a = offbench.fit("liu2002_ex1", port, 1.0, 1e-3)
    b = offbench.fit("liu2002_ex1", "tiller", 1.0, 1e-3)
    assert (a.method, a.status, a.ctrl_points, a.max_err) == ("tiller_py", b.status, b.ctrl_points, b.max_err)
    assert any(m.name == "tiller_py" for m in offbench.methods())


def test_an_exception_is_a_fail_row():
    rows = offbench.run("liu2002_ex1", methods=[broken, "tiller"], tols=1e-3, d=[-1.0, 1.0])
    assert [r.method for r in rows] == ["broken", "tiller", "broken", "tiller"]
    for r in rows[::2]:
        assert r.status == "fail" and "ValueError: no fit at d=" in r.message, r.as_dict()
    assert all(r.status == "ok" for r in rows[1::2])


def test_a_lambda_is_refused():
    with pytest.raises(TypeError, match="module-level function: a lambda"):
        offbench.run("liu2002_ex1", methods=[lambda piece, d, tol: []], tols=1e-3, d=1.0)

    def local(piece, d, tol):
        return []
    with pytest.raises(TypeError, match="module-level function: .*local.*inside a function"):
        offbench.fit("liu2002_ex1", local, 1.0, 1e-3)


def test_a_builtins_name_is_refused():
    clash = offbench.method(name="tiller")(broken)
    try:
        with pytest.raises(offbench.InvalidError, match="'tiller'.*built-in"):
            offbench.run("liu2002_ex1", methods=[clash], tols=1e-3, d=1.0)
    finally:
        del broken.offbench_method


def test_the_walk_through_shows_its_file():
    """docs/python.md "Your method in Python" shows the file its doctest
    imports (test_docs.py runs that doctest): the text may not drift."""
    text = (ROOT / "docs" / "python.md").read_text(encoding="utf-8")
    code = (ROOT / "examples" / "python" / "naive_offset.py").read_text(encoding="utf-8")
    assert "```python\n" + code + "```" in text


def racer_a(piece, d, tol, **params):
    """One of two functions that threads register at once."""
    return tiller_port.fit(piece, d, tol, **params)


def racer_b(piece, d, tol, **params):
    """The other."""
    return tiller_port.fit(piece, d, tol, **params)


def test_threads_register_at_once():
    """Eight threads register two functions at the same moment: each is
    registered once, and no thread sees "the name is taken" (the check and
    the registration were two steps, and two threads could both find the
    name free)."""
    import threading
    from offbench import pymethod
    barrier = threading.Barrier(8)
    errors, names = [], []

    def go(fn):
        barrier.wait()
        try:
            names.append(pymethod.register(fn))
        except Exception as e:  # noqa: BLE001 - the test reports any
            errors.append(repr(e))

    threads = [threading.Thread(target=go, args=(racer_a if i % 2 else racer_b,)) for i in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert sorted(set(names)) == ["racer_a", "racer_b"]
    listed = [m.name for m in offbench.methods()]
    assert listed.count("racer_a") == 1 and listed.count("racer_b") == 1, listed
