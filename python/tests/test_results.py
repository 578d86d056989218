"""read_results and read_meta: a run's files, typed as docs/python.md
documents them, with pandas and without; bad files named FILE:LINE."""

import csv
import math

import pytest

import offbench
from offbench import columns

DTYPES = {
    "curve": "object", "d": "float64", "method": "category", "metric": "category", "split": "category",
    "tol": "float64", "ctrl_points": "int64", "segments": "int64", "out_degree": "int64", "max_err": "float64",
    "status": "category", "fit_ns": "int64", "eval_ns": "int64", "message": "object", "family": "category",
    "offset_degree": "Int64", "offset_rational": "boolean", "max_gap": "float64", "max_kink": "float64",
    "continuity": "category", "time_iqr_ns": "Int64", "time_cv": "float64", "err_upper": "float64",
    "err_lower": "float64", "certified": "boolean", "cert_ns": "Int64", "fit_calls": "Int64",
    "method_ns": "float64", "method_iqr_ns": "float64", "trimmed_err": "float64", "trimmed_cut": "Int64",
}


def test_documented_dtypes_are_the_tables():
    """The table above is docs/python.md's, and the package's."""
    assert {k: columns.PANDAS_DTYPES[v] for k, v in columns.KINDS.items()} == DTYPES
    assert list(DTYPES) == offbench.fit("liu2002_ex1", "tiller", 1, 1e-1).columns


def test_frame(reps_run):
    pd = pytest.importorskip("pandas")
    df = offbench.read_results(reps_run)
    assert isinstance(df, pd.DataFrame) and len(df) == 3
    assert {k: str(v) for k, v in df.dtypes.items()} == DTYPES
    assert list(df["method"]) == ["tiller", "kim2018", "zhao"]
    assert list(df["status"]) == ["ok", "skip", "ok"]
    assert df["time_iqr_ns"].notna().all() and df["time_cv"].notna().all()  # --reps 2
    assert df["offset_rational"].all() and list(df["offset_degree"]) == [4, 4, 4]
    assert df["max_err"].isna().tolist() == [False, True, False]
    assert list(df["continuity"]) == ["", "", "open"]
    # the file itself as well as its directory
    same = offbench.read_results(reps_run / "results.csv")
    assert same.drop(columns=list(columns.TIMING)).equals(df.drop(columns=list(columns.TIMING)))


def test_records_match_the_frame(reps_run, no_pandas):
    recs = offbench.read_results(reps_run)
    assert isinstance(recs, list) and len(recs) == 3 and list(recs[0]) == list(DTYPES)
    tiller, kim, zhao = recs
    assert isinstance(tiller["ctrl_points"], int) and isinstance(tiller["max_err"], float)
    assert isinstance(tiller["time_iqr_ns"], int) and tiller["offset_rational"] is True
    assert kim["status"] == "skip" and math.isnan(kim["max_err"]) and kim["max_gap"] != kim["max_gap"]
    assert zhao["continuity"] == "open"


def test_records_equal_fit(cross_runs):
    """read_results' typed values are fit()'s for the same jobs."""
    for rec in offbench.read_results(cross_runs["atlas_circle"], as_frame=False):
        r = offbench.fit(rec["curve"], rec["method"], rec["d"], rec["tol"])
        for k, v in rec.items():
            if k not in columns.TIMING:
                assert getattr(r, k) == v or (v != v and getattr(r, k) != getattr(r, k)), (k, v)


def test_meta(reps_run):
    meta = offbench.read_meta(reps_run)
    assert meta["program"] == "offbench" and meta["backend"] == "cpu"
    assert offbench.read_meta(reps_run / "meta.json") == meta


def test_as_frame_argument(reps_run):
    with pytest.raises(offbench.InvalidError):
        offbench.read_results(reps_run, as_frame="yes")


def write(path, text):
    path.write_text(text)
    return path


