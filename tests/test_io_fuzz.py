"""Corrupted files (truncated, bytes flipped or inserted) give FileFormatError or points, never
another exception. Regressions from fuzzing: a laspy loop and lazrs aborts (see las_checks)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from core.errors import FileFormatError
from core.io import read_points

FORMATS = ("ply-ascii", "ply-binary", "csv", "xyz", "pcd", "pcd-compressed", "las", "laz",
           "stl", "obj", "off", "vtu", "npy", "npz")


def _write(kind: str, path_base) -> bytes:
    """Bytes of a small valid file of this kind."""
    pts = np.random.default_rng(0).normal(size=(30, 3)).astype(np.float32)
    ext = {"ply-ascii": "ply", "ply-binary": "ply", "pcd-compressed": "pcd"}.get(kind, kind)
    path = path_base.with_suffix("." + ext)
    if kind.startswith("ply"):
        import plyfile

        vert = np.rec.fromarrays(pts.T, names="x,y,z")
        plyfile.PlyData([plyfile.PlyElement.describe(vert, "vertex")],
                        text=kind == "ply-ascii").write(str(path))
    elif kind in ("csv", "xyz"):
        np.savetxt(path, pts, delimiter="," if kind == "csv" else " ",
                   header="x,y,z" if kind == "csv" else "", comments="")
    elif kind.startswith("pcd"):
        from pypcd4 import Encoding, PointCloud

        enc = Encoding("binary_compressed" if kind == "pcd-compressed" else "binary")
        PointCloud.from_xyz_points(pts).save(path, encoding=enc)
    elif kind in ("las", "laz"):
        import laspy

        las = laspy.LasData(laspy.LasHeader(point_format=3, version="1.2"))
        las.x, las.y, las.z = pts.T.astype(np.float64)
        las.write(path)
    elif kind in ("npy", "npz"):
        (np.save if kind == "npy" else lambda p, a: np.savez(p, points=a))(path, pts)
    else:
        import meshio

        meshio.write(str(path), meshio.Mesh(pts, [("triangle", np.array([[0, 1, 2]]))]))
    return path.read_bytes()


@pytest.fixture(scope="module")
def originals(tmp_path_factory) -> dict[str, bytes]:
    """Valid bytes per format."""
    base = tmp_path_factory.mktemp("orig") / "p"
    return {kind: _write(kind, base) for kind in FORMATS}


@settings(max_examples=120, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kind=st.sampled_from(FORMATS), how=st.sampled_from(["cut", "flip", "insert"]),
       where=st.floats(0, 1), junk=st.binary(min_size=1, max_size=12))
def test_corrupt_file_gives_format_error_or_points(tmp_path, originals, kind, how, where, junk):
    raw = bytearray(originals[kind])
    at = int(where * (len(raw) - 1))
    if how == "cut":
        raw = raw[:at]
    elif how == "flip":
        raw[at: at + len(junk)] = junk[: len(raw) - at]
    else:
        raw[at:at] = junk
    ext = {"ply-ascii": "ply", "ply-binary": "ply", "pcd-compressed": "pcd"}.get(kind, kind)
    path = tmp_path / f"corrupt.{ext}"
    path.write_bytes(bytes(raw))
    try:
        ps = read_points(path)
    except FileFormatError as exc:
        assert "corrupt." in str(exc)
    else:
        assert ps.points.ndim == 2 and np.isfinite(ps.points).all()
