"""Finding and loading the library: $OFFBENCH_LIB, the checkout's build/,
the version check, and the error that says where it looked (run in child
processes: a process loads the library once)."""

import os
import re
import shutil
import subprocess
import sys

import offbench
from offbench import _lib

from conftest import ROOT


def child(code, **env):
    """Runs python code with the package from python/ and env changes (None
    removes a variable); (exit status, stdout + stderr)."""
    e = dict(os.environ, PYTHONPATH=str(ROOT / "python"), PYTHONDONTWRITEBYTECODE="1")
    for k, v in env.items():
        if v is None:
            e.pop(k, None)
        else:
            e[k] = v
    p = subprocess.run([sys.executable, "-c", code], env=e, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, cwd="/")
    return p.returncode, p.stdout


def test_version_is_the_headers():
    h = (ROOT / "include" / "offbench.h").read_text()
    want = re.search(r'#define OBX_VERSION "([^"]+)"', h).group(1)
    assert offbench.library_version() == want
    major, minor = (int(x) for x in want.split(".")[:2])
    assert (major, minor) >= (_lib.NEED_MAJOR, _lib.NEED_MINOR) and major == _lib.NEED_MAJOR
    assert os.path.basename(offbench.library_path()) == "liboffbench.so.0"


def test_every_signature_is_exported():
    L = _lib.lib()
    for name in _lib.SIGNATURES:
        assert getattr(L, name).argtypes is not None or not _lib.SIGNATURES[name][1], name
    for name in _lib.OPTIONAL:  # this checkout's library has them all
        assert getattr(L, name).argtypes is not None, name
    # and every obx_ function of the header has a signature here
    h = (ROOT / "include" / "offbench.h").read_text()
    declared = set(re.findall(r"\b(obx_[a-z_]+)\(", h)) - {"obx_progress_fn"}
    known = set(_lib.SIGNATURES) | set(_lib.OPTIONAL)
    assert declared == known, declared ^ known
    assert not set(_lib.SIGNATURES) & set(_lib.OPTIONAL)


def test_bad_offbench_lib_says_where_it_looked():
    rc, out = child("import offbench\n"
                    "try:\n    offbench.fit('liu2002_ex1', 'tiller', 1, 1e-3)\n"
                    "except ImportError as e:\n"
                    "    assert isinstance(e, offbench.Error) and isinstance(e, offbench.LibraryNotFound)\n"
                    "    print(e)\n",
                    OFFBENCH_LIB="/nonexistent/liboffbench.so.0")
    assert rc == 0, out
    assert "$OFFBENCH_LIB: /nonexistent/liboffbench.so.0" in out and "make lib" in out
    # an explicit path is the only one tried: no other copy is loaded behind it
    assert "build" not in out.split("looked in:")[1].split("Build it")[0]


def test_import_and_reading_need_no_library(tmp_path):
    (tmp_path / "results.csv").write_text("curve,d,method\nx,1,tiller\n")
    rc, out = child("import offbench; print(offbench.read_results(%r, as_frame=False))" % str(tmp_path),
                    OFFBENCH_LIB="/nonexistent/liboffbench.so.0")
    assert rc == 0 and "'tiller'" in out, out


def test_checkout_build_is_found_without_offbench_lib():
    built = ROOT / "build" / "liboffbench.so.0"
    rc, out = child("import offbench; print(offbench.library_path())", OFFBENCH_LIB=None)
    if built.exists():
        assert rc == 0 and out.strip() == str(built), out
    else:
        assert rc != 0 and "the checkout's build/" in out, out


def test_candidates_order(monkeypatch):
    monkeypatch.delenv("OFFBENCH_LIB", raising=False)
    monkeypatch.setattr(_lib, "_recorded", lambda: "/rec/liboffbench.so.0")
    monkeypatch.setattr(_lib.sys, "prefix", "/venv")
    got = _lib.candidates()
    assert [w for w, _ in got] == ["the checkout's build/", "the path recorded at install", "the package's directory",
                                   "the system loader", "the environment's PREFIX", "make install's default PREFIX"]
    assert got[1][1] == "/rec/liboffbench.so.0" and got[4][1] == "/venv/lib/liboffbench.so.0"
    # nothing recorded, the environment /usr/local itself: neither is listed (nor twice)
    monkeypatch.setattr(_lib, "_recorded", lambda: None)
    monkeypatch.setattr(_lib.sys, "prefix", "/usr/local")
    assert "the path recorded at install" not in dict(_lib.candidates())
    assert [p for _, p in _lib.candidates()].count("/usr/local/lib/liboffbench.so.0") == 1
    monkeypatch.setenv("OFFBENCH_LIB", "/x/liboffbench.so.0")
    assert _lib.candidates() == [("$OFFBENCH_LIB", "/x/liboffbench.so.0")]


def _installed_copy(tmp_path, recorded=None, beside=None):
    """A copy of the package outside the checkout, as pip installs it
    (python/offbench/ alone, so no checkout's build/ to find), with the
    path pip's build records (_installed.py) and a library beside it when
    given; the directory to put on PYTHONPATH."""
    site = tmp_path / "site"
    shutil.copytree(str(ROOT / "python" / "offbench"), str(site / "offbench"),
                    ignore=shutil.ignore_patterns("__pycache__", "_installed.py"))
    if recorded is not None:
        (site / "offbench" / "_installed.py").write_text("LIBRARY = %r\n" % str(recorded))
    if beside is not None:
        os.symlink(str(beside), str(site / "offbench" / "liboffbench.so.0"))
    return str(site)


WHERE = "import offbench; print(offbench.__file__); print(offbench.library_path())"

def _in_copy(site, out):
    """The output's first line: the package imported is the copy."""
    return out.splitlines()[0].startswith(site)


def test_installed_copy_finds_the_library_recorded_at_install(tmp_path):
    lib = _lib.path()  # this run's library, wherever it is
    site = _installed_copy(tmp_path, recorded=lib)
    rc, out = child(WHERE, OFFBENCH_LIB=None, PYTHONPATH=site)
    assert rc == 0 and _in_copy(site, out) and out.splitlines()[1] == lib, out


def test_installed_copy_finds_a_library_beside_it(tmp_path):
    site = _installed_copy(tmp_path, beside=_lib.path())
    rc, out = child(WHERE, OFFBENCH_LIB=None, PYTHONPATH=site)
    assert rc == 0 and out.splitlines()[1] == os.path.join(site, "offbench", "liboffbench.so.0"), out


def test_installed_copy_without_a_library_says_every_place(tmp_path):
    gone = tmp_path / "gone" / "liboffbench.so.0"
    site = _installed_copy(tmp_path, recorded=gone)
    rc, out = child("import offbench, sys\ntry:\n    print('found', offbench.library_path())\n"
                    "except offbench.LibraryNotFound as e:\n    print(e)\n",
                    OFFBENCH_LIB=None, LD_LIBRARY_PATH=None, PYTHONPATH=site)
    assert rc == 0, out
    if out.startswith("found "):  # a system copy (make install + ldconfig): then nothing more to say
        return
    assert "the path recorded at install: %s" % gone in out, out
    assert "the package's directory: %s" % os.path.join(site, "offbench", "liboffbench.so.0") in out, out
    assert "make install's default PREFIX: /usr/local/lib/liboffbench.so.0" in out, out
    assert "OFFBENCH_LIB" in out and "checkout's build" not in out, out
