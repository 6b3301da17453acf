"""Our numpy PLY writer: byte-identical to plyfile's output for the same mesh, read back by
plyfile, trimesh and our reader."""

from __future__ import annotations

import numpy as np
import plyfile
import pytest
import trimesh

from core.export.plywriter import write_ply_mesh
from core.io import read_points

COMMENTS = ['alpha=0.25', 'source="scan \\u00fc.xyz"', "betti=[1, 0, 2]"]


def _mesh(n_vertices: int, n_faces: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(n_vertices + n_faces)
    v = rng.normal(size=(n_vertices, 3)) * 1e3
    f = rng.integers(0, max(n_vertices, 1), size=(n_faces, 3))
    return v, f


def _plyfile_bytes(tmp_path, v, f, comments) -> bytes:
    vert = np.empty(len(v), dtype=[("x", "f8"), ("y", "f8"), ("z", "f8")])
    vert["x"], vert["y"], vert["z"] = v.T
    face = np.empty(len(f), dtype=[("vertex_indices", "i4", (3,))])
    face["vertex_indices"] = f
    plyfile.PlyData([plyfile.PlyElement.describe(vert, "vertex"),
                     plyfile.PlyElement.describe(face, "face")],
                    text=False, byte_order="<", comments=comments).write(str(tmp_path / "ref.ply"))
    return (tmp_path / "ref.ply").read_bytes()


@pytest.mark.parametrize("n_vertices,n_faces", [(0, 0), (3, 1), (500, 997)])
def test_same_bytes_as_plyfile(tmp_path, n_vertices, n_faces):
    v, f = _mesh(n_vertices, n_faces)
    write_ply_mesh(tmp_path / "ours.ply", v, f, COMMENTS)
    assert (tmp_path / "ours.ply").read_bytes() == _plyfile_bytes(tmp_path, v, f, COMMENTS)


def test_read_back_by_plyfile_trimesh_and_our_reader(tmp_path):
    v, f = _mesh(500, 997)
    path = tmp_path / "m.ply"
    write_ply_mesh(path, v, f, COMMENTS)
    ply = plyfile.PlyData.read(str(path))
    assert ply.comments == COMMENTS
    assert np.array_equal(np.column_stack([ply["vertex"][c] for c in "xyz"]), v)
    assert np.array_equal(np.stack(ply["face"]["vertex_indices"]), f)
    mesh = trimesh.load(str(path), process=False)
    assert np.array_equal(mesh.vertices, v) and np.array_equal(mesh.faces, f)
    assert np.array_equal(read_points(path).points, v)


@pytest.mark.parametrize("comment", ["two\nlines", "caf\u00e9"])
def test_comment_that_the_header_cannot_hold_is_refused(tmp_path, comment):
    v, f = _mesh(3, 1)
    with pytest.raises(ValueError, match="one ASCII line"):
        write_ply_mesh(tmp_path / "m.ply", v, f, [comment])


def test_face_index_outside_the_vertices_is_refused(tmp_path):
    with pytest.raises(ValueError, match="face indices"):
        write_ply_mesh(tmp_path / "m.ply", np.zeros((3, 3)), np.array([[0, 1, 3]]), [])
