"""VTU of the complex, the interval table (NPZ/CSV), and atomic writes."""

from __future__ import annotations

import os

import numpy as np
import pytest

from core import AlphaComplex
from core.errors import Cancelled, FileFormatError
from core.export import csvrows, surface, table, write_shape, write_table
from core.export.vtkxml import text_of

ALPHA = 0.3


def clusters(dim: int, n_centres: int, spread: float, seed: int) -> AlphaComplex:
    """Complex of 50 random points around each of n_centres random centres, so that
    singular simplices exist."""
    rng = np.random.default_rng(seed)
    centres = rng.uniform(-3, 3, (n_centres, dim))
    return AlphaComplex.from_points(np.vstack([c + spread * rng.normal(size=(50, dim))
                                               for c in centres]))


@pytest.fixture(scope="module")
def cloud() -> AlphaComplex:
    """Complex of 300 random 3D points in 6 clusters."""
    return clusters(3, 6, 0.4, seed=11)


@pytest.fixture(scope="module")
def flat() -> AlphaComplex:
    """Complex of 400 random 2D points in 8 clusters (singular edges and vertices exist)."""
    return clusters(2, 8, 0.3, seed=12)


MESHIO_TYPES = {0: "vertex", 1: "line", 2: "triangle", 3: "tetra"}


def _keys(rows: np.ndarray) -> list[tuple[int, ...]]:
    """Each row's sorted vertex ids (orientation ignored)."""
    return list(map(tuple, np.sort(np.asarray(rows, dtype=np.int64), axis=1).tolist()))


def _simplex_set(rows: np.ndarray) -> set[tuple[int, ...]]:
    """Vertex sets of the rows."""
    return set(_keys(rows))


@pytest.mark.parametrize("which", ["cloud", "flat"])
def test_vtu_read_by_meshio_matches_classify(tmp_path, request, which):
    """Every (dimension, class) block holds exactly the simplices ac.classify puts there."""
    import meshio

    ac = request.getfixturevalue(which)
    write_shape(ac, ALPHA, tmp_path / "c.vtu", source="in.ply")
    mesh = meshio.read(tmp_path / "c.vtu")  # field data and all (no String arrays)
    assert text_of(mesh.field_data["source"]) == "in.ply"
    np.testing.assert_array_equal(mesh.points[:, : ac.dim], ac.points)
    written = {(3, ac.dim), (2, ac.dim - 1)} | {(1, k) for k in range(ac.dim)}
    for k in range(ac.dim + 1):
        cells = mesh.cells_dict.get(MESHIO_TYPES[k], np.empty((0, k + 1)))
        cls = mesh.cell_data_dict["class"].get(MESHIO_TYPES[k], np.empty(0)).ravel()
        want_cls = ac.classify(ALPHA, k)
        for c in (1, 2, 3):
            want = ac.simplices(k)[want_cls == c] if (c, k) in written else np.empty((0, k + 1))
            assert _simplex_set(cells[cls == c]) == _simplex_set(want), (k, c)
            assert np.count_nonzero(cls == c) == len(want), (k, c)  # no duplicates
        assert len(cls) == len(cells) and np.isin(cls, (1, 2, 3)).all()
        intervals = dict(zip(_keys(ac.simplices(k)), ac.intervals(k).tolist(), strict=True))
        got = np.column_stack([mesh.cell_data_dict[name].get(MESHIO_TYPES[k], np.empty(0))
                               .ravel() for name in ("enter", "regular", "interior")])
        want_iv = np.array([intervals[key] for key in _keys(cells)]).reshape(-1, 3)
        np.testing.assert_array_equal(got.reshape(-1, 3), want_iv)
        assert np.all(got[:, 0] <= ALPHA)  # everything written is in the complex


def test_vtu_field_data_in_vtk(tmp_path, cloud):
    import pyvista as pv

    write_shape(cloud, ALPHA, tmp_path / "c.vtu", source="in.ply")
    grid = pv.read(tmp_path / "c.vtu")
    assert float(grid.field_data["alpha"][0]) == ALPHA
    assert float(grid.field_data["volume"][0]) == pytest.approx(cloud.shape(ALPHA).measure)
    assert text_of(grid.field_data["source"]) == "in.ply"
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


