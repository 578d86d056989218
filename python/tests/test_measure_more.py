"""measure(metric="trimmed-hausdorff") and measure_pieces give what
`offbench measure --trimmed` and `--per-piece` write for the same pieces
(written to a .curves file the CLI reads), number for number: the CSVs'
numbers read back exactly (the shortest text that does), so == holds.
(liboffbench 0.7; tests/unit/test_api_measure_more.c checks the same in C.)"""

import csv
import math
import subprocess

import pytest

import offbench

from conftest import PROGRAM, ROOT


def _write_curves(path, pieces):
    """The pieces as a .curves file without base links, each control point
    as the shortest text that reads back exactly (repr)."""
    with open(path, "w") as f:
        for k, b in enumerate(pieces):
            f.write("curve p%04d\n  bezier %d\n" % (k, b.degree))
            w = b.weights if b.weights is not None else [1.0] * (b.degree + 1)
            for (x, y), wk in zip(b.points, w):
                f.write("  point %r %r %r\n" % (float(x), float(y), float(wk)))
            f.write("  offset 1\nend\n")  # the format needs one; measure takes --d


def _cli(tmp_path, curve, d, pieces, *args):
    """`offbench measure` of the pieces: its CSV rows (dicts)."""
    if not PROGRAM.is_file():
        pytest.fail("the program %s is missing (make, or set OFFBENCH)" % PROGRAM)
    approx = tmp_path / "pieces.curves"
    _write_curves(approx, pieces)
    cmd = [str(PROGRAM), "measure", "--curve", curve, "--d", repr(float(d)), "--approx", str(approx), *args]
    p = subprocess.run(cmd, cwd=str(ROOT), stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    assert p.returncode == 0, "%s: exit %d: %s" % (" ".join(cmd), p.returncode, p.stderr[-2000:])
    return list(csv.DictReader(p.stdout.splitlines()))


def _bulged(pieces, k, dy=0.02):
    """The pieces with a local defect planted in piece k: its inner control
    points moved dy up (its ends stay on the offset)."""
    out = list(pieces)
    q = out[k].points.copy()
    q[1:-1] += [0, dy]
    out[k] = offbench.Bezier(q, out[k].weights)
    return out


@pytest.fixture(scope="module")
def tiller():
    return offbench.fit("liu2002_ex1", "tiller", 1, 1e-3).pieces


@pytest.mark.parametrize("d, take", [(-1, "all"), (-1, "half"), (1, "all")])
def test_trimmed_hausdorff_is_the_clis(tmp_path, d, take):
    """trimmed-hausdorff: --trimmed's row, bit for bit.  At d = -1 nothing
    is cut (the fit measures within its tol); half the pieces are measured
    too (no cover check: a trimmed file does not cover the untrimmed
    offset), far off where the other half is missing; at d = 1 the end
    circle cuts the offset, and the untrimmed fit is far from it there."""
    pieces = offbench.fit("liu2002_ex1", "tiller", d, 1e-3).pieces
    if take == "half":
        pieces = pieces[:len(pieces) // 2]
    m = offbench.measure("liu2002_ex1", d, pieces, metric="trimmed-hausdorff")
    row, = [r for r in _cli(tmp_path, "liu2002_ex1", d, pieces, "--trimmed") if r["metric"] == "trimmed-hausdorff"]
    assert m.status == row["status"] == "ok" and m.metric == "trimmed-hausdorff" and m.message == ""
    assert m.max_err == float(row["max_err"]) and m.piece == int(row["piece"])
    assert m.max_err > 0.5 if (d, take) != (-1, "all") else m.max_err <= 1e-3


def test_trimmed_hausdorff_where_nothing_is_cut_is_hausdorff_whole():
    """At d = -1 the trimmed offset is the whole offset: the two metrics
    agree to rounding (two searches, not one code); at d = 1 the untrimmed
    fit is within tol of the untrimmed offset, and not of the trimmed."""
    r = offbench.fit("liu2002_ex1", "tiller", -1, 1e-3)
    t = offbench.measure("liu2002_ex1", -1, r, metric="trimmed-hausdorff").max_err
    assert t == pytest.approx(offbench.measure("liu2002_ex1", -1, r, metric="hausdorff-whole").max_err, rel=1e-9)
    r = offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)
    assert offbench.measure("liu2002_ex1", 1, r).max_err <= 1e-3
    assert offbench.measure("liu2002_ex1", 1, r, metric="trimmed-hausdorff").max_err > 0.5


def _rows_as_cli(got, rows):
    assert len(got) == len(rows)
    for k, (g, r) in enumerate(zip(got, rows)):
        assert isinstance(g, offbench.PieceError) and g.piece == k == int(r["piece"])
        want = (int(r["seg0"]), float(r["t0"]), int(r["seg1"]), float(r["t1"]), float(r["max_err"]), int(r["seg"]),
                float(r["t"]), float(r["x"]), float(r["y"]), float(r["x_off"]), float(r["y_off"]))
        have = (g.seg0, g.t0, g.seg1, g.t1, g.max_err, g.seg, g.t, g.x, g.y, g.x_off, g.y_off)
        assert have == want, "piece %d: %r, the CLI's %r" % (k, have, want)
        assert g.status == "ok" and g.message == ""


@pytest.mark.parametrize("method", ["tiller", "lee"])  # lee: rational pieces
def test_measure_pieces_is_the_clis_per_piece(tmp_path, method):
    pieces = offbench.fit("liu2002_ex1", method, 1, 1e-3).pieces
    got = offbench.measure_pieces("liu2002_ex1", 1, pieces)
    out = tmp_path / "pp.csv"
    _cli(tmp_path, "liu2002_ex1", 1, pieces, "--per-piece", str(out))
    with open(out) as f:
        _rows_as_cli(got, list(csv.DictReader(f)))
    # the largest row is measure's hausdorff, at its piece (perpiece.h)
    m = offbench.measure("liu2002_ex1", 1, pieces)
    worst = max(range(len(got)), key=lambda k: got[k].max_err)
    assert got[worst].max_err == m.max_err and worst == m.piece


def test_a_planted_defect_is_found_at_its_piece(tmp_path, tiller):
    k = len(tiller) // 3
    pieces = _bulged(tiller, k)
    got = offbench.measure_pieces("liu2002_ex1", 1, pieces)
    worst = max(range(len(got)), key=lambda i: got[i].max_err)
    assert worst == k and got[k].max_err > 5e-3
    assert all(g.max_err < 1e-3 for i, g in enumerate(got) if i != k)
    out = tmp_path / "pp.csv"
    _cli(tmp_path, "liu2002_ex1", 1, pieces, "--per-piece", str(out))
    with open(out) as f:
        _rows_as_cli(got, list(csv.DictReader(f)))
    # a Result's pieces are taken as measure takes them
    assert offbench.measure_pieces("liu2002_ex1", 1, offbench.fit("liu2002_ex1", "tiller", 1, 1e-3)) == \
        offbench.measure_pieces("liu2002_ex1", 1, tiller)


@pytest.mark.parametrize("kw, exc, words", [
    (dict(pieces=[]), offbench.InvalidError, "pieces: none given"),
    (dict(pieces=[[[0, 0], [float("nan"), 0]]]), offbench.InvalidError, "pieces[0]: point 1 is not finite"),
    (dict(d=float("nan")), offbench.InvalidError, "finite"),
    (dict(curve="nosuch"), offbench.UnknownCurveError, "nosuch"),
    (dict(pieces="half"), offbench.MeasureError, "does not cover the d = 1 offset of curve liu2002_ex1 once"),
    (dict(pieces=[[[50, 50], [60, 60]]]), offbench.MeasureError, "piece 0"),
])
def test_measure_pieces_bad_arguments(tiller, kw, exc, words):
    args = dict(curve="liu2002_ex1", d=1, pieces=tiller)
    args.update(kw)
    if args["pieces"] == "half":
        args["pieces"] = tiller[:len(tiller) // 2]
    with pytest.raises(exc) as e:
        offbench.measure_pieces(args["curve"], args["d"], args["pieces"])
    assert words in str(e.value), str(e.value)
