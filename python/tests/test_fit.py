"""fit(): one job, its typed row and pieces; the row is `offbench run`'s for
the same job (every column but the timings); bad arguments are exceptions
naming them; several threads at once give the same rows."""

import csv
import math
import threading

import numpy as np
import pytest

import offbench
from offbench import columns

from conftest import CROSS, CROSS_TOLS, PUBLISHED


def run_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_result_attributes():
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    assert isinstance(r, offbench.Result) and r.kind == "fit"
    assert r.columns == offbench._lib.text(offbench._lib.lib().obx_results_header()).split(",")
    assert (r.curve, r.d, r.method, r.metric, r.split, r.tol) == ("liu2002_ex1", 1.0, "tiller", "hausdorff", "mid",
                                                                 1e-3)
    assert r.status == "ok" and r.message == "" and r.family == "published"
    assert isinstance(r.ctrl_points, int) and isinstance(r.segments, int) and isinstance(r.out_degree, int)
    assert isinstance(r.fit_ns, int) and isinstance(r.eval_ns, int)
    assert isinstance(r.max_err, float) and 0 < r.max_err <= 1e-3
    assert r.offset_degree == 10 and r.offset_rational is False and r.continuity == "G1"
    assert r.time_iqr_ns is None and math.isnan(r.time_cv)
    assert r.ctrl_points == 1 + 3 * r.segments  # cubic pieces end to end, closed joints
    assert list(r.as_dict()) == r.columns and r.as_dict()["max_err"] == r.max_err
    text = repr(r)
    assert text.startswith("Result(curve='liu2002_ex1'") and "status='ok'" in text and "pieces=28" in text
    assert r.row.startswith("liu2002_ex1,1,tiller,hausdorff,mid,0.001,85,28,3,")


def test_pieces():
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    assert len(r.pieces) == r.segments
    for p in r.pieces:
        assert isinstance(p, offbench.Bezier) and p.degree == 3 and p.points.shape == (4, 2)
        assert p.points.dtype == np.float64 and p.weights is None
    for a, b in zip(r.pieces, r.pieces[1:]):  # G1 joints: end to end
        assert np.allclose(a.points[-1], b.points[0], atol=1e-12)
    lee = offbench.fit("liu2002_ex1", "lee", 1, 1e-2)
    assert any(p.rational for p in lee.pieces)
    for p in lee.pieces:
        assert p.weights is None or (p.weights.shape == (p.degree + 1,) and np.all(p.weights > 0))


def test_statuses_are_results_not_exceptions():
    skip = offbench.fit("atlas_circle", "kim2018", 0.125, 1e-3)
    assert skip.status == "skip" and "rational" in skip.message and skip.pieces == [] and math.isnan(skip.max_err)
    assert skip.max_gap != skip.max_gap and skip.continuity == ""
    limit = offbench.fit("atlas_circle", "lee", 0.125, 1e-3)
    assert limit.status == "limit" and "," in limit.message and limit.pieces


@pytest.mark.parametrize("cid, methods", CROSS)
def test_row_is_offbench_runs(cross_runs, cid, methods):
    """Every job of `offbench run` (ok, limit, skip; rational; sisl in its
    server): fit's row has the same text in every column but the timings,
    and the same typed values."""
    rows = run_rows(cross_runs[cid])
    nd = len(offbench.curves()[cid].offsets)
    assert len(rows) == nd * len(methods.split(",")) * len(CROSS_TOLS.split(","))
    for want in rows:
        r = offbench.fit(want["curve"], want["method"], float(want["d"]), float(want["tol"]))
        got = next(csv.DictReader([r.row], fieldnames=list(want)))
        for k in want:
            if k not in columns.TIMING:
                assert got[k] == want[k], (k, want, r.row)
                v = columns.parse(k, want[k])
                assert getattr(r, k) == v or (v != v and getattr(r, k) != getattr(r, k)), k


def test_a_users_curve_and_a_file():
    seg = offbench.curves(PUBLISHED)["liu2002_ex1"].segments
    mine = offbench.curve_from_segments("mine", seg)
    a = offbench.fit(mine, "tiller", 1, 1e-3)
    b = offbench.fit(offbench.curves(PUBLISHED)["liu2002_ex1"], "tiller", 1, 1e-3)
    assert a.curve == "mine" and a.family == "user"
    assert (a.ctrl_points, a.max_err, a.status) == (b.ctrl_points, b.max_err, b.status)
    two = offbench.curve_from_segments("two", [[[0, 0], [1, 0]], [[1, 0], [2, 0], [2, 1]]])
    r = offbench.fit(two, "cobb", 0.1, 1e-3)
    assert r.status == "ok" and r.segments >= 2


