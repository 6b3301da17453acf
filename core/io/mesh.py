"""Mesh files contribute every vertex record: OBJ read directly, STL/OFF/glTF via trimesh
(every geometry of a scene, point clouds included, with node transforms), VTK via meshio or
the legacy POLYDATA reader. The report says how many vertices no face uses."""

from __future__ import annotations

import importlib
import logging
import tempfile
from pathlib import Path

import numpy as np

from core.arrays import unique_sorted
from core.errors import FileFormatError
from core.io.obj import read_obj, vertex_note
from core.io.problems import unreadable
from core.io.vtk_legacy import POINT_DATASETS, dataset_kind, read_points_section

TRIMESH_EXTS = {".stl", ".off", ".glb", ".gltf"}
MESHIO_READERS = {".vtk": "vtk", ".vtu": "vtu"}  # meshio reads no VTP


def _trimesh_scene(path: Path):
    """The file as a trimesh Scene, opened by handle (names need not be valid UTF-8)."""
    import trimesh

    logging.getLogger("trimesh").setLevel(logging.ERROR)
    ext = path.suffix.lower()
    resolver = trimesh.resolvers.FilePathResolver(str(path.parent)) if ext == ".gltf" else None
    try:
        with open(path, "rb") as fh:
            return trimesh.load_scene(fh, file_type=ext.lstrip("."), process=False,
                                      resolver=resolver)
    except OSError:
        raise
    except Exception as exc:  # trimesh raises anything from its many parsers
        raise unreadable(path, ext.lstrip(".").upper(), exc) from exc


def _geometry_part(geom) -> tuple[np.ndarray, np.ndarray | None, int, int]:
    """(vertices, colours or None, vertices used by faces, face count) of one scene geometry."""
    vertices = np.asarray(geom.vertices, dtype=np.float64).reshape(-1, 3)
    faces = np.asarray(getattr(geom, "faces", np.empty((0, 3))), dtype=np.int64)
    visual = getattr(geom, "visual", None)
    if getattr(visual, "kind", None) == "vertex":
        colors = np.asarray(visual.vertex_colors)
    else:
        colors = np.asarray(getattr(geom, "colors", ())) if faces.size == 0 else np.empty(0)
    colors = colors[:, :3] if colors.ndim == 2 and len(colors) == len(vertices) else None
    used = len(unique_sorted(faces)) if faces.size else 0
    return vertices, colors, used, len(faces)


def _trimesh_vertices(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """Vertices of every geometry in the file (scene transforms applied), no merging."""
    parts = [_geometry_part(g) for g in _trimesh_scene(path).dump(concatenate=False)]
    if not parts:
        raise FileFormatError(f"{path}: mesh has no vertices")
    vertices = np.concatenate([p[0] for p in parts])
    attrs: dict[str, np.ndarray] = {}
    if all(p[1] is not None for p in parts):
        attrs["colors"] = np.concatenate([p[1] for p in parts]).astype(np.uint8)
    note = vertex_note(len(vertices), sum(p[2] for p in parts), sum(p[3] for p in parts))
    return vertices, attrs, (note,)


def _holds(path: Path, needle: bytes, chunk: int = 1 << 20) -> bool:
    """Whether the file holds `needle`, read in chunks (never the whole file at once)."""
    with open(path, "rb") as fh:
        carry = b""
        while block := fh.read(chunk):
            if needle in carry + block:
                return True
            carry = block[-len(needle):]
    return False


def _without_strings(path: Path, folder: str) -> Path:
    """A copy of a VTU without its String arrays (meshio refuses the type; VTK and our own
    export write them as field data), or the file itself when it has none."""
    from xml.etree import ElementTree

    if not _holds(path, b'type="String"'):
        return path
    try:
        tree = ElementTree.parse(path)
    except ElementTree.ParseError:
        return path  # raw appended data: meshio has its own parser for those
    for parent in tree.iter():
        for child in [c for c in parent if c.get("type") == "String"]:
            parent.remove(child)
    out = Path(folder) / "strings_removed.vtu"
    tree.write(out)
    return out


def _meshio_vertices(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """Points of a VTK-family file plus its numeric point data."""
    module = importlib.import_module(f"meshio.{MESHIO_READERS[path.suffix.lower()]}")
    try:  # the format's own reader: meshio.read() calls sys.exit on failure
        with tempfile.TemporaryDirectory(prefix="alphascoop-vtu-") as folder:
            source = _without_strings(path, folder) if module.__name__ == "meshio.vtu" else path
            mesh = module.read(str(source))
    except OSError:
        raise
    except Exception as exc:  # meshio raises ReadError, ValueError, KeyError...
        raise unreadable(path, path.suffix.lstrip(".").upper(), exc) from exc
    vertices = np.asarray(mesh.points, dtype=np.float64)
    attrs = {}
    for name, values in mesh.point_data.items():
        values = np.asarray(values)
        if len(values) == len(vertices) and np.issubdtype(values.dtype, np.number):
            attrs["normals" if name.lower() == "normals" else name] = values
    return vertices, attrs, ("mesh vertices; cells ignored",)


def _vtk_vertices(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """Legacy VTK: POLYDATA read here; grids by meshio (with their point data), and here too
    when meshio refuses their cells: the points never depend on the cells."""
    kind = dataset_kind(path)
    if kind == "POLYDATA":
        return (read_points_section(path), {},
                ("VTK POLYDATA points; polygons and point data ignored",))
    try:
        return _meshio_vertices(path)
    except FileFormatError:
        if kind not in POINT_DATASETS:
            raise
    return (read_points_section(path), {},
            (f"VTK {kind} points; cells and point data ignored (meshio cannot read its cells)",))


def read_mesh(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) vertex coordinates of a mesh file, all vertex records kept (faces ignored)."""
    ext = path.suffix.lower()
    readers = {".obj": read_obj, ".vtk": _vtk_vertices, ".vtu": _meshio_vertices}
    if ext in readers:
        vertices, attrs, notes = readers[ext](path)
    else:
        vertices, attrs, notes = _trimesh_vertices(path)
    if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) == 0:
        raise FileFormatError(f"{path}: mesh has no vertices")
    return vertices, attrs, notes