def test_bad_files(tmp_path, reps_run):
    with pytest.raises(offbench.FileError) as e:
        offbench.read_results(tmp_path)
    assert str(tmp_path / "results.csv") in str(e.value) and isinstance(e.value, OSError)
    with pytest.raises(offbench.FileError):
        offbench.read_meta(tmp_path / "none.json")
    p = write(tmp_path / "other.csv", "a,b\n1,2\n")
    with pytest.raises(offbench.ParseError) as e:
        offbench.read_results(p)
    assert str(e.value).startswith("%s:1: not a results.csv" % p)
    lines = (reps_run / "results.csv").read_text().splitlines()
    rows = list(csv.reader(lines[:3]))
    rows[2][rows[0].index("ctrl_points")] = "many"
    p = tmp_path / "bad.csv"
    with open(p, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(rows)
    with pytest.raises(offbench.ParseError) as e:
        offbench.read_results(p, as_frame=False)
    assert str(e.value) == "%s:3: column ctrl_points: 'many' is not a whole number" % p
    p = write(tmp_path / "short.csv", lines[0] + "\n" + "x,1\n")
    with pytest.raises(offbench.ParseError) as e:
        offbench.read_results(p)
    assert ":2: 2 fields under a header of %d columns" % len(columns.KINDS) in str(e.value)
    p = write(tmp_path / "rat.csv", "curve,method,offset_rational\nx,tiller,maybe\n")
    with pytest.raises(offbench.ParseError) as e:
        offbench.read_results(p)
    assert "column offset_rational: 'maybe' is not yes, no or empty" in str(e.value)
    p = write(tmp_path / "meta.json", '{"a": 1,\n "b": }\n')
    with pytest.raises(offbench.ParseError) as e:
        offbench.read_meta(tmp_path)
    assert str(e.value).startswith("%s:2:" % p) and isinstance(e.value, ValueError)
    write(tmp_path / "meta.json", "[1, 2]")
    with pytest.raises(offbench.ParseError):
        offbench.read_meta(tmp_path)
    p = tmp_path / "bin.csv"
    p.write_bytes(b"curve,method\n\xff\xfe,x\n")
    with pytest.raises(offbench.ParseError):
        offbench.read_results(p)


def test_an_older_file_without_the_later_columns(tmp_path):
    """A results.csv of an older build (no joint or spread columns) reads,
    with the columns it has."""
    p = write(tmp_path / "old.csv", "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,"
              "fit_ns,eval_ns,message\nx,1,tiller,hausdorff,mid,0.01,4,1,3,0.001,ok,10,20,\"a, b\"\n")
    (r,) = offbench.read_results(p, as_frame=False)
    assert r["message"] == "a, b" and r["ctrl_points"] == 4 and "continuity" not in r


def test_empty_run(tmp_path):
    p = write(tmp_path / "results.csv", ",".join(DTYPES) + "\n")
    assert offbench.read_results(p, as_frame=False) == []
    pd = pytest.importorskip("pandas")
    df = offbench.read_results(p)
    assert len(df) == 0 and {k: str(v) for k, v in df.dtypes.items()} == DTYPES
    assert isinstance(df, pd.DataFrame)


def test_certified_run(tmp_path):
    """run --certify: err_upper and err_lower are floats with
    err_lower <= err_upper, certified a boolean that is True exactly when
    err_upper <= tol, cert_ns a whole number; empty (NaN, None) on a job
    without an approximation."""
    from conftest import offbench_run
    p = offbench_run(tmp_path, "--curve", "atlas_circle", "--methods", "tiller,kim2018,zhao", "--tols", "1e-2",
                     "--certify")
    rows = offbench.read_results(p, as_frame=False)
    assert [r["status"] for r in rows] == ["ok", "skip", "ok"]
    for r in rows:
        if r["status"] == "ok":
            assert 0 <= r["err_lower"] <= r["err_upper"] and r["max_err"] <= r["err_upper"]
            assert r["certified"] is (r["err_upper"] <= r["tol"]) and isinstance(r["cert_ns"], int)
        else:
            assert math.isnan(r["err_upper"]) and r["certified"] is None and r["cert_ns"] is None
    pd = pytest.importorskip("pandas")
    df = offbench.read_results(p)
    assert str(df["certified"].dtype) == "boolean" and str(df["err_upper"].dtype) == "float64"
    assert df["certified"].isna().tolist() == [False, True, False]


def test_certificate_timed_out(tmp_path):
    """A certificate stopped by --job-timeout (issue 47): cert_ns alone, no
    verdict: err_upper and err_lower NaN, certified None, cert_ns an int;
    the file's other certificate rows as before.  The row is written here as
    run --certify writes a timed-out one (tests/e2e/e2e_certify_timeout.sh
    checks that the run does): whether a real certificate passes a timeout
    depends on the machine's load, and a test must not."""
    import csv
    from conftest import offbench_run
    p = offbench_run(tmp_path, "--random", "20:7", "--curve", "rnd7_000010", "--methods", "lee,tiller", "--tols",
                     "1e-3", "--certify=tight")
    with open(p, newline="") as f:
        table = list(csv.reader(f))
    head = table[0]
    for row in table[1:]:
        if row[head.index("method")] == "lee":
            for c in ("err_upper", "err_lower", "certified"):
                row[head.index(c)] = ""
            row[head.index("cert_ns")] = "600000000"
    with open(p, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(table)
    rows = {r["method"]: r for r in offbench.read_results(p, as_frame=False)}
    lee, tiller = rows["lee"], rows["tiller"]
    assert lee["status"] == "limit" and math.isnan(lee["err_upper"]) and math.isnan(lee["err_lower"])
    assert lee["certified"] is None and isinstance(lee["cert_ns"], int) and lee["cert_ns"] >= 5e8
    assert tiller["certified"] is True and tiller["err_lower"] <= tiller["err_upper"] <= 1e-3
    pd = pytest.importorskip("pandas")
    df = offbench.read_results(p)
    assert df["certified"].isna().tolist() == [True, False] and df["cert_ns"].notna().all()


def _certify_table(tmp_path):
    """run --certify's results.csv (rows ok, skip, ok) as a list of rows."""
    from conftest import offbench_run
    p = offbench_run(tmp_path, "--curve", "atlas_circle", "--methods", "tiller,kim2018,zhao", "--tols", "1e-2",
                     "--certify")
    with open(p, newline="") as f:
        return p, list(csv.reader(f))


def _set(table, line, **cols):
    """Row `line` of the file (2: the first row) with columns changed."""
    head = table[0]
    for c, v in cols.items():
        table[line - 1][head.index(c)] = v


# (what, line, columns changed, words of the error); rows 2 and 4 are ok, row 3 skip
_BAD_CERTIFICATES = [
    ("certified=yes on a skip row", 3, dict(err_upper="1e-4", err_lower="1e-5", certified="yes", cert_ns="100"),
     "status skip has no approximation to certify"),
    ("err_upper < max_err on a fail row", 2, dict(status="fail", err_upper="1e-9", err_lower="0"),
     "status fail has no approximation to certify"),
    ("a certificate on a timeout row", 4, dict(status="timeout"), "status timeout has no approximation to certify"),
    ("certified=yes over tol", 2, dict(err_upper="1", err_lower="0", certified="yes"),
     "certified must be yes exactly when err_upper <= tol"),
    ("err_lower over err_upper", 2, dict(err_upper="1e-4", err_lower="1e-3"), "err_lower is not a finite number"),
    ("some columns only", 2, dict(err_lower="", certified=""), "all empty or all set"),
]


@pytest.mark.parametrize("what, line, cols, words", _BAD_CERTIFICATES, ids=[c[0] for c in _BAD_CERTIFICATES])
def test_certificate_columns_checked(tmp_path, what, line, cols, words):
    """A row whose certificate the C reader (host/io/results_csv.c) refuses is
    refused here too, naming FILE:LINE: a certificate on a row without an
    approximation (fail, skip, timeout), a verdict that contradicts its
    bounds, half a certificate."""
    p, table = _certify_table(tmp_path)
    _set(table, line, **cols)
    with open(p, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(table)
    for as_frame in (False, None):
        with pytest.raises(offbench.ParseError) as e:
            offbench.read_results(p, as_frame=as_frame)
        assert str(e.value).startswith("%s:%d: " % (p, line)) and words in str(e.value), str(e.value)
