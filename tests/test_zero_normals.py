"""Anisotropic alpha with a file's normals: points whose normal is 0,0,0 (what many PLY
exporters write) get estimated normals, counted in the build info and said on the command
line; never the classic table under an anisotropic label. NaN normals are refused."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from app.cli import main
from core import AlphaComplex
from core.errors import InputError
from core.io import read_points

SCAN = Path(__file__).parent / "data" / "corpus" / "pcd" / "pcl_bun01.pcd"


def write_ply(path: Path, points: np.ndarray, normals: np.ndarray) -> Path:
    """A binary PLY of float x y z nx ny nz, as scanners' exporters write it."""
    rows = np.empty(len(points), dtype=[(n, "<f4") for n in ("x", "y", "z", "nx", "ny", "nz")])
    for i, name in enumerate("xyz"):
        rows[name] = points[:, i]
        rows[f"n{name}"] = normals[:, i]
    header = (f"ply\nformat binary_little_endian 1.0\ncomment exported\n"
              f"element vertex {len(points)}\n"
              + "".join(f"property float {n}\n" for n in rows.dtype.names) + "end_header\n")
    path.write_bytes(header.encode() + rows.tobytes())
    return path


@pytest.fixture(scope="module")
def scan() -> np.ndarray:
    """The corpus bunny scan's points, as float32 (a PLY stores them so)."""
    return read_points(SCAN).points.astype(np.float32).astype(np.float64)


def _info(capsys, path: Path, *options: str) -> tuple[dict, str]:
    assert main(["info", str(path), "--json", "--no-cache", "--anisotropic", "0.5",
                 *options]) == 0
    out, err = capsys.readouterr()
    return json.loads(out), err


def test_a_ply_of_zero_normals_is_anisotropic_not_classic(tmp_path, capsys, scan):
    path = write_ply(tmp_path / "zero_normals.ply", scan, np.zeros_like(scan))
    given, err = _info(capsys, path, "--normals", "file")
    estimated, _ = _info(capsys, path, "--normals", "estimate")
    assert main(["info", str(path), "--json", "--no-cache"]) == 0
    classic = json.loads(capsys.readouterr()[0])
    assert given["mode"]["normals"] == "given"
    assert given["build"]["estimated_normals"] == len(scan)
    assert f"{len(scan):,} of {len(scan):,} points had a zero normal" in err
    for key in ("spectrum", "volume", "optimal_alpha", "classes"):
        assert given[key] == estimated[key], key
    assert given["spectrum"] != classic["spectrum"]


def test_only_the_zero_normals_are_estimated(scan):
    """A file where some normals are zero: those are estimated, the given ones kept."""
    sphere_like = scan - scan.mean(axis=0)
    given = sphere_like / np.linalg.norm(sphere_like, axis=1)[:, None]
    some = given.copy()
    some[::3] = 0.0
    ac = AlphaComplex.from_points(scan, anisotropy=0.5, normals=some)
    assert ac.build_info.estimated_normals == len(scan[::3])
    assert "estimated normals" in ac.build_info.describe()
    full = AlphaComplex.from_points(scan, anisotropy=0.5, normals=given)
    classic = AlphaComplex.from_points(scan)
    assert full.build_info.estimated_normals == 0
    assert "estimated normals" not in full.build_info.describe()
    for other in (full, classic):
        assert not np.array_equal(ac.spectrum(), other.spectrum())


def test_normals_of_any_finite_size_keep_their_direction(scan):
    """Normals scaled by 1e200 or 1e-200 are the same directions (no overflow to zero)."""
    rng = np.random.default_rng(5)
    normals = rng.normal(size=scan.shape)
    want = AlphaComplex.from_points(scan, anisotropy=0.5, normals=normals).spectrum()
    for factor in (1e200, 1e-200):
        ac = AlphaComplex.from_points(scan, anisotropy=0.5, normals=normals * factor)
        assert ac.build_info.estimated_normals == 0
        np.testing.assert_allclose(ac.spectrum(), want, rtol=1e-12)


def test_nan_normals_are_refused_with_the_row(scan):
    normals = np.ones_like(scan)
    normals[7] = np.nan
    with pytest.raises(InputError, match=r"1 of .* normals have NaN.*row 7"):
        AlphaComplex.from_points(scan, anisotropy=0.5, normals=normals)
