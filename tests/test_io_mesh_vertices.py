"""Mesh files give every vertex record as a point; the report counts those no face uses."""

from __future__ import annotations

import os

import numpy as np
import pytest
from reference import data_dir, needs_data

from core.io import read_points

DATA_DIR = data_dir()

RNG = np.random.default_rng(17)


def _note(ps) -> str:
    return next(n for n in ps.report.notes if n.startswith("mesh vertices"))


def test_obj_keeps_vertices_no_face_uses(tmp_path):
    pts = RNG.normal(size=(500, 3)).round(6)
    lines = [f"v {x} {y} {z}" for x, y, z in pts] + ["f 1 2 3", "f 4/1/1 5//2 -3"]
    (tmp_path / "a.obj").write_text("\n".join(lines) + "\n")
    ps = read_points(tmp_path / "a.obj")
    np.testing.assert_array_equal(ps.points, pts)
    assert "494 used by no face" in _note(ps)


def test_point_only_obj_with_colours_and_comments(tmp_path):
    text = "# scanner\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0 # trailing\n\tv 0 1 0 0 0 1\nvn 0 0 1\n"
    (tmp_path / "p.obj").write_text(text)
    ps = read_points(tmp_path / "p.obj")
    np.testing.assert_array_equal(ps.points, [[0, 0, 0], [1, 0, 0], [0, 1, 0]])
    np.testing.assert_array_equal(ps.attributes["colors"], 255 * np.eye(3))
    assert _note(ps) == "mesh vertices: 3 points, no faces"


@pytest.mark.parametrize(("body", "message"), [
    ("v 0 0 0\nf 1 2 3\n", "does not exist"),
    ("v 0 0\n", "fewer than 3"),
    ("v 0 zero 0\n", "not a number"),
    ("vn 0 0 1\n", "no vertex"),
])
def test_bad_obj_says_why(tmp_path, body, message):
    from core.errors import FileFormatError

    (tmp_path / "b.obj").write_text(body)
    with pytest.raises(FileFormatError, match=message):
        read_points(tmp_path / "b.obj")


@needs_data
def test_bunny_as_obj_has_all_35947_vertices(tmp_path):
    import plyfile

    ply = plyfile.PlyData.read(str(DATA_DIR / "bunny.ply"))
    xyz = np.column_stack([ply["vertex"][a] for a in "xyz"]).astype(np.float64)
    faces = np.vstack(ply["face"]["vertex_indices"]) + 1
    with open(tmp_path / "bunny.obj", "w") as fh:
        np.savetxt(fh, xyz, fmt="v %.9g %.9g %.9g")
        np.savetxt(fh, faces, fmt="f %d %d %d")
    ps = read_points(tmp_path / "bunny.obj")
    assert ps.report.n_points == 35_947
    np.testing.assert_array_equal(ps.points.astype(np.float32), xyz.astype(np.float32))
    assert "1,113 used by no face" in _note(ps)


def _scene_files(tmp_path):
    import trimesh

    mesh = trimesh.creation.icosphere(1)  # 42 vertices
    cloud = trimesh.PointCloud(RNG.normal(size=(33, 3)))
    trimesh.Scene([mesh, cloud]).export(tmp_path / "mixed.glb")
    trimesh.Scene([cloud]).export(tmp_path / "cloud.glb")
    gltf = trimesh.exchange.gltf.export_gltf(trimesh.Scene([cloud]), embed_buffers=True)
    (tmp_path / "cloud.gltf").write_bytes(gltf["model.gltf"])
    return mesh.vertices, cloud.vertices


@pytest.mark.parametrize(("name", "n", "unused"), [
    ("mixed.glb", 75, "33 used by no face"), ("cloud.glb", 33, "33 points, no faces"),
    ("cloud.gltf", 33, "33 points, no faces")])
def test_gltf_point_clouds_and_mixed_scenes(tmp_path, name, n, unused):
    mesh_v, cloud_v = _scene_files(tmp_path)
    ps = read_points(tmp_path / name)
    assert ps.report.n_read == n and unused in _note(ps)
    expect = np.vstack([mesh_v, cloud_v]) if n == 75 else cloud_v
    assert {tuple(p) for p in ps.points} == {tuple(p) for p in expect.astype(np.float32)
                                             .astype(np.float64)}


