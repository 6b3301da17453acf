"""The shared real scans load with the counts and boxes that shared/data/SOURCES.md gives."""

from __future__ import annotations

import numpy as np
import pytest
from reference import data_dir, needs_data

from core.io import read_points

DATA = data_dir()
pytestmark = needs_data

# file: (records read, unique points, dim, bbox lower corner, bbox upper corner)
EXPECTED = {
    "bunny.ply": (35947, 35947, 3, (-0.0946899, 0.0329874, -0.0618736),
                  (0.0610091, 0.187321, 0.0587997)),
    "bunny_dupverts.stl": (208986, 34834, 3, (-0.0946899, 0.0329874, -0.0618736),
                           (0.0610091, 0.187321, 0.0587997)),
    "bun000_rangegrid.ply": (40256, 40256, 3, (-0.09475, 0.0357363, -0.0586982),
                             (0.061, 0.18794, 0.0587228)),
    "milk.pcd": (13704, 13704, 3, (-0.140083, -0.26378, 0.714), (0.0138067, -0.0117286, 0.891)),
    "autzen_trim.las": (110000, 110000, 3, (636001.76, 848935.20, 406.26),
                        (637179.22, 849497.90, 520.51)),
    "plane_flat.laz": (28185, 18335, 3, (1423214.52, 4189096.63, 67.86),
                       (1423216.76, 4189098.60, 67.90)),
    # longitude/latitude: metres in an oblique stereographic centred on the data
    "us_airports.csv": (3376, 3376, 2, (-1.5908049e7, -2.2061676e6), (3.5585303e6, 2.151115e7)),
}


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_real_file_counts_and_bbox(name):
    n_read, n_unique, dim, lo, hi = EXPECTED[name]
    ps = read_points(DATA / name)
    rep = ps.report
    assert (rep.n_read, rep.n_points, rep.n_duplicates) == (n_read, n_unique, n_read - n_unique)
    assert ps.points.shape == (n_unique, dim)
    assert ps.points.dtype == np.float64 and not ps.points.flags.writeable
    np.testing.assert_allclose(rep.bbox[0], lo, rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(rep.bbox[1], hi, rtol=1e-5, atol=1e-5)
    assert rep.n_nonfinite == 0 and rep.spacing > 0


def test_stl_unique_vertices_are_the_ply_face_vertices():
    import trimesh

    ply = trimesh.load(str(DATA / "bunny.ply"), process=False)
    xyz = np.asarray(ply.vertices, dtype=np.float64)
    used = np.unique(ply.faces)
    stl = read_points(DATA / "bunny_dupverts.stl").points
    assert len(used) == len(stl) == 34834
    as_set = lambda a: set(map(tuple, a))  # noqa: E731
    assert as_set(xyz[used]) == as_set(stl)


def test_las_scale_offset_and_colours():
    ps = read_points(DATA / "autzen_trim.las")
    # coordinates sit on the 0.01 ft lattice after scale/offset
    np.testing.assert_allclose(ps.points * 100, np.round(ps.points * 100), atol=1e-5)
    colors = ps.attributes["colors"]
    assert colors.dtype == np.uint8 and colors.min() >= 40 and colors.max() <= 236
    assert np.bincount(ps.attributes["classification"]).tolist()[1:3] == [83893, 26107]


def test_plane_flat_keeps_first_of_duplicates_and_no_empty_colours():
    ps = read_points(DATA / "plane_flat.laz")
    assert "colors" not in ps.attributes  # RGB fields exist but are all 0
    assert len(np.unique(ps.points[:, 2])) == 5
    assert not ps.report.planar  # 4 cm of relief over 2 m is thin, not planar


def test_ply_extra_properties_become_attributes():
    ps = read_points(DATA / "bunny.ply")
    assert set(ps.attributes) == {"confidence", "intensity"}
    assert 0 <= ps.attributes["confidence"].min() and ps.attributes["confidence"].max() < 1


def test_milk_depth_quantised():
    ps = read_points(DATA / "milk.pcd")
    assert len(np.unique(ps.points[:, 2])) == 97


def test_rangegrid_x_on_624_planes():
    ps = read_points(DATA / "bun000_rangegrid.ply")
    assert len(np.unique(ps.points[:, 0])) == 624


@pytest.mark.parametrize("method", ["voxel", "random"])
def test_subsample_real_scan(method):
    ps = read_points(DATA / "autzen_trim.las", subsample=5000, subsample_method=method)
    assert 4000 <= len(ps.points) <= 5000
    assert ps.report.subsampled_from == 110000 and ps.report.subsample_method == method
    assert len(ps.attributes["colors"]) == len(ps.points)
