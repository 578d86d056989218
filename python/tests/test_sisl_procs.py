"""The sisl method's server processes seen from Python (methods/sisl_client.c,
docs/reliability.md "The SISL server"): an inherited $OFFBENCH_SISL_SERVER
does nothing, and children forked by multiprocessing after a sisl fit get
servers of their own (the parent's results, not another process's replies)."""

import multiprocessing

import offbench
from test_library import child

JOBS = [("liu2002_ex1", "sisl", d, t) for d in (1, -1, 0.5) for t in (1e-2, 3e-3)]


def test_inherited_server_variable_does_nothing():
    """A process started with OFFBENCH_SISL_SERVER set imports the package
    and fits as any other (it used to die at library load)."""
    for v in ("3,4", "0,1", "garbage"):
        rc, out = child("import offbench\nprint('ctrl', offbench.fit('liu2002_ex1', 'sisl', 1, 1e-2).ctrl_points)\n",
                        OFFBENCH_SISL_SERVER=v)
        assert rc == 0 and "ctrl " in out, (v, rc, out)


def _rows(jobs):
    return [offbench.fit(*j).row for j in jobs]


def test_forked_children_own_their_servers():
    """Children forked after the parent's sisl fits, fitting at the same time
    as each other: every row equals the parent's."""
    want = _rows(JOBS)
    ctx = multiprocessing.get_context("fork")
    with ctx.Pool(4) as pool:
        # the timeout only guards against a hang (children that shared the
        # parent's server used to wait for replies that never came)
        got = pool.map_async(_rows, [JOBS] * 8).get(timeout=600)
    assert all(g == want for g in got), [g for g in got if g != want][:1]
    assert _rows(JOBS) == want