def _legacy_vtk(path, binary: bool, pts: np.ndarray) -> None:
    """A POLYDATA file written by hand (version 3.0 layout, with a FIELD block first)."""
    head = (f"# vtk DataFile Version 3.0\nhand made\n{'BINARY' if binary else 'ASCII'}\n"
            "DATASET POLYDATA\nFIELD FieldData 1\nTIME 1 1 double\n").encode()
    field = np.array([2.5], ">f8").tobytes() if binary else b"2.5"
    body = pts.astype(">f4").tobytes() if binary else " ".join(map(str, pts.ravel())).encode()
    tail = b"\nVERTICES 1 4\n3 0 1 2\n" if not binary else b"\n"
    path.write_bytes(head + field + f"\nPOINTS {len(pts)} float\n".encode() + body + tail)


@pytest.mark.parametrize("binary", [False, True])
def test_legacy_vtk_polydata(tmp_path, binary):
    pts = RNG.normal(size=(7, 3)).astype(np.float32).astype(np.float64)
    _legacy_vtk(tmp_path / "p.vtk", binary, pts)
    np.testing.assert_array_equal(read_points(tmp_path / "p.vtk").points, pts)


@pytest.mark.parametrize("binary", [False, True])
def test_legacy_vtk_polydata_written_by_vtk(tmp_path, binary):
    import pyvista as pv

    sphere = pv.Sphere()
    sphere.save(tmp_path / "s.vtk", binary=binary)
    ps = read_points(tmp_path / "s.vtk")
    np.testing.assert_allclose(ps.points, sphere.points, rtol=0 if binary else 1e-5, atol=1e-7)


@pytest.mark.parametrize("ext", [".obj", ".stl", ".glb", ".off", ".vtu", ".vtk", ".ply"])
def test_non_utf8_file_name(tmp_path, ext):
    import trimesh

    mesh = trimesh.creation.icosphere(0)
    target = os.path.join(os.fsencode(tmp_path), b"scan\xe9\xff" + ext.encode())
    data = (mesh.export(file_type=ext.lstrip(".")) if ext not in (".vtu", ".vtk")
            else _meshio_bytes(tmp_path, mesh, ext))
    with open(target, "wb") as fh:
        fh.write(data if isinstance(data, bytes) else data.encode())
    ps = read_points(os.fsdecode(target))
    assert ps.report.n_points == len(mesh.vertices)


def _meshio_bytes(tmp_path, mesh, ext: str) -> bytes:
    import meshio

    out = tmp_path / f"m{ext}"
    meshio.write(out, meshio.Mesh(mesh.vertices, [("triangle", mesh.faces)]))
    return out.read_bytes()


@needs_data
def test_bunny_ply_report_counts_the_1113_unused_vertices():
    ps = read_points(DATA_DIR / "bunny.ply")  # 1,113: shared/data/SOURCES.md (plyfile)
    assert ps.report.n_points == 35_947 and "1,113 used by no face" in _note(ps)


@pytest.mark.parametrize("binary", [False, True])
def test_unstructured_grid_with_cells_meshio_refuses(tmp_path, binary):
    pts = RNG.normal(size=(6, 3)).astype(np.float32)
    head = (f"# vtk DataFile Version 4.2\nhand made\n{'BINARY' if binary else 'ASCII'}\n"
            "DATASET UNSTRUCTURED_GRID\nPOINTS 6 float\n").encode()
    body = pts.astype(">f4").tobytes() if binary else " ".join(map(repr, pts.ravel().tolist()
                                                                   )).encode()
    cells = (np.array([6, 0, 1, 2, 3, 4, 5], ">i4").tobytes() if binary
             else b"6 0 1 2 3 4 5") + b"\nCELL_TYPES 1\n"
    types = np.array([2], ">i4").tobytes() if binary else b"2"  # VTK_POLY_VERTEX
    (tmp_path / "g.vtk").write_bytes(head + body + b"\nCELLS 1 7\n" + cells + types + b"\n")
    ps = read_points(tmp_path / "g.vtk")
    np.testing.assert_array_equal(ps.points, pts.astype(np.float64))
    assert any("meshio cannot read its cells" in n for n in ps.report.notes)
