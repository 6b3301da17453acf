"""Triangle surfaces of a shape and their writers (PLY, STL, OBJ, OFF, VTP, glTF/GLB).

3D: the regularized boundary (REGULAR facets, oriented outward), closed; optionally split to
a 2-manifold. 2D: the filled triangles (counter-clockwise), lifted to the input's space.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from core.arrays import compact_ids
from core.export.manifold import ManifoldReport, split_nonmanifold
from core.export.metadata import comment_lines
from core.export.plywriter import write_ply_mesh
from core.export.vtkxml import vtp_bytes


def _ambient3(ac, coords: np.ndarray) -> np.ndarray:
    """(k, 3) float64 coordinates in the input's space (2D data gets z = 0)."""
    out = np.asarray(ac.to_ambient(coords), dtype=np.float64)
    if out.shape[1] == 2:
        out = np.column_stack([out, np.zeros(len(out))])
    return out


def _ccw(points: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """(c, 3) triangles reordered counter-clockwise (positive area) in 2D."""
    tris = np.array(tris, dtype=np.int64)
    a, b, c = (points[tris[:, i]] for i in range(3))
    cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    tris[cross < 0, 1:] = tris[cross < 0, 2:0:-1]
    return tris


def surface_arrays(ac, shape, *, manifold: bool = False):
    """(v, 3) float64 vertices, (f, 3) int64 faces, ManifoldReport or None (2D or not asked)."""
    report = None
    if ac.dim == 3:
        if manifold:
            ids, faces, report = split_nonmanifold(ac, shape)
            return _ambient3(ac, ac.points[ids]), faces, report
        faces = np.asarray(shape.regular_facets, dtype=np.int64)
    else:
        faces = _ccw(ac.points, shape.cells)
    used, inverse = compact_ids(faces, len(ac.points))
    return _ambient3(ac, ac.points[used]), inverse.reshape(-1, 3), report


def write_ply(path: Path, vertices: np.ndarray, faces: np.ndarray, meta: dict) -> None:
    """Binary little-endian PLY (own numpy writer); metadata as header comments."""
    write_ply_mesh(path, vertices, faces, comment_lines(meta))


def _trimesh(vertices: np.ndarray, faces: np.ndarray, meta: dict):
    """A trimesh.Trimesh holding exactly these arrays (no merging, which would undo splits)."""
    import trimesh

    return trimesh.Trimesh(vertices=vertices, faces=faces, process=False, validate=False,
                           metadata={"alphascoop": meta})


def write_stl(path: Path, vertices: np.ndarray, faces: np.ndarray, meta: dict) -> None:
    """Binary STL via trimesh."""
    from trimesh.exchange.stl import export_stl

    path.write_bytes(export_stl(_trimesh(vertices, faces, meta)))


def write_obj(path: Path, vertices: np.ndarray, faces: np.ndarray, meta: dict) -> None:
    """Wavefront OBJ via trimesh; metadata as leading comments."""
    from trimesh.exchange.obj import export_obj

    text = export_obj(_trimesh(vertices, faces, meta), include_normals=False,
                      include_color=False, include_texture=False, header=None, digits=17)
    path.write_text("".join(f"# {line}\n" for line in comment_lines(meta)) + text)


def write_off(path: Path, vertices: np.ndarray, faces: np.ndarray, meta: dict) -> None:
    """OFF via trimesh."""
    from trimesh.exchange.off import export_off

    path.write_text(export_off(_trimesh(vertices, faces, meta), digits=17))


def write_glb(path: Path, vertices: np.ndarray, faces: np.ndarray, meta: dict) -> None:
    """Binary glTF via trimesh (float32 positions, as glTF requires); metadata in extras."""
    from trimesh.exchange.gltf import export_glb

    path.write_bytes(export_glb(_trimesh(vertices, faces, meta).scene(), include_normals=False))


def write_gltf(path: Path, vertices: np.ndarray, faces: np.ndarray, meta: dict) -> None:
    """Text glTF with its buffer embedded as a data URI, via trimesh."""
    from trimesh.exchange.gltf import export_gltf

    files = export_gltf(_trimesh(vertices, faces, meta).scene(), embed_buffers=True,
                        include_normals=False)
    path.write_bytes(files["model.gltf"])


def write_vtp(path: Path, vertices: np.ndarray, faces: np.ndarray, meta: dict) -> None:
    """VTK PolyData XML with the metadata as field data."""
    path.write_bytes(vtp_bytes(vertices, faces, meta))


SURFACE_WRITERS = {
    ".ply": write_ply, ".stl": write_stl, ".obj": write_obj, ".off": write_off,
    ".glb": write_glb, ".gltf": write_gltf, ".vtp": write_vtp,
}


def manifold_meta(report: ManifoldReport | None) -> dict:
    """Metadata entries describing a manifold split (empty when none was asked)."""
    if report is None:
        return {}
    counts = {f.name: getattr(report, f.name) for f in dataclasses.fields(report)
              if f.name not in ("split_points", "split_copies")}  # the points: split_listing
    return {"manifold_split": json.loads(json.dumps(counts))}


def split_listing(ac, report: ManifoldReport | None) -> str | None:
    """CSV text 'x,y,z,copies' of the points a manifold split wrote more than once, in the
    coordinates written (None when there are none)."""
    if report is None or len(report.split_points) == 0:
        return None
    xyz = _ambient3(ac, ac.points[report.split_points])
    rows = (f"{x!r},{y!r},{z!r},{c}" for (x, y, z), c in
            zip(xyz.tolist(), report.split_copies.tolist(), strict=True))
    return "x,y,z,copies\n" + "\n".join(rows) + "\n"
