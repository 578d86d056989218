"""Shared fixtures of the Python package's tests (run by
tests/e2e/e2e_python.sh under `make test`, or `python3 -m pytest python/tests`
from the repository root).  The package is imported from python/ (this
checkout's, not an installed copy); the library is $OFFBENCH_LIB, else this
checkout's build/; the program for the cross-checks is $OFFBENCH, else
./offbench."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))

PROGRAM = Path(os.environ.get("OFFBENCH") or ROOT / "offbench").resolve()
PUBLISHED = ROOT / "datasets" / "published.curves"

# The cross-check's jobs: ok, limit (a quoted message with commas), skip,
# open joints, rational pieces (lee), the server-run sisl.
CROSS = [("liu2002_ex1", "tiller,cobb,lee,sisl"), ("atlas_circle", "tiller,kim2018,lee,zhao")]
CROSS_TOLS = "1e-2,1e-3"


def offbench_run(out, *args):
    """`offbench run ... --backend cpu --out OUT --force`; the results.csv path."""
    if not PROGRAM.is_file():
        pytest.fail("the program %s is missing (make, or set OFFBENCH)" % PROGRAM)
    cmd = [str(PROGRAM), "run", *args, "--backend", "cpu", "--out", str(out), "--force"]
    p = subprocess.run(cmd, cwd=str(ROOT), stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    assert p.returncode == 0, "%s: exit %d: %s" % (" ".join(cmd), p.returncode, p.stderr[-2000:])
    return Path(out) / "results.csv"


@pytest.fixture(scope="session")
def cross_runs(tmp_path_factory):
    """{curve id: results.csv path} of `offbench run` over CROSS."""
    out = {}
    for cid, methods in CROSS:
        out[cid] = offbench_run(tmp_path_factory.mktemp("run_" + cid), "--curve", cid, "--methods", methods,
                                "--tols", CROSS_TOLS)
    return out


@pytest.fixture(scope="session")
def reps_run(tmp_path_factory):
    """A run directory with --reps 2 (time_iqr_ns and time_cv filled)."""
    d = tmp_path_factory.mktemp("reps")
    offbench_run(d, "--curve", "atlas_circle", "--methods", "tiller,kim2018,zhao", "--tols", "1e-2", "--reps", "2")
    return d


@pytest.fixture
def no_pandas(monkeypatch):
    """The package as it is without pandas."""
    from offbench import results
    monkeypatch.setattr(results, "_pandas", lambda: None)
