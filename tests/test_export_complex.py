"""VTU of the complex, the interval table (NPZ/CSV), and atomic writes."""

from __future__ import annotations

import os
import re

import numpy as np
import pytest

from core import AlphaComplex
from core.errors import Cancelled, FileFormatError
from core.export import surface, write_shape, write_table

ALPHA = 0.3


@pytest.fixture(scope="module")
def cloud() -> AlphaComplex:
    """Complex of 300 random 3D points (clusters so that singular simplices exist)."""
    rng = np.random.default_rng(11)
    centres = rng.uniform(-3, 3, (6, 3))
    return AlphaComplex.from_points(np.vstack([c + 0.4 * rng.normal(size=(50, 3))
                                               for c in centres]))


def test_vtu_read_by_meshio_matches_classes(tmp_path, cloud):
    import meshio

    write_shape(cloud, ALPHA, tmp_path / "c.vtu", source="in.ply")
    text = (tmp_path / "c.vtu").read_text()
    # meshio cannot parse VTK String arrays: drop the field data (checked with VTK below)
    (tmp_path / "c.vtu").write_text(re.sub(r"<FieldData>.*?</FieldData>", "", text, flags=re.S))
    mesh = meshio.read(tmp_path / "c.vtu")
    shape = cloud.shape(ALPHA)
    cells = mesh.cells_dict
    assert len(cells["tetra"]) == len(shape.cells)
    n_tri = len(shape.regular_facets) + len(shape.singular(2))
    assert len(cells.get("triangle", [])) == n_tri
    assert len(cells.get("line", [])) == len(shape.singular(1))
    assert len(cells.get("vertex", [])) == len(shape.singular(0))
    cls = np.concatenate(mesh.cell_data["class"])
    enter = np.concatenate(mesh.cell_data["enter"])
    assert np.all(enter <= ALPHA)  # everything written is in the complex
    assert np.count_nonzero(cls == 3) == len(shape.cells)
    assert np.count_nonzero(cls == 1) == sum(len(shape.singular(k)) for k in range(3))
    assert np.all(np.concatenate(mesh.cell_data["interior"]) >= enter)


def test_vtu_field_data_in_vtk(tmp_path, cloud):
    import pyvista as pv

    write_shape(cloud, ALPHA, tmp_path / "c.vtu", source="in.ply")
    grid = pv.read(tmp_path / "c.vtu")
    assert float(grid.field_data["alpha"][0]) == ALPHA
    assert float(grid.field_data["volume"][0]) == pytest.approx(cloud.shape(ALPHA).measure)
    assert str(grid.field_data["source"][0]) == "in.ply"
    assert set(np.unique(grid.cell_data["class"])) <= {1, 2, 3}


def test_table_npz_layout(tmp_path, cloud):
    report = write_table(cloud, tmp_path / "t.npz")
    assert report.n_faces == sum(len(cloud.simplices(k)) for k in range(4))
    assert "interval table" in report.line()
    with np.load(tmp_path / "t.npz", allow_pickle=False) as z:
        assert str(z["format"]) == "alphascoop-intervals" and int(z["dim"]) == 3
        np.testing.assert_array_equal(z["points"], cloud.points)
        for k in range(4):
            np.testing.assert_array_equal(z[f"simplices_{k}"], cloud.simplices(k))
            np.testing.assert_array_equal(z[f"intervals_{k}"], cloud.intervals(k))
        np.testing.assert_array_equal(z["spectrum"], cloud.spectrum())


def test_table_csv(tmp_path, cloud):
    write_table(cloud, tmp_path / "t.csv")
    table = np.loadtxt(tmp_path / "t.csv", delimiter=",", skiprows=1)
    for k in range(4):
        rows = table[table[:, 0] == k]
        np.testing.assert_array_equal(rows[:, 1: k + 2], cloud.simplices(k))
        assert np.all(rows[:, k + 2: 5] == -1)
        np.testing.assert_array_equal(rows[:, 5:], cloud.intervals(k))


def test_unknown_export_extension(tmp_path, cloud):
    with pytest.raises(FileFormatError, match="cannot export"):
        write_shape(cloud, ALPHA, tmp_path / "s.xyz")
    with pytest.raises(FileFormatError, match="does not exist"):
        write_shape(cloud, ALPHA, tmp_path / "missing" / "s.ply")


@pytest.mark.parametrize("error", [RuntimeError("disk on fire"), Cancelled("user")])
def test_failed_write_keeps_old_file(tmp_path, cloud, monkeypatch, error):
    target = tmp_path / "s.ply"
    target.write_bytes(b"the good old file")

    def half_then_fail(path, vertices, faces, meta):
        path.write_bytes(b"ply\nformat binary_little_endian 1.0\n")
        raise error

    monkeypatch.setitem(surface.SURFACE_WRITERS, ".ply", half_then_fail)
    with pytest.raises(type(error)):
        write_shape(cloud, ALPHA, target)
    assert target.read_bytes() == b"the good old file"
    assert os.listdir(tmp_path) == ["s.ply"]  # no temporary file left behind


def test_successful_write_replaces_old_file(tmp_path, cloud):
    target = tmp_path / "s.stl"
    target.write_bytes(b"old")
    report = write_shape(cloud, ALPHA, target)
    assert target.stat().st_size == 84 + 50 * report.n_faces
    assert os.listdir(tmp_path) == ["s.stl"]
