"""Every readable format round-trips: write with an independent writer, read, compare."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from core.errors import FileFormatError
from core.io import READ_FORMATS, read_points
from core.io.report import first_unique
from core.io.subsample import subsample_indices


@pytest.fixture
def cloud() -> np.ndarray:
    """(50, 3) float64 random points exactly representable in float32."""
    rng = np.random.default_rng(7)
    return rng.normal(size=(50, 3)).astype(np.float32).astype(np.float64)


@pytest.fixture
def normals(cloud) -> np.ndarray:
    """(50, 3) float64 unit normals (float32-exact)."""
    n = cloud / np.linalg.norm(cloud, axis=1, keepdims=True)
    return n.astype(np.float32).astype(np.float64)


@pytest.mark.parametrize("text", [True, False])
def test_ply_round_trip_with_normals_colours_extra(tmp_path, cloud, normals, text):
    import plyfile

    colors = (np.arange(150) % 256).astype(np.uint8).reshape(50, 3)
    dtype = [(a, "f4") for a in ("x", "y", "z", "nx", "ny", "nz")]
    dtype += [(c, "u1") for c in ("red", "green", "blue")] + [("quality", "f8")]
    vert = np.empty(50, dtype)
    for i, a in enumerate("xyz"):
        vert[a], vert["n" + a] = cloud[:, i], normals[:, i]
    for i, c in enumerate(("red", "green", "blue")):
        vert[c] = colors[:, i]
    vert["quality"] = np.arange(50) / 7
    faces = np.array([([0, 1, 2],)], dtype=[("vertex_indices", "i4", (3,))])
    path = tmp_path / "p.ply"
    plyfile.PlyData([plyfile.PlyElement.describe(vert, "vertex"),
                     plyfile.PlyElement.describe(faces, "face")], text=text).write(str(path))
    ps = read_points(path)
    np.testing.assert_allclose(ps.points, cloud, rtol=1e-6 if text else 0)
    np.testing.assert_allclose(ps.attributes["normals"], normals, rtol=1e-6 if text else 0)
    np.testing.assert_array_equal(ps.attributes["colors"], colors)
    np.testing.assert_allclose(ps.attributes["quality"], np.arange(50) / 7, rtol=1e-6)


def test_ply_vertex_after_other_element(tmp_path, cloud):
    import plyfile

    other = np.zeros(4, dtype=[("a", "i4"), ("b", "f8")])
    vert = np.array([tuple(p) for p in cloud], dtype=[("x", "f8"), ("y", "f8"), ("z", "f8")])
    for text in (True, False):
        path = tmp_path / f"v{text}.ply"
        plyfile.PlyData([plyfile.PlyElement.describe(other, "camera"),
                         plyfile.PlyElement.describe(vert, "vertex")], text=text).write(str(path))
        np.testing.assert_allclose(read_points(path).points, cloud, rtol=1e-12)


TEXT_CASES = {
    "named.csv": ("x,y,z,nx,ny,nz\n", ",", None),
    "lonlat.csv": ("name,latitude,longitude,altitude\n", ",", "lonlat"),
    "plain.xyz": ("", " ", None),
    "tabs.txt": ("", "\t", None),
    "semi.csv": ("X;Y;Z\n", ";", None),
    "cloudcompare.txt": ("//X,Y,Z\n", ",", None),
    "leica.pts": ("50\n", " ", None),
    "units.csv": ("X [m],Y [m],Z (m)\n", ",", None),
}


@pytest.mark.parametrize("name", sorted(TEXT_CASES))
def test_text_round_trip(tmp_path, cloud, normals, name):
    header, sep, kind = TEXT_CASES[name]
    if kind == "lonlat":
        rows = [f'"P{i}, x",{p[1]},{p[0]},{p[2]}' for i, p in enumerate(cloud.tolist())]
    elif "nx" in header:
        rows = [sep.join(map(str, p + n)) for p, n in zip(cloud.tolist(), normals.tolist(),
                                                           strict=True)]
    else:
        rows = [sep.join(map(str, [*p, 7.0])) for p in cloud.tolist()]
    path = tmp_path / name
    path.write_text(header + "\n".join(rows) + "\n")
    ps = read_points(path)
    if kind == "lonlat":  # a 2D footprint in metres (pyproj, the CRS the reader chose)
        from pyproj import Transformer

        to_crs = Transformer.from_crs("EPSG:4326", ps.report.georef.crs, always_xy=True)
        want = np.column_stack(to_crs.transform(cloud[:, 0], cloud[:, 1]))
        np.testing.assert_allclose(ps.points, want, rtol=1e-12)
        np.testing.assert_array_equal(ps.attributes["altitude"], cloud[:, 2])
        return
    np.testing.assert_array_equal(ps.points, cloud)
    if "nx" in header:
        np.testing.assert_array_equal(ps.attributes["normals"], normals)


def test_text_two_numeric_columns_is_2d(tmp_path):
    path = tmp_path / "p.csv"
    path.write_text("id,a,b\nfoo,1,2\nbar,3,4.5\nbaz,5,6\n")
    np.testing.assert_array_equal(read_points(path).points, [[1, 2], [3, 4.5], [5, 6]])


@pytest.mark.parametrize("columns", ["c,a,b", [2, 0, 1], "2,0,1"])
def test_text_explicit_columns(tmp_path, columns):
    path = tmp_path / "p.csv"
    path.write_text("a,b,c\n1,2,3\n4,5,6\n7,8,10\n")
    np.testing.assert_array_equal(read_points(path, columns=columns).points,
                                  [[3, 1, 2], [6, 4, 5], [10, 7, 8]])


def test_text_missing_values_dropped_and_counted(tmp_path):
    path = tmp_path / "p.csv"
    path.write_text("x,y,note\n1,2,a\nNA,3,b\n4,,c\n5,6,d\n1,2,e\n")
    ps = read_points(path)
    np.testing.assert_array_equal(ps.points, [[1, 2], [5, 6]])
    assert (ps.report.n_read, ps.report.n_nonfinite, ps.report.n_duplicates) == (5, 2, 1)


def test_npy_and_npz_round_trip(tmp_path, cloud, normals):
    np.save(tmp_path / "p.npy", cloud)
    np.savez(tmp_path / "p.npz", points=cloud, normals=normals)
    rec = np.rec.fromarrays(cloud.T, names="x,y,z")
    np.save(tmp_path / "s.npy", rec)
    for name in ("p.npy", "p.npz", "s.npy"):
        np.testing.assert_array_equal(read_points(tmp_path / name).points, cloud)
    np.testing.assert_array_equal(read_points(tmp_path / "p.npz").attributes["normals"], normals)


@pytest.mark.parametrize("columns", ["2,0,1", [2, 0, 1], "-1,0,1", "c,a,b"])
def test_npy_explicit_columns(tmp_path, cloud, columns):
    np.save(tmp_path / "p.npy", cloud)
    np.save(tmp_path / "s.npy", np.rec.fromarrays(cloud.T, names="a,b,c"))
    want = cloud[:, [2, 0, 1]]
    if columns != "c,a,b":
        np.testing.assert_array_equal(read_points(tmp_path / "p.npy", columns=columns).points,
                                      want)
    if columns != "-1,0,1":
        np.testing.assert_array_equal(read_points(tmp_path / "s.npy", columns=columns).points,
                                      want)


@pytest.mark.parametrize(("columns", "message"), [
    ("0", r"p\.npy.*needs 2 or 3 columns, got 1"),
    ([0, 1, 2, 0], r"needs 2 or 3 columns, got 4"),
    ("0,5", r"p\.npy: column 5 out of range \(file has 3\)"),
    ("x,y", r"p\.npy: no column named 'x' \(no header\)"),
])
def test_npy_bad_columns_say_why(tmp_path, cloud, columns, message):
    np.save(tmp_path / "p.npy", cloud)
    with pytest.raises(FileFormatError, match=message) as info:
        read_points(tmp_path / "p.npy", columns=columns)
    assert "not a readable NumPy file" not in str(info.value)


@pytest.mark.parametrize("encoding", ["ascii", "binary", "binary_compressed"])
def test_pcd_round_trip(tmp_path, cloud, encoding):
    from pypcd4 import Encoding, PointCloud

    path = tmp_path / "p.pcd"
    PointCloud.from_xyz_points(cloud.astype(np.float32)).save(path, encoding=Encoding(encoding))
    np.testing.assert_allclose(read_points(path).points, cloud, rtol=1e-6)


@pytest.mark.parametrize("ext", [".las", ".laz"])
def test_las_round_trip_applies_scale_offset(tmp_path, ext):
    import laspy

    rng = np.random.default_rng(3)
    xyz = np.round(rng.uniform(0, 100, (200, 3)), 3) + np.array([6.0e5, 4.2e6, 50.0])
    header = laspy.LasHeader(point_format=3, version="1.2")
    header.scales, header.offsets = [0.001] * 3, [6.0e5, 4.2e6, 0.0]
    las = laspy.LasData(header)
    las.x, las.y, las.z = xyz.T
    las.write(tmp_path / f"p{ext}")
    np.testing.assert_allclose(read_points(tmp_path / f"p{ext}").points, xyz, atol=1e-6)


@pytest.mark.parametrize("fmt", ["stl", "stl-ascii", "obj", "off", "vtu", "vtk"])
def test_mesh_vertices_round_trip(tmp_path, fmt):
    import meshio

    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    tris = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    ext = fmt.split("-")[0]
    path = tmp_path / f"m.{ext}"
    kwargs = {"binary": False} if fmt == "stl-ascii" else {}
    meshio.write(str(path), meshio.Mesh(pts, [("triangle", tris)]), file_format=fmt.split("-")[0],
                 **kwargs)
    ps = read_points(path)
    assert {tuple(p) for p in ps.points} == {tuple(p) for p in pts}


def test_read_formats_cover_readers():
    assert {".ply", ".xyz", ".pts", ".txt", ".csv", ".pcd", ".las", ".laz", ".npy", ".npz",
            ".obj", ".stl", ".off", ".vtk", ".vtu"} <= set(READ_FORMATS)


@settings(max_examples=60, deadline=None)
@given(arrays(np.float64, st.tuples(st.integers(1, 40), st.just(3)),
              elements=st.sampled_from([0.0, 1.0, -2.5, 3.0])))
def test_first_unique_keeps_one_of_each(points):
    keep = first_unique(points)
    kept = points[keep]
    assert len({tuple(p) for p in kept}) == len(kept) == len({tuple(p) for p in points})
    first_seen = [i for i, p in enumerate(map(tuple, points))
                  if p not in {tuple(q) for q in points[:i]}]
    assert np.flatnonzero(keep).tolist() == first_seen


@pytest.mark.parametrize("size", [0.3, 0.05, 1e-12])  # 1e-12: too many voxels for one key
def test_voxel_firsts_is_first_point_of_each_voxel(size):
    from core.io.subsample import _voxel_firsts

    pts = np.random.default_rng(3).uniform(0, 1, (400, 3)).round(1)  # shared voxels at any size
    cells = np.floor((pts - pts.min(axis=0)) / size)
    seen: dict = {}
    for i, c in enumerate(map(tuple, cells.tolist())):
        seen.setdefault(c, i)
    assert _voxel_firsts(pts, size).tolist() == sorted(seen.values())


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10_000), st.integers(1, 300), st.sampled_from(["voxel", "random"]))
def test_subsample_at_most_target_and_distinct(seed, target, method):
    points = np.random.default_rng(seed).uniform(size=(400, 3))
    idx = subsample_indices(points, target, method=method, seed=seed)
    assert len(idx) <= target and len(np.unique(idx)) == len(idx)
    assert len(idx) >= (1 if method == "voxel" else target)


def test_report_planar_and_spacing(tmp_path):
    rng = np.random.default_rng(9)
    xy = rng.uniform(size=(300, 2))
    tilted = np.column_stack([xy, 2.0 * xy[:, 0] - xy[:, 1] + 5.0])
    np.save(tmp_path / "plane.npy", tilted)
    np.save(tmp_path / "solid.npy", rng.uniform(size=(300, 3)))
    np.save(tmp_path / "grid.npy", np.mgrid[0:10, 0:10].reshape(2, -1).T * 0.5)
    assert read_points(tmp_path / "plane.npy").report.planar
    assert not read_points(tmp_path / "solid.npy").report.planar
    grid = read_points(tmp_path / "grid.npy").report
    assert grid.dim == 2 and grid.spacing == 0.5 and grid.bbox == ((0.0, 0.0), (4.5, 4.5))


def test_text_crlf_trailing_delimiter_and_weights(tmp_path):
    path = tmp_path / "p.csv"
    path.write_bytes(b"X,Y,Z,Weight,\r\n1,2,3,0.5,\r\n4,5,6,0.25,\r\n7,8,9.5,1,\r\n")
    ps = read_points(path)
    np.testing.assert_array_equal(ps.points, [[1, 2, 3], [4, 5, 6], [7, 8, 9.5]])
    np.testing.assert_array_equal(ps.attributes["weights"], [0.5, 0.25, 1])


@pytest.mark.parametrize("ext", [".glb", ".gltf"])
def test_gltf_vertices_read(tmp_path, ext):
    import trimesh

    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    mesh = trimesh.Trimesh(pts, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], process=False)
    if ext == ".glb":
        (tmp_path / "m.glb").write_bytes(mesh.export(file_type="glb"))
    else:
        files = trimesh.exchange.gltf.export_gltf(mesh.scene(), embed_buffers=True)
        (tmp_path / "m.gltf").write_bytes(files["model.gltf"])
    ps = read_points(tmp_path / f"m{ext}")
    assert {tuple(p) for p in ps.points} == {tuple(p) for p in pts}


@pytest.mark.parametrize("data", ["ascii", "binary"])
def test_pcd_without_the_optional_count_line(tmp_path, cloud, data):
    head = ("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
            f"WIDTH {len(cloud)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(cloud)}\n"
            f"DATA {data}\n").encode()
    body = (cloud.astype("<f4").tobytes() if data == "binary"
            else "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in cloud.tolist()).encode())
    (tmp_path / "p.pcd").write_bytes(head + body)
    np.testing.assert_array_equal(read_points(tmp_path / "p.pcd").points, cloud)
