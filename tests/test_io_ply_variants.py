"""PLY files the standard allows or the wild produces: unknown header lines, list properties in
the vertex element, list elements before the vertices. Files are written with plyfile."""

from __future__ import annotations

import numpy as np
import plyfile
import pytest

from core.errors import FileFormatError
from core.io import read_points

RNG = np.random.default_rng(3)
XYZ = RNG.normal(size=(6, 3)).astype(np.float32)


def _vertex(list_at: str | None, ragged: bool) -> np.ndarray:
    """Vertex rows with x, y, z, a float 'quality' and optionally a list before/after x,y,z."""
    fields = [("x", "f4"), ("y", "f4"), ("z", "f4"), ("quality", "f8")]
    if list_at == "before":
        fields.insert(0, ("tags", "O"))
    elif list_at == "after":
        fields.append(("tags", "O"))
    vert = np.empty(len(XYZ), dtype=fields)
    for i, a in enumerate("xyz"):
        vert[a] = XYZ[:, i]
    vert["quality"] = np.arange(len(XYZ)) / 4
    if list_at:
        for i in range(len(XYZ)):
            vert["tags"][i] = np.arange(i % 3 + 1 if ragged else 2, dtype=np.int32)
    return vert


@pytest.mark.parametrize("text", [True, False])
@pytest.mark.parametrize("list_at", ["before", "after"])
@pytest.mark.parametrize("ragged", [False, True])
def test_vertex_list_property_skipped(tmp_path, text, list_at, ragged):
    vert = plyfile.PlyElement.describe(_vertex(list_at, ragged), "vertex",
                                       len_types={"tags": "u1"}, val_types={"tags": "i4"})
    path = tmp_path / "v.ply"
    plyfile.PlyData([vert], text=text).write(str(path))
    ps = read_points(path)
    np.testing.assert_array_equal(ps.points, XYZ.astype(np.float64))
    np.testing.assert_array_equal(ps.attributes["quality"], np.arange(len(XYZ)) / 4)
    assert "tags" not in ps.attributes


@pytest.mark.parametrize("text", [True, False])
@pytest.mark.parametrize("ragged", [False, True])
def test_list_element_before_vertices(tmp_path, text, ragged):
    sizes = [3, 4, 3] if ragged else [3, 3, 3]
    faces = np.empty(3, dtype=[("vertex_indices", "O"), ("flag", "u1")])
    for i, k in enumerate(sizes):
        faces["vertex_indices"][i] = np.arange(k, dtype=np.int32)
        faces["flag"][i] = 7
    path = tmp_path / "f.ply"
    plyfile.PlyData([plyfile.PlyElement.describe(faces, "face"),
                     plyfile.PlyElement.describe(_vertex(None, False), "vertex")],
                    text=text, byte_order=">").write(str(path))
    np.testing.assert_array_equal(read_points(path).points, XYZ.astype(np.float64))


def _with_header_lines(path, extra: bytes) -> None:
    """Insert lines right after the format line (where Stanford's scans have obj_info/bye)."""
    data = path.read_bytes()
    at = data.index(b"\n", data.index(b"format")) + 1
    path.write_bytes(data[:at] + extra + data[at:])


@pytest.mark.parametrize("text", [True, False])
def test_unknown_header_lines_skipped_with_a_note(tmp_path, text):
    path = tmp_path / "bye.ply"
    plyfile.PlyData([plyfile.PlyElement.describe(_vertex(None, False), "vertex")],
                    text=text).write(str(path))
    _with_header_lines(path, b"obj_info is_cyberware_data 1\nbye\nobj_info is_mesh 0\nbye\n")
    with pytest.raises(plyfile.PlyHeaderParseError):
        plyfile.PlyData.read(str(path))  # plyfile refuses these header lines
    ps = read_points(path)
    np.testing.assert_array_equal(ps.points, XYZ.astype(np.float64))
    assert "PLY header: 2 unknown lines skipped ('bye', 'bye')" in ps.report.notes


