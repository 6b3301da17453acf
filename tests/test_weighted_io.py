"""Weighted point files: weight and radius columns, .npz arrays, the CLI's --weights, --radius,
--radius-add and --alpha2, and exports that carry alpha2."""

from __future__ import annotations

import json

import numpy as np
import pytest

from app.cli import main
from core import AlphaComplex
from core.errors import FileFormatError
from core.io import read_points


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture
def balls(tmp_path) -> tuple:
    """A CSV of 3D balls (x, y, z, radius, size, w) and the arrays it holds."""
    rng = np.random.default_rng(0)
    pts = rng.random((300, 3))
    r = rng.uniform(0.02, 0.06, 300)
    size = rng.uniform(0.01, 0.03, 300)
    path = tmp_path / "balls.csv"
    np.savetxt(path, np.column_stack([pts, r, size]), delimiter=",",
               header="x,y,z,radius,size", comments="")
    return path, pts, r, size


def run(capsys, *argv) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_radius_column_is_squared(balls) -> None:
    path, pts, r, _ = balls
    ps = read_points(path)
    np.testing.assert_array_equal(ps.points, pts)
    np.testing.assert_allclose(ps.weights, r**2, rtol=1e-15)
    assert "radius" in ps.report.weights_from and "weights" in ps.report.attributes


@pytest.mark.parametrize("header", ["x,y,z,w", "x,y,z,weight"])
def test_weight_column_is_taken_as_it_is(tmp_path, header: str) -> None:
    w = np.linspace(0.0, 0.01, 50)
    path = tmp_path / "w.csv"
    np.savetxt(path, np.column_stack([np.random.default_rng(1).random((50, 3)), w]),
               delimiter=",", header=header, comments="")
    np.testing.assert_allclose(read_points(path).weights, w, rtol=1e-15)


def test_named_columns_and_probe_radius(balls) -> None:
    path, _, r, size = balls
    np.testing.assert_allclose(read_points(path, radius="size").weights, size**2, rtol=1e-15)
    np.testing.assert_allclose(read_points(path, weights="size").weights, size, rtol=1e-15)
    probe = read_points(path, radius_add=0.5)
    np.testing.assert_allclose(probe.weights, (r + 0.5) ** 2, rtol=1e-15)
    assert "0.5 added" in probe.report.weights_from
    with pytest.raises(FileFormatError, match="no column named 'nope'"):
        read_points(path, radius="nope")


def test_rgb_colour_r_is_no_radius(tmp_path) -> None:
    path = tmp_path / "rgb.csv"
    np.savetxt(path, np.column_stack([np.random.default_rng(2).random((30, 3)),
                                      np.full((30, 3), 200)]),
               delimiter=",", header="x,y,z,r,g,b", comments="")
    ps = read_points(path)
    assert ps.weights is None and "colors" in ps.report.attributes


def test_npz_weights_and_radius_arrays(tmp_path) -> None:
    pts = np.random.default_rng(3).random((80, 2))
    w = np.linspace(0, 1e-3, 80)
    np.savez(tmp_path / "w.npz", points=pts, weights=w)
    np.savez(tmp_path / "r.npz", points=pts, radius=np.sqrt(w))
    np.testing.assert_allclose(read_points(tmp_path / "w.npz").weights, w)
    np.testing.assert_allclose(read_points(tmp_path / "r.npz").weights, w, rtol=1e-12)


def test_duplicates_keep_the_heaviest_ball(tmp_path) -> None:
    path = tmp_path / "dup.csv"
    path.write_text("x,y,w\n0,0,0.1\n1,0,0.2\n0,1,0.1\n1,0,0.5\n1,1,0.1\n")
    ps = read_points(path)
    assert len(ps.points) == 4
    row = int(np.flatnonzero((ps.points == [1, 0]).all(axis=1))[0])
    assert ps.weights[row] == 0.5


