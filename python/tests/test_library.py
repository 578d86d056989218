"""Finding and loading the library: $OFFBENCH_LIB, the checkout's build/,
the version check, and the error that says where it looked (run in child
processes: a process loads the library once)."""

import os
import re
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
    where = [w for w, _ in _lib.candidates()]
    assert where == ["the checkout's build/", "the system loader", "make install's default PREFIX"]
    monkeypatch.setenv("OFFBENCH_LIB", "/x/liboffbench.so.0")
    assert _lib.candidates() == [("$OFFBENCH_LIB", "/x/liboffbench.so.0")]