@pytest.mark.parametrize(("header", "message"), [
    (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no 'end_header'"),
    (b"plx\n", "first line must be 'ply'"),
    (b"ply\nelement vertex 1\nproperty float x\nend_header\n", "no 'format' line"),
    (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", "quad"),
])
def test_bad_headers_say_why(tmp_path, header, message):
    (tmp_path / "b.ply").write_bytes(header + b"0 0 0\n")
    with pytest.raises(FileFormatError, match=message):
        read_points(tmp_path / "b.ply")


def test_truncated_binary_list_vertex(tmp_path):
    vert = plyfile.PlyElement.describe(_vertex("after", True), "vertex")
    path = tmp_path / "t.ply"
    plyfile.PlyData([vert], text=False).write(str(path))
    path.write_bytes(path.read_bytes()[:-5])
    with pytest.raises(FileFormatError, match="truncated PLY"):
        read_points(path)


@pytest.mark.parametrize("text", [True, False])
def test_range_grid_of_mostly_empty_lists(tmp_path, text):
    """Stanford's range scans: a grid element after the vertices, most cells an empty list."""
    grid = np.empty(2000, dtype=[("vertex_indices", "O")])
    for i in range(len(grid)):
        grid["vertex_indices"][i] = np.array([i // 400], dtype=np.int32) if i % 400 == 0 \
            else np.zeros(0, dtype=np.int32)
    path = tmp_path / "grid.ply"
    plyfile.PlyData([plyfile.PlyElement.describe(_vertex(None, False), "vertex"),
                     plyfile.PlyElement.describe(grid, "range_grid",
                                                 len_types={"vertex_indices": "u1"})],
                    text=text).write(str(path))
    np.testing.assert_array_equal(read_points(path).points, XYZ.astype(np.float64))


def _mesh_ply(path, text: bool, polygons: list[list[int]], flag_first: bool) -> None:
    """Six vertices and faces given as index lists (a uchar 'flags' before the list if asked)."""
    fields = [("flags", "u1"), ("vertex_indices", "O")] if flag_first else [
        ("vertex_indices", "O")]
    faces = np.empty(len(polygons), dtype=fields)
    for i, poly in enumerate(polygons):
        faces["vertex_indices"][i] = np.array(poly, dtype=np.int32)
    if flag_first:
        faces["flags"] = 3
    plyfile.PlyData([plyfile.PlyElement.describe(_vertex(None, False), "vertex"),
                     plyfile.PlyElement.describe(faces, "face")], text=text).write(str(path))


@pytest.mark.parametrize("text", [True, False])
@pytest.mark.parametrize("flag_first", [False, True])
@pytest.mark.parametrize(("polygons", "unused"), [
    ([[0, 1, 2], [0, 2, 3]], 2),          # triangles: strided fast path
    ([[0, 1, 2, 4], [0, 2, 3]], 1),       # mixed polygons: row by row
])
def test_report_counts_vertices_no_face_uses(tmp_path, text, flag_first, polygons, unused):
    _mesh_ply(tmp_path / "m.ply", text, polygons, flag_first)
    ps = read_points(tmp_path / "m.ply")
    assert len(ps.points) == len(XYZ)
    assert (f"mesh vertices: all 6 kept; {unused} used by no face ({len(polygons)} "
            "faces/lines ignored)") in ps.report.notes


def test_unreadable_faces_never_stop_the_points(tmp_path):
    _mesh_ply(tmp_path / "m.ply", True, [[0, 1, 2], [0, 2, 3]], False)
    data = tmp_path.joinpath("m.ply").read_bytes().replace(b"\n3 0 2 3", b"\nx 0 2 3")
    tmp_path.joinpath("m.ply").write_bytes(data)
    ps = read_points(tmp_path / "m.ply")
    np.testing.assert_array_equal(ps.points, XYZ.astype(np.float64))
    assert "PLY faces could not be read; which vertices they use is not known" in ps.report.notes
