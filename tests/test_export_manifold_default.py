"""Surface exports are 2-manifold by default; --no-manifold keeps the raw boundary."""

from __future__ import annotations

import numpy as np
import pytest

from app.cli import build_parser, main
from core import AlphaComplex
from core.export import write_shape

ALPHA = 0.25


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def shell_points(n: int = 600) -> np.ndarray:
    """A thick spherical shell whose shape at ALPHA pinches (non-manifold edges)."""
    rng = np.random.default_rng(1)
    p = rng.normal(size=(n, 3))
    return p * rng.uniform(0.7, 1.0, (n, 1)) / np.linalg.norm(p, axis=1, keepdims=True)


def most_faces_on_an_edge(path) -> int:
    import trimesh

    mesh = trimesh.load(str(path), process=False, force="mesh")
    edges = np.sort(mesh.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    return int(np.unique(edges, axis=0, return_counts=True)[1].max())


def test_core_writes_a_manifold_surface_unless_asked_not_to(tmp_path):
    ac = AlphaComplex.from_points(shell_points())
    default = write_shape(ac, ALPHA, tmp_path / "d.ply")
    raw = write_shape(ac, ALPHA, tmp_path / "r.ply", manifold=False)
    assert default.manifold and "split" in default.manifold and raw.manifold is None
    assert most_faces_on_an_edge(tmp_path / "d.ply") == 2
    assert most_faces_on_an_edge(tmp_path / "r.ply") > 2, "the raw boundary pinches here"


@pytest.mark.parametrize(("options", "manifold"), [([], True), (["--manifold"], True),
                                                   (["--no-manifold"], False)])
def test_cli_manifold_by_default(capsys, tmp_path, options, manifold):
    source = tmp_path / "shell.xyz"
    np.savetxt(source, shell_points())
    out = tmp_path / "s.ply"
    code = main(["export", str(source), "-o", str(out), "--alpha", str(ALPHA), *options])
    stdout, err = capsys.readouterr()
    assert code == 0 and err == ""
    assert ("split" in stdout) == manifold
    assert (most_faces_on_an_edge(out) == 2) == manifold


def test_manifold_options_exclude_each_other(capsys):
    assert main(["export", "x.xyz", "-o", "y.ply", "--manifold", "--no-manifold"]) == 2
    assert "not allowed with" in capsys.readouterr().err
    assert build_parser().parse_args(["export", "x", "-o", "y.ply"]).manifold is True