@pytest.mark.parametrize("chunk", [None, 7])
def test_table_csv_round_trip(tmp_path, cloud, monkeypatch, chunk):
    if chunk is not None:  # many chunk boundaries inside every dimension
        monkeypatch.setattr(csvrows, "CHUNK_ROWS", chunk)
    write_table(cloud, tmp_path / "t.csv")
    lines = (tmp_path / "t.csv").read_text().splitlines()
    assert lines[0] == "k,v0,v1,v2,v3,enter,regular,interior"
    assert len(lines) == 1 + sum(cloud.counts())
    rows = np.loadtxt(tmp_path / "t.csv", delimiter=",", skiprows=1)
    assert np.isinf(rows[:, 5:]).any()  # inf = never, read back as inf
    for k in range(4):
        block = rows[rows[:, 0] == k]
        np.testing.assert_array_equal(block[:, 1: k + 2], cloud.simplices(k))
        assert np.all(block[:, k + 2: 5] == -1)
        np.testing.assert_array_equal(block[:, 5:], cloud.intervals(k))  # exact floats


def test_format_rows_matches_python_formatting():
    ints = np.array([0, -1, 12345678901], dtype=np.int64)
    floats = np.array([0.1, -np.inf, 1e-300])
    names = np.array(["shell", "hole", "hole"])
    want = "".join(f"{i},{s},{x!r},{x:.17g}\n" for i, s, x in zip(ints, names, floats.tolist(),
                                                                   strict=True))
    assert csvrows.format_rows("%d,%s,%r,%.17g\n", [ints, names, floats, floats]) == want
    assert csvrows.format_rows("%d\n", [np.empty(0)]) == ""


def test_unknown_export_extension(tmp_path, cloud):
    with pytest.raises(FileFormatError, match="cannot export"):
        write_shape(cloud, ALPHA, tmp_path / "s.xyz")
    with pytest.raises(FileFormatError, match="does not exist"):
        write_shape(cloud, ALPHA, tmp_path / "missing" / "s.ply")


@pytest.mark.parametrize(("error", "raised"), [
    (RuntimeError("disk on fire"), FileFormatError),
    (ValueError("trimesh: faces must be (n, 3)"), FileFormatError),
    (Cancelled("user"), Cancelled),
])
def test_failed_write_keeps_old_file(tmp_path, cloud, monkeypatch, error, raised):
    target = tmp_path / "s.ply"
    target.write_bytes(b"the good old file")

    def half_then_fail(path, vertices, faces, meta):
        path.write_bytes(b"ply\nformat binary_little_endian 1.0\n")
        raise error

    monkeypatch.setitem(surface.SURFACE_WRITERS, ".ply", half_then_fail)
    with pytest.raises(raised) as info:
        write_shape(cloud, ALPHA, target)
    if raised is FileFormatError:  # names the file and the writer's problem
        assert str(info.value) == f"{target}: cannot write ({error})"
    assert target.read_bytes() == b"the good old file"
    assert os.listdir(tmp_path) == ["s.ply"]  # no temporary file left behind


@pytest.mark.parametrize("ext", [".csv", ".npz"])
def test_failed_table_write_is_a_format_error(tmp_path, cloud, monkeypatch, ext):
    target = tmp_path / f"t{ext}"
    target.write_bytes(b"old table")

    def fail(path, ac):
        path.write_bytes(b"half")
        raise TypeError("unsupported dtype")

    monkeypatch.setitem(table.TABLE_WRITERS, ext, fail)
    with pytest.raises(FileFormatError, match=rf"t\{ext}: cannot write \(unsupported dtype\)"):
        write_table(cloud, target)
    assert target.read_bytes() == b"old table"
    assert os.listdir(tmp_path) == [target.name]


def test_successful_write_replaces_old_file(tmp_path, cloud):
    target = tmp_path / "s.stl"
    target.write_bytes(b"old")
    report = write_shape(cloud, ALPHA, target)
    assert target.stat().st_size == 84 + 50 * report.n_faces
    listing = ["s.stl.split-points.csv"] if report.split_file else []  # points split apart
    assert sorted(os.listdir(tmp_path)) == ["s.stl", *listing]
