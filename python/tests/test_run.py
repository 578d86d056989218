"""run(): many jobs in one batch, in run's order; each equals fit() for its
job; the progress callback rises to the total; bad arguments name the job
or the option."""

import math

import pytest

import offbench
from offbench import columns

from conftest import PUBLISHED


def same_job(a, b):
    """Two Results of one job, timings aside."""
    for k in a.columns:
        if k in columns.TIMING:
            continue
        x, y = getattr(a, k), getattr(b, k)
        assert x == y or (isinstance(x, float) and math.isnan(x) and math.isnan(y)), (k, a, b)
    assert a.pieces == b.pieces


def test_run_equals_fit_job_by_job():
    seen = []
    rs = offbench.run(["liu2002_ex1", "atlas_circle"], "tiller,cobb,kim2018,sisl", [1e-2, 1e-3],
                      progress=lambda done, total: seen.append((done, total)))
    c = offbench.curves()
    want = [(cid, d, m, t) for cid in ("liu2002_ex1", "atlas_circle") for d in c[cid].offsets
            for m in ("tiller", "cobb", "kim2018", "sisl") for t in (1e-2, 1e-3)]
    assert [(r.curve, r.d, r.method, r.tol) for r in rs] == want
    for r, (cid, d, m, t) in zip(rs, want):
        same_job(r, offbench.fit(cid, m, d, t))
    assert seen and seen[-1] == (len(want), len(want))
    assert all(a[0] <= b[0] and a[1] == len(want) for a, b in zip(seen, seen[1:]))
    assert {r.status for r in rs} >= {"ok", "skip"}


def test_options_and_forms():
    s = offbench.curves(PUBLISHED)
    rs = offbench.run(s["liu2002_ex1"], ["zhao"], 1e-3, d=[0.5], metric="normal", split="maxerr",
                      params={"zhao.iterations": 2})
    (r,) = rs
    assert (r.d, r.metric, r.split) == (0.5, "normal", "maxerr")
    same_job(r, offbench.fit(s["liu2002_ex1"], "zhao", 0.5, 1e-3, metric="normal", split="maxerr",
                             params={"iterations": 2}))
    assert len(offbench.run(s, "tiller", 1e-1)) == sum(len(c.offsets) for c in s)
    assert {r.method for r in offbench.run("liu2002_ex1", "all", 1e-1, d=1)} == \
        {m.name for m in offbench.methods()}


def test_curves_of_two_sets():
    """Jobs on curves of different sets: one batch each, results in order,
    progress over all of them."""
    mine = offbench.curve_from_segments("mine", offbench.curves()["liu2002_ex1"].segments)
    seen = []
    rs = offbench.run([mine, "liu2002_ex1"], "tiller", 1e-2, d=1, progress=lambda a, b: seen.append((a, b)))
    assert [r.curve for r in rs] == ["mine", "liu2002_ex1"]
    assert rs[0].max_err == rs[1].max_err and seen[-1] == (2, 2)


def test_as_frame():
    pytest.importorskip("pandas")
    df = offbench.run("liu2002_ex1", "tiller,kim2018", [1e-2, 1e-3], as_frame=True)
    assert len(df) == 8 and list(df.columns) == offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).columns
    assert str(df.dtypes["ctrl_points"]) == "int64" and str(df.dtypes["status"]) == "category"


def test_as_frame_without_pandas(no_pandas):
    with pytest.raises(ImportError) as e:
        offbench.run("liu2002_ex1", "tiller", 1e-2, as_frame=True)
    assert "pandas" in str(e.value)


def test_progress_exception_is_raised():
    class Stop(Exception):
        pass

    def progress(done, total):
        raise Stop("stop at %d" % done)

    with pytest.raises(Stop):
        offbench.run("liu2002_ex1", "tiller", [1e-2, 1e-3], progress=progress)


@pytest.mark.parametrize("kw, exc, words", [
    (dict(methods="tiller,nosuch"), offbench.InvalidError, "job 1: unknown method 'nosuch'"),
    (dict(tols=[1e-2, 0]), offbench.InvalidError, "job 1: tolerance 0"),
    (dict(tols=[]), offbench.InvalidError, "tols: none given"),
    (dict(tols="x"), offbench.InvalidError, "tols: 'x' is not a number"),
    (dict(d=[1, float("nan")]), offbench.InvalidError, "job 1: curve 'liu2002_ex1'"),
    (dict(curves=["liu2002_ex1", "nosuch"]), offbench.UnknownCurveError, "nosuch"),
    (dict(curves=[]), offbench.InvalidError, "curves: none given"),
    (dict(metric="worst"), offbench.InvalidError, "job 0: unknown metric 'worst'"),
    (dict(split="half"), offbench.InvalidError, "job 0: unknown split"),
    (dict(params={"iterations": 2}), offbench.InvalidError, "METHOD.NAME"),
    (dict(params={"zhao.iterations": 2}), offbench.InvalidError, "not among the run's methods"),
    (dict(params={"tiller.x": 2}), offbench.InvalidError, "method tiller has no parameter 'x'"),
    (dict(progress=5), offbench.InvalidError, "progress: a function"),
])
def test_bad_arguments(kw, exc, words):
    args = dict(curves="liu2002_ex1", methods="tiller", tols=1e-2, d=1)
    args.update(kw)
    with pytest.raises(exc) as e:
        offbench.run(**args)
    assert words in str(e.value), str(e.value)


def test_a_curve_without_offsets_needs_d():
    mine = offbench.curve_from_segments("mine", [[[0, 0], [1, 0], [1, 1]]])
    with pytest.raises(offbench.InvalidError) as e:
        offbench.run(mine, "tiller", 1e-2)
    assert "'mine' has no offsets of its own: give d" in str(e.value)
