"""The sisl method's server processes seen from Python (methods/sisl/client.c,
docs/reliability.md "The SISL server"): an inherited $OFFBENCH_SISL_SERVER
does nothing, and children forked by multiprocessing after a sisl fit get
servers of their own (the parent's results, not another process's replies)."""

from test_library import child


def test_inherited_server_variable_does_nothing():
    """A process started with OFFBENCH_SISL_SERVER set imports the package
    and fits as any other (it used to die at library load)."""
    for v in ("3,4", "0,1", "garbage"):
        rc, out = child("import offbench\nprint('ctrl', offbench.fit('liu2002_ex1', 'sisl', 1, 1e-2).ctrl_points)\n",
                        OFFBENCH_SISL_SERVER=v)
        assert rc == 0 and "ctrl " in out, (v, rc, out)


FORKED = """
import multiprocessing, offbench
JOBS = [("liu2002_ex1", "sisl", d, t) for d in (1, -1, 0.5) for t in (1e-2, 3e-3)]
def rows(jobs):
    return [(r.status, r.ctrl_points, r.segments, r.max_err) for r in (offbench.fit(*j) for j in jobs)]
if __name__ == "__main__":
    want = rows(JOBS)
    offbench.run(curves=["liu2002_ex1"], methods=["tiller", "sisl"], tols=[1e-2, 1e-3])  # OpenMP regions, 2+ threads
    with multiprocessing.get_context("fork").Pool(4) as pool:
        # the timeout only guards against a hang
        got = pool.map_async(rows, [JOBS] * 8).get(timeout=300)
    bad = [g for g in got if g != want]
    print("same" if not bad and rows(JOBS) == want else "differ: %r vs %r" % (bad[:1], want))
"""


def test_forked_children_own_their_servers():
    """Children forked after the parent's sisl fits, fitting at the same time
    as each other: every row equals the parent's (they used to read each
    other's replies from the parent's server: 67 control points instead of
    16, bogus failures).  The parent has run OpenMP regions on several
    threads first: libgomp's thread pool does not survive a fork, so the
    library runs its regions on threads of its own, never the caller's
    (a child used to wait on its parent's pool for ever)."""
    rc, out = child(FORKED, OMP_NUM_THREADS="2")
    assert rc == 0 and out.strip().endswith("same"), out[-2000:]
