"""`alphascoop info --backend qhull|gmsh`: the backend that built the table is reported."""

from __future__ import annotations

import json

import numpy as np
import pytest

import core.backends
from app.cli import main


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    """Every test gets its own empty table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path / "cache"


@pytest.fixture
def xyz(tmp_path):
    path = tmp_path / "points.xyz"
    np.savetxt(path, np.random.default_rng(4).uniform(size=(400, 3)))
    return path


def info(capsys, *argv) -> dict:
    assert main(["info", *map(str, argv), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_info_reports_the_qhull_backend(capsys, xyz):
    got = info(capsys, xyz, "--backend", "qhull")
    assert (got["backend"], got["backend_note"]) == ("qhull", "")
    assert main(["info", str(xyz), "--backend", "qhull"]) == 0
    assert "build       backend qhull" in capsys.readouterr().out


@pytest.mark.skipif(not core.backends.gmsh_backend.installed(), reason="gmsh not installed")
def test_info_backend_gmsh_rebuilds_a_table_qhull_cached(capsys, xyz):
    first = info(capsys, xyz, "--backend", "qhull")
    again = info(capsys, xyz, "--backend", "gmsh")
    assert again["backend"] == "gmsh" and not again["complex"]["from_cache"]
    assert {k: v for k, v in again.items() if k not in ("backend", "build", "complex")} == {
        k: v for k, v in first.items() if k not in ("backend", "build", "complex")}
    cached = info(capsys, xyz)  # automatic: whatever table is cached serves
    assert cached["complex"]["from_cache"]


def test_unknown_backend_is_a_usage_error(capsys, xyz):
    assert main(["info", str(xyz), "--backend", "cgal"]) != 0
    err = capsys.readouterr().err
    assert "--backend" in err and len(err.strip().splitlines()) == 1


def test_forced_gmsh_without_gmsh_is_one_line(capsys, xyz, monkeypatch):
    monkeypatch.setattr(core.backends.gmsh_backend, "installed", lambda: False)
    assert main(["info", str(xyz), "--backend", "gmsh"]) != 0
    err = capsys.readouterr().err
    assert "alphascoop[fast]" in err and len(err.strip().splitlines()) == 1


def test_load_report_line_names_the_backend(tmp_path):
    """The window's status line and info dock use Dataset.build_line."""
    from app.dataset import Dataset
    from core import AlphaComplex

    ac = AlphaComplex.from_points(np.random.default_rng(2).uniform(size=(60, 3)),
                                  backend="qhull")
    ds = Dataset(tmp_path / "p.xyz", ac, ac.spectrum(), ac.optimal_alpha(), ac.default_alpha(),
                 ac.signatures(), 60, None, 0.1, 1.25)
    assert ds.build_line() == "built in 1.25 s (qhull)"
