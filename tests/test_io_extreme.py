"""Extreme or corrupt coordinates (1.7e308 in a CSV, a LAS scale or offset of 1e308, a glTF
node scale of 1e308) are a plain one-line error, never a LinAlgError or LAPACK chatter."""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np
import pytest

from app.cli import main
from core import AlphaComplex
from core.errors import FileFormatError, InputError
from core.io import read_points

LAS_Z_SCALE, LAS_X_OFFSET = 147, 155  # byte offsets in every LAS 1.0-1.4 public header


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def _cloud() -> np.ndarray:
    return np.random.default_rng(1).random((40, 3))


def _csv(tmp_path: Path) -> Path:
    pts = _cloud()
    text = "x,y,z\n" + "".join(f"{a},{b},{c}\n" for a, b, c in pts)
    path = tmp_path / "huge.csv"
    path.write_text(text + "1.7e308,0.5,0.5\n")
    return path


def _las(tmp_path: Path, at: int) -> Path:
    import laspy

    las = laspy.LasData(laspy.LasHeader(point_format=3, version="1.2"))
    las.x, las.y, las.z = (_cloud() * 100).T
    path = tmp_path / f"patched{at}.las"
    las.write(path)
    raw = bytearray(path.read_bytes())
    raw[at:at + 8] = struct.pack("<d", 1e308)
    path.write_bytes(bytes(raw))
    return path


def _glb(tmp_path: Path) -> Path:
    import trimesh

    mesh = trimesh.creation.icosphere(subdivisions=2)
    scene = trimesh.Scene()
    scene.add_geometry(mesh, transform=np.diag([1e308, 1e308, 1e308, 1.0]))
    path = tmp_path / "scaled.glb"
    path.write_bytes(scene.export(file_type="glb"))
    return path


MAKERS = {"csv": _csv, "las z scale": lambda t: _las(t, LAS_Z_SCALE),
          "las x offset": lambda t: _las(t, LAS_X_OFFSET), "glb node scale": _glb}


@pytest.mark.parametrize("kind", sorted(MAKERS))
def test_extreme_coordinates_are_a_format_error(tmp_path, capfd, kind):
    path = MAKERS[kind](tmp_path)
    # a z scale of 1e308 overflows every z to inf: then no point is left at all
    with pytest.raises(FileFormatError, match=r"too large|no finite points") as info:
        read_points(path)
    assert path.name in str(info.value) and len(str(info.value).splitlines()) == 1
    out, err = capfd.readouterr()
    assert out == "" and err == ""  # no LAPACK 'DLASCL' lines, no RuntimeWarning


@pytest.mark.parametrize("kind", sorted(MAKERS))
def test_cli_info_on_extreme_coordinates_is_one_line(tmp_path, capfd, kind):
    path = MAKERS[kind](tmp_path)
    assert main(["info", str(path)]) == 1
    out, err = capfd.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1
    assert "too large" in err or "no finite points" in err


@pytest.mark.parametrize("value", [1.7e308, -1.7e308, 1e200])
@pytest.mark.parametrize("dim", [2, 3])
def test_from_points_refuses_extreme_coordinates(capfd, value, dim):
    pts = np.random.default_rng(2).random((30, dim))
    pts[[3, 7]] = value
    with pytest.raises(InputError, match="too large"):
        AlphaComplex.from_points(pts)
    assert capfd.readouterr() == ("", "")


def test_large_but_usable_coordinates_still_build():
    pts = np.random.default_rng(3).random((30, 3)) * 1e90
    assert AlphaComplex.from_points(pts).dim == 3
