"""Binary little-endian PLY triangle meshes written with numpy (no GPL plyfile at runtime).

The layout is the one plyfile wrote before: double x, y, z vertices, faces as a uchar count
and three int indices, the metadata as header comments.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

_FACE = np.dtype([("count", "u1"), ("indices", "<i4", (3,))])  # packed: 13 bytes a face


def ply_header(n_vertices: int, n_faces: int, comments: list[str]) -> bytes:
    """The ASCII header; comments must be single ASCII lines (PLY has no escaping)."""
    for line in comments:
        if "\n" in line or "\r" in line or not line.isascii():
            raise ValueError(f"PLY comment must be one ASCII line: {line[:40]!r}")
    lines = ["ply", "format binary_little_endian 1.0", *(f"comment {c}" for c in comments),
             f"element vertex {n_vertices}", "property double x", "property double y",
             "property double z", f"element face {n_faces}",
             "property list uchar int vertex_indices", "end_header"]
    return ("\n".join(lines) + "\n").encode("ascii")


def write_ply_mesh(path: Path, vertices: np.ndarray, faces: np.ndarray,
                   comments: list[str]) -> None:
    """Write (v, 3) float vertices and (f, 3) int triangles to `path` as binary PLY."""
    vertices = np.ascontiguousarray(vertices, dtype="<f8")
    faces = np.asarray(faces)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ValueError(f"PLY vertices must be (v, 3), not {vertices.shape}")
    if faces.ndim != 2 or faces.shape[1] != 3:
        raise ValueError(f"PLY faces must be (f, 3) triangles, not {faces.shape}")
    if len(faces) and (faces.min() < 0 or faces.max() >= len(vertices)):
        raise ValueError("PLY face indices must refer to the written vertices")
    if len(vertices) > np.iinfo(np.int32).max:
        raise ValueError(f"PLY int indices hold at most 2**31 - 1 vertices, not {len(vertices)}")
    body = np.empty(len(faces), dtype=_FACE)
    body["count"] = 3
    body["indices"] = faces
    with open(path, "wb") as out:
        out.write(ply_header(len(vertices), len(faces), comments))
        vertices.tofile(out)
        body.tofile(out)
