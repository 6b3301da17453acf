"""`alphascoop info` and `export` agree with the window on where a file opens, on real files:
export without --alpha writes the opening alpha's shape (a molecule's at alpha² = 0), info
says so with the pieces there."""

from __future__ import annotations

import json

import numpy as np
import pytest
from reference import data_dir

from app.cli import main
from core import AlphaComplex
from core.io import read_points

DATA = data_dir()
needs_data = pytest.mark.skipif(DATA is None, reason="shared real scans absent")


@pytest.fixture(autouse=True)
def own_cache(tmp_path, monkeypatch):
    """A private table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def info_json(capsys, *args: str) -> dict:
    """`alphascoop info ARGS --json` as a dict."""
    assert main(["info", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@needs_data
def test_export_writes_the_opening_alpha(capsys, tmp_path) -> None:
    """milk.pcd exported without --alpha is the shape at info's default_alpha (it was CGAL's
    optimal, a blob); --optimal still writes the optimal one."""
    info = info_json(capsys, str(DATA / "milk.pcd"))
    assert info["default_alpha"] < info["optimal_alpha"]
    assert main(["export", str(DATA / "milk.pcd"), "-o", str(tmp_path / "x.vtu")]) == 0
    assert f"{info['default_alpha']:.6g}" in capsys.readouterr().out
    ac = AlphaComplex.from_points(read_points(DATA / "milk.pcd").points)
    assert info["default_alpha"] == ac.default_alpha()
    assert main(["export", str(DATA / "milk.pcd"), "-o", str(tmp_path / "y.vtu"),
                 "--optimal"]) == 0
    assert f"{info['optimal_alpha']:.6g}" in capsys.readouterr().out


@needs_data
def test_a_molecule_opens_and_exports_at_alpha_squared_zero(capsys, tmp_path) -> None:
    """1A8O.pdb: info's opening alpha² is 0, where its measures are (it said -6.31), and
    export writes that shape by default (not the optimal alpha² 8.2)."""
    info = info_json(capsys, str(DATA / "1A8O.pdb"))
    assert info["default_alpha2"] == 0.0 and info["alpha2"] == 0.0
    assert info["optimal_alpha2"] > 0
    assert main(["info", str(DATA / "1A8O.pdb")]) == 0
    text = capsys.readouterr().out
    assert "opening     alpha² 0 (alpha 0)" in text and "volume (Å³)" in text
    assert "uncertified -1" not in text
    assert main(["export", str(DATA / "1A8O.pdb"), "-o", str(tmp_path / "m.ply")]) == 0
    assert "alpha² 0" in capsys.readouterr().out


@needs_data
@pytest.mark.slow
def test_info_says_the_pieces_at_the_opening(capsys) -> None:
    """bun000_rangegrid.ply: the opening alpha in spacings and its pieces, text and JSON."""
    info = info_json(capsys, str(DATA / "bun000_rangegrid.ply"))
    assert info["opening_spacings"] <= 2.5
    pieces = info["opening_pieces"]
    assert pieces["count"] == 5 and pieces["held"] >= 0.99
    assert np.isclose(sum(pieces["largest"]), 0.88 + 0.079 + 0.022, atol=0.01)
    assert main(["info", str(DATA / "bun000_rangegrid.ply")]) == 0
    assert "pieces      5 pieces of 41+ points hold 99 % of the points" in (
        capsys.readouterr().out)
