"""What pip installs: the py.typed marker (PEP 561), the [pandas] extra
(declared, documented, and named where pandas is missing), and a package
that finds its library once installed (tests/e2e/e2e_python_install.sh
installs it for real)."""

import re
from pathlib import Path

import pytest

import offbench

from conftest import ROOT

PKG = Path(offbench.__file__).parent
TOML = (ROOT / "python" / "pyproject.toml").read_text()


def test_py_typed_marker_ships():
    assert (PKG / "py.typed").is_file()
    assert re.search(r'package-data\]\s*\noffbench\s*=\s*\[[^]]*"py\.typed"', TOML), \
        "pyproject.toml does not put py.typed in the package"


def test_pandas_extra_is_declared_and_documented():
    assert re.search(r'^pandas\s*=\s*\["pandas[^"]*"\]', TOML, re.M)
    for doc in (ROOT / "docs" / "python.md", ROOT / "python" / "README.md"):
        text = doc.read_text()
        assert "./python[pandas]" in text, "%s does not show pip install './python[pandas]'" % doc.name


def test_missing_pandas_names_the_extra(no_pandas):
    with pytest.raises(ImportError, match=r"offbench\[pandas\]"):
        offbench.run("liu2002_ex1", "tiller", 1e-2, as_frame=True)


def test_setup_records_the_library():
    """setup.py's build step writes offbench/_installed.py, the library's
    absolute path, so that an installed copy finds it (_lib.candidates)."""
    setup = (ROOT / "python" / "setup.py").read_text()
    assert "_installed.py" in setup and "OFFBENCH_LIB" in setup
