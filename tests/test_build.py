"""The build pipeline (core/pipeline.py): backend choice and BuildInfo, saved with the table."""

from __future__ import annotations

import json

import numpy as np
import pytest

from core import AlphaComplex, FileFormatError, InputError
from core.pipeline import BuildInfo, build_complex
from core.storage.compact import unpack


@pytest.fixture(scope="module")
def points() -> np.ndarray:
    return np.random.default_rng(16).random((200, 3))


def test_build_info_records_the_backend(points):
    info = AlphaComplex.from_points(points).build_info
    assert (info.backend, info.uncertified) == ("qhull", 0)  # certified
    assert BuildInfo().uncertified == -1  # default: not certified (old tables, weighted)
    assert AlphaComplex.from_points(points, backend="qhull").build_info.backend == "qhull"


@pytest.mark.parametrize("backend", ["cgal", 3])
def test_unavailable_or_unknown_backend_is_an_input_error(points, backend):
    with pytest.raises(InputError, match="backend"):
        AlphaComplex.from_points(points, backend=backend)


def test_gmsh_backend_without_gmsh_is_an_input_error(points, monkeypatch):
    import core.backends

    monkeypatch.setattr(core.backends.gmsh_backend, "installed", lambda: False)
    with pytest.raises(InputError, match="backend 'gmsh' needs the optional gmsh"):
        AlphaComplex.from_points(points, backend="gmsh")


def test_from_points_is_the_pipeline(points):
    built = build_complex(points, weights=None)
    ac = AlphaComplex.from_points(points)
    np.testing.assert_array_equal(ac.points, built.points)
    for k in range(4):
        np.testing.assert_array_equal(ac.intervals(k)[:, 0], built.table.levels[k].enter)
    assert built.info == ac.build_info and built.ambient_dim == 3


def test_positional_progress_still_works(points):
    seen = []
    AlphaComplex.from_points(points, lambda f, s: seen.append((f, s)))
    fractions = [f for f, _ in seen]
    assert seen[0] == (0.0, "checking points") and fractions == sorted(fractions)


def test_build_info_round_trips_and_old_tables_default(points, tmp_path):
    ac = AlphaComplex.from_points(points)
    ac.save(tmp_path / "t.npz")
    with np.load(tmp_path / "t.npz") as f:
        arrays = dict(f)
    assert str(arrays["build_backend"]) == "qhull"
    assert AlphaComplex.load(tmp_path / "t.npz").build_info == ac.build_info
    old = unpack({k: v for k, v in arrays.items()
                  if not k.startswith("build_") and k != "checksums"})
    old["version"] = np.array(1)  # tables before BuildInfo were version 1: no checksums
    np.savez(tmp_path / "old.npz", **old)
    assert AlphaComplex.load(tmp_path / "old.npz").build_info.backend == "qhull"


def test_damaged_build_info_is_a_format_error(points, tmp_path):
    AlphaComplex.from_points(points).save(tmp_path / "t.npz")
    with np.load(tmp_path / "t.npz") as f:
        arrays = unpack({k: v for k, v in f.items() if k != "checksums"})
    arrays["version"] = np.array(1)  # no checksums: the build info's own check must find it
    arrays["build_backend"] = np.array(["qhull", "gmsh"])
    np.savez(tmp_path / "bad.npz", **arrays)
    with pytest.raises(FileFormatError, match="build info"):
        AlphaComplex.load(tmp_path / "bad.npz")


def test_info_reports_the_build(tmp_path, monkeypatch, capsys):
    from app.cli import main

    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    np.savetxt(tmp_path / "p.xyz", np.random.default_rng(3).random((60, 3)))
    assert main(["info", str(tmp_path / "p.xyz"), "--json"]) == 0
    build = json.loads(capsys.readouterr().out)["build"]
    assert (build["backend"], build["backend_note"]) == ("qhull", "")
    assert build["uncertified"] == 0 and {"exact_predicates", "flips"} <= build.keys()
    assert main(["info", str(tmp_path / "p.xyz")]) == 0
    assert "build       backend qhull, exact predicates " in capsys.readouterr().out
    assert BuildInfo().describe() == ("backend qhull, exact predicates 0, flips 0, "
                                      "not certified (weighted points or an older table)")
    geogram = BuildInfo("geogram")  # exact predicates: no alarm, no counts of a pass not run
    assert geogram.describe() == ("backend geogram, triangulated with its exact predicates "
                                  "(no certification pass)")
    assert BuildInfo("qhull", "geogram failed: x").describe().endswith("not certified (weighted "
                                                                      "points or an older table)")
