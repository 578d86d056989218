"""docs/python.md's examples, run as doctests: what the page shows is what
the package prints."""

import doctest

from conftest import ROOT


def test_docs_examples():
    res = doctest.testfile(str(ROOT / "docs" / "python.md"), module_relative=False, report=True,
                           optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 20 and res.failed == 0, res
