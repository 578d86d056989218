"""run(progress=...): the callback runs on the calling thread, outside the
library's locks; an exception it raises (KeyboardInterrupt, Ctrl-C's, among
them) stops the run and is raised by run; counts rise strictly; a callback
that calls fit or run does not deadlock (hang-guarded in a subprocess)."""

import os
import signal
import subprocess
import sys
import textwrap
import threading

import pytest

import offbench

from conftest import ROOT

HANG_GUARD_S = int(os.environ.get("OB_TEST_HANG_GUARD_S", "600"))  # a deadlock fails the test instead of hanging it; never reached when it works

TOLS = [1e-2, 1e-3]


def _two_sets():
    """Curves of two sets (two batches): the built-in liu2002_ex1 and one of
    arrays."""
    own = offbench.curve_from_segments("own", [[[0, 0], [1, 2], [3, 2], [4, 0]]])
    return ["liu2002_ex1", own]


def test_counts_rise_strictly_on_the_calling_thread():
    seen = []

    def progress(done, total):
        seen.append((done, total, threading.current_thread() is threading.main_thread()))

    rs = offbench.run(_two_sets(), "tiller,cobb", TOLS, d=1, progress=progress)
    n = len(rs)
    counts = [d for d, _, _ in seen]
    assert counts == sorted(set(counts)) and counts[-1] == n, counts
    assert all(t == n for _, t, _ in seen) and all(main for _, _, main in seen)


def _count_library_calls(monkeypatch):
    """{"batches": the batches run, "told": the calls the library made to
    run's callback}, counted from here on."""
    from offbench import _lib
    n = {"batches": 0, "told": 0}
    real = _lib.lib()

    class Counting:
        def __getattr__(self, name):
            f = getattr(real, name)
            if not name.startswith("obx_run_batch"):
                return f

            def batch(*args):
                n["batches"] += 1
                return f(*args)
            return batch

    def counted(kind):
        def make(fn=None):
            if fn is None:
                return kind()

            def told(*args):
                n["told"] += 1
                return fn(*args)
            return kind(told)
        return make

    monkeypatch.setattr(_lib, "lib", lambda: Counting())
    for name in ("PROGRESS", "PROGRESS_STOP"):
        if hasattr(_lib, name):
            monkeypatch.setattr(_lib, name, counted(getattr(_lib, name)))
    return n


@pytest.mark.parametrize("exc", [KeyboardInterrupt, ValueError])
def test_an_exception_stops_the_run_and_is_raised(exc, monkeypatch):
    """The library is told to stop: it calls back no more, and the run's
    second batch (its second curve set) never starts."""
    calls = []
    n = _count_library_calls(monkeypatch)

    def progress(done, total):
        calls.append(done)
        raise exc("stop at %d" % done)

    with pytest.raises(exc, match="stop at"):
        offbench.run(_two_sets(), "tiller,cobb,lee", TOLS, d=1, progress=progress)
    assert len(calls) == 1 and n == {"batches": 1, "told": 1}, (calls, n)


def test_ctrl_c_stops_the_run(monkeypatch):
    """A real SIGINT while the run goes: Python's handler runs in the
    callback (this thread), its KeyboardInterrupt stops the run."""
    calls = []
    n = _count_library_calls(monkeypatch)
    # a shell's background job without job control (`make test &` in a
    # script, nohup) starts python with SIGINT ignored, and python keeps it
    # so: no KeyboardInterrupt would come; the test wants python's handler
    ignored = signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    if ignored:
        signal.signal(signal.SIGINT, signal.default_int_handler)

    def progress(done, total):
        calls.append(done)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    try:
        with pytest.raises(KeyboardInterrupt):
            offbench.run(_two_sets(), "tiller,cobb,lee", TOLS, d=1, progress=progress)
    finally:
        if ignored:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
    assert len(calls) == 1 and n == {"batches": 1, "told": 1}, (calls, n)


def test_without_progress_the_library_still_calls_back(monkeypatch):
    """So that a Ctrl-C during run(progress=None) is raised, and stops it,
    at the next job that finishes, not when the whole run ends."""
    n = _count_library_calls(monkeypatch)
    rs = offbench.run("liu2002_ex1", "tiller,cobb", TOLS)
    assert len(rs) == 8 and n["batches"] == 1 and n["told"] >= 1, n


def _script(tmp_path, script):
    """Runs python code in a subprocess under the hang guard; its output."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "python"), PYTHONDONTWRITEBYTECODE="1")
    try:
        p = subprocess.run([sys.executable, "-c", textwrap.dedent(script)], cwd=str(tmp_path), env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                           timeout=HANG_GUARD_S)
    except subprocess.TimeoutExpired:
        pytest.fail("hung for %d s (a deadlock)" % HANG_GUARD_S)
    assert p.returncode == 0, p.stderr[-2000:]
    return p.stdout


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork")
def test_a_run_in_a_forked_child(tmp_path):
    """The library's batch threads do not survive a fork (multiprocessing's
    default on Linux): the child starts its own instead of waiting on the
    parent's forever."""
    out = _script(tmp_path, """
        import os, signal, offbench
        tell = lambda done, total: None
        offbench.run("liu2002_ex1", "tiller", 1e-2, progress=tell)
        pid = os.fork()
        if pid == 0:
            signal.alarm(%d)  # the child's own hang guard: it is not left behind
            rs = offbench.run("liu2002_ex1", "tiller,cobb", 1e-2, progress=tell)
            os._exit(0 if [r.status for r in rs] == ["ok"] * 4 else 3)
        _, status = os.waitpid(pid, 0)
        print("child", status)
    """ % max(1, HANG_GUARD_S // 2))
    assert out.split() == ["child", "0"], out


def test_a_callback_that_fits_or_runs_does_not_deadlock(tmp_path):
    script = textwrap.dedent("""
        import offbench
        inner = []
        def progress(done, total):
            inner.append(offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).status)
            inner.append(offbench.run("liu2002_ex1", "cobb", 1e-2, d=-1, progress=lambda d, t: None)[0].status)
        rs = offbench.run("liu2002_ex1", "tiller,cobb,lee", [1e-2, 1e-3], progress=progress)
        print(len(rs), len(inner) > 0 and set(inner) == {"ok"})
    """)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "python"), PYTHONDONTWRITEBYTECODE="1")
    try:
        p = subprocess.run([sys.executable, "-c", script], cwd=str(tmp_path), env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, universal_newlines=True, timeout=HANG_GUARD_S)
    except subprocess.TimeoutExpired:
        pytest.fail("run(progress=...) whose callback calls fit and run hung for %d s (a deadlock)" % HANG_GUARD_S)
    assert p.returncode == 0 and p.stdout.split() == ["12", "True"], (p.stdout, p.stderr[-2000:])
