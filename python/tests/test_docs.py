"""docs/python.md's examples, run as doctests: what the page shows is what
the package prints."""

import doctest

from conftest import ROOT


def test_docs_examples(monkeypatch):
    monkeypatch.chdir(ROOT)  # the page's paths (examples/python) are the repository's, as a reader's shell has them
    res = doctest.testfile(str(ROOT / "docs" / "python.md"), module_relative=False, report=True,
                           optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 20 and res.failed == 0, res


def test_offline_install_names_its_interpreter():
    """The offline `pip install` (no PyPI) works only in a venv whose
    interpreter has numpy and setuptools: the documented commands make it
    with Debian's /usr/bin/python3 and say what it needs, in both places
    the install is documented (tests/e2e/e2e_python_install.sh runs it)."""
    import re
    for doc in (ROOT / "python" / "README.md", ROOT / "docs" / "python.md"):
        text = doc.read_text(encoding="utf-8")
        venvs = re.findall(r"^(\S+) -m venv --system-site-packages", text, re.M)
        assert venvs and all(v == "/usr/bin/python3" for v in venvs), (doc, venvs)
        for pkg in ("python3-numpy", "python3-setuptools", "python3-venv"):
            assert pkg in text, (doc, pkg)