def test_options():
    base = offbench.fit("liu2002_ex1", "zhao", 1, 1e-3)
    assert offbench.fit("liu2002_ex1", "zhao", 1, 1e-3, params={"iterations": 5}).row.split(",")[6:11] == \
        base.row.split(",")[6:11]
    one = offbench.fit("liu2002_ex1", "zhao", 1, 1e-3, params={"iterations": 1, "npfac": 2})
    assert one.row.split(",")[6:11] != base.row.split(",")[6:11]
    assert offbench.fit("liu2002_ex1", "zhao", 1, 1e-3, params="iterations=1,npfac=2").max_err == one.max_err
    r = offbench.fit("liu2002_ex1", "tiller", -1, 1e-2, metric="normal", split="greedy")
    assert (r.d, r.metric, r.split) == (-1.0, "normal", "greedy")
    m = [x for x in offbench.methods() if x.name == "cobb"][0]
    assert offbench.fit("liu2002_ex1", m, 1, 1e-2).method == "cobb"  # a Method as well as its name


@pytest.mark.parametrize("kw, exc, words", [
    (dict(method="tillr"), offbench.InvalidError, "unknown method 'tillr' (tiller, cobb"),
    (dict(method=None), offbench.InvalidError, "method: a str"),
    (dict(tol=0), offbench.InvalidError, "tolerance 0"),
    (dict(tol=-1e-3), offbench.InvalidError, "tolerance"),
    (dict(tol=float("nan")), offbench.InvalidError, "tolerance nan"),
    (dict(tol=float("inf")), offbench.InvalidError, "tolerance inf"),
    (dict(tol="small"), offbench.InvalidError, "tol: 'small' is not a number"),
    (dict(d=0), offbench.InvalidError, "liu2002_ex1"),
    (dict(d=float("nan")), offbench.InvalidError, "finite"),
    (dict(d=1e300), offbench.InvalidError, "liu2002_ex1"),
    (dict(d=[1]), offbench.InvalidError, "d: [1] is not a number"),
    (dict(metric="worst"), offbench.InvalidError, "unknown metric 'worst'"),
    (dict(split="half"), offbench.InvalidError, "unknown split 'half'"),
    (dict(curve="nosuch"), offbench.UnknownCurveError, "unknown curve 'nosuch'"),
    (dict(curve=3), offbench.InvalidError, "curve: a Curve"),
    (dict(method="zhao", params={"nope": 1}), offbench.InvalidError, "method zhao has no parameter 'nope'"),
    (dict(method="zhao", params={"iterations": 1000}), offbench.InvalidError, "iterations"),
    (dict(method="zhao", params={"iterations": "x"}), offbench.InvalidError, "iterations='x' is not a number"),
    (dict(method="zhao", params="iterations"), offbench.InvalidError, "not NAME=VALUE"),
    (dict(method="zhao", params=[1]), offbench.InvalidError, "params: a dict"),
    (dict(method="ti\0ller"), offbench.InvalidError, "NUL"),
])
def test_bad_arguments(kw, exc, words):
    args = dict(curve="liu2002_ex1", method="tiller", d=1, tol=1e-3)
    args.update(kw)
    with pytest.raises(exc) as e:
        offbench.fit(args.pop("curve"), args.pop("method"), args.pop("d"), args.pop("tol"), **args)
    assert words in str(e.value), str(e.value)
    assert isinstance(e.value, offbench.Error) and isinstance(e.value, ValueError)


def test_sisl_without_its_server(tmp_path):
    """sisl needs its server program: a bad $OFFBENCH_SISL_EXE is an
    UnsupportedError naming it (in a child: the choice is made once)."""
    from test_library import child
    rc, out = child("import offbench\n"
                    "try:\n    offbench.fit('liu2002_ex1', 'sisl', 1, 1e-3)\n"
                    "except offbench.UnsupportedError as e:\n    print('refused:', e)\n",
                    OFFBENCH_SISL_EXE=str(tmp_path / "none"))
    assert rc == 0 and "refused: method sisl:" in out and "OFFBENCH_SISL_EXE" in out, out