def test_info_reports_weights_hidden_points_and_alpha2(balls, capsys) -> None:
    path = balls[0]
    code, out, err = run(capsys, "info", path, "--alpha2", "-0.0005")
    assert code == 0 and err == ""
    assert "the radius column (radius, r) squared" in out and "hidden" in out
    assert "alpha² -0.0005" in out
    code, out, _ = run(capsys, "info", path, "--alpha2", "-0.0005", "--json")
    info = json.loads(out)
    ps = read_points(path)
    ac = AlphaComplex.from_points(ps.points, weights=ps.weights)
    assert info["weighted"] and info["alpha2"] == -0.0005
    assert info["hidden_points"] == int((ac.input_index < 0).sum())
    assert info["betti"] == list(ac.betti(alpha2=-0.0005))
    assert info["optimal_alpha2"] == pytest.approx(ac.optimal_alpha2())
    assert info["spectrum"]["min2"] == pytest.approx(ac.spectrum_sq()[0])
    assert info["load"]["weights_from"]


def test_hidden_points_counted_by_info(tmp_path, capsys) -> None:
    axes = np.meshgrid(np.arange(6.0), np.arange(6.0), indexing="ij")
    pts = np.column_stack([a.ravel() for a in axes])
    pts = np.vstack([pts, [[2.5, 2.5], [2.6, 2.5]]])
    w = np.full(len(pts), 0.05)
    w[-2:] = 0.3, 0.01
    path = tmp_path / "hidden.csv"
    np.savetxt(path, np.column_stack([pts, w]), delimiter=",", header="x,y,w", comments="")
    code, out, _ = run(capsys, "info", path, "--json")
    assert code == 0 and json.loads(out)["hidden_points"] == 1


def test_negative_alpha_points_to_alpha2(balls, capsys) -> None:
    code, _, err = run(capsys, "info", balls[0], "--alpha", "-0.01")
    assert code == 2 and "--alpha2" in err and "Traceback" not in err
    code, _, err = run(capsys, "info", balls[0], "--alpha", "0.1", "--alpha2", "0.01")
    assert code == 2


def test_cli_weight_options(balls, capsys) -> None:
    path = balls[0]
    code, out, _ = run(capsys, "info", path, "--radius", "size", "--radius-add", "0.01",
                       "--json")
    assert code == 0
    assert "'size'" in json.loads(out)["load"]["weights_from"]
    code, _, err = run(capsys, "info", path, "--weights", "size", "--radius", "size")
    assert code == 2
    code, _, err = run(capsys, "info", path, "--weights", "missing")
    assert code == 1 and "no column named 'missing'" in err


def test_export_carries_alpha2(balls, tmp_path, capsys) -> None:
    out_path = tmp_path / "shape.ply"
    code, out, err = run(capsys, "export", balls[0], "--alpha2", "0.001", "-o", out_path,
                         "--sidecar")
    assert code == 0, err
    assert "alpha² 0.001" in out
    meta = json.loads((tmp_path / "shape.ply.json").read_text())
    assert meta["weighted"] is True and meta["alpha2"] == 0.001
    assert meta["hidden_points"] >= 0 and "betti" in meta
    code, out, _ = run(capsys, "export", balls[0], "--alpha2", "-0.0001", "-o",
                       tmp_path / "low.vtu", "--sidecar")
    assert code == 0
    assert json.loads((tmp_path / "low.vtu.json").read_text())["alpha2"] == -0.0001


def test_table_export_of_a_weighted_set(balls, tmp_path, capsys) -> None:
    ps = read_points(balls[0])
    ac = AlphaComplex.from_points(ps.points, weights=ps.weights)
    assert run(capsys, "export", balls[0], "--table", "-o", tmp_path / "t.npz")[0] == 0
    assert run(capsys, "export", balls[0], "--table", "-o", tmp_path / "t.csv")[0] == 0
    with np.load(tmp_path / "t.npz") as data:
        np.testing.assert_array_equal(data["weights"], ac.weights)
        np.testing.assert_array_equal(data["intervals_sq_1"], ac.intervals_sq(1))
    rows = np.loadtxt(tmp_path / "t.csv", delimiter=",", skiprows=1)
    assert (tmp_path / "t.csv").read_text().startswith("k,v0,v1,v2,v3,enter2,")
    np.testing.assert_array_equal(rows[rows[:, 0] == 0, 5], ac.intervals_sq(0)[:, 0])
