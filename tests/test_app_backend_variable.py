"""$ALPHASCOOP_BACKEND forces the window's triangulation backend as `--backend` does the
command line's: unset, empty or "auto" is the automatic choice; anything else is refused with
a message naming the variable, before the file is read."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from app.dataset import BACKEND_VARIABLE, load_dataset, window_backend
from app.worker import load_failure
from core.backends import GMSH_FROM_POINTS
from core.errors import InputError

HAVE_GMSH = importlib.util.find_spec("gmsh") is not None
N = GMSH_FROM_POINTS + 5_000  # where the automatic choice takes gmsh when it is installed


@pytest.fixture
def points_file(tmp_path, monkeypatch) -> Path:
    """A spread 25k point set and an empty private table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    path = tmp_path / "cloud.npy"
    np.save(path, np.random.default_rng(5).random((N, 3)))
    return path


def _backend(path: Path) -> str:
    return load_dataset(path, lambda *_: None, topology=False).ac.build_info.backend


@pytest.mark.parametrize("value", ["", "auto", " AUTO "])
def test_unset_empty_or_auto_is_the_automatic_choice(value, monkeypatch) -> None:
    monkeypatch.setenv(BACKEND_VARIABLE, value)
    assert window_backend() is None
    monkeypatch.delenv(BACKEND_VARIABLE)
    assert window_backend() is None


@pytest.mark.skipif(not HAVE_GMSH, reason="without gmsh the automatic choice is Qhull too")
def test_qhull_is_forced_where_the_automatic_choice_takes_gmsh(points_file, monkeypatch) -> None:
    monkeypatch.delenv(BACKEND_VARIABLE, raising=False)
    assert _backend(points_file) == "gmsh"
    monkeypatch.setenv(BACKEND_VARIABLE, "qhull")
    assert window_backend() == "qhull"
    assert _backend(points_file) == "qhull"  # the cached gmsh table is not taken for it


@pytest.mark.skipif(not HAVE_GMSH, reason="the optional gmsh package is not installed")
def test_gmsh_is_forced_and_refused_where_it_cannot_build(tmp_path, points_file,
                                                          monkeypatch) -> None:
    monkeypatch.setenv(BACKEND_VARIABLE, "Gmsh")
    assert _backend(points_file) == "gmsh"
    small = tmp_path / "lattice.npy"  # exactly cospherical: gmsh cannot promise Delaunay
    np.save(small, np.stack(np.meshgrid(*[np.arange(4.0)] * 3), axis=-1).reshape(-1, 3))
    with pytest.raises(InputError) as caught:
        load_dataset(small, lambda *_: None, topology=False)
    assert "gmsh" in str(caught.value).split("(the backend")[0]  # gmsh's own reason
    assert str(caught.value).endswith("(the backend was forced by ALPHASCOOP_BACKEND=gmsh)")


def test_a_wrong_value_is_one_line_naming_the_variable(points_file, monkeypatch) -> None:
    monkeypatch.setenv(BACKEND_VARIABLE, "cgal")
    read = []
    with pytest.raises(InputError) as caught:
        load_dataset(points_file, lambda fraction, stage: read.append(stage), topology=False)
    message = load_failure(points_file, caught.value)
    assert message == "ALPHASCOOP_BACKEND='cgal': must be qhull, gmsh, auto or empty (automatic)"
    assert "\n" not in message
    assert read == []  # refused before the file is read
