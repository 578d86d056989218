"""methods(): every method of `offbench list methods`, with its parameters."""

import subprocess

import offbench

from conftest import PROGRAM


def test_methods_as_the_program_lists_them():
    ms = offbench.methods()
    out = subprocess.run([str(PROGRAM), "list", "methods"], stdout=subprocess.PIPE, universal_newlines=True).stdout
    listed = [line.split()[0] for line in out.splitlines()[1:] if line and not line.startswith(" ")]
    # then the Python methods that other tests (test_docs, test_python_methods) registered in this process
    assert [m.name for m in ms][:len(listed)] == listed
    assert not {m.name for m in ms[len(listed):]} - {"naive", "tiller_py", "broken"}, ms[len(listed):]
    assert all(isinstance(m, offbench.Method) and m.citation for m in ms)


def test_params():
    by = {m.name: m for m in offbench.methods()}
    assert by["tiller"].params == []
    zhao = {p.name: p for p in by["zhao"].params}
    it = zhao["iterations"]
    assert isinstance(it, offbench.Param)
    assert (it.default, it.min, it.max, it.integer) == (5.0, 1.0, 100.0, True) and "eq. (2)" in it.meaning
    for m in by.values():
        for p in m.params:
            assert p.min <= p.default <= p.max and isinstance(p.integer, bool), (m.name, p)


def test_methods_is_a_copy():
    a = offbench.methods()
    a.clear()
    assert offbench.methods()
