"""Every format we write and also read reads back with all the points it holds.

Not readable as points (no reader, or no coordinates): .vtp, .geojson, .wkt, .svg, and the
interval table's .csv (simplex rows, no coordinates).
"""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex
from core.export import SHAPE_FORMATS, write_shape, write_table
from core.io import READ_FORMATS, read_points

ALPHA = 1.0


@pytest.fixture(scope="module")
def ball() -> AlphaComplex:
    rng = np.random.default_rng(5)
    p = rng.normal(size=(300, 3))
    return AlphaComplex.from_points(p / np.linalg.norm(p, axis=1, keepdims=True) + 3.0)


@pytest.fixture(scope="module")
def disc() -> AlphaComplex:
    rng = np.random.default_rng(6)
    return AlphaComplex.from_points(rng.uniform(-1, 1, size=(200, 2)))


SURFACES = [".ply", ".stl", ".obj", ".off", ".glb", ".gltf"]


def test_every_written_format_with_a_reader_is_covered():
    readable = set(SHAPE_FORMATS) & set(READ_FORMATS)
    assert readable == {*SURFACES, ".vtu", ".csv"}


@pytest.mark.parametrize("ext", SURFACES)
def test_surface_exports_read_back(tmp_path, ball, ext):
    report = write_shape(ball, ALPHA, tmp_path / f"s{ext}")
    ps = read_points(tmp_path / f"s{ext}")
    copies = report.metadata.get("manifold_split", {}).get("vertices_added", 0)
    assert copies > 0, "surfaces are split to a manifold by default, with vertex copies"
    assert ps.report.n_points == report.n_vertices - copies > 0  # copies merge back
    ours = {tuple(p) for p in np.asarray(ball.points, dtype=np.float32).astype(np.float64)}
    assert {tuple(p) for p in ps.points.astype(np.float32).astype(np.float64)} <= ours


@pytest.mark.parametrize("ext", SURFACES)
def test_2d_surface_exports_read_back(tmp_path, disc, ext):
    report = write_shape(disc, ALPHA, tmp_path / f"s{ext}")  # the filled triangles, z = 0
    ps = read_points(tmp_path / f"s{ext}")
    assert ps.report.n_points == report.n_vertices > 0
    ours = {tuple(p) for p in np.asarray(disc.points, dtype=np.float32).astype(np.float64)}
    got = ps.points.astype(np.float32).astype(np.float64)
    assert np.all(got[:, 2:] == 0) and {tuple(p[:2]) for p in got} <= ours


@pytest.mark.parametrize("fixture", ["ball", "disc"])
def test_vtu_export_reads_back_every_point(tmp_path, request, fixture):
    ac = request.getfixturevalue(fixture)
    write_shape(ac, ALPHA, tmp_path / "c.vtu")
    ps = read_points(tmp_path / "c.vtu")
    pts = np.asarray(ac.to_ambient(ac.points))
    assert ps.report.n_read == len(pts)
    np.testing.assert_array_equal(ps.points[:, : pts.shape[1]], pts)


def test_ring_csv_reads_back_every_ring_vertex(tmp_path, disc):
    import shapely

    from core.export.polygons import shape_polygons

    write_shape(disc, ALPHA, tmp_path / "r.csv")
    ps = read_points(tmp_path / "r.csv")
    rings = shapely.get_coordinates(shapely.get_rings(shapely.get_parts(
        shape_polygons(disc, disc.shape(ALPHA)))))
    assert ps.report.n_read == len(rings)
    np.testing.assert_array_equal(ps.points, np.unique(rings, axis=0)[
        np.argsort(np.unique(rings, axis=0, return_index=True)[1])])


def test_table_npz_reads_back_its_points(tmp_path, ball):
    write_table(ball, tmp_path / "t.npz")
    np.testing.assert_array_equal(read_points(tmp_path / "t.npz").points, ball.points)
