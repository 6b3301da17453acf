"""Structurally valid files with suspicious content load, and the report says what is wrong:
LAS points far outside the header's box, a geographic CRS on metre coordinates, NaN values."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from core.io import read_points

LAS_X_OFFSET = 155


def _las(path, xyz: np.ndarray, crs=None):
    import laspy

    header = laspy.LasHeader(point_format=3, version="1.4")
    if crs is not None:
        header.add_crs(crs)
    las = laspy.LasData(header)
    las.x, las.y, las.z = xyz.T
    las.write(path)
    return path


def _cloud(offset: float = 0.0) -> np.ndarray:
    return np.random.default_rng(0).random((50, 3)) * 100 + offset


def test_geographic_crs_on_metre_coordinates_is_a_warning(tmp_path):
    from pyproj import CRS

    ps = read_points(_las(tmp_path / "wrong.las", _cloud(636000.0), CRS.from_epsg(4326)))
    assert len(ps.points) == 50
    assert any("declares the geographic CRS 'WGS 84'" in n for n in ps.report.notes)


@pytest.mark.parametrize("epsg", [None, 32633, 4326])
def test_consistent_crs_gives_no_warning(tmp_path, epsg):
    from pyproj import CRS

    xyz = _cloud() if epsg != 32633 else _cloud(500000.0)
    if epsg == 4326:
        xyz = xyz * [0.01, 0.01, 1.0] + [12.0, 41.0, 0.0]
    ps = read_points(_las(tmp_path / "ok.las", xyz, None if epsg is None
                          else CRS.from_epsg(epsg)))
    assert not any(n.startswith("warning") for n in ps.report.notes)


def test_points_outside_the_header_box_are_reported(tmp_path):
    path = _las(tmp_path / "moved.las", _cloud(1000.0))
    raw = bytearray(path.read_bytes())
    (offset,) = struct.unpack_from("<d", raw, LAS_X_OFFSET)
    raw[LAS_X_OFFSET:LAS_X_OFFSET + 8] = struct.pack("<d", offset + 5e6)  # a corrupt x offset
    path.write_bytes(bytes(raw))
    ps = read_points(path)
    assert len(ps.points) == 50 and ps.report.bbox[0][0] > 5e6
    note = next(n for n in ps.report.notes if "outside the header's bounding box" in n)
    assert note.startswith("warning: 50 points")


def test_in_bounds_las_has_no_warning(tmp_path):
    ps = read_points(_las(tmp_path / "fine.las", _cloud(1000.0)))
    assert not any(n.startswith("warning") for n in ps.report.notes)


def test_non_finite_attribute_values_are_reported(tmp_path):
    path = tmp_path / "nan.csv"
    rows = [f"{i},{i * i % 7},{i % 3},{'nan' if i % 10 == 0 else i}" for i in range(30)]
    path.write_text("x,y,z,intensity\n" + "\n".join(rows) + "\n")
    ps = read_points(path)
    assert len(ps.points) == 30 and ps.report.n_nonfinite == 0
    assert "warning: attribute 'intensity' has 3 non-finite values" in ps.report.notes