def test_threads():
    """obx_fit runs on several threads at once: the same rows as one by one."""
    jobs = [("liu2002_ex1", m, d, t) for m in ("tiller", "cobb", "lee") for d in (1, -1) for t in (1e-2, 1e-3)]
    want = [offbench.fit(*j).row.split(",") for j in jobs]
    got = [None] * len(jobs)

    def work(i):
        got[i] = offbench.fit(*jobs[i]).row.split(",")

    ts = [threading.Thread(target=work, args=(i,)) for i in range(len(jobs))]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    strip = lambda r: r[:11] + r[13:]  # noqa: E731  (fit_ns, eval_ns are the 12th and 13th)
    assert [strip(r) for r in got] == [strip(r) for r in want]


def test_certify():
    """fit(..., certify=True): the job's certified enclosure, as `run
    --certify` writes it: err_lower <= err_upper, the sampled max_err <=
    err_upper, certified True exactly when err_upper <= tol, cert_ns an
    int; its row is run --certify's (the timings aside)."""
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3, certify=True)
    assert r.status == "ok" and 0 <= r.err_lower <= r.err_upper <= r.tol and r.certified is True
    assert isinstance(r.cert_ns, int) and r.cert_ns > 0
    t = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3, certify="tight")
    assert 0 < t.err_lower <= t.err_upper <= t.err_lower * 1.001 and t.max_err <= t.err_upper
    assert t.certified is (t.err_upper <= t.tol) is True
    v = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3, certify="verdict")
    assert (v.err_upper, v.err_lower, v.certified) == (r.err_upper, r.err_lower, r.certified)
    plain = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    assert math.isnan(plain.err_upper) and plain.certified is None and plain.cert_ns is None
    assert [getattr(r, k) for k in r.columns if k not in columns.TIMING + ("err_upper", "err_lower", "certified")] \
        == [getattr(plain, k) for k in r.columns if k not in columns.TIMING + ("err_upper", "err_lower", "certified")]
    # ok by the radial metric, over tol by the certified distance (e2e_certify.sh's job)
    n = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3, metric="radial", certify=True)
    assert n.status == "ok" and n.max_err <= 1e-3 and n.certified is False and n.err_lower > 0.0017
    # a job without an approximation: nothing to certify, not an error
    skip = offbench.fit("atlas_circle", "kim2018", 0.125, 1e-3, certify=True)
    assert skip.status == "skip" and math.isnan(skip.err_upper) and skip.certified is None and skip.cert_ns is None


@pytest.mark.parametrize("flag, certify", [("--certify", True), ("--certify=tight", "tight")])
def test_certify_row_is_offbench_runs(tmp_path, flag, certify):
    """fit(certify=...)'s row is the row of `offbench run --certify[=tight]`."""
    from conftest import offbench_run
    p = offbench_run(tmp_path, "--curve", "liu2002_ex1", "--methods", "tiller,lee", "--tols", "1e-2", flag)
    for want in run_rows(p):
        r = offbench.fit(want["curve"], want["method"], float(want["d"]), float(want["tol"]), certify=certify)
        got = next(csv.DictReader([r.row], fieldnames=list(want)))
        for k in want:
            if k not in columns.TIMING:
                assert got[k] == want[k], (k, want, r.row)


@pytest.mark.parametrize("value, words", [("yes", "certify: True, False, 'verdict' or 'tight', not 'yes'"),
                                          (1, "certify: True, False, 'verdict' or 'tight', not 1"),
                                          (None, "certify: True, False, 'verdict' or 'tight', not None")])
def test_certify_bad_argument(value, words):
    with pytest.raises(offbench.InvalidError) as e:
        offbench.fit("liu2002_ex1", "tiller", 1, 1e-3, certify=value)
    assert words in str(e.value), str(e.value)


def test_certify_needs_a_new_library(monkeypatch):
    """An older library (before 0.4) has no obx_result_certify: fit without
    certify works, with it an UnsupportedError says what to rebuild."""
    real = offbench._lib.lib()

    class Old:
        def __getattr__(self, name):
            if name == "obx_result_certify":
                raise AttributeError(name)
            return getattr(real, name)

    monkeypatch.setattr(offbench._lib, "lib", lambda: Old())
    assert offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).status == "ok"
    with pytest.raises(offbench.UnsupportedError) as e:
        offbench.fit("liu2002_ex1", "tiller", 1, 1e-2, certify=True)
    assert "obx_result_certify needs liboffbench 0.4" in str(e.value) and "make lib" in str(e.value)
